//! `raylab bench SCENE` and `raylab bench suite`: BVH build time, closest-hit
//! throughput for primary and incoherent rays, Whitted frame time and memory,
//! on one thread and on all, as a table or JSON.

use crate::io::stdout::say;
use anyhow::Result;
use glam::Vec3;
use renderer::diagnostics::quantile::quantile_by;
use renderer::diagnostics::throughput::{self, Cast};
use renderer::geometry::ray::Ray;
use renderer::{Film, RenderOptions, World};
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// Repeats of every timed figure; the median is reported.
const RUNS: usize = 5;

/// One figure measured on one thread and on all of them.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PerThreads<T> {
    /// On a pool of one thread.
    pub one: T,
    /// On every thread of the machine.
    pub all: T,
}

/// Everything `raylab bench SCENE` reports for one scene.
#[derive(Clone, Debug, Serialize)]
pub struct SceneFigures {
    /// What was measured.
    pub scene: String,
    /// Image size the primary rays and the frame were traced at.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Threads in "all".
    pub threads: usize,
    /// The lane type the packets and paths ran on (`avx512`, `avx2` or
    /// `portable`; `RAYLAB_LANES` chooses a narrower one).
    pub lanes: &'static str,
    /// Objects in the scene.
    pub objects: usize,
    /// Triangles drawn (mesh instances).
    pub triangles: usize,
    /// Seconds to build every mesh's BVH from scratch (all threads; median).
    pub mesh_bvh_build_seconds: f64,
    /// The same on one thread.
    pub mesh_bvh_build_seconds_one_thread: f64,
    /// Seconds to prepare the world after an edit (top level; mesh BVHs reused).
    pub edit_rebuild_seconds: f64,
    /// Bytes of the mesh BVHs (nodes and triangle copies) per triangle.
    pub bytes_per_triangle: Option<f64>,
    /// The most memory one worker holds for a pass (its chunk of samples
    /// and the path tracer's batch of lanes), whatever the image's size.
    pub pass_bytes_per_thread: usize,
    /// One closest-hit ray per pixel centre P_ij.
    pub primary: PerThreads<CastFigures>,
    /// The same primary rays in batches (`World::intersect_batch`: runs of
    /// eight neighbouring pixels' rays traced as one packet); the
    /// integrators still trace one ray at a time.
    pub primary_batched: PerThreads<CastFigures>,
    /// Closest-hit rays from random points in the scene's box, uniform directions.
    pub incoherent: Option<PerThreads<CastFigures>>,
    /// The same incoherent rays in batches (`World::intersect_batch`: several
    /// rays traced interleaved, as they form no packets); the integrators
    /// still trace one ray at a time.
    pub incoherent_batched: Option<PerThreads<CastFigures>>,
    /// One Whitted pass of one sample per pixel, seconds.
    pub whitted_frame_seconds: PerThreads<f64>,
}

/// A timed cast, as reported.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct CastFigures {
    /// Rays cast.
    pub rays: usize,
    /// Fraction that hit.
    pub hit_fraction: f64,
    /// Million rays per second (median of the repeats).
    pub mrays_per_second: f64,
}

impl From<Cast> for CastFigures {
    fn from(c: Cast) -> Self {
        CastFigures {
            rays: c.rays,
            hit_fraction: c.hit_fraction(),
            mrays_per_second: c.mrays_per_second(),
        }
    }
}

