//! The infinite plane: the lecture's ray–plane step on its own.

use super::Surface;
use crate::geometry::ray::Ray;
use glam::Vec3;

/// The plane of points q with n · (q − s) = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// s, a point on the plane.
    pub point: Vec3,
    /// n, the unit normal.
    pub normal: Vec3,
}

impl Plane {
    /// The plane through `point` with normal `normal` (normalised here; zero becomes +y).
    pub fn new(point: Vec3, normal: Vec3) -> Self {
        Self {
            point,
            normal: normal.try_normalize().unwrap_or(Vec3::Y),
        }
    }

    /// α = n · (s − P0) / (n · v); a ray parallel to the plane misses (also
    /// when it lies in it, as in the lecture).
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None;
        }
        let alpha = self.normal.dot(self.point - ray.origin) / denom;
        ray.contains(alpha).then_some(alpha)
    }

    /// The hit point projected onto the plane, and n.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let p = ray.at(alpha);
        let point = p - self.normal * self.normal.dot(p - self.point);
        Surface {
            point,
            normal: self.normal,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_toward_plane_hits_at_height_over_cosine() {
        let plane = Plane::new(Vec3::ZERO, Vec3::Y);
        let ray = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.6, -0.8, 0.0));
        let alpha = plane.intersect(&ray).expect("hit");
        assert!((alpha - 2.5).abs() < 1e-6);
        assert!(plane.surface(&ray, alpha).point.y == 0.0);
    }

    #[test]
    fn parallel_ray_misses_even_inside_the_plane() {
        let plane = Plane::new(Vec3::ZERO, Vec3::Y);
        assert_eq!(
            plane.intersect(&Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X)),
            None
        );
        assert_eq!(plane.intersect(&Ray::new(Vec3::ZERO, Vec3::X)), None);
    }

    #[test]
    fn plane_behind_the_ray_misses() {
        let plane = Plane::new(Vec3::ZERO, Vec3::Y);
        assert_eq!(
            plane.intersect(&Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::Y)),
            None
        );
    }
}
