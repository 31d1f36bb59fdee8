//! The conservative ray–box slab test of Ize ("Robust BVH Ray Traversal",
//! JCGT 2013) for boxes stored as exact `f32` corners.
//!
//! - The entry and exit distances of each slab are (plane − P0) · (1/v); each
//!   is within a relative 𝛾₃ of the exact value (one subtraction, the rounded
//!   reciprocal, one product), so the exit distance is enlarged by
//!   2𝛾₃ of its magnitude, and so is the ray's t_max when compared with an
//!   entry distance. t_min is used exactly.
//! - The near plane of each axis is chosen by the sign bit of 1/v, so ±0
//!   components (1/v = ±∞) pick a consistent plane.
//! - A ray lying in a slab's face with a zero direction component gives
//!   0 · ∞ = NaN; the minimum and maximum below ignore NaN, so that slab does
//!   not reject the ray (the face counts as inside).

use crate::geometry::ray::Ray;
use glam::Vec3;

/// Enlargement factor 64ε = 2⁻¹⁷. Ize's bound for the box test alone is
/// 2𝛾₃ (𝛾ₙ = n u / (1 − n u), u = 2⁻²⁴), which 4ε covered; but a box is
/// also skipped when it starts beyond the closest hit so far, and that α
/// carries the triangle test's own rounding: on a shared edge met by a ray
/// lying in a coordinate plane, a nearer triangle's α was found 8.6ε before
/// its leaf's computed entry, and 4ε lost it (proptest, saved in
/// `proptest-regressions/`). Visiting boxes up to 2⁻¹⁷ beyond changed no
/// image, only the shape-test counts.
pub const FAR_SLACK: f32 = 64.0 * f32::EPSILON;

/// max(acc, t) that ignores a NaN `t` (and returns `acc` on ties).
#[inline(always)]
pub fn max_ignoring_nan(acc: f32, t: f32) -> f32 {
    if t > acc { t } else { acc }
}

/// min(acc, t) that ignores a NaN `t` (and returns `acc` on ties).
#[inline(always)]
pub fn min_ignoring_nan(acc: f32, t: f32) -> f32 {
    if t < acc { t } else { acc }
}

/// `x` moved away from zero by `FAR_SLACK` of its magnitude (∞ stays ∞).
#[inline(always)]
pub fn widen_up(x: f32) -> f32 {
    x + x.abs() * FAR_SLACK
}

/// [`widen_up`] lane by lane, for packets of rays.
#[inline(always)]
pub fn widen_up_lanes<F: crate::simd::FloatLanes>(x: F) -> F {
    x + x.abs() * F::splat(FAR_SLACK)
}

/// Ize's test of one box for one ray, in the form the eight-lane loops of
/// the wide node tests vectorise: the entry distance max(t_min, slab
/// entries), and whether the box is entered, that is entry ≤ the widened
/// min(t_max, slab exits). `near` and `far` are the box's near and far
/// planes per axis (chosen by the sign bits of 1/v); a NaN distance (0 · ∞,
/// a ray in a slab's face) is ignored.
#[inline(always)]
pub fn box_entry(
    origin: [f32; 3],
    inv_dir: [f32; 3],
    near: [f32; 3],
    far: [f32; 3],
    t_min: f32,
    t_max: f32,
) -> (f32, bool) {
    let (max, min) = (max_ignoring_nan, min_ignoring_nan);
    let at = |plane: [f32; 3], k: usize| (plane[k] - origin[k]) * inv_dir[k];
    let entry = max(max(max(t_min, at(near, 0)), at(near, 1)), at(near, 2));
    // Starting the exit at t_max folds its test into the widened exit
    // (widening is monotonic, so this only adds slack).
    let exit = min(min(min(t_max, at(far, 0)), at(far, 1)), at(far, 2));
    (entry, entry <= widen_up(exit))
}

/// A ray prepared for many box tests: origin, reciprocal direction, which
/// corner is near on each axis, and its interval.
#[derive(Clone, Copy, Debug)]
pub struct SlabRay {
    /// P0.
    pub origin: Vec3,
    /// 1/v per component (±∞ for ±0).
    pub inv_dir: Vec3,
    /// Per axis: true when the sign bit of 1/v is set (the max plane is near).
    pub neg: [bool; 3],
    /// Hits at α ≤ t_min are ignored (used exactly).
    pub t_min: f32,
    /// Hits at α ≥ t_max are ignored.
    pub t_max: f32,
    /// t_max enlarged by [`FAR_SLACK`], compared with entry distances.
    pub t_max_wide: f32,
}

