//! Integrators: how a ray's radiance is estimated.

pub mod recorder;
pub mod whitted;

pub use recorder::{NoRecorder, Note, RayKind, Recorder};
pub use whitted::{whitted, whitted_recorded};

use crate::shapes::Method;

/// Settings shared by every integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Which intersection formulas to use.
    pub method: Method,
    /// Maximum number of reflection/refraction bounces after the primary hit.
    pub max_depth: u32,
    /// Seed of every random choice; with (pixel, sample index) it fixes a sample.
    pub seed: u64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            method: Method::Robust,
            max_depth: 8,
            seed: 0,
        }
    }
}
