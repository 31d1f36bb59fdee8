//! Many paths at once: each bounce traces the closest hits of every path in
//! the batch together, then every shadow ray of their vertices together;
//! finished paths make room for the next samples. A path's radiance is bit
//! for bit what it is traced alone ([`super::path_recorded`]): the batch
//! changes only when its rays are traced, never its arithmetic.

use super::lane::{Next, PathLane, ShadowRay};
use crate::geometry::counters::shape_tests_on_this_thread;
use crate::integrator::RenderOptions;
use crate::integrator::recorder::NoRecorder;
use crate::integrator::sample_pixel::camera_sample;
use crate::integrator::trace_samples::{SampleRef, SampleResult};
use crate::world::{Hit, World};

/// Paths in flight per batch: enough that a bounce's rays can be traced
/// together, few enough that the batch's state stays in the L1 and L2 caches.
pub const PATHS_PER_BATCH: usize = 64;

/// A path in flight and the sample it belongs to.
struct Slot {
    index: usize,
    lane: PathLane<()>,
    shape_tests: u64,
}

/// Traces every sample of `samples` with the path tracer, up to `batch`
/// paths at a time, and writes each one's result to `results` (same
/// length). The results do not depend on `batch`.
pub fn trace_paths(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    batch: usize,
    results: &mut [SampleResult],
) {
    assert_eq!(samples.len(), results.len(), "one result per sample");
    let batch = batch.max(1);
    let mut slots: Vec<Slot> = Vec::with_capacity(batch);
    let mut next = 0;
    let mut hits: Vec<Option<Hit>> = Vec::with_capacity(batch);
    let mut shadows: Vec<ShadowRay> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::with_capacity(batch);
    let mut blocked: Vec<bool> = Vec::new();
    let mut going_on: Vec<Next> = Vec::with_capacity(batch);
    loop {
        while slots.len() < batch && next < samples.len() {
            let s = samples[next];
            let (sampler, _, ray) = camera_sample(world, options, s.i, s.j, Some(s.sample));
            slots.push(Slot {
                index: next,
                lane: PathLane::new(ray, sampler, &mut NoRecorder),
                shape_tests: 0,
            });
            next += 1;
        }
        if slots.is_empty() {
            return;
        }
        // Every path's closest hit.
        hits.clear();
        for slot in &mut slots {
            let before = shape_tests_on_this_thread();
            hits.push(world.intersect(&slot.lane.ray, options.method));
            slot.shape_tests += shape_tests_on_this_thread() - before;
        }
        // Every path's vertex: emission, its shadow rays and its next ray.
        shadows.clear();
        ranges.clear();
        going_on.clear();
        for (slot, &hit) in slots.iter_mut().zip(&hits) {
            let start = shadows.len();
            going_on.push(
                slot.lane
                    .shade(world, options, hit, &mut shadows, &mut NoRecorder),
            );
            ranges.push((start, shadows.len()));
        }
        // Every shadow ray, then each vertex takes its answers.
        blocked.clear();
        for (slot, &(start, end)) in slots.iter_mut().zip(&ranges) {
            let before = shape_tests_on_this_thread();
            blocked.extend(
                shadows[start..end]
                    .iter()
                    .map(|s| world.occluded(&s.ray, options.method)),
            );
            slot.shape_tests += shape_tests_on_this_thread() - before;
        }
        for (slot, &(start, end)) in slots.iter_mut().zip(&ranges) {
            slot.lane
                .finish_vertex(&shadows[start..end], &blocked[start..end], &mut NoRecorder);
        }
        // Finished paths leave their slots to the next samples.
        let mut k = 0;
        while k < slots.len() {
            if going_on[k] == Next::Done {
                let done = slots.swap_remove(k);
                going_on.swap_remove(k);
                results[done.index] = SampleResult {
                    radiance: done.lane.radiance,
                    shape_tests: done.shape_tests,
                };
            } else {
                k += 1;
            }
        }
    }
}
