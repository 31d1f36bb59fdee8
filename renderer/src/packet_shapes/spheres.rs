//! Spheres against sixteen rays: the robust quadratic of [`Sphere::intersect`]
//! (Ray Tracing Gems ch. 7) and [`Sphere::surface`], lane by lane.

use super::{FloatLanes, MaskLanes, Nearest, Rays, Vec3s, WIDTH, gather, gather3};
use crate::shapes::Sphere;
use glam::Vec3;
use std::ops::Range;

/// One sphere's constants.
#[derive(Clone, Copy, Debug)]
struct PackedSphere {
    /// C, the centre.
    center: Vec3,
    /// r, the radius.
    radius: f32,
    /// r², as the scalar code forms it (r · r).
    radius_sq: f32,
    /// The object id.
    object: i32,
}

/// The spheres of a world.
#[derive(Clone, Debug, Default)]
pub(super) struct Spheres {
    /// In the order they were pushed.
    items: Vec<PackedSphere>,
}

/// Sixteen rays prepared for the sphere test: what depends on the rays only.
#[derive(Clone, Copy, Debug)]
pub(super) struct SphereRays<F: FloatLanes> {
    /// P0.
    origin: Vec3s<F>,
    /// v.
    dir: Vec3s<F>,
    /// a = v · v.
    a: F,
}

impl<F: FloatLanes> SphereRays<F> {
    /// `rays` ready for the sphere test.
    #[inline(always)]
    pub(super) fn new(rays: &Rays<F>) -> Self {
        Self {
            origin: rays.origin,
            dir: rays.dir,
            a: rays.dir.dot(rays.dir),
        }
    }
}

impl Spheres {
    /// Adds object `object`, the sphere `s`; returns its index here.
    pub(super) fn push(&mut self, object: i32, s: &Sphere) -> u32 {
        self.items.push(PackedSphere {
            center: s.center,
            radius: s.radius,
            radius_sq: s.radius * s.radius,
            object,
        });
        self.items.len() as u32 - 1
    }

