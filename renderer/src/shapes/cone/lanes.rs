//! The cone's exact test for sixteen rays at once: each lane's α is
//! [`Cone::intersect_exact`]'s for that lane's ray, bit for bit — the same
//! float operations in the same order (glam's matrix product and dot
//! product summed x, then y, then z; no fused multiply–add), every branch
//! of the scalar code taken as a blend of both sides.
//!
//! A packet asks it of the lanes the cone's bounding sphere lets through,
//! where it asked the scalar test lane by lane: the glass cone of
//! `seed.xml` was 13–15% of a pass that way.

use super::Cone;
use crate::packet::{FloatLanes, MaskLanes, Vec3s};
use glam::{Mat3, Vec3};

impl Cone {
    /// α of each lane's nearest hit on the cone with 0 < α < `t_max`, +∞
    /// where there is none: [`Cone::intersect_exact`] of each lane's ray
    /// (origin, direction, t_min 0, that lane's `t_max`), bit for bit.
    #[inline(always)]
    pub(crate) fn intersect_exact_lanes<F: FloatLanes>(
        &self,
        origin: Vec3s<F>,
        dir: Vec3s<F>,
        t_max: F,
    ) -> F {
        let rotation = self.placement.world_from_object;
        let o = to_object(rotation, origin - Vec3s::splat(self.placement.origin));
        let d = to_object(rotation, dir);
        let (r2, h) = (self.radius * self.radius, self.height);
        // shift_near: the origin moved to its closest approach to the
        // mid-axis point.
        let centre = Vec3s::splat(Vec3::new(0.0, 0.5 * h, 0.0));
        let dd = d.length_squared();
        let shift = (dd.simd_gt(F::ZERO)).select((centre - o).dot(d) / dd, F::ZERO);
        let shift = shift.is_finite().select(shift, F::ZERO);
        let o = o + d * shift;
        let h2 = h * h;
        let (h2s, r2s, hs) = (F::splat(h2), F::splat(r2), F::splat(h));
        let w0 = hs - o.y;
        let a = h2s * (d.x * d.x + d.z * d.z) - r2s * d.y * d.y;
        let b = F::splat(2.0) * (h2s * (o.x * d.x + o.z * d.z) + r2s * w0 * d.y);
        let c = h2s * (o.x * o.x + o.z * o.z) - r2s * w0 * w0;
        let (roots, t0, t1) = solve_quadratic_lanes(a, b, c);
        let mut best = F::splat(f32::INFINITY);
        for t in [t0, t1] {
            let y = o.y + t * d.y;
            let alpha = shift + t;
            let take = roots
                & inside(alpha, t_max)
                & alpha.simd_lt(best)
                & F::ZERO.simd_le(y)
                & y.simd_le(hs);
            best = take.select(alpha, best);
        }
        // The base disk.
        let t = -o.y / d.y;
        let alpha = shift + t;
        let (x, z) = (o.x + t * d.x, o.z + t * d.z);
        let take = d.y.simd_ne(F::ZERO)
            & inside(alpha, t_max)
            & alpha.simd_lt(best)
            & (x * x + z * z).simd_le(r2s);
        take.select(alpha, best)
    }
}

/// The lanes whose α lies in (0, t_max), as `Ray::contains` has it.
#[inline(always)]
fn inside<F: FloatLanes>(alpha: F, t_max: F) -> F::Mask {
    alpha.simd_gt(F::ZERO) & alpha.simd_lt(t_max)
}

/// `v` in object space: glam's `Mat3::transpose(rotation) * v`, component
/// by component (x column, then y, then z).
#[inline(always)]
fn to_object<F: FloatLanes>(rotation: Mat3, v: Vec3s<F>) -> Vec3s<F> {
    let m = rotation.transpose();
    scaled(m.x_axis, v.x) + scaled(m.y_axis, v.y) + scaled(m.z_axis, v.z)
}

/// The vector `axis` times each lane's `s`.
#[inline(always)]
fn scaled<F: FloatLanes>(axis: Vec3, s: F) -> Vec3s<F> {
    Vec3s::new(
        F::splat(axis.x) * s,
        F::splat(axis.y) * s,
        F::splat(axis.z) * s,
    )
}

