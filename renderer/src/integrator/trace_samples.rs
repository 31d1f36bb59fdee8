//! Tracing a list of samples, as a pass of the film does: the path tracer
//! traces them sixteen at a time in SIMD lanes (`integrator/wavefront/`);
//! Whitted's camera rays sixteen at a time and the rest of each sample by
//! its recursion (`integrator/whitted_batch.rs`; as a lane, every ray
//! stopping for the others, it measured 8–18% slower than its recursion).
//! Either way a sample's radiance is [`sample_pixel`](super::sample_pixel)'s
//! bit for bit, whatever the other samples of the list.

pub use super::lanes::{SampleRef, SampleResult};
use super::wavefront::{WavefrontScene, trace_wavefront, wavefront_bytes};
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
    let scene = wavefront_scene(world, options);
    match options.integrator {
        Integrator::Path => trace_wavefront(world, &scene, options, samples, results),
        Integrator::Whitted => {
            trace_whitted(world, scene.shapes.as_ref(), options, samples, results);
        }
    }
}

/// The wavefront view of `world` ([`WavefrontScene::new`]), whose packet
/// shapes Whitted's camera rays use too.
///
/// Built once per world, method and thread, not per call: the film calls
/// once per chunk of a pass, and building the tree of spheres.xml's 104
/// primitives every time took 3% of its render.
fn wavefront_scene(world: &World, options: &RenderOptions) -> Rc<WavefrontScene> {
    /// A world's view: its id, the method, the view.
    type Keyed = (u64, Method, Rc<WavefrontScene>);
    thread_local! {
        /// This thread's view of the last world it traced.
        static LAST: RefCell<Option<Keyed>> = const { RefCell::new(None) };
    }
    LAST.with_borrow_mut(|last| match last {
        Some((id, method, scene)) if *id == world.id() && *method == options.method => {
            scene.clone()
        }
        _ => {
            let scene = Rc::new(WavefrontScene::new(world, options.method));
            *last = Some((world.id(), options.method, scene.clone()));
            scene
        }
    })
}

/// The most memory [`trace_samples`] holds at once for the path tracer in
/// `world` (bytes) given lists of at most `samples` samples.
pub fn path_batch_bytes(world: &World, samples: usize) -> usize {
    wavefront_bytes(world, samples)
}
