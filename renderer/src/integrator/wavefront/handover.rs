//! Lanes handed to the scalar path tracer: a hit the lanes do not shade (an
//! emitting mesh triangle, whose emitter is per triangle) is
//! shaded by `PathLane` itself, resumed from the lane's state and put back
//! into it afterwards, its shadow ray traced in the same packet as the
//! others'. The lane's arithmetic is then the scalar path tracer's by
//! construction.

use super::paths::Paths;
use super::tracing::Closest;
use crate::integrator::RenderOptions;
use crate::integrator::lanes::{Lane, Next, ShadowRay, ShadowTarget};
use crate::integrator::path::{PathLane, PathState};
use crate::integrator::recorder::NoRecorder;
use crate::integrator::sampler::Sampler;
use crate::packet::{FloatLanes, MaskLanes, Rays, WIDTH, lane_set, mask_from};
use crate::world::World;

/// A handed-over lane between its shading and its shadow rays' answers.
struct Pending {
    /// The path, shaded, its shadow rays out.
    lane: PathLane<()>,
    /// Whether it goes on after the shadow rays.
    next: Next,
}

/// Which packet of shadow rays a shadow ray goes in: one per light, then
/// one toward the emitters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Target {
    /// Toward the point or directional light of this index.
    Light(usize),
    /// Toward a point drawn on the emitters.
    Emitter,
    /// Toward a direction drawn from the environment.
    Environment,
}

impl Target {
    /// The packet `shadow` goes in.
    fn of(shadow: &ShadowRay) -> Self {
        match shadow.target {
            ShadowTarget::Light(index) => Target::Light(index),
            ShadowTarget::Emitter(_) => Target::Emitter,
            ShadowTarget::Environment(_) => Target::Environment,
        }
    }
}

/// The lanes of one bounce that the scalar code shades. A group keeps one
/// for all its bounces, so that the shadow-ray lists are allocated once.
pub(super) struct Handover {
    /// The lanes handed over this bounce (bit k for lane k): most bounces
    /// hand over none, and then nothing below is read.
    handed: u32,
    pending: [Option<Pending>; WIDTH],
    /// Per lane, its shadow rays: at most one toward each light, then one
    /// toward the emitters, then one toward the environment, in that order (empty for a lane not handed over).
    shadows: [Vec<ShadowRay>; WIDTH],
    /// Per shadow ray of a lane, whether it is blocked (scratch).
    blocked: Vec<bool>,
}

impl Handover {
    /// No lane handed over.
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            handed: 0,
            pending: std::array::from_fn(|_| None),
            shadows: std::array::from_fn(|_| Vec::new()),
            blocked: Vec::new(),
        }
    }

    /// Shades the hits of the lanes `lanes` with `PathLane::shade`, taking
    /// their state out of `group`.
    #[inline(always)]
    pub(super) fn shade<F: FloatLanes>(
        &mut self,
        group: &mut Paths<F>,
        world: &World,
        options: &RenderOptions,
        lanes: F::Mask,
        closest: &Closest<F>,
    ) {
        if !lanes.any() {
            return;
        }
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
                sampler: Sampler::from_pixel_stream(group.streams.stream(k)),
            };
            let mut lane = PathLane::resume(state);
            let shadows = &mut self.shadows[k];
            debug_assert!(
                shadows.is_empty(),
                "the last bounce's shadow rays are answered"
            );
            let next = lane.shade(
                world,
                options,
                Some(closest.hit(k)),
                shadows,
                &mut NoRecorder,
            );
            self.pending[k] = Some(Pending { lane, next });
            self.handed |= 1 << k;
        }
    }

    /// The handed-over lanes with a shadow ray for packet `target`.
    #[inline(always)]
    pub(super) fn shadowed<F: FloatLanes>(&self, target: Target) -> F::Mask {
        if self.handed == 0 {
            return F::Mask::NONE;
        }
        mask_from::<F>(|k| self.shadow(k, target).is_some())
    }

    /// Lane `k`'s shadow ray for packet `target`, if it has one.
    #[inline(always)]
    fn shadow(&self, k: usize, target: Target) -> Option<&ShadowRay> {
        self.shadows[k].iter().find(|s| Target::of(s) == target)
    }

    /// `shadows`, the packet `target`, with the handed-over lanes' shadow
    /// rays for it in their lanes.
    #[inline(always)]
    pub(super) fn add_shadow_rays<F: FloatLanes>(
        &self,
        target: Target,
        mut shadows: Rays<F>,
    ) -> Rays<F> {
        let mut handed = self.handed;
        while handed != 0 {
            let k = handed.trailing_zeros() as usize;
            handed &= handed - 1;
            if let Some(shadow) = self.shadow(k, target) {
                shadows.origin.set_lane(k, shadow.ray.origin);
                shadows.dir.set_lane(k, shadow.ray.dir);
                shadows.t_max.as_mut_array()[k] = shadow.ray.t_max;
            }
        }
        shadows
    }

    /// Gives each handed-over lane its shadow rays' answers (`toward_lights`
    /// per light, `toward_emitter`, `toward_environment`: the lanes blocked
    /// in each packet), puts
    /// its state back into `group` and returns the lanes that finished (bit
    /// k for lane k).
    #[inline(always)]
    pub(super) fn finish<F: FloatLanes>(
        &mut self,
        group: &mut Paths<F>,
        toward_lights: &[F::Mask],
        toward_emitter: F::Mask,
        toward_environment: F::Mask,
    ) -> u32 {
        let mut finished = 0;
        let mut handed = std::mem::take(&mut self.handed);
        while handed != 0 {
            let k = handed.trailing_zeros() as usize;
            handed &= handed - 1;
            let Some(Pending { mut lane, next }) = self.pending[k].take() else {
                unreachable!("lane {k} was handed over");
            };
            let shadows = &mut self.shadows[k];
            self.blocked.clear();
            self.blocked.extend(shadows.iter().map(|s| {
                let packet = match Target::of(s) {
                    Target::Light(index) => toward_lights[index],
                    Target::Emitter => toward_emitter,
                    Target::Environment => toward_environment,
                };
                lane_set(packet, k)
            }));
            lane.finish(shadows, &self.blocked, &mut NoRecorder);
            shadows.clear();
            let state = lane.into_state();
            group.radiance.set_lane(k, state.radiance);
            group.throughput.set_lane(k, state.throughput);
            group.rays.origin.set_lane(k, state.ray.origin);
            group.rays.dir.set_lane(k, state.ray.dir);
            group.rays.t_max.as_mut_array()[k] = state.ray.t_max;
            let (point, pdf) = state.previous.unwrap_or_default();
            group.previous_point.set_lane(k, point);
            group.previous_pdf.as_mut_array()[k] = pdf;
            let lane_k = F::Mask::from_bitmask(1 << k);
            group.has_previous = if state.previous.is_some() {
                group.has_previous | lane_k
            } else {
                group.has_previous & !lane_k
            };
            group.eta_scale.as_mut_array()[k] = state.eta_scale;
            group.depth[k] = state.depth;
            if next == Next::Done {
                finished |= 1 << k;
            }
        }
        finished
    }
}
