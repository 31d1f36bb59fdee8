//! The bottom level: a BVH over one triangle mesh, built as 8-wide nodes
//! with exact boxes by our binned-SAH builder ([`super::wide_build`]; or,
//! for comparison, by obvhs's PLOC as a binary tree collapsed to the same
//! nodes, [`super::ploc`]) and traversed by our conservative code
//! ([`super::wide`]), nearest child first. Leaf triangles are copied into
//! packs of four ([`TrianglePack`]) tested with the same watertight
//! arithmetic as [`crate::shapes::Triangle`] ([`WatertightRay`]), so
//! closest hits equal brute force exactly.

mod lanes;

use super::ploc::build_ploc;
use super::scene::Aabb;
use super::simd::{prefetch, with_widest_simd};
use super::stack::Stack;
use super::triangle_pack::{PACK, PackHit, TrianglePack};
use super::wide::{ChildRef, WideNode, WideRay, pop_within, push_children_nearest_last};
use super::wide_build::build_wide;
use crate::geometry::ray::Ray;
use crate::shapes::WatertightRay;
use crate::simd::{FloatLanes, WithLanes, dispatch};
use glam::Vec3;
use obvhs::BvhBuildParams;

/// The closest hit of one ray so far: its pack and the hit in it.
type LaneBest<'a> = Option<(&'a TrianglePack, PackHit)>;

/// The closest hit of a ray with a mesh: P0 + α v = (1 − β − γ) t0 + β t1 + γ t2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Index of the triangle in the caller's `triangles`.
    pub triangle: u32,
    /// α, the ray parameter of the hit (the ray's direction is not normalised
    /// by the BVH, so this is the caller's α).
    pub alpha: f32,
    /// β, the weight of t1.
    pub beta: f32,
    /// γ, the weight of t2.
    pub gamma: f32,
}

/// Which builder makes the tree, and with how much effort. Without spatial
/// splits in every case, so each triangle is in exactly one leaf.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BuildQuality {
    /// Our binned-SAH builder of 8-wide nodes ([`super::wide_build`]).
    #[default]
    BinnedSah,
    /// obvhs PLOC `fastest_build` (smallest search, no reinsertion), collapsed.
    Fastest,
    /// obvhs PLOC `very_fast_build`, collapsed.
    VeryFast,
    /// obvhs PLOC `fast_build`, collapsed.
    Fast,
    /// obvhs PLOC `medium_build`, collapsed.
    Medium,
}

impl BuildQuality {
    /// obvhs's parameters for this quality (`None` for our own builder).
    fn params(self) -> Option<BvhBuildParams> {
        let mut p = match self {
            BuildQuality::BinnedSah => return None,
            BuildQuality::Fastest => BvhBuildParams::fastest_build(),
            BuildQuality::VeryFast => BvhBuildParams::very_fast_build(),
            BuildQuality::Fast => BvhBuildParams::fast_build(),
            BuildQuality::Medium => BvhBuildParams::medium_build(),
        };
        p.pre_split = false;
        Some(p)
    }
}

/// A BVH over one triangle mesh.
#[derive(Clone, Debug)]
pub struct MeshBvh {
    /// The 8-wide nodes; node 0 is the root (none for an empty mesh).
    nodes: Vec<WideNode>,
    /// The leaves' triangles, in packs of four.
    packs: Vec<TrianglePack>,
    /// Number of triangles.
    triangle_count: usize,
    /// The box around every triangle.
    bounds: Aabb,
    /// Where every walk starts ([`start_of`]).
    start: Option<ChildRef>,
    /// A small mesh's triangles (at most [`FLAT_TRIANGLES`]) in packs in
    /// index order, which a ray tests without a walk: no node, so no
    /// reciprocal direction or stack to prepare and no children to sort.
    /// Empty for a larger mesh.
    flat: Vec<TrianglePack>,
    /// Whether [`MeshBvh::closest_hits`] traces incoherent rays
    /// interleaved ([`INTERLEAVED`] at a time): for a tree larger than
    /// half the last-level cache, whose walks wait on memory; one after
    /// another otherwise ([`interleaves`]).
    interleave: bool,
}