/// Measures `scene` at `width × height` (its own size when `None`); the
/// incoherent set has as many rays as the image has pixels.
pub fn measure(
    scene: Scene,
    label: &str,
    width: Option<u32>,
    height: Option<u32>,
) -> Result<SceneFigures> {
    let scene = sized(scene, width, height);
    let resolved = scene::resolve(&scene)?;
    let world = World::new(&resolved)?;
    renderer::film::image_memory::check_world_fits(&world)?;
    let threads = rayon::current_num_threads();
    let (triangles, bytes) = throughput::mesh_bvh_footprint(&world);
    let build = || median_seconds(|| throughput::rebuild_mesh_bvhs(&world).as_secs_f64());
    let (build_all, build_one) = (build(), throughput::on_threads(1, build));
    let edit = median_seconds(|| {
        let start = Instant::now();
        let _ = World::new(&resolved);
        start.elapsed().as_secs_f64()
    });
    let primary_rays = throughput::primary_rays(&world);
    let cast_with = |cast: fn(&World, &[Ray]) -> throughput::Cast, rays: &[Ray]| PerThreads {
        one: throughput::on_threads(1, || throughput::median_of(RUNS, || cast(&world, rays)))
            .into(),
        all: throughput::median_of(RUNS, || cast(&world, rays)).into(),
    };
    let primary = cast_with(throughput::cast_closest, &primary_rays);
    let primary_batched = cast_with(throughput::cast_closest_batched, &primary_rays);
    drop(primary_rays);
    let incoherent_set = incoherent_rays(&world).map(|(_, rays)| rays);
    let incoherent = incoherent_set
        .as_ref()
        .map(|rays| cast_with(throughput::cast_closest, rays));
    let incoherent_batched = incoherent_set
        .as_ref()
        .map(|rays| cast_with(throughput::cast_closest_batched, rays));
    drop(incoherent_set);
    let options = RenderOptions::default();
    let frame = || {
        median_seconds(|| {
            let start = Instant::now();
            let _ = Film::render(&world, &options, 1);
            start.elapsed().as_secs_f64()
        })
    };
    let whitted_frame_seconds = PerThreads {
        one: throughput::on_threads(1, frame),
        all: frame(),
    };
    Ok(SceneFigures {
        scene: label.to_owned(),
        width: world.camera.w,
        height: world.camera.h,
        threads,
        lanes: renderer::simd::LaneType::chosen().name(),
        objects: world.objects.len(),
        triangles: world.triangle_count(),
        mesh_bvh_build_seconds: build_all,
        mesh_bvh_build_seconds_one_thread: build_one,
        edit_rebuild_seconds: edit,
        bytes_per_triangle: (triangles > 0).then(|| bytes as f64 / triangles as f64),
        pass_bytes_per_thread: Film::pass_bytes_per_thread(&world),
        primary,
        primary_batched,
        incoherent,
        incoherent_batched,
        whitted_frame_seconds,
    })
}

/// Seed of the incoherent rays, so that every run (and an export) casts the same ones.
pub const INCOHERENT_SEED: u64 = 1;

/// The incoherent rays `measure` casts in `world`: as many as the image has
/// pixels, starting in [`throughput::incoherent_origin_box`] (returned
/// too); `None` when nothing is bounded.
pub fn incoherent_rays(world: &World) -> Option<((Vec3, Vec3), Vec<Ray>)> {
    let (lo, hi) = throughput::incoherent_origin_box(world)?;
    let count = (world.camera.w * world.camera.h) as usize;
    let rays = throughput::incoherent_rays(lo, hi, count, INCOHERENT_SEED);
    Some(((lo, hi), rays))
}

/// `scene` at `width × height` (its own size where `None`).
pub fn sized(mut scene: Scene, width: Option<u32>, height: Option<u32>) -> Scene {
    if let Some(w) = width {
        scene.camera.width = w;
    }
    if let Some(h) = height {
        scene.camera.height = h;
    }
    scene
}

/// The median of [`RUNS`] timings.
fn median_seconds(mut f: impl FnMut() -> f64) -> f64 {
    let mut t: Vec<f64> = (0..RUNS).map(|_| f()).collect();
    quantile_by(&mut t, 0.5, f64::total_cmp).expect("RUNS timings")
}

