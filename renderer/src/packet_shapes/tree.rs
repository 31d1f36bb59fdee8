//! A binary BVH over a world's primitives, walked by whole packets (Wald,
//! Slusallek, Benthin and Wagner, "Interactive Rendering with Coherent Ray
//! Tracing", 2001): a node is visited once for the sixteen rays, its box
//! tested against all of them in one go, and skipped only when no lane
//! still searching enters it. A leaf's few primitives are then tested
//! against every lane with the packet tests of their kinds, so each lane's
//! answer is the one the brute-force packet test gives: the tree only
//! leaves out primitives a lane cannot hit.
//!
//! The box test is Ize's conservative slab test of `accel/slab.rs`
//! ([`crate::accel::slab::box_entry`]) lane by lane, and a primitive's box
//! is the one the world's own top level holds it in
//! ([`World::shape_bounds`], padded for its test's rounding), so no hit is
//! lost that the scalar BVH finds.
//!
//! Embree's hybrid scheme in its place measured slower (commit 8608396,
//! reverted): 8-wide nodes whose eight boxes are tested against the sixteen
//! rays, and once at most n lanes enter a subtree each walks it alone, eight
//! boxes per test, leaves by the scalar tests (four triangles at once). The
//! path tracer at 16 spp, 512×384, 2 threads, two alternated rounds, this
//! tree against the hybrid for n = 0 (packets only), 2, 4, 8 and 16 (every
//! lane alone):
//!
//! | scene | this tree | n = 0 | 2 | 4 | 8 | 16 |
//! |---|---|---|---|---|---|---|
//! | mesh sphere, 3,480 triangles | 0.66 s | 0.69 | 0.69 | 0.72 | 0.86 | 1.14 |
//! | tessellated sphere and five spheres | 0.57 | 0.65 | 0.61 | 0.61 | 0.74 | 1.04 |
//! | 900 spheres on a floor | 0.64 | 0.62 | 0.66 | 0.71 | 0.93 | 1.42 |
//! | 3,000 scattered spheres | 2.02 | 2.08 | 2.05 | 2.22 | 2.98 | 3.21 |
//! | spheres.xml | 0.50 | 0.53 | 0.52 | 0.55 | 0.66 | 1.13 |
//!
//! Lanes alone visiting children nearest first (which could change a
//! cross-kind tie) did no better: 16 alone took 1.04–1.46 s. Sixteen
//! incoherent bounce rays share enough of these small trees that a packet
//! costs less than a few rays walked alone.
//!
//! [`World::shape_bounds`]: crate::world::World::shape_bounds

use super::{FloatLanes, MaskLanes, Rays, Vec3s, coordinate};
use crate::accel::Aabb;
use crate::accel::binned_sah::{PrimRef, Span, Splitter};
use crate::accel::slab::widen_up_lanes;
use glam::Vec3A;
use std::ops::Range;

/// A leaf holds at most this many primitives: a node's box test costs
/// about one primitive test, so leaves of a few primitives keep both
/// small.
const LEAF_MAX: usize = 4;

/// The deepest tree [`Tree::build`] accepts (the traversal's stack).
pub(super) const MAX_DEPTH: usize = 64;

/// A leaf's primitives: a range of each kind's list (the kinds store their
/// primitives in leaf order).
#[derive(Clone, Debug, Default)]
pub(super) struct Leaf {
    /// Indices among the triangles.
    pub(super) triangles: Range<usize>,
    /// Indices among the boxes.
    pub(super) boxes: Range<usize>,
    /// Indices among the spheres.
    pub(super) spheres: Range<usize>,
}

impl Leaf {
    /// How many primitives it holds.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.triangles.len() + self.boxes.len() + self.spheres.len()
    }
}

/// A node: its box and either two children or a leaf.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// The box's low corner.
    lo: [f32; 3],
    /// The box's high corner.
    hi: [f32; 3],
    /// An inner node's second child (its first follows it in
    /// [`Tree::nodes`]); a leaf's index in [`Tree::leaves`].
    link: u32,
    /// Whether it is a leaf.
    leaf: bool,
}

/// The tree: nodes in depth-first order, node 0 the root.
#[derive(Clone, Debug)]
pub(super) struct Tree {
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
}

/// Sixteen rays prepared for box tests: origins, reciprocal directions and
/// the sign of each.
pub(super) struct BoxRays<F: FloatLanes> {
    /// P0.
    origin: Vec3s<F>,
    /// 1/v (±∞ for ±0).
    inv_dir: Vec3s<F>,
    /// Per axis, the mask of the lanes whose 1/v has its sign bit set
    /// (whose near plane is the box's high one).
    negative: [F::Mask; 3],
}

impl<F: FloatLanes> BoxRays<F> {
    /// `rays` ready for box tests.
    #[inline(always)]
    pub(super) fn new(rays: &Rays<F>) -> Self {
        let inv_dir = Vec3s {
            x: F::ONE / rays.dir.x,
            y: F::ONE / rays.dir.y,
            z: F::ONE / rays.dir.z,
        };
        // (Written out: a closure through `array::map` is not inlined into
        // the caller's SIMD instruction set, and its lane operations then
        // run as calls.)
        let negative = [
            inv_dir.x.is_sign_negative(),
            inv_dir.y.is_sign_negative(),
            inv_dir.z.is_sign_negative(),
        ];
        Self {
            origin: rays.origin,
            inv_dir,
            negative,
        }
    }

