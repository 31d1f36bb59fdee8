//! Whitted's samples on the film, sixteen at a time: the closest hits of
//! their camera rays are found together — in SIMD packets in a world of
//! lone triangles (small meshes' included), boxes, spheres, planes and a
//! few cylinders, cones and tori ([`PacketShapes`]), as a batch through
//! each mesh instance in a world of meshes ([`World::intersect_batch`]),
//! which takes coherent rays in packets. A sample's radiance is
//! [`sample_pixel`](super::sample_pixel)'s bit for bit: every way gives a
//! ray — camera ray or later — [`World::intersect`]'s hit, and the shading
//! is the same code.
//!
//! In a world in packets, the rest of each sample's rays go in packets too:
//! the reflected, refracted and shadow rays of the sixteen samples' trees,
//! level by level (`whitted_tree.rs`; `render --spp 4` of the shipped
//! scenes, 2 threads, medians of 5 alternated runs against the recursion:
//! glass.xml 0.74 of the time, the Cornell box 0.73, spheres.xml 0.63,
//! primitives.xml 0.92, seed.xml at 1280×720 0.94). Elsewhere (a world of
//! meshes, or one that packets do not cover) those rays stay with the
//! recursion, one by one; they scatter, where packets of meshes gain
//! little (the
//! 1,000,000-triangle knot's camera rays: 1.5× Embree's single-ray rate
//! batched, 0.9× one by one).

use super::RenderOptions;
use super::lanes::{SampleRef, SampleResult, camera_jitter};
use super::whitted::{whitted_from_context, whitted_from_hit};
use super::whitted_packets::{packet_hits, shading_contexts};
use super::whitted_tree::Trees;
use crate::geometry::counters::shape_tests_on_this_thread;
use crate::geometry::ray::Ray;
use crate::packet::{FloatLanes, WIDTH, WithLanes, dispatch};
use crate::packet_shapes::PacketShapes;
use crate::world::World;
use glam::Vec3;

/// Traces every sample of `samples` with Whitted's integrator and writes
/// each one's result to `results` (same length); `packets` are `world`'s
/// primitives for packet tests, when it is made of lone ones.
pub(crate) fn trace_whitted(
    world: &World,
    packets: Option<&PacketShapes>,
    options: &RenderOptions,
    samples: &[SampleRef],
    results: &mut [SampleResult],
) {
    assert_eq!(samples.len(), results.len(), "one result per sample");
    let camera_hits = match packets {
        Some(shapes) => CameraHits::Packets(shapes),
        None if world.meshes.is_empty() => CameraHits::OneByOne,
        None => CameraHits::Batch,
    };
    dispatch(Trace {
        world,
        camera_hits,
        options,
        samples,
        results,
    });
}

/// How the closest hits of a batch of camera rays are found.
#[derive(Clone, Copy)]
enum CameraHits<'a> {
    /// Sixteen rays in SIMD lanes against the world's lone primitives.
    Packets(&'a PacketShapes),
    /// [`World::intersect_batch`]: each mesh instance takes the batch
    /// (ray by ray past [`crate::world::BATCHED_INSTANCES`] instances).
    Batch,
    /// [`World::intersect`] ray by ray: a world without meshes that
    /// packets do not cover (more than eight cylinders, cones and tori, the
    /// lecture's formulas, more than [`PacketShapes::MAX_PRIMITIVES`]
    /// primitives).
    OneByOne,
}

/// A call of [`trace_whitted`], to run with some lane type.
struct Trace<'a> {
    world: &'a World,
    camera_hits: CameraHits<'a>,
    options: &'a RenderOptions,
    samples: &'a [SampleRef],
    results: &'a mut [SampleResult],
}

impl WithLanes for Trace<'_> {
    type Output = ();

    /// Sixteen samples at a time: their camera rays, their hits, then
    /// each one shaded.
    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        let Trace {
            world,
            camera_hits,
            options,
            samples,
            results,
        } = self;
        // Lanes past the last sample hold a ray that hits nothing.
        let dead = Ray::NOTHING;
        let mut trees = Trees::default();
        for batch in tiles(samples).chunks(WIDTH) {
            let n = batch.len();
            let rays = camera_rays(world, options, samples, batch, dead);
            let mut hits = [None; WIDTH];
            let mut tests = [0u32; WIDTH];
            match camera_hits {
                CameraHits::Packets(shapes) => {
                    packet_hits::<F>(shapes, &rays, n, &mut hits, &mut tests);
                }
                CameraHits::Batch => world.intersect_batch_counted(
                    &rays[..n],
                    options.method,
                    &mut hits[..n],
                    &mut tests[..n],
                ),
                CameraHits::OneByOne => {
                    for k in 0..n {
                        let before = shape_tests_on_this_thread();
                        hits[k] = world.intersect(&rays[k], options.method);
                        tests[k] = (shape_tests_on_this_thread() - before) as u32;
                    }
                }
            }
            let mut contexts = [None; WIDTH];
            shading_contexts::<F>(world, &rays, &hits[..n], &mut contexts[..n]);
            if let CameraHits::Packets(shapes) = camera_hits {
                let radiance = trees.shade::<F>(
                    world,
                    shapes,
                    options,
                    &rays,
                    &hits[..n],
                    &contexts,
                    &mut tests,
                );
                for (k, &index) in batch.iter().enumerate() {
                    results[index as usize] = SampleResult {
                        radiance: radiance[k],
                        shape_tests: u64::from(tests[k]),
                    };
                }
                continue;
            }
            for (k, &index) in batch.iter().enumerate() {
                let before = shape_tests_on_this_thread();
                let radiance = match (hits[k], &contexts[k]) {
                    (Some(hit), Some(at)) => {
                        whitted_from_context(world, &rays[k], hit, at, options)
                    }
                    _ => whitted_from_hit(world, &rays[k], hits[k], options),
                };
                results[index as usize] = SampleResult {
                    radiance,
                    shape_tests: u64::from(tests[k]) + shape_tests_on_this_thread() - before,
                };
            }
        }
    }
}