impl MeshBvh {
    /// Builds the BVH of the triangles `triangles` (indices into
    /// `positions`) with the default [`BuildQuality`], in parallel on the
    /// current rayon pool. Positions must be finite; indices in range.
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> MeshBvh {
        Self::build_with(positions, triangles, BuildQuality::default())
    }

    /// [`MeshBvh::build`] with a chosen build effort.
    pub fn build_with(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        quality: BuildQuality,
    ) -> MeshBvh {
        let (nodes, packs, bounds) = match quality.params() {
            None => build_wide(positions, triangles),
            Some(params) => build_ploc(positions, triangles, params),
        };
        let flat = if triangles.len() <= FLAT_TRIANGLES {
            flat_packs(positions, triangles)
        } else {
            Vec::new()
        };
        let mut bvh = MeshBvh {
            flat,
            start: start_of(&nodes),
            nodes,
            packs,
            triangle_count: triangles.len(),
            bounds,
            interleave: false,
        };
        bvh.interleave = interleaves(bvh.bytes());
        bvh
    }

    /// This BVH with its batches' incoherent rays traced interleaved or
    /// not, whatever its size (for tests of both ways).
    #[cfg(test)]
    pub(crate) fn with_interleaving(mut self, on: bool) -> MeshBvh {
        self.interleave = on;
        self
    }

