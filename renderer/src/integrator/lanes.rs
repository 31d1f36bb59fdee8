//! Integrators as lanes: a sample's estimator written as a state machine
//! that stops wherever it needs rays traced — the closest hit of its next
//! ray, then the shadow rays of that hit — so that the same arithmetic runs
//! whether a sample is traced alone ([`trace_alone`], the pixel inspector
//! and the reference of every batched way) or with many others whose rays
//! are traced together (`trace_lanes`, which the wavefront's tests count
//! shape tests against; the film traces the path tracer's samples on SIMD
//! lanes, `super::wavefront`). Both integrators are lanes: [`super::path`]
//! and [`super::whitted`].

use super::RenderOptions;
use super::recorder::{EmitterLightSample, EnvironmentLightSample, Recorder};
use super::sampler::Sampler;
use crate::geometry::ray::Ray;
use crate::world::{Hit, World};
use glam::{Vec2, Vec3};

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
    /// Its radiance: [`sample_pixel`](super::sample_pixel)'s, bit for bit.
    pub radiance: Vec3,
    /// The shape tests its rays cost.
    pub shape_tests: u64,
}

/// The start of sample `sample` of pixel (i, j) (`None`: the centre ray):
/// its random stream after the camera's draw, where the ray crosses the
/// pixel, and the camera ray R_ij. Every way of tracing a sample starts here.
#[inline(always)]
pub(crate) fn camera_sample(
    world: &World,
    options: &RenderOptions,
    i: u32,
    j: u32,
    sample: Option<u32>,
) -> (Sampler, Vec2, Ray) {
    let mut sampler =
        Sampler::for_pixel_sample(options.sampling, options.seed, i, j, sample.unwrap_or(0));
    let jitter = sampler.next_2d();
    let offset = if sample.is_some() {
        jitter
    } else {
        Vec2::splat(0.5)
    };
    (sampler, offset, world.camera.ray(i, j, offset))
}

/// The jitter [`camera_sample`] aims sample `sample` of pixel (i, j) at:
/// the first two numbers of its stream.
#[inline]
pub(crate) fn camera_jitter(options: &RenderOptions, i: u32, j: u32, sample: u32) -> Vec2 {
    Sampler::for_pixel_sample(options.sampling, options.seed, i, j, sample).next_2d()
}

/// A shadow ray a lane waits on, and the radiance it lets through (before
/// the lane's weights) when nothing blocks it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShadowRay {
    /// The ray, its interval ending before the light.
    pub(crate) ray: Ray,
    /// What it lets through when unblocked.
    pub(crate) lit: Vec3,
    /// Which light it goes toward.
    pub(crate) target: ShadowTarget,
}

/// What a shadow ray goes toward.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ShadowTarget {
    /// The point or directional light of this index.
    Light(usize),
    /// A point the path tracer drew on an emitter.
    Emitter(EmitterLightSample),
    /// A direction the path tracer drew toward the environment.
    Environment(EnvironmentLightSample),
}

/// Whether a lane has another ray to trace after [`Lane::shade`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Next {
    /// Its next ray waits for its closest hit (after the shadow rays).
    Trace,
    /// The sample is complete once its shadow rays are in.
    Done,
}

/// One sample's estimator, stopping for rays.
pub(crate) trait Lane<N: Copy>: Sized {
    /// The lane of the camera ray `ray`, drawing from `sampler` (its
    /// camera draw taken).
    fn start<R: Recorder<Node = N>>(
        options: &RenderOptions,
        ray: Ray,
        sampler: Sampler,
        rec: &mut R,
    ) -> Self;

    /// The ray whose closest hit the lane waits for.
    fn ray(&self) -> &Ray;

    /// Shades `hit`, the closest hit of [`Lane::ray`] (`None` on a miss),
    /// appending the shadow rays it needs to `shadows`.
    fn shade<R: Recorder<Node = N>>(
        &mut self,
        world: &World,
        options: &RenderOptions,
        hit: Option<Hit>,
        shadows: &mut Vec<ShadowRay>,
        rec: &mut R,
    ) -> Next;

