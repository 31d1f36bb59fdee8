//! The BVH's hardest cases, generated in code for its tests and benchmark:
//! tiled floors whose triangles share edges and vertices at exact lattice
//! coordinates, and rays aimed exactly at those edges and vertices. (The
//! benchmark scenes themselves — the torus knot, the sphere field — are
//! `scene::generate`.)

use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use glam::Vec3;
use scene::TriangleMesh;
use std::f32::consts::TAU;

/// An `nx` × `ny` grid of unit squares in the plane z = `z`, corners at
/// integer (x, y), each square split along alternating diagonals: 2 nx ny
/// triangles sharing edges and vertices at exact lattice coordinates.
pub fn tiled_floor(nx: u32, ny: u32, z: f32) -> TriangleMesh {
    let mut positions = Vec::with_capacity(((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push(Vec3::new(i as f32, j as f32, z));
        }
    }
    let mut triangles = Vec::with_capacity((2 * nx * ny) as usize);
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            if (i + j).is_multiple_of(2) {
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([b, c, d]);
            }
        }
    }
    TriangleMesh {
        positions,
        triangles,
        ..TriangleMesh::default()
    }
}

/// A point on a shared edge or vertex of cell (i, j) of [`tiled_floor`]:
/// by `kind` its corner, a point at `f` along its bottom or left edge, or on
/// its diagonal.
fn shared_point(i: u32, j: u32, kind: u32, f: f32) -> Vec3 {
    let (x, y) = (i as f32, j as f32);
    match kind % 4 {
        0 => Vec3::new(x, y, 0.0),
        1 => Vec3::new(x + f, y, 0.0),
        2 => Vec3::new(x, y + f, 0.0),
        _ if (i + j).is_multiple_of(2) => Vec3::new(x + f, y + f, 0.0),
        _ => Vec3::new(x + 1.0 - f, y + f, 0.0),
    }
}

/// `count` unit-direction rays from above and below aimed exactly at shared
/// edges and vertices of the inner cells of an n × n [`tiled_floor`] at
/// z = 0, from steep to grazing (elevation down to 10⁻³ rad), from a seed.
pub fn rays_at_shared_edges(n: u32, count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Sampler::for_sample(seed, 0, 0, 0);
    (0..count)
        .map(|k| {
            let i = 1 + (rng.next_f32() * (n - 2) as f32) as u32;
            let j = 1 + (rng.next_f32() * (n - 2) as f32) as u32;
            let f = if k % 2 == 0 {
                rng.next_f32()
            } else {
                (rng.next_f32() * 64.0).floor() / 64.0
            };
            let target = shared_point(i, j, k as u32, f);
            let elevation = if k % 4 == 3 {
                1e-3 + 0.05 * rng.next_f32()
            } else {
                0.05 + 1.5 * rng.next_f32()
            };
            let azimuth = TAU * rng.next_f32();
            let side = if k % 5 == 0 { -1.0 } else { 1.0 };
            let to_origin = Vec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                side * elevation.sin(),
            );
            let origin = target + to_origin * (0.5 + 30.0 * rng.next_f32());
            Ray::new(origin, (target - origin).normalize())
        })
        .collect()
}
