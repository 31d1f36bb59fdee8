//! Both integrators traced in batches: every sample's radiance is the one
//! the same sample gets traced alone, bit for bit, whatever list it is
//! traced in, the order of the samples or the thread count.

use glam::Vec3;
use renderer::integrator::sampler::Sampling;
use renderer::integrator::{Integrator, SampleRef, SampleResult, sample_pixel, trace_samples};
use renderer::{Film, Method, RenderOptions, World};
mod common;

fn reference(name: &str, width: u32, height: u32) -> World {
    common::asset_world("reference", name, width, height)
}

fn shipped(name: &str, width: u32, height: u32) -> World {
    common::asset_world("scenes", name, width, height)
}

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

#[test]
fn a_batched_sample_is_the_sample_traced_alone_bit_for_bit_in_any_list() {
    let worlds = [
        ("spheres.xml", reference("spheres.xml", 24, 18)),
        ("rough.xml", reference("rough.xml", 16, 16)),
        ("glass.xml", shipped("glass.xml", 20, 12)),
        ("seed.xml", shipped("seed.xml", 20, 12)),
        ("cornell.xml", shipped("cornell.xml", 12, 12)),
        ("roughness.xml", shipped("roughness.xml", 16, 10)),
    ];
    let settings = [
        (Integrator::Path, Sampling::Independent),
        (Integrator::Path, Sampling::Sobol),
        (Integrator::Whitted, Sampling::Independent),
    ];
    for (name, world) in &worlds {
        for (integrator, sampling) in settings {
            let options = RenderOptions {
                integrator,
                method: Method::Robust,
                sampling,
                seed: 5,
                ..Default::default()
            };
            // Samples in a scrambled order, several per pixel.
            let mut samples = Vec::new();
            for k in [0, 3, 17] {
                for j in 0..world.camera.h {
                    for i in 0..world.camera.w {
                        samples.push(SampleRef { i, j, sample: k });
                    }
                }
            }
            samples.reverse();
            let third = samples.len() / 3;
            samples.rotate_left(third);
            let alone: Vec<[u32; 3]> = samples
                .iter()
                .map(|s| bits(sample_pixel(world, &options, s.i, s.j, s.sample)))
                .collect();
            // The list whole, or cut into lists of `batch` traced one by one.
            for batch in [1, 2, 7, 64, samples.len()] {
                let mut results = vec![SampleResult::default(); samples.len()];
                for (list, out) in samples.chunks(batch).zip(results.chunks_mut(batch)) {
                    trace_samples(world, &options, list, out);
                }
                for ((s, result), expected) in samples.iter().zip(&results).zip(&alone) {
                    assert_eq!(
                        &bits(result.radiance),
                        expected,
                        "{name} {integrator:?} {sampling:?} batch {batch}: pixel ({}, {}) sample {}",
                        s.i,
                        s.j,
                        s.sample
                    );
                }
            }
        }
    }
}

#[test]
fn a_film_is_the_same_on_one_thread_and_on_all() {
    for (integrator, world) in [
        (Integrator::Path, reference("cornell.xml", 40, 40)),
        (Integrator::Whitted, shipped("glass.xml", 40, 40)),
    ] {
        let options = RenderOptions {
            integrator,
            sampling: Sampling::Sobol,
            ..Default::default()
        };
        let all = Film::render(&world, &options, 3);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a one-thread pool")
            .install(|| Film::render(&world, &options, 3));
        for j in 0..40 {
            for i in 0..40 {
                assert_eq!(
                    bits(all.pixel(i, j)),
                    bits(one.pixel(i, j)),
                    "{integrator:?} pixel ({i}, {j})"
                );
            }
        }
    }
}

/// Whitted's ray trees, grown level by level and tested in packets, give
/// the recursion's radiance bit for bit at every depth limit: the limit
/// decides which hits ask for reflected and refracted rays.
#[test]
fn whitted_trees_give_the_recursions_radiance_at_every_depth_limit() {
    for (name, world) in [
        ("glass.xml", shipped("glass.xml", 20, 12)),
        ("primitives.xml", shipped("primitives.xml", 16, 12)),
    ] {
        for max_depth in [0, 1, 2, 3] {
            let options = RenderOptions {
                integrator: Integrator::Whitted,
                max_depth,
                ..Default::default()
            };
            let samples: Vec<SampleRef> = (0..world.camera.h)
                .flat_map(|j| (0..world.camera.w).map(move |i| SampleRef { i, j, sample: 1 }))
                .collect();
            let mut results = vec![SampleResult::default(); samples.len()];
            trace_samples(&world, &options, &samples, &mut results);
            for (s, result) in samples.iter().zip(&results) {
                let alone = sample_pixel(&world, &options, s.i, s.j, s.sample);
                assert_eq!(
                    bits(result.radiance),
                    bits(alone),
                    "{name} max depth {max_depth}: pixel ({}, {})",
                    s.i,
                    s.j
                );
            }
        }
    }
}
