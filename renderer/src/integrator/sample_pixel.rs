//! One sample of one pixel, from the pixel and the sample index alone: the
//! camera ray through the jittered point on the view window, traced by the
//! chosen integrator with the sample's own random numbers.

use super::sampler::Sampler;
use super::{Integrator, RenderOptions, path, whitted};
use crate::world::World;
use glam::{Vec2, Vec3};

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
