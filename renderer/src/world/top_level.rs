//! The top level of a world's BVH as each intersection method sees it. With
//! [`Method::Lecture`] every bounded object is an item of one [`SceneBvh`],
//! each tested with its own formulas. With [`Method::Robust`], when there are
//! at least [`GROUPED_TRIANGLES`] lone triangles (`<triangle>` objects, and
//! small mesh instances' triangles placed in world space: [`BAKED_TRIANGLES`]),
//! they leave it for one mesh BVH of their own, itself one item: its packed
//! watertight test is exactly [`Triangle::hit`] with `Method::Robust` (bit for
//! bit the same α), four triangles at a time, and its 8-wide nodes cull
//! them; a Cornell box of triangles then costs a few SIMD tests per ray
//! instead of one scalar test per wall.
//!
//! [`Triangle::hit`]: crate::shapes::Triangle::hit

use super::lone_spheres::LoneSpheres;
use super::{Hit, Item, TriangleRef};

/// Lone triangles are grouped in a BVH of their own from this many on:
/// below, preparing the ray for the packed test costs more than testing
/// each triangle its box lets through.
pub(super) const GROUPED_TRIANGLES: usize = 4;
use crate::accel::{Aabb, MeshBvh, SceneBvh};
use crate::geometry::ray::Ray;
use crate::shapes::{Method, Sphere};
use glam::Vec3;

/// Items in a BVH over their boxes.
#[derive(Clone, Debug)]
pub(super) struct TopLevel {
    /// The BVH; its item ids index `items`.
    pub(super) bvh: SceneBvh,
    /// What each item is.
    pub(super) items: Vec<Item>,
}

impl TopLevel {
    /// The BVH over `items`, item i boxed by `bounds[i]`.
    pub(super) fn new(items: Vec<Item>, bounds: &[Aabb]) -> Self {
        Self {
            bvh: SceneBvh::build(bounds),
            items,
        }
    }
}

/// A world's triangles that need no instance: its lone triangles and, when
/// the mesh instances are small ([`BAKED_TRIANGLES`] in all), the
/// instances' triangles placed in world space, all in one mesh BVH
/// ([`Method::Robust`] only). A ray then walks one tree, prepared once,
/// where it walked the top level and each instance it entered with a ray
/// of its own (mapped into the instance's space, its walk set up again);
/// and a world of such triangles, boxes, spheres and planes is traced in
/// packets (`packet_shapes`), which test these same world-space corners.
#[derive(Clone, Debug)]
pub(super) struct LoneTriangles {
    bvh: MeshBvh,
    /// The triangles, by their index in the BVH (the lowest wins a tie).
    triangles: Vec<GroupedTriangle>,
}

/// One triangle of [`LoneTriangles`]: its object, its corners in world
/// space, its box as the top level would hold it, and the mesh instance and
/// triangle it was placed from, if any.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GroupedTriangle {
    /// The object id: the `<triangle>` itself, or the model of the instance.
    pub(crate) object: u32,
    /// t0, t1, t2 in world space.
    pub(crate) corners: [Vec3; 3],
    /// The corners' box padded for the test's rounding, as a `<triangle>`'s
    /// is in the top level.
    pub(crate) bounds: Aabb,
    /// The instance ([`World::meshes`] index) and the triangle's index in
    /// its mesh; `None` for a `<triangle>` object.
    ///
    /// [`World::meshes`]: super::World::meshes
    pub(crate) from_mesh: Option<(u32, u32)>,
}

/// Up to this many mesh triangles in all (every instance counted), a
/// world's mesh instances are placed in world space among its lone
/// triangles ([`LoneTriangles`]), where packets of rays can test them
/// (`PacketShapes::MAX_PRIMITIVES`, the same number, says why there); with
/// more, each stays an instance of its shared BVH, built once and kept
/// across edits (a group is built again with every world; one ray at a time
/// it gained only ~5% on a sphere of 3,480 triangles).
pub(super) const BAKED_TRIANGLES: usize = 8192;

impl LoneTriangles {
    /// The BVH over `triangles`, ties going to the lowest index;
    /// `None` when there are fewer than [`GROUPED_TRIANGLES`].
    pub(super) fn new(triangles: &[GroupedTriangle]) -> Option<Self> {
        if triangles.len() < GROUPED_TRIANGLES {
            return None;
        }
        let positions: Vec<Vec3> = triangles.iter().flat_map(|t| t.corners).collect();
        let indices: Vec<[u32; 3]> = (0..triangles.len() as u32)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect();
        Some(Self {
            bvh: MeshBvh::build(&positions, &indices),
            triangles: triangles.to_vec(),
        })
    }

