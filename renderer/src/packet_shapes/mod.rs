//! Packet intersection for worlds of lone primitives: sixteen rays (one per
//! lane) tested against the triangles, boxes, spheres and infinite planes of
//! a world made of them and at most eight cylinders, cones or tori (a cone's
//! lanes tested together, a cylinder's or torus's lane by lane by its scalar
//! test, `others.rs`), with exactly the [`Method::Robust`] formulas of
//! the scalar code (`shapes/triangle.rs`, `shapes/cuboid.rs`,
//! `shapes/sphere.rs`, `shapes/plane.rs`): the
//! same operations in the same order in every lane, no fused multiply–add,
//! so each lane's α, hit point and normal are bit for bit what
//! [`World::intersect`] and [`World::surface`] give for its ray.
//!
//! Small meshes count as lone triangles: the world places their triangles
//! in world space among its `<triangle>`s ([`World::grouped_triangles`]),
//! and the packets test those same corners. Among these triangles a tie
//! goes to the lowest index, as in the group's BVH, so a lane finds the
//! scalar query's very triangle; its β and γ, which the mesh's shading
//! needs, are the watertight test's again on that one triangle
//! ([`PacketShapes::lane_hit`]).
//!
//! Each primitive's constants are splatted against the sixteen rays in turn.
//! A few primitives ([`PacketShapes::BRUTE_FORCE_MAX`]) are all tested;
//! more are walked through a binary BVH by the whole packet (`tree.rs`),
//! up to [`PacketShapes::MAX_PRIMITIVES`]; planes, which no box holds,
//! after the bounded primitives (`planes.rs`). What depends on the rays only
//! (the watertight test's axis permutation and shear, the spheres' v · v,
//! the reciprocal directions) is computed once per packet.
//!
//! [`Method::Robust`]: crate::shapes::Method::Robust

mod boxes;
mod others;
mod planes;
mod spheres;
mod tree;
mod triangles;

use crate::geometry::ray::Ray;
use crate::packet::ShearedRays;
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, Vec3s, WIDTH};
use crate::shapes::{Method, Shape, Triangle};
use crate::world::{Hit, Object, TriangleRef, World};
use boxes::Boxes;
use others::Others;
use planes::Planes;
use spheres::{SphereRays, Spheres};
use tree::{BoxRays, Leaf, Tree, Visitor};
use triangles::Triangles;

/// The closest hits of a packet: α per lane (+∞ where nothing was hit),
/// the object id hit (−1 where none) and, where a triangle was hit, which.
#[derive(Clone, Copy, Debug)]
pub struct PacketHits<F: FloatLanes> {
    /// α of each lane's nearest hit, +∞ where its ray hit nothing.
    pub alpha: F,
    /// The object id ([`World::objects`] index) hit in each lane, −1 where nothing was.
    pub object: F::Ints,
    /// The triangle hit in each lane, by its key (its index among
    /// [`World::grouped_triangles`], or among the `<triangle>`s in object
    /// order when there is no group); −1 where the hit is no triangle.
    pub triangle: F::Ints,
}

/// Which primitive an object is: its kind ([`TRIANGLE`], [`BOX`],
/// [`SPHERE`], [`PLANE`]; [`NO_KIND`] for no primitive) and its index among that kind's.
#[derive(Clone, Copy, Debug)]
struct Slot {
    /// The kind.
    kind: usize,
    /// The index in the kind's list.
    index: u32,
}

impl Slot {
    /// No primitive.
    const NONE: Slot = Slot {
        kind: NO_KIND,
        index: 0,
    };

    /// As [`PacketShapes::slots`] holds it, for lanes to gather: the kind
    /// in the bits from [`KIND_SHIFT`] up, the index below.
    fn packed(self) -> i32 {
        assert!(
            self.index < 1 << KIND_SHIFT,
            "{} primitives of a kind",
            self.index
        );
        ((self.kind as i32) << KIND_SHIFT) | self.index as i32
    }
}

/// Where a packed [`Slot`] keeps the kind: the bits above the index.
const KIND_SHIFT: i32 = 28;

/// [`Slot::kind`] of a triangle.
const TRIANGLE: usize = 0;
/// [`Slot::kind`] of a box.
const BOX: usize = 1;
/// [`Slot::kind`] of a sphere.
const SPHERE: usize = 2;
/// [`Slot::kind`] of an infinite plane.
const PLANE: usize = 3;
/// [`Slot::kind`] of a shape tested lane by lane (cylinder, cone, torus).
const OTHER: usize = 4;
/// [`Slot::kind`] of a lane that hit nothing.
const NO_KIND: usize = 5;

/// Every primitive of a world made only of lone triangles, small meshes
/// (their triangles placed in world space, as [`World::grouped_triangles`]
/// holds them), boxes, spheres and infinite planes, and at most eight
/// cylinders, cones or tori, laid out for packet tests.
#[derive(Clone, Debug)]
pub struct PacketShapes {
    /// The triangles: `<triangle>` objects and mesh triangles.
    triangles: Triangles,
    /// The `<box>` objects.
    boxes: Boxes,
    /// The `<sphere>` objects.
    spheres: Spheres,
    /// The infinite planes (`<plane>`, `<floor>`), outside the tree.
    planes: Planes,
    /// The cylinders, cones and tori, tested lane by lane, outside the tree.
    others: Others,
    /// Per object id, which primitive it is ([`Slot::packed`]; for a
    /// triangle or a model, only the kind: [`PacketHits::triangle`] says
    /// which triangle), then one entry of no kind, which an id past the
    /// objects (−1: no hit) reads.
    slots: Vec<i32>,
    /// Per triangle key ([`PacketHits::triangle`]), its index in `triangles`.
    triangle_at: Vec<u32>,
    /// Per triangle key, the mesh instance and the triangle's index in its
    /// mesh, for a mesh's triangle (`None` for a `<triangle>`); empty when
    /// the world has no mesh.
    from_mesh: Vec<Option<(u32, u32)>>,
    /// How many primitives there are, planes included.
    count: usize,
    /// With more than [`PacketShapes::BRUTE_FORCE_MAX`] primitives, the
    /// BVH that packets walk (the kinds then hold their primitives in its
    /// leaf order); `None`: every packet tests every primitive.
    tree: Option<Tree>,
}

/// A primitive to lay out: an object that is one (a box, a sphere, a plane,
/// or a `<triangle>` when the world groups no triangles), or a triangle of
/// [`World::grouped_triangles`] (by its index there, its key).
#[derive(Clone, Copy, Debug)]
enum Primitive {
    /// Object id.
    Object(u32),
    /// Index among the grouped triangles.
    Grouped(u32),
}

/// The running nearest hit of a packet while its primitives are tested.
pub(super) struct Nearest<F: FloatLanes> {
    /// Per lane, hits must lie below this: t_max, then the nearest α so far.
    pub(super) limit: F,
    /// Per lane, the object of the nearest hit so far (−1: none yet).
    pub(super) object: F::Ints,
    /// Per lane, the key of the triangle hit nearest so far (−1: none, or
    /// the nearest hit is no triangle).
    pub(super) triangle: F::Ints,
}

impl<F: FloatLanes> Nearest<F> {
    /// No hit yet, in the rays' intervals.
    #[inline(always)]
    fn new(rays: &Rays<F>) -> Self {
        Self {
            limit: rays.t_max,
            object: F::Ints::splat(-1),
            triangle: F::Ints::splat(-1),
        }
    }

    /// Takes `alpha` with `object` in the lanes of `hit` (each of them
    /// nearer than `limit`). Callers take every primitive's lanes, without
    /// first asking whether any lane hit: in incoherent packets that branch
    /// goes either way and mispredicting it cost more than two blends.
    #[inline(always)]
    pub(super) fn take(&mut self, hit: F::Mask, alpha: F, object: i32) {
        self.limit = hit.select(alpha, self.limit);
        self.object = F::Ints::select(hit, F::Ints::splat(object), self.object);
        self.triangle = F::Ints::select(hit, F::Ints::splat(-1), self.triangle);
    }

