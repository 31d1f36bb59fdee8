//! Accumulating a pass: one sample for every pixel that needs one, traced
//! in parallel over bands of rows. A pixel's k-th sample is sample index k
//! of [`sample_pixel`](crate::integrator::sample_pixel), so a film is the same for any number of threads and
//! every sample can be re-traced exactly.

use super::preview::{PreviewSamples, for_each_with_known_in};
use super::{Film, PASS_CHUNK, PixelStats};
use crate::geometry::counters::rays_on_this_thread;
use crate::integrator::adaptive::{Adaptive, pixels_needing_samples};
use crate::integrator::{RenderOptions, SampleRef, SampleResult, trace_samples};
use crate::world::World;
use glam::Vec3;
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

    /// Like [`Film::add_pass`], but once `cancelled()` returns true, bands
    /// not yet started are skipped and bands under way stop at their next
    /// chunk of samples. Returns false when the pass was cut short:
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
            .filter(|_| self.passes == 0 && self.first_sample == 0 && self.region.is_none());
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
        let fresh_pages = std::mem::take(&mut self.fresh_pages);
        let (region, first_sample) = (self.region, self.first_sample);
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
                if fresh_pages {
                    // Written before they are read: a new film's pages, fresh
                    // from the OS, are then each faulted in once, not first
                    // mapped to the zero page by a read and then copied on
                    // write, with a TLB flush on every core.
                    rows.fill(Vec3::ZERO);
                    stats.fill(PixelStats::default());
                    counts.fill(0);
                }
                let rays_before = rays_on_this_thread();
                // The band's samples, at most PASS_CHUNK at a time (so a
                // worker's memory does not grow with the image's width):
                // those a preview already holds, and those to trace
                // (together, so the path tracer can batch them).
                let mut chunk = Chunk::with_capacity(PASS_CHUNK.min(counts.len()));
                let (mut bad, mut traced) = (0, 0);
                let rows_in_band = counts.len() / width;
                // The band is gathered in strips of columns, every row of
                // a strip in turn, so that a chunk holds squares of
                // neighbouring pixels (Whitted traces camera rays in 4 × 4
                // tiles).
                // (A multiple of four columns, so tiles stay on the grid.)
                let strip = ((PASS_CHUNK / rows_in_band) & !3).max(4);
                let mut start = 0;
                while start < width {
                    let end = (start + strip).min(width);
                    for row in 0..rows_in_band {
                        let j = (band * BAND_ROWS + row) as u32;
                        if region.is_some_and(|r| !(r.y0..r.y1).contains(&j)) {
                            continue;
                        }
                        let needing_row = needing.map(|n| &n[j as usize * width..][..width]);
                        let known_row = known
                            .and_then(|k| k.row(j))
                            .map(|row| (row, row.stride as usize));
                        // The strip's columns inside the region, if any.
                        let (lo, hi) =
                            region.map_or((start, end), |r| (r.x0 as usize, r.x1 as usize));
                        let columns = start.max(lo)..end.min(hi).max(start.max(lo));
                        for_each_with_known_in(columns, known_row, |i, sample| {
                            if needing_row.is_some_and(|n| !n[i]) {
                                return;
                            }
                            let at = row * width + i;
                            match sample {
                                Some((radiance, tests)) => chunk.found.push((
                                    at,
                                    SampleResult {
                                        radiance,
                                        shape_tests: u64::from(tests),
                                    },
                                )),
                                None => {
                                    chunk.at.push(at);
                                    chunk.samples.push(SampleRef {
                                        i: i as u32,
                                        j,
                                        sample: first_sample + counts[at],
                                    });
                                }
                            }
                        });
                    }
                    start = end;
                    // A stale pass stops within a chunk, not a band: an
                    // edit's preview waits for at most this much.
                    if cancelled() {
                        return (bad, 1, rays_on_this_thread() - rays_before, traced);
                    }
                    let (b, t) = chunk.trace_and_add(world, options, rows, stats, counts);
                    (bad, traced) = (bad + b, traced + t);
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

    /// The most memory one worker holds while it adds its share of a pass
    /// of `world` (bytes): one chunk's sample lists and the path tracer's
    /// batch of lanes. It does not depend on the image's size.
    pub fn pass_bytes_per_thread(world: &World) -> usize {
        PASS_CHUNK * Chunk::BYTES_PER_SAMPLE
            + crate::integrator::path_batch_bytes(world, PASS_CHUNK)
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

/// The samples of a band a worker is gathering: those a preview holds
/// (`found`, by index in the band) and those to trace (`samples`, with their
/// indices in `at`).
struct Chunk {
    found: Vec<(usize, SampleResult)>,
    at: Vec<usize>,
    samples: Vec<SampleRef>,
    /// Scratch: the traced samples' results.
    results: Vec<SampleResult>,
}

impl Chunk {
    /// Bytes a chunk's lists hold per sample of capacity.
    const BYTES_PER_SAMPLE: usize = std::mem::size_of::<(usize, SampleResult)>()
        + std::mem::size_of::<usize>()
        + std::mem::size_of::<SampleRef>()
        + std::mem::size_of::<SampleResult>();

    fn with_capacity(n: usize) -> Self {
        Chunk {
            found: Vec::with_capacity(n),
            at: Vec::with_capacity(n),
            samples: Vec::with_capacity(n),
            results: Vec::with_capacity(n),
        }
    }

    /// Traces the samples to trace, adds every sample to the band's pixels
    /// (`rows`, `stats`, `counts`), and empties the chunk. Returns the
    /// samples lost to NaN or infinity, and the samples added.
    fn trace_and_add(
        &mut self,
        world: &World,
        options: &RenderOptions,
        rows: &mut [Vec3],
        stats: &mut [PixelStats],
        counts: &mut [u32],
    ) -> (u64, u64) {
        self.results.clear();
        self.results
            .resize(self.samples.len(), SampleResult::default());
        trace_samples(world, options, &self.samples, &mut self.results);
        let traced = self.at.drain(..).zip(self.results.iter().copied());
        let (mut bad, mut added) = (0, 0);
        for (at, result) in self.found.drain(..).chain(traced) {
            let (acc, stat, count) = (&mut rows[at], &mut stats[at], &mut counts[at]);
            let value = result.radiance;
            *count += 1;
            added += 1;
            stat.add_cost(result.shape_tests);
            // Welford's weight of this sample. A pixel that lost a NaN
            // sample still counts it (rare, and the mean then treats it as
            // black).
            if value.is_finite() {
                *acc += value;
                stat.add(luminance(value), 1.0 / *count as f32);
            } else {
                bad += 1;
            }
        }
        self.samples.clear();
        (bad, added)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::preview::PreviewSamples;
    use crate::film::preview::tests::world_of;
    use crate::integrator::{Integrator, sample_pixel};

    /// A world wider than a chunk: a band's pixels span several chunks, and
    /// chunks span rows.
    fn wide_world(width: u32, height: u32) -> World {
        world_of(&["sphere", "box", "floor"], width, height)
    }

    /// A film made in the memory of another (of the same size, or not) is
    /// the film a new one becomes, bit for bit, pass after pass.
    #[test]
    fn a_recycled_film_is_a_new_film() {
        let world = wide_world(40, 9);
        let options = RenderOptions::default();
        let expected = Film::render(&world, &options, 2);
        let other = Film::render(&wide_world(40, 9), &options, 3);
        let smaller = Film::render(&wide_world(20, 9), &options, 1);
        for old in [Some(other), Some(smaller), None] {
            let mut film = Film::recycled(old, 40, 9);
            assert_eq!(film.passes(), 0);
            assert!(film.linear().iter().all(|&p| p == Vec3::ZERO));
            for _ in 0..2 {
                film.add_pass(&world, &options);
            }
            assert_eq!(film.linear(), expected.linear());
            assert_eq!(film.cost_per_sample(), expected.cost_per_sample());
            assert_eq!(film.relative_variance(), expected.relative_variance());
            assert_eq!(film.samples(), expected.samples());
        }
    }

    #[test]
    fn a_pass_traced_chunk_by_chunk_holds_each_pixels_own_sample() {
        let (w, h) = (PASS_CHUNK as u32 + 301, 6);
        let world = wide_world(w, h);
        for integrator in [Integrator::Whitted, Integrator::Path] {
            let options = RenderOptions {
                integrator,
                ..RenderOptions::default()
            };
            let film = Film::render(&world, &options, 1);
            let linear = film.linear();
            let lit = linear.iter().filter(|p| p.max_element() > 0.0).count();
            assert!(
                lit > linear.len() / 4,
                "{integrator:?}: the scene is in view ({lit} lit)"
            );
            for j in 0..h {
                for i in 0..w {
                    let want = sample_pixel(&world, &options, i, j, 0);
                    let got = linear[(j * w + i) as usize];
                    assert_eq!(got, want, "{integrator:?}: pixel ({i}, {j})");
                }
            }
        }
    }

    /// A pass cancelled while a band is under way stops at that band's next
    /// chunk: with one band of several chunks, a cancel seen at the second
    /// check leaves most of the band untraced, and the pass says it was cut
    /// short.
    #[test]
    fn a_cancelled_pass_stops_within_a_band() {
        let (w, h) = (3 * PASS_CHUNK as u32, BAND_ROWS as u32);
        let world = wide_world(w, h);
        let checks = std::sync::atomic::AtomicUsize::new(0);
        // False at the band's start and its first chunk, true from then on.
        let cancelled = || checks.fetch_add(1, std::sync::atomic::Ordering::SeqCst) >= 2;
        let mut film = Film::new(w, h);
        assert!(!film.add_pass_unless(&world, &RenderOptions::default(), &cancelled));
        assert_eq!(
            film.samples(),
            PASS_CHUNK as u64,
            "one chunk traced of {}",
            w * h
        );
    }

    #[test]
    fn preview_samples_on_both_sides_of_a_chunk_edge_are_reused_exactly() {
        let (w, h) = (PASS_CHUNK as u32 + 301, 6);
        let world = wide_world(w, h);
        let options = RenderOptions::default();
        // A stride that does not divide the chunk: runs straddle its edges.
        let known = PreviewSamples::trace(&world, &options, 3, None);
        let mut traced = Film::new(w, h);
        let mut reusing = Film::new(w, h);
        traced.add_pass(&world, &options);
        assert!(reusing.add_pass_reusing(&world, &options, &known, &|| false));
        assert_eq!(reusing.linear(), traced.linear(), "bit for bit");
        assert_eq!(reusing.cost_per_sample(), traced.cost_per_sample());
        assert!(
            reusing.rays() < traced.rays(),
            "the known samples were not traced again"
        );
    }

    #[test]
    fn a_workers_pass_memory_is_bounded_whatever_the_image_size() {
        let small = Film::pass_bytes_per_thread(&wide_world(64, 36));
        let uhd = Film::pass_bytes_per_thread(&wide_world(3840, 2160));
        assert_eq!(small, uhd, "independent of the image's size");
        assert!(uhd <= 256 * 1024, "{uhd} bytes per worker at 3840×2160");
        println!("pass memory per worker: {uhd} bytes");
    }

    /// A render split by regions gives each pixel exactly the whole
    /// render's value; one split by sample ranges, weighted by their
    /// counts, its mean within rounding (both integrators).
    #[test]
    fn regions_and_sample_ranges_of_a_render_put_back_together_are_the_whole_render() {
        use crate::film::Region;
        let (w, h) = (37, 11);
        let world = wide_world(w, h);
        for integrator in [Integrator::Whitted, Integrator::Path] {
            let options = RenderOptions {
                integrator,
                ..RenderOptions::default()
            };
            let whole = Film::render(&world, &options, 3).linear();
            let region = Region {
                x0: 5,
                y0: 2,
                x1: 30,
                y1: 9,
            };
            let mut part = Film::new(w, h).in_region(region);
            for _ in 0..3 {
                part.add_pass(&world, &options);
            }
            let part = part.linear();
            for j in 0..h {
                for i in 0..w {
                    let k = (j * w + i) as usize;
                    let want = if region.contains(i, j) {
                        whole[k]
                    } else {
                        Vec3::ZERO
                    };
                    assert_eq!(part[k], want, "{integrator:?} pixel ({i}, {j})");
                }
            }
            let first = Film::render(&world, &options, 2).linear();
            let mut rest = Film::new(w, h).from_sample(2);
            rest.add_pass(&world, &options);
            let rest = rest.linear();
            for k in 0..whole.len() {
                let merged = (first[k] * 2.0 + rest[k]) / 3.0;
                let scale = whole[k].max_element().max(1e-3);
                assert!(
                    (merged - whole[k]).abs().max_element() <= 1e-6 * scale,
                    "{integrator:?} pixel {k}: {merged} against {}",
                    whole[k]
                );
            }
        }
    }
}
