//! A binary BVH over a world's primitives, walked by whole packets (Wald,
//! Slusallek, Benthin and Wagner, "Interactive Rendering with Coherent Ray
//! Tracing", 2001): a node is visited once for the eight rays, its box
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
//! [`World::shape_bounds`]: crate::world::World::shape_bounds

use super::{FloatLanes, Rays, Vec3s, coordinate};
use crate::accel::Aabb;
use crate::accel::binned_sah::{PrimRef, Span, split};
use crate::accel::slab::FAR_SLACK;
use glam::Vec3A;
use std::ops::Range;

/// A leaf holds at most this many primitives: a node's box test costs
/// about one primitive test, so leaves of a few primitives keep both
/// small.
const LEAF_MAX: usize = 4;

/// The deepest tree [`Tree::build`] accepts (the traversal's stack).
pub(super) const MAX_DEPTH: usize = 64;

/// [`Node::axis`] of a leaf.
const LEAF: u32 = 3;

/// A leaf's primitives: a range of each kind's list (the kinds store their
/// primitives in leaf order).
#[derive(Clone, Debug, Default)]
pub(super) struct Leaf {
    /// Indices among the triangles.
    pub(super) triangles: Range<u32>,
    /// Indices among the boxes.
    pub(super) boxes: Range<u32>,
    /// Indices among the spheres.
    pub(super) spheres: Range<u32>,
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
    /// An inner node's split axis (its first child lies on the low side);
    /// [`LEAF`] for a leaf.
    axis: u32,
}

/// The tree: nodes in depth-first order, node 0 the root.
#[derive(Clone, Debug)]
pub(super) struct Tree {
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
}

/// Eight rays prepared for box tests: origins, reciprocal directions, the
/// sign of each, and the order in which the packet visits children.
pub(super) struct BoxRays<F> {
    /// P0.
    origin: Vec3s<F>,
    /// 1/v (±∞ for ±0).
    inv_dir: Vec3s<F>,
    /// Per axis, the mask of the lanes whose 1/v has its sign bit set
    /// (whose near plane is the box's high one).
    negative: [F; 3],
    /// Per axis, whether most live lanes travel toward −axis: the packet
    /// then visits the high child first.
    high_first: [bool; 3],
}

impl<F: FloatLanes> BoxRays<F> {
    /// `rays` ready for box tests; `live` are the lanes that count when
    /// choosing the order of children.
    #[inline(always)]
    pub(super) fn new(rays: &Rays<F>, live: F) -> Self {
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
        let live_count = live.to_bitmask().count_ones();
        let most = |n: F| 2 * (n & live).to_bitmask().count_ones() > live_count;
        let high_first = [most(negative[0]), most(negative[1]), most(negative[2])];
        Self {
            origin: rays.origin,
            inv_dir,
            negative,
            high_first,
        }
    }

    /// The lanes whose ray may meet `node`'s box in (0, limit): Ize's test
    /// lane by lane, exactly `slab::box_entry` with t_min = 0 (its NaN-
    /// ignoring maximum and minimum are `fast_max` and `fast_min` with the
    /// new distance first).
    #[inline(always)]
    fn enter(&self, node: &Node, limit: F) -> F {
        let mut entry = F::ZERO;
        let mut exit = limit;
        for axis in 0..3 {
            let (lo, hi) = (F::splat(node.lo[axis]), F::splat(node.hi[axis]));
            let negative = self.negative[axis];
            let (near, far) = (negative.select(hi, lo), negative.select(lo, hi));
            let o = coordinate(&self.origin, axis);
            let inv = coordinate(&self.inv_dir, axis);
            entry = ((near - o) * inv).fast_max(entry);
            exit = ((far - o) * inv).fast_min(exit);
        }
        entry.simd_le(exit + exit.abs() * F::splat(FAR_SLACK))
    }
}

/// What a walk through the tree does at the leaves it reaches.
pub(super) trait Visitor<F: FloatLanes> {
    /// Per lane, hits must lie below this (the ray's t_max, or the nearest
    /// hit so far): boxes entered beyond it are skipped.
    fn limit(&self) -> F;
    /// The lanes still searching.
    fn searching(&self) -> F;
    /// Tests `leaf`'s primitives, which the lanes `entered` may hit; true
    /// ends the walk.
    fn leaf(&mut self, leaf: &Leaf, entered: F) -> bool;
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
        tree.grow(&mut refs, span, 1, &mut push_leaf)?;
        Some(tree)
    }

    /// Appends the subtree of `span` (at `depth`, the root's being 1).
    fn grow(
        &mut self,
        refs: &mut [PrimRef],
        span: Span,
        depth: usize,
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
            axis: LEAF,
        });
        if span.len() <= LEAF_MAX {
            let ids: Vec<u32> = own.iter().map(PrimRef::id).collect();
            self.nodes[index].link = self.leaves.len() as u32;
            self.leaves.push(push_leaf(&ids));
            return Some(());
        }
        let (left, right) = split(&mut refs[span.begin..span.end], &span);
        // The axis along which the halves' centroids lie apart the most:
        // the packet orders the children by its rays' signs along it.
        let apart = ((right.centroids.lo + right.centroids.hi)
            - (left.centroids.lo + left.centroids.hi))
            .to_array();
        let axis = (0..3).fold(0, |best, k| if apart[k] > apart[best] { k } else { best });
        self.grow(refs, left, depth + 1, push_leaf)?;
        let second = self.nodes.len() as u32;
        self.grow(refs, right, depth + 1, push_leaf)?;
        self.nodes[index].link = second;
        self.nodes[index].axis = axis as u32;
        Some(())
    }

    /// Walks the tree for the packet `rays`: each node whose box some
    /// searching lane enters below its limit, children in the packet's
    /// order (nearest first for most lanes), each leaf handed to `visitor`.
    #[inline(always)]
    pub(super) fn walk<F: FloatLanes>(&self, rays: &BoxRays<F>, visitor: &mut impl Visitor<F>) {
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0;
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let entered = rays.enter(n, visitor.limit()) & visitor.searching();
            if entered.any() {
                if n.axis != LEAF {
                    let (low, high) = (node + 1, n.link);
                    let (first, second) = if rays.high_first[n.axis as usize] {
                        (high, low)
                    } else {
                        (low, high)
                    };
                    stack[top] = second;
                    top += 1;
                    node = first;
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