/// The figures as a readable table.
pub fn print_table(f: &SceneFigures) {
    say!(
        "{} — {} objects, {} triangles, {}×{}, {} threads, {} lanes",
        f.scene,
        f.objects,
        f.triangles,
        f.width,
        f.height,
        f.threads,
        f.lanes
    );
    say!(
        "  mesh BVH build            {:>9.3} s on 1 thread, {:>7.3} on {}   top level after an edit {:>8.2} ms",
        f.mesh_bvh_build_seconds_one_thread,
        f.mesh_bvh_build_seconds,
        f.threads,
        f.edit_rebuild_seconds * 1e3
    );
    if let Some(b) = f.bytes_per_triangle {
        say!("  acceleration structure    {b:>9.1} bytes per triangle");
    }
    say!(
        "  pass memory per worker    {:>9.1} KiB (chunk of samples + batch of paths, any image size)",
        f.pass_bytes_per_thread as f64 / 1024.0
    );
    let row = |name: &str, c: &PerThreads<CastFigures>| {
        say!(
            "  {name:<25} {:>9.2} Mrays/s on 1 thread, {:>7.2} on {} ({:.0}% hit, {} rays)",
            c.one.mrays_per_second,
            c.all.mrays_per_second,
            f.threads,
            100.0 * c.all.hit_fraction,
            c.all.rays
        );
    };
    row("primary closest-hit", &f.primary);
    row("  the same, batched", &f.primary_batched);
    if let Some(inc) = &f.incoherent {
        row("incoherent closest-hit", inc);
    }
    if let Some(inc) = &f.incoherent_batched {
        row("  the same, batched", inc);
    }
    say!(
        "  Whitted frame, 1 spp      {:>9.1} ms on 1 thread, {:>7.1} ms on {}",
        f.whitted_frame_seconds.one * 1e3,
        f.whitted_frame_seconds.all * 1e3,
        f.threads
    );
}

/// How cost grows with the triangle count: the knot at each size, all threads.
#[derive(Clone, Debug, Serialize)]
pub struct ScalingRow {
    /// Triangles.
    pub triangles: usize,
    /// Mesh BVH build seconds (median).
    pub build_seconds: f64,
    /// Primary closest-hit Mrays/s (all threads).
    pub primary_mrays_per_second: f64,
    /// Incoherent closest-hit Mrays/s (all threads).
    pub incoherent_mrays_per_second: f64,
    /// Bytes per triangle.
    pub bytes_per_triangle: f64,
}

/// The knot at 1k, 10k, 100k and 1M triangles, 1920×1080 rays, all threads.
pub fn scaling() -> Result<Vec<ScalingRow>> {
    [1_000usize, 10_000, 100_000, 1_000_000]
        .into_iter()
        .map(|n| {
            let world = World::from_scene(&scene::generate::knot_scene(n))?;
            let (triangles, bytes) = throughput::mesh_bvh_footprint(&world);
            let build = median_seconds(|| throughput::rebuild_mesh_bvhs(&world).as_secs_f64());
            let primary = throughput::primary_rays(&world);
            let p = throughput::median_of(RUNS, || throughput::cast_closest(&world, &primary));
            let (_, rays) = incoherent_rays(&world).unwrap_or_default();
            let i = throughput::median_of(RUNS, || throughput::cast_closest(&world, &rays));
            Ok(ScalingRow {
                triangles,
                build_seconds: build,
                primary_mrays_per_second: p.mrays_per_second(),
                incoherent_mrays_per_second: i.mrays_per_second(),
                bytes_per_triangle: bytes as f64 / triangles.max(1) as f64,
            })
        })
        .collect()
}

/// The scaling rows as a table.
pub fn print_scaling(rows: &[ScalingRow]) {
    say!("cost against triangle count (torus knot, 1920×1080 rays, all threads):");
    say!(
        "  {:>10} {:>10} {:>16} {:>19} {:>12}",
        "triangles",
        "build s",
        "primary Mrays/s",
        "incoherent Mrays/s",
        "bytes/tri"
    );
    for r in rows {
        say!(
            "  {:>10} {:>10.4} {:>16.2} {:>19.2} {:>12.1}",
            r.triangles,
            r.build_seconds,
            r.primary_mrays_per_second,
            r.incoherent_mrays_per_second,
            r.bytes_per_triangle
        );
    }
}
