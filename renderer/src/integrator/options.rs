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
    /// Whitted: a reflected or refracted ray whose weight in the pixel (the
    /// product of the reflectances and transmittances that led to it, its
    /// largest channel) is below this is not traced but taken to see the
    /// background (the ambient light and the sky) — Hall and Greenberg's
    /// adaptive tree depth, POV-Ray's `adc_bailout`. 0 traces every ray to
    /// `max_depth`.
    pub min_weight: f32,
}

/// [`RenderOptions::min_weight`]'s default, POV-Ray's: one step of an
/// 8-bit display.
pub const MIN_WEIGHT: f32 = 1.0 / 255.0;

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            integrator: Integrator::Whitted,
            method: Method::Robust,
            max_depth: 8,
            seed: 0,
            sampling: Sampling::Independent,
            adaptive: None,
            min_weight: MIN_WEIGHT,
        }
    }
}
