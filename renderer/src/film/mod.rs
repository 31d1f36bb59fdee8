//! Progressive accumulation: each pass adds one jittered sample per pixel —
//! to every pixel, or with adaptive sampling to those still noisy.

pub mod aov;
pub mod image_memory;
pub mod pixel_stats;
pub mod preview;

use crate::integrator::adaptive::{Adaptive, pixels_needing_samples};
use crate::integrator::{Integrator, RenderOptions, path, whitted};
use crate::film::pixel_stats::{PixelStats, luminance};
use crate::film::preview::PreviewSamples;
use crate::integrator::sampler::Sampler;
use crate::geometry::counters::shape_tests_on_this_thread;
use crate::world::World;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Rows per parallel work item: bands of rows are the tiles rayon shares out.
const BAND_ROWS: usize = 4;

/// The radiance of sample `sample` of pixel (i, j): the ray through the
/// jittered point (i + x, j + y) on the view window, seeded from
/// (seed, pixel, sample) alone, so it can be re-traced exactly at any time.
pub fn sample_pixel(world: &World, options: &RenderOptions, i: u32, j: u32, sample: u32) -> Vec3 {
    let mut sampler = Sampler::for_pixel_sample(options.sampling, options.seed, i, j, sample);
    let ray = world.camera.ray(i, j, sampler.next_2d());
    match options.integrator {
        Integrator::Whitted => whitted(world, &ray, options),
        Integrator::Path => path(world, &ray, options, &mut sampler),
    }
}

/// (x, y) in [0, 1)², where sample `sample` of pixel (i, j) passes through
/// the pixel: the jitter replacing the lecture's (½, ½) in P_ij (the first
/// two numbers of the sample's stream, as [`sample_pixel`] draws them).
pub fn sample_offset(options: &RenderOptions, i: u32, j: u32, sample: u32) -> Vec2 {
    Sampler::for_pixel_sample(options.sampling, options.seed, i, j, sample).next_2d()
}

/// A sum of samples per pixel with each pixel's sample count, and per pixel
/// the statistics of the diagnostic heatmaps and of adaptive sampling.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    sum: Vec<Vec3>,
    stats: Vec<PixelStats>,
    /// Samples traced per pixel (discarded ones included): the pass count
    /// everywhere unless adaptive sampling stopped the pixel.
    counts: Vec<u32>,
    passes: u32,
    /// Samples the last pass traced (all pixels without adaptive sampling).
    last_pass_samples: u64,
    samples: u64,
    discarded: u64,
    rays: u64,
}

impl Film {
    /// An empty film of `width` × `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            sum: vec![Vec3::ZERO; width as usize * height as usize],
            stats: vec![PixelStats::default(); width as usize * height as usize],
            counts: vec![0; width as usize * height as usize],
            passes: 0,
            last_pass_samples: 0,
            samples: 0,
            discarded: 0,
            rays: 0,
        }
    }

    /// Bytes a film holds per pixel (sum, statistics and sample count).
    pub fn bytes_per_pixel() -> u64 {
        (size_of::<Vec3>() + size_of::<PixelStats>() + size_of::<u32>()) as u64
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Passes so far: the samples of every pixel that never stopped.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// Samples traced so far, over all pixels.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Samples per pixel on average.
    pub fn mean_spp(&self) -> f64 {
        self.samples as f64 / self.counts.len().max(1) as f64
    }

    /// Samples each pixel has, row by row from the top.
    pub fn samples_per_pixel(&self) -> &[u32] {
        &self.counts
    }

    /// True once adaptive sampling has stopped every pixel: more passes add nothing.
    pub fn converged(&self) -> bool {
        self.passes > 0 && self.last_pass_samples == 0
    }

    /// Samples that came out NaN or infinite and were left out (counted, not hidden).
    pub fn discarded(&self) -> u64 {
        self.discarded
    }

    /// Rays traced for the passes so far: camera, secondary and shadow rays.
    pub fn rays(&self) -> u64 {
        self.rays
    }

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
        let (discarded, skipped, rays, traced): (u64, u64, u64, u64) = self
            .sum
            .par_chunks_mut(width * BAND_ROWS)
            .zip(self.stats.par_chunks_mut(width * BAND_ROWS))
            .zip(self.counts.par_chunks_mut(width * BAND_ROWS))
            .enumerate()
            .map(|(band, ((rows, stats), counts))| {
                if cancelled() {
                    return (0, 1, 0, 0);
                }
                let rays_before = crate::geometry::counters::rays_on_this_thread();
                let (mut bad, mut traced) = (0, 0);
                for (row, ((accs, stats), counts)) in rows
                    .chunks_mut(width)
                    .zip(stats.chunks_mut(width))
                    .zip(counts.chunks_mut(width))
                    .enumerate()
                {
                    let j = (band * BAND_ROWS + row) as u32;
                    let needing_row = needing.map(|n| &n[j as usize * width..][..width]);
                    // Blocks of pixels whose first sample may be known (no
                    // division per pixel): the whole row when none is.
                    let known_row = known.and_then(|k| k.row(j));
                    let stride = known_row.map_or(width, |row| row.stride as usize);
                    for (block, ((accs, stats), counts)) in accs
                        .chunks_mut(stride)
                        .zip(stats.chunks_mut(stride))
                        .zip(counts.chunks_mut(stride))
                        .enumerate()
                    {
                        for (k, ((acc, stat), count)) in
                            accs.iter_mut().zip(stats).zip(counts).enumerate()
                        {
                            let i = block * stride + k;
                            if needing_row.is_some_and(|n| !n[i]) {
                                continue;
                            }
                            let i = i as u32;
                            let (value, tests) = match known_row {
                                Some(row) if k == 0 => {
                                    (row.values[block], u64::from(row.tests[block]))
                                }
                                _ => {
                                    let before = shape_tests_on_this_thread();
                                    let value = sample_pixel(world, options, i, j, *count);
                                    (value, shape_tests_on_this_thread() - before)
                                }
                            };
                            *count += 1;
                            traced += 1;
                            stat.add_cost(tests);
                            // Welford's weight of this sample. A pixel that
                            // lost a NaN sample still counts it (rare, and
                            // the mean then treats it as black).
                            if value.is_finite() {
                                *acc += value;
                                stat.add(luminance(value), 1.0 / *count as f32);
                            } else {
                                bad += 1;
                            }
                        }
                    }
                }
                let rays = crate::geometry::counters::rays_on_this_thread() - rays_before;
                (bad, 0, rays, traced)
            })
            .reduce(
                || (0, 0, 0, 0),
                |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2, a.3 + b.3),
            );
        self.discarded += discarded;
        self.rays += rays;
        self.samples += traced;
        self.last_pass_samples = traced;
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

    /// The mean radiance of pixel (i, j).
    pub fn pixel(&self, i: u32, j: u32) -> Vec3 {
        let k = j as usize * self.width as usize + i as usize;
        self.sum[k] / self.counts[k].max(1) as f32
    }

    /// The mean radiance of every pixel, row by row from the top.
    pub fn linear(&self) -> Vec<Vec3> {
        self.sum
            .iter()
            .zip(&self.counts)
            .map(|(s, &n)| *s / n.max(1) as f32)
            .collect()
    }

    /// The relative variance of every pixel's mean (see
    /// [`PixelStats::relative_variance`]), row by row from the top; `None`
    /// below two passes.
    pub fn relative_variance(&self) -> Option<Vec<f32>> {
        (self.passes >= 2).then(|| {
            self.stats
                .iter()
                .zip(&self.counts)
                .map(|(s, &n)| s.relative_variance(n).unwrap_or(0.0))
                .collect()
        })
    }

    /// Shape tests per sample of every pixel, row by row from the top.
    pub fn cost_per_sample(&self) -> Vec<f32> {
        self.stats
            .iter()
            .zip(&self.counts)
            .map(|(s, &n)| s.cost_per_sample(n))
            .collect()
    }

    /// The image as 8-bit sRGB (clamped), row by row from the top.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.linear()
            .into_iter()
            .flat_map(linear_to_srgb8)
            .collect()
    }
}

