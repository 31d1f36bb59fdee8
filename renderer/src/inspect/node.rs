//! The nodes of a ray tree: one traced ray each, with what it hit or what
//! blocked it, its weight and the colour it adds to the sample.

use crate::integrator::RayKind;
use crate::integrator::recorder::{EmitterLightSample, EnvironmentLightSample};
use crate::shading::bsdf::Lobe;
use crate::shapes::SphereQuadratic;
use glam::Vec3;
use serde::Serialize;

/// One ray of an [`Inspection`](super::Inspection)'s tree.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayNode {
    /// What the ray is for.
    pub kind: RayKind,
    /// The index in [`Inspection::rays`](super::Inspection::rays) of the ray
    /// whose hit spawned this one; `None` for the primary ray R_ij.
    pub parent: Option<usize>,
    /// Bounces before this ray: 0 for R_ij and for the shadow rays of its
    /// hit, 1 for what its reflection or refraction finds, and so on.
    pub depth: u32,
    /// P0 of the ray: the viewpoint, or a hit point moved off its surface.
    pub origin: Vec3,
    /// v, the unit direction.
    pub direction: Vec3,
    /// Hits at α ≥ t_max are ignored: the light's distance for a shadow ray,
    /// ∞ otherwise (`null` in JSON).
    pub t_max: f32,
    /// The throughput from the camera: Whitted's product of the
    /// reflectivity, reflectance and Fresnel factors along the path, and
    /// (1 − reflectivity) for a shadow ray; the path tracer's throughput
    /// (Π f·cos/pdf, Russian roulette's divisions included). The sample's
    /// colour gains weight × what this ray brings.
    pub weight: Vec3,
    /// The colour this ray adds to the sample: weight × its local term
    /// (emission + ambient·albedo·(1 − reflectivity) at a hit, the ambient
    /// background on a miss, Lambert + specular through an unblocked shadow
    /// ray). The contributions of all rays add up to the sample's colour.
    pub contribution: Vec3,
    /// What a primary, reflected or refracted ray hit; `None` on a miss and
    /// for shadow rays.
    #[serde(flatten)]
    pub hit: Option<SurfaceHit>,
    /// The light test of a shadow ray; `None` for other rays.
    #[serde(flatten)]
    pub shadow: Option<ShadowTest>,
    /// How the path tracer drew this ray from its parent's BSDF; `None` for
    /// primary, shadow and Whitted rays.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scatter: Option<Scatter>,
}

/// A path tracer's bounce: the BSDF sample that chose a ray's direction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scatter {
    /// The lobe the direction was drawn from.
    pub lobe: Lobe,
    /// Its density in solid angle (0 for a delta lobe).
    pub pdf: f32,
    /// f · |cos θ_i| / pdf, what the throughput was multiplied by (before
    /// any Russian roulette division).
    pub bsdf_weight: Vec3,
}

/// The path tracer's Russian roulette at a hit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Roulette {
    /// The probability that the path went on.
    pub keep: f32,
    /// Whether it did.
    pub survived: bool,
}

/// An object of the scene: its index (object id) and name.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ObjectRef {
    /// The object's index in the world (its object id).
    pub index: u32,
    /// The object's name (`<tag> <index>` when the scene gave none).
    pub name: String,
}

/// What a ray hit, with the intersection's unknowns as the lecture names them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurfaceHit {
    /// The object hit.
    pub object: ObjectRef,
    /// Its shape's kind ("sphere", "triangle", "box", …).
    pub shape: &'static str,
    /// α, the distance along the ray: the hit is P0 + α v.
    pub alpha: f32,
    /// The hit point, placed on the surface.
    pub point: Vec3,
    /// The unit geometric normal (outward for closed shapes, along
    /// (t1 − t0) × (t2 − t0) for triangles).
    pub normal: Vec3,
    /// True when the ray arrived against the normal (v · n < 0).
    pub front: bool,
    /// The object's material.
    pub material: MaterialInfo,
    /// β and γ of a triangle hit: P0 + α v = t0 + β v1 + γ v2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub barycentrics: Option<Barycentrics>,
    /// A sphere's quadratic in α: coefficients and both roots.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sphere: Option<SphereQuadratic>,
    /// A reflection or refraction would have followed but `max_depth` stopped it.
    pub depth_limited: bool,
    /// Glass reflected everything here: no refracted ray (total internal reflection).
    pub total_internal_reflection: bool,
    /// Whitted left a reflection or refraction untraced here: its weight in
    /// the pixel was below `min_weight` (adaptive tree depth).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub negligible: bool,
    /// The path tracer counted this hit's emission with this multiple-importance
    /// weight (1 when no light sample could have found it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub emission_weight: Option<f32>,
    /// The path tracer's Russian roulette after this hit, when it was played.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roulette: Option<Roulette>,
    /// The path tracer's BSDF sample here carried no light: the path ended.
    pub absorbed: bool,
}

/// β and γ of a triangle hit, as the method computed them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Barycentrics {
    /// β, the weight of v1 = t1 − t0.
    pub beta: f32,
    /// γ, the weight of v2 = t2 − t0.
    pub gamma: f32,
}

/// The material at a hit, as the integrator used it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MaterialInfo {
    /// The built-in base ("matte", "plastic", "mirror", "metal", "glass", "marble").
    pub base: &'static str,
    /// Albedo, reflectance or tint (marble's texture varies around it).
    pub color: Vec3,
    /// The mirror-reflected fraction (plastic, marble).
    pub reflectivity: f32,
    /// The index of refraction inside (glass).
    pub ior: f32,
    /// Microfacet roughness (mirror, metal, glass; the path tracer's GGX α = roughness²).
    pub roughness: f32,
    /// Emitted radiance from the front side.
    pub emission: Vec3,
}

/// What a shadow ray goes toward.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShadowTarget {
    /// A point or directional light: its index in the world's lights.
    Light(usize),
    /// A point the path tracer drew on an emitter.
    Emitter(EmitterLightSample),
    /// A direction the path tracer drew toward the environment (`<sky>`).
    Environment(EnvironmentLightSample),
}

/// The light test of a shadow ray.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShadowTest {
    /// The light or emitter the ray goes toward (in JSON `"light": index`
    /// or `"emitter": {…}`, beside the other fields).
    #[serde(flatten)]
    pub target: ShadowTarget,
    /// True when something lies between the hit point and the light.
    pub blocked: bool,
    /// The nearest object on the shadow ray, when blocked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blocker: Option<Blocker>,
}

/// What blocks a shadow ray.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Blocker {
    /// The nearest object on the shadow ray.
    pub object: ObjectRef,
    /// α of that object along the shadow ray.
    pub alpha: f32,
}
