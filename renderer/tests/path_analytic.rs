//! The path tracer against analytic truth: furnaces, where the radiance of
//! every pixel is known in closed form whatever the light transport.

use glam::Vec3;
use renderer::integrator::Integrator;
use renderer::{Film, RenderOptions, Sampling, World};
use scene::{Camera, MaterialParams, Object, Scene, Shape};

fn matte(shape: Shape, albedo: f32, emission: Option<f32>) -> Object {
    Object {
        name: None,
        shape,
        material: Some("matte".into()),
        params: MaterialParams {
            color: Some(Vec3::splat(albedo)),
            emission: emission.map(Vec3::splat),
            ..Default::default()
        },
    }
}

fn camera(eye: Vec3, target: Vec3, size: u32) -> Camera {
    Camera {
        eye: Some(eye),
        toward: Some(target - eye),
        theta_deg: 40.0,
        width: size,
        height: size,
        ..Default::default()
    }
}

/// Every bounce, no depth limit: Russian roulette alone ends paths.
fn path_options(seed: u64) -> RenderOptions {
    RenderOptions {
        integrator: Integrator::Path,
        max_depth: u32::MAX,
        seed,
        ..Default::default()
    }
}

fn mean(film: &Film) -> Vec3 {
    let pixels = film.linear();
    pixels.iter().copied().sum::<Vec3>() / pixels.len() as f32
}

#[test]
fn white_furnace_a_white_sphere_in_a_uniform_sky_is_invisible() {
    // Albedo 1 reflects all the sky's radiance L: every pixel is L.
    let sky = 0.75;
    let scene = Scene {
        camera: camera(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 24),
        sky: Some(scene::Sky::constant(Vec3::splat(sky))),
        objects: vec![matte(
            Shape::Sphere {
                center: Some(Vec3::ZERO),
                radius: 1.0,
            },
            1.0,
            None,
        )],
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    let film = Film::render(&world, &path_options(1), 4);
    for (k, p) in film.linear().iter().enumerate() {
        assert!(
            (*p - Vec3::splat(sky)).abs().max_element() < 1e-5,
            "pixel {k} is {p}, the sky {sky}"
        );
    }
}

#[test]
fn a_grey_sphere_in_a_uniform_sky_reflects_albedo_times_the_sky() {
    // Convex: every reflected ray escapes, so the sphere shows a · L exactly.
    let (sky, albedo) = (0.6, 0.35);
    let scene = Scene {
        camera: Camera {
            theta_deg: 5.0,
            ..camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 8)
        },
        sky: Some(scene::Sky::constant(Vec3::splat(sky))),
        objects: vec![matte(
            Shape::Sphere {
                center: Some(Vec3::ZERO),
                radius: 1.0,
            },
            albedo,
            None,
        )],
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    let film = Film::render(&world, &path_options(2), 2);
    for p in film.linear() {
        assert!(
            (p - Vec3::splat(albedo * sky)).abs().max_element() < 1e-5,
            "{p}"
        );
    }
}

/// A closed cube of inward-facing triangles, all emitting `emission` and of albedo `albedo`.
fn glowing_enclosure(albedo: f32, emission: f32) -> Vec<Object> {
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    // Each face as a quad a, b, c, d, wound to face inward below.
    let faces = [
        [
            c(-1., -1., -1.),
            c(1., -1., -1.),
            c(1., -1., 1.),
            c(-1., -1., 1.),
        ],
        [
            c(-1., 1., -1.),
            c(-1., 1., 1.),
            c(1., 1., 1.),
            c(1., 1., -1.),
        ],
        [
            c(-1., -1., -1.),
            c(-1., 1., -1.),
            c(1., 1., -1.),
            c(1., -1., -1.),
        ],
        [
            c(-1., -1., 1.),
            c(1., -1., 1.),
            c(1., 1., 1.),
            c(-1., 1., 1.),
        ],
        [
            c(-1., -1., -1.),
            c(-1., -1., 1.),
            c(-1., 1., 1.),
            c(-1., 1., -1.),
        ],
        [
            c(1., -1., -1.),
            c(1., 1., -1.),
            c(1., 1., 1.),
            c(1., -1., 1.),
        ],
    ];
    let mut objects = Vec::new();
    for [a, b, cc, d] in faces {
        // The face's centre is (a + cc) / 2; the normal must point back to the origin.
        let (b, d) = if (b - a).cross(cc - a).dot(-(a + cc)) > 0.0 {
            (b, d)
        } else {
            (d, b)
        };
        for (t0, t1, t2) in [(a, b, cc), (a, cc, d)] {
            objects.push(matte(
                Shape::Triangle { t0, t1, t2 },
                albedo,
                Some(emission),
            ));
        }
    }
    objects
}

#[test]
fn furnace_inside_a_glowing_box_every_pixel_is_emission_over_one_minus_albedo() {
    // L = E + a L everywhere inside, so L = E / (1 − a): infinite bounces,
    // with light sampling and MIS at every vertex.
    // Sample counts for a 1% tolerance of at least 4 standard deviations:
    // over 96 seeds a 16-spp image's mean spread by 0.39% (albedo 0.5) and
    // 1.45% (albedo 0.8) of the expected value, their grand means within
    // 0.4 standard errors of it.
    for (albedo, spp, sampling) in [
        (0.0f32, 1, Sampling::Independent),
        (0.5, 64, Sampling::Independent),
        (0.8, 512, Sampling::Independent),
        (0.8, 512, Sampling::Sobol),
    ] {
        let emission = 0.25;
        let scene = Scene {
            camera: camera(Vec3::new(0.1, 0.2, 0.5), Vec3::new(-0.3, -0.1, -1.0), 12),
            objects: glowing_enclosure(albedo, emission),
            ..Default::default()
        };
        let world = World::from_scene(&scene).expect("valid");
        let options = RenderOptions {
            sampling,
            ..path_options(3)
        };
        let film = Film::render(&world, &options, spp);
        let expected = emission / (1.0 - albedo);
        let m = mean(&film);
        assert!(
            (m - Vec3::splat(expected)).abs().max_element() < 0.01 * expected,
            "albedo {albedo}, {sampling:?}: mean {m}, expected {expected}"
        );
        // Single pixels are heavy-tailed (Russian roulette), so the image
        // mean is what is tested; no sample may be lost either.
        assert_eq!(film.discarded(), 0);
    }
}

#[test]
fn mitsuba_depth_one_sees_emitters_only_and_depth_two_adds_direct_light() {
    // Inside the glowing box: max_depth 1 gives E, 2 gives E + a E exactly
    // in expectation (one bounce of a uniform emitter).
    let (albedo, emission) = (0.5f32, 0.3f32);
    let scene = Scene {
        camera: camera(Vec3::ZERO, Vec3::new(0.2, -0.4, -1.0), 8),
        objects: glowing_enclosure(albedo, emission),
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    for (depth, expected) in [(1, emission), (2, emission * (1.0 + albedo))] {
        let options = RenderOptions {
            max_depth: depth,
            ..path_options(4)
        };
        let m = mean(&Film::render(&world, &options, 32));
        assert!(
            (m - Vec3::splat(expected)).abs().max_element() < 0.01 * expected,
            "max_depth {depth}: mean {m}, expected {expected}"
        );
    }
}