    /// The lanes whose ray may meet `node`'s box in (0, limit): Ize's test
    /// lane by lane, exactly `slab::box_entry` with t_min = 0, whose
    /// maximum and minimum ignore a NaN distance (a ray lying in a face
    /// with a zero direction component: 0 · ∞).
    #[inline(always)]
    fn enter(&self, node: &Node, limit: F) -> F::Mask {
        let mut entry = F::ZERO;
        let mut exit = limit;
        for axis in 0..3 {
            let (lo, hi) = (F::splat(node.lo[axis]), F::splat(node.hi[axis]));
            let negative = self.negative[axis];
            let (near, far) = (negative.select(hi, lo), negative.select(lo, hi));
            let o = coordinate(&self.origin, axis);
            let inv = coordinate(&self.inv_dir, axis);
            // `t > acc ? t : acc` and `t < acc ? t : acc`, one instruction
            // each (`maxps`, `minps`): a NaN t keeps acc.
            let t_near = (near - o) * inv;
            entry = t_near.fast_max(entry);
            let t_far = (far - o) * inv;
            exit = t_far.fast_min(exit);
        }
        entry.simd_le(widen_up_lanes(exit))
    }
}

/// What a walk through the tree does at the leaves it reaches.
pub(super) trait Visitor<F: FloatLanes> {
    /// Per lane, hits must lie below this (the ray's t_max, or the nearest
    /// hit so far): boxes entered beyond it are skipped.
    fn limit(&self) -> F;
    /// The lanes still searching.
    fn searching(&self) -> F::Mask;
    /// Tests `leaf`'s primitives, which the lanes `entered` may hit; true
    /// ends the walk.
    fn leaf(&mut self, leaf: &Leaf, entered: F::Mask) -> bool;
}

impl Tree {
    /// The tree over `items` (object id and box each), or `None` when it
    /// would be deeper than [`MAX_DEPTH`]. `push_leaf` is called once per
    /// leaf, in depth-first order, with the leaf's object ids; it stores
    /// them and says where.
    pub(super) fn build(
        items: &[(u32, Aabb)],
        mut push_leaf: impl FnMut(&[u32]) -> Leaf,
    ) -> Option<Tree> {
        let mut refs: Vec<PrimRef> = items
            .iter()
            .map(|&(id, b)| PrimRef::new(id, Vec3A::from(b.min), Vec3A::from(b.max)))
            .collect();
        let mut tree = Tree {
            nodes: Vec::with_capacity(2 * items.len() / LEAF_MAX + 1),
            leaves: Vec::new(),
        };
        if refs.is_empty() {
            return None;
        }
        let span = Span::around(&refs, 0);
        tree.grow(&mut refs, span, 1, &mut Splitter::default(), &mut push_leaf)?;
        Some(tree)
    }

    /// Appends the subtree of `span` (at `depth`, the root's being 1),
    /// split by `splitter`.
    fn grow(
        &mut self,
        refs: &mut [PrimRef],
        span: Span,
        depth: usize,
        splitter: &mut Splitter,
        push_leaf: &mut impl FnMut(&[u32]) -> Leaf,
    ) -> Option<()> {
        if depth > MAX_DEPTH {
            return None;
        }
        let own = &refs[span.begin..span.end];
        let (lo, hi) = own.iter().fold(
            (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
            |(lo, hi), r| (lo.min(r.lo()), hi.max(r.hi())),
        );
        let index = self.nodes.len();
        self.nodes.push(Node {
            lo: lo.to_array(),
            hi: hi.to_array(),
            link: 0,
            leaf: true,
        });
        if span.len() <= LEAF_MAX {
            let ids: Vec<u32> = own.iter().map(PrimRef::id).collect();
            self.nodes[index].link = self.leaves.len() as u32;
            self.leaves.push(push_leaf(&ids));
            return Some(());
        }
        let (left, right) = splitter.split(&mut refs[span.begin..span.end], &span);
        self.grow(refs, left, depth + 1, splitter, push_leaf)?;
        let second = self.nodes.len() as u32;
        self.grow(refs, right, depth + 1, splitter, push_leaf)?;
        self.nodes[index].link = second;
        self.nodes[index].leaf = false;
        Some(())
    }

    /// Walks the tree for the packet `rays`: each node whose box some
    /// searching lane enters below its limit, each leaf handed to `visitor`.
    /// Children go in a fixed order (the SAH split's first side first),
    /// whatever the rays:
    /// so a lane's answer, which of two primitives at exactly the same α
    /// included, never depends on the other rays of its packet. (Visiting
    /// the side most of the packet's rays reach first measured no faster:
    /// spheres.xml path-traced 1.458 against 1.457 s, a grid of 500
    /// spheres 0.577 against 0.539 s.)
    #[inline(always)]
    pub(super) fn walk<F: FloatLanes>(&self, rays: &BoxRays<F>, visitor: &mut impl Visitor<F>) {
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0;
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let entered = rays.enter(n, visitor.limit()) & visitor.searching();
            if entered.any() {
                if !n.leaf {
                    stack[top] = n.link;
                    top += 1;
                    node += 1;
                    continue;
                }
                if visitor.leaf(&self.leaves[n.link as usize], entered) {
                    return;
                }
            }
            if top == 0 {
                return;
            }
            top -= 1;
            node = stack[top];
        }
    }
}
