//! What both integrators know about a hit before they shade it: the surface
//! point, the material there, which side the ray came from, the normals
//! turned to that side, and where secondary and shadow rays start off the
//! surface.

use crate::geometry::offset::offset_ray_origin;
use crate::geometry::ray::Ray;
use crate::geometry::terminator::ShadowStart;
use crate::shading::bsdf::{Bsdf, PreparedBsdf};
use crate::shading::texture::albedo_at;
use crate::shapes::Surface;
use crate::world::{Hit, HitSurface, World};
use glam::Vec3;
use scene::Material;

/// A ray's hit, ready to shade.
#[derive(Clone, Copy, Debug)]
pub struct ShadingContext<'w> {
    /// The hit point and the shape's own (outward) geometric normal.
    pub surface: Surface,
    /// The material of the object (or mesh instance) hit; its colour
    /// before a texture, see `color`.
    pub material: &'w Material,
    /// The material's colour at the hit (a mesh's texture applied).
    pub color: Vec3,
    /// The material's BSDF as prepared with the world (the colour at the
    /// hit and `front` still to add).
    pub bsdf: &'w PreparedBsdf,
    /// True when the ray arrived on the side the geometric normal faces.
    pub front: bool,
    /// The unit geometric normal on the side the ray came from.
    pub geometric: Vec3,
    /// The unit shading normal (interpolated on meshes) on that side.
    pub shading_normal: Vec3,
    /// The largest coordinate of the object hit ([`World::magnitude`]):
    /// secondary rays start off the surface by an offset that scales with it.
    pub magnitude: f32,
    /// On a mesh hit from the side its normals face, Hanika's point on the
    /// surface those normals describe: shadow rays toward lights near or
    /// below the flat triangle start there ([`ShadingContext::shadow_ray`]).
    pub curved_point: Option<Vec3>,
    /// The albedo when a caller found it already ([`ShadingContext::with_albedo`]).
    known_albedo: Option<Vec3>,
}

impl<'w> ShadingContext<'w> {
    /// The context of `hit`, which `ray` found in `world`. Which side the
    /// ray came from follows the geometric normal; the shading normal is
    /// turned to that side.
    ///
    /// Inlined into the integrators, with the hit by reference: taking it by
    /// value made each call copy the hit with wide stores just after
    /// `World::intersect` wrote it with narrow ones, and the stalled loads
    /// cost 4–5% of a Whitted pass of `seed.xml` (same instruction count).
    #[inline(always)]
    pub fn new(world: &'w World, ray: &Ray, hit: &Hit) -> Self {
        let HitSurface {
            surface,
            shading_normal,
            material,
            color,
            bsdf,
            curved_point,
        } = world.hit_surface(ray, hit);
        let front = ray.dir.dot(surface.normal) < 0.0;
        let toward_ray = |n: Vec3| if front { n } else { -n };
        Self {
            surface,
            material,
            color,
            bsdf,
            front,
            geometric: toward_ray(surface.normal),
            shading_normal: toward_ray(shading_normal),
            magnitude: world.magnitude(hit.object),
            curved_point: curved_point.filter(|_| front),
            known_albedo: None,
        }
    }

    /// This context with its albedo given: what [`ShadingContext::albedo`]
    /// would compute, found by a caller that evaluates the marble texture
    /// of many hits at once.
    #[inline]
    pub fn with_albedo(self, albedo: Vec3) -> Self {
        Self {
            known_albedo: Some(albedo),
            ..self
        }
    }

    /// The albedo at the hit: the colour, or for marble the solid texture
    /// through it.
    #[inline]
    pub fn albedo(&self) -> Vec3 {
        match self.known_albedo {
            Some(albedo) => albedo,
            None => albedo_at(self.material.base, self.color, self.point()),
        }
    }

    /// The BSDF at the hit.
    #[inline]
    pub fn bsdf(&self) -> Bsdf {
        self.bsdf.at(self.albedo(), self.front)
    }

    /// The hit point.
    pub fn point(&self) -> Vec3 {
        self.surface.point
    }

    /// True when light from `to_light` reaches the side the ray came from
    /// (a shadow ray toward it is [`ShadingContext::shadow_ray`]): the light
    /// lies above the geometric normal, or, on a mesh seen from the side its
    /// normals face, above the shading normal, as on the curved surface
    /// those normals describe.
    #[inline]
    pub fn lit_side(&self, to_light: Vec3) -> bool {
        to_light.dot(self.geometric) > 0.0
            || (self.curved_point.is_some() && to_light.dot(self.shading_normal) > 0.0)
    }

    /// The shadow ray, on the side the ray came from, toward the light
    /// `distance` along `to_light` from the hit point (∞ for light from
    /// infinitely far), ending at `reach` of the way there: off the hit
    /// point, or near a smooth-shaded mesh's terminator off the curved
    /// surface ([`ShadowStart::ray`]).
    #[inline]
    pub fn shadow_ray(&self, to_light: Vec3, distance: f32, reach: f32) -> Ray {
        ShadowStart {
            point: self.surface.point,
            geometric: self.geometric,
            magnitude: self.magnitude,
            curved: self.curved_point,
        }
        .ray(to_light, distance, reach)
    }

    /// The ray leaving the hit point in direction `dir`, starting just off
    /// the side of the surface that `dir` goes to.
    #[inline]
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
