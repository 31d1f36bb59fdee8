//! Whitted's recursive ray tracer: ambient + Σ lights (shadow ray, Lambert +
//! Blinn-Phong), mirror reflection, and refraction with Fresnel and total
//! internal reflection.
//!
//! Whitted traces no glossy rays: a rough mirror or metal takes its lights'
//! light through its GGX lobe (exact for point and directional lights), the
//! ambient light in proportion to its roughness, and mirrors the scene
//! weighted by 1 − roughness; rough glass is traced as smooth glass.
//!
//! One integrator serves the image and the pixel inspector: it is generic
//! over a [`Recorder`], told about every ray beside the radiance computation.
//! The image uses [`NoRecorder`], whose empty calls compile away. It is
//! generic too over where its reflected, refracted and shadow rays get their
//! answers ([`Secondary`]): traced at once by the recursion, or — for the
//! film's batches of samples — recorded first, traced many at a time, and
//! handed back (`whitted_tree.rs`).

use super::RenderOptions;
use super::recorder::{NoRecorder, Note, RayKind, Recorder};
use super::shading_context::ShadingContext;
use crate::geometry::ray::Ray;
use crate::shading::bsdf::rough_conductor::RoughConductor;
use crate::shading::bsdf::{Bsdf, ShadingFrame, conductor_reflectance};
use crate::shading::optics::{fresnel_dielectric, reflect, refract};
use crate::world::{Hit, World};
use glam::Vec3;
use scene::BaseMaterial;
use std::f32::consts::PI;

/// The radiance arriving along `ray`, recursing at most `options.max_depth` bounces.
pub fn whitted(world: &World, ray: &Ray, options: &RenderOptions) -> Vec3 {
    whitted_recorded(world, ray, options, &mut NoRecorder)
}

/// [`whitted`], telling `recorder` about every ray it traces (the camera ray
/// `ray` first); the radiance is bit for bit the same for any recorder.
pub fn whitted_recorded<R: Recorder>(
    world: &World,
    ray: &Ray,
    options: &RenderOptions,
    recorder: &mut R,
) -> Vec3 {
    let node = recorder.primary(ray);
    trace(
        world,
        ray,
        options,
        Level::CAMERA,
        recorder,
        node,
        &mut Recursive,
    )
}

/// Where a ray is in its sample's tree: its bounces from the camera ray
/// and its weight in the pixel, the product of the factors of the
/// reflections and refractions that led to it (the camera ray's is 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Level {
    /// Bounces from the camera ray (0).
    pub(crate) depth: u32,
    /// The ray's radiance's factor in the sample's, channel by channel.
    pub(crate) weight: Vec3,
}

impl Level {
    /// The camera ray's.
    pub(crate) const CAMERA: Level = Level {
        depth: 0,
        weight: Vec3::ONE,
    };

    /// A reflected or refracted ray's, whose radiance counts `factor` times
    /// in this ray's.
    #[inline(always)]
    fn child(self, factor: Vec3) -> Level {
        Level {
            depth: self.depth + 1,
            weight: self.weight * factor,
        }
    }
}

/// Where a hit's reflected, refracted and shadow rays get their answers.
/// Whitted's shading asks for them in an order that depends only on the hit
/// (never on an answer), so they may be recorded first and answered later.
pub(crate) trait Secondary {
    /// The radiance arriving along the reflected or refracted ray `ray`, at
    /// `level` of its tree, recorded as `node`.
    fn radiance<R: Recorder>(
        &mut self,
        world: &World,
        ray: &Ray,
        options: &RenderOptions,
        level: Level,
        rec: &mut R,
        node: R::Node,
    ) -> Vec3;

    /// True when something blocks the shadow ray `ray`.
    fn occluded(&mut self, world: &World, ray: &Ray, options: &RenderOptions) -> bool;
}

/// Each ray traced when it is asked for: Whitted's recursion.
struct Recursive;