    /// Takes the answers to the shadow rays [`Lane::shade`] appended
    /// (`blocked`, in the same order) and moves on to the next ray.
    fn finish<R: Recorder<Node = N>>(
        &mut self,
        shadows: &[ShadowRay],
        blocked: &[bool],
        rec: &mut R,
    );

    /// The radiance gathered.
    fn radiance(&self) -> Vec3;
}

/// Traces the lane `L` of camera ray `ray` alone, ray by ray, telling
/// `rec` about everything; returns its radiance.
pub(crate) fn trace_alone<L: Lane<R::Node>, R: Recorder>(
    world: &World,
    options: &RenderOptions,
    ray: &Ray,
    sampler: Sampler,
    rec: &mut R,
) -> Vec3 {
    let mut lane = L::start(options, *ray, sampler, rec);
    let mut shadows = Vec::new();
    let mut blocked = Vec::new();
    loop {
        let hit = world.intersect(lane.ray(), options.method);
        shadows.clear();
        let next = lane.shade(world, options, hit, &mut shadows, rec);
        blocked.clear();
        blocked.extend(
            shadows
                .iter()
                .map(|s| world.occluded(&s.ray, options.method)),
        );
        lane.finish(&shadows, &blocked, rec);
        if next == Next::Done {
            return lane.radiance();
        }
    }
}

/// A lane in flight and the sample it belongs to.
#[cfg(test)]
struct Slot<L> {
    index: usize,
    lane: L,
    shape_tests: u64,
}

/// Traces every sample of `samples` as lanes `L`, up to `batch` at a time,
/// and writes each one's result to `results` (same length): each step
/// traces the closest hits of every lane together, then every shadow ray
/// of their hits together; finished lanes make room for the next samples.
/// A sample's radiance is what [`trace_alone`] gives it, bit for bit,
/// whatever `batch` and whatever the other samples.
#[cfg(test)]
pub(crate) fn trace_lanes<L: Lane<()>>(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    batch: usize,
    results: &mut [SampleResult],
) {
    use super::recorder::NoRecorder;
    use crate::geometry::counters::shape_tests_on_this_thread;
    assert_eq!(samples.len(), results.len(), "one result per sample");
    let batch = batch.max(1);
    let mut slots: Vec<Slot<L>> = Vec::with_capacity(batch);
    let mut next = 0;
    let mut hits: Vec<Option<Hit>> = Vec::with_capacity(batch);
    let mut shadows: Vec<ShadowRay> = Vec::new();
    let mut ranges: Vec<(usize, usize)> = Vec::with_capacity(batch);
    let mut blocked: Vec<bool> = Vec::new();
    let mut going_on: Vec<Next> = Vec::with_capacity(batch);
    let start = |index: usize| {
        let s = samples[index];
        let (sampler, _, ray) = camera_sample(world, options, s.i, s.j, Some(s.sample));
        Slot {
            index,
            lane: L::start(options, ray, sampler, &mut NoRecorder),
            shape_tests: 0,
        }
    };
    while slots.len() < batch && next < samples.len() {
        slots.push(start(next));
        next += 1;
    }
    loop {
        if slots.is_empty() {
            return;
        }
        // Every lane's closest hit.
        hits.clear();
        for slot in &mut slots {
            let before = shape_tests_on_this_thread();
            hits.push(world.intersect(slot.lane.ray(), options.method));
            slot.shape_tests += shape_tests_on_this_thread() - before;
        }
        // Every lane's hit: its shadow rays and its next ray.
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
        // Every shadow ray, then each lane takes its answers.
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
                .finish(&shadows[start..end], &blocked[start..end], &mut NoRecorder);
        }
        // Finished lanes leave their slots to the next samples, in place
        // (a lane is large: moving lanes around costs more than it seems).
        let mut k = 0;
        while k < slots.len() {
            if going_on[k] == Next::Trace {
                k += 1;
                continue;
            }
            let done = &slots[k];
            results[done.index] = SampleResult {
                radiance: done.lane.radiance(),
                shape_tests: done.shape_tests,
            };
            if next < samples.len() {
                slots[k] = start(next);
                next += 1;
                k += 1;
            } else {
                slots.swap_remove(k);
                going_on.swap_remove(k);
            }
        }
    }
}