    /// The box around every triangle (empty for an empty mesh).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangle_count
    }

    /// True for a mesh without triangles.
    pub fn is_empty(&self) -> bool {
        self.triangle_count == 0
    }

    /// Bytes held by the structure: nodes plus the leaf packs.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.nodes.capacity() * std::mem::size_of::<WideNode>()
            + (self.packs.capacity() + self.flat.capacity()) * std::mem::size_of::<TrianglePack>()
    }

    /// The hit with the smallest α in (t_min, t_max), exactly as testing
    /// every triangle with the watertight test finds it: the same α, β and γ,
    /// and on a tie the lowest triangle index, whatever the order the walk
    /// meets them in (so a packet of rays, which visits nodes in its own
    /// order, reports the same triangle).
    pub fn closest_hit(&self, ray: &Ray) -> Option<MeshHit> {
        with_widest_simd(
            #[inline(always)]
            || self.closest_hit_inline(ray),
        )
    }

    /// True when any triangle is hit in (t_min, t_max) (for shadow rays:
    /// stops at the first hit found).
    pub fn any_hit(&self, ray: &Ray) -> bool {
        with_widest_simd(
            #[inline(always)]
            || self.any_hit_inline(ray),
        )
    }

    /// [`MeshBvh::closest_hit`] of every ray in `rays`, written to `hits`
    /// (same length): the same hit bit for bit, the lowest triangle index
    /// on a tie. Each run of sixteen consecutive rays that
    /// are coherent (camera rays through a 4 × 4 tile of pixels: one
    /// octant, close directions and origins) is traced as a packet in SIMD
    /// lanes (`mesh/lanes.rs`), each node loaded and each triangle tested
    /// once for all its rays. The other rays are traced
    /// [`INTERLEAVED`] at a time, one node or leaf of each in turn, so that
    /// while one ray waits for its next node to arrive from memory (it was
    /// prefetched) the others compute: incoherent rays in a large mesh
    /// spend most of their time waiting otherwise.
    pub fn closest_hits(&self, rays: &[Ray], hits: &mut [Option<MeshHit>]) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        let mut alone = Vec::new();
        dispatch(Packets {
            bvh: self,
            rays,
            hits: &mut *hits,
            alone: &mut alone,
        });
        if self.interleave {
            with_widest_simd(
                #[inline(always)]
                || self.interleaved(alone.into_iter().map(|i| (i, &rays[i])), hits),
            );
        } else {
            with_widest_simd(
                #[inline(always)]
                || {
                    for i in alone {
                        hits[i] = self.closest_hit_inline(&rays[i]);
                    }
                },
            );
        }
    }

    /// [`MeshBvh::closest_hit`], compiled into its caller.
    #[inline(always)]
    fn closest_hit_inline(&self, ray: &Ray) -> Option<MeshHit> {
        if !self.flat.is_empty() {
            return mesh_hit(self.nearest_in_flat::<false>(ray));
        }
        let mut walk = Walk::new(ray, self.root());
        while self.step::<false>(&mut walk) {}
        walk.closest()
    }

    /// [`MeshBvh::any_hit`], compiled into its caller.
    #[inline(always)]
    fn any_hit_inline(&self, ray: &Ray) -> bool {
        if !self.flat.is_empty() {
            return self.nearest_in_flat::<true>(ray).is_some();
        }
        let mut walk = Walk::new(ray, self.root());
        while self.step::<true>(&mut walk) {}
        walk.best.is_some()
    }

    /// The closest hit of each ray `waiting` yields (its index in `hits`
    /// and the ray), [`INTERLEAVED`] rays at a time, one step of each in turn.
    #[inline(always)]
    fn interleaved<'r>(
        &self,
        mut waiting: impl Iterator<Item = (usize, &'r Ray)>,
        hits: &mut [Option<MeshHit>],
    ) {
        // Each slot: the ray it traces (its index) and its walk; the walks
        // are reused so their stacks are not initialised again per ray.
        let mut slots: [(usize, Walk); INTERLEAVED] =
            std::array::from_fn(|_| (usize::MAX, Walk::new(&Ray::new(Vec3::ZERO, Vec3::X), None)));
        let mut active = 0;
        for (index, walk) in &mut slots {
            if let Some((i, ray)) = waiting.next() {
                (*index, active) = (i, active + 1);
                walk.restart(ray, self.root());
            }
        }
        while active > 0 {
            for (index, walk) in &mut slots {
                if *index == usize::MAX || self.step::<false>(walk) {
                    continue;
                }
                hits[*index] = walk.closest();
                match waiting.next() {
                    Some((i, ray)) => {
                        *index = i;
                        walk.restart(ray, self.root());
                    }
                    None => {
                        *index = usize::MAX;
                        active -= 1;
                    }
                }
            }
        }
    }

    /// The closest hit among a small mesh's `flat` packs in the ray's
    /// interval (the first found with `ANY`); on a tie the lowest triangle
    /// index (packs and lanes are in index order, and a later pack must be
    /// strictly nearer).
    #[inline(always)]
    fn nearest_in_flat<const ANY: bool>(&self, ray: &Ray) -> LaneBest<'_> {
        let triangle_ray = WatertightRay::new(ray);
        let mut t_max = ray.t_max;
        let mut best = None;
        for pack in &self.flat {
            if let Some(hit) = pack.nearest(&triangle_ray, ray.t_min, t_max) {
                t_max = hit.alpha;
                best = Some((pack, hit));
                if ANY {
                    break;
                }
            }
        }
        best
    }

    /// Where every walk starts (decided at build: [`start_of`]).
    #[inline(always)]
    fn root(&self) -> Option<ChildRef> {
        self.start
    }

    /// One step of `walk`: tests its next node or leaf and picks what comes
    /// after (prefetching it); false when the walk is over. Nodes go nearest
    /// child first; a child waiting on the stack is skipped when its entry
    /// distance is beyond the (shrunk) t_max. `ANY` stops at the first hit
    /// (shadow rays).
    #[inline(always)]
    fn step<'a, const ANY: bool>(&'a self, walk: &mut Walk<'a>) -> bool {
        let Some(current) = walk.next else {
            return false;
        };
        if let Some(range) = current.packs() {
            for pack in &self.packs[range] {
                let s = &mut walk.ray.slab;
                // Once a hit is found, one at the same α with a lower index
                // still wins: the pack is tested up to and including it.
                let limit = if walk.best_index == u32::MAX {
                    s.t_max
                } else {
                    s.t_max.next_up()
                };
                if let Some(hit) = pack.nearest(&walk.triangle_ray, s.t_min, limit) {
                    let index = pack.id(hit.lane);
                    if hit.alpha < s.t_max || index < walk.best_index {
                        s.set_t_max(hit.alpha);
                        walk.best = Some((pack, hit));
                        walk.best_index = index;
                    }
                    if ANY {
                        walk.next = None;
                        return false;
                    }
                }
            }
        } else {
            let node = &self.nodes[current.0 as usize];
            let (mask, t_near) = walk.ray.child_hits(node);
            if mask != 0 {
                walk.next = Some(push_children_nearest_last(
                    node,
                    mask,
                    &t_near,
                    &mut walk.stack,
                    |child| self.prefetch(child),
                ));
                return true;
            }
        }
        walk.next = pop_within(&mut walk.stack, walk.ray.slab.t_max_wide);
        walk.next.is_some()
    }

    /// Starts loading `child` (a node, or every pack of a leaf).
    #[inline(always)]
    fn prefetch(&self, child: ChildRef) {
        match child.packs() {
            Some(range) => self.packs[range].iter().for_each(prefetch),
            None => prefetch(&self.nodes[child.0 as usize]),
        }
    }
}

