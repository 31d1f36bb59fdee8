//! The 8-wide node of the mesh BVH and its conservative ray test.
//!
//! The tree is obvhs's compressed wide BVH (CWBVH, Ylitie et al. 2017): its
//! topology, child order and leaf layout are kept, but each node's eight
//! quantised child boxes are replaced by the exact `f32` boxes they were
//! quantised from (the BVH2 node boxes, or the union of the leaf's triangle
//! boxes), stored plane by plane so the test of eight children vectorises.
//! Exact boxes are tighter than the quantised ones and make the test Ize's
//! slab test ([`super::slab`]) with nothing more to account for. (Measured
//! against testing the quantised 80-byte nodes directly, with a slack for
//! their rounding: that ran slower, see the commit message.)

use super::slab::{FAR_SLACK, SlabRay, max_ignoring_nan, min_ignoring_nan};
use obvhs::cwbvh::CwBvh;

/// One node: up to eight children, each an inner node or a leaf of up to
/// three triangles.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct WideNode {
    /// planes[2k][h][j] is child 4h + j's min along axis k, planes[2k + 1]
    /// its max (two halves of four lanes, the width of an SSE register);
    /// empty slots have min = +∞ and max = −∞ (never hit).
    planes: [[[f32; 4]; 2]; 6],
    /// Index of the first inner child; the others follow in slot order.
    pub child_base: u32,
    /// Index of the first triangle of the leaf children.
    pub prim_base: u32,
    /// Bit i set when child i is an inner node.
    pub imask: u8,
    /// obvhs's per-child meta: inner: 0b001 << 5 | (24 + i); leaf: unary
    /// triangle count << 5 | first triangle offset; empty: 0.
    meta: [u8; 8],
}

impl WideNode {
    /// The nodes of `cw` with exact child boxes: `exact` are the nodes' own
    /// exact boxes (obvhs's `exact_node_aabbs`), `triangle_box(slot)` the
    /// box of the triangle at a leaf slot.
    pub fn from_cwbvh(
        cw: &CwBvh,
        triangle_box: impl Fn(usize) -> ([f32; 3], [f32; 3]),
    ) -> Vec<WideNode> {
        let exact = cw
            .exact_node_aabbs
            .as_ref()
            .expect("CWBVH built with exact node boxes");
        cw.nodes
            .iter()
            .map(|n| {
                let mut planes = [[f32::INFINITY; 8], [f32::NEG_INFINITY; 8]].repeat(3);
                for i in 0..8 {
                    let meta = n.child_meta[i];
                    if meta == 0 {
                        continue;
                    }
                    let (lo, hi) = if n.imask & (1 << i) != 0 {
                        let b = exact[n.child_node_index(i) as usize];
                        (b.min.to_array(), b.max.to_array())
                    } else {
                        let (first, count) = n.child_primitives(i);
                        (first..first + count).fold(
                            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
                            |(lo, hi), s| {
                                let (a, b) = triangle_box(s as usize);
                                (
                                    std::array::from_fn(|k| lo[k].min(a[k])),
                                    std::array::from_fn(|k| hi[k].max(b[k])),
                                )
                            },
                        )
                    };
                    for k in 0..3 {
                        planes[2 * k][i] = lo[k];
                        planes[2 * k + 1][i] = hi[k];
                    }
                }
                WideNode {
                    planes: halves(&planes),
                    child_base: n.child_base_idx,
                    prim_base: n.primitive_base_idx,
                    imask: n.imask,
                    meta: n.child_meta,
                }
            })
            .collect()
    }
}

/// Eight lanes per plane split into two halves of four.
fn halves(planes: &[[f32; 8]]) -> [[[f32; 4]; 2]; 6] {
    std::array::from_fn(|j| std::array::from_fn(|h| std::array::from_fn(|i| planes[j][4 * h + i])))
}

/// A ray prepared for 8-wide node tests: the slab ray and obvhs's octant
/// code for the child order.
#[derive(Clone, Copy, Debug)]
pub struct WideRay {
    /// Origin, reciprocal direction, near planes, interval.
    pub slab: SlabRay,
    /// Bit 2 for v.x ≥ 0, 1 for y, 0 for z; child slot i is visited in the
    /// order of i XOR `oct` (obvhs orders the slots for this at build time).
    pub oct: u32,
    /// Per axis k, the index in `WideNode::planes` of the near planes
    /// (2k + sign bit of 1/v) and of the far planes.
    near_far: [(usize, usize); 3],
}

impl WideRay {
    /// Prepares `ray`.
    #[inline(always)]
    pub fn new(ray: &crate::ray::Ray) -> Self {
        let d = ray.dir;
        let slab = SlabRay::new(ray);
        Self {
            near_far: std::array::from_fn(|k| {
                let n = slab.neg[k] as usize;
                (2 * k + n, 2 * k + 1 - n)
            }),
            slab,
            oct: (if d.x < 0.0 { 0 } else { 4 })
                | (if d.y < 0.0 { 0 } else { 2 })
                | (if d.z < 0.0 { 0 } else { 1 }),
        }
    }

