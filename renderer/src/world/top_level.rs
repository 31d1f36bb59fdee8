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
use crate::accel::{Aabb, MeshBvh, MeshHit, SceneBvh};
use crate::geometry::ray::Ray;
use crate::shapes::{Method, Sphere};
use glam::Vec3;
use std::sync::Arc;

/// Items in a BVH over their boxes.
#[derive(Clone, Debug)]
pub(super) struct TopLevel {
    /// The BVH; its item ids index `items`.
    pub(super) bvh: SceneBvh,
    /// What each item is.
    pub(super) items: Vec<Item>,
    /// True when the only item is a BVH of its own (a mesh instance or the
    /// grouped triangles), whose walk tests its box first anyway: rays go
    /// to it without the top level's walk (~20 ns a ray when a world's
    /// triangles are all grouped).
    alone: bool,
}

impl TopLevel {
    /// The BVH over `items`, item i boxed by `bounds[i]`.
    pub(super) fn new(items: Vec<Item>, bounds: &[Aabb]) -> Self {
        Self {
            bvh: SceneBvh::build(bounds),
            alone: matches!(items[..], [Item::Mesh(_) | Item::LoneTriangles]),
            items,
        }
    }

    /// [`SceneBvh::closest_with`] over the items.
    #[inline(always)]
    pub(super) fn closest_with<T>(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<(f32, T)>,
    ) -> Option<(u32, f32, T)> {
        if self.alone {
            return test(0, ray).map(|(alpha, kept)| (0, alpha, kept));
        }
        self.bvh.closest_with(ray, test)
    }

    /// [`SceneBvh::any`] over the items.
    #[inline(always)]
    pub(super) fn any(&self, ray: &Ray, mut test: impl FnMut(u32, &Ray) -> bool) -> bool {
        if self.alone {
            return test(0, ray);
        }
        self.bvh.any(ray, test)
    }
}

/// A world's triangles that need no instance: its lone triangles and the
/// mesh instances' triangles placed in world space, all in one mesh BVH
/// ([`Method::Robust`] only), when the world's meshes are small
/// ([`BAKED_TRIANGLES`] in all) or each is placed once ([`World::new`]
/// decides). A ray then walks one tree, prepared once, where it walked the
/// top level and each instance it entered with a ray of its own (mapped
/// into the instance's space, its walk set up again); and a world of such
/// triangles, boxes, spheres and planes is traced in packets
/// (`packet_shapes`), which test these same world-space corners.
///
/// [`World::new`]: super::World::new
#[derive(Clone, Debug)]
pub(super) struct LoneTriangles {
    bvh: MeshBvh,
    /// What the triangles of the BVH are: runs of consecutive triangle
    /// indices (the lowest wins a tie), by their first.
    runs: Vec<Run>,
    /// The triangles with their corners and boxes, for packet tests;
    /// `None` past [`BAKED_TRIANGLES`] mesh triangles (packets are not used
    /// there).
    triangles: Option<Vec<GroupedTriangle>>,
    /// True when instances' triangles are in the group.
    placed: bool,
}

/// Where a run of grouped triangles, from index `first` on, comes from: the
/// triangles of one mesh instance (of object `object`, in the mesh's
/// order), or `<triangle>` objects with consecutive ids from `object` on
/// (`instance` is `NOT_MESH`). A table of runs, not of triangles: a hit
/// looks its triangle up in a few cached entries, where a table of a
/// million triangles would miss the cache.
#[derive(Clone, Copy, Debug)]
struct Run {
    first: u32,
    object: u32,
    instance: u32,
}

/// [`Run::instance`] of `<triangle>` objects.
const NOT_MESH: u32 = u32::MAX;

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
/// triangles ([`LoneTriangles`]) even when instances share a mesh, and
/// packets of rays can test them (`PacketShapes::MAX_PRIMITIVES`, the same
/// number, says why there). Past it they are placed only when no mesh is
/// shared (so the world holds each triangle once more at most); the group
/// is then kept across worlds while the meshes and their placements stay
/// (`group_cache.rs`).
pub(super) const BAKED_TRIANGLES: usize = 8192;

