//! The state of sixteen paths between bounces, lane by lane: what `PathLane`
//! carries from one bounce to the next, as structures of arrays.

use crate::integrator::sampler::lanes::StreamLanes;
use crate::packet::{FloatLanes, Rays, Vec3s, WIDTH};

/// Sixteen paths' state, one per lane.
pub(super) struct Paths<F: FloatLanes> {
    /// Per lane, its random stream.
    pub(super) streams: StreamLanes<F>,
    /// The rays whose closest hits the lanes wait for.
    pub(super) rays: Rays<F>,
    /// Radiance gathered so far.
    pub(super) radiance: Vec3s<F>,
    /// Path throughput.
    pub(super) throughput: Vec3s<F>,
    /// Where each lane's ray started and the BSDF density it was drawn with
    /// (valid where `has_previous`: not for camera rays).
    pub(super) previous_point: Vec3s<F>,
    /// The density of the previous BSDF sample.
    pub(super) previous_pdf: F,
    /// Lanes whose ray was drawn from a BSDF (MIS applies to what it hits).
    pub(super) has_previous: F::Mask,
    /// Product of refraction's radiance scaling, divided out for roulette.
    pub(super) eta_scale: F,
    /// Scattering events so far.
    pub(super) depth: [u32; WIDTH],
}
