//! The capped cylinder: the side's quadratic x² + z² = R² in object space,
//! restricted to 0 ≤ y ≤ H, plus the two cap disks.

use super::bound::BoundingSphere;
use super::placement::Placement;
use super::quadratic::solve_quadratic;
use super::{AreaSample, Surface};
use crate::geometry::ray::Ray;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A capped cylinder standing on the disk of radius R at its base point,
/// its axis along the local +y, its top cap at local y = H.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// Object space: the base centre at the origin, the axis along +y.
    placement: Placement,
    /// R, the radius.
    radius: f32,
    /// H, the height.
    height: f32,
    /// Rays that miss it skip the exact test.
    bound: BoundingSphere,
}

impl Cylinder {
    /// A cylinder on the disk of `radius` centred at `base`, `height` tall
    /// along +y, rotated by `rotate_deg` degrees (x, then y, then z) about `base`.
    pub fn new(base: Vec3, radius: f32, height: f32, rotate_deg: Vec3) -> Self {
        debug_assert!(radius >= 0.0 && height >= 0.0, "r {radius} h {height}");
        let placement = Placement::from_euler_degrees(base, rotate_deg);
        let (radius, height) = (radius.abs(), height.abs());
        Self {
            placement,
            radius,
            height,
            bound: BoundingSphere::new(
                placement.point_to_world(Vec3::new(0.0, 0.5 * height, 0.0)),
                radius.hypot(0.5 * height),
            ),
        }
    }

    /// The loose world-space sphere [`Cylinder::intersect`] tests first: a ray
    /// it turns away misses the shape.
    pub(crate) fn bound(&self) -> &BoundingSphere {
        &self.bound
    }

    /// α of the nearest hit with t_min < α < t_max, or `None`. The origin is
    /// first moved along the ray to its closest approach to the mid-axis
    /// point (α = shift + t), which keeps the quadratic's coefficients small
    /// for far rays. The hit is the nearest of
    /// the side's roots with 0 ≤ y ≤ H and the caps' hits with x² + z² ≤ R².
    /// A ray along the axis (no side quadratic: a = b = 0) sees only the caps;
    /// a ray parallel to the caps (d_y = 0) sees only the side.
    /// A loose world-space bounding sphere first turns clear misses away
    /// without the object-space transform; the answer is the same either way.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        if !self.bound.may_hit(ray) {
            return None;
        }
        self.intersect_exact(ray)
    }

    /// [`Cylinder::intersect`] without the bounding-sphere test.
    fn intersect_exact(&self, ray: &Ray) -> Option<f32> {
        let local = self.placement.ray_to_object(ray);
        let (r2, h) = (self.radius * self.radius, self.height);
        let (shift, o, d) = shift_near(&local, Vec3::new(0.0, 0.5 * h, 0.0));
        let mut best = f32::INFINITY;
        let a = d.x * d.x + d.z * d.z;
        let b = 2.0 * (o.x * d.x + o.z * d.z);
        let c = o.x * o.x + o.z * o.z - r2;
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
            for cap in [0.0, h] {
                let t = (cap - o.y) / d.y;
                let alpha = shift + t;
                if local.contains(alpha) && alpha < best {
                    let (x, z) = (o.x + t * d.x, o.z + t * d.z);
                    if x * x + z * z <= r2 {
                        best = alpha;
                    }
                }
            }
        }
        debug_assert!(!best.is_nan());
        best.is_finite().then_some(best)
    }

    /// The hit point placed on the nearest part (side: reprojected radially
    /// to ρ = R; cap: snapped to its plane), with that part's outward normal.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let p = self.placement.ray_to_object(ray).at(alpha);
        let (r, h) = (self.radius, self.height);
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let side = (rho - r).abs();
        let (bottom, top) = (p.y.abs(), (p.y - h).abs());
        let (point, normal) = if side <= bottom.min(top) && rho > 0.0 {
            let radial = Vec3::new(p.x / rho, 0.0, p.z / rho);
            (r * radial + Vec3::new(0.0, p.y.clamp(0.0, h), 0.0), radial)
        } else {
            // Snap to the cap plane and clamp into the disk.
            let (y, n) = if bottom <= top {
                (0.0, -Vec3::Y)
            } else {
                (h, Vec3::Y)
            };
            let scale = if rho > r { r / rho } else { 1.0 };
            (Vec3::new(p.x * scale, y, p.z * scale), n)
        };
        self.placement.surface_to_world(point, normal)
    }
}