    /// Bit i set when child slot i of `node` may be hit within
    /// (t_min, t_max) (Ize's test, eight children at once).
    #[inline(always)]
    pub fn child_hits(&self, node: &WideNode) -> u32 {
        let s = &self.slab;
        let o = s.origin.to_array();
        let inv = s.inv_dir.to_array();
        let mut mask = 0u32;
        for h in 0..2 {
            // Starting the exit at t_max folds its test into the widened
            // exit (widening is monotonic, so this only adds slack).
            let mut t_near = [s.t_min; 4];
            let mut t_far = [s.t_max; 4];
            for k in 0..3 {
                let (n, f) = self.near_far[k];
                let (near, far) = (&node.planes[n][h], &node.planes[f][h]);
                for i in 0..4 {
                    t_near[i] = max_ignoring_nan(t_near[i], (near[i] - o[k]) * inv[k]);
                    t_far[i] = min_ignoring_nan(t_far[i], (far[i] - o[k]) * inv[k]);
                }
            }
            for i in 0..4 {
                let far = t_far[i] + t_far[i].abs() * FAR_SLACK;
                mask |= ((t_near[i] <= far) as u32) << (4 * h + i);
            }
        }
        mask
    }

    /// obvhs's traversal mask for `node`: bits 24..32 are the hit inner
    /// children in visiting order (bit 24 + (slot XOR oct)), bits 0..24 the
    /// hit leaves' triangles, relative to `node.prim_base`.
    #[inline(always)]
    pub fn intersect(&self, node: &WideNode) -> u32 {
        let hits = self.child_hits(node);
        let imask = node.imask as u32;
        let inner = permute_slots(hits & imask, self.oct) << 24;
        let mut leaves = hits & !imask;
        let mut triangles = 0u32;
        while leaves != 0 {
            let i = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            let meta = node.meta[i] as u32;
            // Unary triangle count in the top 3 bits, first offset in the low 5.
            triangles |= (meta >> 5) << (meta & 31);
        }
        inner | triangles
    }
}

/// Moves bit i of the 8-bit `mask` to bit i XOR `oct`.
#[inline(always)]
pub fn permute_slots(mut mask: u32, oct: u32) -> u32 {
    if oct & 1 != 0 {
        mask = ((mask & 0x55) << 1) | ((mask >> 1) & 0x55);
    }
    if oct & 2 != 0 {
        mask = ((mask & 0x33) << 2) | ((mask >> 2) & 0x33);
    }
    if oct & 4 != 0 {
        mask = ((mask & 0x0f) << 4) | ((mask >> 4) & 0x0f);
    }
    mask
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::Ray;
    use glam::Vec3;

    #[test]
    fn permute_slots_moves_bit_i_to_i_xor_oct() {
        for oct in 0..8 {
            for i in 0..8 {
                assert_eq!(permute_slots(1 << i, oct), 1 << (i ^ oct), "{i} {oct}");
            }
        }
    }

    /// A node whose child 0 is the box [lo, hi]³ and whose other slots are empty.
    fn node_with_child(lo: f32, hi: f32) -> WideNode {
        let mut planes = [[f32::INFINITY; 8], [f32::NEG_INFINITY; 8]].repeat(3);
        for k in 0..3 {
            planes[2 * k][0] = lo;
            planes[2 * k + 1][0] = hi;
        }
        WideNode {
            planes: halves(&planes),
            child_base: 0,
            prim_base: 0,
            imask: 0,
            meta: [0b0010_0000, 0, 0, 0, 0, 0, 0, 0],
        }
    }

    #[test]
    fn rays_in_a_child_face_with_zero_components_hit_it_and_empty_slots_never() {
        let node = node_with_child(2.0, 4.0);
        for (ox, dx) in [(0.0f32, 1.0f32), (6.0, -1.0), (3.0, 1.0)] {
            for zero in [0.0f32, -0.0] {
                // In the face z = 2, then along the edge y = 4, z = 4.
                for (y, z) in [(3.0, 2.0), (4.0, 4.0)] {
                    let ray = Ray::new(Vec3::new(ox, y, z), Vec3::new(dx, zero, zero));
                    assert_eq!(WideRay::new(&ray).child_hits(&node), 1, "{ray:?}");
                }
            }
        }
    }

    #[test]
    fn t_min_is_honoured_not_clamped() {
        let node = node_with_child(2.0, 4.0);
        // The box's exit is at t = 1e-6: kept with t_min = 0, culled with 1e-5.
        let ray = Ray::new(Vec3::new(3.0, 3.0, 4.0 - 1e-6), Vec3::Z);
        assert_eq!(WideRay::new(&ray).child_hits(&node), 1);
        let late = Ray { t_min: 1e-5, ..ray };
        assert_eq!(WideRay::new(&late).child_hits(&node), 0);
    }

    #[test]
    fn child_beyond_t_max_is_culled() {
        let node = node_with_child(2.0, 4.0);
        let ray = Ray::new(Vec3::new(3.0, 3.0, -10.0), Vec3::Z);
        assert_eq!(WideRay::new(&ray.with_t_max(11.99)).child_hits(&node), 0);
        assert_eq!(WideRay::new(&ray.with_t_max(12.01)).child_hits(&node), 1);
    }
}
