//! Spawning shadow rays from a hit point: a fixed t_min = 10⁻⁴ is too small
//! for a large scene (the ray finds its own surface: acne) and too large for
//! a small one (it skips a nearby occluder: a leak). raylab offsets the
//! origin by a few units in the last place instead ([`offset_ray_origin`]).

use super::measure::measure;
use super::{Case, Effort, Row};
use crate::geometry::offset::offset_ray_origin;
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::{Method, Plane, Shape, Sphere};
use glam::Vec3;

/// The acne case.
pub const ACNE: Case = Case {
    name: "self-intersection: acne",
    about: "shadow rays from lit points of a sphere of radius = scale: \
            finding the sphere itself is a failure",
    run: run_acne,
};

/// The leak case.
pub const LEAK: Case = Case {
    name: "self-intersection: leak",
    about: "shadow rays from a floor with an occluder 10⁻⁵ × scale above it: \
            missing the occluder is a failure",
    run: run_leak,
};

const CONDITION: &str = "scene scale";

/// Scene scales swept.
const SCALES: [f64; 6] = [1e-2, 1.0, 1e2, 1e3, 1e4, 1e5];

/// The lecture's fixed ε.
const FIXED_T_MIN: f32 = 1e-4;

/// The gap under the occluder, as a fraction of the scale.
const GAP: f32 = 1e-5;

/// Toward the light.
fn light_dir() -> Vec3 {
    Vec3::new(0.2, 1.0, 0.4).normalize()
}

/// A primary hit: the point as the ray gives it (P0 + α v), the point as the
/// shape places it, and the normal there.
#[derive(Clone, Copy, Debug)]
struct Hit {
    raw: Vec3,
    placed: Vec3,
    normal: Vec3,
    /// The largest coordinate of the shape (its error scale).
    magnitude: f32,
}

/// Hits of rays from a camera at `eye` aimed at random points near `aim`
/// within `spread` of it, on `shape`, that face the light.
fn lit_hits(
    shape: &Shape,
    magnitude: f32,
    eye: Vec3,
    aim: Vec3,
    spread: f32,
    effort: Effort,
) -> Vec<Hit> {
    let mut rng = Sampler::for_sample(23, spread.to_bits(), 0, 0);
    let mut hits = Vec::with_capacity(effort.trials);
    let mut attempts = 0;
    while hits.len() < effort.trials && attempts < 20 * effort.trials {
        attempts += 1;
        let target = aim + spread * rng.next_direction();
        let ray = Ray::new(eye, (target - eye).normalize());
        let Some(alpha) = shape.intersect(&ray, Method::Robust) else {
            continue;
        };
        let surface = shape.surface(&ray, alpha);
        if surface.normal.dot(light_dir()) > 0.1 && surface.normal.dot(ray.dir) < 0.0 {
            hits.push(Hit {
                raw: ray.at(alpha),
                placed: surface.point,
                normal: surface.normal,
                magnitude,
            });
        }
    }
    hits
}

/// A way to spawn the shadow ray toward the light from a hit.
type Spawn = fn(&Hit) -> Ray;

/// The two ways compared.
const SPAWNS: [(&str, Spawn); 2] = [("fixed ε", fixed_epsilon), ("robust", offset)];

/// The lecture's way: from P0 + α v, ignoring hits closer than 10⁻⁴.
fn fixed_epsilon(hit: &Hit) -> Ray {
    Ray {
        t_min: FIXED_T_MIN,
        ..Ray::new(hit.raw, light_dir())
    }
}

/// raylab's way: from the placed point moved off the surface by 64 ε times
/// the shape's largest coordinate.
fn offset(hit: &Hit) -> Ray {
    Ray::new(
        offset_ray_origin(hit.placed, hit.normal, hit.magnitude),
        light_dir(),
    )
}

/// One row per way of spawning at `scale`: a shadow ray from each hit, tested
/// against `target`; `right` says whether what it found (α, if anything) is right.
fn spawn_rows(
    case: &Case,
    scale: f64,
    hits: &[Hit],
    target: &Shape,
    right: fn(Option<f32>) -> bool,
) -> Vec<Row> {
    SPAWNS
        .iter()
        .map(|&(name, spawn)| {
            let (tally, ns) = measure(
                hits,
                |hit| target.intersect(&spawn(hit), Method::Robust),
                |_, found, tally| tally.judge(right(*found), None),
            );
            tally.row(case.name, CONDITION, scale, name, ns)
        })
        .collect()
}

fn run_acne(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for scale in SCALES {
        let s = scale as f32;
        let center = s * Vec3::new(0.3, 0.2, -0.5);
        let radius = 0.25 * s;
        let sphere = Shape::Sphere(Sphere::new(center, radius));
        let hits = lit_hits(
            &sphere,
            center.abs().max_element() + radius,
            s * Vec3::new(0.1, 0.4, 0.4),
            s * Vec3::new(0.3, 0.2, -0.5),
            0.2 * s,
            effort,
        );
        // Right when the shadow ray does not find the sphere it left.
        rows.extend(spawn_rows(&ACNE, scale, &hits, &sphere, |hit| {
            hit.is_none()
        }));
    }
    rows
}

fn run_leak(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for scale in SCALES {
        let s = scale as f32;
        let normal = Vec3::new(0.3, 1.0, 0.2).normalize();
        let on_floor = s * Vec3::new(0.3, -0.2, -0.5);
        let floor = Shape::Plane(Plane::new(on_floor, normal));
        let occluder = Shape::Plane(Plane::new(on_floor + GAP * s * normal, normal));
        let hits = lit_hits(
            &floor,
            on_floor.abs().max_element(),
            s * Vec3::new(0.1, 0.4, 0.4),
            on_floor,
            0.3 * s,
            effort,
        );
        // Right when the shadow ray finds the occluder just above.
        rows.extend(spawn_rows(&LEAK, scale, &hits, &occluder, |hit| {
            hit.is_some()
        }));
    }
    rows
}