    /// [`Nearest::take`] for the triangle of key `key`.
    #[inline(always)]
    pub(super) fn take_triangle(&mut self, hit: F::Mask, alpha: F, object: i32, key: i32) {
        self.limit = hit.select(alpha, self.limit);
        self.object = F::Ints::select(hit, F::Ints::splat(object), self.object);
        self.triangle = F::Ints::select(hit, F::Ints::splat(key), self.triangle);
    }

    /// The limit the triangle of key `key` is tested below: `limit`, or
    /// just above it in the lanes whose nearest hit is a triangle of a
    /// higher key, so that at the same α the lowest key wins, as in the
    /// group's BVH ([`crate::accel::MeshBvh::closest_hit`]) whatever the
    /// order the triangles are met in. (There the nearest α is a hit's:
    /// finite and positive, and its next float up is its bits plus one.)
    #[inline(always)]
    pub(super) fn triangle_limit(&self, key: i32) -> F {
        let higher = self.triangle.simd_gt(F::Ints::splat(key));
        let next_up = (self.limit.bits() + F::Ints::splat(1)).bits_to_floats();
        higher.select(next_up, self.limit)
    }

    /// The hits found: α where an object was hit, +∞ elsewhere.
    #[inline(always)]
    fn hits(self) -> PacketHits<F> {
        let found = self.object.simd_gt(F::Ints::splat(-1));
        PacketHits {
            alpha: found.select(self.limit, F::INFINITY),
            object: self.object,
            triangle: self.triangle,
        }
    }
}

/// Whether `p` is a shape without a packet test (cylinder, cone, torus).
fn is_other(world: &World, p: &Primitive) -> bool {
    match *p {
        Primitive::Object(id) => matches!(
            world.shape(id),
            Some(Shape::Cylinder(_) | Shape::Cone(_) | Shape::Torus(_))
        ),
        Primitive::Grouped(_) => false,
    }
}

/// The live lanes of a packet: those with t_max > 0 (dead ones hold 0).
#[inline(always)]
fn live_lanes<F: FloatLanes>(rays: &Rays<F>) -> F::Mask {
    rays.t_max.simd_gt(F::ZERO)
}

impl PacketShapes {
    /// Up to this many primitives, every packet tests every primitive:
    /// below it the tree's box tests cost more than the primitives they
    /// skip (path-traced Cornell box, 14 primitives: 17% slower through a
    /// tree; spheres.xml, 104: twice as fast).
    pub const BRUTE_FORCE_MAX: usize = 20;

    /// The most primitives [`PacketShapes::new`] accepts. A packet walks
    /// the tree node by node, which pays while its rays share nodes; in a
    /// bigger tree incoherent bounce rays part early and the world's own
    /// 8-wide BVH, one ray at a time, walks as well. The wavefront path
    /// tracer through the tree against the same through the world's BVH
    /// (32 spp, 2 threads, 512×384, medians of 3 alternated runs): grids
    /// of 324, 900 and 2,500 spheres 0.99 against 2.25 s, 1.18 against
    /// 2.43 s, 1.22 against 2.51 s; 3,000 spheres scattered in the air
    /// 3.72 against 3.80 s; a sphere of 3,480 lone triangles 1.06 against
    /// 1.76 s; at 16 spp, a grid of 10,000 spheres 1.45 against 1.29 s and
    /// 10,000 scattered 2.68 against 2.81 s. Meshes placed in world space
    /// (glTF ducks of 4,212 triangles on a floor, under an area light):
    /// one duck 1.34 against 1.79 s, two 2.27 against 2.47 s, three 2.67
    /// against 2.62 s (through each instance's BVH, ray by ray).
    pub const MAX_PRIMITIVES: usize = 8192;

    /// `None` when `world` holds anything else (a mesh too large to be
    /// placed among its lone triangles), more than [`Others::MAX`]
    /// cylinders, cones and tori (each tested lane by lane), more
    /// than [`PacketShapes::MAX_PRIMITIVES`] primitives, or primitives so
    /// unevenly spread that their tree would be deeper than its walk's stack
    /// (64 levels); such worlds are traced by the scalar lanes.
    pub fn new(world: &World) -> Option<Self> {
        let primitives = Self::primitives(world)?;
        let with_tree = primitives.len() > Self::BRUTE_FORCE_MAX;
        Self::laid_out(world, &primitives, with_tree)
    }

    /// The world's primitives, planes included: the grouped triangles when
    /// there is a group, then every other object that is one; `None` when
    /// an object has no packet test or there are too many.
    fn primitives(world: &World) -> Option<Vec<Primitive>> {
        let grouped = world.grouped_triangles();
        let mut primitives: Vec<Primitive> = grouped
            .map_or(0..0, |g| 0..g.len() as u32)
            .map(Primitive::Grouped)
            .collect();
        for (id, object) in world.objects.iter().enumerate() {
            match object {
                Object::Shape(Shape::Triangle(_)) if grouped.is_some() => {}
                Object::Shape(_) => primitives.push(Primitive::Object(id as u32)),
                // Its instances' triangles are among the grouped ones.
                Object::Model { .. } if world.instances_grouped() && grouped.is_some() => {}
                _ => return None,
            }
        }
        let others = primitives.iter().filter(|p| is_other(world, p)).count();
        (primitives.len() <= Self::MAX_PRIMITIVES && others <= Others::MAX).then_some(primitives)
    }

    /// [`PacketShapes::new`] with a tree or without, whatever the count.
    #[cfg(test)]
    fn with_tree_or_not(world: &World, with_tree: bool) -> Option<Self> {
        Self::laid_out(world, &Self::primitives(world)?, with_tree)
    }

    /// `world`'s `primitives` laid out, in a tree or not.
    fn laid_out(world: &World, primitives: &[Primitive], with_tree: bool) -> Option<Self> {
        let grouped = world.grouped_triangles().unwrap_or(&[]);
        // Keys: a grouped triangle's index in the group; without a group,
        // the `<triangle>`s numbered in object order.
        let mut key_of = vec![-1i32; world.objects.len()];
        let mut next_key = 0;
        for p in primitives {
            if let Primitive::Object(id) = *p
                && matches!(world.shape(id), Some(Shape::Triangle(_)))
            {
                key_of[id as usize] = next_key;
                next_key += 1;
            }
        }
        let mut shapes = PacketShapes {
            triangles: Triangles::default(),
            boxes: Boxes::default(),
            spheres: Spheres::default(),
            planes: Planes::default(),
            others: Others::default(),
            slots: vec![Slot::NONE.packed(); world.objects.len() + 1],
            triangle_at: vec![0; grouped.len() + next_key as usize],
            from_mesh: Vec::new(),
            count: primitives.len(),
            tree: None,
        };
        if grouped.iter().any(|t| t.from_mesh.is_some()) {
            shapes.from_mesh = grouped.iter().map(|t| t.from_mesh).collect();
        }
        let push = |shapes: &mut PacketShapes, p: Primitive| match p {
            Primitive::Grouped(k) => {
                let t = &grouped[k as usize];
                let index = shapes.triangles.push(t.object as i32, &t.corners, k as i32);
                shapes.triangle_at[k as usize] = index;
                shapes.slots[t.object as usize] = Slot {
                    kind: TRIANGLE,
                    index: 0,
                }
                .packed();
            }
            Primitive::Object(id) => shapes.push(world, id, key_of[id as usize]),
        };
        // Planes and the shapes tested lane by lane stay outside the tree.
        let outside_tree = |p: &Primitive| match *p {
            Primitive::Object(id) => matches!(world.shape(id), Some(Shape::Plane(_))),
            Primitive::Grouped(_) => false,
        } || is_other(world, p);
        if !with_tree || primitives.is_empty() {
            for &p in primitives {
                push(&mut shapes, p);
            }
            return Some(shapes);
        }
        let items = primitives
            .iter()
            .enumerate()
            .filter(|(_, p)| !outside_tree(p))
            .map(|(k, p)| {
                let bounds = match *p {
                    Primitive::Grouped(g) => grouped[g as usize].bounds,
                    Primitive::Object(id) => world.shape_bounds(id)?,
                };
                Some((k as u32, bounds))
            })
            .collect::<Option<Vec<_>>>()?;
        for &p in primitives.iter().filter(|p| outside_tree(p)) {
            push(&mut shapes, p);
        }
        if items.is_empty() {
            return Some(shapes);
        }
        let tree = Tree::build(&items, |ks| {
            let before = shapes.counts();
            for &k in ks {
                push(&mut shapes, primitives[k as usize]);
            }
            let after = shapes.counts();
            Leaf {
                triangles: before[TRIANGLE]..after[TRIANGLE],
                boxes: before[BOX]..after[BOX],
                spheres: before[SPHERE]..after[SPHERE],
            }
        })?;
        shapes.tree = Some(tree);
        Some(shapes)
    }