    /// How many there are.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.items.len()
    }

    /// The lanes whose ray hits `s` in (0, limit), and α there (anything
    /// elsewhere). The scalar robust method's operations: f = P0 − C,
    /// b' = −f · v, c = f · f − r², l = f + (b'/a) v, disc = a (r² − l · l);
    /// with q = b' + sign(b')√disc the roots are c/q and q/a (both 0 when
    /// q = 0), used only when both are finite; the near root if it is in
    /// the interval, else the far one.
    #[inline(always)]
    fn hit<F: FloatLanes>(s: &PackedSphere, r: &SphereRays<F>, limit: F) -> (F::Mask, F) {
        let zero = F::ZERO;
        let f = r.origin - Vec3s::splat(s.center);
        let (v, a) = (r.dir, r.a);
        let radius_sq = F::splat(s.radius_sq);
        let b = -f.dot(v);
        let c = f.dot(f) - radius_sq;
        let l = f + v * (b / a);
        let disc = a * (radius_sq - l.dot(l));
        let real = disc.simd_ge(zero);
        // √disc with the sign of b' (f32::copysign: the magnitude's bits
        // with b's sign bit).
        let root = disc.sqrt().abs() | (b & F::splat(-0.0));
        let q = b + root;
        let q_zero = q.simd_eq(zero);
        let r0 = q_zero.select(zero, c / q);
        let r1 = q_zero.select(zero, q / a);
        let ordered = r0.simd_le(r1);
        let near = ordered.select(r0, r1);
        let far = ordered.select(r1, r0);
        let finite = near.is_finite() & far.is_finite();
        let near_inside = near.simd_gt(zero) & near.simd_lt(limit);
        let far_inside = far.simd_gt(zero) & far.simd_lt(limit);
        (
            real & finite & (near_inside | far_inside),
            near_inside.select(near, far),
        )
    }

    /// Takes the hits of the spheres `range` (indices here) that are
    /// nearer than `nearest`'s.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        r: &SphereRays<F>,
        range: Range<usize>,
        nearest: &mut Nearest<F>,
    ) {
        for s in &self.items[range] {
            let (hit, alpha) = Self::hit(s, r, nearest.limit);
            nearest.take(hit, alpha, s.object);
        }
    }

    /// Adds the lanes some sphere of `range` blocks within `t_max` to
    /// `settled`; true as soon as every lane is settled.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        r: &SphereRays<F>,
        range: Range<usize>,
        t_max: F,
        settled: &mut F::Mask,
    ) -> bool {
        for s in &self.items[range] {
            let (hit, _) = Self::hit(s, r, t_max);
            *settled = *settled | hit;
            if settled.all() {
                return true;
            }
        }
        false
    }

    /// Hit point and normal at α of the spheres `index` (per lane), as
    /// [`Sphere::surface`] computes them: the normal (P0 + α v − C) / ‖…‖
    /// (+y when that is not finite), the point C + r n.
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
    ) -> (Vec3s<F>, Vec3s<F>) {
        let center = gather3(index, |k| self.items[k].center);
        let radius: F = gather(index, |k| self.items[k].radius);
        let radial = rays.at(alpha) - center;
        // glam's try_normalize: 1/‖radial‖ must be finite and positive.
        let rcp = F::ONE / radial.length_squared().sqrt();
        let ok = rcp.is_finite() & rcp.simd_gt(F::ZERO);
        let normal = Vec3s::select(ok, radial * rcp, Vec3s::splat(Vec3::Y));
        (center + normal * radius, normal)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::{
        assert_lanes_equal_scalar, check_rays, rays_for, same_everywhere, world_of,
    };
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::Method;
    use crate::simd::{WithLanes, on_every_lane_type};

    /// Each lane's α against one sphere equals `Sphere::intersect`'s with
    /// [`Method::Robust`], and its surface `Sphere::surface`'s, bit for bit,
    /// in lanes `F`.
    fn check_against_one_with<F: FloatLanes>(s: &Sphere, lanes: &[Ray; WIDTH]) -> usize {
        let mut spheres = Spheres::default();
        spheres.push(5, s);
        let rays = Rays::<F>::from_lanes(lanes);
        let (hit, alpha) = Spheres::hit(&spheres.items[0], &SphereRays::new(&rays), rays.t_max);
        let (point, normal) = spheres.surface(&rays, alpha, &[0; WIDTH]);
        assert_lanes_equal_scalar(
            lanes,
            (hit, alpha),
            (point, normal),
            |ray| s.intersect(ray, Method::Robust),
            |ray, alpha| s.surface(ray, alpha),
            s,
        )
    }

    /// [`check_against_one_with`] for every lane type.
    #[derive(Clone)]
    struct AgainstOne<'a>(&'a Sphere, &'a [Ray; WIDTH]);

    impl WithLanes for AgainstOne<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            check_against_one_with::<F>(self.0, self.1)
        }
    }

    /// [`check_against_one_with`] with every lane type; how many lanes hit.
    fn check_against_one(s: &Sphere, lanes: &[Ray; WIDTH]) -> usize {
        same_everywhere(on_every_lane_type(AgainstOne(s, lanes)))
    }

    #[test]
    fn every_lane_equals_the_scalar_robust_quadratic_and_surface() {
        let mut rng = Sampler::for_sample(31, 0, 0, 0);
        let mut hits = 0;
        for case in 0..4000 {
            let scale = [1.0, 1e-3, 1e3, 1e-2][case % 4];
            let center = rng.next_direction() * 4.0 * rng.next_f32() * scale;
            let radius = (0.05 + 2.0 * rng.next_f32()) * scale;
            let s = Sphere::new(center, radius);
            let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
                let origin = match k % 3 {
                    // Inside.
                    0 => center + 0.9 * radius * rng.next_f32() * rng.next_direction(),
                    // On the surface (a secondary ray's origin, α ≈ 0 roots).
                    1 => center + radius * rng.next_direction(),
                    _ => center + radius * (1.0 + 1e4 * rng.next_f32()) * rng.next_direction(),
                };
                let dir = match (k + case) % 3 {
                    // Grazing: aimed at the silhouette.
                    0 => (center + radius * rng.next_direction() - origin).normalize_or(Vec3::Z),
                    1 => rng.next_direction() * (0.5 + rng.next_f32()),
                    _ => (center - origin).normalize_or(Vec3::Z),
                };
                let ray = Ray::new(origin, dir);
                match (k + case) % 7 {
                    0 => ray.with_t_max(3.0 * radius * rng.next_f32()),
                    1 if k == 6 => ray.with_t_max(0.0),
                    _ => ray,
                }
            });
            hits += check_against_one(&s, &lanes);
        }
        assert!(hits > 10_000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn tangent_centre_and_degenerate_rays_equal_the_scalar_test() {
        let unit = Sphere::new(Vec3::ZERO, 1.0);
        let cases = [
            // Tangent: a double root.
            Ray::new(Vec3::new(1.0, 0.0, 5.0), -Vec3::Z),
            // From the centre: roots ∓1.
            Ray::new(Vec3::ZERO, Vec3::Y),
            // From inside with t_max before the exit.
            Ray::new(Vec3::new(0.0, 0.0, 0.5), -Vec3::Z).with_t_max(1.0),
            // Pointing away, and beside.
            Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z),
            Ray::new(Vec3::new(1.5, 0.0, 5.0), -Vec3::Z),
            // Unnormalised.
            Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -2.0)),
            // t_max exactly at the hit, and just past it.
            Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(4.0),
            Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(4.0000005),
        ];
        // The cases repeated over the packet's lanes.
        let lanes: [Ray; WIDTH] = std::array::from_fn(|k| cases[k % cases.len()]);
        assert_eq!(check_against_one(&unit, &lanes), 4 * WIDTH / cases.len());
        // A small sphere far away.
        let far = Sphere::new(Vec3::new(0.0, 0.0, -1.0e4), 1.0);
        let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
            let target = far.center + Vec3::new(0.065 * k as f32, 0.0, 0.0);
            Ray::new(Vec3::ZERO, target.normalize())
        });
        assert_eq!(check_against_one(&far, &lanes), WIDTH);
    }

    #[test]
    fn a_world_of_many_spheres_gives_the_scalar_worlds_hits_bit_for_bit() {
        // Twelve spheres: the scalar world groups them in its own BVH.
        let mut rng = Sampler::for_sample(32, 0, 0, 0);
        let list: String = (0..12)
            .map(|k| {
                let c = rng.next_direction() * 2.0 * rng.next_f32();
                let r = if k == 0 {
                    0.5
                } else {
                    0.1 + 0.4 * rng.next_f32()
                };
                format!(r#"<sphere center="{} {} {}" radius="{r}"/>"#, c.x, c.y, c.z)
            })
            .collect();
        // Two spheres touching, and one inside another.
        let world = world_of(&format!(
            r#"<scene>{list}<sphere center="3 0 0" radius="0.5"/><sphere center="4 0 0" radius="0.5"/><sphere center="3 0 0" radius="0.2"/></scene>"#
        ));
        let rays = rays_for(&world, 33, 4000);
        let found = check_rays(&world, &rays);
        assert!(found > 2000, "too few hits to mean anything: {found}");
    }
}
