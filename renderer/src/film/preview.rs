//! Coarse previews: one ray per block of pixels, so a first image of an edit
//! is on screen within a display frame.
//!
//! A preview traces sample 0 of every `stride`-th pixel in both directions,
//! the very samples that finer previews and the first full pass trace again;
//! [`PreviewSamples`] keeps them so that they are traced once per edit.

use super::PASS_CHUNK;
use crate::integrator::{RenderOptions, SampleRef, SampleResult, trace_samples};
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Rows of preview samples per parallel work item.
const BAND_ROWS: usize = 4;

/// Sample 0 of pixel (i, j) for every i and j that are multiples of the
/// stride, exactly as [`sample_pixel`](crate::integrator::sample_pixel) returns it (NaN and infinities kept).
#[derive(Clone, Debug)]
pub struct PreviewSamples {
    stride: u32,
    width: u32,
    height: u32,
    /// Samples per row: ⌈width / stride⌉.
    columns: usize,
    /// Row by row from the top.
    values: Vec<Vec3>,
    /// The shape tests each sample cost, in the same order.
    tests: Vec<u32>,
}

/// One row of preview samples: pixels 0, stride, 2 stride … of a pixel row.
#[derive(Clone, Copy, Debug)]
pub struct PreviewRow<'a> {
    /// The samples.
    pub values: &'a [Vec3],
    /// The shape tests each sample cost.
    pub tests: &'a [u32],
    /// The pixels between two samples.
    pub stride: u32,
}

impl PreviewSamples {
    /// Traces the samples of stride `stride`, taking those that `coarser`
    /// (samples of the same world and options, every stride it holds being a
    /// multiple of this one) already holds.
    pub fn trace(
        world: &World,
        options: &RenderOptions,
        stride: u32,
        coarser: Option<&PreviewSamples>,
    ) -> Self {
        Self::trace_unless(world, options, stride, coarser, &|| false).expect("never cancelled")
    }

    /// Like [`PreviewSamples::trace`], but strips of samples not yet started
    /// are skipped once `cancelled()` returns true, and then the preview is `None`: an
    /// edit need not wait for a stale preview to finish. Strips of a band of
    /// rows go through [`trace_samples`] together (the path tracer's SIMD
    /// lanes, Whitted's camera rays in squares of pixels), each sample [`sample_pixel`](crate::integrator::sample_pixel)'s bit for bit.
    pub fn trace_unless(
        world: &World,
        options: &RenderOptions,
        stride: u32,
        coarser: Option<&PreviewSamples>,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> Option<Self> {
        let (width, height) = (world.camera.w, world.camera.h);
        let stride = stride.max(1);
        let columns = width.div_ceil(stride) as usize;
        let rows = height.div_ceil(stride) as usize;
        let coarser =
            coarser.filter(|c| c.is_for(width, height) && c.stride.is_multiple_of(stride));
        let mut values = vec![Vec3::ZERO; columns * rows];
        let mut tests = vec![0u32; columns * rows];
        let skipped = AtomicBool::new(false);
        let band = columns * BAND_ROWS;
        values
            .par_chunks_mut(band)
            .zip(tests.par_chunks_mut(band))
            .enumerate()
            .for_each(|(band, (out, out_tests))| {
                let rows_in_band = out.len() / columns;
                // The band's samples that no coarser preview holds, gathered
                // in strips of columns, every row of a strip in turn, and
                // traced a strip at a time: a list of several rows keeps the
                // path tracer's lanes full to its end, and Whitted traces its
                // camera rays in squares of neighbouring pixels.
                let strip = ((PASS_CHUNK / rows_in_band) & !3).max(4);
                let mut wanted = Vec::with_capacity(PASS_CHUNK);
                let mut samples = Vec::with_capacity(PASS_CHUNK);
                let mut results = Vec::with_capacity(PASS_CHUNK);
                for start in (0..columns).step_by(strip) {
                    if cancelled() {
                        skipped.store(true, Ordering::Relaxed);
                        return;
                    }
                    let end = (start + strip).min(columns);
                    wanted.clear();
                    samples.clear();
                    for row in 0..rows_in_band {
                        let j = (band * BAND_ROWS + row) as u32 * stride;
                        let known = coarser
                            .and_then(|c| c.row(j))
                            .map(|row| (row, (row.stride / stride) as usize));
                        for_each_with_known_in(start..end, known, |k, sample| {
                            let at = row * columns + k;
                            match sample {
                                Some((value, tests)) => (out[at], out_tests[at]) = (value, tests),
                                None => {
                                    wanted.push(at);
                                    samples.push(SampleRef {
                                        i: k as u32 * stride,
                                        j,
                                        sample: 0,
                                    });
                                }
                            }
                        });
                    }
                    results.clear();
                    results.resize(samples.len(), SampleResult::default());
                    trace_samples(world, options, &samples, &mut results);
                    for (&at, result) in wanted.iter().zip(&results) {
                        out[at] = result.radiance;
                        out_tests[at] = u32::try_from(result.shape_tests).unwrap_or(u32::MAX);
                    }
                }
            });
        if skipped.load(Ordering::Relaxed) {
            return None;
        }
        Some(Self {
            stride,
            width,
            height,
            columns,
            values,
            tests,
        })
    }

    /// The stride: one sample per `stride` × `stride` block.
    pub fn stride(&self) -> u32 {
        self.stride
    }

    /// The image's width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// True when these are samples of a `width` × `height` image.
    pub fn is_for(&self, width: u32, height: u32) -> bool {
        (self.width, self.height) == (width, height)
    }

    /// How many samples these are.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True when there are none (never, for a valid camera).
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Sample 0 of pixel (i, j), when it is one of these.
    pub fn get(&self, i: u32, j: u32) -> Option<Vec3> {
        (i < self.width
            && j < self.height
            && i.is_multiple_of(self.stride)
            && j.is_multiple_of(self.stride))
        .then(|| {
            self.values[(j / self.stride) as usize * self.columns + (i / self.stride) as usize]
        })
    }

    /// The samples of pixel row `j` (pixels 0, stride, 2 stride …), when
    /// that row is one of these.
    pub fn row(&self, j: u32) -> Option<PreviewRow<'_>> {
        (j < self.height && j.is_multiple_of(self.stride)).then(|| {
            let range = (j / self.stride) as usize * self.columns..;
            let range = range.start..range.start + self.columns;
            PreviewRow {
                values: &self.values[range.clone()],
                tests: &self.tests[range],
                stride: self.stride,
            }
        })
    }

