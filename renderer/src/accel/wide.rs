//! The conservative ray test of one compressed 8-wide node (obvhs's
//! `CwBvhNode`, Ylitie et al. 2017): eight child boxes quantised to 8 bits
//! per plane on a grid p + e·q, with e a power of two per axis.
//!
//! Each plane's distance is computed as t = q·c + b with c = e/v and
//! b = (p − P0)/v per node and axis. Its rounding error (and the builder's
//! own rounding when it quantised the boxes, at most a few ulps of the node's
//! extent 255·e) is bounded by an absolute slack
//! s = 2⁻¹⁹ (255 |c| + |b|) + 10⁻³⁰ per node and axis, far above the
//! worst case (about 10 u (255 |c| + |b|), u = 2⁻²⁴); entry distances
//! are lowered and exit distances raised by s. The slack is absolute rather
//! than relative to t because p − P0 and q·e may cancel. Near planes are chosen
//! by the sign bit of 1/v, and NaN (0 · ∞ for a zero direction component) is
//! ignored by the minimum and maximum, so the axis does not reject the ray.
//! The ray's t_min and t_max are used exactly.

use super::slab::{max_ignoring_nan, min_ignoring_nan};
use crate::ray::Ray;
use glam::Vec3;
use obvhs::cwbvh::node::CwBvhNode;

/// Relative slack 2⁻¹⁹ = 32 u on the terms of a plane's distance.
const REL_SLACK: f32 = 16.0 * f32::EPSILON;
/// Absolute slack: covers underflow of the terms in degenerate cases.
const ABS_SLACK: f32 = 1.0e-30;
/// The largest quantised plane coordinate.
const Q_MAX: f32 = 255.0;

/// A ray prepared for 8-wide node tests.
#[derive(Clone, Copy, Debug)]
pub struct WideRay {
    /// P0.
    pub origin: Vec3,
    /// 1/v per component (±∞ for ±0).
    pub inv_dir: Vec3,
    /// Per axis: the sign bit of 1/v (the max plane is near).
    pub neg: [bool; 3],
    /// The octant code of obvhs's child ordering: bit 2 for x ≥ 0, 1 for y,
    /// 0 for z; child slot i is visited in the order of i XOR `oct`.
    pub oct: u32,
    /// Hits at α ≤ t_min are ignored.
    pub t_min: f32,
    /// Hits at α ≥ t_max are ignored; lowered as closer hits are found.
    pub t_max: f32,
}

