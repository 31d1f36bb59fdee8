//! The torus (√(x² + z²) − R)² + y² = r² in object space: a quartic in α,
//! formed in f64 from an origin first moved onto the bounding sphere.

use super::bound::BoundingSphere;
use super::placement::Placement;
use super::{AreaSample, Surface};
use crate::geometry::ray::Ray;
use glam::{DVec3, Vec2, Vec3};

/// A torus around its centre in the local xz-plane: major radius R (centre
/// to tube centre), minor radius r (the tube's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    /// Object space: the centre at the origin, the axis of symmetry along +y.
    placement: Placement,
    /// R, the major radius.
    major: f32,
    /// r, the minor radius.
    minor: f32,
    /// A loose world-space sphere around it, tested before anything else.
    bound: BoundingSphere,
}

/// f(p) = (‖p‖² + R² − r²)² − 4R²(x² + z²), zero on the torus, and its gradient.
fn implicit(p: DVec3, major: f64, minor: f64) -> (f64, DVec3) {
    let s = p.length_squared() + major * major - minor * minor;
    let k = 4.0 * major * major;
    let f = s * s - k * (p.x * p.x + p.z * p.z);
    let grad = 4.0 * s * p - 2.0 * k * DVec3::new(p.x, 0.0, p.z);
    (f, grad)
}

impl Torus {
    /// A torus centred at `center` with major radius `major` and minor radius
    /// `minor`, lying in the local xz-plane rotated by `rotate_deg` degrees
    /// (x, then y, then z) about the centre.
    pub fn new(center: Vec3, major: f32, minor: f32, rotate_deg: Vec3) -> Self {
        debug_assert!(major >= 0.0 && minor >= 0.0, "R {major} r {minor}");
        let (major, minor) = (major.abs(), minor.abs());
        Self {
            placement: Placement::from_euler_degrees(center, rotate_deg),
            major,
            minor,
            bound: BoundingSphere::new(center, major + minor),
        }
    }

    /// The loose world-space sphere [`Torus::intersect`] tests first: a ray
    /// it turns away misses the torus.
    pub(crate) fn bound(&self) -> &BoundingSphere {
        &self.bound
    }

    /// α of the nearest hit with t_min < α < t_max, or `None`.
    ///
    /// A loose world-space bounding sphere first turns clear misses away,
    /// before the object-space transform. The ray is then clipped to the bounding sphere of radius R + r (a miss
    /// there is a miss); its origin is moved to the sphere's entry point
    /// P0 + α_s v (α_s = max(entry, 0)), so that the quartic's coefficients
    /// are formed, in f64, from an origin within R + r of the centre. The
    /// roots from `roots::find_roots_quartic` are polished by two Newton steps
    /// on f(P0 + α v) and shifted back by α_s.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        if !self.bound.may_hit(ray) {
            return None;
        }
        self.intersect_exact(ray)
    }

    /// [`Torus::intersect`] without the loose bounding-sphere test.
    fn intersect_exact(&self, ray: &Ray) -> Option<f32> {
        let local = self.placement.ray_to_object(ray);
        let (o, d) = (local.origin.as_dvec3(), local.dir.as_dvec3());
        let (big, small) = (f64::from(self.major), f64::from(self.minor));
        let dd = d.length_squared();
        if !(dd > 0.0) {
            return None;
        }
        // Bounding sphere, from the point of closest approach (no cancellation).
        let t_closest = -o.dot(d) / dd;
        let closest = o + t_closest * d;
        let bound = big + small;
        let h2 = bound * bound - closest.length_squared();
        if h2 < 0.0 {
            return None;
        }
        let half = (h2 / dd).sqrt();
        let (t_in, t_out) = (t_closest - half, t_closest + half);
        if t_out <= f64::from(ray.t_min) || t_in >= f64::from(ray.t_max) {
            return None;
        }
        let shift = t_in.max(0.0);
        let o = o + shift * d;

        // Quartic in t (α = shift + t): with s(t) = dd t² + 2 od t + K.
        let od = o.dot(d);
        let k = o.length_squared() + big * big - small * small;
        let four_r2 = 4.0 * big * big;
        let dxz = d.x * d.x + d.z * d.z;
        let odxz = o.x * d.x + o.z * d.z;
        let oxz = o.x * o.x + o.z * o.z;
        let a4 = dd * dd;
        let a3 = 4.0 * dd * od;
        let a2 = 4.0 * od * od + 2.0 * dd * k - four_r2 * dxz;
        let a1 = 4.0 * od * k - 2.0 * four_r2 * odxz;
        let a0 = k * k - four_r2 * oxz;
        let roots = roots::find_roots_quartic(a4, a3, a2, a1, a0);

        let max_step = 0.25 * small / dd.sqrt();
        let mut best = f32::INFINITY;
        for &root in roots.as_ref() {
            let mut t = root;
            for _ in 0..2 {
                let (f, grad) = implicit(o + t * d, big, small);
                let step = f / grad.dot(d);
                if step.is_finite() && step.abs() <= max_step {
                    t -= step;
                }
            }
            let alpha = (shift + t) as f32;
            if local.contains(alpha) && alpha < best {
                best = alpha;
            }
        }
        debug_assert!(!best.is_nan());
        best.is_finite().then_some(best)
    }

    /// The hit point projected onto the torus (the closest point: from the
    /// nearest point c of the tube's centre circle, r along p − c), and the
    /// outward normal (p − c)/‖p − c‖, which on the surface is the unit
    /// gradient of the implicit function.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let p = self.placement.ray_to_object(ray).at(alpha);
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let radial = if rho > 0.0 {
            Vec3::new(p.x / rho, 0.0, p.z / rho)
        } else {
            Vec3::X
        };
        let c = self.major * radial;
        let normal = (p - c).try_normalize().unwrap_or(Vec3::Y);
        self.placement
            .surface_to_world(c + self.minor * normal, normal)
    }
}