impl Secondary for Recursive {
    #[inline(always)]
    fn radiance<R: Recorder>(
        &mut self,
        world: &World,
        ray: &Ray,
        options: &RenderOptions,
        level: Level,
        rec: &mut R,
        node: R::Node,
    ) -> Vec3 {
        trace(world, ray, options, level, rec, node, self)
    }

    #[inline(always)]
    fn occluded(&mut self, world: &World, ray: &Ray, options: &RenderOptions) -> bool {
        world.occluded(ray, options.method)
    }
}

/// [`whitted`] of the camera ray `ray` whose closest hit `hit` is already
/// known (`None`: it escapes), as camera rays traced together find it (a
/// packet, or [`World::intersect_batch`]): the same radiance bit for bit,
/// the hit being [`World::intersect`]'s.
pub(crate) fn whitted_from_hit(
    world: &World,
    ray: &Ray,
    hit: Option<Hit>,
    options: &RenderOptions,
) -> Vec3 {
    shade(
        world,
        ray,
        hit,
        options,
        Level::CAMERA,
        &mut NoRecorder,
        (),
        &mut Recursive,
    )
}

/// [`whitted_from_hit`] of a camera ray that hit, with the hit's shading
/// context already made (its albedo perhaps found already, see
/// [`ShadingContext::with_albedo`]): the same radiance bit for bit.
pub(crate) fn whitted_from_context(
    world: &World,
    ray: &Ray,
    hit: Hit,
    at: &ShadingContext,
    options: &RenderOptions,
) -> Vec3 {
    shade_hit(
        world,
        ray,
        hit,
        at,
        options,
        Level::CAMERA,
        &mut NoRecorder,
        (),
        &mut Recursive,
    )
}

/// The radiance of the ray `ray`, at `level` of its tree, whose hit `hit`
/// has the shading context `at`, its reflected, refracted and shadow rays
/// asked of `secondary`: with the answers the recursion would give, the
/// radiance is [`whitted`]'s bit for bit.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn whitted_at_hit<S: Secondary>(
    world: &World,
    ray: &Ray,
    hit: Hit,
    at: &ShadingContext,
    options: &RenderOptions,
    level: Level,
    secondary: &mut S,
) -> Vec3 {
    shade_hit(
        world,
        ray,
        hit,
        at,
        options,
        level,
        &mut NoRecorder,
        (),
        secondary,
    )
}

/// The radiance of a ray in direction `dir` that hits nothing: the ambient
/// light and the sky in that direction.
#[inline]
pub(crate) fn background(world: &World, dir: Vec3) -> Vec3 {
    world.ambient + world.environment.radiance(dir)
}

/// The radiance along `ray`, traced at `level` of its tree.
fn trace<R: Recorder, S: Secondary>(
    world: &World,
    ray: &Ray,
    options: &RenderOptions,
    level: Level,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
) -> Vec3 {
    let hit = world.intersect(ray, options.method);
    shade(world, ray, hit, options, level, rec, node, secondary)
}

/// The radiance along `ray` (at `level` of its tree) whose closest hit is
/// `hit`: the background on a miss, else the hit shaded, recursing.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn shade<R: Recorder, S: Secondary>(
    world: &World,
    ray: &Ray,
    hit: Option<Hit>,
    options: &RenderOptions,
    level: Level,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
) -> Vec3 {
    let Some(hit) = hit else {
        let background = background(world, ray.dir);
        rec.miss(node, background);
        return background;
    };
    let at = ShadingContext::new(world, ray, &hit);
    shade_hit(world, ray, hit, &at, options, level, rec, node, secondary)
}

