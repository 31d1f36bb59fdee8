//! Unbiased path tracing with next-event estimation and multiple importance
//! sampling (power heuristic), as Mitsuba 3's `path` integrator does it, so
//! that a render can be set up exactly like a Mitsuba reference:
//! - `max_depth` counts path segments as Mitsuba does: 1 = emitters seen
//!   directly, 2 = direct lighting, and so on;
//! - Russian roulette from the [`RR_DEPTH`]th scattering event on, keeping a
//!   path with probability min(0.95, max throughput channel), the radiance
//!   scaling of refraction divided out;
//! - emitters seen by a BSDF-sampled ray are weighted against the chance that
//!   light sampling finds them; point and directional lights (delta lights)
//!   are each sampled at every smooth vertex;
//! - no ambient term: only emitters, lights and the `<sky>` bring light.

use super::RenderOptions;
use super::recorder::{EmitterLightSample, NoRecorder, Note, Recorder};
use super::sampler::{BounceDraw, Sampler};
use super::shading_context::ShadingContext;
use crate::geometry::offset::offset_ray_origin;
use crate::geometry::ray::Ray;
use crate::shading::bsdf::{Bsdf, ShadingFrame};
use crate::shading::texture::albedo_at;
use crate::world::World;
use glam::Vec3;

/// The first scattering event counted by Russian roulette (Mitsuba's `rr_depth`).
pub const RR_DEPTH: u32 = 5;

/// A shadow ray toward an area light stops this fraction short of the
/// sampled point, so that it cannot hit the emitter itself.
const SHADOW_SHORTENING: f32 = 1.0e-4;

/// The power heuristic (β = 2): the weight of a sample drawn with density
/// `own` where another strategy would have drawn it with density `other`.
#[inline]
pub fn power_heuristic(own: f32, other: f32) -> f32 {
    let (a, b) = (own * own, other * other);
    if a + b > 0.0 && a.is_finite() {
        a / (a + b)
    } else if own > 0.0 {
        1.0
    } else {
        0.0
    }
}

/// The radiance arriving along the camera ray `ray`, one path traced with
/// the random numbers of `sampler`.
pub fn path(world: &World, ray: &Ray, options: &RenderOptions, sampler: &mut Sampler) -> Vec3 {
    path_recorded(world, ray, options, sampler, &mut NoRecorder)
}

/// [`path`], telling `rec` about every ray it traces (the camera ray `ray`
/// first), every emission it counts and every roulette decision; the
/// radiance is bit for bit the same for any recorder.
pub fn path_recorded<R: Recorder>(
    world: &World,
    ray: &Ray,
    options: &RenderOptions,
    sampler: &mut Sampler,
    rec: &mut R,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    let mut ray = *ray;
    let mut node = rec.primary(&ray);
    // Where the ray started and the BSDF density it was drawn with; `None`
    // for the camera ray and after a delta lobe (no light sample competes).
    let mut previous: Option<(Vec3, f32)> = None;
    // Product of refraction's radiance scaling, divided out for roulette.
    let mut eta_scale = 1.0f32;
    let mut depth = 0u32;
    loop {
        let Some(hit) = world.intersect(&ray, options.method) else {
            radiance += throughput * world.sky;
            rec.miss(node, world.sky);
            break;
        };
        let at = ShadingContext::new(world, &ray, &hit);
        rec.hit(node, &ray, hit, &at.surface, at.front);
        let material = &at.material;
        if at.front && material.emission != Vec3::ZERO {
            let weight = match (previous, world.emitters.index_of(&hit)) {
                (Some((from, bsdf_pdf)), Some(index)) => power_heuristic(
                    bsdf_pdf,
                    world
                        .emitters
                        .pdf(from, index, at.point(), at.surface.normal),
                ),
                _ => 1.0,
            };
            radiance += throughput * weight * material.emission;
            rec.emission(node, material.emission, weight);
        }
        if depth + 1 >= options.max_depth {
            rec.note(node, Note::DepthLimit);
            break;
        }
        let frame = ShadingFrame::new(at.shading_normal);
        let wo = frame.to_local(-ray.dir);
        let bsdf = Bsdf::new(material, albedo_at(material, at.point()), at.front);
        let vertex = Vertex {
            at: &at,
            frame,
            wo,
            bsdf,
        };
        if bsdf.has_smooth() {
            sampler.seek_bounce(depth, BounceDraw::Light);
            radiance += throughput * direct_light(world, options, &vertex, sampler, rec, node);
        }
        sampler.seek_bounce(depth, BounceDraw::Scatter);
        let u_lobe = sampler.next_f32();
        let Some(sample) = bsdf.sample(wo, u_lobe, sampler.next_2d()) else {
            rec.note(node, Note::Absorbed);
            break;
        };
        let wi = frame.to_world(sample.wi);
        throughput *= sample.weight;
        eta_scale *= sample.radiance_scale;
        previous = (!sample.is_delta()).then_some((at.point(), sample.pdf));
        ray = at.spawn(wi);
        depth += 1;
        if depth >= RR_DEPTH {
            let keep = (throughput.max_element() / eta_scale).min(0.95);
            let survived = sampler.next_f32() < keep;
            rec.note(node, Note::Roulette { keep, survived });
            if !survived {
                break;
            }
            throughput /= keep;
        }
        if !(throughput.max_element() > 0.0) {
            rec.note(node, Note::Absorbed);
            break;
        }
        node = rec.scatter(node, &ray, depth, throughput, &sample);
    }
    radiance
}

