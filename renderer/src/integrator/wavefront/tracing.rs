//! A group's ray queries: packets tested against the primitives of a world
//! of lone triangles, boxes, spheres and planes ([`PacketShapes`]: every primitive,
//! or those a tree lets through), else each lane's ray traced through the world's BVH
//! (`World::intersect` and `World::occluded`, the scalar path tracer's own
//! queries). Either way a lane's hit is the scalar one bit for bit.

use super::scene::{ObjectTable, WavefrontScene};
use crate::geometry::counters::{count_ray, count_shape_tests, shape_tests_on_this_thread};
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, Vec3s, WIDTH, lane_set, mask_from};
use crate::packet_shapes::PacketHits;
use crate::shapes::Method;
use crate::world::{Hit, World};
use glam::Vec3;

/// The closest hits of a group's rays.
pub(super) struct Closest<F: FloatLanes> {
    /// Each lane's α (+∞ on a miss) and object id (−1).
    pub(super) packet: PacketHits<F>,
    /// Each lane's hit in full, when traced through the world or when a
    /// packet lane hit a mesh (a mesh triangle's barycentrics included);
    /// `None` where `PacketHits` says all (analytic shapes only).
    pub(super) hits: Option<[Option<Hit>; WIDTH]>,
    /// Lanes that hit a mesh triangle.
    pub(super) mesh: F::Mask,
}

impl<F: FloatLanes> Closest<F> {
    /// Each lane's row of `table`: its object's, or a mesh triangle's
    /// instance's (−1 on a miss, past every row).
    #[inline(always)]
    pub(super) fn rows(&self, table: &ObjectTable) -> F::Ints {
        match &self.hits {
            Some(hits) if self.mesh.any() => {
                let mut rows = self.packet.object.to_array();
                for (row, hit) in rows.iter_mut().zip(hits) {
                    if let Some(t) = hit.and_then(|h| h.triangle) {
                        *row = table.mesh_row(t.instance) as i32;
                    }
                }
                F::Ints::from_array(rows)
            }
            _ => self.packet.object,
        }
    }

    /// Lane `k`'s hit (it hit something).
    #[inline(always)]
    pub(super) fn hit(&self, k: usize) -> Hit {
        match &self.hits {
            Some(hits) => hits[k].expect("lane k hit something"),
            None => Hit {
                object: self.packet.object.to_array()[k] as u32,
                alpha: self.packet.alpha.as_array()[k],
                triangle: None,
            },
        }
    }
}

/// The closest hits of the lanes `live` of `rays`, counting rays and shape
/// tests (per lane into `tests`): the primitives a packet tested each lane
/// against, or what the scalar query counts.
#[inline(always)]
pub(super) fn closest<F: FloatLanes>(
    world: &World,
    scene: &WavefrontScene,
    method: Method,
    rays: &Rays<F>,
    live: F::Mask,
    tests: &mut [u64; WIDTH],
) -> Closest<F> {
    if let Some(shapes) = &scene.shapes {
        let mut tested = F::Ints::splat(0);
        let packet = shapes.closest(rays, &mut tested);
        count::<F>(live, tested, tests);
        // Mesh triangles' lanes need the whole hit (β, γ) for their
        // surface (`World::hit_surface`).
        let mesh = shapes.mesh_lanes(&packet);
        let hits = mesh
            .any()
            .then(|| std::array::from_fn(|k| shapes.lane_hit(&packet, k, &rays.lane(k))));
        return Closest { packet, hits, mesh };
    }
    let mut hits = [None; WIDTH];
    for (k, hit) in hits.iter_mut().enumerate() {
        if lane_set(live, k) {
            let before = shape_tests_on_this_thread();
            *hit = world.intersect(&rays.lane(k), method);
            tests[k] += shape_tests_on_this_thread() - before;
        }
    }
    Closest {
        packet: PacketHits {
            alpha: F::from_array(hits.map(|h| h.map_or(f32::INFINITY, |h| h.alpha))),
            object: F::Ints::from_array(hits.map(|h| h.map_or(-1, |h| h.object as i32))),
            triangle: F::Ints::splat(-1),
        },
        mesh: mask_from::<F>(|k| hits[k].is_some_and(|h| h.triangle.is_some())),
        hits: Some(hits),
    }
}

/// The hit points and outward geometric normals of the lanes `lanes` of
/// `closest` (analytic shapes only; anything in the other lanes).
#[inline(always)]
pub(super) fn surfaces<F: FloatLanes>(
    world: &World,
    scene: &WavefrontScene,
    rays: &Rays<F>,
    closest: &Closest<F>,
    lanes: F::Mask,
) -> (Vec3s<F>, Vec3s<F>) {
    if let Some(shapes) = &scene.shapes {
        return shapes.surface(rays, &closest.packet);
    }
    let mut points = [Vec3::ZERO; WIDTH];
    let mut normals = [Vec3::Z; WIDTH];
    for k in (0..WIDTH).filter(|&k| lane_set(lanes, k)) {
        let surface = world.surface(&rays.lane(k), closest.hit(k));
        points[k] = surface.point;
        normals[k] = surface.normal;
    }
    (Vec3s::from_lanes(&points), Vec3s::from_lanes(&normals))
}

/// Per lane of `lanes`: whether anything blocks its ray of `rays`.
#[inline(always)]
pub(super) fn occluded<F: FloatLanes>(
    world: &World,
    scene: &WavefrontScene,
    method: Method,
    rays: &Rays<F>,
    lanes: F::Mask,
    tests: &mut [u64; WIDTH],
) -> F::Mask {
    if !lanes.any() {
        return F::Mask::NONE;
    }
    if let Some(shapes) = &scene.shapes {
        let mut tested = F::Ints::splat(0);
        let blocked = shapes.occluded(rays, &mut tested) & lanes;
        count::<F>(lanes, tested, tests);
        return blocked;
    }
    let mut blocked = [false; WIDTH];
    for (k, blocked) in blocked.iter_mut().enumerate() {
        if lane_set(lanes, k) {
            let before = shape_tests_on_this_thread();
            *blocked = world.occluded(&rays.lane(k), method);
            tests[k] += shape_tests_on_this_thread() - before;
        }
    }
    mask_from::<F>(|k| blocked[k])
}

/// Counts one ray and its lane of `tested` shape tests for every lane of
/// `lanes`.
#[inline(always)]
fn count<F: FloatLanes>(lanes: F::Mask, tested: F::Ints, tests: &mut [u64; WIDTH]) {
    let tested = tested.to_array();
    for (k, tests) in tests.iter_mut().enumerate() {
        if lane_set(lanes, k) {
            count_ray();
            count_shape_tests(tested[k] as usize);
            *tests += tested[k] as u64;
        }
    }
}
