//! The film: per pixel, the sum of the samples traced so far, their count
//! and the statistics of the diagnostic heatmaps. `pass.rs` accumulates one
//! pass of samples into it (every pixel, or with adaptive sampling those
//! still noisy); [`preview`] traces the coarse images shown first; [`aov`]
//! the per-pixel outputs beside the colour.

pub mod aov;
pub mod image_memory;
mod pass;
pub mod pixel_stats;
pub mod preview;

use glam::Vec3;
use pixel_stats::PixelStats;
use rayon::prelude::*;

/// Samples a worker gathers, traces and accumulates at a time (a pass's
/// and a preview's): enough for the path tracer's batches to stay full, few enough that a
/// worker's lists stay in its caches and do not grow with the image's width.
pub const PASS_CHUNK: usize = 1024;

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
    /// The arrays are fresh pages from the OS, zero but not yet written:
    /// the first pass writes each band before adding to it.
    fresh_pages: bool,
    passes: u32,
    /// Samples the last pass traced (all pixels without adaptive sampling).
    last_pass_samples: u64,
    samples: u64,
    discarded: u64,
    rays: u64,
    /// The pixels traced: all, or a rectangle (a render split by regions).
    region: Option<Region>,
    /// The sample index of a pixel's first sample here: its k-th sample
    /// traces index `first_sample + k` (a render split by sample ranges).
    first_sample: u32,
}

/// A rectangle of pixels: columns `x0..x1`, rows `y0..y1` (rows from the
/// top, as the image's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Region {
    /// True when pixel (i, j) is inside.
    #[inline]
    pub fn contains(&self, i: u32, j: u32) -> bool {
        (self.x0..self.x1).contains(&i) && (self.y0..self.y1).contains(&j)
    }

    /// True when the two share a pixel.
    pub fn overlaps(&self, other: &Region) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// Pixels inside.
    pub fn pixels(&self) -> u64 {
        u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0)
    }
}

impl Film {
    /// An empty film of `width` × `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        // Zeroed allocations: fresh pages from the OS, already zero, are
        // not written here but where a pass first adds to them (a film of
        // 1280×720 is 30 MB; writing it held up every edit's first preview).
        let pixels = width as usize * height as usize;
        Self {
            width,
            height,
            sum: bytemuck::zeroed_vec(pixels),
            stats: bytemuck::zeroed_vec(pixels),
            counts: vec![0; pixels],
            fresh_pages: true,
            passes: 0,
            region: None,
            first_sample: 0,
            last_pass_samples: 0,
            samples: 0,
            discarded: 0,
            rays: 0,
        }
    }

    /// This film tracing only the pixels of `region` (the others stay
    /// zero, with no samples): each pixel gets exactly the samples it gets
    /// in the whole image, since a sample is seeded by (seed, pixel, index).
    /// `region` must lie inside the image and hold a pixel.
    pub fn in_region(mut self, region: Region) -> Self {
        assert!(
            region.x0 < region.x1
                && region.y0 < region.y1
                && region.x1 <= self.width
                && region.y1 <= self.height,
            "{region:?} inside {}×{}",
            self.width,
            self.height
        );
        self.region = Some(region);
        self
    }

    /// This film's pixels taking sample indices from `first` on: its k-th
    /// pass traces index `first + k` of every pixel, the samples the whole
    /// render's pass `first + k` traces.
    pub fn from_sample(mut self, first: u32) -> Self {
        self.first_sample = first;
        self
    }

    /// An empty film of `width` × `height` pixels in `old`'s memory when it
    /// is of that size (zeroed in parallel, a few ms for 1280×720), else a
    /// [`Film::new`]. A new film's 30 MB of fresh pages cost a first pass
    /// more than that in page faults (~10 ms on two threads).
    pub fn recycled(old: Option<Film>, width: u32, height: u32) -> Self {
        let Some(mut film) = old.filter(|f| (f.width, f.height) == (width, height)) else {
            return Self::new(width, height);
        };
        film.sum.par_iter_mut().for_each(|s| *s = Vec3::ZERO);
        film.stats
            .par_iter_mut()
            .for_each(|s| *s = PixelStats::default());
        film.counts.par_iter_mut().for_each(|n| *n = 0);
        Self {
            passes: 0,
            last_pass_samples: 0,
            samples: 0,
            discarded: 0,
            rays: 0,
            region: None,
            first_sample: 0,
            ..film
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

    /// The mean radiance of pixel (i, j).
    pub fn pixel(&self, i: u32, j: u32) -> Vec3 {
        let k = j as usize * self.width as usize + i as usize;
        self.sum[k] / self.counts[k].max(1) as f32
    }

    /// The mean radiance of every pixel, row by row from the top.
    pub fn linear(&self) -> Vec<Vec3> {
        self.sum
            .par_iter()
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
}
