//! The oriented box: a slab test in object space (Kay–Kajiya), written so that
//! zero direction components and rays lying in a face plane never produce NaN.

use super::bound::BoundingSphere;
use super::placement::Placement;
use super::{AreaSample, Surface};
use crate::geometry::ray::Ray;
use glam::{Vec2, Vec3};

/// An oriented box: centre, half edge lengths along its own axes, rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    /// Object space: the box's centre at the origin, its edges along x, y, z.
    placement: Placement,
    /// Half the edge lengths, ≥ 0.
    half: Vec3,
    /// Rays that miss it skip the exact test.
    bound: BoundingSphere,
}

impl Cuboid {
    /// A box centred at `center` with edge lengths `size` along its own axes,
    /// rotated by `rotate_deg` degrees about x, then y, then z (about the centre).
    pub fn new(center: Vec3, size: Vec3, rotate_deg: Vec3) -> Self {
        debug_assert!(size.is_finite() && size.min_element() >= 0.0, "size {size}");
        let half = 0.5 * size.abs();
        Self {
            placement: Placement::from_euler_degrees(center, rotate_deg),
            half,
            bound: BoundingSphere::new(center, half.length()),
        }
    }

    /// Where the box stands: its centre and rotation (object space has the
    /// box's centre at the origin, its edges along x, y, z).
    pub(crate) fn placement(&self) -> &Placement {
        &self.placement
    }

    /// Half the edge lengths, along the box's own axes.
    pub(crate) fn half(&self) -> Vec3 {
        self.half
    }

    /// α of the nearest hit with t_min < α < t_max, or `None`.
    ///
    /// The box is closed: a ray that only grazes a face, edge or corner hits.
    /// A zero direction component means the slab of that axis does not
    /// constrain the ray if the origin lies inside it (boundary included), and
    /// misses otherwise. Only the slab distances t_near (entry) and t_far
    /// (exit) are candidates, and each must itself lie inside the interval.
    /// A loose world-space bounding sphere first turns clear misses away
    /// without the object-space transform; the answer is the same either way.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        if !self.bound.may_hit(ray) {
            return None;
        }
        self.intersect_exact(ray)
    }

    /// [`Cuboid::intersect`] without the bounding-sphere test.
    fn intersect_exact(&self, ray: &Ray) -> Option<f32> {
        let local = self.placement.ray_to_object(ray);
        let (o, d) = (local.origin.to_array(), local.dir.to_array());
        let h = self.half.to_array();
        let mut t_near = f32::NEG_INFINITY;
        let mut t_far = f32::INFINITY;
        for i in 0..3 {
            if d[i] == 0.0 {
                if o[i].abs() > h[i] {
                    return None;
                }
                continue;
            }
            // Division (not multiplication by 1/d) keeps 0/d = 0 even for a
            // subnormal d, where 1/d would overflow and 0·∞ would be NaN.
            let t_lo = (-h[i] - o[i]) / d[i];
            let t_hi = (h[i] - o[i]) / d[i];
            t_near = t_near.max(t_lo.min(t_hi));
            t_far = t_far.min(t_lo.max(t_hi));
        }
        if !(t_near <= t_far) {
            return None;
        }
        let alpha = if local.contains(t_near) {
            t_near
        } else if local.contains(t_far) {
            t_far
        } else {
            return None;
        };
        debug_assert!(alpha.is_finite(), "box α {alpha}");
        Some(alpha)
    }

    /// The hit point with the hit face's coordinate snapped to ±half-size
    /// (the others clamped onto the face), and the face's outward normal.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let local = self.placement.ray_to_object(ray);
        let mut p = local.at(alpha);
        // The face is the one whose plane the point is closest to.
        let excess = p.abs() - self.half;
        let axis = if excess.x >= excess.y && excess.x >= excess.z {
            0
        } else if excess.y >= excess.z {
            1
        } else {
            2
        };
        p = p.clamp(-self.half, self.half);
        p[axis] = self.half[axis].copysign(p[axis]);
        let mut normal = Vec3::ZERO;
        normal[axis] = 1.0f32.copysign(p[axis]);
        self.placement.surface_to_world(p, normal)
    }
}

impl Cuboid {
    /// The surface area of the six faces.
    pub fn area(&self) -> f32 {
        let h = self.half;
        8.0 * (h.y * h.z + h.x * h.z + h.x * h.y)
    }

