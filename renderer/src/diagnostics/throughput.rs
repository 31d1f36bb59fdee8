//! Ray-casting throughput, measured the way other ray tracers are compared:
//! closest-hit queries on a fixed set of rays, on one thread and on all.

use super::quantile::quantile_by;
use crate::World;
use crate::accel::MeshBvh;
use crate::geometry::ray::Ray;
use crate::integrator::sampler::Sampler;
use crate::shapes::Method;
use crate::world::placed_mesh::PlacedMesh;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The side of the square tiles [`primary_rays`] come in: 4 × 4 pixels,
/// sixteen rays, one SIMD packet ([`crate::packet::WIDTH`]).
pub const PRIMARY_TILE: u32 = 4;

/// One ray per pixel centre P_ij (coherent), in tiles of
/// [`PRIMARY_TILE`]² pixels, as a renderer hands out camera rays: each
/// tile's rays row by row, tiles row by row from the top. (Tiles let the
/// batched cast trace a tile's rays as one packet; scanline order would
/// give a packet sixteen pixels in a row, which spread four times wider.)
pub fn primary_rays(world: &World) -> Vec<Ray> {
    let camera = &world.camera;
    let (w, h, tile) = (camera.w, camera.h, PRIMARY_TILE);
    let mut rays = Vec::with_capacity(w as usize * h as usize);
    for tile_j in (0..h).step_by(tile as usize) {
        for tile_i in (0..w).step_by(tile as usize) {
            for j in tile_j..(tile_j + tile).min(h) {
                for i in tile_i..(tile_i + tile).min(w) {
                    rays.push(camera.center_ray(i, j));
                }
            }
        }
    }
    rays
}

/// `count` incoherent rays: origins uniform in the box [min, max],
/// directions uniform on the sphere, reproducible from `seed`.
pub fn incoherent_rays(min: Vec3, max: Vec3, count: usize, seed: u64) -> Vec<Ray> {
    (0..count)
        .into_par_iter()
        .map(|k| {
            let mut s = Sampler::for_sample(seed, k as u32, (k >> 32) as u32, 0x1ac0);
            let t = Vec3::new(s.next_f32(), s.next_f32(), s.next_f32());
            Ray::new(min + t * (max - min), s.next_direction())
        })
        .collect()
}

/// What one timed cast measured.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Cast {
    /// Rays cast.
    pub rays: usize,
    /// Rays that hit something.
    pub hits: usize,
    /// Wall-clock time of the cast.
    pub seconds: f64,
}

impl Cast {
    /// Million rays per second.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds / 1e6
    }

    /// The fraction of rays that hit.
    pub fn hit_fraction(&self) -> f64 {
        self.hits as f64 / self.rays.max(1) as f64
    }
}

/// Casts every ray for its closest hit on the current rayon pool (in
/// chunks, so one thread or many run the same code) and times it.
pub fn cast_closest(world: &World, rays: &[Ray]) -> Cast {
    let start = Instant::now();
    let hits: usize = rays
        .par_chunks(4096)
        .map(|chunk| {
            chunk
                .iter()
                .filter(|r| world.intersect(r, Method::Robust).is_some())
                .count()
        })
        .sum();
    Cast {
        rays: rays.len(),
        hits,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// [`cast_closest`] with [`World::intersect_batch`] on chunks of rays (the
/// interleaved traversal that hides memory latency on incoherent rays).
pub fn cast_closest_batched(world: &World, rays: &[Ray]) -> Cast {
    let start = Instant::now();
    let hits: usize = rays
        .par_chunks(4096)
        .map(|chunk| {
            let mut hits = vec![None; chunk.len()];
            world.intersect_batch(chunk, Method::Robust, &mut hits);
            hits.iter().filter(|h| h.is_some()).count()
        })
        .sum();
    Cast {
        rays: rays.len(),
        hits,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The median of `runs` repeats of `measure` (by time); the machine is
/// shared, so one run says little.
pub fn median_of(runs: usize, mut measure: impl FnMut() -> Cast) -> Cast {
    let mut casts: Vec<Cast> = (0..runs.max(1)).map(|_| measure()).collect();
    quantile_by(&mut casts, 0.5, |a, b| a.seconds.total_cmp(&b.seconds)).expect("at least one run")
}

/// Runs `f` on a rayon pool of `threads` threads.
pub fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(f),
        Err(_) => f(),
    }
}

/// The time `f` takes.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let start = Instant::now();
    let value = f();
    (value, start.elapsed())
}

/// Every distinct mesh of `world` with its bottom-level BVH (instances of
/// one mesh share both, so each is listed once).
fn distinct_meshes(world: &World) -> Vec<&PlacedMesh> {
    let mut distinct: Vec<&PlacedMesh> = Vec::new();
    for placed in &world.meshes {
        if !distinct.iter().any(|d| Arc::ptr_eq(&d.mesh, &placed.mesh)) {
            distinct.push(placed);
        }
    }
    distinct
}

/// The triangles of `world`'s distinct meshes and the bytes of their BVHs.
pub fn mesh_bvh_footprint(world: &World) -> (usize, usize) {
    distinct_meshes(world).iter().fold((0, 0), |(t, b), m| {
        (t + m.mesh.triangles.len(), b + m.bvh().bytes())
    })
}

/// How long building the bottom-level BVH of every distinct mesh of
/// `world` again from scratch takes, in parallel (as a first load builds
/// them).
pub fn rebuild_mesh_bvhs(world: &World) -> Duration {
    let distinct = distinct_meshes(world);
    // The BVHs are dropped after the clock stops.
    timed(|| {
        distinct
            .par_iter()
            .map(|m| MeshBvh::build(&m.mesh.positions, &m.mesh.triangles))
            .collect::<Vec<_>>()
    })
    .1
}

/// Where incoherent rays start: the box of the mesh instance with the most
/// triangles (the model under test: the knot, not its floor), or, in a
/// scene without meshes, the box around every bounded shape; `None` when
/// nothing is bounded.
pub fn incoherent_origin_box(world: &World) -> Option<(Vec3, Vec3)> {
    let b = match world.meshes.iter().max_by_key(|m| m.mesh.triangles.len()) {
        Some(main) => main.bounds,
        None => world.bounded_box(),
    };
    (!b.is_empty()).then_some((b.min, b.max))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn incoherent_rays_start_in_the_box_with_unit_directions_and_are_reproducible() {
        let (min, max) = (Vec3::new(-1.0, 0.0, 2.0), Vec3::new(3.0, 1.0, 4.0));
        let rays = incoherent_rays(min, max, 1000, 7);
        assert_eq!(rays, incoherent_rays(min, max, 1000, 7));
        for r in &rays {
            assert!(r.origin.cmpge(min).all() && r.origin.cmple(max).all());
            assert!((r.dir.length() - 1.0).abs() < 1e-5);
        }
        // Uniform directions: the mean is near zero.
        let mean = rays.iter().map(|r| r.dir).sum::<Vec3>() / 1000.0;
        assert!(mean.length() < 0.1, "{mean}");
    }
}
