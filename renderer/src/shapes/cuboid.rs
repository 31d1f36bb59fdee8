//! PLACEHOLDER (being written): oriented box.
use super::Surface;
use crate::ray::Ray;
use glam::Vec3;
/// An oriented box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid;
impl Cuboid {
    /// A box.
    pub fn new(_center: Vec3, _size: Vec3, _rotate_deg: Vec3) -> Self {
        Cuboid
    }
    /// α of the nearest hit.
    pub fn intersect(&self, _ray: &Ray) -> Option<f32> {
        None
    }
    /// Hit surface.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        Surface {
            point: ray.at(alpha),
            normal: Vec3::Y,
        }
    }
}
