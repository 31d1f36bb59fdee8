//! Rays parallel to a triangle's plane: n · v is zero (or rounding noise),
//! so α = (n · u)/(n · v) is ±∞ or NaN. No method may accept such a hit.

use super::measure::measure;
use super::triangle_edges::TRIANGLE_METHODS;
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::Triangle;
use glam::{Quat, Vec3};

/// The case.
pub const CASE: Case = Case {
    name: "triangles: parallel rays",
    about: "rays parallel to the triangle's plane (half exactly, in an axis plane; \
            half up to rounding, turned): a NaN or infinite α accepted, or a hit \
            off the plane, is a failure",
    run,
};

const CONDITION: &str = "offset of the ray from the plane";

/// Offsets swept (the triangle's legs are 3 long); 0 is in the plane.
const OFFSETS: [f64; 4] = [0.0, 1e-6, 1e-3, 1.0];

/// Half the rays in the axis plane z = 1 + offset (exactly parallel), half
/// turned with the triangle (parallel up to rounding).
fn rays(offset: f64, effort: Effort) -> Vec<(Triangle, Ray)> {
    let flat = Triangle::new(
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(2.0, -1.0, 1.0),
        Vec3::new(-1.0, 2.0, 1.0),
    );
    let turn = Quat::from_euler(glam::EulerRot::XYZ, 0.5, 0.8, -0.3);
    let turned = Triangle::new(turn * flat.t0, turn * flat.t1, turn * flat.t2);
    let mut rng = Sampler::for_sample(17, (offset * 1e6) as u32, 0, 0);
    (0..effort.trials)
        .map(|k| {
            let origin = Vec3::new(
                6.0 * rng.next_f32() - 3.0,
                6.0 * rng.next_f32() - 3.0,
                1.0 + offset as f32,
            );
            let phi = std::f32::consts::TAU * rng.next_f32();
            let dir = Vec3::new(phi.cos(), phi.sin(), 0.0);
            if k % 2 == 0 {
                (flat, Ray::new(origin, dir))
            } else {
                (turned, Ray::new(turn * origin, (turn * dir).normalize()))
            }
        })
        .collect()
}

fn run(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for offset in OFFSETS {
        let rays = rays(offset, effort);
        for (name, method) in TRIANGLE_METHODS {
            let (tally, ns) = measure(
                &rays,
                |(tri, ray)| method(tri, ray),
                |_, alpha, tally| {
                    let wrong = match alpha {
                        Some(a) => !a.is_finite() || offset > 0.0,
                        None => false,
                    };
                    tally.judge(!wrong, None);
                },
            );
            rows.push(tally.row(CASE.name, CONDITION, offset, name, ns));
        }
    }
    rows
}
