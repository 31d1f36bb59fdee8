//! A small sphere far from the camera: the lecture's quadratic loses the
//! hit to cancellation in b² − 4ac long before the sphere leaves f32's range.

use super::measure::{measure, relative_error};
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::{Method, Sphere};
use glam::{DVec3, Vec3};

/// The case.
pub const CASE: Case = Case {
    name: "sphere far away",
    about: "rays aimed inside the inner half of a sphere's disk, from far away: \
            a miss is a failure; error is α's against f64",
    run,
};

const CONDITION: &str = "distance / radius";

/// Distances (in radii) swept.
const DISTANCES: [f64; 7] = [1e1, 1e2, 1e3, 3e3, 1e4, 1e5, 1e6];

/// The nearer root α of the sphere's quadratic for the f32 ray, in f64.
fn exact_alpha(sphere: &Sphere, ray: &Ray) -> Option<f64> {
    let (o, d, c) = (
        ray.origin.as_dvec3(),
        ray.dir.as_dvec3(),
        sphere.center.as_dvec3(),
    );
    let r = f64::from(sphere.radius);
    let f = o - c;
    let a = d.dot(d);
    let b = -f.dot(d);
    let l = f + (b / a) * d;
    let disc = a * (r * r - l.dot(l));
    if disc < 0.0 {
        return None;
    }
    let q = b + disc.sqrt().copysign(b);
    let (r0, r1) = ((f.dot(f) - r * r) / q, q / a);
    Some(r0.min(r1))
}

/// Rays from the origin aimed at points within half a radius of the centre
/// of a unit sphere `distance` away, in a direction off every axis.
fn rays(distance: f64, effort: Effort) -> (Sphere, Vec<Ray>) {
    let axis = DVec3::new(0.3, 0.2, -1.0).normalize();
    let center = (distance * axis).as_vec3();
    let sphere = Sphere::new(center, 1.0);
    let (e1, e2) = axis.as_vec3().any_orthonormal_pair();
    let mut rng = Sampler::for_sample(7, distance as u32, 0, 0);
    let rays = (0..effort.trials)
        .map(|_| {
            let (rho, phi) = (
                0.5 * rng.next_f32().sqrt(),
                std::f32::consts::TAU * rng.next_f32(),
            );
            let target = center + rho * (phi.cos() * e1 + phi.sin() * e2);
            Ray::new(Vec3::ZERO, target.normalize())
        })
        .collect();
    (sphere, rays)
}

fn run(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for distance in DISTANCES {
        let (sphere, rays) = rays(distance, effort);
        for (method, name) in [(Method::Lecture, "lecture"), (Method::Robust, "robust")] {
            let (tally, ns) = measure(
                &rays,
                |ray| sphere.intersect(ray, method),
                |ray, alpha, tally| {
                    let exact = exact_alpha(&sphere, ray);
                    match (alpha, exact) {
                        (Some(a), Some(e)) => {
                            tally.pass(Some(relative_error(f64::from(*a), e)));
                        }
                        _ => tally.fail(),
                    }
                },
            );
            rows.push(tally.row(CASE.name, CONDITION, distance, name, ns));
        }
    }
    rows
}
