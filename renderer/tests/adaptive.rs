//! Adaptive sampling: pixels whose error estimate is below the threshold
//! stop receiving samples, the others go on, and a film where every pixel
//! has stopped says it has converged.

use glam::Vec3;
use renderer::integrator::Integrator;
use renderer::integrator::adaptive::Adaptive;
use renderer::{Film, RenderOptions, World};
use scene::{Camera, MaterialParams, Object, Scene, Shape};

fn sphere(center: Vec3, radius: f32, emission: Option<f32>) -> Object {
    Object {
        name: None,
        shape: Shape::Sphere {
            center: Some(center),
            radius,
        },
        material: Some("matte".into()),
        params: MaterialParams {
            color: Some(Vec3::splat(0.6)),
            emission: emission.map(Vec3::splat),
            ..Default::default()
        },
    }
}

/// A matte sphere lit by a small glowing one, against a black background.
fn lit_sphere(size: u32) -> World {
    let scene = Scene {
        camera: Camera {
            eye: Some(Vec3::new(0.0, 0.0, 3.0)),
            toward: Some(Vec3::NEG_Z),
            theta_deg: 30.0,
            width: size,
            height: size,
            ..Default::default()
        },
        objects: vec![
            sphere(Vec3::ZERO, 1.0, None),
            sphere(Vec3::new(2.0, 2.0, 2.0), 0.3, Some(10.0)),
        ],
        ..Default::default()
    };
    World::from_scene(&scene).expect("valid")
}

fn adaptive_path(threshold: f32) -> RenderOptions {
    RenderOptions {
        integrator: Integrator::Path,
        adaptive: Some(Adaptive { threshold }),
        ..Default::default()
    }
}

#[test]
fn black_background_pixels_stop_after_the_minimum_and_lit_ones_go_on() {
    let size = 24;
    let world = lit_sphere(size);
    let passes = 40;
    let film = Film::render(&world, &adaptive_path(0.005), passes);
    let counts = film.samples_per_pixel();
    let at = |i: u32, j: u32| counts[(j * size + i) as usize];
    // The corners see the black background: zero variance.
    for (i, j) in [(0, 0), (size - 1, 0), (0, size - 1), (size - 1, size - 1)] {
        assert_eq!(at(i, j), Adaptive::MIN_SAMPLES, "corner ({i}, {j})");
        assert_eq!(film.pixel(i, j), Vec3::ZERO);
    }
    // The sphere's lit centre is noisy (light sampling of a small sphere):
    // far above 0.5% error after 40 samples.
    assert_eq!(at(size / 2, size / 2), passes);
    assert!(film.mean_spp() < f64::from(passes));
    assert_eq!(
        film.samples(),
        counts.iter().map(|&n| u64::from(n)).sum::<u64>()
    );
    assert!(!film.converged());
}

#[test]
fn without_adaptive_sampling_every_pixel_gets_every_pass() {
    let world = lit_sphere(12);
    let options = RenderOptions {
        adaptive: None,
        ..adaptive_path(0.005)
    };
    let film = Film::render(&world, &options, 20);
    assert!(film.samples_per_pixel().iter().all(|&n| n == 20));
}

#[test]
fn adaptive_and_uniform_sampling_agree_on_the_image() {
    // Stopping early must not move the answer: the image mean agrees with
    // a uniform render's within their noise.
    let world = lit_sphere(16);
    let mean = |film: &Film| film.linear().iter().copied().sum::<Vec3>() / 256.0;
    let uniform = Film::render(
        &world,
        &RenderOptions {
            adaptive: None,
            seed: 1,
            ..adaptive_path(0.02)
        },
        64,
    );
    let adaptive = Film::render(&world, &adaptive_path(0.02), 64);
    let (u, a) = (mean(&uniform), mean(&adaptive));
    assert!(
        (u - a).abs().max_element() < 0.02 * u.max_element(),
        "{u} {a}"
    );
}

#[test]
fn a_film_whose_pixels_all_stopped_has_converged() {
    // Nothing in view: every sample is black, every pixel stops at the minimum.
    let scene = Scene {
        camera: Camera {
            width: 8,
            height: 6,
            ..Default::default()
        },
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    let options = adaptive_path(0.02);
    let mut film = Film::render(&world, &options, Adaptive::MIN_SAMPLES);
    assert!(!film.converged());
    film.add_pass(&world, &options);
    assert!(film.converged());
    assert_eq!(film.samples(), 48 * u64::from(Adaptive::MIN_SAMPLES));
}