/// The lone triangles of a world being built, in object order: their world
/// corners as one indexed mesh (a placed mesh's vertices shared as in the
/// mesh, so the group is as watertight as the mesh) and where each comes
/// from.
pub(super) struct GroupInput {
    positions: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    runs: Vec<Run>,
    /// Each triangle with its corners and box, for packet tests; `None` in
    /// a world of more mesh triangles than packets take
    /// ([`BAKED_TRIANGLES`]).
    triangles: Option<Vec<GroupedTriangle>>,
}

impl GroupInput {
    /// An empty group; `for_packets`: its triangles are kept for packet
    /// tests too.
    pub(super) fn new(for_packets: bool) -> Self {
        Self {
            positions: Vec::new(),
            indices: Vec::new(),
            runs: Vec::new(),
            triangles: for_packets.then(Vec::new),
        }
    }

    /// A `<triangle>` object, `bounds` its padded box.
    pub(super) fn triangle(&mut self, object: u32, corners: [Vec3; 3], bounds: Aabb) {
        let first = self.positions.len() as u32;
        self.positions.extend(corners);
        let index = self.indices.len() as u32;
        let follows = self
            .runs
            .last()
            .is_some_and(|r| r.instance == NOT_MESH && r.object + (index - r.first) == object);
        if !follows {
            self.runs.push(Run {
                first: index,
                object,
                instance: NOT_MESH,
            });
        }
        self.indices.push([first, first + 1, first + 2]);
        if let Some(triangles) = &mut self.triangles {
            triangles.push(GroupedTriangle {
                object,
                corners,
                bounds,
                from_mesh: None,
            });
        }
    }

    /// Every triangle of instance `instance` of `object`: its mesh's
    /// vertices placed by `to_world`, each once; `padded` boxes a triangle
    /// as the top level would.
    pub(super) fn instance(
        &mut self,
        object: u32,
        instance: u32,
        mesh: &scene::TriangleMesh,
        to_world: impl Fn(Vec3) -> Vec3,
        padded: impl Fn(Aabb) -> Aabb,
    ) {
        let first = self.positions.len() as u32;
        self.positions
            .extend(mesh.positions.iter().map(|&p| to_world(p)));
        self.runs.push(Run {
            first: self.indices.len() as u32,
            object,
            instance,
        });
        for (k, corners) in mesh.triangles.iter().enumerate() {
            let indices = corners.map(|i| first + i);
            self.indices.push(indices);
            if let Some(triangles) = &mut self.triangles {
                let corners = indices.map(|i| self.positions[i as usize]);
                triangles.push(GroupedTriangle {
                    object,
                    corners,
                    bounds: padded(Aabb::around(corners)),
                    from_mesh: Some((instance, k as u32)),
                });
            }
        }
    }
}

impl LoneTriangles {
    /// The BVH over `input`'s triangles, ties going to the lowest index;
    /// `None` when there are fewer than [`GROUPED_TRIANGLES`].
    pub(super) fn new(input: GroupInput) -> Option<Self> {
        if input.indices.len() < GROUPED_TRIANGLES {
            return None;
        }
        Some(Self {
            bvh: MeshBvh::build(&input.positions, &input.indices),
            placed: input.runs.iter().any(|r| r.instance != NOT_MESH),
            runs: input.runs,
            triangles: input.triangles,
        })
    }

    /// The hit as the object it is (with the mesh triangle and its β and γ
    /// for a placed instance's).
    #[inline(always)]
    fn hit(&self, h: MeshHit) -> Hit {
        let run = self.runs[self.runs.partition_point(|r| r.first <= h.triangle) - 1];
        let offset = h.triangle - run.first;
        if run.instance == NOT_MESH {
            Hit {
                object: run.object + offset,
                alpha: h.alpha,
                triangle: None,
            }
        } else {
            Hit {
                object: run.object,
                alpha: h.alpha,
                triangle: Some(TriangleRef {
                    instance: run.instance,
                    triangle: offset,
                    beta: h.beta,
                    gamma: h.gamma,
                }),
            }
        }
    }

