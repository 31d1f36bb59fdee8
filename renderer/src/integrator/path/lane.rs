//! One path as a [`Lane`]: it waits for the closest hit of its next ray,
//! then for the shadow rays of its vertex. Its arithmetic never depends on
//! how the rays were traced, so one path traced alone
//! ([`super::path_recorded`]) and the same path traced in a batch with
//! others ([`crate::integrator::trace_samples()`]) give the same radiance bit
//! for bit.

use super::{RR_DEPTH, SHADOW_SHORTENING, power_heuristic};
use crate::geometry::offset::offset_ray_origin;
use crate::geometry::ray::Ray;
use crate::integrator::RenderOptions;
use crate::integrator::lanes::{Lane, Next, ShadowRay, ShadowTarget};
use crate::integrator::recorder::{EmitterLightSample, EnvironmentLightSample, Note, Recorder};
use crate::integrator::sampler::{BounceDraw, Sampler};
use crate::integrator::shading_context::ShadingContext;
use crate::shading::bsdf::{Bsdf, BsdfSample, ShadingFrame};
use crate::world::{Hit, World};
use glam::Vec3;

/// A path being traced: its radiance so far, its throughput and the ray it
/// waits on.
pub(crate) struct PathLane<N> {
    /// Radiance gathered so far.
    radiance: Vec3,
    throughput: Vec3,
    /// The ray whose closest hit the path waits for.
    ray: Ray,
    /// Where the ray started and the BSDF density it was drawn with; `None`
    /// for the camera ray and after a delta lobe (no light sample competes).
    previous: Option<(Vec3, f32)>,
    /// Product of refraction's radiance scaling, divided out for roulette.
    eta_scale: f32,
    /// Scattering events so far.
    depth: u32,
    sampler: Sampler,
    /// The recorder's handle to `ray`.
    node: N,
    /// The vertex whose shadow rays are out: its throughput, and the BSDF
    /// sample of the next ray (recorded once the shadow rays are).
    vertex: Option<PendingVertex>,
}

/// What a vertex keeps while its shadow rays are traced.
#[derive(Default)]
struct PendingVertex {
    /// The throughput arriving at the vertex, when it sampled lights (the
    /// light its shadow rays let through is scaled by it).
    lit_by: Option<Vec3>,
    /// The next ray's BSDF sample and throughput, when the path goes on.
    next: Option<(BsdfSample, Vec3)>,
}

/// A path between bounces, as the wavefront keeps a lane it hands to the
/// scalar code (a material it has no lanes for): everything `PathLane`
/// carries from one bounce to the next.
pub(crate) struct PathState {
    /// Radiance gathered so far.
    pub(crate) radiance: Vec3,
    /// Path throughput.
    pub(crate) throughput: Vec3,
    /// The ray whose closest hit the path waits for.
    pub(crate) ray: Ray,
    /// Where the ray started and its BSDF density (`None`: camera ray or delta lobe).
    pub(crate) previous: Option<(Vec3, f32)>,
    /// Product of refraction's radiance scaling.
    pub(crate) eta_scale: f32,
    /// Scattering events so far.
    pub(crate) depth: u32,
    /// The path's random stream.
    pub(crate) sampler: Sampler,
}

impl PathLane<()> {
    /// The path in `state`, waiting for the closest hit of its ray.
    pub(crate) fn resume(state: PathState) -> Self {
        Self {
            radiance: state.radiance,
            throughput: state.throughput,
            ray: state.ray,
            previous: state.previous,
            eta_scale: state.eta_scale,
            depth: state.depth,
            sampler: state.sampler,
            node: (),
            vertex: None,
        }
    }

    /// The path's state after [`Lane::finish`].
    pub(crate) fn into_state(self) -> PathState {
        debug_assert!(self.vertex.is_none(), "shadow rays still out");
        PathState {
            radiance: self.radiance,
            throughput: self.throughput,
            ray: self.ray,
            previous: self.previous,
            eta_scale: self.eta_scale,
            depth: self.depth,
            sampler: self.sampler,
        }
    }
}

impl<N: Copy> Lane<N> for PathLane<N> {
    /// A path starting with the camera ray `ray`, drawing from `sampler`.
    fn start<R: Recorder<Node = N>>(
        _: &RenderOptions,
        ray: Ray,
        sampler: Sampler,
        rec: &mut R,
    ) -> Self {
        Self {
            radiance: Vec3::ZERO,
            throughput: Vec3::ONE,
            ray,
            previous: None,
            eta_scale: 1.0,
            depth: 0,
            sampler,
            node: rec.primary(&ray),
            vertex: None,
        }
    }

