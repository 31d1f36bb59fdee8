//! Where a shape stands: a rigid placement, rotation then translation
//! (world_from_object), mapping rays into the shape's own space and its hit
//! points and normals back.

use crate::geometry::ray::Ray;
use crate::shapes::Surface;
use glam::{Mat3, Vec3};

/// world_from_object = translate(origin) · rotation. Rotations preserve length,
/// so α along a ray is the same in object and world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The rotation part of world_from_object (orthonormal).
    pub world_from_object: Mat3,
    /// Where the object's origin (its centre or base) is in the world.
    pub origin: Vec3,
}

impl Placement {
    /// A placement at `origin` rotated by `rotate_deg` degrees about x, then y, then z.
    pub fn from_euler_degrees(origin: Vec3, rotate_deg: Vec3) -> Self {
        let r = rotate_deg * (std::f32::consts::PI / 180.0);
        let world_from_object =
            Mat3::from_rotation_z(r.z) * Mat3::from_rotation_y(r.y) * Mat3::from_rotation_x(r.x);
        Self {
            world_from_object,
            origin,
        }
    }

    /// A placement at `origin` with no rotation.
    pub fn at(origin: Vec3) -> Self {
        Self {
            world_from_object: Mat3::IDENTITY,
            origin,
        }
    }

    /// The ray in object space (same α interval).
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        let object_from_world = self.world_from_object.transpose();
        Ray {
            origin: object_from_world * (ray.origin - self.origin),
            dir: object_from_world * ray.dir,
            ..*ray
        }
    }

    /// A world-space point in object space.
    pub fn point_to_object(&self, p: Vec3) -> Vec3 {
        self.world_from_object.transpose() * (p - self.origin)
    }

    /// An object-space point in world space.
    pub fn point_to_world(&self, p: Vec3) -> Vec3 {
        self.world_from_object * p + self.origin
    }

    /// An object-space hit point and unit normal in world space.
    pub fn surface_to_world(&self, point: Vec3, normal: Vec3) -> Surface {
        let surface = Surface {
            point: self.point_to_world(point),
            normal: self.vector_to_world(normal),
        };
        debug_assert!(
            surface.point.is_finite() && surface.normal.is_finite(),
            "{surface:?}"
        );
        surface
    }

    /// An object-space direction or normal in world space (rotation only).
    pub fn vector_to_world(&self, v: Vec3) -> Vec3 {
        self.world_from_object * v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_order_is_x_then_y_then_z() {
        // Rotating +y by 90° about x gives +z; then 90° about y turns +z into +x.
        let f = Placement::from_euler_degrees(Vec3::ZERO, Vec3::new(90.0, 90.0, 0.0));
        let v = f.vector_to_world(Vec3::Y);
        assert!((v - Vec3::X).length() < 1e-6, "{v}");
    }

    #[test]
    fn ray_round_trips_through_object_space() {
        let f =
            Placement::from_euler_degrees(Vec3::new(1.0, 2.0, 3.0), Vec3::new(10.0, 20.0, 30.0));
        let ray = Ray::new(Vec3::new(-4.0, 5.0, 6.0), Vec3::new(0.6, 0.0, 0.8));
        let local = f.ray_to_object(&ray);
        let back = f.point_to_world(local.at(2.5));
        assert!((back - ray.at(2.5)).length() < 1e-5);
    }
}