/// The object-space ray's origin moved to its closest approach to `centre`:
/// (shift, shifted origin, direction), so that α = shift + t. Only rounding
/// changes: the roots of a quadratic lose precision in proportion to how far
/// the origin is (Ray Tracing Gems ch. 7), the shifted ones do not.
pub(super) fn shift_near(local: &Ray, centre: Vec3) -> (f32, Vec3, Vec3) {
    let (o, d) = (local.origin, local.dir);
    let dd = d.length_squared();
    let shift = if dd > 0.0 {
        (centre - o).dot(d) / dd
    } else {
        0.0
    };
    let shift = if shift.is_finite() { shift } else { 0.0 };
    (shift, o + shift * d, d)
}

impl Cylinder {
    /// The surface area: the side and both caps.
    pub fn area(&self) -> f32 {
        let r = self.radius;
        2.0 * PI * r * (self.height + r)
    }

    /// A point drawn uniformly over the side and caps, with its outward normal.
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        let (r, h) = (self.radius, self.height);
        let area = self.area();
        if !(area > 0.0) {
            return None;
        }
        let side = h / (h + r);
        let (p, n) = if u.x < side {
            let phi = 2.0 * PI * u.y;
            let radial = Vec3::new(phi.cos(), 0.0, phi.sin());
            (r * radial + Vec3::new(0.0, h * (u.x / side), 0.0), radial)
        } else {
            // The caps: the lower half of the rest is the bottom one.
            let t = (u.x - side) / (1.0 - side);
            let (t, y, n) = if t < 0.5 {
                (2.0 * t, 0.0, -Vec3::Y)
            } else {
                (2.0 * t - 1.0, h, Vec3::Y)
            };
            let d = r * crate::geometry::warp::concentric_disk(Vec2::new(t, u.y));
            (Vec3::new(d.x, y, d.y), n)
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

    fn unit() -> Cylinder {
        // Radius 1, from y = 0 to y = 2.
        Cylinder::new(Vec3::ZERO, 1.0, 2.0, Vec3::ZERO)
    }

    fn hit(o: Vec3, d: Vec3) -> Option<f32> {
        unit().intersect(&Ray::new(o, d))
    }

    #[test]
    fn side_hit_from_outside_is_exact() {
        let ray = Ray::new(Vec3::new(0.0, 1.0, 5.0), -Vec3::Z);
        assert_eq!(unit().intersect(&ray), Some(4.0));
        let s = unit().surface(&ray, 4.0);
        assert_eq!((s.point, s.normal), (Vec3::new(0.0, 1.0, 1.0), Vec3::Z));
    }

    #[test]
    fn cap_hits_from_above_and_below() {
        let ray = Ray::new(Vec3::new(0.5, 5.0, 0.0), -Vec3::Y);
        assert_eq!(unit().intersect(&ray), Some(3.0));
        assert_eq!(unit().surface(&ray, 3.0).normal, Vec3::Y);
        let ray = Ray::new(Vec3::new(0.5, -1.0, 0.0), Vec3::Y);
        assert_eq!(unit().intersect(&ray), Some(1.0));
        assert_eq!(unit().surface(&ray, 1.0).normal, -Vec3::Y);
    }

    #[test]
    fn rays_beside_above_or_behind_miss() {
        assert_eq!(hit(Vec3::new(1.5, 1.0, 5.0), -Vec3::Z), None);
        assert_eq!(hit(Vec3::new(0.0, 2.5, 5.0), -Vec3::Z), None);
        assert_eq!(hit(Vec3::new(0.0, 1.0, 5.0), Vec3::Z), None);
        assert_eq!(hit(Vec3::new(1.5, 5.0, 0.0), -Vec3::Y), None);
    }

    #[test]
    fn tangent_ray_touches_the_side_once_without_nan() {
        assert_eq!(hit(Vec3::new(1.0, 1.0, 5.0), -Vec3::Z), Some(5.0));
    }

    #[test]
    fn origin_inside_hits_the_exit() {
        assert_eq!(hit(Vec3::new(0.0, 1.0, 0.0), Vec3::X), Some(1.0));
        assert_eq!(hit(Vec3::new(0.0, 1.0, 0.0), Vec3::Y), Some(1.0));
        assert_eq!(hit(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y), Some(1.0));
    }

    #[test]
    fn ray_starting_inside_with_short_t_max_misses() {
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X).with_t_max(0.9);
        assert_eq!(unit().intersect(&ray), None);
        let ray = Ray::new(Vec3::new(0.0, 1.0, 5.0), -Vec3::Z).with_t_max(4.0);
        assert_eq!(unit().intersect(&ray), None, "open interval excludes t_max");
    }

