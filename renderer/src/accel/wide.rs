//! The 8-wide node of the mesh BVH and its conservative ray test.
//!
//! A node holds the exact `f32` boxes of up to eight children, stored plane
//! by plane (all eight minima along x, then all maxima, …) so that the test
//! of the eight children is a handful of 8-lane operations
//! ([`super::simd`]). The test is Ize's slab test ([`super::slab`]), with
//! nothing more to account for since the boxes are the exact unions of
//! their triangles' boxes. It returns each child's entry distance, so the
//! traversal visits the nearest child first and skips, when it pops a
//! child, one that starts beyond the closest hit found meanwhile.

use super::slab::{SlabRay, box_entry};
use super::stack::Stack;
use super::triangle_pack::PACK;
use wide::f32x8;

/// Children per node.
pub const WIDTH: usize = 8;

/// A set of at most this many triangles becomes one leaf (four packs).
/// A walk through a mesh too large for the caches waits for each node and
/// leaf in turn, and a larger leaf is one level fewer to wait for, its
/// packs loaded together. On the million-triangle knot against leaves of
/// two packs (alternated runs, medians): incoherent closest hits on one
/// thread 2.30 -> 2.48 Mrays/s (8 runs; 3.77 -> 4.20 on a knot of 200,000,
/// 6 runs), primary rays 12.5 -> 12.9 (4 runs), 6% less memory. Leaves of
/// five packs gave the same, of six and eight 1-2% less (within the noise).
/// (Against one pack, two had given a fifth less memory and the same speed.)
pub const LEAF_TRIANGLES: usize = 4 * PACK;

/// A reference to a child: an inner node, a leaf (a run of triangle packs)
/// or nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ChildRef(pub u32);

impl ChildRef {
    /// Bit set for a leaf.
    const LEAF: u32 = 1 << 31;
    /// Where a leaf keeps its pack count minus one.
    const COUNT_SHIFT: u32 = 28;
    /// Most packs in one leaf.
    pub const MAX_PACKS: usize = 8;
    /// Most packs in a mesh (the bits left for a leaf's first pack).
    pub const MAX_PACK_INDEX: usize = (1 << Self::COUNT_SHIFT) - 1;
    /// An empty slot.
    pub const EMPTY: ChildRef = ChildRef(u32::MAX);

    /// The inner node at `index`.
    pub fn node(index: u32) -> ChildRef {
        debug_assert!(index < Self::LEAF);
        ChildRef(index)
    }

    /// The leaf of `count` (1..=MAX_PACKS) packs starting at `first`.
    pub fn leaf(first: usize, count: usize) -> ChildRef {
        assert!((1..=Self::MAX_PACKS).contains(&count) && first <= Self::MAX_PACK_INDEX);
        ChildRef(Self::LEAF | ((count as u32 - 1) << Self::COUNT_SHIFT) | first as u32)
    }

    /// The packs of a leaf, `None` for an inner node.
    #[inline(always)]
    pub fn packs(self) -> Option<std::ops::Range<usize>> {
        (self.0 & Self::LEAF != 0).then(|| {
            let first = (self.0 & ((1 << Self::COUNT_SHIFT) - 1)) as usize;
            let count = ((self.0 >> Self::COUNT_SHIFT) & 0b111) as usize + 1;
            first..first + count
        })
    }
}

/// One node: up to eight children with their exact boxes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct WideNode {
    /// `planes[2k][i]` is child i's min along axis k, `planes[2k + 1][i]` its
    /// max; empty slots have min = +∞ and max = −∞ (never hit).
    planes: [[f32; WIDTH]; 6],
    /// The children; [`ChildRef::EMPTY`] for an empty slot.
    pub children: [ChildRef; WIDTH],
}

impl WideNode {
    /// A node with no children.
    pub const EMPTY: WideNode = WideNode {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        children: [ChildRef::EMPTY; WIDTH],
    };

    /// Plane `p` of child `slot`: the min (p = 2k) or max (p = 2k + 1) of
    /// its box along axis k.
    #[inline(always)]
    pub fn plane(&self, p: usize, slot: usize) -> f32 {
        self.planes[p][slot]
    }

    /// Puts `child` with the box [min, max] in slot `slot`.
    pub fn set_child(&mut self, slot: usize, child: ChildRef, min: [f32; 3], max: [f32; 3]) {
        for k in 0..3 {
            self.planes[2 * k][slot] = min[k];
            self.planes[2 * k + 1][slot] = max[k];
        }
        self.children[slot] = child;
    }
}

/// A ray prepared for 8-wide node tests.
#[derive(Clone, Copy, Debug)]
pub struct WideRay {
    /// Origin, reciprocal direction, near planes, interval.
    pub slab: SlabRay,
    /// Per axis k, the index in `WideNode::planes` of the near planes
    /// (2k + sign bit of 1/v) and of the far planes.
    near_far: [(usize, usize); 3],
}

impl WideRay {
    /// Prepares `ray`.
    #[inline(always)]
    pub fn new(ray: &crate::geometry::ray::Ray) -> Self {
        let slab = SlabRay::new(ray);
        Self {
            near_far: std::array::from_fn(|k| {
                let n = slab.neg[k] as usize;
                (2 * k + n, 2 * k + 1 - n)
            }),
            slab,
        }
    }