    /// The nearest triangle hit in the ray's interval, as the object it is
    /// (with the mesh triangle and its β and γ for a placed instance's).
    #[inline]
    pub(super) fn closest(&self, ray: &Ray) -> Option<Hit> {
        self.bvh.closest_hit(ray).map(|h| {
            let grouped = &self.triangles[h.triangle as usize];
            Hit {
                object: grouped.object,
                alpha: h.alpha,
                triangle: grouped.from_mesh.map(|(instance, triangle)| TriangleRef {
                    instance,
                    triangle,
                    beta: h.beta,
                    gamma: h.gamma,
                }),
            }
        })
    }

    /// The triangles, by index (the BVH's triangle ids).
    pub(super) fn triangles(&self) -> &[GroupedTriangle] {
        &self.triangles
    }

    /// True when some lone triangle lies on the ray inside its interval.
    #[inline]
    pub(super) fn any(&self, ray: &Ray) -> bool {
        self.bvh.any_hit(ray)
    }

    /// The box around every lone triangle.
    pub(super) fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }
}

/// The top levels of both methods.
#[derive(Clone, Debug)]
pub(super) struct TopLevels {
    /// Every bounded object ([`Method::Lecture`]).
    pub(super) all: TopLevel,
    /// [`Method::Robust`]'s: the lone triangles and the lone spheres each
    /// grouped in one item (`lone_triangles`, `lone_spheres`); `None` when
    /// neither is grouped (then `all` serves both methods).
    pub(super) robust: Option<TopLevel>,
    /// The grouped lone triangles ([`Item::LoneTriangles`]).
    pub(super) lone_triangles: Option<LoneTriangles>,
    /// The grouped lone spheres ([`Item::LoneSpheres`]).
    pub(super) lone_spheres: Option<LoneSpheres>,
    /// True when every mesh instance was placed among the lone triangles
    /// (or there is none): the robust top level holds no instance.
    pub(super) instances_grouped: bool,
}

/// The objects a world may group for [`Method::Robust`]: `<triangle>`s and
/// small mesh instances' triangles ([`GroupedTriangle`]), and `<sphere>`s
/// (object id, the sphere, and its box as the top level has it).
#[derive(Default)]
pub(super) struct Lone {
    pub(super) triangles: Vec<GroupedTriangle>,
    pub(super) spheres: Vec<(u32, Sphere, Aabb)>,
}

impl TopLevels {
    /// The top levels over `items` (boxed by `bounds`) for both methods; the
    /// `lone` triangles and spheres are grouped for the robust one when
    /// there are enough of them.
    pub(super) fn new(items: Vec<Item>, bounds: &[Aabb], lone: &Lone) -> TopLevels {
        let lone_triangles = LoneTriangles::new(&lone.triangles);
        let (spheres, sphere_bounds): (Vec<(u32, Sphere)>, Vec<Aabb>) =
            lone.spheres.iter().map(|&(id, s, b)| ((id, s), b)).unzip();
        let lone_spheres = LoneSpheres::new(&spheres, &sphere_bounds);
        let mut grouped_ids = Vec::new();
        if lone_triangles.is_some() {
            grouped_ids.extend(
                lone.triangles
                    .iter()
                    .filter(|t| t.from_mesh.is_none())
                    .map(|t| t.object),
            );
        }
        // The world places every instance among the lone triangles or none
        // (`BAKED_TRIANGLES`); they are in the group when it exists.
        let placed =
            lone_triangles.is_some() && lone.triangles.iter().any(|t| t.from_mesh.is_some());
        let instances_grouped = placed || !items.iter().any(|item| matches!(item, Item::Mesh(_)));
        if lone_spheres.is_some() {
            grouped_ids.extend(spheres.iter().map(|s| s.0));
        }
        let robust = (!grouped_ids.is_empty() || placed).then(|| {
            let mut grouped = Vec::new();
            for &id in &grouped_ids {
                grouped.resize(grouped.len().max(id as usize + 1), false);
                grouped[id as usize] = true;
            }
            let is_grouped = |item: &Item| match *item {
                Item::Shape(id) => grouped.get(id as usize).copied().unwrap_or(false),
                Item::Mesh(_) => placed,
                Item::LoneTriangles | Item::LoneSpheres => false,
            };
            let (mut robust_items, mut robust_bounds): (Vec<Item>, Vec<Aabb>) = items
                .iter()
                .zip(bounds)
                .filter(|(item, _)| !is_grouped(item))
                .map(|(item, b)| (*item, *b))
                .unzip();
            if let Some(group) = &lone_triangles {
                robust_items.push(Item::LoneTriangles);
                robust_bounds.push(group.bounds());
            }
            if let Some(group) = &lone_spheres {
                robust_items.push(Item::LoneSpheres);
                robust_bounds.push(group.bounds());
            }
            TopLevel::new(robust_items, &robust_bounds)
        });
        TopLevels {
            all: TopLevel::new(items, bounds),
            robust,
            lone_triangles,
            lone_spheres,
            instances_grouped,
        }
    }