    /// Adds object `id` of `world` (a lone triangle of key `key`, a box, a
    /// sphere or a plane) to its kind.
    fn push(&mut self, world: &World, id: u32, key: i32) {
        let object = id as i32;
        let (kind, index) = match &world.objects[id as usize] {
            Object::Shape(Shape::Triangle(t)) => {
                let index = self.triangles.push(object, &[t.t0, t.t1, t.t2], key);
                self.triangle_at[key as usize] = index;
                (TRIANGLE, 0)
            }
            Object::Shape(Shape::Box(b)) => (BOX, self.boxes.push(object, b)),
            Object::Shape(Shape::Sphere(s)) => (SPHERE, self.spheres.push(object, s)),
            Object::Shape(Shape::Plane(p)) => (PLANE, self.planes.push(object, p)),
            Object::Shape(shape) => (OTHER, self.others.push(object, shape)),
            other => unreachable!("object {id} has no packet test: {other:?}"),
        };
        self.slots[id as usize] = Slot { kind, index }.packed();
    }

    /// How many primitives each bounded kind holds.
    fn counts(&self) -> [usize; 3] {
        [self.triangles.len(), self.boxes.len(), self.spheres.len()]
    }

    /// How many primitives there are.
    pub fn len(&self) -> usize {
        self.count
    }

    /// True when the world has no primitive.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The nearest hit of each lane's ray in (0, t_max). Adds to `tests`,
    /// lane by lane, how many primitives its ray was tested against.
    #[inline(always)]
    pub fn closest<F: FloatLanes>(&self, rays: &Rays<F>, tests: &mut F::Ints) -> PacketHits<F> {
        let live = live_lanes(rays);
        let mut search = Closest {
            prepared: Prepared::new(self, rays, live, *tests),
            nearest: Nearest::new(rays),
            live,
        };
        if live.any() {
            self.search(rays, live, &mut search);
            self.others
                .closest(rays, live, &mut search.nearest, &mut search.prepared.tests);
            // Planes last: a plane must be strictly nearer.
            self.planes
                .closest(rays, live, &mut search.nearest, &mut search.prepared.tests);
        }
        *tests = search.prepared.tests;
        search.nearest.hits()
    }

    /// Per lane: true when anything lies on its ray in (0, t_max) (stop
    /// testing once every lane is blocked). Adds to `tests`, lane by lane,
    /// how many primitives its ray was tested against.
    #[inline(always)]
    pub fn occluded<F: FloatLanes>(&self, rays: &Rays<F>, tests: &mut F::Ints) -> F::Mask {
        let live = live_lanes(rays);
        if !live.any() {
            return F::Mask::NONE;
        }
        let mut search = Occluded {
            prepared: Prepared::new(self, rays, live, *tests),
            // Lanes settled: blocked ones, and the dead ones from the start.
            settled: !live,
        };
        // Planes first, as the scalar test has them; the lanes they block
        // walk no further.
        let all_blocked =
            self.planes
                .occluded(rays, &mut search.settled, &mut search.prepared.tests);
        if !all_blocked && self.others.len() > 0 {
            self.others
                .occluded(rays, &mut search.settled, &mut search.prepared.tests);
        }
        if !all_blocked && !search.settled.all() {
            let open = !search.settled;
            self.search(rays, open, &mut search);
        }
        *tests = search.prepared.tests;
        search.settled & live
    }

    /// Hands `visitor` the leaves the lanes `live` of `rays` may hit: those
    /// the tree lets through, or every primitive as one leaf.
    #[inline(always)]
    fn search<F: FloatLanes>(&self, rays: &Rays<F>, live: F::Mask, visitor: &mut impl Visitor<F>) {
        match &self.tree {
            Some(tree) => tree.walk(&BoxRays::new(rays), visitor),
            None => {
                visitor.leaf(&self.everything(), live);
            }
        }
    }

    /// A leaf of every primitive (no tree).
    #[inline(always)]
    fn everything(&self) -> Leaf {
        let [triangles, boxes, spheres] = self.counts();
        Leaf {
            triangles: 0..triangles,
            boxes: 0..boxes,
            spheres: 0..spheres,
        }
    }

    /// Lane `k` of `hits` as the world's query gives it: with the mesh
    /// triangle and its β and γ ([`World::intersect`]'s, bit for bit: the
    /// watertight test again, on `ray`, lane `k`'s ray) where the lane hit a
    /// mesh's triangle; `None` where it hit nothing.
    pub fn lane_hit<F: FloatLanes>(
        &self,
        hits: &PacketHits<F>,
        k: usize,
        ray: &Ray,
    ) -> Option<Hit> {
        let alpha = hits.alpha.as_array()[k];
        if alpha == f32::INFINITY {
            return None;
        }
        let key = hits.triangle.to_array()[k];
        let triangle =
            self.from_mesh
                .get(key as usize)
                .copied()
                .flatten()
                .map(|(instance, triangle)| {
                    let corners = self.triangles.corners(self.triangle_at[key as usize]);
                    let hit =
                        Triangle::new(corners[0], corners[1], corners[2]).hit(ray, Method::Robust);
                    debug_assert_eq!(hit.map(|h| h.alpha), Some(alpha), "lane {k}: {ray:?}");
                    let (beta, gamma) = hit.map_or((0.0, 0.0), |h| (h.beta, h.gamma));
                    TriangleRef {
                        instance,
                        triangle,
                        beta,
                        gamma,
                    }
                });
        Some(Hit {
            object: hits.object.to_array()[k] as u32,
            alpha,
            triangle,
        })
    }

    /// True when some triangle comes from a mesh, whose hits
    /// [`PacketShapes::lane_hit`] completes.
    pub fn has_meshes(&self) -> bool {
        !self.from_mesh.is_empty()
    }

    /// The lanes of `hits` that hit a mesh's triangle.
    #[inline(always)]
    pub fn mesh_lanes<F: FloatLanes>(&self, hits: &PacketHits<F>) -> F::Mask {
        if !self.has_meshes() {
            return F::Mask::NONE;
        }
        let keys = hits.triangle.to_array();
        F::Mask::from_bitmask((0..WIDTH).fold(0, |bits, k| {
            let mesh = self
                .from_mesh
                .get(keys[k] as usize)
                .is_some_and(Option::is_some);
            bits | (u32::from(mesh) << k)
        }))
    }

