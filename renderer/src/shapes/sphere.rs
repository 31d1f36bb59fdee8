//! The sphere: the lecture's quadratic in α, and the Ray Tracing Gems ch. 7 form.

use super::{AreaSample, Method, Surface};
use crate::geometry::ray::Ray;
use glam::{Vec2, Vec3};
use serde::Serialize;

/// A sphere with centre C and radius r.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// C, the centre.
    pub center: Vec3,
    /// r, the radius.
    pub radius: f32,
}

/// The two roots of the sphere's quadratic in α, as the pixel inspector shows them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SphereRoots {
    /// The smaller root.
    pub near: f32,
    /// The larger root.
    pub far: f32,
}

/// The sphere's quadratic a α² + b α + c = 0 for one ray, as a method forms
/// it: the lecture's ‖v‖² α² − 2 (u · v) α + ‖u‖² − r² with u = C − P0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SphereQuadratic {
    /// a = ‖v‖².
    pub a: f32,
    /// b = −2 (u · v).
    pub b: f32,
    /// c = ‖u‖² − r².
    pub c: f32,
    /// b² − 4ac; the robust method forms it as 4a (r² − ‖f + (b'/a) v‖²)
    /// with f = P0 − C and b' = −f · v. Negative: the ray misses.
    pub discriminant: f32,
    /// The real roots, if any (exactly those [`Sphere::intersect`] chooses from).
    pub roots: Option<SphereRoots>,
}

impl Sphere {
    /// A sphere with centre `center` and radius `radius`.
    pub fn new(center: Vec3, radius: f32) -> Self {
        Self { center, radius }
    }

    /// α of the nearest hit inside the ray's interval.
    #[inline]
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<f32> {
        let roots = self.roots(ray, method)?;
        [roots.near, roots.far]
            .into_iter()
            .find(|&a| ray.contains(a))
    }

    /// The real roots of the quadratic in α, if any.
    #[inline]
    pub fn roots(&self, ray: &Ray, method: Method) -> Option<SphereRoots> {
        self.quadratic(ray, method).roots
    }

    /// The quadratic in α with its coefficients and roots, as `method`
    /// computes them: what [`Sphere::intersect`] decides from.
    #[inline]
    pub fn quadratic(&self, ray: &Ray, method: Method) -> SphereQuadratic {
        match method {
            Method::Lecture => self.lecture_quadratic(ray),
            Method::Robust => self.robust_quadratic(ray),
        }
    }

    /// The lecture: with u = C − P0, the roots of
    /// ‖v‖² α² − 2 (u · v) α + ‖u‖² − r² by the textbook formula.
    #[inline]
    fn lecture_quadratic(&self, ray: &Ray) -> SphereQuadratic {
        let u = self.center - ray.origin;
        let v = ray.dir;
        let a = v.dot(v);
        let b = -2.0 * u.dot(v);
        let c = u.dot(u) - self.radius * self.radius;
        let disc = b * b - 4.0 * a * c;
        let roots = if disc >= 0.0 {
            let root = disc.sqrt();
            let near = (-b - root) / (2.0 * a);
            let far = (-b + root) / (2.0 * a);
            (near.is_finite() && far.is_finite()).then_some(SphereRoots { near, far })
        } else {
            None
        };
        SphereQuadratic {
            a,
            b,
            c,
            discriminant: disc,
            roots,
        }
    }

    /// Ray Tracing Gems ch. 7 (Haines et al.): with f = P0 − C and
    /// b' = −f · v, the discriminant is formed as a (r² − ‖f + (b'/a) v‖²),
    /// which keeps its precision when the sphere is small and far away, and
    /// the roots are c/q and q/a with q = b' + sign(b')√disc.
    #[inline]
    fn robust_quadratic(&self, ray: &Ray) -> SphereQuadratic {
        let f = ray.origin - self.center;
        let v = ray.dir;
        let a = v.dot(v);
        let b = -f.dot(v);
        let c = f.dot(f) - self.radius * self.radius;
        let l = f + (b / a) * v;
        let disc = a * (self.radius * self.radius - l.dot(l));
        let roots = if disc >= 0.0 {
            let q = b + disc.sqrt().copysign(b);
            let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (c / q, q / a) };
            let (near, far) = if r0 <= r1 { (r0, r1) } else { (r1, r0) };
            (near.is_finite() && far.is_finite()).then_some(SphereRoots { near, far })
        } else {
            None
        };
        // In the lecture's form: b = −2 (u · v) = 2 (f · v) = −2b', and the
        // discriminant b² − 4ac = 4 (b'² − ac) = 4 disc (both exact in binary).
        SphereQuadratic {
            a,
            b: -2.0 * b,
            c,
            discriminant: 4.0 * disc,
            roots,
        }
    }

    /// The hit point reprojected onto the sphere, and the outward normal.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let radial = ray.at(alpha) - self.center;
        let normal = radial.try_normalize().unwrap_or(Vec3::Y);
        Surface {
            point: self.center + self.radius * normal,
            normal,
        }
    }
}

impl Sphere {
    /// The surface area 4π r².
    pub fn area(&self) -> f32 {
        4.0 * std::f32::consts::PI * self.radius * self.radius
    }

