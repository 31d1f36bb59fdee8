//! A loose bounding sphere in world space: a cheap test that lets a shape
//! skip its object-space transform and exact intersection for rays that
//! clearly pass it by, without ever changing which rays hit it.

use crate::geometry::ray::Ray;
use crate::packet::{FloatLanes, Vec3s};
use glam::Vec3;

/// Relative slack on the shape's enclosing radius.
const RADIUS_SLACK: f32 = 0.05;
/// Slack per unit of the centre's largest coordinate (covers the rounding of
/// the centre and of the shape's own transform far from the world origin).
const POSITION_SLACK: f32 = 1.0e-4;
/// Slack per unit of distance from the ray's origin to the centre (covers
/// the exact tests' rounding for far rays, including their nearly tangent
/// roots, whose error grows like the square root of that distance).
const DISTANCE_SLACK: f32 = 1.0e-2;

/// A sphere enclosing a shape with generous slack: a ray it rejects misses
/// the shape in exact arithmetic by far more than any rounding of the
/// shape's exact test, so that test would have reported no hit either.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingSphere {
    /// The centre, in world space.
    center: Vec3,
    /// The square of the enclosing radius plus the slack that does not depend on the ray.
    radius_sq: f32,
}

impl BoundingSphere {
    /// The bound of a shape lying wholly within `radius` of `center`.
    pub fn new(center: Vec3, radius: f32) -> Self {
        let radius =
            radius.abs() * (1.0 + RADIUS_SLACK) + POSITION_SLACK * center.abs().max_element();
        Self {
            center,
            radius_sq: radius * radius,
        }
    }

    /// False only when the ray certainly misses the sphere: its line passes
    /// too far from the centre, or the sphere lies wholly before t_min or
    /// wholly beyond t_max. No division or square root: this runs for every
    /// ray and shape. Degenerate or non-finite rays are never rejected
    /// (every comparison with NaN is false).
    #[inline(always)]
    pub fn may_hit(&self, ray: &Ray) -> bool {
        let d = ray.dir;
        let f = ray.origin - self.center;
        let (dd, ff, fd) = (d.length_squared(), f.length_squared(), f.dot(d));
        let reach_sq = self.radius_sq + DISTANCE_SLACK * DISTANCE_SLACK * ff;
        // ‖f‖² ‖d‖² − (f · d)² is ‖d‖² times the squared distance from the
        // centre to the line; its cancellation error is far below the slack.
        if ff * dd - fd * fd > reach_sq * dd {
            return false;
        }
        // Where the ray starts and ends, relative to the centre: with
        // p(t) = f + t d, ‖p(t)‖² = ff + t (2 fd + t dd) and p(t) · d = fd + t dd
        // (t = ∞ gives ∞ or NaN below, never a rejection).
        let (t0, t1) = (ray.t_min, ray.t_max);
        // Starting outside and moving away: the sphere is wholly behind.
        if ff + t0 * (2.0 * fd + t0 * dd) > reach_sq && fd + t0 * dd > 0.0 {
            return false;
        }
        // Ending outside and still approaching: the sphere is wholly beyond.
        if ff + t1 * (2.0 * fd + t1 * dd) > reach_sq && fd + t1 * dd < 0.0 {
            return false;
        }
        true
    }

    /// [`BoundingSphere::may_hit`] of sixteen rays over (0, t_max) at once,
    /// each lane's answer bit for bit the scalar one for that lane's ray
    /// (the same operations in the same order, no fused multiply–add): a
    /// packet asks the exact scalar test only of the lanes this lets through.
    #[inline(always)]
    pub fn may_hit_lanes<F: FloatLanes>(
        &self,
        origin: Vec3s<F>,
        dir: Vec3s<F>,
        t_max: F,
    ) -> F::Mask {
        let d = dir;
        let f = origin - Vec3s::splat(self.center);
        let (dd, ff, fd) = (d.length_squared(), f.length_squared(), f.dot(d));
        let slack = F::splat(DISTANCE_SLACK * DISTANCE_SLACK);
        let reach_sq = F::splat(self.radius_sq) + slack * ff;
        let far_from_line = (ff * dd - fd * fd).simd_gt(reach_sq * dd);
        let outside_at = |t: F| (ff + t * (F::splat(2.0) * fd + t * dd)).simd_gt(reach_sq);
        let t0 = F::ZERO;
        let behind = outside_at(t0) & (fd + t0 * dd).simd_gt(F::ZERO);
        let beyond = outside_at(t_max) & (fd + t_max * dd).simd_lt(F::ZERO);
        !(far_from_line | behind | beyond)
    }
}

/// Rays for checking that a bound never changes a shape's answer.
#[cfg(test)]
pub(super) mod testing {
    use super::*;
    use crate::integrator::sampler::Sampler;

