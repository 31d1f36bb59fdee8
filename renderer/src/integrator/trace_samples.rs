//! Tracing a list of samples, as a pass of the film does: the path tracer
//! traces them sixteen at a time in SIMD lanes where the wavefront is the
//! faster (`integrator/wavefront/`), else in batches of scalar lanes
//! (`trace_lanes` in `integrator/lanes.rs`); Whitted's camera rays sixteen
//! at a time and the rest of each sample by its recursion
//! (`integrator/whitted_batch.rs`; as a lane, every ray stopping for the
//! others, it measured 8–18% slower than its recursion). Either way a
//! sample's radiance is [`sample_pixel`](super::sample_pixel)'s bit for bit.

use super::lanes::{LANES_PER_BATCH, trace_lanes};
pub use super::lanes::{SampleRef, SampleResult};
use super::path::PathLane;
use super::wavefront::{WavefrontScene, trace_wavefront};
use super::whitted_batch::trace_whitted;
use super::{Integrator, RenderOptions};
use crate::shapes::Method;
use crate::world::World;
use std::cell::RefCell;
use std::rc::Rc;

/// Traces every sample of `samples` with the integrator of `options` and
/// writes each one's result to `results` (same length).
pub fn trace_samples(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    results: &mut [SampleResult],
) {
    trace_samples_batched(world, options, samples, LANES_PER_BATCH, results);
}

/// The wavefront view of `world` when the wavefront path tracer is the
/// faster there ([`WavefrontScene::for_film`] says when and what was
/// measured), else `None`: the scalar lanes.
///
/// Built once per world, method and thread, not per call: the film calls
/// once per chunk of a pass, and building the tree of spheres.xml's 104
/// primitives every time took 3% of its render.
fn wavefront_scene(world: &World, options: &RenderOptions) -> Rc<Option<WavefrontScene>> {
    /// A world's view: its id, the method, the view (`None`: no packets).
    type Keyed = (u64, Method, Rc<Option<WavefrontScene>>);
    thread_local! {
        /// This thread's view of the last world it traced.
        static LAST: RefCell<Option<Keyed>> = const { RefCell::new(None) };
    }
    LAST.with_borrow_mut(|last| match last {
        Some((id, method, scene)) if *id == world.id() && *method == options.method => {
            scene.clone()
        }
        _ => {
            let scene = Rc::new(WavefrontScene::for_film(world, options.method));
            *last = Some((world.id(), options.method, scene.clone()));
            scene
        }
    })
}

/// The most memory [`trace_samples`] holds at once for the path tracer's
/// batch in `world` (bytes), whatever the number of samples.
pub fn path_batch_bytes(world: &World) -> usize {
    super::lanes::lanes_bytes::<PathLane<()>>(world, LANES_PER_BATCH)
}

/// [`trace_samples`] with up to `batch` samples in flight at a time; the
/// results do not depend on `batch`.
pub fn trace_samples_batched(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    batch: usize,
    results: &mut [SampleResult],
) {
    match options.integrator {
        Integrator::Path => match &*wavefront_scene(world, options) {
            Some(scene) => trace_wavefront(world, scene, options, samples, results),
            None => trace_lanes::<PathLane<()>>(world, options, samples, batch, results),
        },
        Integrator::Whitted => {
            let scene = wavefront_scene(world, options);
            let packets = scene.as_ref().as_ref().and_then(|s| s.shapes.as_ref());
            trace_whitted(world, packets, options, samples, results);
        }
    }
}