    /// A point drawn uniformly over the surface, with its outward normal.
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        let area = self.area();
        if !(area > 0.0) {
            return None;
        }
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * u.y;
        let normal = Vec3::new(r * phi.cos(), r * phi.sin(), z);
        Some(AreaSample {
            point: self.center + self.radius * normal,
            normal,
            pdf_area: 1.0 / area,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const METHODS: [Method; 2] = [Method::Lecture, Method::Robust];

    fn unit_sphere() -> Sphere {
        Sphere::new(Vec3::ZERO, 1.0)
    }

    #[test]
    fn hit_from_outside_is_at_distance_minus_radius() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), Some(4.0), "{m:?}");
        }
    }

    #[test]
    fn ray_pointing_away_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), None, "{m:?}");
        }
    }

    #[test]
    fn ray_passing_beside_misses() {
        let ray = Ray::new(Vec3::new(1.5, 0.0, 5.0), -Vec3::Z);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), None, "{m:?}");
        }
    }

    #[test]
    fn tangent_ray_touches_once() {
        let ray = Ray::new(Vec3::new(1.0, 0.0, 5.0), -Vec3::Z);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), Some(5.0), "{m:?}");
        }
    }

    #[test]
    fn origin_inside_hits_the_far_side() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.5), -Vec3::Z);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), Some(1.5), "{m:?}");
        }
    }

    #[test]
    fn t_max_before_the_hit_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(3.9);
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), None, "{m:?}");
        }
    }

    #[test]
    fn lecture_quadratic_accepts_unnormalised_directions() {
        // The lecture's quadratic keeps ‖v‖²: α scales inversely with ‖v‖.
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -2.0));
        for m in METHODS {
            assert_eq!(unit_sphere().intersect(&ray, m), Some(2.0), "{m:?}");
        }
    }

    #[test]
    fn robust_form_keeps_hits_on_a_small_far_sphere() {
        // Distance/radius = 1e4: rays aimed at the inner half of the disk must hit.
        let sphere = Sphere::new(Vec3::new(0.0, 0.0, -1.0e4), 1.0);
        let mut misses = 0;
        for k in 0..100 {
            let target = sphere.center + Vec3::new(0.5 * (k as f32 / 100.0), 0.0, 0.0);
            let ray = Ray::new(Vec3::ZERO, target.normalize());
            if sphere.intersect(&ray, Method::Robust).is_none() {
                misses += 1;
            }
        }
        assert_eq!(misses, 0);
    }

    #[test]
    fn surface_point_lies_on_sphere_with_outward_normal() {
        let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0);
        let ray = Ray::new(Vec3::new(1.0, 2.0, 10.0), -Vec3::Z);
        let alpha = s.intersect(&ray, Method::Robust).expect("hit");
        let surf = s.surface(&ray, alpha);
        assert!((surf.point - Vec3::new(1.0, 2.0, 5.0)).length() < 1e-6);
        assert!((surf.normal - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn quadratic_of_a_ray_through_the_centre_has_roots_at_distance_minus_and_plus_radius() {
        // P0 = (0, 0, 5), v = −z, C = 0, r = 1: u = C − P0 = (0, 0, −5), so
        // a = ‖v‖² = 1, b = −2 (u · v) = −10, c = ‖u‖² − r² = 24,
        // b² − 4ac = 4, roots (10 ∓ 2)/2 = 4 and 6.
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        for m in METHODS {
            let q = unit_sphere().quadratic(&ray, m);
            assert_eq!(
                (q.a, q.b, q.c, q.discriminant),
                (1.0, -10.0, 24.0, 4.0),
                "{m:?}"
            );
            assert_eq!(
                q.roots,
                Some(SphereRoots {
                    near: 4.0,
                    far: 6.0
                }),
                "{m:?}"
            );
        }
    }

    #[test]
    fn quadratic_of_a_missing_ray_has_a_negative_discriminant_and_no_roots() {
        // 1.5 beside the axis: u = (−1.5, 0, −5), b = −2 (u · v) = −10,
        // c = 2.25 + 25 − 1 = 26.25, b² − 4ac = 100 − 105 = −5.
        let ray = Ray::new(Vec3::new(1.5, 0.0, 5.0), -Vec3::Z);
        for m in METHODS {
            let q = unit_sphere().quadratic(&ray, m);
            assert!(q.discriminant < 0.0, "{m:?} {q:?}");
            assert_eq!(q.roots, None, "{m:?}");
        }
    }

    #[test]
    fn quadratic_roots_are_the_ones_intersect_chooses_from() {
        // From inside, the near root is negative and intersect takes the far one.
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.5), -Vec3::Z);
        for m in METHODS {
            let roots = unit_sphere().quadratic(&ray, m).roots.expect("two roots");
            assert_eq!((roots.near, roots.far), (-0.5, 1.5), "{m:?}");
            assert_eq!(unit_sphere().intersect(&ray, m), Some(roots.far), "{m:?}");
        }
    }

    proptest! {
        #[test]
        fn both_methods_agree_on_well_conditioned_rays(
            ox in -10.0f32..10.0, oy in -10.0f32..10.0, oz in 3.0f32..10.0,
            tx in -0.6f32..0.6, ty in -0.6f32..0.6,
        ) {
            let s = unit_sphere();
            let origin = Vec3::new(ox, oy, oz);
            let ray = Ray::new(origin, (Vec3::new(tx, ty, 0.0) - origin).normalize());
            let lecture = s.intersect(&ray, Method::Lecture).expect("aimed inside");
            let robust = s.intersect(&ray, Method::Robust).expect("aimed inside");
            prop_assert!((lecture - robust).abs() <= 1e-4 * robust);
            let p = s.surface(&ray, robust).point;
            prop_assert!((p.length() - 1.0).abs() < 1e-6);
        }
    }
}
