//! Spheres in packs of four, stored coordinate by coordinate, so that one
//! ray is tested against four spheres at once with the robust quadratic of
//! [`Sphere::intersect`] (Ray Tracing Gems ch. 7) — the same operations in
//! the same order in each lane, so the same α bit for bit.

use crate::geometry::ray::Ray;
use crate::shapes::Sphere;
use wide::f32x4;

/// Spheres per pack.
pub const SPHERES_PER_PACK: usize = 4;

/// Up to four spheres. A pack of fewer repeats its last sphere in the spare
/// lanes (same α, same id: harmless).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct SpherePack {
    /// C, the centres, coordinate by coordinate.
    center: [f32x4; 3],
    /// r², as [`Sphere::intersect`] forms it (r · r).
    radius_sq: f32x4,
    /// The caller's id of each sphere.
    ids: [u32; SPHERES_PER_PACK],
}

/// A ray prepared for [`SpherePack::nearest`]: P0, v and a = v · v, each
/// broadcast to the four lanes.
#[derive(Clone, Copy, Debug)]
pub struct SphereRay {
    origin: [f32x4; 3],
    dir: [f32x4; 3],
    /// a = v · v.
    a: f32x4,
}

impl SphereRay {
    /// `ray` ready for the packed test.
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        let (o, v) = (ray.origin, ray.dir);
        Self {
            origin: [o.x, o.y, o.z].map(f32x4::splat),
            dir: [v.x, v.y, v.z].map(f32x4::splat),
            a: f32x4::splat(v.dot(v)),
        }
    }
}

/// x · y of two vectors given coordinate by coordinate, summed left to
/// right as glam's `Vec3::dot` sums them.
#[inline(always)]
fn dot(x: [f32x4; 3], y: [f32x4; 3]) -> f32x4 {
    x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
}

impl SpherePack {
    /// The pack of `spheres` (1 to 4 of them): (caller's id, sphere).
    pub fn new(spheres: &[(u32, Sphere)]) -> SpherePack {
        assert!((1..=SPHERES_PER_PACK).contains(&spheres.len()));
        let lane = |i: usize| spheres[i.min(spheres.len() - 1)];
        let coordinate = |k: usize| f32x4::new(std::array::from_fn(|i| lane(i).1.center[k]));
        SpherePack {
            center: [0, 1, 2].map(coordinate),
            radius_sq: f32x4::new(std::array::from_fn(|i| {
                let r = lane(i).1.radius;
                r * r
            })),
            ids: std::array::from_fn(|i| lane(i).0),
        }
    }

    /// The caller's id of the sphere in `lane`.
    #[inline(always)]
    pub fn id(&self, lane: usize) -> u32 {
        self.ids[lane]
    }

    /// The nearest hit in (t_min, t_max) among the pack's spheres: (lane,
    /// α), the lowest lane on a tie, α exactly what [`Sphere::intersect`]
    /// gives with `Method::Robust`.
    #[inline(always)]
    pub fn nearest(&self, ray: &SphereRay, t_min: f32, t_max: f32) -> Option<(usize, f32)> {
        let alpha = self.alphas(ray, t_min, t_max).to_array();
        // α is never NaN (a lane without a hit holds +∞), so the plain
        // comparison is the minimum.
        let min = |x: f32, y: f32| if x < y { x } else { y };
        let nearest = min(min(alpha[0], alpha[1]), min(alpha[2], alpha[3]));
        if nearest == f32::INFINITY {
            return None;
        }
        let lane = alpha.iter().position(|&a| a == nearest)?;
        Some((lane, nearest))
    }

    /// True when some sphere of the pack is hit in (t_min, t_max).
    #[inline(always)]
    pub fn any(&self, ray: &SphereRay, t_min: f32, t_max: f32) -> bool {
        self.alphas(ray, t_min, t_max)
            .simd_lt(f32x4::INFINITY)
            .any()
    }

