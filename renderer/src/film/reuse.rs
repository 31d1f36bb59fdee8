//! Samples traced once per edit: a preview traces sample 0 of every
//! stride-th pixel, and finer previews and the first full pass take those
//! samples instead of tracing them again. Both walk a row of samples the
//! same way, here.

use crate::geometry::counters::shape_tests_on_this_thread;
use crate::integrator::{RenderOptions, sample_pixel};
use crate::world::World;
use glam::Vec3;

/// The samples of a row already traced: those of every `step`-th item of
/// the row, from item 0 (a row of [`PreviewSamples`](super::preview::PreviewSamples)).
#[derive(Clone, Copy, Debug)]
pub(super) struct Known<'a> {
    /// The samples, one per `step` items.
    pub values: &'a [Vec3],
    /// The shape tests each sample cost.
    pub tests: &'a [u32],
    /// Items from one known sample to the next.
    pub step: usize,
}

/// Calls `visit(index, known)` for every index in 0..`len`, in order, where
/// `known` is the sample already traced for that index — its value and the
/// shape tests it cost — or `None`. Runs of `step` items, the first of each
/// known, find them without a division per item.
pub(super) fn for_each_with_known(
    len: usize,
    known: Option<Known>,
    mut visit: impl FnMut(usize, Option<(Vec3, u32)>),
) {
    let step = known.map_or(len, |k| k.step).max(1);
    for (run, start) in (0..len).step_by(step).enumerate() {
        for index in start..(start + step).min(len) {
            let sample = known
                .filter(|_| index == start)
                .map(|k| (k.values[run], k.tests[run]));
            visit(index, sample);
        }
    }
}

/// Sample `sample` of pixel (i, j), traced, and the shape tests it cost.
pub(super) fn trace_with_cost(
    world: &World,
    options: &RenderOptions,
    i: u32,
    j: u32,
    sample: u32,
) -> (Vec3, u64) {
    let before = shape_tests_on_this_thread();
    let value = sample_pixel(world, options, i, j, sample);
    (value, shape_tests_on_this_thread() - before)
}
