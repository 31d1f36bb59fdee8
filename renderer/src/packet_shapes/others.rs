//! The few shapes without a packet test of their own (cylinders, cones,
//! tori), a cone's lanes tested together and the others lane by lane with
//! the scalar code's own test, so that one of them does
//! not send every ray of its world lane by lane through the BVH (the cone
//! of `seed.xml` did).
//!
//! Each shape's loose bounding sphere is tested first for all sixteen lanes
//! at once ([`BoundingSphere::may_hit_lanes`], the scalar test's answer
//! bit for bit). The lanes it lets through are tested below each lane's
//! nearest hit so far — a cone's all at once (`Cone::intersect_exact_lanes`,
//! the scalar test's α bit for bit), a cylinder's or torus's lane by lane
//! with [`Shape::intersect`] — and each hit placed with [`Shape::surface`]:
//! the numbers [`crate::world::World::intersect`] and
//! [`crate::world::World::surface`] give for that ray, bit for bit.
//!
//! [`BoundingSphere::may_hit_lanes`]: crate::shapes::bound::BoundingSphere::may_hit_lanes

use super::Nearest;
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, Vec3s, WIDTH, mask_from};
use crate::shapes::{Method, Shape};
use glam::Vec3;

/// Shapes tested lane by lane, with their object ids.
#[derive(Clone, Debug, Default)]
pub(super) struct Others {
    /// Per shape, its object id.
    objects: Vec<i32>,
    /// The shapes.
    shapes: Vec<Shape>,
}

impl Others {
    /// The most shapes a world in packets may hold: each costs every packet
    /// a sixteen-lane bounding-sphere test, and the lanes it lets through a
    /// scalar test each (a cone: one test of the sixteen lanes), where the
    /// world's BVH tests only the rays that come near the shape. With the
    /// lane bounding sphere, before the cone's lane test, 8 against 2 (`render --spp 8`,
    /// 2 threads, medians of 5–7 alternated runs, path / Whitted):
    /// glass.xml's five 0.62 / 0.96 of the time, primitives.xml's three
    /// 0.49 / 0.82, roughness.xml's three 0.68 / 1.00. Before it (every live
    /// lane tested scalar) three or more were slower than the BVH.
    pub(super) const MAX: usize = 8;

    /// Adds `shape`, object `object`; returns its index.
    pub(super) fn push(&mut self, object: i32, shape: &Shape) -> u32 {
        self.objects.push(object);
        self.shapes.push(*shape);
        (self.shapes.len() - 1) as u32
    }

    /// How many shapes there are.
    pub(super) fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Tests the lanes `live` of `rays` against every shape, below each
    /// lane's nearest hit so far, taking the nearer hits; counts one test
    /// per shape and live lane.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        live: F::Mask,
        nearest: &mut Nearest<F>,
        tests: &mut F::Ints,
    ) {
        if self.shapes.is_empty() {
            return;
        }
        for (shape, &object) in self.shapes.iter().zip(&self.objects) {
            let mut near = candidates(shape, rays, nearest.limit, live);
            if near == 0 {
                continue;
            }
            if let Shape::Cone(cone) = shape {
                let alpha = cone.intersect_exact_lanes(rays.origin, rays.dir, nearest.limit);
                let hit = F::Mask::from_bitmask(near) & alpha.simd_lt(F::splat(f32::INFINITY));
                nearest.take(hit, alpha, object);
                continue;
            }
            let limit = nearest.limit.to_array();
            let mut alpha = [f32::INFINITY; WIDTH];
            while near != 0 {
                let k = near.trailing_zeros() as usize;
                near &= near - 1;
                let ray = rays.lane(k).with_t_max(limit[k]);
                if let Some(a) = shape.intersect(&ray, Method::Robust) {
                    alpha[k] = a;
                }
            }
            let hit = mask_from::<F>(|k| alpha[k] < f32::INFINITY);
            nearest.take(hit, F::from_array(alpha), object);
        }
        *tests = *tests + super::count::<F>(live, self.shapes.len());
    }

    /// Marks as settled the lanes of `rays` not yet settled whose ray any
    /// shape blocks; counts one test per shape and lane tested.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        settled: &mut F::Mask,
        tests: &mut F::Ints,
    ) {
        let mut open = !*settled;
        let mut tested = F::Ints::splat(0);
        for shape in &self.shapes {
            // One test counted per shape and lane still open, as the
            // scalar occlusion test counts them (it stops at the first blocker).
            tested = tested + super::count::<F>(open, 1);
            let mut near = candidates(shape, rays, rays.t_max, open);
            let mut blocked = 0u32;
            if let (Shape::Cone(cone), true) = (shape, near != 0) {
                let alpha = cone.intersect_exact_lanes(rays.origin, rays.dir, rays.t_max);
                blocked = near & alpha.simd_lt(F::splat(f32::INFINITY)).to_bitmask();
                near = 0;
            }
            while near != 0 {
                let k = near.trailing_zeros() as usize;
                near &= near - 1;
                if shape.intersect(&rays.lane(k), Method::Robust).is_some() {
                    blocked |= 1 << k;
                }
            }
            open = open & !F::Mask::from_bitmask(blocked);
            if !open.any() {
                break;
            }
        }
        *settled = !open;
        *tests = *tests + tested;
    }

    /// The hit points and outward normals of the lanes whose hit is the
    /// shape at `index[k]`, at `alpha` (anything in the other lanes).
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
        lanes: u32,
    ) -> (Vec3s<F>, Vec3s<F>) {
        let alpha = alpha.to_array();
        let mut points = [Vec3::ZERO; WIDTH];
        let mut normals = [Vec3::Z; WIDTH];
        for k in (0..WIDTH).filter(|&k| lanes & (1 << k) != 0) {
            let surface = self.shapes[index[k] as usize].surface(&rays.lane(k), alpha[k]);
            points[k] = surface.point;
            normals[k] = surface.normal;
        }
        (Vec3s::from_lanes(&points), Vec3s::from_lanes(&normals))
    }
}

/// The lanes of `lanes` whose ray over (0, t_max) may hit `shape`, as a
/// bit mask: those its bounding sphere lets through, tested for all
/// sixteen at once (bit for bit the scalar test's answer, which
/// [`Shape::intersect`] asks first), or all of `lanes` for a shape without one.
#[inline(always)]
fn candidates<F: FloatLanes>(shape: &Shape, rays: &Rays<F>, t_max: F, lanes: F::Mask) -> u32 {
    match shape.bounding_sphere() {
        Some(bound) => (bound.may_hit_lanes(rays.origin, rays.dir, t_max) & lanes).to_bitmask(),
        None => lanes.to_bitmask(),
    }
}