/// [`MeshBvh::closest_hits`]'s packets, run with the widest lane type:
/// each run of [`lanes::LANES`] consecutive rays that are coherent is
/// traced as one packet; the others are left in `alone`, by index.
struct Packets<'a> {
    bvh: &'a MeshBvh,
    rays: &'a [Ray],
    hits: &'a mut [Option<MeshHit>],
    alone: &'a mut Vec<usize>,
}

impl WithLanes for Packets<'_> {
    type Output = ();

    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        for (k, chunk) in self.rays.chunks(lanes::LANES).enumerate() {
            let first = k * lanes::LANES;
            let hits = &mut self.hits[first..first + chunk.len()];
            if !self.bvh.trace_lanes::<F>(chunk, hits) {
                self.alone.extend(first..first + chunk.len());
            }
        }
    }
}

/// Up to this many triangles, a ray tests every triangle of a mesh, four at
/// a time in index order, instead of walking its tree; a tie goes to the
/// lowest index. A Cornell box's twelve walls and light (three packs):
/// callgrind counted 9% fewer instructions per path-traced pass than
/// through the root node and its leaves (15% fewer branches, 8% more of
/// them mispredicted).
pub const FLAT_TRIANGLES: usize = 16;

/// Whether a tree of `bytes` is traced interleaved in batches: when it is
/// larger than half the last-level cache. Incoherent rays of the knot
/// (`raylab bench knot:N`, single rays against batches, 1 / 2 threads, in
/// Mrays/s, on a 32 MiB L3): 50,000 triangles (2.4 MB) 5.51 / 10.7 one at
/// a time against 4.72 / 9.38 interleaved; 200,000 (9.5 MB) 5.09 / 10.3
/// against 4.49 / 8.95; 400,000 (19.6 MB) 3.96 / 8.32 against 4.25 / 8.38;
/// 600,000 2.98 / 6.69 against 4.00 / 7.91; a million 2.70 / 5.81 against
/// 3.79 / 7.53.
fn interleaves(bytes: usize) -> bool {
    bytes > super::cache_size::last_level_cache_bytes() / 2
}

/// Rays traced at a time by [`MeshBvh::closest_hits`]. On the
/// million-triangle knot's incoherent rays (`cargo bench --bench bvh`, one
/// thread) 4 gave 2.2 Mrays/s, 8 gave 2.4–2.5 and 16 gave 2.55 (within the
/// noise of 8, with twice the walks' memory).
pub const INTERLEAVED: usize = 8;

