//! PLACEHOLDER (being written): torus.
use super::Surface;
use crate::ray::Ray;
use glam::Vec3;
/// An torus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus;
impl Torus {
    /// A box.
    pub fn new(_center: Vec3, _major: f32, _minor: f32, _rotate_deg: Vec3) -> Self {
        Torus
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