impl SlabRay {
    /// Prepares `ray`.
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        let inv_dir = Vec3::ONE / ray.dir;
        Self {
            origin: ray.origin,
            inv_dir,
            neg: [
                inv_dir.x.is_sign_negative(),
                inv_dir.y.is_sign_negative(),
                inv_dir.z.is_sign_negative(),
            ],
            t_min: ray.t_min,
            t_max: ray.t_max,
            t_max_wide: widen_up(ray.t_max),
        }
    }

    /// Shrinks the interval's end to `t_max` (after a closer hit).
    #[inline(always)]
    pub fn set_t_max(&mut self, t_max: f32) {
        self.t_max = t_max;
        self.t_max_wide = widen_up(t_max);
    }

    /// The conservative entry distance of the box [min, max], or `None` when
    /// the ray certainly misses it within (t_min, t_max): every point of the
    /// box the ray reaches at some α in the interval makes this `Some`.
    #[inline(always)]
    pub fn enter(&self, min: Vec3, max: Vec3) -> Option<f32> {
        let o = self.origin.to_array();
        let inv = self.inv_dir.to_array();
        let (lo, hi) = (min.to_array(), max.to_array());
        let mut t_near = self.t_min;
        let mut t_far = f32::INFINITY;
        for k in 0..3 {
            let (near, far) = if self.neg[k] {
                (hi[k], lo[k])
            } else {
                (lo[k], hi[k])
            };
            t_near = max_ignoring_nan(t_near, (near - o[k]) * inv[k]);
            t_far = min_ignoring_nan(t_far, (far - o[k]) * inv[k]);
        }
        let t_far = widen_up(t_far);
        (t_near <= t_far && t_near <= self.t_max_wide).then_some(t_near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> (Vec3, Vec3) {
        (Vec3::ZERO, Vec3::ONE)
    }

    #[test]
    fn ray_lying_in_a_box_face_with_zero_direction_components_hits() {
        let (lo, hi) = unit_box();
        for dz in [0.0f32, -0.0] {
            for dy in [0.0f32, -0.0] {
                // In the face z = 0, travelling along +x or −x, from inside and outside.
                for (ox, dx) in [(-1.0, 1.0), (2.0, -1.0), (0.5, 1.0), (0.5, -1.0)] {
                    let ray = Ray::new(Vec3::new(ox, 0.5, 0.0), Vec3::new(dx, dy, dz));
                    assert!(
                        SlabRay::new(&ray).enter(lo, hi).is_some(),
                        "{ray:?} in face z = 0"
                    );
                    // Along the edge y = 0, z = 0 and the edge y = 1, z = 1.
                    let ray = Ray::new(Vec3::new(ox, 1.0, 1.0), Vec3::new(dx, dy, dz));
                    assert!(SlabRay::new(&ray).enter(lo, hi).is_some(), "{ray:?}");
                }
            }
        }
    }

    #[test]
    fn flat_box_is_hit_by_rays_crossing_or_lying_in_it() {
        let (lo, hi) = (Vec3::new(0.0, 0.0, 2.0), Vec3::new(1.0, 1.0, 2.0));
        let crossing = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::Z);
        assert_eq!(SlabRay::new(&crossing).enter(lo, hi), Some(2.0));
        let lying = Ray::new(Vec3::new(-3.0, 0.5, 2.0), Vec3::X);
        assert!(SlabRay::new(&lying).enter(lo, hi).is_some());
    }

    #[test]
    fn zero_direction_component_outside_the_slab_misses() {
        let (lo, hi) = unit_box();
        let ray = Ray::new(Vec3::new(-1.0, 2.0, 0.5), Vec3::X).with_t_max(10.0);
        assert_eq!(SlabRay::new(&ray).enter(lo, hi), None);
    }

    #[test]
    fn box_beyond_t_max_or_before_t_min_misses() {
        let (lo, hi) = unit_box();
        let ray = Ray::new(Vec3::new(0.5, 0.5, -3.0), Vec3::Z);
        assert!(SlabRay::new(&ray.with_t_max(2.9)).enter(lo, hi).is_none());
        assert!(SlabRay::new(&ray.with_t_max(3.1)).enter(lo, hi).is_some());
        let late = Ray { t_min: 4.1, ..ray };
        assert!(SlabRay::new(&late).enter(lo, hi).is_none());
    }

    #[test]
    fn nan_is_ignored_by_min_and_max() {
        assert_eq!(max_ignoring_nan(1.0, f32::NAN), 1.0);
        assert_eq!(min_ignoring_nan(1.0, f32::NAN), 1.0);
        assert_eq!(max_ignoring_nan(1.0, 2.0), 2.0);
        assert_eq!(min_ignoring_nan(1.0, 0.5), 0.5);
    }
}