    /// Bit i set when child i of `node` may be hit within (t_min, t_max)
    /// (Ize's test, eight children at once), and each child's entry
    /// distance (at least t_min; meaningless for a child not hit).
    #[inline(always)]
    pub fn child_hits(&self, node: &WideNode) -> (u32, [f32; WIDTH]) {
        let s = &self.slab;
        let (origin, inv_dir) = (s.origin.to_array(), s.inv_dir.to_array());
        let [(n0, f0), (n1, f1), (n2, f2)] = self.near_far;
        let (nx, ny, nz) = (&node.planes[n0], &node.planes[n1], &node.planes[n2]);
        let (fx, fy, fz) = (&node.planes[f0], &node.planes[f1], &node.planes[f2]);
        let mut t_near = [0.0f32; WIDTH];
        // Whether child i is entered, as a lane of all ones or zeros, so
        // that the mask is one compare-and-extract across the lanes.
        let mut entered = [0.0f32; WIDTH];
        // One lane per child: the shape the compiler vectorises into
        // whole-register operations.
        for i in 0..WIDTH {
            let (near, hit) = box_entry(
                origin,
                inv_dir,
                [nx[i], ny[i], nz[i]],
                [fx[i], fy[i], fz[i]],
                s.t_min,
                s.t_max,
            );
            t_near[i] = near;
            entered[i] = f32::from_bits(if hit { u32::MAX } else { 0 });
        }
        let mask = f32x8::new(entered).to_bitmask();
        (mask, t_near)
    }
}

/// The children of `node` whose bits are set in `mask` (from
/// [`WideRay::child_hits`], with their entry distances `t_near`): all but the
/// nearest are pushed on `stack`, nearest last, and the nearest is returned
/// to visit next. `each` sees every child as it is sorted in (a walk
/// prefetches it). `mask` must not be 0.
#[inline(always)]
pub(crate) fn push_children_nearest_last<const N: usize>(
    node: &WideNode,
    mut mask: u32,
    t_near: &[f32; WIDTH],
    stack: &mut Stack<(ChildRef, f32), N>,
    mut each: impl FnMut(ChildRef),
) -> ChildRef {
    debug_assert_ne!(mask, 0, "a node with no child hit");
    let mut hits = [(ChildRef::EMPTY, 0.0f32); WIDTH];
    let mut n = 0;
    while mask != 0 {
        let i = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        let mut j = n;
        while j > 0 && hits[j - 1].1 < t_near[i] {
            hits[j] = hits[j - 1];
            j -= 1;
        }
        let child = node.children[i];
        each(child);
        hits[j] = (child, t_near[i]);
        n += 1;
    }
    for &h in &hits[..n - 1] {
        stack.push(h);
    }
    hits[n - 1].0
}

/// The next child waiting on `stack` that may still hold a hit closer than
/// `t_max_wide` (the slab's widened t_max); children entered beyond it are
/// dropped. `None` when the walk is over.
#[inline(always)]
pub(crate) fn pop_within<const N: usize>(
    stack: &mut Stack<(ChildRef, f32), N>,
    t_max_wide: f32,
) -> Option<ChildRef> {
    loop {
        match stack.pop() {
            None => return None,
            Some((child, t_near)) if t_near <= t_max_wide => return Some(child),
            Some(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ray::Ray;
    use glam::Vec3;

    /// A node whose child 0 is the box [lo, hi]³ and whose other slots are empty.
    fn node_with_child(lo: f32, hi: f32) -> WideNode {
        let mut node = WideNode::EMPTY;
        node.set_child(0, ChildRef::leaf(0, 1), [lo; 3], [hi; 3]);
        node
    }

    #[test]
    fn child_refs_round_trip() {
        assert_eq!(ChildRef::leaf(7, 3).packs(), Some(7..10));
        assert_eq!(
            ChildRef::leaf(ChildRef::MAX_PACK_INDEX, 8).packs(),
            Some(ChildRef::MAX_PACK_INDEX..ChildRef::MAX_PACK_INDEX + 8)
        );
        assert_eq!(ChildRef::node(12).packs(), None);
    }

    #[test]
    fn rays_in_a_child_face_with_zero_components_hit_it_and_empty_slots_never() {
        let node = node_with_child(2.0, 4.0);
        for (ox, dx) in [(0.0f32, 1.0f32), (6.0, -1.0), (3.0, 1.0)] {
            for zero in [0.0f32, -0.0] {
                // In the face z = 2, then along the edge y = 4, z = 4.
                for (y, z) in [(3.0, 2.0), (4.0, 4.0)] {
                    let ray = Ray::new(Vec3::new(ox, y, z), Vec3::new(dx, zero, zero));
                    assert_eq!(WideRay::new(&ray).child_hits(&node).0, 1, "{ray:?}");
                }
            }
        }
    }

    #[test]
    fn entry_distance_is_reported_and_t_min_is_honoured_not_clamped() {
        let node = node_with_child(2.0, 4.0);
        let ray = Ray::new(Vec3::new(3.0, 3.0, -1.0), Vec3::Z);
        let (mask, t_near) = WideRay::new(&ray).child_hits(&node);
        assert_eq!((mask, t_near[0]), (1, 3.0));
        // The box's exit is at t = 1e-6: kept with t_min = 0, culled with 1e-5.
        let ray = Ray::new(Vec3::new(3.0, 3.0, 4.0 - 1e-6), Vec3::Z);
        assert_eq!(WideRay::new(&ray).child_hits(&node).0, 1);
        let late = Ray { t_min: 1e-5, ..ray };
        assert_eq!(WideRay::new(&late).child_hits(&node).0, 0);
    }

    #[test]
    fn child_beyond_t_max_is_culled() {
        let node = node_with_child(2.0, 4.0);
        let ray = Ray::new(Vec3::new(3.0, 3.0, -10.0), Vec3::Z);
        assert_eq!(WideRay::new(&ray.with_t_max(11.99)).child_hits(&node).0, 0);
        assert_eq!(WideRay::new(&ray.with_t_max(12.01)).child_hits(&node).0, 1);
    }
}
