//! Degenerate cameras: the lecture's formulas take t and u to be orthogonal
//! unit vectors and form P_ij in absolute f32 coordinates. Given t nearly
//! parallel to u, a t of any other length, or θ near 0°, they skew the basis
//! or lose the pixels; [`Camera::new`] either builds an orthonormal basis
//! (in f64) or refuses with a clear error.

use super::measure::measure;
use super::{Case, Effort, Row};
use crate::camera::Camera;
use crate::integrator::sampler::Sampler;
use glam::{DVec3, Vec3};
use scene::ResolvedCamera;

/// t and u nearly parallel.
pub const UP_NEAR_TOWARD: Case = Case {
    name: "camera: u near t",
    about: "t and u at a shrinking angle: error is the basis's distance from orthonormal; \
            a NaN, a basis off by more than 10⁻⁶ or a ray off by more than 0.1 pixel \
            is a failure, a clear error is a refusal",
    run: run_up_near_toward,
};

/// θ near 0° or 90°.
pub const THETA: Case = Case {
    name: "camera: θ near 0° or 90°",
    about: "the half-height angle θ from 10⁻⁴° to 89.9999°: error is the pixel rays' \
            angle from exact, in pixels; a NaN or an error over 0.1 pixel is a failure, \
            a clear error is a refusal",
    run: run_theta,
};

/// t of any length.
pub const TOWARD_LENGTH: Case = Case {
    name: "camera: length of t",
    about: "t of length 10⁻⁶ to 10⁶, u orthogonal: error is the basis's distance from \
            orthonormal; a skewed basis or a ray off by more than 0.1 pixel is a failure",
    run: run_toward_length,
};

/// A ray further than this from exact (in pixels) is a failure.
const MAX_PIXEL_ERROR: f64 = 0.1;

/// Image size of the cameras tested.
const W: u32 = 64;
const H: u32 = 48;

/// What a method makes of a camera: its basis (t, u, r) and pixel rays.
struct Built {
    basis: [Vec3; 3],
    directions: Vec<Vec3>,
}

/// The pixels whose rays are checked: the four corners, the centre, a diagonal.
fn pixels() -> impl Iterator<Item = (u32, u32)> {
    [
        (0, 0),
        (W - 1, 0),
        (0, H - 1),
        (W - 1, H - 1),
        (W / 2, H / 2),
    ]
    .into_iter()
    .chain((1..8).map(|k| (k * W / 8, k * H / 8)))
}

/// The lecture: r = t × u, d = h / (2 tan θ), H_d = 2 d tan θ, W_d = ρ H_d,
/// C00 = P0 + d t + (H_d/2) u − (W_d/2) r,
/// P_ij = C00 + (i + ½)(W_d/w) r − (j + ½)(H_d/h) u, v_ij = (P_ij − P0)/‖P_ij − P0‖,
/// in f32 with t and u as given.
fn lecture(input: &ResolvedCamera) -> Option<Built> {
    let (p0, t, u) = (input.eye, input.toward, input.up);
    let r = t.cross(u);
    let theta = input.theta_deg.to_radians();
    let d = H as f32 / (2.0 * theta.tan());
    let h_d = 2.0 * d * theta.tan();
    let w_d = (W as f32 / H as f32) * h_d;
    let c00 = p0 + d * t + (h_d / 2.0) * u - (w_d / 2.0) * r;
    let directions = pixels()
        .map(|(i, j)| {
            let p = c00 + (i as f32 + 0.5) * (w_d / W as f32) * r
                - (j as f32 + 0.5) * (h_d / H as f32) * u;
            (p - p0) / (p - p0).length()
        })
        .collect();
    Some(Built {
        basis: [t, u, r],
        directions,
    })
}

/// raylab's [`Camera::new`]; `None` when it refuses.
fn robust(input: &ResolvedCamera) -> Option<Built> {
    let camera = Camera::new(input).ok()?;
    let half = glam::Vec2::splat(0.5);
    Some(Built {
        basis: [camera.t, camera.u, camera.r],
        directions: pixels()
            .map(|(i, j)| camera.direction(i, j, half))
            .collect(),
    })
}

/// The exact pixel rays, in f64, of the camera the user meant: t normalised,
/// u made orthogonal to it.
fn exact_directions(input: &ResolvedCamera) -> Vec<DVec3> {
    let t = input.toward.as_dvec3().normalize();
    let up = input.up.as_dvec3();
    let u = (up - up.dot(t) * t).normalize();
    let r = t.cross(u);
    let tan = f64::from(input.theta_deg).to_radians().tan();
    let d = f64::from(H) / (2.0 * tan);
    let (h_d, w_d) = (f64::from(H), f64::from(W));
    pixels()
        .map(|(i, j)| {
            (d * t + (h_d / 2.0) * u - (w_d / 2.0) * r + (f64::from(i) + 0.5) * r
                - (f64::from(j) + 0.5) * u)
                .normalize()
        })
        .collect()
}