    /// The hit point and unit outward geometric normal at each lane's hit,
    /// equal bit for bit to `world.surface(&ray, hit)` (i.e.
    /// `Shape::surface`) for lanes that hit an analytic shape; for a mesh's
    /// triangle, the point and normal of its plane as a `<triangle>` would
    /// have them (not the mesh's: shade those lanes from
    /// [`PacketShapes::lane_hit`]); anything for the others.
    #[inline(always)]
    pub fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        hits: &PacketHits<F>,
    ) -> (Vec3s<F>, Vec3s<F>) {
        // Each lane's primitive: its kind and its index among that kind's
        // (a triangle's by its key), gathered on lanes.
        let slot = F::Ints::gather_from(&self.slots, hits.object);
        let kinds = slot.shr::<KIND_SHIFT>();
        let mut at = slot & F::Ints::splat((1 << KIND_SHIFT) - 1);
        if !self.triangle_at.is_empty() {
            let triangle_at: &[i32] = bytemuck::cast_slice(&self.triangle_at);
            let triangles = F::Ints::gather_from(triangle_at, hits.triangle);
            at = F::Ints::select(
                kinds.simd_gt(F::Ints::splat(TRIANGLE as i32)),
                at,
                triangles,
            );
        }
        // Per kind, its lanes and their indices (0 in the other lanes,
        // which its surface also reads).
        let mut index = [[0u32; WIDTH]; NO_KIND + 1];
        let mut bits = [0u32; NO_KIND + 1];
        for kind in [TRIANGLE, BOX, SPHERE, PLANE, OTHER] {
            let lanes = of_kind::<F>(kinds, kind);
            bits[kind] = lanes.to_bitmask();
            if bits[kind] != 0 {
                let own = F::Ints::select(lanes, at, F::Ints::splat(0)).to_array();
                index[kind] = own.map(|i| i as u32);
            }
        }
        let hit_bits = bits[TRIANGLE] | bits[BOX] | bits[SPHERE] | bits[PLANE] | bits[OTHER];
        let (mut point, mut normal) = (Vec3s::ZERO, Vec3s::ZERO);
        for kind in [TRIANGLE, BOX, SPHERE, PLANE, OTHER] {
            if bits[kind] == 0 {
                continue;
            }
            let (p, n) = match kind {
                TRIANGLE => self.triangles.surface(rays, hits.alpha, &index[kind]),
                BOX => self.boxes.surface(rays, hits.alpha, &index[kind]),
                SPHERE => self.spheres.surface(rays, hits.alpha, &index[kind]),
                PLANE => self.planes.surface(rays, hits.alpha, &index[kind]),
                _ => self
                    .others
                    .surface(rays, hits.alpha, &index[kind], bits[kind]),
            };
            if bits[kind] == hit_bits {
                // Every lane that hit, hit this kind.
                return (p, n);
            }
            let mask = F::Mask::from_bitmask(bits[kind]);
            point = Vec3s::select(mask, p, point);
            normal = Vec3s::select(mask, n, normal);
        }
        (point, normal)
    }
}

/// What both searches share: the rays prepared for each kind's test, and
/// the count of tests.
struct Prepared<'a, F: FloatLanes> {
    shapes: &'a PacketShapes,
    rays: &'a Rays<F>,
    /// The rays prepared for triangles (when there are any).
    sheared: Option<ShearedRays<F>>,
    /// The rays prepared for spheres.
    spheres: SphereRays<F>,
    /// Per lane, primitives tested.
    tests: F::Ints,
}

impl<'a, F: FloatLanes> Prepared<'a, F> {
    /// `rays` (live in `live`) prepared for `shapes`' tests, `tests` counted so far.
    #[inline(always)]
    fn new(shapes: &'a PacketShapes, rays: &'a Rays<F>, live: F::Mask, tests: F::Ints) -> Self {
        Self {
            shapes,
            rays,
            sheared: (!shapes.triangles.is_empty()).then(|| ShearedRays::new(rays, live)),
            spheres: SphereRays::new(rays),
            tests,
        }
    }
}

/// A nearest-hit search: the prepared rays and the nearest hit so far.
struct Closest<'a, F: FloatLanes> {
    prepared: Prepared<'a, F>,
    nearest: Nearest<F>,
    /// The lanes with a ray.
    live: F::Mask,
}

impl<F: FloatLanes> Visitor<F> for Closest<'_, F> {
    #[inline(always)]
    fn limit(&self) -> F {
        self.nearest.limit
    }

    #[inline(always)]
    fn searching(&self) -> F::Mask {
        self.live
    }

    /// Tests the leaf's triangles, boxes, then spheres, each kind in order.
    #[inline(always)]
    fn leaf(&mut self, leaf: &Leaf, entered: F::Mask) -> bool {
        let p = &mut self.prepared;
        if let Some(sheared) = &p.sheared {
            let range = leaf.triangles.clone();
            p.shapes
                .triangles
                .closest(sheared, range, &mut self.nearest);
        }
        let range = leaf.boxes.clone();
        p.shapes.boxes.closest(p.rays, range, &mut self.nearest);
        let range = leaf.spheres.clone();
        p.shapes
            .spheres
            .closest(&p.spheres, range, &mut self.nearest);
        p.tests = p.tests + count::<F>(entered, leaf.len());
        false
    }
}

/// An any-hit search: the prepared rays and the lanes settled so far.
struct Occluded<'a, F: FloatLanes> {
    prepared: Prepared<'a, F>,
    /// Blocked lanes and dead ones.
    settled: F::Mask,
}

impl<F: FloatLanes> Visitor<F> for Occluded<'_, F> {
    #[inline(always)]
    fn limit(&self) -> F {
        self.prepared.rays.t_max
    }

    #[inline(always)]
    fn searching(&self) -> F::Mask {
        !self.settled
    }

    /// Tests the leaf's triangles, boxes, then spheres; true once every
    /// lane is settled.
    #[inline(always)]
    fn leaf(&mut self, leaf: &Leaf, entered: F::Mask) -> bool {
        let p = &mut self.prepared;
        let t_max = p.rays.t_max;
        p.tests = p.tests + count::<F>(entered, leaf.len());
        let settled = &mut self.settled;
        if let Some(sheared) = &p.sheared
            && p.shapes
                .triangles
                .occluded(sheared, leaf.triangles.clone(), t_max, settled)
        {
            return true;
        }
        if p.shapes.boxes.occluded(p.rays, leaf.boxes.clone(), settled) {
            return true;
        }
        p.shapes
            .spheres
            .occluded(&p.spheres, leaf.spheres.clone(), t_max, settled)
    }
}

/// The lanes whose kind (`kinds`) is `kind`.
#[inline(always)]
fn of_kind<F: FloatLanes>(kinds: F::Ints, kind: usize) -> F::Mask {
    let from = kinds.simd_gt(F::Ints::splat(kind as i32 - 1));
    let past = kinds.simd_gt(F::Ints::splat(kind as i32));
    from & !past
}

/// `n` in the lanes of `lanes`, 0 elsewhere.
#[inline(always)]
fn count<F: FloatLanes>(lanes: F::Mask, n: usize) -> F::Ints {
    F::Ints::select(lanes, F::Ints::splat(n as i32), F::Ints::splat(0))
}

/// Sixteen lanes' values of a primitive kind's data, each lane's from the
/// primitive `index[lane]`.
#[inline(always)]
fn gather<F: FloatLanes>(index: &[u32; WIDTH], value: impl Fn(usize) -> f32) -> F {
    F::from_array(std::array::from_fn::<f32, WIDTH, _>(|lane| {
        value(index[lane] as usize)
    }))
}

/// Sixteen lanes' vectors of a primitive kind's data, each lane's from the
/// primitive `index[lane]`.
#[inline(always)]
fn gather3<F: FloatLanes>(index: &[u32; WIDTH], value: impl Fn(usize) -> glam::Vec3) -> Vec3s<F> {
    Vec3s::from_lanes(&std::array::from_fn(|lane| value(index[lane] as usize)))
}