/// One ray's traversal in progress: the ray prepared for the box and
/// triangle tests, the children still to visit, and the closest hit so far.
struct Walk<'a> {
    /// The ray for the node test; its t_max shrinks with each closer hit.
    ray: WideRay,
    /// The same ray for the triangle test.
    triangle_ray: WatertightRay,
    /// Children waiting, with their entry distances.
    stack: Stack<(ChildRef, f32), 48>,
    /// The node or leaf to visit next; `None` when done.
    next: Option<ChildRef>,
    /// The closest hit so far (its pack and lane).
    best: LaneBest<'a>,
    /// The triangle index of the closest hit so far (of `best`, or of one a
    /// packet found before handing the ray over); `u32::MAX` for none.
    best_index: u32,
}

impl<'a> Walk<'a> {
    /// A walk of `ray` from `root` (`None`: nothing to visit).
    #[inline(always)]
    fn new(ray: &Ray, root: Option<ChildRef>) -> Self {
        Walk {
            ray: WideRay::new(ray),
            triangle_ray: WatertightRay::new(ray),
            stack: Stack::new(),
            next: root,
            best: None,
            best_index: u32::MAX,
        }
    }

    /// This walk made a new one of `ray` from `root`, keeping the stack's
    /// storage.
    #[inline(always)]
    fn restart(&mut self, ray: &Ray, root: Option<ChildRef>) {
        self.ray = WideRay::new(ray);
        self.triangle_ray = WatertightRay::new(ray);
        self.stack.clear();
        self.next = root;
        self.best = None;
        self.best_index = u32::MAX;
    }

    /// The closest hit found.
    #[inline(always)]
    fn closest(&self) -> Option<MeshHit> {
        mesh_hit(self.best)
    }
}

