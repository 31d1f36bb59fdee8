//! Meshes and rays generated in code for the BVH benchmark and tests: a
//! (2, 3) torus-knot tube of a chosen triangle count on a floor, a camera
//! framing it, and its primary and incoherent ray sets.

use crate::ray::Ray;
use crate::sampler::Sampler;
use glam::Vec3;
use std::f32::consts::TAU;

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Appends `other`'s triangles.
    pub fn append(&mut self, other: &Mesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|k| k + base)));
    }

    /// The smallest and largest corner of the vertices.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            })
    }
}

/// The centre line of the (p, q) = (2, 3) torus knot (the trefoil) around
/// the y axis: r = 2 + cos 3φ, point (r cos 2φ, −sin 3φ, r sin 2φ).
fn knot_curve(phi: f32) -> Vec3 {
    let r = 2.0 + (3.0 * phi).cos();
    Vec3::new(
        r * (2.0 * phi).cos(),
        -(3.0 * phi).sin(),
        r * (2.0 * phi).sin(),
    )
}

/// Tube radius of [`torus_knot`].
const TUBE_RADIUS: f32 = 0.4;

/// A closed tube of radius 0.4 around the (2, 3) torus knot with
/// 2 × segments × sides ≈ `triangles` triangles (exactly, when
/// `triangles`/2 has a divisor near √(triangles/16), as 1,000,000 does:
/// 2000 segments × 250 sides). At least 3 × 3 quads.
pub fn torus_knot(triangles: usize) -> Mesh {
    let quads = (triangles / 2).max(9);
    let ideal = ((quads as f64 / 8.0).sqrt().round() as usize).max(3);
    let sides = (ideal / 2..=ideal * 2)
        .filter(|s| *s >= 3 && quads.is_multiple_of(*s) && quads / s >= 3)
        .min_by_key(|s| s.abs_diff(ideal))
        .unwrap_or(ideal);
    let segments = (quads / sides).max(3);
    let mut positions = Vec::with_capacity(segments * sides);
    for i in 0..segments {
        let phi = TAU * i as f32 / segments as f32;
        let h = 1e-3;
        let tangent = (knot_curve(phi + h) - knot_curve(phi - h)).normalize();
        let side = tangent.cross(Vec3::Y).normalize();
        let up = side.cross(tangent);
        let c = knot_curve(phi);
        for j in 0..sides {
            let theta = TAU * j as f32 / sides as f32;
            positions.push(c + TUBE_RADIUS * (theta.cos() * side + theta.sin() * up));
        }
    }
    let v = |i: usize, j: usize| ((i % segments) * sides + j % sides) as u32;
    let mut tris = Vec::with_capacity(2 * segments * sides);
    for i in 0..segments {
        for j in 0..sides {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    Mesh {
        positions,
        triangles: tris,
    }
}

/// A square floor of half-size `half` at height `y`, as four triangles
/// around its centre.
pub fn floor(y: f32, half: f32) -> Mesh {
    let positions = vec![
        Vec3::new(-half, y, -half),
        Vec3::new(half, y, -half),
        Vec3::new(half, y, half),
        Vec3::new(-half, y, half),
        Vec3::new(0.0, y, 0.0),
    ];
    Mesh {
        positions,
        triangles: vec![[0, 4, 1], [1, 4, 2], [2, 4, 3], [3, 4, 0]],
    }
}

/// The benchmark scene: [`torus_knot`] of `knot_triangles` triangles on a
/// [`floor`] just under it (4 more triangles).
pub fn knot_on_floor(knot_triangles: usize) -> Mesh {
    let mut mesh = torus_knot(knot_triangles);
    let (lo, _) = mesh.bounds();
    mesh.append(&floor(lo.y - 0.05, 6.0));
    mesh
}

/// A pinhole camera.
#[derive(Clone, Copy, Debug)]
pub struct Pinhole {
    /// Eye point.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit right vector, scaled by tan(θ) × aspect.
    pub right: Vec3,
    /// Unit up vector, scaled by tan(θ).
    pub up: Vec3,
}

impl Pinhole {
    /// Looking from `eye` at `target` with half vertical field of view
    /// `half_fov` (radians) on a `width` × `height` image.
    pub fn look_at(eye: Vec3, target: Vec3, half_fov: f32, width: u32, height: u32) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let t = half_fov.tan();
        Pinhole {
            eye,
            forward,
            right: right * t * width as f32 / height as f32,
            up: up * t,
        }
    }

    /// The unit-direction ray through the centre of pixel (i, j) (row j from the top).
    pub fn ray(&self, i: u32, j: u32, width: u32, height: u32) -> Ray {
        let x = 2.0 * (i as f32 + 0.5) / width as f32 - 1.0;
        let y = 1.0 - 2.0 * (j as f32 + 0.5) / height as f32;
        Ray::new(
            self.eye,
            (self.forward + x * self.right + y * self.up).normalize(),
        )
    }
}

/// The camera of the benchmark, framing [`knot_on_floor`] so that about 60%
/// of primary rays hit it.
pub fn knot_camera(width: u32, height: u32) -> Pinhole {
    Pinhole::look_at(
        Vec3::new(0.0, 4.5, 8.5),
        Vec3::new(0.0, -0.6, 0.0),
        0.36,
        width,
        height,
    )
}

/// One ray per pixel centre, row by row.
pub fn primary_rays(camera: &Pinhole, width: u32, height: u32) -> Vec<Ray> {
    (0..height)
        .flat_map(|j| (0..width).map(move |i| camera.ray(i, j, width, height)))
        .collect()
}

/// The same rays as [`primary_rays`], ordered tile by tile (`tile` × `tile`
/// pixels, tiles row by row, pixels row by row inside a tile), as a renderer
/// traces them: consecutive rays then share most of the BVH's nodes.
pub fn primary_rays_tiled(camera: &Pinhole, width: u32, height: u32, tile: u32) -> Vec<Ray> {
    let mut rays = Vec::with_capacity((width * height) as usize);
    for ty in (0..height).step_by(tile as usize) {
        for tx in (0..width).step_by(tile as usize) {
            for j in ty..(ty + tile).min(height) {
                for i in tx..(tx + tile).min(width) {
                    rays.push(camera.ray(i, j, width, height));
                }
            }
        }
    }
    rays
}

/// `n` rays with origins uniform in the box [lo, hi] and uniform unit
/// directions, from a fixed seed.
pub fn incoherent_rays(lo: Vec3, hi: Vec3, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Sampler::for_sample(seed, 0, 0, 0);
    (0..n)
        .map(|_| {
            let u = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            Ray::new(lo + u * (hi - lo), rng.next_direction())
        })
        .collect()
}

/// An `nx` × `ny` grid of unit squares in the plane z = `z`, corners at
/// integer (x, y), each square split along alternating diagonals: 2 nx ny
/// triangles sharing edges and vertices at exact lattice coordinates.
pub fn tiled_floor(nx: u32, ny: u32, z: f32) -> Mesh {
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
    Mesh {
        positions,
        triangles,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn torus_knot_has_the_requested_triangle_count_when_it_factors() {
        assert_eq!(torus_knot(1_000_000).triangles.len(), 1_000_000);
        assert_eq!(torus_knot(20_000).triangles.len(), 20_000);
        assert_eq!(knot_on_floor(20_000).triangles.len(), 20_004);
    }

    #[test]
    fn torus_knot_is_a_closed_tube() {
        // Every edge of a closed 2-manifold is shared by exactly two triangles.
        let m = torus_knot(2_000);
        let mut edges = std::collections::HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
        let (lo, hi) = m.bounds();
        assert!(lo.cmpgt(Vec3::splat(-3.5)).all() && hi.cmplt(Vec3::splat(3.5)).all());
    }

    #[test]
    fn tiled_primary_rays_are_the_same_rays_reordered() {
        let cam = knot_camera(50, 30);
        let key = |r: &Ray| (r.dir.x.to_bits(), r.dir.y.to_bits(), r.dir.z.to_bits());
        let mut a: Vec<_> = primary_rays(&cam, 50, 30).iter().map(key).collect();
        let mut b: Vec<_> = primary_rays_tiled(&cam, 50, 30, 16)
            .iter()
            .map(key)
            .collect();
        assert_eq!(b.len(), 50 * 30);
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
    }

    #[test]
    fn camera_rays_have_unit_directions_and_the_centre_looks_at_the_target() {
        let cam = knot_camera(64, 36);
        let rays = primary_rays(&cam, 64, 36);
        assert_eq!(rays.len(), 64 * 36);
        assert!(rays.iter().all(|r| (r.dir.length() - 1.0).abs() < 1e-5));
        assert!(cam.forward.dot(rays[18 * 64 + 32].dir) > 0.999);
    }
}
