//! The capped cone: the side's quadratic H²(x² + z²) = R²(H − y)² in object
//! space, restricted to the nappe 0 ≤ y ≤ H, plus the base disk.

mod lanes;

use super::bound::BoundingSphere;
use super::cylinder::shift_near;
use super::placement::Placement;
use super::quadratic::solve_quadratic;
use super::{AreaSample, Surface};
use crate::geometry::ray::Ray;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A cone on the base disk of radius R (local y = 0), apex at local (0, H, 0),
/// capped at its base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Object space: the base centre at the origin, the apex on +y.
    placement: Placement,
    /// R, the base radius.
    radius: f32,
    /// H, the height of the apex above the base.
    height: f32,
    /// Rays that miss it skip the exact test.
    bound: BoundingSphere,
}

impl Cone {
    /// A cone on the disk of `radius` centred at `base`, apex `height` above
    /// it along +y, rotated by `rotate_deg` degrees (x, then y, then z) about `base`.
    pub fn new(base: Vec3, radius: f32, height: f32, rotate_deg: Vec3) -> Self {
        debug_assert!(radius >= 0.0 && height >= 0.0, "r {radius} h {height}");
        let placement = Placement::from_euler_degrees(base, rotate_deg);
        let (radius, height) = (radius.abs(), height.abs());
        // The smallest enclosing sphere: through the apex and the base rim
        // when the cone is taller than wide, else the base disk's own sphere.
        let (centre_y, enclosing) = if height > radius {
            let y = (height * height - radius * radius) / (2.0 * height);
            (y, height - y)
        } else {
            (0.0, radius)
        };
        Self {
            placement,
            radius,
            height,
            bound: BoundingSphere::new(
                placement.point_to_world(Vec3::new(0.0, centre_y, 0.0)),
                enclosing,
            ),
        }
    }

    /// The loose world-space sphere [`Cone::intersect`] tests first: a ray
    /// it turns away misses the shape.
    pub(crate) fn bound(&self) -> &BoundingSphere {
        &self.bound
    }

    /// α of the nearest hit with t_min < α < t_max, or `None`.
    ///
    /// The origin is first moved along the ray to its closest approach to the
    /// cone's mid-axis point (α = shift + t), so the coefficients stay small
    /// for far rays. The side's quadratic is multiplied through by H² (no division) and
    /// solved in the stable form, so a ray parallel to a generator (a = 0)
    /// gets its single linear root. Roots on the mirror nappe (y > H) or
    /// below the base (y < 0) are rejected; the base disk is the other candidate.
    /// A loose world-space bounding sphere first turns clear misses away
    /// without the object-space transform; the answer is the same either way.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        if !self.bound.may_hit(ray) {
            return None;
        }
        self.intersect_exact(ray)
    }

    /// [`Cone::intersect`] without the bounding-sphere test.
    fn intersect_exact(&self, ray: &Ray) -> Option<f32> {
        let local = self.placement.ray_to_object(ray);
        let (r2, h) = (self.radius * self.radius, self.height);
        let (shift, o, d) = shift_near(&local, Vec3::new(0.0, 0.5 * h, 0.0));
        let h2 = h * h;
        // With w = H − y along the ray: w(t) = w0 − t d_y.
        let w0 = h - o.y;
        let a = h2 * (d.x * d.x + d.z * d.z) - r2 * d.y * d.y;
        let b = 2.0 * (h2 * (o.x * d.x + o.z * d.z) + r2 * w0 * d.y);
        let c = h2 * (o.x * o.x + o.z * o.z) - r2 * w0 * w0;
        let mut best = f32::INFINITY;
        if let Some((t0, t1)) = solve_quadratic(a, b, c) {
            for t in [t0, t1] {
                let y = o.y + t * d.y;
                let alpha = shift + t;
                if local.contains(alpha) && alpha < best && (0.0..=h).contains(&y) {
                    best = alpha;
                }
            }
        }
        if d.y != 0.0 {
            let t = -o.y / d.y;
            let alpha = shift + t;
            if local.contains(alpha) && alpha < best {
                let (x, z) = (o.x + t * d.x, o.z + t * d.z);
                if x * x + z * z <= r2 {
                    best = alpha;
                }
            }
        }
        debug_assert!(!best.is_nan());
        best.is_finite().then_some(best)
    }

    /// The hit point placed on the nearest part (side: projected onto the
    /// generator in its half-plane through the axis; base: snapped to y = 0),
    /// with that part's outward normal.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let p = self.placement.ray_to_object(ray).at(alpha);
        let (r, h) = (self.radius, self.height);
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        // The generator from (ρ, y) = (R, 0) to (0, H), and its outward normal (H, R).
        let len = (r * r + h * h).sqrt();
        let side = (h * rho + r * p.y - r * h).abs() / len;
        let (point, normal) = if side <= p.y.abs() && len > 0.0 {
            let s = (((rho - r) * -r + p.y * h) / (len * len)).clamp(0.0, 1.0);
            let (rho_on, y_on) = (r * (1.0 - s), h * s);
            let radial = if rho > 0.0 {
                Vec3::new(p.x / rho, 0.0, p.z / rho)
            } else {
                Vec3::X
            };
            let normal = if rho > 0.0 {
                (h * radial + Vec3::new(0.0, r, 0.0)) / len
            } else {
                Vec3::Y // the apex: no unique normal
            };
            (rho_on * radial + Vec3::new(0.0, y_on, 0.0), normal)
        } else {
            let scale = if rho > r { r / rho } else { 1.0 };
            (Vec3::new(p.x * scale, 0.0, p.z * scale), -Vec3::Y)
        };
        self.placement.surface_to_world(point, normal)
    }
}

