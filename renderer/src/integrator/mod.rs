//! Integrators: how the radiance of a pixel's sample is estimated, and the
//! sampling that drives them.
//!
//! [`sample_pixel()`] is the one entry point of the film, the previews and the
//! inspector: the camera ray of a sample, then [`whitted()`] or [`path()`] with
//! the sample's own random numbers ([`sampler`]). [`Recorder`] lets the
//! pixel inspector watch every ray an integrator traces.

pub mod adaptive;
mod lanes;
mod options;
pub mod path;
pub mod recorder;
mod sample_pixel;
pub mod sampler;
mod shading_context;
pub mod trace_samples;
mod wavefront;
pub mod whitted;
mod whitted_batch;
mod whitted_packets;
mod whitted_tree;

pub use adaptive::Adaptive;
pub use options::{Integrator, MIN_WEIGHT, RenderOptions};
pub use path::{path, path_recorded};
pub use recorder::{NoRecorder, Note, RayKind, Recorder};
pub use sample_pixel::{TracedSample, sample_offset, sample_pixel, sample_pixel_recorded};
pub use shading_context::ShadingContext;
pub use trace_samples::{SampleRef, SampleResult, path_batch_bytes, trace_samples};
pub use whitted::{whitted, whitted_recorded};