    #[test]
    fn ray_parallel_to_the_axis_sees_only_the_caps() {
        // a = b = 0: no side quadratic, no NaN.
        assert_eq!(hit(Vec3::new(0.3, -2.0, 0.4), Vec3::Y), Some(2.0));
        assert_eq!(hit(Vec3::new(1.2, -2.0, 0.0), Vec3::Y), None);
        // Exactly on the side's line: closed shape, the bottom rim is hit.
        assert_eq!(hit(Vec3::new(1.0, -2.0, 0.0), Vec3::Y), Some(2.0));
    }

    #[test]
    fn ray_in_a_cap_plane_grazes_the_rim_consistently() {
        // d_y = 0 exactly in the top plane: the side's root at y = H counts.
        assert_eq!(hit(Vec3::new(-5.0, 2.0, 0.0), Vec3::X), Some(4.0));
        assert_eq!(hit(Vec3::new(-5.0, 2.0 + 1e-6, 0.0), Vec3::X), None);
        assert_eq!(hit(Vec3::new(-5.0, 0.0, 0.0), Vec3::X), Some(4.0));
    }

    #[test]
    fn rotated_cylinder_lies_along_the_rotated_axis() {
        // 90° about z turns +y into −x: the cylinder spans x ∈ [−2, 0].
        let c = Cylinder::new(Vec3::ZERO, 1.0, 2.0, Vec3::new(0.0, 0.0, 90.0));
        let ray = Ray::new(Vec3::new(-5.0, 0.2, 0.0), Vec3::X);
        let a = c.intersect(&ray).expect("top cap");
        assert!((a - 3.0).abs() < 1e-5, "{a}");
        assert!((c.surface(&ray, a).normal + Vec3::X).length() < 1e-6);
        let ray = Ray::new(Vec3::new(-1.0, 5.0, 0.0), -Vec3::Y);
        let a = c.intersect(&ray).expect("side");
        assert!((a - 4.0).abs() < 1e-5, "{a}");
        assert!((c.surface(&ray, a).normal - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn the_bounding_sphere_only_skips_rays_that_miss() {
        for (k, (radius, height, rotate)) in [
            (0.6, 1.8, Vec3::ZERO),
            (2.0, 0.3, Vec3::new(30.0, 40.0, 50.0)),
        ]
        .into_iter()
        .enumerate()
        {
            let c = Cylinder::new(Vec3::new(1.0, 2.0, -3.0), radius, height, rotate);
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
            let c = Cylinder::new(base, radius, height, rotate);
            let (s, phi, v) = target;
            let local = Vec3::new(s * radius * phi.cos(), v * height, s * radius * phi.sin());
            let target = c.placement.point_to_world(local);
            let origin = target + distance * from.try_normalize().unwrap_or(Vec3::X);
            let ray = Ray::new(origin, (target - origin).normalize());
            let alpha = c.intersect(&ray).expect("aimed inside");
            prop_assert!(ray.contains(alpha) && alpha < distance);
            let hit = c.surface(&ray, alpha);
            prop_assert!((hit.point - ray.at(alpha)).length() < 1e-4 * distance);
            let p = c.placement.world_from_object.transpose() * (hit.point - base);
            let rho = (p.x * p.x + p.z * p.z).sqrt();
            // Distance to the solid's boundary: zero on the surface.
            let residual = (rho - radius).max(-p.y).max(p.y - height);
            prop_assert!(residual.abs() < 1e-5, "residual {residual}");
            prop_assert!((hit.normal.length() - 1.0).abs() < 1e-5);
            let centre = c.placement.point_to_world(Vec3::new(0.0, 0.5 * height, 0.0));
            prop_assert!(hit.normal.dot(hit.point - centre) > 0.0);
            let away = Ray::new(hit.point + 1e-3 * hit.normal, hit.normal);
            prop_assert_eq!(c.intersect(&away), None);
        }
    }
}
