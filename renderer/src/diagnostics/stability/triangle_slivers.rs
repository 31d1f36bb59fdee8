//! Sliver triangles: the lecture's 2×2 barycentric solve divides by
//! (v1·v1)(v2·v2) − (v1·v2)², which cancels to nothing as the triangle thins.

use super::measure::{measure, relative_error};
use super::triangle_edges::TRIANGLE_METHODS;
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::Triangle;
use glam::{Quat, Vec3};

/// The case.
pub const CASE: Case = Case {
    name: "triangles: slivers",
    about: "rays aimed well inside (10% from every edge) ever thinner triangles: \
            a miss is a failure; error is α's against f64",
    run,
};

const CONDITION: &str = "aspect ratio (length / width)";

/// Aspect ratios swept.
const RATIOS: [f64; 5] = [1.0, 1e1, 1e2, 1e3, 1e4];

/// α where the f32 ray meets the triangle's plane, in f64.
fn exact_alpha(tri: &Triangle, ray: &Ray) -> f64 {
    let t0 = tri.t0.as_dvec3();
    let n = (tri.t1.as_dvec3() - t0).cross(tri.t2.as_dvec3() - t0);
    n.dot(t0 - ray.origin.as_dvec3()) / n.dot(ray.dir.as_dvec3())
}

/// A sliver of length 1 and width 1 / `ratio`, turned off the axes, and rays
/// aimed at points at least 10% of the way in from each of its edges.
fn sliver_and_rays(ratio: f64, effort: Effort) -> (Triangle, Vec<Ray>) {
    let turn = Quat::from_euler(glam::EulerRot::XYZ, 0.4, -0.9, 0.25);
    let center = Vec3::new(3.0, -2.0, 5.0);
    let place = |p: Vec3| center + turn * p;
    let width = (1.0 / ratio) as f32;
    let tri = Triangle::new(
        place(Vec3::new(-0.5, 0.0, 0.0)),
        place(Vec3::new(0.5, 0.0, 0.0)),
        place(Vec3::new(0.0, width, 0.0)),
    );
    let normal = turn * Vec3::Z;
    let mut rng = Sampler::for_sample(13, ratio as u32, 0, 0);
    let rays = (0..effort.trials)
        .map(|_| {
            // Barycentrics β, γ ≥ 0.1 and β + γ ≤ 0.9.
            let (mut b, mut g) = (rng.next_f32(), rng.next_f32());
            if b + g > 1.0 {
                (b, g) = (1.0 - b, 1.0 - g);
            }
            let (b, g) = (0.1 + 0.7 * b, 0.1 + 0.7 * g);
            let target = tri.t0 + b * (tri.t1 - tri.t0) + g * (tri.t2 - tri.t0);
            let mut away = rng.next_direction();
            if away.dot(normal).abs() < 0.1 {
                away += 0.2 * normal;
            }
            let origin = target + (1.0 + 9.0 * rng.next_f32()) * away.normalize();
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    (tri, rays)
}

fn run(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for ratio in RATIOS {
        let (tri, rays) = sliver_and_rays(ratio, effort);
        for (name, method) in TRIANGLE_METHODS {
            let (tally, ns) = measure(
                &rays,
                |ray| method(&tri, ray),
                |ray, alpha, tally| match alpha {
                    Some(a) => {
                        tally.pass(Some(relative_error(f64::from(*a), exact_alpha(&tri, ray))));
                    }
                    None => tally.fail(),
                },
            );
            rows.push(tally.row(CASE.name, CONDITION, ratio, name, ns));
        }
    }
    rows
}