/// [`shade`] of a hit whose shading context `at` is made.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn shade_hit<R: Recorder, S: Secondary>(
    world: &World,
    ray: &Ray,
    hit: Hit,
    at: &ShadingContext,
    options: &RenderOptions,
    level: Level,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
) -> Vec3 {
    rec.hit(node, ray, hit, &at.surface, at.front);
    let (material, front, n) = (at.material, at.front, at.shading_normal);
    let mut radiance = if front { material.emission } else { Vec3::ZERO };
    rec.local(node, radiance);

    let can_recurse = level.depth < options.max_depth;
    // A reflected or refracted ray, recorded as `node`'s child carrying
    // `factor`. When its weight in the pixel is negligible (every channel
    // below `options.min_weight`) it is not traced but taken to see the
    // background, as if it escaped: a cut-off tree then keeps its energy
    // (clear glass in a uniform sky stays invisible).
    let bounce = |rec: &mut R, secondary: &mut S, kind: RayKind, dir: Vec3, factor: Vec3| {
        let child = level.child(factor);
        if child.weight.max_element() < options.min_weight {
            let seen = background(world, dir);
            rec.note(node, Note::Negligible);
            // What it adds to the sample, told to the recorder as `node`'s own.
            rec.local(node, factor * seen);
            return seen;
        }
        let next = at.spawn(dir);
        let child_node = rec.bounce(node, kind, &next, child.depth, factor);
        secondary.radiance(world, &next, options, child, rec, child_node)
    };

    // The hit as light from the point and directional lights shades it.
    let shading = |albedo| Shading {
        hit: at,
        albedo,
        to_eye: -ray.dir,
    };
    match material.base {
        BaseMaterial::Matte | BaseMaterial::Plastic | BaseMaterial::Marble => {
            let albedo = at.albedo();
            let diffuse_weight = 1.0 - material.reflectivity;
            rec.local(node, diffuse_weight * (albedo * world.shading_ambient()));
            let at = shading(albedo);
            radiance +=
                diffuse_weight * direct(world, options, &at, diffuse_weight, rec, node, secondary);
            if material.reflectivity > 0.0 {
                if can_recurse {
                    let factor = Vec3::splat(material.reflectivity);
                    let mirrored = bounce(
                        rec,
                        secondary,
                        RayKind::Reflection,
                        reflect(ray.dir, n),
                        factor,
                    );
                    radiance += material.reflectivity * mirrored;
                } else {
                    rec.note(node, Note::DepthLimit);
                }
            }
        }
        BaseMaterial::Mirror | BaseMaterial::Metal => {
            // A rough conductor (see `rough_conductor_direct`) mirrors 1 − roughness.
            let mut mirrored = 1.0;
            if let Bsdf::RoughConductor(conductor) = at.bsdf.at(at.color, front) {
                let roughness = material.roughness.clamp(0.0, 1.0);
                let at = shading(at.color);
                radiance += rough_conductor_direct(
                    world, options, &at, &conductor, roughness, rec, node, secondary,
                );
                mirrored = 1.0 - roughness;
            }
            if can_recurse {
                let metal = material.base == BaseMaterial::Metal;
                let reflectance =
                    mirrored * conductor_reflectance(at.color, metal, -ray.dir.dot(n));
                if reflectance != Vec3::ZERO {
                    radiance += reflectance
                        * bounce(
                            rec,
                            secondary,
                            RayKind::Reflection,
                            reflect(ray.dir, n),
                            reflectance,
                        );
                }
            } else {
                rec.note(node, Note::DepthLimit);
            }
        }
        BaseMaterial::Glass => {
            if can_recurse {
                // η = η_incident / η_transmitted; the ior is inside the shape.
                let eta = if front {
                    1.0 / material.ior
                } else {
                    material.ior
                };
                let fresnel = fresnel_dielectric(-ray.dir.dot(n), eta);
                let reflected = bounce(
                    rec,
                    secondary,
                    RayKind::Reflection,
                    reflect(ray.dir, n),
                    Vec3::splat(fresnel),
                );
                radiance += fresnel * reflected;
                if let Some(dir) = refract(ray.dir, n, eta) {
                    let tint = (1.0 - fresnel) * at.color;
                    let transmitted = bounce(rec, secondary, RayKind::Refraction, dir, tint);
                    radiance += (1.0 - fresnel) * at.color * transmitted;
                } else {
                    rec.note(node, Note::TotalInternalReflection);
                }
            } else {
                rec.note(node, Note::DepthLimit);
            }
        }
    }
    radiance
}