/// [`solve_quadratic`](super::super::quadratic::solve_quadratic) lane by
/// lane: the lanes with real roots, and each lane's two roots in
/// increasing order (anything where there are none).
#[inline(always)]
fn solve_quadratic_lanes<F: FloatLanes>(a: F, b: F, c: F) -> (F::Mask, F, F) {
    // a = 0: the linear root −c/b, unless b = 0 too.
    let linear = a.simd_eq(F::ZERO);
    let root = -c / b;
    let disc = b * b - F::splat(4.0) * a * c;
    let real = !disc.simd_lt(F::ZERO) & disc.is_finite();
    let sqrt = disc.sqrt();
    let q = F::splat(-0.5) * (b + b.is_sign_negative().select(-sqrt, sqrt));
    let double_zero = q.simd_eq(F::ZERO);
    let r0 = double_zero.select(F::ZERO, q / a);
    let r1 = double_zero.select(F::ZERO, c / q);
    let ordered = r0.simd_le(r1);
    let (low, high) = (ordered.select(r0, r1), ordered.select(r1, r0));
    (
        linear.select_mask(b.simd_ne(F::ZERO), real),
        linear.select(root, low),
        linear.select(root, high),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::packet::{Rays, WIDTH, WithLanes};
    use crate::shapes::bound::testing::rays_around;
    use crate::simd::on_every_lane_type;

    /// Runs every cone's lane test on its rays sixteen at a time and
    /// returns each lane's α bits.
    #[derive(Clone)]
    struct LaneAlphas<'a> {
        cone: &'a Cone,
        rays: &'a [Ray],
    }

    impl WithLanes for LaneAlphas<'_> {
        type Output = Vec<u32>;
        fn run<F: FloatLanes>(self) -> Vec<u32> {
            let mut out = Vec::with_capacity(self.rays.len());
            for chunk in self.rays.chunks(WIDTH) {
                let mut lanes = [Ray::NOTHING; WIDTH];
                lanes[..chunk.len()].copy_from_slice(chunk);
                let rays = Rays::<F>::from_lanes(&lanes);
                let alpha = self
                    .cone
                    .intersect_exact_lanes(rays.origin, rays.dir, rays.t_max);
                out.extend(alpha.to_array()[..chunk.len()].iter().map(|a| a.to_bits()));
            }
            out
        }
    }

    /// Cones upright, tilted, flat, needle-thin and degenerate.
    fn cones() -> Vec<Cone> {
        vec![
            Cone::new(Vec3::ZERO, 1.0, 2.0, Vec3::ZERO),
            Cone::new(
                Vec3::new(-1.5, 0.0, 0.3),
                0.6,
                1.6,
                Vec3::new(20.0, 35.0, -10.0),
            ),
            Cone::new(
                Vec3::new(3.0, -2.0, 1.0),
                2.0,
                0.3,
                Vec3::new(90.0, 0.0, 45.0),
            ),
            Cone::new(
                Vec3::new(0.0, 5.0, -4.0),
                0.01,
                3.0,
                Vec3::new(0.0, 0.0, 180.0),
            ),
            Cone::new(Vec3::new(1.0, 1.0, 1.0), 0.0, 1.0, Vec3::ZERO),
            Cone::new(
                Vec3::new(2.0e3, 0.0, -1.0e3),
                50.0,
                80.0,
                Vec3::new(5.0, 0.0, 0.0),
            ),
        ]
    }

    /// Rays around the cone's bound (near its silhouette, from inside it,
    /// from far off, some stopping short), along its generators (the
    /// quadratic's a = 0), level with its base (d_y = 0 in object space) and
    /// through its apex.
    fn rays_for(cone: &Cone, seed: u64) -> Vec<Ray> {
        let mut rays = Vec::new();
        rays_around(cone.bound(), seed, |ray| rays.push(*ray));
        let p = cone.placement;
        let apex = p.point_to_world(Vec3::new(0.0, cone.height, 0.0));
        let rim = p.point_to_world(Vec3::new(cone.radius, 0.0, 0.0));
        let generator = (rim - apex).normalize_or_zero();
        let level = p.vector_to_world(Vec3::X);
        for k in 0..64 {
            let s = k as f32 / 64.0;
            let below = p.point_to_world(Vec3::new(-3.0 * cone.radius, s * cone.height, 0.1));
            rays.push(Ray::new(apex - generator * (1.0 + s), generator));
            rays.push(Ray::new(below, level));
            rays.push(Ray::new(below, (apex - below).normalize_or_zero()));
            rays.push(Ray::new(
                apex + Vec3::splat(s),
                -Vec3::splat(1.0).normalize(),
            ));
        }
        rays
    }

    #[test]
    fn sixteen_rays_at_once_get_the_scalar_tests_alpha_bit_for_bit() {
        for (index, cone) in cones().iter().enumerate() {
            let rays = rays_for(cone, 40 + index as u64);
            let expected: Vec<u32> = rays
                .iter()
                .map(|ray| cone.intersect_exact(ray).unwrap_or(f32::INFINITY).to_bits())
                .collect();
            let hits = expected
                .iter()
                .filter(|&&a| a != f32::INFINITY.to_bits())
                .count();
            assert!(hits > 100, "cone {index}: {hits} hits of {}", rays.len());
            for alphas in on_every_lane_type(LaneAlphas { cone, rays: &rays }) {
                for (k, (got, want)) in alphas.iter().zip(&expected).enumerate() {
                    assert_eq!(
                        got,
                        want,
                        "cone {index}, ray {k} {:?}: {} vs {}",
                        rays[k],
                        f32::from_bits(*got),
                        f32::from_bits(*want)
                    );
                }
            }
        }
    }
}
