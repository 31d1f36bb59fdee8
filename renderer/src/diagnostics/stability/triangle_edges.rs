//! Rays aimed exactly at the edge two triangles share: a ray that hits
//! neither has leaked through a closed surface. Only a watertight test
//! (Woop, Benthin, Wald 2013) guarantees it never happens.

use super::measure::measure;
use super::{Case, Effort, Row};
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::{Method, Triangle};
use glam::{Quat, Vec3};

/// The case.
pub const CASE: Case = Case {
    name: "triangles: shared edge",
    about: "rays aimed at the diagonal shared by a quad's two triangles: \
            hitting neither is a leak",
    run,
};

const CONDITION: &str = "distance of the unit quad from the origin";

/// The quad's distances from the world origin swept (its size is 1).
const DISTANCES: [f64; 5] = [1.0, 1e1, 1e2, 1e3, 1e4];

/// A ray–triangle test: α of the hit, if any.
pub type TriangleTest = fn(&Triangle, &Ray) -> Option<f32>;

/// The triangle tests compared: the lecture's, Möller–Trumbore's, the watertight one.
pub const TRIANGLE_METHODS: [(&str, TriangleTest); 3] = [
    ("lecture", lecture),
    ("Möller–Trumbore", moller_trumbore),
    ("robust", robust),
];

/// The lecture's ray–plane α and 2×2 barycentric solve.
fn lecture(tri: &Triangle, ray: &Ray) -> Option<f32> {
    tri.intersect(ray, Method::Lecture)
}

/// The watertight test.
fn robust(tri: &Triangle, ray: &Ray) -> Option<f32> {
    tri.intersect(ray, Method::Robust)
}

/// Möller–Trumbore (1997), the common textbook alternative to the lecture:
/// α of the hit, with its barycentric test on u, v and u + v.
fn moller_trumbore(tri: &Triangle, ray: &Ray) -> Option<f32> {
    let (e1, e2) = (tri.t1 - tri.t0, tri.t2 - tri.t0);
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - tri.t0;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = ray.dir.dot(q) * inv;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let alpha = e2.dot(q) * inv;
    ray.contains(alpha).then_some(alpha)
}

/// The quad's two triangles, sharing the diagonal t0–t2 of the first, and
/// rays from both sides aimed at points on that diagonal away from its ends.
fn quad_and_rays(distance: f64, effort: Effort) -> ([Triangle; 2], Vec<Ray>) {
    let turn = Quat::from_euler(glam::EulerRot::XYZ, 0.7, 0.3, 1.1);
    let center = (distance as f32) * Vec3::new(0.6, -0.48, 0.64);
    let corner = |x: f32, y: f32| center + turn * Vec3::new(x - 0.5, y - 0.5, 0.0);
    let (a, b, c, d) = (
        corner(0.0, 0.0),
        corner(1.0, 0.0),
        corner(1.0, 1.0),
        corner(0.0, 1.0),
    );
    let tris = [Triangle::new(a, b, c), Triangle::new(a, c, d)];
    let normal = turn * Vec3::Z;
    let mut rng = Sampler::for_sample(11, distance as u32, 0, 0);
    let rays = (0..effort.trials)
        .map(|k| {
            // Not within 5% of the corners, where rounding could legitimately miss the quad.
            let target = a + (0.05 + 0.9 * rng.next_f32()) * (c - a);
            let mut away = rng.next_direction();
            // Half from each side, none grazing closer than ~1°.
            let side = if k % 2 == 0 { 1.0 } else { -1.0 };
            if away.dot(normal) * side < 0.02 {
                away -= (away.dot(normal) - side * (0.02 + 0.98 * rng.next_f32())) * normal;
            }
            let origin = target + (1.0 + 9.0 * rng.next_f32()) * away.normalize();
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    (tris, rays)
}

fn run(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for distance in DISTANCES {
        let (tris, rays) = quad_and_rays(distance, effort);
        let hits_either = |f: TriangleTest, ray: &Ray| {
            // Both tests always run, so the cost is two tests per ray.
            let (first, second) = (f(&tris[0], ray), f(&tris[1], ray));
            first.is_some() || second.is_some()
        };
        for (name, method) in TRIANGLE_METHODS {
            let (tally, ns) = measure(
                &rays,
                |ray| hits_either(method, ray),
                |_, hit, tally| tally.judge(*hit, None),
            );
            // Two triangle tests per ray.
            rows.push(tally.row(CASE.name, CONDITION, distance, name, ns / 2.0));
        }
    }
    rows
}