/// One linear channel to 8-bit sRGB the direct way: clamp to [0, 1], the
/// sRGB transfer curve (`powf`), round. [`linear_to_srgb8`] gives the same bytes faster.
pub fn encode_srgb8_direct(x: f32) -> u8 {
    (scene::color::linear_to_srgb(x.clamp(0.0, 1.0)) * 255.0).round() as u8
}

/// Buckets of the fast encoding's first guess, over [0, 1].
const BUCKETS: usize = 4096;

/// The tables of the fast sRGB encoding.
struct Srgb8Table {
    /// `thresholds[k]`: the smallest f32 whose [`encode_srgb8_direct`] is ≥ k + 1.
    thresholds: [f32; 255],
    /// `bucket_start[b]`: the code of b / BUCKETS, a lower bound for the bucket.
    bucket_start: [u8; BUCKETS + 1],
}

/// The thresholds are found by bisection over the bit patterns of [0, 1]
/// (where float order is integer order); the encoding is monotonic, so a
/// value's code is the number of thresholds at or below it.
fn srgb8_table() -> &'static Srgb8Table {
    static TABLE: std::sync::OnceLock<Srgb8Table> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut thresholds = [0.0f32; 255];
        for (k, threshold) in (1u8..=255).zip(thresholds.iter_mut()) {
            let (mut below, mut at) = (0u32, 1.0f32.to_bits());
            while at - below > 1 {
                let middle = below + (at - below) / 2;
                if encode_srgb8_direct(f32::from_bits(middle)) >= k {
                    at = middle;
                } else {
                    below = middle;
                }
            }
            *threshold = f32::from_bits(at);
        }
        let mut bucket_start = [0u8; BUCKETS + 1];
        for (b, start) in bucket_start.iter_mut().enumerate() {
            let x = b as f32 / BUCKETS as f32; // exact: a power-of-two division
            *start = thresholds.partition_point(|&t| t <= x) as u8;
        }
        Srgb8Table {
            thresholds,
            bucket_start,
        }
    })
}

/// One channel through the tables: the bucket's code, then the few steps
/// inside the bucket.
fn encode_srgb8_fast(table: &Srgb8Table, x: f32) -> u8 {
    if !(x > 0.0) {
        return 0; // also NaN
    }
    if x >= 1.0 {
        return 255;
    }
    // x · BUCKETS is exact, so the bucket's lower bound is ≤ x.
    let mut code = table.bucket_start[(x * BUCKETS as f32) as usize];
    while code < 255 && x >= table.thresholds[code as usize] {
        code += 1;
    }
    code
}

/// Linear radiance to an 8-bit sRGB pixel, clamping to [0, 1] (NaN gives 0):
/// exactly the bytes of [`encode_srgb8_direct`], from tables instead of `powf`.
pub fn linear_to_srgb8(c: Vec3) -> [u8; 3] {
    let table = srgb8_table();
    [
        encode_srgb8_fast(table, c.x),
        encode_srgb8_fast(table, c.y),
        encode_srgb8_fast(table, c.z),
    ]
}