/// Coordinate `axis` (0, 1, 2: x, y, z) of sixteen vectors.
#[inline(always)]
fn coordinate<F: FloatLanes>(v: &Vec3s<F>, axis: usize) -> F {
    match axis {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// Shared by the kinds' tests: worlds from scene text and rays aimed at
/// what is hard to get right (edges, vertices, silhouettes, short intervals).
#[cfg(test)]
pub(super) mod testing {
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::integrator::sampler::Sampler;
    use crate::packet::lane_set;
    use crate::shapes::Method;
    use crate::simd::{WithLanes, on_every_lane_type};
    use crate::world::Hit;
    use glam::Vec3;

    /// The world of a scene given as XML.
    pub fn world_of(xml: &str) -> World {
        World::from_scene(&scene::read_str(xml, "test.xml").expect("parses")).expect("valid")
    }

    /// The world of `assets/reference/<name>`.
    pub fn reference_world(name: &str) -> World {
        let path = format!("{}/../assets/reference/{name}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("reference scene");
        World::from_scene(&scene::read_str(&text, &path).expect("parses")).expect("valid")
    }

    /// Asserts that every lane of a packet test of one primitive agrees bit
    /// for bit with the scalar primitive on that lane's ray: α where `hit`
    /// is set against `intersect`, and the hit's `point` and `normal`
    /// against `surface`. Returns how many lanes hit.
    pub fn assert_lanes_equal_scalar<F: FloatLanes>(
        lanes: &[Ray; WIDTH],
        (hit, alpha): (F::Mask, F),
        (point, normal): (Vec3s<F>, Vec3s<F>),
        intersect: impl Fn(&Ray) -> Option<f32>,
        surface: impl Fn(&Ray, f32) -> crate::shapes::Surface,
        shape: &dyn std::fmt::Debug,
    ) -> usize {
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        let mut hits = 0;
        for (k, ray) in lanes.iter().enumerate() {
            let want = intersect(ray);
            let got = lane_set(hit, k).then(|| alpha.as_array()[k]);
            let context = || format!("lane {k}: {ray:?} {shape:?}");
            assert_eq!(
                got.map(f32::to_bits),
                want.map(f32::to_bits),
                "α, {}",
                context()
            );
            if let Some(alpha) = want {
                hits += 1;
                let s = surface(ray, alpha);
                assert_eq!(bits(point.lane(k)), bits(s.point), "point, {}", context());
                assert_eq!(
                    bits(normal.lane(k)),
                    bits(s.normal),
                    "normal, {}",
                    context()
                );
            }
        }
        hits
    }

    /// A dead lane: any ray over the empty interval.
    pub fn dead(k: usize) -> Ray {
        Ray::new(Vec3::splat(k as f32 - 3.0), Vec3::X).with_t_max(0.0)
    }

    /// Packs `rays` (at most [`WIDTH`]) in the lanes listed by `lanes`
    /// (distinct), the other lanes dead.
    pub fn packet(rays: &[Ray], lanes: &[usize]) -> [Ray; WIDTH] {
        let mut packed: [Ray; WIDTH] = std::array::from_fn(dead);
        for (ray, &lane) in rays.iter().zip(lanes) {
            packed[lane] = *ray;
        }
        packed
    }

    /// `count` rays around and through `world`'s primitives, seeded: from
    /// random points and from points on surfaces (α ≈ 0 self-hits), aimed
    /// at random points, at vertices, along edges, at silhouettes, with
    /// axis-parallel directions (zero and −0 components), some with t_max
    /// cut before or just at the target.
    pub fn rays_for(world: &World, seed: u64, count: usize) -> Vec<Ray> {
        let mut rng = Sampler::for_sample(seed, 0, 0, 0);
        let targets = targets_of(world);
        let mut rays = Vec::with_capacity(count);
        let scale = targets
            .iter()
            .fold(1.0f32, |s, t| s.max(t.abs().max_element()));
        while rays.len() < count {
            let k = rays.len();
            let pick = |rng: &mut Sampler, n: usize| {
                ((rng.next_f32() * n as f32) as usize).min(n.saturating_sub(1))
            };
            let target = if targets.is_empty() {
                Vec3::ZERO
            } else {
                let a = targets[pick(&mut rng, targets.len())];
                let b = targets[pick(&mut rng, targets.len())];
                match k % 4 {
                    // A vertex, corner or centre exactly.
                    0 => a,
                    // A point on the segment between two (an edge, often).
                    1 => {
                        let s = rng.next_f32();
                        a + s * (b - a)
                    }
                    // Near one.
                    2 => a + 0.05 * scale * rng.next_direction(),
                    _ => {
                        scale * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0
                            - scale
                    }
                }
            };
            let origin = match k % 5 {
                0 | 1 => 1.5 * scale * rng.next_direction() * rng.next_f32().sqrt(),
                2 => 4.0 * scale * rng.next_direction(),
                3 => {
                    // On a surface: where an earlier ray hit.
                    let from = rays
                        .get(k / 2)
                        .copied()
                        .unwrap_or(Ray::new(Vec3::ZERO, Vec3::Z));
                    match world.intersect(&from, Method::Robust) {
                        Some(hit) => world.surface(&from, hit).point,
                        None => Vec3::ZERO,
                    }
                }
                _ => {
                    // A lattice point (exact edge-function zeros).
                    let mut c = || (rng.next_f32() * 5.0).floor() - 2.0;
                    Vec3::new(c(), c(), c()) * 0.5
                }
            };
            let mut dir = match k % 7 {
                // Axis-parallel, with signed zeros.
                0 => {
                    let axis = pick(&mut rng, 3);
                    let sign = if rng.next_f32() < 0.5 { -1.0 } else { 1.0 };
                    let zero = if rng.next_f32() < 0.5 { -0.0 } else { 0.0 };
                    let mut d = Vec3::splat(zero);
                    d[axis] = sign;
                    d
                }
                1 => rng.next_direction(),
                _ => (target - origin).normalize_or(Vec3::Y),
            };
            if k % 11 == 0 {
                // Not unit length: α scales with 1/‖v‖.
                dir *= 0.5 + 2.0 * rng.next_f32();
            }
            let mut ray = Ray::new(origin, dir);
            match k % 6 {
                0 => ray.t_max = (target - origin).length() * (0.25 + rng.next_f32()),
                1 => ray.t_max = (target - origin).length(),
                _ => {}
            }
            rays.push(ray);
        }
        rays
    }

    /// Points worth aiming at: triangles' corners, boxes' corners and
    /// centres, spheres' centres and silhouette points.
    fn targets_of(world: &World) -> Vec<Vec3> {
        let mut targets = Vec::new();
        for object in &world.objects {
            match object {
                Object::Shape(Shape::Triangle(t)) => targets.extend([t.t0, t.t1, t.t2]),
                Object::Shape(Shape::Box(b)) => {
                    let (placement, half) = (b.placement(), b.half());
                    targets.push(placement.origin);
                    for corner in 0..8 {
                        let sign = |bit: usize| if corner & (1 << bit) != 0 { 1.0 } else { -1.0 };
                        let local = Vec3::new(sign(0), sign(1), sign(2)) * half;
                        targets.push(placement.point_to_world(local));
                    }
                }
                Object::Shape(Shape::Sphere(s)) => {
                    targets.push(s.center);
                    for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
                        targets.push(s.center + s.radius * axis);
                        targets.push(s.center - s.radius * axis);
                    }
                }
                _ => {}
            }
        }
        // Mesh triangles' corners, placed in world space.
        let placed = world.grouped_triangles().unwrap_or(&[]).iter();
        targets.extend(
            placed
                .filter(|t| t.from_mesh.is_some())
                .flat_map(|t| t.corners),
        );
        targets
    }

    /// Checks every live lane of `lanes` (with `packet`'s answers, in lanes
    /// `F`) against the scalar world: the same α bits and object (on an
    /// exact tie, an object the scalar test also hits at that α), the same
    /// occlusion, the same surface bits. Dead lanes hit nothing and are not
    /// occluded. Returns how many lanes hit.
    pub fn check_packet_with<F: FloatLanes>(
        world: &World,
        shapes: &PacketShapes,
        lanes: &[Ray; WIDTH],
    ) -> usize {
        let rays = Rays::<F>::from_lanes(lanes);
        let (mut closest_tests, mut occluded_tests) = (F::Ints::splat(0), F::Ints::splat(0));
        let hits = shapes.closest(&rays, &mut closest_tests);
        let blocked = shapes.occluded(&rays, &mut occluded_tests);
        let (point, normal) = shapes.surface(&rays, &hits);
        let objects = hits.object.to_array();
        let mut found = 0;
        for (k, ray) in lanes.iter().enumerate() {
            let (alpha, object) = (hits.alpha.as_array()[k], objects[k]);
            for (tests, shadow) in [(closest_tests, false), (occluded_tests, true)]
                .map(|(t, shadow)| (t.to_array()[k] as usize, shadow))
            {
                // Every primitive without a tree, at most every one with it
                // (or when a plane or a cylinder, cone or torus, met first,
                // blocks a shadow ray).
                let stops_early = shadow && (!shapes.planes.is_empty() || shapes.others.len() > 0);
                let expected = match (&shapes.tree, ray.t_max) {
                    (_, 0.0) => 0..=0,
                    (None, _) if !stops_early => shapes.len()..=shapes.len(),
                    _ => 0..=shapes.len(),
                };
                assert!(expected.contains(&tests), "lane {k}: {tests} tests");
            }
            if ray.t_max == 0.0 {
                assert_eq!((alpha, object), (f32::INFINITY, -1), "dead lane {k}");
                assert!(!lane_set(blocked, k), "dead lane {k}");
                continue;
            }
            let want = world.intersect(ray, Method::Robust);
            assert_eq!(
                alpha.to_bits(),
                want.map_or(f32::INFINITY, |h| h.alpha).to_bits(),
                "lane {k}: {ray:?} want {want:?}, got α {alpha} object {object}"
            );
            assert_eq!(
                lane_set(blocked, k),
                world.occluded(ray, Method::Robust),
                "occluded, lane {k}: {ray:?}"
            );
            let Some(want) = want else {
                assert_eq!(object, -1, "lane {k}: {ray:?}");
                continue;
            };
            found += 1;
            let object = u32::try_from(object).expect("a hit has an object");
            // Among the grouped triangles a tie goes to the lowest index,
            // in packets as in the group's BVH: the same triangle, and on a
            // mesh the same β and γ.
            let grouped = |id: u32| {
                world.grouped_triangles().is_some()
                    && matches!(
                        world.objects[id as usize],
                        Object::Model { .. } | Object::Shape(Shape::Triangle(_))
                    )
            };
            if grouped(object) && grouped(want.object) {
                assert_eq!(
                    object, want.object,
                    "lane {k}: a tie among triangles: {ray:?}"
                );
            }
            let got = shapes.lane_hit(&hits, k, ray).expect("a lane that hit");
            if object == want.object && (want.triangle.is_some() || got.triangle.is_some()) {
                let bits = |h: Hit| {
                    let t = h
                        .triangle
                        .map(|t| (t.instance, t.triangle, t.beta.to_bits(), t.gamma.to_bits()));
                    (h.object, h.alpha.to_bits(), t)
                };
                assert_eq!(bits(got), bits(want), "lane {k}: a mesh's hit: {ray:?}");
                // Its surface is the mesh's, which the scalar code shades.
                continue;
            }
            if object != want.object {
                // A plane ties with nothing: it wins only when strictly nearer.
                let plane = |id: u32| matches!(world.shape(id), Some(Shape::Plane(_)));
                assert!(
                    !plane(object) && !plane(want.object),
                    "lane {k}: object {object} instead of {} (a plane): {ray:?}",
                    want.object
                );
                // Another object at exactly that α (a box standing on a
                // mesh's floor, seen from below): the packet's object must
                // lie there too.
                let at = match got.triangle {
                    Some(_) => {
                        let key = hits.triangle.to_array()[k];
                        let c = shapes.triangles.corners(shapes.triangle_at[key as usize]);
                        Triangle::new(c[0], c[1], c[2]).intersect(ray, Method::Robust)
                    }
                    None => world
                        .shape(object)
                        .expect("an analytic shape")
                        .intersect(ray, Method::Robust),
                };
                assert_eq!(
                    at.map(f32::to_bits),
                    Some(alpha.to_bits()),
                    "lane {k}: object {object} instead of {} without a tie: {ray:?}",
                    want.object
                );
                if got.triangle.is_some() {
                    continue;
                }
            }
            let hit = Hit {
                object,
                alpha,
                triangle: None,
            };
            let surface = world.surface(ray, hit);
            let (p, n) = (point.lane(k), normal.lane(k));
            assert_eq!(
                (
                    p.to_array().map(f32::to_bits),
                    n.to_array().map(f32::to_bits)
                ),
                (
                    surface.point.to_array().map(f32::to_bits),
                    surface.normal.to_array().map(f32::to_bits)
                ),
                "surface, lane {k}: {ray:?}: {p} {n} against {surface:?}"
            );
        }
        found
    }

    /// [`check_packet_with`] for every lane type.
    #[derive(Clone)]
    struct CheckPacket<'a> {
        world: &'a World,
        shapes: &'a PacketShapes,
        lanes: &'a [Ray; WIDTH],
    }

    impl WithLanes for CheckPacket<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            check_packet_with::<F>(self.world, self.shapes, self.lanes)
        }
    }

    /// [`check_packet_with`] with every lane type (each must pass, and find
    /// as many hits). Returns how many lanes hit.
    pub fn check_packet(world: &World, shapes: &PacketShapes, lanes: &[Ray; WIDTH]) -> usize {
        same_everywhere(on_every_lane_type(CheckPacket {
            world,
            shapes,
            lanes,
        }))
    }

    /// The one value every lane type gave.
    pub fn same_everywhere<T: PartialEq + std::fmt::Debug>(results: Vec<T>) -> T {
        let mut results = results.into_iter();
        let first = results.next().expect("at least one lane type");
        for other in results {
            assert_eq!(other, first, "lane types disagree");
        }
        first
    }

    /// Checks `rays` in packets of sixteen (in lanes `F`), then each of them
    /// again in lane `k % 8` among dead lanes and among other rays in
    /// other orders (a lane's answer must not depend on its neighbours).
    /// Returns how many lanes hit in the first pass.
    fn check_rays_with<F: FloatLanes>(world: &World, rays: &[Ray], tree: bool) -> usize {
        let shapes = PacketShapes::with_tree_or_not(world, tree).expect("a packet world");
        let bounded = shapes.counts().iter().sum::<usize>() > 0;
        assert_eq!(shapes.tree.is_some(), tree && bounded);
        let mut found = 0;
        for chunk in rays.chunks(WIDTH) {
            let lanes: Vec<usize> = (0..chunk.len()).collect();
            found += check_packet_with::<F>(world, &shapes, &packet(chunk, &lanes));
        }
        for (k, ray) in rays.iter().enumerate() {
            // Alone among dead lanes.
            check_packet_with::<F>(world, &shapes, &packet(&[*ray], &[k % WIDTH]));
            // Among neighbours from elsewhere in the list, with two lanes dead.
            if k % 3 == 0 {
                let others: Vec<Ray> = (1..6)
                    .map(|j| rays[(k * 7 + j * 13) % rays.len()])
                    .collect();
                let mut group = vec![*ray];
                group.extend(others);
                let lanes: Vec<usize> = (0..group.len()).map(|j| (k + 3 * j) % WIDTH).collect();
                check_packet_with::<F>(world, &shapes, &packet(&group, &lanes));
            }
        }
        found
    }

    /// [`check_rays_with`] for every lane type.
    #[derive(Clone)]
    struct CheckRays<'a> {
        world: &'a World,
        rays: &'a [Ray],
    }

    impl WithLanes for CheckRays<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            let with_tree = check_rays_with::<F>(self.world, self.rays, true);
            let without = check_rays_with::<F>(self.world, self.rays, false);
            assert_eq!(with_tree, without, "hits with and without the tree");
            with_tree
        }
    }

    /// [`check_rays_with`] with every lane type, each with the tree and
    /// without (each must pass, and find as many hits). Returns how many
    /// lanes hit in the first pass.
    pub fn check_rays(world: &World, rays: &[Ray]) -> usize {
        same_everywhere(on_every_lane_type(CheckRays { world, rays }))
    }
}