    /// The nearest triangle hit in the ray's interval, as the object it is
    /// (with the mesh triangle and its β and γ for a placed instance's).
    #[inline]
    pub(super) fn closest(&self, ray: &Ray) -> Option<Hit> {
        self.bvh.closest_hit(ray).map(|h| self.hit(h))
    }

    /// [`LoneTriangles::closest`] of every ray, bit for bit, through the
    /// BVH's batch walk ([`MeshBvh::closest_hits`]: packets and interleaved
    /// rays); `found` is scratch of the rays' length.
    pub(super) fn closest_hits(
        &self,
        rays: &[Ray],
        found: &mut [Option<MeshHit>],
        mut each: impl FnMut(usize, Hit),
    ) {
        self.bvh.closest_hits(rays, found);
        for (k, h) in found.iter().enumerate() {
            if let Some(h) = h {
                each(k, self.hit(*h));
            }
        }
    }

    /// The triangles with their corners, by index (the BVH's triangle ids);
    /// `None` past [`BAKED_TRIANGLES`].
    pub(super) fn triangles(&self) -> Option<&[GroupedTriangle]> {
        self.triangles.as_deref()
    }

    /// True when instances' triangles are in the group.
    pub(super) fn has_mesh_triangles(&self) -> bool {
        self.placed
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
    /// The grouped lone triangles ([`Item::LoneTriangles`]), shared with
    /// later worlds of the same triangles (`group_cache.rs`).
    pub(super) lone_triangles: Option<Arc<LoneTriangles>>,
    /// The grouped lone spheres ([`Item::LoneSpheres`]).
    pub(super) lone_spheres: Option<LoneSpheres>,
    /// True when every mesh instance was placed among the lone triangles
    /// (or there is none): the robust top level holds no instance.
    pub(super) instances_grouped: bool,
}

/// The objects a world may group for [`Method::Robust`]: `<triangle>`s and
/// mesh instances' triangles, already grouped ([`LoneTriangles`], `None`
/// when there are too few), the ids of the `<triangle>` objects among them,
/// and `<sphere>`s (object id, the sphere, and its box as the top level has
/// it).
#[derive(Default)]
pub(super) struct Lone {
    pub(super) triangles: Option<Arc<LoneTriangles>>,
    pub(super) triangle_objects: Vec<u32>,
    pub(super) spheres: Vec<(u32, Sphere, Aabb)>,
}

impl TopLevels {
    /// The top levels over `items` (boxed by `bounds`) for both methods; the
    /// `lone` triangles and spheres are grouped for the robust one when
    /// there are enough of them.
    pub(super) fn new(items: Vec<Item>, bounds: &[Aabb], lone: Lone) -> TopLevels {
        let lone_triangles = lone.triangles;
        let (spheres, sphere_bounds): (Vec<(u32, Sphere)>, Vec<Aabb>) =
            lone.spheres.iter().map(|&(id, s, b)| ((id, s), b)).unzip();
        let lone_spheres = LoneSpheres::new(&spheres, &sphere_bounds);
        let mut grouped_ids = Vec::new();
        if lone_triangles.is_some() {
            grouped_ids.extend(lone.triangle_objects.iter().copied());
        }
        // The world places every instance among the lone triangles or none
        // (`World::new`); they are in the group when it exists.
        let placed = lone_triangles
            .as_ref()
            .is_some_and(|g| g.has_mesh_triangles());
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

    /// A world whose meshes are each placed once is grouped past
    /// [`BAKED_TRIANGLES`] too: its hits are the watertight test's on the
    /// placed triangles, brute forced, bit for bit (α, β, γ, the instance
    /// and its triangle), shadow rays agree, and a batch finds the same.
    #[test]
    fn large_unshared_meshes_are_grouped_and_hit_as_brute_force_bit_for_bit() {
        let mut scene = scene::generate::knot_scene(9000);
        scene.camera.width = 48;
        scene.camera.height = 27;
        let world = World::from_scene(&scene).expect("valid");
        assert!(world.instances_grouped(), "each mesh is placed once");
        assert!(
            world.meshes.iter().all(|m| !m.bvh_built()),
            "a grouped world builds no instance BVH"
        );
        let (mut positions, mut indices, mut from) = (Vec::new(), Vec::new(), Vec::new());
        for (instance, placed) in world.meshes.iter().enumerate() {
            let first = positions.len() as u32;
            positions.extend(
                placed
                    .mesh
                    .positions
                    .iter()
                    .map(|&p| placed.instance.point_to_world(p)),
            );
            for (k, t) in placed.mesh.triangles.iter().enumerate() {
                indices.push(t.map(|i| i + first));
                from.push((placed.object, instance as u32, k as u32));
            }
        }
        let mut rays = crate::diagnostics::throughput::primary_rays(&world);
        let mut rng = Sampler::for_sample(3, 0, 0, 0);
        rays.extend((0..600).map(|_| {
            let origin = Vec3::new(
                rng.next_f32() * 8.0 - 4.0,
                rng.next_f32() * 3.0,
                rng.next_f32() * 8.0 - 4.0,
            );
            Ray::new(origin, rng.next_direction())
        }));
        let mut hits = 0;
        for (k, ray) in rays.iter().enumerate() {
            let want = crate::accel::reference::closest_hit(&positions, &indices, ray);
            let got = world.intersect(ray, Method::Robust);
            match (got, want) {
                (Some(got), Some(want)) => {
                    let (object, instance, triangle) = from[want.triangle as usize];
                    let t = got.triangle.expect("a mesh triangle");
                    assert_eq!(
                        (got.object, t.instance, t.triangle, got.alpha.to_bits()),
                        (object, instance, triangle, want.alpha.to_bits()),
                        "ray {k}"
                    );
                    assert_eq!(
                        (t.beta.to_bits(), t.gamma.to_bits()),
                        (want.beta.to_bits(), want.gamma.to_bits())
                    );
                    hits += 1;
                }
                (None, None) => {}
                other => panic!("ray {k}: {other:?}"),
            }
            assert_eq!(
                world.occluded(ray, Method::Robust),
                want.is_some(),
                "ray {k}"
            );
        }
        assert!(hits > 800, "too few hits to mean anything: {hits}");
        let mut batch = vec![None; rays.len()];
        world.intersect_batch(&rays, Method::Robust, &mut batch);
        for (k, (ray, got)) in rays.iter().zip(&batch).enumerate() {
            assert_eq!(*got, world.intersect(ray, Method::Robust), "ray {k}");
        }
        assert!(world.meshes.iter().all(|m| !m.bvh_built()));
        // The lecture's method traces the instances: their BVHs are built
        // then, and find the same triangles.
        let hit = |method| world.intersect(&rays[rays.len() / 2], method);
        let (lecture, robust) = (hit(Method::Lecture), hit(Method::Robust));
        assert!(robust.is_some(), "the middle camera ray hits");
        assert!(world.meshes.iter().any(|m| m.bvh_built()));
        assert_eq!(
            lecture
                .and_then(|h| h.triangle)
                .map(|t| (t.instance, t.triangle)),
            robust
                .and_then(|h| h.triangle)
                .map(|t| (t.instance, t.triangle))
        );
    }

    /// Instances of one mesh past [`BAKED_TRIANGLES`] stay instances (a
    /// group would hold the mesh once per instance).
    #[test]
    fn large_shared_meshes_stay_instances() {
        let mut scene = scene::generate::knot_scene(9000);
        let mut copy = scene.objects[0].clone();
        if let scene::Shape::Mesh { translate, .. } = &mut copy.shape {
            *translate = Some(Vec3::new(3.0, 1.15, 0.0));
        }
        scene.objects.push(copy);
        let world = World::from_scene(&scene).expect("valid");
        assert!(!world.instances_grouped());
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