impl Cone {
    /// The surface area: the lateral surface and the base disk.
    pub fn area(&self) -> f32 {
        let r = self.radius;
        PI * r * (r + r.hypot(self.height))
    }

    /// A point drawn uniformly over the lateral surface and the base, with
    /// its outward normal.
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        let (r, h) = (self.radius, self.height);
        let area = self.area();
        if !(area > 0.0) {
            return None;
        }
        let slant = r.hypot(h);
        let lateral = slant / (slant + r);
        let (p, n) = if u.x < lateral {
            // Distance from the apex ∝ √u: area grows linearly with it.
            let s = (u.x / lateral).sqrt();
            let phi = 2.0 * PI * u.y;
            let radial = Vec3::new(phi.cos(), 0.0, phi.sin());
            let n = (h * radial + Vec3::new(0.0, r, 0.0)) / slant;
            (r * s * radial + Vec3::new(0.0, h * (1.0 - s), 0.0), n)
        } else {
            let t = (u.x - lateral) / (1.0 - lateral);
            let d = r * crate::geometry::warp::concentric_disk(Vec2::new(t, u.y));
            (Vec3::new(d.x, 0.0, d.y), -Vec3::Y)
        };
        let s = self.placement.surface_to_world(p, n);
        Some(AreaSample {
            point: s.point,
            normal: s.normal,
            pdf_area: 1.0 / area,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn unit() -> Cone {
        // Base radius 1 at y = 0, apex at (0, 2, 0).
        Cone::new(Vec3::ZERO, 1.0, 2.0, Vec3::ZERO)
    }

    fn hit(o: Vec3, d: Vec3) -> Option<f32> {
        unit().intersect(&Ray::new(o, d))
    }

    #[test]
    fn side_hit_from_outside_is_exact() {
        // At y = 1 the radius is 0.5.
        let ray = Ray::new(Vec3::new(5.0, 1.0, 0.0), -Vec3::X);
        assert_eq!(unit().intersect(&ray), Some(4.5));
        let s = unit().surface(&ray, 4.5);
        assert!((s.point - Vec3::new(0.5, 1.0, 0.0)).length() < 1e-6);
        assert!((s.normal - Vec3::new(2.0, 1.0, 0.0) / 5f32.sqrt()).length() < 1e-6);
    }

    #[test]
    fn base_hit_from_below() {
        let ray = Ray::new(Vec3::new(0.2, -3.0, 0.0), Vec3::Y);
        assert_eq!(unit().intersect(&ray), Some(3.0));
        assert_eq!(unit().surface(&ray, 3.0).normal, -Vec3::Y);
    }

    #[test]
    fn ray_parallel_to_a_generator_hits_the_unit_cone() {
        // x² + z² = y², 0 ≤ y ≤ 1: base disk at y = 1, apex at the origin.
        let cone = Cone::new(
            Vec3::new(0.0, 1.0, 0.0),
            1.0,
            1.0,
            Vec3::new(180.0, 0.0, 0.0),
        );
        let ray = Ray::new(
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0).normalize(),
        );
        let alpha = cone.intersect(&ray).expect("generator-parallel ray hits");
        assert!(
            (alpha - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-5,
            "{alpha}"
        );
        let s = cone.surface(&ray, alpha);
        assert!(
            (s.point - Vec3::new(0.0, 0.5, -0.5)).length() < 1e-5,
            "{}",
            s.point
        );
        assert!((s.normal - Vec3::new(0.0, -1.0, -1.0).normalize()).length() < 1e-5);
    }

    #[test]
    fn the_mirror_nappe_beyond_the_apex_is_not_hit() {
        // At y = 4 the mirror nappe has radius 1.
        assert_eq!(hit(Vec3::new(5.0, 4.0, 0.0), -Vec3::X), None);
        // Starting inside the mirror nappe's cone, leaving it at y = 4 (not a
        // hit), then entering the real nappe at (0, 4/3, 1/3).
        let d = Vec3::new(0.0, -5.0, -1.25);
        let a = hit(Vec3::new(0.0, 6.0, 1.5), d.normalize()).expect("real nappe");
        let expected = (14.0 / 15.0) * d.length();
        assert!((a - expected).abs() < 1e-5, "{a} {expected}");
    }

    #[test]
    fn rays_beside_or_behind_miss() {
        assert_eq!(hit(Vec3::new(5.0, 1.0, 0.6), -Vec3::X), None);
        assert_eq!(hit(Vec3::new(5.0, 1.0, 0.0), Vec3::X), None);
        assert_eq!(hit(Vec3::new(5.0, -0.1, 0.0), -Vec3::X), None);
    }

    #[test]
    fn rays_along_the_axis_touch_the_apex_or_the_side() {
        assert_eq!(hit(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y), Some(3.0));
        let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
        let s = unit().surface(&ray, 3.0);
        assert!(s.point.is_finite() && (s.normal.length() - 1.0).abs() < 1e-6);
        assert_eq!(hit(Vec3::new(0.5, 5.0, 0.0), -Vec3::Y), Some(4.0));
        assert_eq!(hit(Vec3::new(1.5, 5.0, 0.0), -Vec3::Y), None);
    }

    #[test]
    fn tangent_and_base_plane_rays_give_no_nan() {
        // In the base plane (d_y = 0, y = 0): grazes the rim.
        assert_eq!(hit(Vec3::new(-5.0, 0.0, 0.0), Vec3::X), Some(4.0));
        // Tangent to the side at (0, 1, 0.5) along x.
        let a = hit(Vec3::new(-5.0, 1.0, 0.5), Vec3::X).expect("tangent");
        assert!((a - 5.0).abs() < 1e-3, "{a}");
    }

    #[test]
    fn origin_inside_hits_the_exit() {
        assert_eq!(hit(Vec3::new(0.0, 0.5, 0.0), Vec3::X), Some(0.75));
        assert_eq!(hit(Vec3::new(0.0, 0.5, 0.0), -Vec3::Y), Some(0.5));
    }

    #[test]
    fn ray_starting_inside_with_short_t_max_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::X).with_t_max(0.7);
        assert_eq!(unit().intersect(&ray), None);
    }