    /// A point drawn uniformly over the faces (a face in proportion to its
    /// area, then uniformly on it), with its outward normal.
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        let area = self.area();
        if !(area > 0.0) {
            return None;
        }
        let h = self.half;
        // Face pairs by axis, each pair's share of the area.
        let pairs = [h.y * h.z, h.x * h.z, h.x * h.y];
        let total = pairs[0] + pairs[1] + pairs[2];
        let mut x = u.x * total;
        let mut axis = 2;
        for (k, &a) in pairs.iter().enumerate() {
            if x < a || k == 2 {
                axis = k;
                break;
            }
            x -= a;
        }
        // x / pairs[axis] ∈ [0, 1): its lower half picks the − face.
        let t = (x / pairs[axis]).clamp(0.0, 1.0);
        let (sign, t) = if t < 0.5 {
            (-1.0, 2.0 * t)
        } else {
            (1.0, 2.0 * t - 1.0)
        };
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut p = Vec3::ZERO;
        p[axis] = sign * h[axis];
        p[a] = (2.0 * t - 1.0) * h[a];
        p[b] = (2.0 * u.y - 1.0) * h[b];
        let mut n = Vec3::ZERO;
        n[axis] = sign;
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

    fn unit_box() -> Cuboid {
        // [-1, 1]³.
        Cuboid::new(Vec3::ZERO, Vec3::splat(2.0), Vec3::ZERO)
    }

    #[test]
    fn hit_from_outside_is_at_the_near_face() {
        let ray = Ray::new(Vec3::new(0.3, -0.2, 5.0), -Vec3::Z);
        assert_eq!(unit_box().intersect(&ray), Some(4.0));
        let s = unit_box().surface(&ray, 4.0);
        assert_eq!(s.point, Vec3::new(0.3, -0.2, 1.0));
        assert_eq!(s.normal, Vec3::Z);
    }

