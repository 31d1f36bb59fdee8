//! PLACEHOLDER (being written): cone.
use super::Surface;
use crate::ray::Ray;
use glam::Vec3;
/// An cone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone;
impl Cone {
    /// A box.
    pub fn new(_base: Vec3, _radius: f32, _height: f32, _rotate_deg: Vec3) -> Self {
        Cone
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
