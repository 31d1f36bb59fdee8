//! The settings every integrator shares: which integrator, which
//! intersection formulas, the depth, the seed, how samples are drawn and
//! whether adaptive sampling spends them where the image is noisy.

use super::adaptive::Adaptive;
use super::sampler::Sampling;
use crate::shapes::Method;

/// Which estimator of a ray's radiance renders the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Whitted's recursive ray tracer: direct light from point and
    /// directional lights, ambient light, perfect reflection and refraction.
    #[default]
    Whitted,
    /// Unbiased path tracing with next-event estimation and multiple
    /// importance sampling, as Mitsuba 3's `path`.
    Path,
}

/// Settings shared by every integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Which estimator renders the image.
    pub integrator: Integrator,
    /// Which intersection formulas to use.
    pub method: Method,
    /// Whitted: the most reflection/refraction bounces after the primary hit.
    /// Path: the longest path in segments, counted as Mitsuba counts
    /// `max_depth` (1 = emitters seen directly, 2 = direct lighting).
    pub max_depth: u32,
    /// Seed of every random choice; with (pixel, sample index) it fixes a sample.
    pub seed: u64,
    /// How each pixel's samples draw their random numbers.
    pub sampling: Sampling,
    /// Adaptive sampling: pixels below its error threshold stop receiving
    /// samples; `None` samples every pixel in every pass.
    pub adaptive: Option<Adaptive>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            integrator: Integrator::Whitted,
            method: Method::Robust,
            max_depth: 8,
            seed: 0,
            sampling: Sampling::Independent,
            adaptive: None,
        }
    }
}
