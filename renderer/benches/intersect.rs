//! Nanoseconds per intersection test, for every shape through
//! `Shape::intersect`, over a fixed seeded set of rays of which roughly half
//! hit. Run: `cargo bench -p raylab-renderer --bench intersect`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use renderer::geometry::ray::Ray;
use renderer::integrator::sampler::Sampler;
use renderer::shapes::{Method, Shape};
use scene::Geometry;
use std::hint::black_box;

/// Rays per benchmark iteration.
const RAYS: usize = 1024;

/// Rays from 3–10 units away, aimed at random points of a ball of `spread`
/// around the origin; `spread` is tuned per shape so that about half hit.
fn rays(seed: u64, spread: f32) -> Vec<Ray> {
    let mut rng = Sampler::for_sample(seed, 0, 0, 0);
    (0..RAYS)
        .map(|_| {
            let origin = (3.0 + 7.0 * rng.next_f32()) * rng.next_direction();
            let target = spread * rng.next_f32().cbrt() * rng.next_direction();
            Ray::new(origin, (target - origin).normalize())
        })
        .collect()
}

fn shapes() -> Vec<(&'static str, Method, Geometry, f32)> {
    let rotate = Vec3::new(20.0, 30.0, 40.0);
    vec![
        (
            "sphere/lecture",
            Method::Lecture,
            Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            1.6,
        ),
        (
            "sphere/robust",
            Method::Robust,
            Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            1.6,
        ),
        (
            "triangle/lecture",
            Method::Lecture,
            Geometry::Triangle {
                t0: Vec3::new(-1.0, -1.0, 0.0),
                t1: Vec3::new(1.0, -1.0, 0.0),
                t2: Vec3::new(0.0, 1.0, 0.3),
            },
            0.8,
        ),
        (
            "triangle/robust",
            Method::Robust,
            Geometry::Triangle {
                t0: Vec3::new(-1.0, -1.0, 0.0),
                t1: Vec3::new(1.0, -1.0, 0.0),
                t2: Vec3::new(0.0, 1.0, 0.3),
            },
            0.8,
        ),
        (
            "box",
            Method::Robust,
            Geometry::Box {
                center: Vec3::ZERO,
                size: Vec3::new(1.6, 1.2, 1.0),
                rotate,
            },
            1.4,
        ),
        (
            "cylinder",
            Method::Robust,
            Geometry::Cylinder {
                base: Vec3::new(0.0, -0.7, 0.0),
                radius: 0.7,
                height: 1.4,
                rotate,
            },
            1.4,
        ),
        (
            "cone",
            Method::Robust,
            Geometry::Cone {
                base: Vec3::new(0.0, -0.7, 0.0),
                radius: 0.9,
                height: 1.4,
                rotate,
            },
            1.2,
        ),
        (
            "torus",
            Method::Robust,
            Geometry::Torus {
                center: Vec3::ZERO,
                major: 1.0,
                minor: 0.35,
                rotate,
            },
            1.5,
        ),
        (
            "plane",
            Method::Robust,
            Geometry::Plane {
                point: Vec3::ZERO,
                normal: Vec3::new(0.2, 1.0, 0.1),
            },
            // Aimed at a huge ball: nearly uniform directions, half cross the plane.
            1000.0,
        ),
    ]
}

fn bench_intersect(c: &mut Criterion) {
    let mut group = c.benchmark_group("intersect");
    group.throughput(Throughput::Elements(RAYS as u64));
    for (k, (name, method, geometry, spread)) in shapes().into_iter().enumerate() {
        let shape = Shape::from_geometry(&geometry).expect("an analytic shape");
        let rays = rays(0x5EED + k as u64, spread);
        let hits = rays
            .iter()
            .filter(|r| shape.intersect(r, method).is_some())
            .count();
        eprintln!("intersect/{name}: {hits}/{RAYS} rays hit");
        group.bench_function(name, |b| {
            b.iter(|| {
                let shape = black_box(&shape);
                rays.iter()
                    .filter(|r| shape.intersect(black_box(r), method).is_some())
                    .count()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_intersect);
criterion_main!(benches);
