//! The path tracer against converged Mitsuba 3 renders of the same scenes
//! (assets/reference/, made as its README says). A short render is compared
//! on block averages, which divide its noise by the block's pixel count
//! while keeping any bias: a wrong convention (light units, emitting side,
//! depth counting, Fresnel) moves every block and fails the bound.

use renderer::diagnostics::metrics::{downsample, rel_mse};
use renderer::diagnostics::reference_image::read_exr_rgb;
use renderer::integrator::Integrator;
use renderer::{Film, RenderOptions, Sampling, World};
use std::path::PathBuf;

fn reference_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets/reference")
}

/// relMSE of an `spp` render of `name` against its reference, both averaged
/// over `block` × `block` pixel squares.
fn block_error(name: &str, spp: u32, block: u32, sampling: Sampling) -> f64 {
    let dir = reference_dir();
    let scene = scene::read_file(&dir.join(format!("{name}.xml"))).expect("reference scene");
    let world = World::from_scene(&scene).expect("valid");
    let reference = read_exr_rgb(&dir.join(format!("{name}.exr"))).expect("reference image");
    let (w, h) = (world.camera.w, world.camera.h);
    assert_eq!((reference.width, reference.height), (w, h));
    let options = RenderOptions {
        integrator: Integrator::Path,
        max_depth: 8,
        seed: 5,
        sampling,
        ..Default::default()
    };
    let film = Film::render(&world, &options, spp);
    assert_eq!(film.discarded(), 0, "no NaN or infinite samples");
    let (ours, _, _) = downsample(&film.linear(), w, h, block);
    let (theirs, _, _) = downsample(&reference.pixels, w, h, block);
    rel_mse(&ours, &theirs)
}

/// The issues' bound on a converged render (the reference's own noise is ~1e-4).
const BOUND: f64 = 2.0e-3;

#[test]
fn cornell_box_matches_mitsuba() {
    let e = block_error("cornell", 8, 8, Sampling::Independent);
    eprintln!("cornell, 8 spp: relMSE of 8×8 blocks {e:.3e}");
    assert!(e <= BOUND, "relMSE of 8×8 blocks {e:.3e} > {BOUND:.0e}");
}

#[test]
fn hundred_spheres_with_glass_and_mirrors_match_mitsuba() {
    // Caustics through glass are noisy at low sample counts: larger blocks.
    let e = block_error("spheres", 16, 16, Sampling::Independent);
    eprintln!("spheres, 16 spp: relMSE of 16×16 blocks {e:.3e}");
    assert!(e <= BOUND, "relMSE of 16×16 blocks {e:.3e} > {BOUND:.0e}");
}

#[test]
fn rough_conductor_and_rough_glass_match_mitsuba() {
    // GGX microfacets against Mitsuba's roughconductor and roughdielectric;
    // the frosted sphere's caustic is noisy at low sample counts.
    let e = block_error("rough", 16, 16, Sampling::Independent);
    eprintln!("rough, 16 spp: relMSE of 16×16 blocks {e:.3e}");
    assert!(e <= BOUND, "relMSE of 16×16 blocks {e:.3e} > {BOUND:.0e}");
}

#[test]
fn cornell_box_with_sobol_samples_matches_mitsuba() {
    // Stratifying the first bounce must not move the answer.
    let e = block_error("cornell", 8, 8, Sampling::Sobol);
    eprintln!("cornell, Sobol, 8 spp: relMSE of 8×8 blocks {e:.3e}");
    assert!(e <= BOUND, "relMSE of 8×8 blocks {e:.3e} > {BOUND:.0e}");
}

#[test]
fn environment_map_lighting_matches_mitsuba() {
    // An HDR sky with a small bright sun, turned 30° about y, over matte,
    // mirror, glass and rough spheres on a floor: the map's orientation,
    // its interpolation, and its importance sampling weighed by MIS
    // against BSDF sampling, against Mitsuba's `envmap`.
    let e = block_error("sky", 16, 8, Sampling::Independent);
    eprintln!("sky, 16 spp: relMSE of 8×8 blocks {e:.3e}");
    assert!(e <= BOUND, "relMSE of 8×8 blocks {e:.3e} > {BOUND:.0e}");
}
