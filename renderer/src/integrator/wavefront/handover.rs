//! Lanes handed to the scalar path tracer: a hit on a material the lanes do
//! not shade (a highlight, a mirror lobe, marble, conductors, glass) is
//! shaded by `PathLane` itself, resumed from the lane's state and put back
//! into it afterwards, its shadow ray traced in the same packet as the
//! others'. The lane's arithmetic is then the scalar path tracer's by
//! construction.

use super::group::PathGroup;
use crate::integrator::RenderOptions;
use crate::integrator::lanes::{Lane, Next, ShadowRay};
use crate::integrator::path::{PathLane, PathState};
use crate::integrator::recorder::NoRecorder;
use crate::integrator::sampler::Sampler;
use crate::packet::{FloatLanes, IntLanes, PacketHits, Rays, WIDTH, lane_set, mask_from};
use crate::world::{Hit, World};

/// A handed-over lane between its shading and its shadow ray's answer.
struct Pending {
    /// The path, shaded, its shadow ray out.
    lane: PathLane<()>,
    /// Whether it goes on after the shadow ray.
    next: Next,
    /// Its shadow ray (a world without point lights gives at most one).
    shadow: Option<ShadowRay>,
}

/// The lanes of one bounce that the scalar code shades.
pub(super) struct Handover<F> {
    pending: [Option<Pending>; WIDTH],
    /// The lanes with a shadow ray out.
    pub(super) shadowed: F,
}

impl<F: FloatLanes> Handover<F> {
    /// No lane handed over.
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            pending: std::array::from_fn(|_| None),
            shadowed: F::ZERO,
        }
    }

    /// Shades the hits of the lanes `lanes` with `PathLane::shade`, taking
    /// their state out of `group`.
    #[inline(always)]
    pub(super) fn shade(
        &mut self,
        group: &mut PathGroup<F>,
        world: &World,
        options: &RenderOptions,
        lanes: F,
        hits: &PacketHits<F>,
    ) {
        if !lanes.any() {
            return;
        }
        let (alpha, object) = (hits.alpha.to_array(), hits.object.to_array());
        let mut shadows = Vec::with_capacity(1);
        for k in (0..WIDTH).filter(|&k| lane_set(lanes, k)) {
            let state = PathState {
                radiance: group.radiance.lane(k),
                throughput: group.throughput.lane(k),
                ray: group.rays.lane(k),
                previous: lane_set(group.has_previous, k).then(|| {
                    (
                        group.previous_point.lane(k),
                        group.previous_pdf.as_array()[k],
                    )
                }),
                eta_scale: group.eta_scale.as_array()[k],
                depth: group.depth[k],
                sampler: std::mem::replace(&mut group.samplers[k], Sampler::for_sample(0, 0, 0, 0)),
            };
            let mut lane = PathLane::resume(state);
            let hit = Hit {
                object: object[k] as u32,
                alpha: alpha[k],
                triangle: None,
            };
            shadows.clear();
            let next = lane.shade(world, options, Some(hit), &mut shadows, &mut NoRecorder);
            assert!(
                shadows.len() <= 1,
                "a world without point lights gives a vertex one shadow ray at most"
            );
            self.pending[k] = Some(Pending {
                lane,
                next,
                shadow: shadows.first().copied(),
            });
        }
        let pending = &self.pending;
        self.shadowed = mask_from(|k| pending[k].as_ref().is_some_and(|p| p.shadow.is_some()));
    }

    /// `shadows` with the handed-over lanes' shadow rays in their lanes.
    #[inline(always)]
    pub(super) fn add_shadow_rays(&self, mut shadows: Rays<F>) -> Rays<F> {
        for (k, pending) in self.pending.iter().enumerate() {
            if let Some(shadow) = pending.as_ref().and_then(|p| p.shadow) {
                shadows.origin.set_lane(k, shadow.ray.origin);
                shadows.dir.set_lane(k, shadow.ray.dir);
                shadows.t_max.as_mut_array()[k] = shadow.ray.t_max;
            }
        }
        shadows
    }

    /// Gives each handed-over lane its shadow ray's answer (`blocked`),
    /// puts its state back into `group` and returns the lanes that finished
    /// (bit k for lane k).
    #[inline(always)]
    pub(super) fn finish(self, group: &mut PathGroup<F>, blocked: F) -> u32 {
        let mut finished = 0;
        for (k, pending) in self.pending.into_iter().enumerate() {
            let Some(Pending {
                mut lane,
                next,
                shadow,
            }) = pending
            else {
                continue;
            };
            match shadow {
                Some(shadow) => lane.finish(&[shadow], &[lane_set(blocked, k)], &mut NoRecorder),
                None => lane.finish(&[], &[], &mut NoRecorder),
            }
            let state = lane.into_state();
            group.radiance.set_lane(k, state.radiance);
            group.throughput.set_lane(k, state.throughput);
            group.rays.origin.set_lane(k, state.ray.origin);
            group.rays.dir.set_lane(k, state.ray.dir);
            group.rays.t_max.as_mut_array()[k] = state.ray.t_max;
            let (point, pdf) = state.previous.unwrap_or_default();
            group.previous_point.set_lane(k, point);
            group.previous_pdf.as_mut_array()[k] = pdf;
            group.has_previous.as_mut_array()[k] = f32::from_bits(if state.previous.is_some() {
                u32::MAX
            } else {
                0
            });
            group.eta_scale.as_mut_array()[k] = state.eta_scale;
            group.depth[k] = state.depth;
            group.samplers[k] = state.sampler;
            if next == Next::Done {
                finished |= 1 << k;
            }
        }
        finished
    }
}