/// The largest departure of (t, u, r) from an orthonormal basis; NaN if any is.
fn basis_error([t, u, r]: [Vec3; 3]) -> f64 {
    let terms = [
        t.dot(u),
        t.dot(r),
        u.dot(r),
        t.length() - 1.0,
        u.length() - 1.0,
        r.length() - 1.0,
    ];
    terms
        .iter()
        .map(|&x| f64::from(x).abs())
        .fold(0.0, |acc, x| {
            if x.is_nan() || acc.is_nan() {
                f64::NAN
            } else {
                acc.max(x)
            }
        })
}

/// The largest angle between a method's pixel rays and the exact ones, in
/// pixels (one pixel subtends about 2θ / h at the centre); NaN if any is.
fn direction_error(input: &ResolvedCamera, directions: &[Vec3]) -> f64 {
    let pixel = 2.0 * f64::from(input.theta_deg).to_radians() / f64::from(H);
    directions
        .iter()
        .zip(exact_directions(input))
        .map(|(v, e)| {
            let v = v.as_dvec3();
            // The angle by atan2 keeps its precision for tiny angles.
            v.cross(e).length().atan2(v.dot(e)) / pixel
        })
        .fold(0.0, |acc, x| {
            if x.is_nan() || acc.is_nan() {
                f64::NAN
            } else {
                acc.max(x)
            }
        })
}

/// What the case records as a passing camera's error.
#[derive(Clone, Copy)]
enum Measure {
    Basis,
    Pixels,
}

/// One row per (value, method): cameras made by `camera(value, rng)`.
fn sweep(
    case: &Case,
    condition: &'static str,
    values: &[f64],
    measured: Measure,
    effort: Effort,
    camera: impl Fn(f64, &mut Sampler) -> ResolvedCamera,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for (k, &value) in values.iter().enumerate() {
        let mut rng = Sampler::for_sample(31, k as u32, 0, 0);
        let inputs: Vec<ResolvedCamera> = (0..(effort.trials / 100).max(10))
            .map(|_| camera(value, &mut rng))
            .collect();
        for (name, method) in [("lecture", lecture as fn(&_) -> _), ("robust", robust)] {
            let (tally, ns) = measure(&inputs, method, |input, built, tally| {
                let Some(built) = built else {
                    return tally.refuse();
                };
                let basis = basis_error(built.basis);
                let pixels = direction_error(input, &built.directions);
                let ok = basis <= 1e-6 && pixels <= MAX_PIXEL_ERROR;
                let error = match measured {
                    Measure::Basis => basis,
                    Measure::Pixels => pixels,
                };
                tally.judge(ok, Some(error));
            });
            rows.push(tally.row(case.name, condition, value, name, ns));
        }
    }
    rows
}

/// A w × h camera (d by default) at a random eye within 10 of the origin,
/// looking along a random unit t, with u orthogonal to it and θ = 30°.
fn random_camera(rng: &mut Sampler) -> ResolvedCamera {
    let eye = 10.0 * rng.next_direction() * rng.next_f32();
    let toward = rng.next_direction();
    ResolvedCamera {
        eye,
        toward,
        up: toward.any_orthonormal_vector(),
        theta_deg: 30.0,
        d: None,
        width: W,
        height: H,
    }
}

fn run_up_near_toward(effort: Effort) -> Vec<Row> {
    let angles = [90.0, 10.0, 1.0, 1e-2, 1e-4, 1e-6, 0.0];
    sweep(
        &UP_NEAR_TOWARD,
        "angle between t and u (degrees)",
        &angles,
        Measure::Basis,
        effort,
        |angle, rng| {
            let camera = random_camera(rng);
            let a = (angle as f32).to_radians();
            ResolvedCamera {
                up: a.cos() * camera.toward + a.sin() * camera.up,
                ..camera
            }
        },
    )
}

fn run_theta(effort: Effort) -> Vec<Row> {
    let thetas = [1e-4, 1e-2, 1.0, 30.0, 89.0, 89.99, 89.9999];
    sweep(
        &THETA,
        "half-height angle θ (degrees)",
        &thetas,
        Measure::Pixels,
        effort,
        |theta, rng| ResolvedCamera {
            theta_deg: theta as f32,
            ..random_camera(rng)
        },
    )
}

fn run_toward_length(effort: Effort) -> Vec<Row> {
    let lengths = [1e-6, 1e-3, 1.0, 1e3, 1e6];
    sweep(
        &TOWARD_LENGTH,
        "length of t",
        &lengths,
        Measure::Basis,
        effort,
        |length, rng| {
            let camera = random_camera(rng);
            ResolvedCamera {
                toward: length as f32 * camera.toward,
                ..camera
            }
        },
    )
}
