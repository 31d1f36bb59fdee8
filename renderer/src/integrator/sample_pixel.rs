//! One sample of one pixel, from the pixel and the sample index alone: the
//! camera ray through the jittered point on the view window, traced by the
//! chosen integrator with the sample's own random numbers.

use super::lanes::camera_sample;
use super::recorder::{NoRecorder, Recorder};
use super::sampler::Sampler;
use super::{Integrator, RenderOptions, path::path_recorded, whitted::whitted_recorded};
use crate::geometry::ray::Ray;
use crate::world::World;
use glam::{Vec2, Vec3};

/// The radiance of sample `sample` of pixel (i, j): the ray through the
/// jittered point (i + x, j + y) on the view window, seeded from
/// (seed, pixel, sample) alone, so it can be re-traced exactly at any time.
pub fn sample_pixel(world: &World, options: &RenderOptions, i: u32, j: u32, sample: u32) -> Vec3 {
    sample_pixel_recorded(world, options, i, j, Some(sample), &mut NoRecorder).color
}

/// A sample as [`sample_pixel_recorded`] traced it.
#[derive(Clone, Copy, Debug)]
pub struct TracedSample {
    /// (x, y) in [0, 1)² where the camera ray crosses the pixel.
    pub offset: Vec2,
    /// The camera ray R_ij.
    pub ray: Ray,
    /// The radiance it brought back.
    pub color: Vec3,
}

/// [`sample_pixel`] telling `rec` about every ray: the one code path of the
/// film and the pixel inspector, so an inspected sample is bit for bit the
/// image's. With `sample` `None`, the ray goes through the pixel centre
/// (offset (½, ½), the ray of the AOVs) and the path tracer uses sample 0's
/// random numbers after it.
#[inline(always)]
pub fn sample_pixel_recorded<R: Recorder>(
    world: &World,
    options: &RenderOptions,
    i: u32,
    j: u32,
    sample: Option<u32>,
    rec: &mut R,
) -> TracedSample {
    let (sampler, offset, ray) = camera_sample(world, options, i, j, sample);
    let color = match options.integrator {
        Integrator::Whitted => whitted_recorded(world, &ray, options, rec),
        Integrator::Path => path_recorded(world, &ray, options, sampler, rec),
    };
    TracedSample { offset, ray, color }
}

/// (x, y) in [0, 1)², where sample `sample` of pixel (i, j) passes through
/// the pixel: the jitter replacing the lecture's (½, ½) in P_ij (the first
/// two numbers of the sample's stream, as [`sample_pixel`] draws them).
pub fn sample_offset(options: &RenderOptions, i: u32, j: u32, sample: u32) -> Vec2 {
    Sampler::for_pixel_sample(options.sampling, options.seed, i, j, sample).next_2d()
}