/// A scattering vertex as light sampling needs it.
struct Vertex<'a> {
    /// The hit, with its normals turned toward the ray.
    at: &'a ShadingContext,
    frame: ShadingFrame,
    /// Toward the previous vertex, local.
    wo: Vec3,
    bsdf: Bsdf,
}

/// Light reflected at `at` straight from a light: every point and
/// directional light, plus one point drawn on the emitters, weighted by the
/// power heuristic against BSDF sampling. Each shadow ray is told to `rec`
/// as a child of `node`.
fn direct_light<R: Recorder>(
    world: &World,
    options: &RenderOptions,
    vertex: &Vertex,
    sampler: &mut Sampler,
    rec: &mut R,
    node: R::Node,
) -> Vec3 {
    let (at, point) = (vertex.at, vertex.at.point());
    let mut sum = Vec3::ZERO;
    // A shadow ray starts off the side its light is on; only a transmitting
    // BSDF sees lights behind the surface.
    let above = offset_ray_origin(point, at.geometric, at.magnitude);
    let below = vertex
        .bsdf
        .transmits()
        .then(|| offset_ray_origin(point, -at.geometric, at.magnitude));
    let origin_toward = |to_light: Vec3| {
        if to_light.dot(at.geometric) > 0.0 {
            Some(above)
        } else {
            below
        }
    };
    for (index, light) in world.lights.iter().enumerate() {
        let Some(s) = light.sample(point) else {
            continue;
        };
        let Some(origin) = origin_toward(s.to_light) else {
            continue;
        };
        let f = vertex
            .bsdf
            .eval(vertex.wo, vertex.frame.to_local(s.to_light));
        if f == Vec3::ZERO {
            continue;
        }
        let shadow = Ray::new(origin, s.to_light).with_t_max(s.distance);
        if world.occluded(&shadow, options.method) {
            rec.shadow(node, index, &shadow, 1.0, None);
        } else {
            let lit = f * s.irradiance;
            sum += lit;
            rec.shadow(node, index, &shadow, 1.0, Some(lit));
        }
    }
    let u_select = sampler.next_f32();
    let u = sampler.next_2d();
    if let Some(s) = world.emitters.sample(point, u_select, u)
        && let Some(origin) = origin_toward(s.to_light)
    {
        let wi = vertex.frame.to_local(s.to_light);
        let f = vertex.bsdf.eval(vertex.wo, wi);
        if f != Vec3::ZERO {
            let shadow =
                Ray::new(origin, s.to_light).with_t_max(s.distance * (1.0 - SHADOW_SHORTENING));
            let mis_weight = power_heuristic(s.pdf, vertex.bsdf.pdf(vertex.wo, wi));
            let drawn = EmitterLightSample {
                emitter: s.index,
                pdf: s.pdf,
                mis_weight,
            };
            if world.occluded(&shadow, options.method) {
                rec.emitter_shadow(node, drawn, &shadow, None);
            } else {
                let lit = f * s.radiance * (mis_weight / s.pdf);
                sum += lit;
                rec.emitter_shadow(node, drawn, &shadow, Some(lit));
            }
        }
    }
    sum
}