    /// The top level `method` traces.
    #[inline(always)]
    pub(super) fn for_method(&self, method: Method) -> &TopLevel {
        match (method, &self.robust) {
            (Method::Robust, Some(robust)) => robust,
            _ => &self.all,
        }
    }

    /// The grouped lone triangles, which only [`Item::LoneTriangles`] refers to.
    #[inline(always)]
    pub(super) fn lone_triangles(&self) -> &LoneTriangles {
        self.lone_triangles
            .as_ref()
            .expect("an Item::LoneTriangles exists only with its group")
    }

    /// The grouped lone spheres, which only [`Item::LoneSpheres`] refers to.
    #[inline(always)]
    pub(super) fn lone_spheres(&self) -> &LoneSpheres {
        self.lone_spheres
            .as_ref()
            .expect("an Item::LoneSpheres exists only with its group")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::world::World;
    use std::fmt::Write;

    /// `n` random lone triangles and `n` / 4 spheres in a 10-unit cube, with
    /// a few triangles sharing edges (a quad split on its diagonal).
    fn world(n: usize, seed: u64) -> World {
        let mut rng = Sampler::for_sample(seed, 0, 0, 0);
        let mut point = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0 - 5.0;
        let v = |p: Vec3| format!("{} {} {}", p.x, p.y, p.z);
        let mut xml = String::from("<scene>");
        for _ in 0..n {
            let (a, b, c) = (point(), point(), point());
            let _ = write!(
                xml,
                r#"<triangle t0="{}" t1="{}" t2="{}"/>"#,
                v(a),
                v(b),
                v(c)
            );
        }
        for _ in 0..n / 4 {
            let _ = write!(xml, r#"<sphere center="{}" radius="0.7"/>"#, v(point()));
        }
        xml.push_str(
            r#"<triangle t0="-5 -5 0" t1="5 -5 0" t2="5 5 0"/><triangle t0="-5 -5 0" t1="5 5 0" t2="-5 5 0"/></scene>"#,
        );
        World::from_scene(&scene::read_str(&xml, "t.xml").expect("parses")).expect("valid")
    }

    #[test]
    fn grouped_lone_triangles_find_the_brute_force_nearest_alpha_bit_for_bit() {
        for n in [2, 3, 4, 40] {
            let world = world(n, n as u64);
            assert_eq!(
                world.top.lone_triangles.is_some(),
                n + 2 >= GROUPED_TRIANGLES,
                "{n} triangles"
            );
            let mut rng = Sampler::for_sample(7, 0, 0, 0);
            let mut hits = 0;
            for k in 0..3000 {
                let origin = rng.next_direction() * 8.0;
                let mut ray = Ray::new(origin, rng.next_direction());
                if k % 4 == 0 {
                    ray.t_max = 6.0 * rng.next_f32();
                }
                // Brute force: every object's own robust test.
                let want = (0..world.objects.len() as u32)
                    .filter_map(|id| {
                        let alpha = world.analytic(id).intersect(&ray, Method::Robust)?;
                        Some((id, alpha))
                    })
                    .min_by(|a, b| a.1.total_cmp(&b.1));
                let got = world.intersect(&ray, Method::Robust);
                assert_eq!(
                    got.map(|h| h.alpha.to_bits()),
                    want.map(|w| w.1.to_bits()),
                    "{n} triangles, ray {k}: {ray:?}"
                );
                if let (Some(got), Some(_)) = (got, want) {
                    // On a tie any object at that α may win, but it must be one.
                    let at = world.analytic(got.object).intersect(&ray, Method::Robust);
                    assert_eq!(at, Some(got.alpha), "{n} triangles, ray {k}");
                    assert_eq!(got.triangle, None, "a lone triangle is an object");
                    hits += 1;
                }
                assert_eq!(world.occluded(&ray, Method::Robust), want.is_some());
            }
            assert!(hits > 100, "{n} triangles: too few hits ({hits})");
        }
    }
}