    #[test]
    fn ray_passing_beside_misses() {
        let ray = Ray::new(Vec3::new(1.5, 0.0, 5.0), -Vec3::Z);
        assert_eq!(unit_box().intersect(&ray), None);
        let diagonal = Ray::new(
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0).normalize(),
        );
        assert_eq!(unit_box().intersect(&diagonal), None);
    }

    #[test]
    fn box_behind_the_ray_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::Z);
        assert_eq!(unit_box().intersect(&ray), None);
    }

    #[test]
    fn origin_inside_hits_the_exit_face() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::Y);
        assert_eq!(unit_box().intersect(&ray), Some(0.5));
        assert_eq!(unit_box().surface(&ray, 0.5).normal, Vec3::Y);
    }

    #[test]
    fn ray_starting_inside_with_short_t_max_misses() {
        // The tungsten trap: t_near < t_min and t_far ≥ t_max is no hit.
        let ray = Ray::new(Vec3::ZERO, Vec3::X).with_t_max(0.5);
        assert_eq!(unit_box().intersect(&ray), None);
    }

    #[test]
    fn t_max_before_the_near_face_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(3.9);
        assert_eq!(unit_box().intersect(&ray), None);
        let ray = ray.with_t_max(5.5);
        assert_eq!(unit_box().intersect(&ray), Some(4.0));
    }

    #[test]
    fn t_min_past_the_near_face_gives_the_far_face() {
        let mut ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        ray.t_min = 4.5;
        assert_eq!(unit_box().intersect(&ray), Some(6.0));
    }

    #[test]
    fn zero_direction_components_give_no_nan() {
        // dir = +x exactly: the y and z slabs have d = 0 and the origin inside them.
        let ray = Ray::new(Vec3::new(-3.0, 0.0, 0.0), Vec3::X);
        assert_eq!(unit_box().intersect(&ray), Some(2.0));
        // Same, but the origin outside the y slab.
        let ray = Ray::new(Vec3::new(-3.0, 2.0, 0.0), Vec3::X);
        assert_eq!(unit_box().intersect(&ray), None);
        // Subnormal components behave like zero components, not like NaN.
        let tiny = f32::from_bits(1);
        let ray = Ray::new(Vec3::new(-3.0, 1.0, -1.0), Vec3::new(1.0, -tiny, tiny));
        assert_eq!(unit_box().intersect(&ray), Some(2.0));
    }

    #[test]
    fn ray_lying_in_a_face_plane_hits_consistently() {
        // The ray runs inside the plane y = 1 of the top face: the box is
        // closed, so it grazes the face from the x = −1 edge on.
        let ray = Ray::new(Vec3::new(-5.0, 1.0, 0.2), Vec3::X);
        assert_eq!(unit_box().intersect(&ray), Some(4.0));
        let s = unit_box().surface(&ray, 4.0);
        assert!(s.point.is_finite() && s.normal.is_finite());
        assert!((s.normal.length() - 1.0).abs() < 1e-6);
        // In the face plane but beside the face: miss.
        let ray = Ray::new(Vec3::new(-5.0, 1.0, 1.5), Vec3::X);
        assert_eq!(unit_box().intersect(&ray), None);
        // Along an edge line (two zero components at the boundary).
        let ray = Ray::new(Vec3::new(1.0, 1.0, -4.0), Vec3::Z);
        assert_eq!(unit_box().intersect(&ray), Some(3.0));
    }

    #[test]
    fn ray_parallel_to_a_face_just_outside_misses() {
        let ray = Ray::new(Vec3::new(-5.0, 1.0 + 1e-6, 0.0), Vec3::X);
        assert_eq!(unit_box().intersect(&ray), None);
    }

    #[test]
    fn box_rotated_90_about_y_equals_box_of_swapped_size() {
        let rotated = Cuboid::new(
            Vec3::ZERO,
            Vec3::new(4.0, 2.0, 1.0),
            Vec3::new(0.0, 90.0, 0.0),
        );
        let swapped = Cuboid::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 4.0), Vec3::ZERO);
        for (o, d) in [
            (Vec3::new(5.0, 0.1, 0.2), -Vec3::X),
            (Vec3::new(0.1, 0.3, -6.0), Vec3::Z),
            (Vec3::new(0.0, 5.0, 1.9), -Vec3::Y),
            (
                Vec3::new(3.0, 2.0, 5.0),
                Vec3::new(-0.4, -0.3, -1.0).normalize(),
            ),
        ] {
            let ray = Ray::new(o, d);
            let (a, b) = (rotated.intersect(&ray), swapped.intersect(&ray));
            let (a, b) = (a.expect("rotated hit"), b.expect("swapped hit"));
            assert!((a - b).abs() < 1e-5, "{a} {b}");
            let (sa, sb) = (rotated.surface(&ray, a), swapped.surface(&ray, b));
            assert!((sa.point - sb.point).length() < 1e-5);
            assert!((sa.normal - sb.normal).length() < 1e-5);
        }
    }

    #[test]
    fn translated_box_hits_where_expected() {
        let b = Cuboid::new(
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(2.0, 2.0, 2.0),
            Vec3::ZERO,
        );
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(b.intersect(&ray), Some(9.0));
        assert_eq!(b.surface(&ray, 9.0).normal, -Vec3::X);
    }

    #[test]
    fn the_bounding_sphere_only_skips_rays_that_miss() {
        for (k, (size, rotate)) in [
            (Vec3::splat(1.5), Vec3::ZERO),
            (Vec3::new(3.0, 0.1, 1.0), Vec3::new(30.0, 40.0, 50.0)),
        ]
        .into_iter()
        .enumerate()
        {
            let b = Cuboid::new(Vec3::new(2.3, 0.75, 0.0), size, rotate);
            let rejected = super::super::bound::testing::rays_around(&b.bound, k as u64, |ray| {
                assert_eq!(b.intersect(ray), b.intersect_exact(ray), "{ray:?}");
            });
            assert!(
                rejected > 3_000,
                "the bound turns clear misses away ({rejected})"
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
            center in any_vec(5.0),
            size in (0.1f32..3.0, 0.1f32..3.0, 0.1f32..3.0),
            rotate in any_vec(180.0),
            from in any_vec(1.0),
            target in any_vec(0.45),
            distance in 6.0f32..50.0,
            t_max in 1.0f32..100.0,
        ) {
            let size = Vec3::new(size.0, size.1, size.2);
            let b = Cuboid::new(center, size, rotate);
            let target = center + b.placement.vector_to_world(target * size);
            let origin = target + distance * from.try_normalize().unwrap_or(Vec3::X);
            let ray = Ray::new(origin, (target - origin).normalize()).with_t_max(t_max);
            let Some(alpha) = b.intersect(&ray) else {
                prop_assert!(t_max < distance);
                return Ok(());
            };
            prop_assert!(ray.contains(alpha));
            let s = b.surface(&ray, alpha);
            prop_assert!((s.point - ray.at(alpha)).length() < 1e-4 * distance.max(1.0));
            let local = b.placement.world_from_object.transpose() * (s.point - center);
            let residual = (local.abs() - b.half).max_element();
            prop_assert!(residual.abs() < 1e-5, "residual {residual}");
            prop_assert!((s.normal.length() - 1.0).abs() < 1e-5);
            prop_assert!(s.normal.dot(s.point - center) > 0.0);
            prop_assert!(s.normal.dot(ray.dir) < 0.0, "entry normal faces the ray");
            // Leaving along the outward normal from just outside never hits again.
            let away = Ray::new(s.point + 1e-3 * s.normal, s.normal);
            prop_assert_eq!(b.intersect(&away), None);
        }
    }
}
