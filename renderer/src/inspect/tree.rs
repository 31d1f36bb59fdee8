//! The recorder that keeps every ray the Whitted integrator traces as a
//! node of a flat tree, with its weight and contribution.

use super::node::{
    Barycentrics, Blocker, MaterialInfo, ObjectRef, RayNode, Roulette, Scatter, ShadowTarget,
    ShadowTest, SurfaceHit,
};
use crate::geometry::ray::Ray;
use crate::integrator::recorder::{EmitterLightSample, EnvironmentLightSample};
use crate::integrator::{Note, RayKind, Recorder};
use crate::shading::bsdf::BsdfSample;
use crate::shapes::{Method, Shape, Surface};
use crate::world::{Hit, World};
use glam::Vec3;

/// Records the ray tree of one sample; node handles are indices into `rays`.
pub(super) struct TreeRecorder<'w> {
    world: &'w World,
    method: Method,
    /// The rays in the order they were traced (parents before children).
    pub(super) rays: Vec<RayNode>,
}

impl<'w> TreeRecorder<'w> {
    /// An empty tree for rays traced in `world` with `method`.
    pub(super) fn new(world: &'w World, method: Method) -> Self {
        Self {
            world,
            method,
            rays: Vec::new(),
        }
    }

    fn push(&mut self, node: RayNode) -> usize {
        self.rays.push(node);
        self.rays.len() - 1
    }

    fn object(&self, index: u32) -> ObjectRef {
        ObjectRef {
            index,
            name: self.world.names[index as usize].clone(),
        }
    }
}

/// A node for `ray` with nothing hit and nothing contributed yet.
fn node(kind: RayKind, parent: Option<usize>, depth: u32, ray: &Ray, weight: Vec3) -> RayNode {
    RayNode {
        kind,
        parent,
        depth,
        origin: ray.origin,
        direction: ray.dir,
        t_max: ray.t_max,
        weight,
        contribution: Vec3::ZERO,
        hit: None,
        shadow: None,
        scatter: None,
    }
}

impl Recorder for TreeRecorder<'_> {
    type Node = usize;

    fn primary(&mut self, ray: &Ray) -> usize {
        self.push(node(RayKind::Primary, None, 0, ray, Vec3::ONE))
    }

    fn bounce(
        &mut self,
        parent: usize,
        kind: RayKind,
        ray: &Ray,
        depth: u32,
        factor: Vec3,
    ) -> usize {
        let weight = self.rays[parent].weight * factor;
        self.push(node(kind, Some(parent), depth, ray, weight))
    }

    fn miss(&mut self, at: usize, radiance: Vec3) {
        self.local(at, radiance);
    }

    fn hit(&mut self, at: usize, ray: &Ray, hit: Hit, surface: &Surface, front: bool) {
        let shape = self.world.shape(hit.object);
        let material = &self.world.material(hit);
        let (barycentrics, sphere) = match shape {
            None => (
                hit.triangle.map(|t| Barycentrics {
                    beta: t.beta,
                    gamma: t.gamma,
                }),
                None,
            ),
            Some(Shape::Triangle(t)) => (
                t.hit(ray, self.method).map(|h| Barycentrics {
                    beta: h.beta,
                    gamma: h.gamma,
                }),
                None,
            ),
            Some(Shape::Sphere(s)) => (None, Some(s.quadratic(ray, self.method))),
            _ => (None, None),
        };
        self.rays[at].hit = Some(SurfaceHit {
            object: self.object(hit.object),
            shape: shape.map_or("mesh triangle", Shape::kind_name),
            alpha: hit.alpha,
            point: surface.point,
            normal: surface.normal,
            front,
            material: MaterialInfo {
                base: material.base.name(),
                color: material.color,
                reflectivity: material.reflectivity,
                ior: material.ior,
                roughness: material.roughness,
                emission: material.emission,
            },
            barycentrics,
            sphere,
            depth_limited: false,
            total_internal_reflection: false,
            negligible: false,
            emission_weight: None,
            roulette: None,
            absorbed: false,
        });
    }

    fn local(&mut self, at: usize, radiance: Vec3) {
        let node = &mut self.rays[at];
        node.contribution += node.weight * radiance;
    }

    fn shadow(&mut self, at: usize, light: usize, ray: &Ray, scale: f32, lit: Option<Vec3>) {
        self.push_shadow(at, ShadowTarget::Light(light), ray, scale, lit);
    }

    fn note(&mut self, at: usize, note: Note) {
        if let Some(hit) = &mut self.rays[at].hit {
            match note {
                Note::DepthLimit => hit.depth_limited = true,
                Note::TotalInternalReflection => hit.total_internal_reflection = true,
                Note::Negligible => hit.negligible = true,
                Note::Roulette { keep, survived } => {
                    hit.roulette = Some(Roulette { keep, survived });
                }
                Note::Absorbed => hit.absorbed = true,
            }
        }
    }

    fn emission(&mut self, at: usize, radiance: Vec3, mis_weight: f32) {
        self.local(at, mis_weight * radiance);
        if let Some(hit) = &mut self.rays[at].hit {
            hit.emission_weight = Some(mis_weight);
        }
    }

    fn scatter(
        &mut self,
        parent: usize,
        ray: &Ray,
        depth: u32,
        throughput: Vec3,
        sample: &BsdfSample,
    ) -> usize {
        // Local directions: z > 0 is the side the path arrived from.
        let kind = if sample.wi.z > 0.0 {
            RayKind::Reflection
        } else {
            RayKind::Refraction
        };
        let mut child = node(kind, Some(parent), depth, ray, throughput);
        child.scatter = Some(Scatter {
            lobe: sample.lobe,
            pdf: sample.pdf,
            bsdf_weight: sample.weight,
        });
        self.push(child)
    }

    fn emitter_shadow(
        &mut self,
        at: usize,
        sample: EmitterLightSample,
        ray: &Ray,
        lit: Option<Vec3>,
    ) {
        self.push_shadow(at, ShadowTarget::Emitter(sample), ray, 1.0, lit);
    }

    fn environment_shadow(
        &mut self,
        at: usize,
        sample: EnvironmentLightSample,
        ray: &Ray,
        lit: Option<Vec3>,
    ) {
        self.push_shadow(at, ShadowTarget::Environment(sample), ray, 1.0, lit);
    }
}

impl TreeRecorder<'_> {
    /// A shadow ray from `at`'s hit toward `target`, weighted by `at`'s
    /// weight × `scale`; `lit` is what it lets through, `None` when blocked.
    fn push_shadow(
        &mut self,
        at: usize,
        target: ShadowTarget,
        ray: &Ray,
        scale: f32,
        lit: Option<Vec3>,
    ) {
        let (weight, depth) = (self.rays[at].weight * scale, self.rays[at].depth);
        // The integrator's test is any-hit; the nearest blocker is found here only.
        let blocker = match lit {
            Some(_) => None,
            None => self.world.intersect(ray, self.method).map(|h| Blocker {
                object: self.object(h.object),
                alpha: h.alpha,
            }),
        };
        let mut shadow = node(RayKind::Shadow, Some(at), depth, ray, weight);
        shadow.contribution = lit.map_or(Vec3::ZERO, |l| weight * l);
        shadow.shadow = Some(ShadowTest {
            target,
            blocked: lit.is_none(),
            blocker,
        });
        self.push(shadow);
    }
}
