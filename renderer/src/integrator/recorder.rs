//! What the integrators tell an observer while they trace: the hook the pixel
//! inspector uses to rebuild one sample as a ray tree. The image is traced
//! with [`NoRecorder`], whose calls are empty and compile away, so the image
//! and the inspector run the same integrator.

use crate::geometry::ray::Ray;
use crate::shading::bsdf::BsdfSample;
use crate::shapes::Surface;
use crate::world::Hit;
use glam::Vec3;
use serde::Serialize;

/// What a traced ray is for (lower-case names in JSON).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RayKind {
    /// R_ij = (P0, v_ij), the camera ray through the pixel.
    Primary,
    /// From a hit point toward a light, to test whether the light is blocked.
    Shadow,
    /// The mirror direction at a hit (mirror, metal, reflective plastic and marble, glass).
    Reflection,
    /// The transmitted direction through glass (Snell's law).
    Refraction,
}

/// An event that shaped a hit's subtree without tracing a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Note {
    /// A reflection or refraction would have followed, but `max_depth` stopped it.
    DepthLimit,
    /// Glass reflected everything: no refracted ray exists (total internal reflection).
    TotalInternalReflection,
    /// A reflection or refraction was not traced but taken to see the
    /// background: its weight in the pixel was below
    /// [`RenderOptions::min_weight`](super::RenderOptions::min_weight).
    Negligible,
    /// The path tracer's Russian roulette at this hit: the path went on with
    /// probability `keep` (its throughput then divided by `keep`), and did
    /// when `survived`.
    Roulette {
        /// The probability of going on: min(0.95, max throughput channel / η scale).
        keep: f32,
        /// Whether the path went on.
        survived: bool,
    },
    /// The path tracer's BSDF sample carried no light (zero density or zero
    /// weight): the path ends here.
    Absorbed,
}

/// A point drawn on an emitter by the path tracer's light sampling, as its
/// shadow ray tests it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EmitterLightSample {
    /// The emitter's index in the world's emitters.
    pub index: usize,
    /// The density in solid angle of the drawn direction, the choice of
    /// emitter included.
    pub pdf: f32,
    /// Its multiple-importance weight against BSDF sampling (power heuristic).
    pub mis_weight: f32,
}

/// A direction the path tracer drew toward the environment (`<sky>`), as
/// its shadow ray tests it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnvironmentLightSample {
    /// The density in solid angle of the drawn direction.
    pub pdf: f32,
    /// Its multiple-importance weight against BSDF sampling (power heuristic).
    pub mis_weight: f32,
}

/// An observer of an integrator. Every call is made beside the radiance
/// computation, never inside it, so a recorder cannot change the result;
/// nodes are the recorder's handles to the rays it was told about.
///
/// A node's weight is what the sample's colour gains per unit of radiance
/// the ray brings back: Whitted's product of factors, the path tracer's
/// throughput.
pub trait Recorder {
    /// A handle to a recorded ray (`()` when nothing is kept).
    type Node: Copy;

    /// The camera ray starts the tree (depth 0).
    fn primary(&mut self, ray: &Ray) -> Self::Node;

    /// A reflected or refracted ray of bounce `depth` leaves `parent`'s hit
    /// point; `parent`'s radiance gains `factor` × the radiance it brings back
    /// (reflectivity, reflectance, Fresnel F or (1 − F)·tint).
    fn bounce(
        &mut self,
        parent: Self::Node,
        kind: RayKind,
        ray: &Ray,
        depth: u32,
        factor: Vec3,
    ) -> Self::Node;

    /// `node` left the scene and sees `radiance`: the background (Whitted),
    /// or the sky times its multiple-importance weight against the sky's
    /// light sample (the path tracer; 1 for the camera ray and after a
    /// delta lobe).
    fn miss(&mut self, node: Self::Node, radiance: Vec3);

    /// `node` hit `hit`, at `surface`, on the front side when `front`.
    fn hit(&mut self, node: Self::Node, ray: &Ray, hit: Hit, surface: &Surface, front: bool);

    /// `node`'s hit point adds `radiance` of its own: emission, the ambient
    /// term ambient·albedo·(1 − reflectivity), or what a bounce Whitted
    /// left untraced adds (its factor times the background).
    fn local(&mut self, node: Self::Node, radiance: Vec3);

    /// A shadow ray toward light `light` left `node`'s hit point. `lit` is
    /// `None` when something blocks it, else the Lambert + specular radiance
    /// it lets through, which `node` adds scaled by `scale` (1 − reflectivity).
    fn shadow(&mut self, node: Self::Node, light: usize, ray: &Ray, scale: f32, lit: Option<Vec3>);

    /// Something shaped `node`'s subtree without tracing a ray.
    fn note(&mut self, node: Self::Node, note: Note);

    /// The path tracer: `node`'s hit is an emitter seen from its front, which
    /// adds `mis_weight` × `radiance` (its power-heuristic weight against
    /// light sampling; 1 for the camera ray and after a delta lobe).
    fn emission(&mut self, node: Self::Node, radiance: Vec3, mis_weight: f32);

    /// The path tracer: a ray of bounce `depth` leaves `parent`'s hit in the
    /// direction `sample` drew from its BSDF, carrying the path throughput
    /// `throughput` (Russian roulette's division included).
    fn scatter(
        &mut self,
        parent: Self::Node,
        ray: &Ray,
        depth: u32,
        throughput: Vec3,
        sample: &BsdfSample,
    ) -> Self::Node;

    /// The path tracer: a shadow ray toward the point `sample` drew on an
    /// emitter left `node`'s hit point; `lit` as in [`Recorder::shadow`]
    /// (f · L · weight / pdf when unblocked).
    fn emitter_shadow(
        &mut self,
        node: Self::Node,
        sample: EmitterLightSample,
        ray: &Ray,
        lit: Option<Vec3>,
    );

    /// The path tracer: a shadow ray toward the direction `sample` drew
    /// toward the environment left `node`'s hit point; `lit` as in
    /// [`Recorder::emitter_shadow`].
    fn environment_shadow(
        &mut self,
        node: Self::Node,
        sample: EnvironmentLightSample,
        ray: &Ray,
        lit: Option<Vec3>,
    );
}

/// The recorder of the image: keeps nothing, costs nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoRecorder;

impl Recorder for NoRecorder {
    type Node = ();

    #[inline(always)]
    fn primary(&mut self, _: &Ray) {}

    #[inline(always)]
    fn bounce(&mut self, _: (), _: RayKind, _: &Ray, _: u32, _: Vec3) {}

    #[inline(always)]
    fn miss(&mut self, _: (), _: Vec3) {}

    #[inline(always)]
    fn hit(&mut self, _: (), _: &Ray, _: Hit, _: &Surface, _: bool) {}

    #[inline(always)]
    fn local(&mut self, _: (), _: Vec3) {}

    #[inline(always)]
    fn shadow(&mut self, _: (), _: usize, _: &Ray, _: f32, _: Option<Vec3>) {}

    #[inline(always)]
    fn note(&mut self, _: (), _: Note) {}

    #[inline(always)]
    fn emission(&mut self, _: (), _: Vec3, _: f32) {}

    #[inline(always)]
    fn scatter(&mut self, _: (), _: &Ray, _: u32, _: Vec3, _: &BsdfSample) {}

    #[inline(always)]
    fn emitter_shadow(&mut self, _: (), _: EmitterLightSample, _: &Ray, _: Option<Vec3>) {}

    #[inline(always)]
    fn environment_shadow(&mut self, _: (), _: EnvironmentLightSample, _: &Ray, _: Option<Vec3>) {}
}