    /// Each lane's α of [`Sphere::intersect`] (robust), +∞ where it misses.
    /// Lane by lane the scalar code's operations: f = P0 − C, b' = −f · v,
    /// c = f · f − r², l = f + (b'/a) v, disc = a (r² − l · l); with
    /// q = b' + sign(b')√disc the roots are c/q and q/a (both 0 when q = 0),
    /// used only when both are finite; the near root if it is inside the
    /// interval, else the far one.
    #[inline(always)]
    fn alphas(&self, ray: &SphereRay, t_min: f32, t_max: f32) -> f32x4 {
        let f: [f32x4; 3] = std::array::from_fn(|k| ray.origin[k] - self.center[k]);
        let v = ray.dir;
        let a = ray.a;
        let b = -dot(f, v);
        let c = dot(f, f) - self.radius_sq;
        let ratio = b / a;
        let l: [f32x4; 3] = std::array::from_fn(|k| f[k] + ratio * v[k]);
        let disc = a * (self.radius_sq - dot(l, l));
        let real = disc.simd_ge(f32x4::ZERO);
        // √disc with the sign of b' (f32::copysign: the magnitude's bits
        // with b's sign bit).
        let sign = f32x4::splat(-0.0);
        let root = disc.sqrt().abs() | (b & sign);
        let q = b + root;
        let q_zero = q.simd_eq(f32x4::ZERO);
        let r0 = q_zero.select(f32x4::ZERO, c / q);
        let r1 = q_zero.select(f32x4::ZERO, q / a);
        let ordered = r0.simd_le(r1);
        let near = ordered.select(r0, r1);
        let far = ordered.select(r1, r0);
        let finite = near.is_finite() & far.is_finite();
        let (lo, hi) = (f32x4::splat(t_min), f32x4::splat(t_max));
        let inside = |x: f32x4| x.simd_gt(lo) & x.simd_lt(hi);
        let alpha = inside(near).select(near, inside(far).select(far, f32x4::INFINITY));
        (real & finite).select(alpha, f32x4::INFINITY)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::Method;
    use glam::Vec3;

    /// Random spheres and rays (some starting inside, some with a short
    /// interval, some huge or tiny spheres far away, some grazing): every
    /// lane's α equals the scalar robust test's bit for bit, and the pack's
    /// nearest is the smallest of them at its lowest lane.
    #[test]
    fn every_lane_matches_the_scalar_robust_test_bit_for_bit() {
        let mut rng = Sampler::for_sample(3, 0, 0, 0);
        let mut hits = 0;
        for k in 0..20_000 {
            let scale = [1.0, 1e-3, 1e3][k % 3];
            let spheres: Vec<(u32, Sphere)> = (0..1 + k % 4)
                .map(|i| {
                    let center = (rng.next_direction() * 4.0 * rng.next_f32()) * scale;
                    let radius = (0.05 + 2.0 * rng.next_f32()) * scale;
                    (10 + i as u32, Sphere::new(center, radius))
                })
                .collect();
            let pack = SpherePack::new(&spheres);
            let origin = rng.next_direction() * 6.0 * rng.next_f32() * scale;
            // Aim near a sphere's edge now and then (grazing rays).
            let target = spheres[0].1.center + rng.next_direction() * spheres[0].1.radius;
            let dir = if k % 5 == 0 {
                target - origin
            } else {
                rng.next_direction() * (0.5 + rng.next_f32())
            };
            let mut ray = Ray::new(origin, dir);
            if k % 7 == 0 {
                ray.t_max = 3.0 * scale * rng.next_f32();
            }
            if k % 11 == 0 {
                ray.t_min = scale * rng.next_f32();
            }
            let prepared = SphereRay::new(&ray);
            let want = spheres
                .iter()
                .enumerate()
                .filter_map(|(lane, (_, s))| Some((lane, s.intersect(&ray, Method::Robust)?)))
                .fold(
                    None,
                    |best: Option<(usize, f32)>, (lane, alpha)| match best {
                        Some((_, b)) if b <= alpha => best,
                        _ => Some((lane, alpha)),
                    },
                );
            let got = pack.nearest(&prepared, ray.t_min, ray.t_max);
            assert_eq!(
                got.map(|(lane, a)| (pack.id(lane), a.to_bits())),
                want.map(|(lane, a)| (spheres[lane].0, a.to_bits())),
                "case {k}: {ray:?} {spheres:?}"
            );
            assert_eq!(pack.any(&prepared, ray.t_min, ray.t_max), want.is_some());
            hits += usize::from(want.is_some());
        }
        assert!(hits > 5000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn a_ray_from_inside_hits_the_far_side_and_spare_lanes_repeat_the_last_sphere() {
        let pack = SpherePack::new(&[(4, Sphere::new(Vec3::ZERO, 2.0))]);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        let got = pack.nearest(&SphereRay::new(&ray), ray.t_min, ray.t_max);
        assert_eq!(got, Some((0, 2.0)));
        assert!((0..SPHERES_PER_PACK).all(|lane| pack.id(lane) == 4));
        // Nothing inside the interval: no hit.
        assert_eq!(pack.nearest(&SphereRay::new(&ray), 0.0, 2.0), None);
    }
}
