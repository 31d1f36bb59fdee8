//! What both integrators know about a hit before they shade it: the surface
//! point, the material there, which side the ray came from, the normals
//! turned to that side, and how far secondary rays must start off the
//! surface.

use crate::geometry::offset::offset_ray_origin;
use crate::geometry::ray::Ray;
use crate::shapes::Surface;
use crate::world::{Hit, World};
use glam::Vec3;
use scene::Material;

/// A ray's hit, ready to shade.
#[derive(Clone, Copy, Debug)]
pub struct ShadingContext {
    /// The hit point and the shape's own (outward) geometric normal.
    pub surface: Surface,
    /// The material at the hit (a mesh's texture applied).
    pub material: Material,
    /// True when the ray arrived on the side the geometric normal faces.
    pub front: bool,
    /// The unit geometric normal on the side the ray came from.
    pub geometric: Vec3,
    /// The unit shading normal (interpolated on meshes) on that side.
    pub shading_normal: Vec3,
    /// The largest coordinate of the object hit ([`World::magnitude`]):
    /// secondary rays start off the surface by an offset that scales with it.
    pub magnitude: f32,
}

impl ShadingContext {
    /// The context of `hit`, which `ray` found in `world`. Which side the
    /// ray came from follows the geometric normal; the shading normal is
    /// turned to that side.
    pub fn new(world: &World, ray: &Ray, hit: Hit) -> Self {
        let surface = world.surface(ray, hit);
        let front = ray.dir.dot(surface.normal) < 0.0;
        let shading_normal = world.shading_normal(hit, &surface);
        let toward_ray = |n: Vec3| if front { n } else { -n };
        Self {
            surface,
            material: world.material(hit),
            front,
            geometric: toward_ray(surface.normal),
            shading_normal: toward_ray(shading_normal),
            magnitude: world.magnitude(hit.object),
        }
    }

    /// The hit point.
    pub fn point(&self) -> Vec3 {
        self.surface.point
    }

    /// The ray leaving the hit point in direction `dir`, starting just off
    /// the side of the surface that `dir` goes to.
    pub fn spawn(&self, dir: Vec3) -> Ray {
        let side = if dir.dot(self.geometric) >= 0.0 {
            self.geometric
        } else {
            -self.geometric
        };
        Ray::new(
            offset_ray_origin(self.surface.point, side, self.magnitude),
            dir,
        )
    }
}