impl WideRay {
    /// Prepares `ray`.
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        let inv_dir = Vec3::ONE / ray.dir;
        let d = ray.dir;
        Self {
            origin: ray.origin,
            inv_dir,
            neg: [
                inv_dir.x.is_sign_negative(),
                inv_dir.y.is_sign_negative(),
                inv_dir.z.is_sign_negative(),
            ],
            oct: (if d.x < 0.0 { 0 } else { 4 })
                | (if d.y < 0.0 { 0 } else { 2 })
                | (if d.z < 0.0 { 0 } else { 1 }),
            t_min: ray.t_min,
            t_max: ray.t_max,
        }
    }

    /// Bit i set when child slot i of `node` may be hit within (t_min, t_max).
    #[inline(always)]
    pub fn child_hits(&self, node: &CwBvhNode) -> u32 {
        let e = Vec3::from(node.compute_extent());
        let c = e * self.inv_dir;
        let b = (node.p - self.origin) * self.inv_dir;
        let s = (c.abs() * Q_MAX + b.abs()) * REL_SLACK + Vec3::splat(ABS_SLACK);
        let (b_near, b_far) = ((b - s).to_array(), (b + s).to_array());
        let c = c.to_array();
        let planes = [
            (&node.child_min_x, &node.child_max_x),
            (&node.child_min_y, &node.child_max_y),
            (&node.child_min_z, &node.child_max_z),
        ];
        let mut t_near = [self.t_min; 8];
        let mut t_far = [self.t_max; 8];
        for k in 0..3 {
            let (near, far) = if self.neg[k] {
                (planes[k].1, planes[k].0)
            } else {
                (planes[k].0, planes[k].1)
            };
            for i in 0..8 {
                let tn = near[i] as f32 * c[k] + b_near[k];
                let tf = far[i] as f32 * c[k] + b_far[k];
                t_near[i] = max_ignoring_nan(t_near[i], tn);
                t_far[i] = min_ignoring_nan(t_far[i], tf);
            }
        }
        let mut mask = 0u32;
        for i in 0..8 {
            mask |= ((t_near[i] <= t_far[i]) as u32) << i;
        }
        mask
    }

    /// obvhs's traversal mask for `node`: bits 24..32 are the hit internal
    /// children in visiting order (bit 24 + (slot XOR oct)), bits 0..24 the
    /// hit leaves' triangles, relative to `node.primitive_base_idx`.
    #[inline(always)]
    pub fn intersect(&self, node: &CwBvhNode) -> u32 {
        let hits = self.child_hits(node);
        let imask = node.imask as u32;
        let inner = permute_slots(hits & imask, self.oct) << 24;
        let mut leaves = hits & !imask;
        let mut triangles = 0u32;
        while leaves != 0 {
            let i = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            let meta = node.child_meta[i] as u32;
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

    #[test]
    fn permute_slots_moves_bit_i_to_i_xor_oct() {
        for oct in 0..8 {
            for i in 0..8 {
                assert_eq!(permute_slots(1 << i, oct), 1 << (i ^ oct), "{i} {oct}");
            }
        }
    }

    /// A node at p = 0 with e = 1 per axis and child 0 the box [q_lo, q_hi]³.
    fn node_with_child(q_lo: u8, q_hi: u8) -> CwBvhNode {
        let one = 127u8; // exponent byte of 1.0
        let mut node = CwBvhNode {
            e: [one, one, one],
            ..Default::default()
        };
        node.child_min_x[0] = q_lo;
        node.child_min_y[0] = q_lo;
        node.child_min_z[0] = q_lo;
        node.child_max_x[0] = q_hi;
        node.child_max_y[0] = q_hi;
        node.child_max_z[0] = q_hi;
        node.child_meta[0] = 0b0010_0000;
        node
    }

    #[test]
    fn rays_in_a_child_face_with_zero_components_hit_it() {
        let node = node_with_child(2, 4);
        for (ox, dx) in [(0.0f32, 1.0f32), (6.0, -1.0), (3.0, 1.0)] {
            for zero in [0.0f32, -0.0] {
                // In the face z = 2, then along the edge y = 4, z = 4.
                for (y, z) in [(3.0, 2.0), (4.0, 4.0)] {
                    let ray = Ray::new(Vec3::new(ox, y, z), Vec3::new(dx, zero, zero));
                    assert_eq!(WideRay::new(&ray).child_hits(&node) & 1, 1, "{ray:?}");
                }
            }
        }
    }

    #[test]
    fn t_min_is_honoured_not_clamped() {
        let node = node_with_child(2, 4);
        // The box spans t in [2 − 1e-6, 4 − 1e-6]: entering at t = 1e-6 is kept.
        let ray = Ray::new(Vec3::new(3.0, 3.0, 4.0 - 2e-6), Vec3::Z);
        assert_eq!(WideRay::new(&ray).child_hits(&node) & 1, 1);
        // With t_min beyond the exit it is culled.
        let late = Ray { t_min: 1e-3, ..ray };
        assert_eq!(WideRay::new(&late).child_hits(&node) & 1, 0);
    }

    #[test]
    fn child_beyond_t_max_is_culled() {
        let node = node_with_child(2, 4);
        let ray = Ray::new(Vec3::new(3.0, 3.0, -10.0), Vec3::Z);
        assert_eq!(WideRay::new(&ray.with_t_max(11.9)).child_hits(&node) & 1, 0);
        assert_eq!(WideRay::new(&ray.with_t_max(12.1)).child_hits(&node) & 1, 1);
    }
}