    /// Shape tests of each block's one sample, as an image row by row from
    /// the top (the cost heatmap of a preview).
    pub fn tests_image(&self) -> Vec<f32> {
        let costs: Vec<f32> = self.tests.iter().map(|&t| t as f32).collect();
        self.blocks(&costs)
    }

    /// The preview image, row by row from the top: each block shows the
    /// sample of its top-left pixel (black where that sample is not finite).
    pub fn image(&self) -> Vec<Vec3> {
        self.blocks(&self.finite_values())
    }

    /// The samples, row by row from the top, one per block, black where a
    /// sample is not finite: the preview image at its own resolution.
    pub fn finite_values(&self) -> Vec<Vec3> {
        self.values
            .iter()
            .map(|&v| if v.is_finite() { v } else { Vec3::ZERO })
            .collect()
    }

    /// An image where each block holds its entry of `per_sample` (one per
    /// sample, in the order of [`PreviewSamples::finite_values`]).
    pub fn blocks<T: Copy + Default + Send + Sync>(&self, per_sample: &[T]) -> Vec<T> {
        expand_blocks(per_sample, self.width, self.height, self.stride)
    }
}

/// A `width` × `height` image, row by row from the top, from one value per
/// `stride` × `stride` block (⌈width/stride⌉ per row of blocks): each pixel
/// holds its block's.
pub fn expand_blocks<T: Copy + Default + Send + Sync>(
    per_block: &[T],
    width: u32,
    height: u32,
    stride: u32,
) -> Vec<T> {
    let (w, stride) = (width as usize, stride.max(1) as usize);
    let columns = w.div_ceil(stride);
    let mut pixels = vec![T::default(); w * height as usize];
    pixels
        .par_chunks_mut(w * stride)
        .zip(per_block.par_chunks(columns))
        .for_each(|(rows, blocks)| {
            for (block, &value) in rows[..w].chunks_mut(stride).zip(blocks) {
                block.fill(value);
            }
            let (first, rest) = rows.split_at_mut(w);
            for row in rest.chunks_mut(w) {
                row.copy_from_slice(first);
            }
        });
    pixels
}

/// An image where each `stride` × `stride` block shows sample 0 of its
/// top-left pixel, row by row from the top. Stride 1 is one full sample.
pub fn preview(world: &World, options: &RenderOptions, stride: u32) -> Vec<Vec3> {
    PreviewSamples::trace(world, options, stride, None).image()
}