    /// Calls `check` on 20 000 rays around the bound `b` (its slack
    /// included): from inside it, just outside and up to 10⁴ radii away,
    /// aimed within 1.5 radii of the centre so that many pass the shape's
    /// silhouette closely, a third of them with a finite t_max ending near
    /// the shape. Returns how many `b` rejected.
    pub fn rays_around(b: &BoundingSphere, seed: u64, mut check: impl FnMut(&Ray)) -> usize {
        let radius = b.radius_sq.sqrt();
        let mut rejected = 0;
        for k in 0..20_000u32 {
            let mut s = Sampler::for_sample(seed, k, 0, 0);
            let distance = radius * 10f32.powf(5.0 * s.next_f32() - 1.0);
            let origin = b.center + distance * s.next_direction();
            let target = b.center + 1.5 * radius * s.next_f32().cbrt() * s.next_direction();
            let Some(dir) = (target - origin).try_normalize() else {
                continue;
            };
            let mut ray = Ray::new(origin, dir);
            if k % 3 == 0 {
                ray = ray.with_t_max((target - origin).length() * (0.5 + s.next_f32()));
            }
            rejected += usize::from(!b.may_hit(&ray));
            check(&ray);
        }
        rejected
    }

    /// Checks on [`rays_around`]'s rays around `b` that a shape's test with
    /// the bound first (`bounded`) answers as its test without it
    /// (`exact`), and that the bound turns many clear misses away.
    pub fn assert_only_misses_skipped(
        b: &BoundingSphere,
        seed: u64,
        bounded: impl Fn(&Ray) -> Option<f32>,
        exact: impl Fn(&Ray) -> Option<f32>,
    ) {
        let rejected = rays_around(b, seed, |ray| {
            assert_eq!(bounded(ray), exact(ray), "{ray:?}");
        });
        assert!(
            rejected > 3_000,
            "the bound turns clear misses away ({rejected})"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_through_or_near_the_sphere_may_hit_and_clear_misses_do_not() {
        let bound = BoundingSphere::new(Vec3::ZERO, 1.0);
        let toward = |o: Vec3, target: Vec3| Ray::new(o, (target - o).normalize());
        let eye = Vec3::new(0.0, 0.0, 10.0);
        assert!(bound.may_hit(&toward(eye, Vec3::ZERO)));
        assert!(bound.may_hit(&toward(eye, Vec3::new(1.0, 0.0, 0.0))));
        assert!(!bound.may_hit(&toward(eye, Vec3::new(2.0, 0.0, 0.0))));
        // Pointing away, or stopping short of the sphere.
        assert!(!bound.may_hit(&Ray::new(eye, Vec3::Z)));
        assert!(!bound.may_hit(&toward(eye, Vec3::ZERO).with_t_max(8.0)));
        assert!(bound.may_hit(&toward(eye, Vec3::ZERO).with_t_max(9.5)));
    }

    /// Each lane's [`BoundingSphere::may_hit_lanes`] answer for `rays` (in
    /// packets of sixteen, a short last packet padded with its last ray).
    #[derive(Clone)]
    struct InLanes<'a>(&'a BoundingSphere, &'a [Ray]);

    impl crate::simd::WithLanes for InLanes<'_> {
        type Output = Vec<bool>;
        fn run<F: FloatLanes>(self) -> Vec<bool> {
            use crate::packet::{MaskLanes, Rays, WIDTH};
            let mut answers = Vec::new();
            for chunk in self.1.chunks(WIDTH) {
                let lanes: [Ray; WIDTH] = std::array::from_fn(|k| chunk[k.min(chunk.len() - 1)]);
                let rays = Rays::<F>::from_lanes(&lanes);
                let bits = self
                    .0
                    .may_hit_lanes(rays.origin, rays.dir, rays.t_max)
                    .to_bitmask();
                answers.extend((0..chunk.len()).map(|k| bits & (1 << k) != 0));
            }
            answers
        }
    }

    #[test]
    fn sixteen_lanes_answer_each_rays_scalar_test_bit_for_bit_on_every_lane_type() {
        for (k, (center, radius)) in [
            (Vec3::ZERO, 1.0),
            (Vec3::new(40.0, -3.0, 7.5), 0.3),
            (Vec3::new(-1e3, 2e3, 5e2), 25.0),
        ]
        .into_iter()
        .enumerate()
        {
            let bound = BoundingSphere::new(center, radius);
            let mut rays = Vec::new();
            let rejected = testing::rays_around(&bound, 10 + k as u64, |ray| rays.push(*ray));
            let scalar: Vec<bool> = rays.iter().map(|r| bound.may_hit(r)).collect();
            for lanes in crate::simd::on_every_lane_type(InLanes(&bound, &rays)) {
                assert_eq!(lanes, scalar, "bound {k}");
            }
            // Both answers occur often enough for the comparison to mean something.
            assert!(
                (3_000..17_000).contains(&rejected),
                "{rejected} of {}",
                rays.len()
            );
        }
    }

    #[test]
    fn degenerate_rays_are_never_rejected() {
        let bound = BoundingSphere::new(Vec3::ZERO, 1.0);
        let zero = Ray {
            origin: Vec3::new(0.0, 0.0, 10.0),
            dir: Vec3::ZERO,
            t_min: 0.0,
            t_max: f32::INFINITY,
        };
        assert!(bound.may_hit(&zero));
    }
}
