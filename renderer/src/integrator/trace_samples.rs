//! Tracing a list of samples, as a pass of the film does: the path tracer
//! traces them in batches ([`trace_paths`]), Whitted one by one. Either way a
//! sample's radiance is [`sample_pixel`]'s bit for bit.

use super::path::batch::{PATHS_PER_BATCH, trace_paths};
use super::{Integrator, RenderOptions, sample_pixel};
use crate::geometry::counters::shape_tests_on_this_thread;
use crate::world::World;
use glam::Vec3;

/// Sample `sample` of pixel (i, j).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleRef {
    /// The pixel's column.
    pub i: u32,
    /// The pixel's row.
    pub j: u32,
    /// The sample index k.
    pub sample: u32,
}

/// What a traced sample brought back.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleResult {
    /// Its radiance: [`sample_pixel`]'s, bit for bit.
    pub radiance: Vec3,
    /// The shape tests its rays cost.
    pub shape_tests: u64,
}

/// Traces every sample of `samples` with the integrator of `options` and
/// writes each one's result to `results` (same length).
pub fn trace_samples(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    results: &mut [SampleResult],
) {
    assert_eq!(samples.len(), results.len(), "one result per sample");
    match options.integrator {
        Integrator::Path => trace_paths(world, options, samples, PATHS_PER_BATCH, results),
        Integrator::Whitted => {
            for (s, result) in samples.iter().zip(results.iter_mut()) {
                let before = shape_tests_on_this_thread();
                let radiance = sample_pixel(world, options, s.i, s.j, s.sample);
                *result = SampleResult {
                    radiance,
                    shape_tests: shape_tests_on_this_thread() - before,
                };
            }
        }
    }
}