    fn ray(&self) -> &Ray {
        &self.ray
    }

    fn radiance(&self) -> Vec3 {
        self.radiance
    }

    /// Adds emission, appends the vertex's shadow rays, and draws the next ray.
    fn shade<R: Recorder<Node = N>>(
        &mut self,
        world: &World,
        options: &RenderOptions,
        hit: Option<Hit>,
        shadows: &mut Vec<ShadowRay>,
        rec: &mut R,
    ) -> Next {
        let ray = self.ray;
        let Some(hit) = hit else {
            let seen = escaped(world, &ray, self.previous);
            self.radiance += self.throughput * seen;
            rec.miss(self.node, seen);
            return Next::Done;
        };
        let at = ShadingContext::new(world, &ray, &hit);
        rec.hit(self.node, &ray, hit, &at.surface, at.front);
        let material = at.material;
        if at.front && material.emission != Vec3::ZERO {
            let weight = match (self.previous, world.emitters.index_of(&hit)) {
                (Some((from, bsdf_pdf)), Some(index)) => power_heuristic(
                    bsdf_pdf,
                    world
                        .emitters
                        .pdf(from, index, at.point(), at.surface.normal),
                ),
                _ => 1.0,
            };
            self.radiance += self.throughput * weight * material.emission;
            rec.emission(self.node, material.emission, weight);
        }
        if self.depth + 1 >= options.max_depth {
            rec.note(self.node, Note::DepthLimit);
            return Next::Done;
        }
        let frame = ShadingFrame::new(at.shading_normal);
        let wo = frame.to_local(-ray.dir);
        let bsdf = at.bsdf();
        if bsdf.has_smooth() {
            self.sampler.seek_bounce(self.depth, BounceDraw::Light);
            light_samples(
                world,
                &at,
                frame,
                wo,
                &bsdf,
                self.depth,
                &mut self.sampler,
                shadows,
            );
            self.vertex = Some(PendingVertex {
                lit_by: Some(self.throughput),
                next: None,
            });
        }
        self.sampler.seek_bounce(self.depth, BounceDraw::Scatter);
        let u_lobe = self.sampler.next_f32();
        let Some(sample) = bsdf.sample(wo, u_lobe, self.sampler.next_2d()) else {
            rec.note(self.node, Note::Absorbed);
            return Next::Done;
        };
        let wi = frame.to_world(sample.wi);
        self.throughput *= sample.weight;
        self.eta_scale *= sample.radiance_scale;
        self.previous = (!sample.is_delta()).then_some((at.point(), sample.pdf));
        self.ray = at.spawn(wi);
        self.depth += 1;
        if self.depth >= RR_DEPTH {
            let keep = (self.throughput.max_element() / self.eta_scale).min(0.95);
            let survived = self.sampler.next_f32() < keep;
            rec.note(self.node, Note::Roulette { keep, survived });
            if !survived {
                return Next::Done;
            }
            self.throughput /= keep;
        }
        if !(self.throughput.max_element() > 0.0) {
            rec.note(self.node, Note::Absorbed);
            return Next::Done;
        }
        self.vertex.get_or_insert_default().next = Some((sample, self.throughput));
        Next::Trace
    }

    /// Adds the light of the shadow rays that nothing blocks; records them,
    /// then the next ray.
    fn finish<R: Recorder<Node = N>>(
        &mut self,
        shadows: &[ShadowRay],
        blocked: &[bool],
        rec: &mut R,
    ) {
        debug_assert_eq!(shadows.len(), blocked.len());
        let Some(vertex) = self.vertex.take() else {
            debug_assert!(shadows.is_empty());
            return;
        };
        let vertex_node = self.node;
        if let Some(throughput) = vertex.lit_by {
            let mut sum = Vec3::ZERO;
            for (shadow, &blocked) in shadows.iter().zip(blocked) {
                let lit = (!blocked).then_some(shadow.lit);
                if let Some(lit) = lit {
                    sum += lit;
                }
                match shadow.target {
                    ShadowTarget::Light(index) => {
                        rec.shadow(vertex_node, index, &shadow.ray, 1.0, lit);
                    }
                    ShadowTarget::Emitter(drawn) => {
                        rec.emitter_shadow(vertex_node, drawn, &shadow.ray, lit);
                    }
                    ShadowTarget::Environment(drawn) => {
                        rec.environment_shadow(vertex_node, drawn, &shadow.ray, lit);
                    }
                }
            }
            self.radiance += throughput * sum;
        }
        if let Some((sample, throughput)) = vertex.next {
            self.node = rec.scatter(vertex_node, &self.ray, self.depth, throughput, &sample);
        }
    }
}