/// Calls `visit(index, known)` for every index in `range`, in order, where
/// `known` is the sample `row` already holds for that index — its value and
/// the shape tests it cost — or `None`: `row` holds one for every `step`-th
/// index from 0 (a finer preview: the stride ratio; a full pass: the stride).
/// Runs of `step` items, the first of each known, find them without a
/// division per item.
pub(super) fn for_each_with_known_in(
    range: std::ops::Range<usize>,
    known: Option<(PreviewRow, usize)>,
    mut visit: impl FnMut(usize, Option<(Vec3, u32)>),
) {
    let step = known.map_or(range.len(), |(_, step)| step).max(1);
    // The run holding the range's first index, and where it starts.
    let first_run = range.start / step;
    for (run, start) in (first_run * step..range.end).step_by(step).enumerate() {
        for index in start.max(range.start)..(start + step).min(range.end) {
            let sample = known
                .filter(|_| index == start)
                .map(|(row, _)| (row.values[first_run + run], row.tests[first_run + run]));
            visit(index, sample);
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::film::Film;
    use crate::integrator::sample_pixel;
    use scene::{Object, Scene, Shape};

    /// A world of the default shapes of `tags` seen by the default camera
    /// at `width` × `height` (shared with the pass's tests).
    pub(in crate::film) fn world_of(tags: &[&str], width: u32, height: u32) -> World {
        let scene = Scene {
            camera: scene::Camera {
                width,
                height,
                ..Default::default()
            },
            objects: tags
                .iter()
                .map(|tag| Object {
                    name: None,
                    shape: Shape::default_for_tag(tag).expect("tag"),
                    material: None,
                    params: Default::default(),
                })
                .collect(),
            ..Default::default()
        };
        World::from_scene(&scene).expect("valid")
    }

    fn world() -> World {
        world_of(&["cone", "sphere", "box", "floor"], 37, 21)
    }

    #[test]
    fn each_block_shows_the_first_sample_of_its_corner_pixel() {
        let world = world();
        let options = RenderOptions::default();
        let coarse = preview(&world, &options, 8);
        for (j, i) in [(0, 0), (8, 16), (20, 36), (19, 33)] {
            let corner = sample_pixel(&world, &options, (i / 8 * 8) as u32, (j / 8 * 8) as u32, 0);
            assert_eq!(coarse[j * 37 + i], corner, "pixel ({i}, {j})");
        }
    }

    /// Preview samples go through the batched tracer (the path tracer's
    /// SIMD lanes where the world allows them): each is still
    /// `sample_pixel`'s, bit for bit, for both integrators.
    #[test]
    fn every_preview_sample_is_sample_pixels_for_both_integrators() {
        use crate::integrator::Integrator;
        for world in [world(), world_of(&["sphere", "box", "sphere"], 37, 21)] {
            for integrator in [Integrator::Whitted, Integrator::Path] {
                let options = RenderOptions {
                    integrator,
                    ..Default::default()
                };
                let samples = PreviewSamples::trace(&world, &options, 2, None);
                for j in (0..21).step_by(2) {
                    for i in (0..37).step_by(2) {
                        let want = sample_pixel(&world, &options, i, j, 0);
                        let got = samples.get(i, j).expect("on the grid");
                        assert_eq!(
                            got.to_array().map(f32::to_bits),
                            want.to_array().map(f32::to_bits),
                            "{integrator:?} ({i}, {j})"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_cancelled_preview_is_none() {
        let world = world();
        let options = RenderOptions::default();
        let cancelled = PreviewSamples::trace_unless(&world, &options, 2, None, &|| true);
        assert!(cancelled.is_none());
        let done = PreviewSamples::trace_unless(&world, &options, 2, None, &|| false);
        assert_eq!(done.map(|d| d.len()), Some(19 * 11));
    }

    #[test]
    fn finer_samples_taken_from_coarser_ones_equal_samples_traced_afresh() {
        let world = world();
        let options = RenderOptions::default();
        let coarse = PreviewSamples::trace(&world, &options, 8, None);
        let reusing = PreviewSamples::trace(&world, &options, 4, Some(&coarse));
        let fresh = PreviewSamples::trace(&world, &options, 4, None);
        assert_eq!(reusing.values, fresh.values);
        assert_eq!(reusing.tests, fresh.tests, "costs are carried over too");
        assert_eq!(reusing.image(), preview(&world, &options, 4));
    }

    #[test]
    fn samples_are_held_for_exactly_the_pixels_on_the_stride_grid() {
        let world = world();
        let samples = PreviewSamples::trace(&world, &RenderOptions::default(), 4, None);
        assert_eq!(samples.len(), 10 * 6);
        for j in 0..world.camera.h + 4 {
            for i in 0..world.camera.w + 4 {
                let on_grid = i % 4 == 0 && j % 4 == 0 && i < 37 && j < 21;
                assert_eq!(samples.get(i, j).is_some(), on_grid, "({i}, {j})");
            }
        }
    }

    #[test]
    fn a_first_pass_reusing_a_preview_is_the_same_film_with_fewer_rays_traced() {
        let world = world();
        let options = RenderOptions::default();
        let known = PreviewSamples::trace(&world, &options, 2, None);
        let mut traced = Film::new(37, 21);
        let mut reusing = Film::new(37, 21);
        for _ in 0..2 {
            traced.add_pass(&world, &options);
            assert!(reusing.add_pass_reusing(&world, &options, &known, &|| false));
            assert_eq!(reusing.linear(), traced.linear(), "bit for bit");
            assert_eq!(reusing.cost_per_sample(), traced.cost_per_sample());
            assert_eq!(reusing.relative_variance(), traced.relative_variance());
        }
        assert_eq!(reusing.discarded(), traced.discarded());
        assert!(reusing.rays() < traced.rays());
    }

    #[test]
    fn stride_one_equals_the_first_full_pass() {
        let world = world();
        let options = RenderOptions::default();
        assert_eq!(
            preview(&world, &options, 1),
            Film::render(&world, &options, 1).linear()
        );
    }
}
