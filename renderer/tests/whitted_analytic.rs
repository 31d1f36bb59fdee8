//! The Whitted integrator against analytic radiance.

mod common;

use glam::Vec3;
use renderer::integrator::sample_pixel;
use renderer::{Film, RenderOptions, World};
use scene::{Camera, Light, LightKind, MaterialParams, Object, Scene, Shape};
use std::f32::consts::PI;

fn object(shape: Shape, material: &str, color: Vec3) -> Object {
    Object {
        name: None,
        shape,
        material: Some(material.into()),
        params: MaterialParams {
            color: Some(color),
            ..Default::default()
        },
    }
}

fn point_light(position: Vec3, intensity: f32) -> Light {
    Light {
        name: None,
        kind: LightKind::Point { position },
        color: Vec3::ONE,
        intensity,
    }
}

fn ambient(radiance: f32) -> Light {
    Light {
        name: None,
        kind: LightKind::Ambient,
        color: Vec3::ONE,
        intensity: radiance,
    }
}

/// A camera at `eye` looking at `target` with a tiny field of view (one pixel ≈ one ray).
fn narrow_camera(eye: Vec3, target: Vec3, size: u32) -> Camera {
    Camera {
        eye: Some(eye),
        toward: Some(target - eye),
        up: if (target - eye).cross(Vec3::Y).length() > 0.0 {
            Vec3::Y
        } else {
            Vec3::NEG_Z
        },
        theta_deg: 0.05,
        width: size,
        height: size,
        ..Default::default()
    }
}

#[test]
fn lambert_floor_under_a_point_light_has_radiance_albedo_over_pi_times_i_over_r_squared() {
    let scene = Scene {
        camera: narrow_camera(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, 1),
        lights: vec![point_light(Vec3::new(0.0, 2.0, 0.0), 40.0)],
        objects: vec![object(Shape::Floor { y: 0.0 }, "matte", Vec3::splat(0.5))],
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    let radiance = sample_pixel(&world, &RenderOptions::default(), 0, 0, 0);
    let expected = 0.5 / PI * 40.0 / 4.0;
    assert!(
        (radiance - Vec3::splat(expected)).abs().max_element() < 1e-4 * expected,
        "{radiance} vs {expected}"
    );
}

#[test]
fn a_blocker_between_light_and_floor_casts_a_black_shadow() {
    let scene = Scene {
        camera: narrow_camera(Vec3::new(3.0, 5.0, 0.0), Vec3::ZERO, 1),
        lights: vec![point_light(Vec3::new(0.0, 4.0, 0.0), 40.0)],
        objects: vec![
            object(Shape::Floor { y: 0.0 }, "matte", Vec3::splat(0.5)),
            object(
                Shape::Sphere {
                    center: Some(Vec3::new(0.0, 2.0, 0.0)),
                    radius: 0.5,
                },
                "matte",
                Vec3::ONE,
            ),
        ],
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    assert_eq!(
        sample_pixel(&world, &RenderOptions::default(), 0, 0, 0),
        Vec3::ZERO
    );
}

#[test]
fn surfaces_in_uniform_ambient_light_reflect_albedo_times_ambient() {
    for (material, color) in [
        ("matte", Vec3::new(0.2, 0.5, 0.8)),
        ("mirror", Vec3::new(0.9, 0.6, 0.3)),
    ] {
        let scene = Scene {
            camera: narrow_camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 1),
            lights: vec![ambient(0.7)],
            objects: vec![object(
                Shape::Sphere {
                    center: Some(Vec3::ZERO),
                    radius: 1.0,
                },
                material,
                color,
            )],
            ..Default::default()
        };
        let world = World::from_scene(&scene).expect("valid");
        let radiance = sample_pixel(&world, &RenderOptions::default(), 0, 0, 0);
        assert!(
            (radiance - 0.7 * color).abs().max_element() < 1e-5,
            "{material}: {radiance}"
        );
    }
}

#[test]
fn clear_glass_in_a_uniform_environment_is_invisible() {
    // Fresnel reflection and refraction split energy without loss, so every
    // pixel of a glass sphere sees the environment's radiance (up to the depth cut-off).
    let world = common::glass_sphere_under_sky(1.0, 24);
    let options = RenderOptions {
        max_depth: 24,
        ..Default::default()
    };
    let film = Film::render(&world, &options, 1);
    for value in film.linear() {
        assert!((value - Vec3::ONE).abs().max_element() < 0.01, "{value}");
    }
}

#[test]
fn no_shadow_acne_on_a_floor_1e4_units_across() {
    // A lit floor seen from 1e4 units away: no pixel may shadow itself.
    let scene = Scene {
        camera: Camera {
            eye: Some(Vec3::new(0.0, 6000.0, 10000.0)),
            toward: Some(Vec3::new(5000.0, -6000.0, -5000.0)),
            theta_deg: 10.0,
            width: 64,
            height: 64,
            ..Default::default()
        },
        lights: vec![point_light(Vec3::new(5000.0, 8000.0, 5000.0), 1e8)],
        objects: vec![
            object(Shape::Floor { y: 0.0 }, "matte", Vec3::splat(0.5)),
            object(
                Shape::Sphere {
                    center: Some(Vec3::new(5000.0, 2000.0, 5000.0)),
                    radius: 1500.0,
                },
                "matte",
                Vec3::ONE,
            ),
        ],
        ..Default::default()
    };
    let world = World::from_scene(&scene).expect("valid");
    let options = RenderOptions::default();
    let mut lit_sphere = 0;
    for j in 0..64 {
        for i in 0..64 {
            let ray = world.camera.center_ray(i, j);
            let Some(hit) = world.intersect(&ray, options.method) else {
                continue;
            };
            let surface = world.surface(&ray, hit);
            let to_light = (Vec3::new(5000.0, 8000.0, 5000.0) - surface.point).normalize();
            let facing = surface.normal.dot(to_light) > 0.05;
            let in_shadow = hit.object == 0 && {
                // The floor under the sphere is legitimately shadowed, out to
                // radius 8000 · tan(asin(1500 / 6000)) ≈ 2066.
                let flat = Vec3::new(surface.point.x - 5000.0, 0.0, surface.point.z - 5000.0);
                flat.length() < 2100.0
            };
            if facing && !in_shadow {
                let radiance = renderer::integrator::whitted(&world, &ray, &options);
                assert!(
                    radiance.max_element() > 0.0,
                    "acne at pixel ({i}, {j}) on object {} at {} n {}",
                    hit.object,
                    surface.point,
                    surface.normal
                );
                lit_sphere += (hit.object == 1) as u32;
            }
        }
    }
    assert!(
        lit_sphere > 100,
        "the test sees the lit side of the sphere ({lit_sphere})"
    );
}
