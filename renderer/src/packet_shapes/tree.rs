//! An 8-wide BVH over a world's primitives, walked as Embree's hybrid
//! traversal walks its BVH8 for a packet of sixteen rays (Benthin, Wald,
//! Woop, Ernst and Mark, "Combining Single and Packet-Ray Tracing for
//! Arbitrary Ray Distributions on the Intel MIC Architecture", 2012): a node
//! is visited once for the whole packet, each of its eight children's boxes
//! tested against the sixteen rays at once; and once a subtree is entered by
//! only a few of the packet's rays ([`ALONE_MAX`]), each of them walks it
//! alone, eight children per box test, while the others wait. A leaf's
//! primitives are tested against every lane with the packet tests of their
//! kinds, or against the one ray walking alone with the scalar tests, which
//! give the same α bit for bit; so each lane's answer is the one the
//! brute-force packet test gives: the tree only leaves out primitives a lane
//! cannot hit.
//!
//! Children go in a fixed order (the order the builder gave them), in
//! packets and alone alike: so which of two primitives at exactly the same α
//! a lane finds never depends on the other rays of its packet, nor on
//! whether it walked part of the tree alone. (Visiting the side most of the
//! packet's rays reach first measured no faster with the binary tree this
//! one replaced: spheres.xml path-traced 1.458 against 1.457 s.)
//!
//! The box test is Ize's conservative slab test of `accel/slab.rs` lane by
//! lane, and a primitive's box is the one the world's own top level holds it
//! in ([`World::shape_bounds`], padded for its test's rounding), so no hit
//! is lost that the scalar BVH finds.
//!
//! [`World::shape_bounds`]: crate::world::World::shape_bounds

use super::{FloatLanes, MaskLanes, Rays, Vec3s};
use crate::accel::Aabb;
use crate::accel::binned_sah::PrimRef;
use crate::accel::slab::{widen_up, widen_up_lanes};
use crate::accel::stack::Stack;
use crate::accel::triangle_pack::TrianglePack;
use crate::accel::wide::{ChildRef, WIDTH as CHILDREN, WideNode, WideRay, pop_within};
use crate::accel::wide_build::build_wide_refs;
use crate::geometry::ray::Ray;
use glam::Vec3A;
use std::ops::Range;

/// A leaf holds at most this many primitives: a node's box test costs
/// about one primitive test, so leaves of a few primitives keep both
/// small.
const LEAF_MAX: usize = 4;

/// A subtree entered by at most this many of a packet's rays is walked by
/// each of them alone.
pub(super) const ALONE_MAX: u32 = 4;

/// A leaf's primitives: a range of each kind's list (the kinds store their
/// primitives in leaf order), and its triangles packed for one ray.
#[derive(Clone, Debug, Default)]
pub(super) struct Leaf {
    /// Indices among the triangles.
    pub(super) triangles: Range<usize>,
    /// Indices among the boxes.
    pub(super) boxes: Range<usize>,
    /// Indices among the spheres.
    pub(super) spheres: Range<usize>,
    /// The triangles again, for one ray at a time, each by its key; `None`
    /// when the leaf has none.
    pub(super) pack: Option<TrianglePack>,
}

impl Leaf {
    /// How many primitives it holds.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.triangles.len() + self.boxes.len() + self.spheres.len()
    }
}

/// The tree: 8-wide nodes (node 0 the root) and their leaves.
#[derive(Clone, Debug)]
pub(super) struct Tree {
    nodes: Vec<WideNode>,
    /// Indexed by the first (and only) pack of a leaf's [`ChildRef`].
    leaves: Vec<Leaf>,
    /// A subtree entered by at most this many of a packet's lanes is
    /// walked by each of them alone: [`ALONE_MAX`] (tests try 0, packets
    /// only, and 16, every lane alone from the root).
    pub(super) alone_max: u32,
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