/// The camera rays of the samples `batch` (indices into `samples`, at most
/// [`WIDTH`]), `dead` past them: each [`camera_sample`]'s ray bit for bit,
/// the jitter drawn sample by sample and the directions v_ij found
/// together ([`Camera::directions`]).
///
/// [`Camera::directions`]: crate::camera::Camera::directions
/// [`camera_sample`]: super::lanes::camera_sample
#[inline(always)]
fn camera_rays(
    world: &World,
    options: &RenderOptions,
    samples: &[SampleRef],
    batch: &[u32],
    dead: Ray,
) -> [Ray; WIDTH] {
    let (mut i, mut j) = ([0; WIDTH], [0; WIDTH]);
    let (mut x, mut y) = ([0.5; WIDTH], [0.5; WIDTH]);
    for (k, &index) in batch.iter().enumerate() {
        let s = samples[index as usize];
        let jitter = camera_jitter(options, s.i, s.j, s.sample);
        (i[k], j[k], x[k], y[k]) = (s.i, s.j, jitter.x, jitter.y);
    }
    let v = world.camera.directions(&i, &j, &x, &y);
    let mut rays = [dead; WIDTH];
    for (k, ray) in rays.iter_mut().enumerate().take(batch.len()) {
        *ray = Ray::new(world.camera.p0, Vec3::new(v[0][k], v[1][k], v[2][k]));
    }
    rays
}

/// The indices of `samples` in the order of 4 × 4 tiles of pixels, when
/// `samples` is a few rows of pixels (a chunk of a pass: a strip of
/// columns of a band of four rows, each row left to right): column by
/// column of four pixels, each row's four in turn, so that sixteen in a row
/// of this order are a square of neighbouring pixels. Any other list keeps
/// its order. Neighbouring camera rays are coherent: the
/// 1,000,000-triangle knot's traced 14.2–16.0 Mrays/s in tiles against
/// 11.2–13.3 in rows of sixteen (one thread).
fn tiles(samples: &[SampleRef]) -> Vec<u32> {
    /// More rows than this: the list is not a chunk of a pass.
    const MAX_ROWS: usize = 8;
    // The runs of one row each, left to right.
    let mut runs: Vec<std::ops::Range<usize>> = Vec::with_capacity(MAX_ROWS);
    let mut start = 0;
    for k in 1..=samples.len() {
        let ends = k == samples.len()
            || samples[k].j != samples[k - 1].j
            || samples[k].i <= samples[k - 1].i;
        if ends {
            runs.push(start..k);
            start = k;
            if runs.len() > MAX_ROWS {
                return (0..samples.len() as u32).collect();
            }
        }
    }
    let mut order = Vec::with_capacity(samples.len());
    loop {
        // The leftmost column of four that some row still holds.
        let Some(column) = runs
            .iter()
            .filter(|run| run.start < run.end)
            .map(|run| samples[run.start].i >> 2)
            .min()
        else {
            return order;
        };
        for run in &mut runs {
            while run.start < run.end && samples[run.start].i >> 2 == column {
                order.push(run.start as u32);
                run.start += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sample 0 of each pixel of `columns` × `rows`, row by row.
    fn rows(columns: std::ops::Range<u32>, rows: std::ops::Range<u32>) -> Vec<SampleRef> {
        rows.flat_map(|j| columns.clone().map(move |i| SampleRef { i, j, sample: 0 }))
            .collect()
    }

    #[test]
    fn a_strip_of_a_band_goes_in_squares_of_four_by_four_pixels() {
        let samples = rows(6..14, 8..12);
        let order = tiles(&samples);
        let pixels: Vec<(u32, u32)> = order
            .iter()
            .map(|&k| (samples[k as usize].i, samples[k as usize].j))
            .collect();
        // Columns 6–7 (the end of a column of four), then 8–11, then 12–13.
        let expected: Vec<(u32, u32)> = [6..8, 8..12, 12..14]
            .into_iter()
            .flat_map(|columns| (8..12).flat_map(move |j| columns.clone().map(move |i| (i, j))))
            .collect();
        assert_eq!(pixels, expected);
    }

    #[test]
    fn any_list_keeps_each_sample_once() {
        // Rows out of order, a gap, one pixel twice (two samples), and a
        // list of many short rows (kept as it is).
        let mut scrambled = rows(0..9, 3..5);
        scrambled.extend(rows(20..23, 0..2));
        scrambled.push(SampleRef {
            i: 21,
            j: 1,
            sample: 1,
        });
        let many: Vec<SampleRef> = rows(0..40, 0..40).into_iter().rev().collect();
        for samples in [scrambled, many.clone(), Vec::new()] {
            let mut order = tiles(&samples);
            order.sort_unstable();
            assert_eq!(order, (0..samples.len() as u32).collect::<Vec<_>>());
        }
        assert_eq!(tiles(&many), (0..many.len() as u32).collect::<Vec<_>>());
    }
}