#[cfg(test)]
mod tests {
    use super::testing::*;
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec3;

    #[test]
    fn the_reference_cornell_box_gives_the_scalar_worlds_hits_bit_for_bit() {
        let world = reference_world("cornell.xml");
        let rays = rays_for(&world, 1, 4000);
        let found = check_rays(&world, &rays);
        assert!(found > 2000, "too few hits to mean anything: {found}");
    }

    #[test]
    fn small_meshes_among_shapes_give_the_scalar_worlds_hits_bit_for_bit() {
        // A knot of ~1,500 triangles and its floor square (two mesh
        // instances, placed among the lone triangles), with spheres, a
        // box, two `<triangle>`s sharing an edge with nothing and the floor
        // plane: the same α, object, triangle, β and γ as `World::intersect`.
        let mut scene = scene::generate::knot_scene(1500);
        let extra = scene::read_str(
            r#"<scene>
              <sphere center="2 1 1" radius="0.6"/>
              <sphere center="-2.5 0.5 -1" radius="0.5"/>
              <box center="0 0.4 2.5" size="1 0.8 0.6" rotate="0 30 0"/>
              <triangle t0="-3 0 -3" t1="3 0 -3" t2="0 3 -3"/>
              <triangle t0="-3 0 -3" t1="0 3 -3" t2="-3 3 -3"/>
              <floor y="-0.01"/>
            </scene>"#,
            "extra.xml",
        )
        .expect("parses");
        scene.objects.extend(extra.objects);
        let world = World::from_scene(&scene).expect("valid");
        assert!(world.instances_grouped(), "small meshes are placed");
        let shapes = PacketShapes::new(&world).expect("a packet world");
        assert!(shapes.has_meshes() && shapes.tree.is_some());
        let rays = rays_for(&world, 5, 3000);
        let found = check_rays(&world, &rays);
        assert!(found > 1500, "too few hits to mean anything: {found}");
    }