impl Torus {
    /// The surface area 4π² R r.
    pub fn area(&self) -> f32 {
        4.0 * std::f32::consts::PI * std::f32::consts::PI * self.major * self.minor
    }

    /// A point drawn with the angles around the axis (φ) and around the tube
    /// (ψ) uniform: area density 1 / (4π² r (R + r cos ψ)), not uniform.
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        let (big, small) = (self.major, self.minor);
        if !(self.area() > 0.0) {
            return None;
        }
        let tau = 2.0 * std::f32::consts::PI;
        let (phi, psi) = (tau * u.x, tau * u.y);
        let radial = Vec3::new(phi.cos(), 0.0, phi.sin());
        let n = psi.cos() * radial + psi.sin() * Vec3::Y;
        let p = big * radial + small * n;
        let s = self.placement.surface_to_world(p, n);
        Some(AreaSample {
            point: s.point,
            normal: s.normal,
            pdf_area: self.pdf_area(s.point),
        })
    }

    /// The area density of [`Torus::sample_area`] at a point on the torus.
    pub fn pdf_area(&self, point: Vec3) -> f32 {
        let p = self.placement.point_to_object(point);
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        // R + r cos ψ is the distance from the axis.
        let tau = 2.0 * std::f32::consts::PI;
        let d = tau * tau * self.minor * rho.max(self.major - self.minor).max(f32::MIN_POSITIVE);
        1.0 / d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use proptest::prelude::*;

    #[test]
    fn the_bounding_sphere_only_skips_rays_that_miss() {
        for (k, (major, minor, rotate)) in [
            (1.0, 0.25, Vec3::ZERO),
            (0.5, 0.5, Vec3::new(30.0, 40.0, 50.0)),
            (2.0, 0.05, Vec3::new(90.0, 0.0, 10.0)),
        ]
        .into_iter()
        .enumerate()
        {
            let t = Torus::new(Vec3::new(1.0, 2.0, -3.0), major, minor, rotate);
            super::super::bound::testing::assert_only_misses_skipped(
                &t.bound,
                k as u64,
                |ray| t.intersect(ray),
                |ray| t.intersect_exact(ray),
            );
        }
    }

    fn ring() -> Torus {
        Torus::new(Vec3::ZERO, 2.0, 0.5, Vec3::ZERO)
    }

    fn hit(o: Vec3, d: Vec3) -> Option<f32> {
        ring().intersect(&Ray::new(o, d))
    }

    /// Distance from `p` (object space) to the torus surface.
    fn distance(t: &Torus, p: Vec3) -> f32 {
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        ((rho - t.major).hypot(p.y) - t.minor).abs()
    }

    #[test]
    fn hits_from_outside_are_exact() {
        let ray = Ray::new(Vec3::new(5.0, 0.0, 0.0), -Vec3::X);
        assert_eq!(ring().intersect(&ray), Some(2.5));
        let s = ring().surface(&ray, 2.5);
        assert_eq!((s.point, s.normal), (Vec3::new(2.5, 0.0, 0.0), Vec3::X));
        let ray = Ray::new(Vec3::new(0.0, 5.0, -2.0), -Vec3::Y);
        assert_eq!(ring().intersect(&ray), Some(4.5));
        assert_eq!(ring().surface(&ray, 4.5).normal, Vec3::Y);
    }

    #[test]
    fn rays_along_the_axis_through_the_hole_miss() {
        assert_eq!(hit(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y), None);
        assert_eq!(hit(Vec3::new(0.5, -100.0, 1.0), Vec3::Y), None);
    }

    #[test]
    fn rays_beside_or_behind_miss() {
        assert_eq!(hit(Vec3::new(5.0, 0.6, 0.0), -Vec3::X), None);
        assert_eq!(hit(Vec3::new(5.0, 0.0, 0.0), Vec3::X), None);
        assert_eq!(hit(Vec3::new(0.0, 5.0, 2.6), -Vec3::Y), None);
    }

    #[test]
    fn tangent_ray_gives_no_nan() {
        // Touches the top circle of the tube at x = ±2.
        if let Some(a) = hit(Vec3::new(5.0, 0.5, 0.0), -Vec3::X) {
            assert!((a - 3.0).abs() < 1e-2, "{a}");
        }
    }

    #[test]
    fn origin_inside_the_tube_or_hole_hits_the_exit() {
        assert_eq!(hit(Vec3::new(2.0, 0.0, 0.0), Vec3::X), Some(0.5));
        assert_eq!(hit(Vec3::new(2.0, 0.0, 0.0), Vec3::Y), Some(0.5));
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(ring().intersect(&ray), Some(1.5));
        assert_eq!(ring().surface(&ray, 1.5).normal, -Vec3::X);
    }

    #[test]
    fn interval_selects_among_the_four_roots() {
        // Roots at 2.5, 3.5, 6.5, 7.5.
        let mut ray = Ray::new(Vec3::new(5.0, 0.0, 0.0), -Vec3::X);
        ray.t_min = 3.0;
        assert_eq!(ring().intersect(&ray), Some(3.5));
        ray.t_min = 4.0;
        assert_eq!(ring().intersect(&ray), Some(6.5));
        assert_eq!(ring().intersect(&ray.with_t_max(2.4)), None);
        let inside = Ray::new(Vec3::new(2.0, 0.0, 0.0), Vec3::X).with_t_max(0.4);
        assert_eq!(ring().intersect(&inside), None);
    }

    #[test]
    fn rotated_torus_lies_in_the_rotated_plane() {
        // 90° about x turns the local y axis into world z: the ring is in xy.
        let t = Torus::new(
            Vec3::new(1.0, 0.0, 0.0),
            2.0,
            0.5,
            Vec3::new(90.0, 0.0, 0.0),
        );
        assert_eq!(
            t.intersect(&Ray::new(Vec3::new(1.0, 0.0, 5.0), -Vec3::Z)),
            None
        );
        let ray = Ray::new(Vec3::new(1.0, 5.0, 0.0), -Vec3::Y);
        let a = t.intersect(&ray).expect("outer equator");
        assert!((a - 2.5).abs() < 1e-5, "{a}");
        assert!((t.surface(&ray, a).normal - Vec3::Y).length() < 1e-5);
    }

    /// Fraction of rays from `dist` away, aimed at random points of the outer
    /// half (whose tangent planes support the torus, so the aimed-at point is
    /// the first hit), that hit with relative α error ≤ 1e-4.
    fn far_hit_rate(dist: f32) -> f64 {
        let t = Torus::new(
            Vec3::new(0.3, -0.2, 0.1),
            1.0,
            0.25,
            Vec3::new(30.0, 10.0, 50.0),
        );
        let mut rng = Sampler::for_sample(7, 0, 0, 0);
        let (n, mut good) = (4000, 0);
        for _ in 0..n {
            let theta = std::f32::consts::PI * (rng.next_f32() - 0.5);
            let phi = std::f32::consts::TAU * rng.next_f32();
            let radial = Vec3::new(phi.cos(), 0.0, phi.sin());
            let n_local = theta.cos() * radial + Vec3::new(0.0, theta.sin(), 0.0);
            let p = t
                .placement
                .point_to_world(t.major * radial + t.minor * n_local);
            let normal = t.placement.vector_to_world(n_local);
            let u = loop {
                let u = rng.next_direction();
                if u.dot(normal) > 0.1 {
                    break u;
                }
            };
            let origin = p + dist * u;
            let ray = Ray::new(origin, (p - origin).normalize());
            let expected = (p - origin).length();
            if let Some(a) = t.intersect(&ray) {
                good += usize::from((a - expected).abs() <= 1e-4 * expected);
            }
        }
        good as f64 / n as f64
    }

    #[test]
    fn far_rays_at_distance_100_hit_the_aimed_at_point() {
        let rate = far_hit_rate(100.0);
        assert!(rate >= 0.995, "{rate}");
    }

    #[test]
    fn far_rays_at_distance_1e4_hit_the_aimed_at_point() {
        let rate = far_hit_rate(1.0e4);
        assert!(rate >= 0.995, "{rate}");
    }

    #[test]
    fn far_rays_through_the_hole_with_nothing_in_the_way_never_hit() {
        let t = ring();
        let mut rng = Sampler::for_sample(11, 0, 0, 0);
        let mut tested = 0;
        for k in 0..2000 {
            let dist = if k % 2 == 0 { 100.0 } else { 1.0e4 };
            let phi = std::f32::consts::TAU * rng.next_f32();
            let hole = 1.4 * rng.next_f32() * Vec3::new(phi.cos(), 0.0, phi.sin());
            let mut d = rng.next_direction();
            d.y = d.y.signum() * d.y.abs().max(0.8);
            let d = d.normalize();
            // The distance to the tube is 1-Lipschitz along the ray: sampling
            // every 1e-3 with a margin of 1e-2 proves the ray stays clear.
            let clear = (-3000..=3000)
                .map(|i| distance(&t, hole + (i as f32 * 1e-3) * d))
                .all(|e| e > 1e-2);
            if !clear {
                continue;
            }
            tested += 1;
            let ray = Ray::new(hole - dist * d, d);
            assert_eq!(t.intersect(&ray), None, "{ray:?}");
        }
        assert!(tested > 1000, "{tested}");
    }

    fn any_vec(r: f32) -> impl Strategy<Value = Vec3> {
        (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn hits_lie_on_the_surface_with_outward_unit_normals(
            center in any_vec(5.0),
            major in 0.5f32..3.0,
            ratio in 0.05f32..0.9,
            rotate in any_vec(180.0),
            from in any_vec(1.0),
            target in any_vec(1.0),
            distance_to in 1.0f32..60.0,
        ) {
            let t = Torus::new(center, major, ratio * major, rotate);
            let bound = major * (1.0 + ratio);
            let target = center + bound * target;
            let origin = target + distance_to * from.try_normalize().unwrap_or(Vec3::X);
            let ray = Ray::new(origin, (target - origin).normalize());
            let Some(alpha) = t.intersect(&ray) else { return Ok(()) };
            prop_assert!(ray.contains(alpha));
            let to_local = |p: Vec3| t.placement.world_from_object.transpose() * (p - center);
            let raw = distance(&t, to_local(ray.at(alpha)));
            prop_assert!(raw < 2e-5 * (distance_to + bound), "ray point off by {raw}");
            let s = t.surface(&ray, alpha);
            let p = to_local(s.point);
            prop_assert!(distance(&t, p) < 2e-6 * bound, "{}", distance(&t, p));
            prop_assert!((s.normal.length() - 1.0).abs() < 1e-5);
            let rho = (p.x * p.x + p.z * p.z).sqrt();
            let tube = t.placement.point_to_world(major / rho * Vec3::new(p.x, 0.0, p.z));
            prop_assert!(s.normal.dot(s.point - tube) > 0.0);
        }
    }
}