    /// Per lane, the entry distance into child `slot` of `node`, and the
    /// lanes whose ray may meet that box in (0, limit): Ize's test lane by
    /// lane, exactly `slab::box_entry` with t_min = 0, whose maximum and
    /// minimum ignore a NaN distance (a ray lying in a face with a zero
    /// direction component: 0 · ∞).
    #[inline(always)]
    fn enter(&self, node: &WideNode, slot: usize, limit: F) -> (F, F::Mask) {
        let mut entry = F::ZERO;
        let mut exit = limit;
        for axis in 0..3 {
            let lo = F::splat(node.plane(2 * axis, slot));
            let hi = F::splat(node.plane(2 * axis + 1, slot));
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
        (entry, entry.simd_le(widen_up_lanes(exit)))
    }
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

/// What a walk through the tree does at the leaves a packet reaches.
pub(super) trait Visitor<F: FloatLanes> {
    /// One lane's search, walking part of the tree alone.
    type Lane: LaneVisitor;
    /// Per lane, hits must lie below this (the ray's t_max, or the nearest
    /// hit so far): boxes entered beyond it are skipped.
    fn limit(&self) -> F;
    /// The lanes still searching.
    fn searching(&self) -> F::Mask;
    /// Tests `leaf`'s primitives, which the lanes `entered` may hit; true
    /// ends the walk.
    fn leaf(&mut self, leaf: &Leaf, entered: F::Mask) -> bool;
    /// Lane `k`'s search as it stands, to go on alone.
    fn lane(&self, k: usize) -> Self::Lane;
    /// Takes back lane `k`'s search after it went on alone; true ends the
    /// walk.
    fn put_lane(&mut self, k: usize, lane: Self::Lane) -> bool;
}

/// What one lane walking alone does at the leaves it reaches.
pub(super) trait LaneVisitor {
    /// Its ray, over (0, its limit).
    fn ray(&self) -> Ray;
    /// Hits must lie below this: boxes entered beyond it are skipped.
    fn limit(&self) -> f32;
    /// Tests `leaf`'s primitives; true ends this lane's walk.
    fn leaf(&mut self, leaf: &Leaf) -> bool;
}

/// A subtree waiting on the packet's stack: its root, and per lane the
/// distance at which the lane's ray enters it (+∞ for a lane that does not).
#[derive(Clone, Copy)]
struct Waiting<F: FloatLanes> {
    child: ChildRef,
    entry: F,
}

impl Tree {
    /// The tree over `items` (object id and box each). `push_leaf` is
    /// called once per leaf with the leaf's object ids; it stores them and
    /// says where.
    pub(super) fn build(items: &[(u32, Aabb)], mut push_leaf: impl FnMut(&[u32]) -> Leaf) -> Tree {
        let mut refs: Vec<PrimRef> = items
            .iter()
            .map(|&(id, b)| PrimRef::new(id, Vec3A::from(b.min), Vec3A::from(b.max)))
            .collect();
        let (nodes, runs, _) = build_wide_refs(&mut refs, LEAF_MAX);
        // With leaves of at most LEAF_MAX = PACK primitives, each leaf is
        // one run.
        let leaves = runs
            .iter()
            .map(|&(first, count)| {
                let ids: Vec<u32> = refs[first as usize..(first + count) as usize]
                    .iter()
                    .map(PrimRef::id)
                    .collect();
                push_leaf(&ids)
            })
            .collect();
        Tree {
            nodes,
            leaves,
            alone_max: ALONE_MAX,
        }
    }

    /// The leaf `child` refers to, or `None` for an inner node.
    #[inline(always)]
    fn leaf(&self, child: ChildRef) -> Option<&Leaf> {
        child.packs().map(|packs| &self.leaves[packs.start])
    }

    /// Walks the tree for the packet `rays`: each node whose box some
    /// searching lane enters below its limit, each leaf handed to
    /// `visitor`; a subtree entered by at most [`ALONE_MAX`] lanes is
    /// walked by each of them alone ([`Tree::walk_alone`]).
    #[inline(always)]
    pub(super) fn walk<F: FloatLanes, V: Visitor<F>>(&self, rays: &BoxRays<F>, visitor: &mut V) {
        let mut stack: Stack<Waiting<F>, 64> = Stack::new();
        stack.push(Waiting {
            child: ChildRef::node(0),
            entry: F::ZERO,
        });
        while let Some(Waiting { child, entry }) = stack.pop() {
            let limit = visitor.limit();
            let active = entry.simd_le(widen_up_lanes(limit)) & visitor.searching();
            let mut bits = active.to_bitmask();
            if bits == 0 {
                continue;
            }
            if bits.count_ones() <= self.alone_max {
                while bits != 0 {
                    let k = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let mut lane = visitor.lane(k);
                    self.walk_alone(child, &mut lane);
                    if visitor.put_lane(k, lane) {
                        return;
                    }
                }
                continue;
            }
            if let Some(leaf) = self.leaf(child) {
                if visitor.leaf(leaf, active) {
                    return;
                }
                continue;
            }
            let node = &self.nodes[child.0 as usize];
            // Last child pushed first, so that they are popped in order.
            for slot in (0..CHILDREN).rev() {
                let child = node.children[slot];
                if child == ChildRef::EMPTY {
                    continue;
                }
                let (entry, entered) = rays.enter(node, slot, limit);
                let entered = entered & active;
                if entered.any() {
                    stack.push(Waiting {
                        child,
                        entry: entered.select(entry, F::INFINITY),
                    });
                }
            }
        }
    }

    /// Walks the subtree of `start` for one lane alone: the children of a
    /// node tested eight at once ([`WideRay::child_hits`]) and visited in
    /// their fixed order, each leaf handed to `lane`.
    #[inline(always)]
    fn walk_alone(&self, start: ChildRef, lane: &mut impl LaneVisitor) {
        let mut ray = WideRay::new(&lane.ray());
        let mut stack: Stack<(ChildRef, f32), 64> = Stack::new();
        let mut child = start;
        loop {
            if let Some(leaf) = self.leaf(child) {
                if lane.leaf(leaf) {
                    return;
                }
            } else {
                let node = &self.nodes[child.0 as usize];
                let limit = lane.limit();
                ray.slab.t_max = limit;
                ray.slab.t_max_wide = widen_up(limit);
                let (mut mask, entry) = ray.child_hits(node);
                // Last child pushed first, so that they are popped in order.
                while mask != 0 {
                    let slot = 31 - mask.leading_zeros() as usize;
                    mask &= !(1 << slot);
                    stack.push((node.children[slot], entry[slot]));
                }
            }
            match pop_within(&mut stack, widen_up(lane.limit())) {
                Some(next) => child = next,
                None => return,
            }
        }
    }
}
