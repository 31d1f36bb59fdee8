//! The wavefront path tracer: sixteen paths at once, one per SIMD lane, every
//! stage of a bounce — the closest hit, the surface, emission, the light
//! sample and its shadow ray, the BSDF sample, roulette — done for the
//! sixteen together on structures of arrays ([`crate::packet`]). Finished
//! lanes take the next samples at once, so the lanes stay full, or once
//! half of them have finished, so that their new paths trace coherent rays
//! together: each thread measures which is faster on the scene
//! (`refill.rs`).
//!
//! It computes exactly what the scalar path tracer ([`super::path`], a
//! `PathLane`) computes, in the same order, lane by lane: the same random
//! numbers from the same streams, the same formulas without fused
//! multiply–add. Each sample's radiance is therefore the scalar one bit for
//! bit — the pixel inspector, which traces one sample alone with the scalar
//! lane, sees exactly the film's sample — and a test holds it to that over
//! every pixel of the scenes it covers.
//!
//! Rays are tested in packets in worlds of lone triangles (small meshes'
//! placed in world space included), boxes, spheres and planes ([`crate::packet_shapes::PacketShapes`]: against every
//! primitive, or through a tree, then the planes), else traced lane by lane through the world's BVH
//! (`tracing.rs`). Every material is shaded on lanes: Lambertian with a
//! white GGX highlight and a mirror lobe (matte, plastic, marble — whose
//! solid texture each lane evaluates at its point), rough conductors and
//! the highlights (`glossy.rs`), rough glass (`rough_glass.rs`), mirror,
//! metal and smooth glass (`delta.rs`), point and directional lights
//! included. Mesh triangles among them too: each lane's point, interpolated
//! normal and texture colour are found by the scalar code
//! (`World::hit_surface`), the rest on lanes in the shading normal's frame.
//! Only a hit on an emitting mesh triangle (whose emitter is per triangle)
//! is shaded by the scalar `PathLane` itself (`handover.rs`).
//!
//! Lane code is written in `#[inline(always)]` functions and methods, not
//! closures: a closure that is not inlined is compiled without the AVX2
//! instruction set, and its lane operations then run as calls (a closure
//! for the BSDF's value made `rough.xml` 40% slower). The film's path tracer
//! uses the wavefront for every world ([`WavefrontScene::new`] gives the
//! figures against the scalar lanes it replaced).

mod delta;
mod draws;
mod emitter_table;
mod glossy;
mod group;
mod handover;
mod lane_math;
mod paths;
mod refill;
mod rough_glass;
mod scene;
mod shadow_sides;
mod surfaces;
mod tracing;

pub(crate) use scene::WavefrontScene;

use super::RenderOptions;
use super::lanes::{SampleRef, SampleResult};
use crate::packet::{FloatLanes, WIDTH, WithLanes, dispatch};
use crate::world::World;
use group::PathGroup;
use refill::{COHORTS, Plan};
use std::time::Instant;

/// Traces every sample of `samples` with the wavefront path tracer over
/// `scene` (prepared from `world`) and writes each one's result to
/// `results`; each radiance is the scalar path tracer's bit for bit. Runs
/// with the widest SIMD lanes this CPU has.
pub(crate) fn trace_wavefront(
    world: &World,
    scene: &WavefrontScene,
    options: &RenderOptions,
    samples: &[SampleRef],
    results: &mut [SampleResult],
) {
    assert_eq!(samples.len(), results.len(), "one result per sample");
    let trace = |samples: &[SampleRef], results: &mut [SampleResult], way: usize| {
        dispatch(Trace {
            world,
            scene,
            options,
            samples,
            results,
            cohort: COHORTS[way],
        });
    };
    match scene.refill.plan() {
        Plan::Way(way) => trace(samples, results, way),
        Plan::Trial => {
            // The even samples one way, the odd ones the other, timed.
            for way in 0..2 {
                let half: Vec<SampleRef> = samples.iter().copied().skip(way).step_by(2).collect();
                let mut traced = vec![SampleResult::default(); half.len()];
                let start = Instant::now();
                trace(&half, &mut traced, way);
                scene.refill.record(way, half.len(), start.elapsed());
                for (result, t) in results.iter_mut().skip(way).step_by(2).zip(traced) {
                    *result = t;
                }
            }
        }
    }
}

/// The most memory [`trace_wavefront`] holds at once for a list of at most
/// `samples` samples of `world` (bytes), whatever the lane type: its group
/// of sixteen paths, the scalar code's shadow rays for handed-over lanes
/// (at most one toward each light and one toward the emitters a lane), the
/// shadow masks toward each light, and, while a thread still measures its
/// two ways of refilling lanes, a copy of every other sample with its
/// result.
pub(crate) fn wavefront_bytes(world: &World, samples: usize) -> usize {
    use crate::integrator::lanes::ShadowRay;
    use std::mem::size_of;
    let group = size_of::<PathGroup<crate::simd::Portable>>();
    #[cfg(target_arch = "x86_64")]
    let group = group
        .max(size_of::<PathGroup<crate::simd::avx2::Avx2>>())
        .max(size_of::<PathGroup<crate::simd::avx512::Avx512>>());
    let shadows_per_lane = world.lights.len() + 1;
    let handover = WIDTH * shadows_per_lane * size_of::<ShadowRay>() + shadows_per_lane;
    // A mask of sixteen lanes takes at most 4 bytes a lane.
    let masks = world.lights.len() * WIDTH * 4;
    let trial = samples.div_ceil(2) * (size_of::<SampleRef>() + size_of::<SampleResult>());
    group + handover + masks + trial
}

/// A call of [`trace_wavefront`], to run with some lane type.
struct Trace<'a> {
    world: &'a World,
    scene: &'a WavefrontScene,
    options: &'a RenderOptions,
    samples: &'a [SampleRef],
    results: &'a mut [SampleResult],
    /// Finished lanes a group waits for before refilling them (`refill.rs`).
    cohort: u32,
}

impl WithLanes for Trace<'_> {
    type Output = ();

    /// Fills the lanes, steps them all, refills the finished ones (once
    /// `cohort` of them have finished), until every sample is done.
    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        let Trace {
            world,
            scene,
            options,
            samples,
            results,
            cohort,
        } = self;
        let mut queue = samples.iter().copied().enumerate();
        let mut group = PathGroup::<F>::new();
        // The lanes without a sample (bit k for lane k).
        let mut idle = u32::MAX >> (32 - WIDTH);
        loop {
            if idle.count_ones() >= cohort {
                while idle != 0 {
                    let lane = idle.trailing_zeros() as usize;
                    let Some((index, s)) = queue.next() else {
                        break;
                    };
                    group.start(options, lane, index, s);
                    idle &= idle - 1;
                }
            }
            if !group.any_live() {
                return;
            }
            let finished = group.step(world, scene, options);
            for lane in (0..WIDTH).filter(|lane| finished & (1 << lane) != 0) {
                let (index, result) = group.take(lane);
                results[index] = result;
            }
            idle |= finished;
        }
    }
}

#[cfg(test)]
mod tests;