    #[test]
    fn meshes_too_large_for_packets_stay_with_the_scalar_lanes() {
        // Each mesh placed once: grouped, but too many triangles for packets.
        let world = World::from_scene(&scene::generate::knot_scene(9000)).expect("valid");
        assert!(world.instances_grouped() && world.grouped_triangles().is_none());
        assert!(PacketShapes::new(&world).is_none());
    }

    #[test]
    fn the_reference_rough_scene_gives_the_scalar_worlds_hits_bit_for_bit() {
        let world = reference_world("rough.xml");
        let rays = rays_for(&world, 2, 4000);
        let found = check_rays(&world, &rays);
        assert!(found > 2000, "too few hits to mean anything: {found}");
    }

    #[test]
    fn a_mixed_scene_of_every_kind_gives_the_scalar_worlds_hits_bit_for_bit() {
        // Ten spheres (the scalar world groups them in its own BVH), boxes
        // rotated or not, one flat, triangles sharing edges and a box's face.
        let world = world_of(
            r#"<scene>
              <triangle t0="-2 -1 -2" t1="2 -1 -2" t2="2 -1 2"/>
              <triangle t0="-2 -1 -2" t1="2 -1 2" t2="-2 -1 2"/>
              <triangle t0="0 0 0" t1="1 0 0" t2="0 1 0"/>
              <triangle t0="1 1 0" t1="0 1 0" t2="1 0 0"/>
              <triangle t0="-1 -1 -1" t1="-1 1 -1" t2="-1 -1 1"/>
              <box center="0.5 -0.5 0.5" size="1 1 1"/>
              <box center="-0.8 0.3 0.2" size="0.5 1.5 0.4" rotate="10 -35 70"/>
              <box center="1.2 0.4 -0.6" size="0.8 0.0001 0.8"/>
              <sphere center="0 0.5 -1" radius="0.5"/>
              <sphere center="1.5 1.5 1.5" radius="0.25"/>
              <sphere center="-1.5 1.2 0.4" radius="0.3"/>
              <sphere center="0.3 -0.7 1.4" radius="0.2"/>
              <sphere center="-0.4 1.6 -1.3" radius="0.35"/>
              <sphere center="1.7 -0.5 -1.5" radius="0.4"/>
              <sphere center="-1.6 -0.6 -1.4" radius="0.3"/>
              <sphere center="0.9 1.1 0.9" radius="0.15"/>
              <sphere center="0.5 -0.5 0.5" radius="0.3"/>
              <sphere center="-0.2 0.2 1.8" radius="0.45"/>
            </scene>"#,
        );
        let rays = rays_for(&world, 3, 6000);
        let found = check_rays(&world, &rays);
        assert!(found > 3000, "too few hits to mean anything: {found}");
    }