/// A hit as [`direct`] shades it.
struct Shading<'a> {
    /// The hit, with its normals turned toward the ray (shadow rays start
    /// off the geometric one).
    hit: &'a ShadingContext<'a>,
    albedo: Vec3,
    to_eye: Vec3,
}

/// Ambient plus direct light from every point and directional light that the
/// shadow ray finds unblocked: Lambert (albedo/π · E cos θ) plus a normalised
/// Blinn-Phong highlight. `scale` is the weight the caller gives the result,
/// told to the recorder with each shadow ray.
fn direct<R: Recorder, S: Secondary>(
    world: &World,
    options: &RenderOptions,
    at: &Shading,
    scale: f32,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
) -> Vec3 {
    let (material, albedo, n) = (at.hit.material, at.albedo, at.hit.shading_normal);
    let ambient = albedo * world.shading_ambient();
    ambient
        + lights(
            world,
            options,
            at,
            scale,
            rec,
            node,
            secondary,
            |to_light, irradiance| {
                let lambert = albedo / PI * irradiance;
                if material.specular > 0.0 {
                    let half = (to_light + at.to_eye).normalize_or_zero();
                    let lobe = n.dot(half).max(0.0).powf(material.shininess);
                    let normalisation = (material.shininess + 8.0) / (8.0 * PI);
                    lambert + material.specular * normalisation * lobe * irradiance
                } else {
                    lambert
                }
            },
        )
}

/// The light of every point and directional light whose shadow ray is
/// unblocked and which lies above the surface, as `shade(to_light, E cos θ)`
/// reflects it toward the eye; `scale` as in [`direct`].
#[allow(clippy::too_many_arguments)]
fn lights<R: Recorder, S: Secondary>(
    world: &World,
    options: &RenderOptions,
    at: &Shading,
    scale: f32,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
    shade: impl Fn(Vec3, Vec3) -> Vec3,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let (point, n) = (at.hit.point(), at.hit.shading_normal);
    for (index, light) in world.lights.iter().enumerate() {
        let Some(sample) = light.sample(point) else {
            continue;
        };
        let cos = n.dot(sample.to_light);
        if cos <= 0.0 {
            continue;
        }
        let shadow = at.hit.shadow_ray(sample.to_light, sample.distance, 1.0);
        if secondary.occluded(world, &shadow, options) {
            rec.shadow(node, index, &shadow, scale, None);
            continue;
        }
        let lit = shade(sample.to_light, sample.irradiance * cos);
        radiance += lit;
        rec.shadow(node, index, &shadow, scale, Some(lit));
    }
    radiance
}

/// A rough conductor's light from the point and directional lights through
/// its GGX lobe (exact for such lights), plus the ambient light scaled by
/// its reflectance and `roughness`: Whitted traces no glossy reflections,
/// so the caller mirrors the rest, weighted by 1 − roughness.
#[allow(clippy::too_many_arguments)]
fn rough_conductor_direct<R: Recorder, S: Secondary>(
    world: &World,
    options: &RenderOptions,
    at: &Shading,
    conductor: &RoughConductor,
    roughness: f32,
    rec: &mut R,
    node: R::Node,
    secondary: &mut S,
) -> Vec3 {
    let n = at.hit.shading_normal;
    let frame = ShadingFrame::new(n);
    let wo = frame.to_local(at.to_eye);
    let ambient = roughness * (conductor.f0 * world.shading_ambient());
    rec.local(node, ambient);
    ambient
        + lights(
            world,
            options,
            at,
            1.0,
            rec,
            node,
            secondary,
            |to_light, irradiance| {
                // eval includes cos θ_i; the irradiance passed in does too.
                let cos = n.dot(to_light);
                conductor.eval(wo, frame.to_local(to_light)) * irradiance / cos
            },
        )
}
