//! Everything shading needs from the object a ray hit, looked up in one go:
//! a mesh's instance and triangle are found once for the point, both
//! normals, the colour and the curved surface's point, and the material is
//! lent, not copied.

use super::{Hit, World};
use crate::geometry::ray::Ray;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::Surface;
use glam::Vec3;
use scene::Material;

/// The surface at a hit and what it is made of.
#[derive(Clone, Copy, Debug)]
pub struct HitSurface<'w> {
    /// The hit point and the shape's own (outward) geometric normal.
    pub surface: Surface,
    /// The normal to shade with (interpolated on meshes), not yet turned
    /// toward the ray.
    pub shading_normal: Vec3,
    /// The object's or mesh instance's material; its colour is `color`'s
    /// before a texture.
    pub material: &'w Material,
    /// The material's colour at the hit (a mesh's texture applied).
    pub color: Vec3,
    /// The material's BSDF as prepared with the world.
    pub bsdf: &'w PreparedBsdf,
    /// On a mesh, Hanika's point on the surface its vertex normals describe
    /// (`geometry::terminator`), where shadow rays near the terminator
    /// start; `None` on analytic shapes, whose normals are their surface's.
    pub curved_point: Option<Vec3>,
}

impl World {
    /// The surface, normals, material and prepared BSDF at `hit`, which
    /// `ray` found: [`World::surface`], [`World::shading_normal`] and
    /// [`World::material`]'s colour, bit for bit.
    #[inline(always)]
    pub fn hit_surface(&self, ray: &Ray, hit: &Hit) -> HitSurface<'_> {
        match hit.triangle {
            Some(t) => {
                let mesh = &self.meshes[t.instance as usize];
                let at = mesh.shading_point(&t.mesh_hit(hit.alpha));
                HitSurface {
                    surface: at.surface,
                    shading_normal: at.shading_normal,
                    material: &mesh.material,
                    color: at.color,
                    bsdf: &mesh.bsdf,
                    curved_point: Some(at.curved_point),
                }
            }
            None => {
                let surface = self.analytic(hit.object).surface(ray, hit.alpha);
                let material = &self.materials[hit.object as usize];
                HitSurface {
                    surface,
                    shading_normal: surface.normal,
                    material,
                    color: material.color,
                    bsdf: &self.bsdfs[hit.object as usize],
                    curved_point: None,
                }
            }
        }
    }
}