    #[test]
    fn cylinders_cones_and_tori_among_shapes_give_the_scalar_worlds_hits_bit_for_bit() {
        // Tested lane by lane by their own scalar test after the lanes'
        // bounding-sphere test, two to five to a world: rotated, a cone's
        // base on the floor plane, a cylinder through a box, a torus around
        // a sphere, tori and cones in a row; with and without the tree
        // (past the brute-force limit).
        for pair in [
            r#"<cylinder base="-1 -1 0" radius="0.4" height="1.2" rotate="10 0 20"/>
               <cone base="0.8 -1 0.3" radius="0.5" height="1.4"/>"#,
            r#"<torus center="0 0.6 -0.8" major="0.6" minor="0.15" rotate="70 10 0"/>
               <cylinder base="-1 -1.2 0" radius="0.2" height="1.5" rotate="90 0 0"/>"#,
            r#"<torus center="-1.2 0 0.5" major="0.3" minor="0.1" rotate="0 0 90"/>
               <torus center="-0.4 0 0.5" major="0.3" minor="0.12" rotate="90 0 0"/>
               <cone base="0.4 -1 0.5" radius="0.3" height="1.1" rotate="0 0 15"/>
               <cone base="1.2 -0.2 0.5" radius="0.25" height="0.6" rotate="180 0 0"/>
               <cylinder base="0 -1 1.2" radius="0.1" height="2.4" rotate="0 0 80"/>"#,
        ] {
            let mut xml = format!(
                r#"<scene>
              <plane point="0 -1 0" normal="0 1 0"/>
              {pair}
              <sphere center="0 0.6 -0.8" radius="0.3"/>
              <box center="-1 -0.4 0" size="0.5 0.3 0.5"/>"#
            );
            for k in 0..20 {
                let (x, z) = ((k % 5) as f32 * 0.8 - 1.6, (k / 5) as f32 * 0.8 - 1.6);
                xml += &format!(r#"<sphere center="{x} 1.8 {z}" radius="0.2"/>"#);
            }
            xml += "</scene>";
            let world = world_of(&xml);
            let rays = rays_for(&world, 9, 6000);
            let found = check_rays(&world, &rays);
            assert!(found > 3000, "too few hits to mean anything: {found}");
        }
    }

    #[test]
    fn worlds_with_too_many_other_shapes_or_primitives_are_refused() {
        // A plane is a packet primitive; up to `Others::MAX` cylinders,
        // cones and tori are tested lane by lane.
        let with_plane = world_of(
            r#"<scene><sphere center="0 0 0" radius="1"/><plane point="0 -1 0" normal="0 1 0"/></scene>"#,
        );
        assert!(PacketShapes::new(&with_plane).is_some());
        for other in [
            r#"<cylinder base="{k} 0 0" radius="0.3" height="1"/>"#,
            r#"<cone base="{k} 0 0" radius="0.3" height="1"/>"#,
            r#"<torus center="{k} 0 0" major="0.3" minor="0.1"/>"#,
        ] {
            let world = |n: usize| {
                let list: String = (0..n)
                    .map(|k| other.replace("{k}", &k.to_string()))
                    .collect();
                world_of(&format!(
                    r#"<scene><sphere center="0 2 0" radius="1"/>{list}</scene>"#
                ))
            };
            assert!(PacketShapes::new(&world(Others::MAX)).is_some(), "{other}");
            assert!(
                PacketShapes::new(&world(Others::MAX + 1)).is_none(),
                "{other}"
            );
        }
        let spheres = |n: usize| {
            let list: String = (0..n)
                .map(|k| format!(r#"<sphere center="{k} 0 0" radius="0.3"/>"#))
                .collect();
            world_of(&format!("<scene>{list}</scene>"))
        };
        assert!(PacketShapes::new(&spheres(PacketShapes::MAX_PRIMITIVES)).is_some());
        assert!(PacketShapes::new(&spheres(PacketShapes::MAX_PRIMITIVES + 1)).is_none());
        let few = PacketShapes::new(&spheres(PacketShapes::BRUTE_FORCE_MAX)).expect("small");
        assert!(
            few.tree.is_none(),
            "a few primitives are tested without a tree"
        );
        let many = PacketShapes::new(&reference_world("spheres.xml")).expect("lone shapes");
        assert!(
            many.tree.is_some(),
            "104 primitives are walked through a tree"
        );
    }

    #[test]
    fn the_reference_spheres_give_the_scalar_worlds_hits_bit_for_bit() {
        let world = reference_world("spheres.xml");
        let rays = rays_for(&world, 4, 4000);
        let found = check_rays(&world, &rays);
        assert!(found > 2000, "too few hits to mean anything: {found}");
    }

    /// Per lane, the primitives tested by the nearest-hit search of each
    /// packet of `rays`, in lanes `F`.
    #[derive(Clone)]
    struct TestsPerRay<'a>(&'a PacketShapes, &'a [Ray]);

    impl WithLanes for TestsPerRay<'_> {
        type Output = Vec<i32>;
        fn run<F: FloatLanes>(self) -> Vec<i32> {
            let mut all = Vec::new();
            for chunk in self.1.chunks_exact(WIDTH) {
                let rays = Rays::<F>::from_lanes(chunk.try_into().expect("WIDTH lanes"));
                let mut tests = F::Ints::splat(0);
                self.0.closest(&rays, &mut tests);
                all.extend(tests.to_array());
            }
            all
        }
    }

    #[test]
    fn the_tree_spares_most_primitive_tests_on_a_big_world() {
        // 400 spheres on a grid: a packet of camera rays through a few
        // pixels meets a few of them; without the tree it tests all.
        let list: String = (0..400)
            .map(|k| {
                let (x, z) = ((k % 20) as f32, (k / 20) as f32);
                format!(r#"<sphere center="{x} 0 {z}" radius="0.4"/>"#)
            })
            .collect();
        let world = world_of(&format!("<scene>{list}</scene>"));
        let shapes = PacketShapes::new(&world).expect("lone spheres");
        let rays: Vec<Ray> = (0..64)
            .map(|k| {
                let target = Vec3::new(
                    9.5 + 0.01 * (k % 8) as f32,
                    0.0,
                    9.5 + 0.01 * (k / 8) as f32,
                );
                let origin = Vec3::new(9.0, 10.0, 5.0);
                Ray::new(origin, target - origin)
            })
            .collect();
        for tests in on_every_lane_type(TestsPerRay(&shapes, &rays)) {
            let mean = tests.iter().sum::<i32>() as f32 / tests.len() as f32;
            assert!(mean < 40.0, "{mean} tests per ray of 400 primitives");
        }
        check_rays(&world, &rays_for(&world, 5, 800));
    }

    /// Each ray's (α bits, object) in lane `k % WIDTH` alone, then in
    /// packets of `WIDTH` rays taken in the orders i·step mod n, in lanes `F`.
    #[derive(Clone)]
    struct AloneAndAmongOthers<'a>(&'a PacketShapes, &'a [Ray]);

    impl WithLanes for AloneAndAmongOthers<'_> {
        type Output = Vec<Vec<(u32, i32)>>;
        fn run<F: FloatLanes>(self) -> Self::Output {
            let (shapes, rays) = (self.0, self.1);
            let answer = |lanes: &[Ray; WIDTH], k: usize| {
                let packet = Rays::<F>::from_lanes(lanes);
                let hits = shapes.closest(&packet, &mut F::Ints::splat(0));
                (
                    hits.alpha.to_array()[k].to_bits(),
                    hits.object.to_array()[k],
                )
            };
            let alone = (0..rays.len())
                .map(|k| answer(&packet(&[rays[k]], &[k % WIDTH]), k % WIDTH))
                .collect();
            let mut runs = vec![alone];
            // Every ray in packets of others: the rays in the order
            // i·step mod n (a permutation, `step` prime to n), WIDTH at a time.
            let n = rays.len();
            for step in [1, 3, 7] {
                let order: Vec<usize> = (0..n).map(|i| i * step % n).collect();
                let mut among = vec![None; n];
                for start in (0..n).step_by(WIDTH) {
                    let ids: Vec<usize> = (0..WIDTH).map(|j| order[(start + j) % n]).collect();
                    let group: Vec<Ray> = ids.iter().map(|&i| rays[i]).collect();
                    let lanes = packet(&group, &(0..WIDTH).collect::<Vec<_>>());
                    for (j, &i) in ids.iter().enumerate() {
                        among[i] = Some(answer(&lanes, j));
                    }
                }
                let among: Option<Vec<_>> = among.into_iter().collect();
                runs.push(among.expect("every ray answered among others"));
            }
            runs
        }
    }

    #[test]
    fn a_lanes_hit_does_not_depend_on_the_other_rays_of_its_packet() {
        // Rays through the floor's shared diagonal meet two triangles at
        // exactly the same α; with random rays around them, in every lane
        // and every company, each ray gets the same α and object.
        let world = reference_world("spheres.xml");
        let shapes = PacketShapes::new(&world).expect("lone shapes");
        assert!(shapes.tree.is_some(), "walked through the tree");
        let mut rays = rays_for(&world, 9, 160);
        let eye = Vec3::new(0.3, 5.0, 9.0);
        for k in 0..40 {
            let x = -4.05 + 0.2 * k as f32;
            rays.push(Ray::new(eye, Vec3::new(x, 0.0, -x) - eye));
        }
        for runs in on_every_lane_type(AloneAndAmongOthers(&shapes, &rays)) {
            for among in &runs[1..] {
                assert_eq!(among, &runs[0], "answers alone and among others");
            }
        }
    }

    #[test]
    fn one_primitive_past_the_brute_force_limit_gets_a_tree() {
        let spheres = |n: usize| {
            let list: String = (0..n)
                .map(|k| format!(r#"<sphere center="{k} 0 0" radius="0.3"/>"#))
                .collect();
            world_of(&format!("<scene>{list}</scene>"))
        };
        let at = PacketShapes::new(&spheres(PacketShapes::BRUTE_FORCE_MAX)).expect("small");
        let past = PacketShapes::new(&spheres(PacketShapes::BRUTE_FORCE_MAX + 1)).expect("lone");
        assert!(at.tree.is_none() && past.tree.is_some());
    }

    #[test]
    fn the_cornell_box_walked_through_a_tree_keeps_its_shared_edges_watertight() {
        // Its rays aimed at corners and shared edges, now through leaves:
        // the tree must not lose what the brute-force test finds.
        let world = reference_world("cornell.xml");
        assert!(
            PacketShapes::with_tree_or_not(&world, true)
                .expect("packets")
                .tree
                .is_some()
        );
        let found = check_rays(&world, &rays_for(&world, 6, 3000));
        assert!(found > 1500, "too few hits to mean anything: {found}");
    }

    /// An empty world's answers to sixteen rays, in lanes `F`.
    #[derive(Clone)]
    struct EmptyWorld<'a>(&'a PacketShapes);

    impl WithLanes for EmptyWorld<'_> {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            let shapes = self.0;
            let rays = Rays::<F>::from_lanes(&std::array::from_fn(|k| {
                Ray::new(Vec3::ZERO, Vec3::X * (k as f32 + 1.0))
            }));
            let mut tests = F::Ints::splat(0);
            let hits = shapes.closest(&rays, &mut tests);
            assert_eq!(hits.alpha.to_array(), [f32::INFINITY; WIDTH]);
            assert_eq!(hits.object.to_array(), [-1; WIDTH]);
            assert_eq!(shapes.occluded(&rays, &mut tests).to_bitmask(), 0);
            assert_eq!(tests.to_array(), [0; WIDTH]);
        }
    }

    #[test]
    fn an_empty_world_hits_nothing() {
        let world = world_of("<scene></scene>");
        let shapes = PacketShapes::new(&world).expect("nothing is small");
        on_every_lane_type(EmptyWorld(&shapes));
    }

    #[test]
    fn a_packet_of_dead_lanes_hits_nothing() {
        let world = reference_world("cornell.xml");
        let shapes = PacketShapes::new(&world).expect("a packet world");
        let dead: [Ray; WIDTH] = std::array::from_fn(|k| {
            Ray::new(
                Vec3::new(0.0, 0.0, 0.1 * k as f32),
                Vec3::new(0.0, -1.0, 0.0),
            )
            .with_t_max(0.0)
        });
        check_packet(&world, &shapes, &dead);
    }
}