/// The packs of `triangles` in index order: triangle k is lane k % 4 of
/// pack k / 4.
fn flat_packs(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<TrianglePack> {
    let corners = |k: usize| (k as u32, triangles[k].map(|i| positions[i as usize]));
    (0..triangles.len())
        .step_by(PACK)
        .map(|first| {
            let lanes: Vec<_> = (first..triangles.len().min(first + PACK))
                .map(corners)
                .collect();
            TrianglePack::new(&lanes)
        })
        .collect()
}

/// Where every walk of the tree `nodes` starts: the root node, if any; or,
/// for a mesh that is one leaf (at most [`super::wide::LEAF_TRIANGLES`]
/// triangles), that leaf, whose exact triangle tests make the root's box
/// test redundant (and the walk never loads the node).
fn start_of(nodes: &[WideNode]) -> Option<ChildRef> {
    match nodes.first()?.children {
        [only, ChildRef::EMPTY, ..] if only.packs().is_some() => Some(only),
        _ => Some(ChildRef::node(0)),
    }
}

/// The hit of a traversal's best (pack, hit in it), if any.
#[inline(always)]
fn mesh_hit(best: LaneBest) -> Option<MeshHit> {
    let (pack, hit) = best?;
    let (beta, gamma) = hit.barycentrics();
    Some(MeshHit {
        triangle: pack.id(hit.lane),
        alpha: hit.alpha,
        beta,
        gamma,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::reference;
    use crate::accel::tests::meshes::grid;
    use crate::accel::wide::LEAF_TRIANGLES;

    #[test]
    fn empty_mesh_has_no_hits_and_empty_bounds() {
        let bvh = MeshBvh::build(&[], &[]);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(bvh.closest_hit(&ray), None);
        assert!(!bvh.any_hit(&ray));
        assert!(bvh.bounds().is_empty());
    }

    #[test]
    fn single_triangle_hit_reports_caller_index_and_barycentrics() {
        let p = [
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let bvh = MeshBvh::build(&p, &[[0, 1, 2]]);
        let h = bvh
            .closest_hit(&Ray::new(Vec3::new(0.0, 0.5, 2.0), -Vec3::Z))
            .expect("hit");
        assert_eq!(h.triangle, 0);
        assert!((h.alpha - 2.0).abs() < 1e-6);
        assert!(
            (h.beta - 0.25).abs() < 1e-6 && (h.gamma - 0.5).abs() < 1e-6,
            "{h:?}"
        );
    }

    #[test]
    fn closest_hit_and_bounds_match_brute_force_on_a_small_grid() {
        let (p, t) = grid(8, 8, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        assert_eq!(bvh.len(), t.len());
        assert_eq!(bvh.bounds().min, Vec3::new(0.0, 0.0, 0.0));
        assert_eq!(bvh.bounds().max, Vec3::new(8.0, 8.0, 0.0));
        let ray = Ray::new(Vec3::new(3.3, 2.7, 5.0), Vec3::new(0.01, 0.02, -1.0));
        let want = reference::closest_hit(&p, &t, &ray).expect("brute-force hit");
        let got = bvh.closest_hit(&ray).expect("bvh hit");
        assert_eq!(got, want);
    }

    /// A small mesh's closest hit on a tie is its lowest triangle index,
    /// whichever pack or lane holds it: the same triangle at indices 2 and 9
    /// (and turned at 3..8), and a quad's diagonal met exactly (0 and 1).
    #[test]
    fn in_a_small_mesh_a_tie_goes_to_the_lowest_triangle_index() {
        let positions = vec![
            Vec3::new(-1.0, -1.0, -2.0),
            Vec3::new(1.0, -1.0, -2.0),
            Vec3::new(1.0, 1.0, -2.0),
            Vec3::new(-1.0, 1.0, -2.0),
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, 1.0, -5.0),
        ];
        let far = [4, 5, 6];
        let mut triangles = vec![[0, 1, 2], [0, 2, 3], far];
        triangles.extend([[5, 6, 4]; 6]);
        triangles.push(far);
        let bvh = MeshBvh::build(&positions, &triangles);
        let diagonal = bvh.closest_hit(&Ray::new(Vec3::ZERO, Vec3::new(0.25, 0.25, -1.0)));
        assert_eq!(diagonal.map(|h| (h.triangle, h.alpha)), Some((0, 2.0)));
        let past_the_quad = Ray::new(Vec3::new(0.0, 0.0, -3.0), -Vec3::Z);
        let far_hit = bvh.closest_hit(&past_the_quad);
        assert_eq!(far_hit.map(|h| (h.triangle, h.alpha)), Some((2, 2.0)));
    }

    #[test]
    fn small_meshes_tested_flat_or_from_their_one_leaf_match_brute_force() {
        let mut rng = crate::integrator::sampler::Sampler::for_sample(5, 0, 0, 0);
        for n in 1..=20usize {
            let (p, mut t) = grid(10, 1, 0.0);
            t.truncate(n);
            let bvh = MeshBvh::build(&p, &t).with_interleaving(true);
            let root = bvh.root().expect("a root");
            assert_eq!(root.packs().is_some(), n <= LEAF_TRIANGLES, "{n} triangles");
            let mut rays = Vec::new();
            for _ in 0..2000 {
                // From above or below, aimed anywhere near the strip, some
                // rays ending (t_max) or starting (t_min) short of it.
                let target = Vec3::new(
                    (0.5 * n as f32 + 1.0) * rng.next_f32() - 0.5,
                    1.5 * rng.next_f32() - 0.25,
                    0.0,
                );
                let origin = target + 3.0 * rng.next_direction();
                let mut ray = Ray::new(origin, target - origin);
                ray.t_max = 2.0 * rng.next_f32();
                ray.t_min = 0.5 * rng.next_f32();
                let want = reference::closest_hit(&p, &t, &ray);
                let got = bvh.closest_hit(&ray);
                // α, β, γ and the triangle (the lowest index on a tie).
                assert_eq!(got, want, "{n} triangles, {ray:?}");
                assert_eq!(bvh.any_hit(&ray), want.is_some(), "{n} triangles, {ray:?}");
                rays.push(ray);
            }
            // The batched paths start there too: interleaved walks for the
            // random rays above, packets for runs of sixteen parallel rays
            // close enough together to travel as one (1e-4 apart, within
            // a hundredth of the strip's size).
            let lanes = crate::packet::WIDTH;
            assert_eq!(rays.len() % lanes, 0, "each run below is one chunk");
            for run in 0..32 {
                let base = Vec3::new(0.16 * run as f32, 0.02 * run as f32, 2.0);
                rays.extend((0..lanes).map(|k| {
                    Ray::new(base + Vec3::X * 1e-4 * k as f32, Vec3::new(0.01, 0.0, -1.0))
                }));
            }
            let mut hits = vec![None; rays.len()];
            bvh.closest_hits(&rays, &mut hits);
            for (ray, hit) in rays.iter().zip(hits) {
                let want = reference::closest_hit(&p, &t, ray);
                assert_eq!(hit, want, "batched, {n} triangles, {ray:?}");
            }
        }
    }

    #[test]
    fn widest_simd_and_baseline_code_find_the_same_hits() {
        let (p, t) = grid(30, 30, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        let mut rng = crate::integrator::sampler::Sampler::for_sample(3, 0, 0, 0);
        for _ in 0..2000 {
            let origin = Vec3::new(30.0 * rng.next_f32(), 30.0 * rng.next_f32(), 5.0);
            let ray = Ray::new(origin, rng.next_direction());
            // `closest_hit` runs AVX2 code where the CPU has it; the
            // `_inline` functions called here are compiled for the baseline.
            assert_eq!(
                bvh.closest_hit(&ray),
                bvh.closest_hit_inline(&ray),
                "{ray:?}"
            );
            assert_eq!(bvh.any_hit(&ray), bvh.any_hit_inline(&ray), "{ray:?}");
        }
    }

    #[test]
    fn closest_hits_of_a_batch_equal_closest_hit_ray_by_ray() {
        let (p, t) = grid(30, 30, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        let mut rng = crate::integrator::sampler::Sampler::for_sample(5, 0, 0, 0);
        let rays: Vec<Ray> = (0..500)
            .map(|_| {
                let origin = Vec3::new(30.0 * rng.next_f32(), 30.0 * rng.next_f32(), 5.0);
                Ray::new(origin, rng.next_direction())
            })
            .collect();
        // Interleaved (as a tree too large for the cache is) or one ray
        // after another; fewer rays than interleaved slots, exactly as
        // many, and many more.
        for interleaved in [true, false] {
            let bvh = bvh.clone().with_interleaving(interleaved);
            for n in [0, 1, INTERLEAVED - 1, INTERLEAVED, rays.len()] {
                let mut hits = vec![None; n];
                bvh.closest_hits(&rays[..n], &mut hits);
                for (ray, hit) in rays[..n].iter().zip(&hits) {
                    assert_eq!(*hit, bvh.closest_hit(ray), "{ray:?}");
                }
                assert!(n < 100 || hits.iter().filter(|h| h.is_some()).count() > n / 4);
            }
        }
        let empty = MeshBvh::build(&[], &[]);
        let mut hits = vec![
            Some(MeshHit {
                triangle: 0,
                alpha: 1.0,
                beta: 0.0,
                gamma: 0.0
            });
            3
        ];
        empty.closest_hits(&rays[..3], &mut hits);
        assert_eq!(hits, vec![None; 3]);
    }

    #[test]
    fn bytes_counts_nodes_and_triangle_copies() {
        let (p, t) = grid(20, 20, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        assert!(bvh.bytes() >= t.len() * std::mem::size_of::<[Vec3; 3]>());
        assert!(bvh.bytes() < t.len() * 200, "{}", bvh.bytes());
    }
}
