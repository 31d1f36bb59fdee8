//! A torus seen from far away: the quartic's coefficients, formed from the
//! ray's own origin, grow like distance⁴ and drown the tube in rounding.
//! raylab's torus first moves the origin onto the bounding sphere, forms the
//! quartic in f64 and polishes its roots.

use super::measure::measure;
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::Torus;
use glam::Vec3;

/// Rays that must hit.
pub const TUBE: Case = Case {
    name: "torus far away: tube",
    about: "rays aimed at the tube's centre circle from any direction: a miss is a failure; \
            textbook: the f32 quartic from the unshifted origin",
    run: run_tube,
};

/// Rays that must miss.
pub const HOLE: Case = Case {
    name: "torus far away: hole",
    about: "rays through the middle of the hole within 20° of the axis: a hit is a failure; \
            textbook: the f32 quartic from the unshifted origin",
    run: run_hole,
};

const CONDITION: &str = "distance / major radius";

/// Distances (in major radii) swept.
const DISTANCES: [f64; 5] = [3.0, 1e1, 1e2, 1e3, 1e4];

/// R and r of the torus (centred at the origin, axis +y).
const MAJOR: f32 = 1.0;
const MINOR: f32 = 0.25;

/// The textbook torus test: the quartic in α formed in f32 from the ray's
/// origin as it is, its roots by the same solver, the nearest one in range.
fn textbook_torus(ray: &Ray) -> Option<f32> {
    let (o, d) = (ray.origin, ray.dir);
    let (big, small) = (MAJOR, MINOR);
    let dd = d.dot(d);
    let od = o.dot(d);
    let k = o.dot(o) + big * big - small * small;
    let four_r2 = 4.0 * big * big;
    let a4 = dd * dd;
    let a3 = 4.0 * dd * od;
    let a2 = 4.0 * od * od + 2.0 * dd * k - four_r2 * (d.x * d.x + d.z * d.z);
    let a1 = 4.0 * od * k - 2.0 * four_r2 * (o.x * d.x + o.z * d.z);
    let a0 = k * k - four_r2 * (o.x * o.x + o.z * o.z);
    let roots = roots::find_roots_quartic(a4, a3, a2, a1, a0);
    roots
        .as_ref()
        .iter()
        .copied()
        .filter(|&t| ray.contains(t))
        .min_by(f32::total_cmp)
}

/// Rays from `distance` away: at a point of the tube's centre circle from
/// any direction if `tube` (they must hit), else through the middle of the
/// hole within 20° of the axis (they must miss).
fn rays(distance: f64, tube: bool, effort: Effort) -> Vec<Ray> {
    let far = distance as f32 * MAJOR;
    let mut rng = Sampler::for_sample(19, distance as u32, u32::from(tube), 0);
    (0..effort.trials)
        .map(|_| {
            if tube {
                let phi = std::f32::consts::TAU * rng.next_f32();
                let target = MAJOR * Vec3::new(phi.cos(), 0.0, phi.sin());
                let origin = far * rng.next_direction();
                Ray::new(origin, (target - origin).normalize())
            } else {
                let tilt = 20f32.to_radians() * rng.next_f32().sqrt();
                let phi = std::f32::consts::TAU * rng.next_f32();
                let side = if rng.next_f32() < 0.5 { 1.0 } else { -1.0 };
                let from = Vec3::new(
                    tilt.sin() * phi.cos(),
                    side * tilt.cos(),
                    tilt.sin() * phi.sin(),
                );
                let psi = std::f32::consts::TAU * rng.next_f32();
                let rho = 0.5 * (MAJOR - MINOR) * rng.next_f32().sqrt();
                let target = rho * Vec3::new(psi.cos(), 0.0, psi.sin());
                let origin = target + far * from;
                Ray::new(origin, (target - origin).normalize())
            }
        })
        .collect()
}

fn run_tube(effort: Effort) -> Vec<Row> {
    run(&TUBE, true, effort)
}

fn run_hole(effort: Effort) -> Vec<Row> {
    run(&HOLE, false, effort)
}

/// One row per (distance, method); `must_hit` says which rays these are.
fn run(case: &Case, must_hit: bool, effort: Effort) -> Vec<Row> {
    let torus = Torus::new(Vec3::ZERO, MAJOR, MINOR, Vec3::ZERO);
    let mut rows = Vec::new();
    for distance in DISTANCES {
        let rays = rays(distance, must_hit, effort);
        type TorusTest<'a> = &'a dyn Fn(&Ray) -> Option<f32>;
        let methods: [(&str, TorusTest); 2] = [
            ("textbook", &textbook_torus),
            ("robust", &|ray: &Ray| torus.intersect(ray)),
        ];
        for (name, method) in methods {
            let (tally, ns) = measure(
                &rays,
                |ray| method(ray),
                |_, alpha, tally| tally.judge(alpha.is_some() == must_hit, None),
            );
            rows.push(tally.row(case.name, CONDITION, distance, name, ns));
        }
    }
    rows
}
