//! A ray parallel to one of the cone's generators: the side's quadratic has
//! a = 0, and the textbook (−b ± √(b² − 4ac)) / 2a divides by it — NaN at
//! a = 0 and cancellation near it. raylab's cone solves the stable form,
//! which falls back to the linear root.

use super::measure::{measure, relative_error};
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::Cone;
use glam::{DVec3, Vec3};

/// The case.
pub const CASE: Case = Case {
    name: "cone: ray along a generator",
    about: "rays from above the apex tilted δ from a generator of a unit cone \
            (base radius 1, height 1): a miss, or α off by more than 10⁻³, is a failure",
    run,
};

const CONDITION: &str = "tilt δ from the generator (rad)";

/// Tilts swept.
const TILTS: [f64; 5] = [0.0, 1e-7, 1e-5, 1e-3, 1e-1];

/// A failure when α is further than this (relative) from the exact one.
const TOLERANCE: f64 = 1e-3;

/// The cone's side (x² + z²) = (1 − y)² for 0 ≤ y ≤ 1 and its base disk,
/// for the ray in f64: the nearest α > 0.
fn exact_alpha(ray: &Ray) -> Option<f64> {
    let (o, d): (DVec3, DVec3) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let w0 = 1.0 - o.y;
    let a = d.x * d.x + d.z * d.z - d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.z * d.z + w0 * d.y);
    let c = o.x * o.x + o.z * o.z - w0 * w0;
    let mut roots = Vec::new();
    if a == 0.0 {
        roots.push(-c / b);
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + disc.sqrt().copysign(b));
            roots.extend([q / a, c / q]);
        }
    }
    let side = roots
        .into_iter()
        .filter(|&t| t > 0.0 && (0.0..=1.0).contains(&(o.y + t * d.y)));
    let base = Some(-o.y / d.y).filter(|&t| {
        let p = o + t * d;
        t > 0.0 && p.x * p.x + p.z * p.z <= 1.0
    });
    side.chain(base).min_by(f64::total_cmp)
}

/// The textbook test, in f32 from the ray's own origin: the side's quadratic
/// by (−b ± √disc) / 2a (roots kept for 0 ≤ y ≤ 1), then the base disk.
fn textbook_cone(ray: &Ray) -> Option<f32> {
    let (o, d) = (ray.origin, ray.dir);
    let w0 = 1.0 - o.y;
    let a = d.x * d.x + d.z * d.z - d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.z * d.z + w0 * d.y);
    let c = o.x * o.x + o.z * o.z - w0 * w0;
    let disc = b * b - 4.0 * a * c;
    let mut best = None::<f32>;
    let mut consider = |t: f32| {
        if ray.contains(t) && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    };
    if disc >= 0.0 {
        for t in [
            (-b - disc.sqrt()) / (2.0 * a),
            (-b + disc.sqrt()) / (2.0 * a),
        ] {
            if (0.0..=1.0).contains(&(o.y + t * d.y)) {
                consider(t);
            }
        }
    }
    let t = -o.y / d.y;
    let p = o + t * d;
    if p.x * p.x + p.z * p.z <= 1.0 {
        consider(t);
    }
    best
}

/// Rays from 3 above the base plane, travelling down at angle π/4 + δ to the
/// axis (δ = 0: parallel to a generator), offset so they meet the side.
fn rays(tilt: f64, effort: Effort) -> Vec<Ray> {
    let slope = (std::f64::consts::FRAC_PI_4 + tilt).tan() as f32;
    let dir = Vec3::new(0.0, -1.0, -slope).normalize();
    let mut rng = Sampler::for_sample(29, (tilt * 1e9) as u32, 0, 0);
    (0..effort.trials)
        .map(|_| {
            let (x, c) = (0.4 * rng.next_f32() - 0.2, 0.2 + 0.6 * rng.next_f32());
            let y0 = 3.0;
            Ray::new(Vec3::new(x, y0, y0 - c), dir)
        })
        .collect()
}

fn run(effort: Effort) -> Vec<Row> {
    let cone = Cone::new(Vec3::ZERO, 1.0, 1.0, Vec3::ZERO);
    let mut rows = Vec::new();
    for tilt in TILTS {
        let rays = rays(tilt, effort);
        type ConeTest<'a> = &'a dyn Fn(&Ray) -> Option<f32>;
        let methods: [(&str, ConeTest); 2] = [
            ("textbook", &textbook_cone),
            ("robust", &|ray: &Ray| cone.intersect(ray)),
        ];
        for (name, method) in methods {
            let (tally, ns) = measure(
                &rays,
                |ray| method(ray),
                |ray, alpha, tally| match (alpha, exact_alpha(ray)) {
                    (Some(a), Some(e)) => {
                        let error = relative_error(f64::from(*a), e);
                        if error <= TOLERANCE {
                            tally.pass(Some(error));
                        } else {
                            tally.fail();
                        }
                    }
                    (None, None) => tally.pass(None),
                    _ => tally.fail(),
                },
            );
            rows.push(tally.row(CASE.name, CONDITION, tilt, name, ns));
        }
    }
    rows
}
