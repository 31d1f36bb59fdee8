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
//!
//! A path is a `PathLane` (`integrator/lanes.rs`): a state machine that stops
//! for its closest hits and its shadow rays, so that the film can trace the
//! rays of many paths together ([`super::trace_samples()`]) and
//! [`path_recorded`] one path alone, with the same result.

mod lane;

use super::RenderOptions;
use super::lanes::trace_alone;
use super::recorder::{NoRecorder, Recorder};
use super::sampler::Sampler;
use crate::geometry::ray::Ray;
use crate::world::World;
use glam::Vec3;
pub(crate) use lane::{PathLane, PathState};

/// The first scattering event counted by Russian roulette (Mitsuba's `rr_depth`).
pub const RR_DEPTH: u32 = 5;

/// A shadow ray toward an area light stops this fraction short of the
/// sampled point, so that it cannot hit the emitter itself.
pub(crate) const SHADOW_SHORTENING: f32 = 1.0e-4;

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
pub fn path(world: &World, ray: &Ray, options: &RenderOptions, sampler: Sampler) -> Vec3 {
    path_recorded(world, ray, options, sampler, &mut NoRecorder)
}

/// [`path`], telling `rec` about every ray it traces (the camera ray `ray`
/// first), every emission it counts and every roulette decision. The path
/// is traced alone, ray by ray, with the arithmetic of a batch's paths
/// (a `PathLane`): the radiance is bit for bit the same for any recorder and
/// as in the film's batches ([`super::trace_samples()`]).
pub fn path_recorded<R: Recorder>(
    world: &World,
    ray: &Ray,
    options: &RenderOptions,
    sampler: Sampler,
    rec: &mut R,
) -> Vec3 {
    trace_alone::<PathLane<R::Node>, R>(world, options, ray, sampler, rec)
}