    #[test]
    fn rotated_cone_points_along_the_rotated_axis() {
        // 90° about x turns +y into +z: apex at (0, 0, 2).
        let c = Cone::new(Vec3::ZERO, 1.0, 2.0, Vec3::new(90.0, 0.0, 0.0));
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        let a = c.intersect(&ray).expect("apex");
        assert!((a - 3.0).abs() < 1e-5, "{a}");
        let ray = Ray::new(Vec3::new(0.0, 5.0, 1.0), -Vec3::Y);
        let a = c.intersect(&ray).expect("side");
        assert!((a - 4.5).abs() < 1e-5, "{a}");
    }

    #[test]
    fn the_bounding_sphere_only_skips_rays_that_miss() {
        for (k, (radius, height, rotate)) in [
            (0.8, 2.0, Vec3::ZERO),
            (2.0, 0.5, Vec3::new(30.0, 40.0, 50.0)),
            (1.0, 1.0, Vec3::new(90.0, 0.0, 0.0)),
        ]
        .into_iter()
        .enumerate()
        {
            let c = Cone::new(Vec3::new(-2.25, 0.0, 3.0), radius, height, rotate);
            super::super::bound::testing::assert_only_misses_skipped(
                &c.bound,
                k as u64,
                |ray| c.intersect(ray),
                |ray| c.intersect_exact(ray),
            );
        }
    }

    fn any_vec(r: f32) -> impl Strategy<Value = Vec3> {
        (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn hits_lie_on_the_surface_with_outward_unit_normals(
            base in any_vec(5.0),
            radius in 0.1f32..2.0,
            height in 0.1f32..3.0,
            rotate in any_vec(180.0),
            from in any_vec(1.0),
            target in (0.0f32..0.95, 0.0f32..6.3, 0.02f32..0.98),
            distance in 6.0f32..50.0,
        ) {
            let c = Cone::new(base, radius, height, rotate);
            let (s, phi, v) = target;
            let rho = s * radius * (1.0 - v);
            let local = Vec3::new(rho * phi.cos(), v * height, rho * phi.sin());
            let target = c.placement.point_to_world(local);
            let origin = target + distance * from.try_normalize().unwrap_or(Vec3::X);
            let ray = Ray::new(origin, (target - origin).normalize());
            let alpha = c.intersect(&ray).expect("aimed inside");
            prop_assert!(ray.contains(alpha) && alpha < distance);
            let hit = c.surface(&ray, alpha);
            prop_assert!((hit.point - ray.at(alpha)).length() < 1e-4 * distance);
            let p = c.placement.world_from_object.transpose() * (hit.point - base);
            let rho = (p.x * p.x + p.z * p.z).sqrt();
            let len = (radius * radius + height * height).sqrt();
            let residual = ((height * rho + radius * p.y - radius * height) / len).max(-p.y);
            prop_assert!(residual.abs() < 1e-5, "residual {residual}");
            prop_assert!((hit.normal.length() - 1.0).abs() < 1e-5);
            let centre = c.placement.point_to_world(Vec3::new(0.0, 0.25 * height, 0.0));
            prop_assert!(hit.normal.dot(hit.point - centre) > 0.0);
            let away = Ray::new(hit.point + 1e-3 * hit.normal, hit.normal);
            prop_assert_eq!(c.intersect(&away), None);
        }
    }
}