/// What a ray that escapes the scene brings back: the sky's radiance in its
/// direction, weighted by the power heuristic against the sky's light
/// sample when the ray was drawn from a BSDF that competes with it
/// (`previous`: not the camera ray, not after a delta lobe). The wavefront
/// weighs sixteen at once the same way (`Environment::radiance_and_pdf_lanes`).
#[inline]
fn escaped(world: &World, ray: &Ray, previous: Option<(Vec3, f32)>) -> Vec3 {
    let environment = &world.environment;
    let (radiance, pdf) = environment.radiance_and_pdf(ray.dir);
    let weight = match previous {
        Some((_, bsdf_pdf)) if environment.is_sampled() => power_heuristic(bsdf_pdf, pdf),
        _ => 1.0,
    };
    weight * radiance
}

/// The shadow rays of a vertex with a smooth lobe: one toward every point
/// and directional light, then one toward a point drawn on the emitters,
/// then one toward a direction drawn from the sky's map, the last two weighted by
/// the power heuristic against BSDF sampling. Lights the BSDF does not
/// reflect toward the eye get no ray.
#[allow(clippy::too_many_arguments)]
fn light_samples(
    world: &World,
    at: &ShadingContext,
    frame: ShadingFrame,
    wo: Vec3,
    bsdf: &Bsdf,
    depth: u32,
    sampler: &mut Sampler,
    shadows: &mut Vec<ShadowRay>,
) {
    let point = at.point();
    // A shadow ray starts off the side its light is on (near a smooth
    // mesh's terminator, off the curved surface its normals describe); only
    // a transmitting BSDF sees lights behind the surface.
    let below = bsdf
        .transmits()
        .then(|| offset_ray_origin(point, -at.geometric, at.magnitude));
    let shadow_ray = |to_light: Vec3, distance: f32, reach: f32| {
        if at.lit_side(to_light) {
            Some(at.shadow_ray(to_light, distance, reach))
        } else {
            below.map(|origin| Ray::new(origin, to_light).with_t_max(distance * reach))
        }
    };
    for (index, light) in world.lights.iter().enumerate() {
        let Some(s) = light.sample(point) else {
            continue;
        };
        let Some(ray) = shadow_ray(s.to_light, s.distance, 1.0) else {
            continue;
        };
        let f = bsdf.eval(wo, frame.to_local(s.to_light));
        if f == Vec3::ZERO {
            continue;
        }
        shadows.push(ShadowRay {
            ray,
            lit: f * s.irradiance,
            target: ShadowTarget::Light(index),
        });
    }
    let u_select = sampler.next_f32();
    let u = sampler.next_2d();
    if let Some(s) = world.emitters.sample(point, u_select, u)
        && let Some(ray) = shadow_ray(s.to_light, s.distance, 1.0 - SHADOW_SHORTENING)
    {
        let wi = frame.to_local(s.to_light);
        let f = bsdf.eval(wo, wi);
        if f != Vec3::ZERO {
            let mis_weight = power_heuristic(s.pdf, bsdf.pdf(wo, wi));
            shadows.push(ShadowRay {
                ray,
                lit: f * s.radiance * (mis_weight / s.pdf),
                target: ShadowTarget::Emitter(EmitterLightSample {
                    index: s.index,
                    pdf: s.pdf,
                    mis_weight,
                }),
            });
        }
    }
    if !world.environment.is_sampled() {
        return;
    }
    sampler.seek_environment(depth);
    if let Some(s) = world.environment.sample(sampler.next_2d())
        && let Some(ray) = shadow_ray(s.dir, f32::INFINITY, 1.0)
    {
        let wi = frame.to_local(s.dir);
        let f = bsdf.eval(wo, wi);
        if f != Vec3::ZERO {
            let mis_weight = power_heuristic(s.pdf, bsdf.pdf(wo, wi));
            shadows.push(ShadowRay {
                ray,
                lit: f * s.radiance * (mis_weight / s.pdf),
                target: ShadowTarget::Environment(EnvironmentLightSample {
                    pdf: s.pdf,
                    mis_weight,
                }),
            });
        }
    }
}
