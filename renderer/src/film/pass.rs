//! Accumulating a pass: one sample for every pixel that needs one, traced
//! in parallel over bands of rows. A pixel's k-th sample is sample index k
//! of [`sample_pixel`](crate::integrator::sample_pixel), so a film is the same for any number of threads and
//! every sample can be re-traced exactly.

use super::Film;
use super::preview::{PreviewSamples, for_each_with_known};
use crate::geometry::counters::rays_on_this_thread;
use crate::integrator::adaptive::{Adaptive, pixels_needing_samples};
use crate::integrator::{RenderOptions, SampleRef, SampleResult, trace_samples};
use crate::world::World;
use rayon::prelude::*;
use scene::color::luminance;

/// Rows per parallel work item: bands of rows are the tiles rayon shares out.
const BAND_ROWS: usize = 4;

impl Film {
    /// Adds one sample to every pixel that needs one (a pixel's k-th sample
    /// traces sample index k), in parallel over bands of rows. Every pixel
    /// needs one unless `options.adaptive` stopped it.
    pub fn add_pass(&mut self, world: &World, options: &RenderOptions) {
        let completed = self.add_pass_unless(world, options, &|| false);
        debug_assert!(completed);
    }

    /// Like [`Film::add_pass`], but bands not yet started are skipped once
    /// `cancelled()` returns true. Returns false when the pass was cut short:
    /// the film then holds a partial pass and must be discarded.
    pub fn add_pass_unless(
        &mut self,
        world: &World,
        options: &RenderOptions,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        self.add_pass_inner(world, options, None, cancelled)
    }

    /// Like [`Film::add_pass_unless`], but the first pass takes the samples
    /// that `known` holds instead of tracing them again: `known` must come
    /// from the same world and options (a preview of this very job). The film
    /// is bit for bit the same; [`Film::rays`] counts only the rays traced here.
    pub fn add_pass_reusing(
        &mut self,
        world: &World,
        options: &RenderOptions,
        known: &PreviewSamples,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let known = known
            .is_for(self.width, self.height)
            .then_some(known)
            .filter(|_| self.passes == 0);
        self.add_pass_inner(world, options, known, cancelled)
    }

    fn add_pass_inner(
        &mut self,
        world: &World,
        options: &RenderOptions,
        known: Option<&PreviewSamples>,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let width = self.width as usize;
        let needing = options
            .adaptive
            .filter(|_| self.passes >= Adaptive::MIN_SAMPLES)
            .map(|adaptive| {
                let variance: Vec<f32> = self
                    .stats
                    .iter()
                    .zip(&self.counts)
                    .map(|(s, &n)| s.relative_variance(n).unwrap_or(f32::INFINITY))
                    .collect();
                pixels_needing_samples(width, self.height as usize, &variance, adaptive.threshold)
            });
        let needing = needing.as_deref();
        let (discarded, skipped, rays, samples): (u64, u64, u64, u64) = self
            .sum
            .par_chunks_mut(width * BAND_ROWS)
            .zip(self.stats.par_chunks_mut(width * BAND_ROWS))
            .zip(self.counts.par_chunks_mut(width * BAND_ROWS))
            .enumerate()
            .map(|(band, ((rows, stats), counts))| {
                if cancelled() {
                    return (0, 1, 0, 0);
                }
                let rays_before = rays_on_this_thread();
                // The band's samples: those a preview already holds, and those
                // to trace (together, so the path tracer can batch them).
                let mut found: Vec<(usize, SampleResult)> = Vec::with_capacity(counts.len());
                let mut todo: Vec<(usize, SampleRef)> = Vec::with_capacity(counts.len());
                for row in 0..counts.len() / width {
                    let j = (band * BAND_ROWS + row) as u32;
                    let needing_row = needing.map(|n| &n[j as usize * width..][..width]);
                    let known_row = known
                        .and_then(|k| k.row(j))
                        .map(|row| (row, row.stride as usize));
                    for_each_with_known(width, known_row, |i, sample| {
                        if needing_row.is_some_and(|n| !n[i]) {
                            return;
                        }
                        let at = row * width + i;
                        match sample {
                            Some((radiance, tests)) => found.push((
                                at,
                                SampleResult {
                                    radiance,
                                    shape_tests: u64::from(tests),
                                },
                            )),
                            None => todo.push((
                                at,
                                SampleRef {
                                    i: i as u32,
                                    j,
                                    sample: counts[at],
                                },
                            )),
                        }
                    });
                }
                let samples: Vec<SampleRef> = todo.iter().map(|&(_, s)| s).collect();
                let mut traced_results = vec![SampleResult::default(); samples.len()];
                trace_samples(world, options, &samples, &mut traced_results);
                found.extend(todo.iter().map(|&(at, _)| at).zip(traced_results));
                let (mut bad, mut traced) = (0, 0);
                for (at, result) in found {
                    let (acc, stat, count) = (&mut rows[at], &mut stats[at], &mut counts[at]);
                    let value = result.radiance;
                    *count += 1;
                    traced += 1;
                    stat.add_cost(result.shape_tests);
                    // Welford's weight of this sample. A pixel that lost
                    // a NaN sample still counts it (rare, and the mean
                    // then treats it as black).
                    if value.is_finite() {
                        *acc += value;
                        stat.add(luminance(value), 1.0 / *count as f32);
                    } else {
                        bad += 1;
                    }
                }
                let rays = rays_on_this_thread() - rays_before;
                (bad, 0, rays, traced)
            })
            .reduce(
                || (0, 0, 0, 0),
                |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2, a.3 + b.3),
            );
        self.discarded += discarded;
        self.rays += rays;
        self.samples += samples;
        self.last_pass_samples = samples;
        self.passes += 1;
        skipped == 0
    }

    /// A film with `spp` passes of `world`.
    pub fn render(world: &World, options: &RenderOptions, spp: u32) -> Film {
        let mut film = Film::new(world.camera.w, world.camera.h);
        for _ in 0..spp {
            film.add_pass(world, options);
        }
        film
    }
}
