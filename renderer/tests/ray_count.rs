//! The film counts every ray it traces: camera rays, the shadow rays of
//! diffuse hits and the secondary rays a mirror spawns, exactly.

use renderer::integrator::sampler::Sampler;
use renderer::{Film, Method, RenderOptions, World};
use scene::{Light, LightKind, Object, Scene, Shape};

/// A sphere of `material` lit only by ambient light (so no shadow rays).
fn world(material: &str) -> World {
    world_lit(
        material,
        Light {
            name: None,
            kind: LightKind::Ambient,
            color: glam::Vec3::ONE,
            intensity: 0.5,
        },
    )
}

/// A sphere of `material` lit by `light` alone, seen by a framing camera.
fn world_lit(material: &str, light: Light) -> World {
    let scene = Scene {
        camera: scene::Camera {
            width: 40,
            height: 30,
            ..Default::default()
        },
        lights: vec![light],
        objects: vec![Object {
            name: None,
            shape: Shape::default_for_tag("sphere").expect("sphere"),
            material: Some(material.to_owned()),
            params: Default::default(),
        }],
        ..Default::default()
    };
    World::from_scene(&scene).expect("valid")
}

/// Pixels whose first-pass camera ray (the same jitter the film uses) hits.
fn hits(world: &World, options: &RenderOptions) -> u64 {
    let mut count = 0;
    for j in 0..world.camera.h {
        for i in 0..world.camera.w {
            let mut sampler = Sampler::for_pixel_sample(options.sampling, options.seed, i, j, 0);
            let ray = world.camera.ray(i, j, sampler.next_2d());
            count += u64::from(world.intersect(&ray, Method::Robust).is_some());
        }
    }
    count
}

#[test]
fn a_matte_scene_without_lights_traces_one_ray_per_pixel() {
    let world = world("matte");
    let mut film = Film::new(world.camera.w, world.camera.h);
    film.add_pass(&world, &RenderOptions::default());
    assert_eq!(film.rays(), 40 * 30);
    film.add_pass(&world, &RenderOptions::default());
    assert_eq!(film.rays(), 2 * 40 * 30);
}

#[test]
fn a_mirror_sphere_adds_one_reflected_ray_per_hit() {
    let world = world("mirror");
    let options = RenderOptions::default();
    let hit = hits(&world, &options);
    assert!(hit > 100, "the sphere fills part of the image ({hit})");
    let mut film = Film::new(world.camera.w, world.camera.h);
    film.add_pass(&world, &options);
    // A ray reflected off a lone convex sphere escapes: one more ray per hit.
    assert_eq!(film.rays(), 40 * 30 + hit);
}

#[test]
fn a_point_light_at_the_eye_adds_one_shadow_ray_per_diffuse_hit() {
    // Every point the camera sees faces a light at the eye, so each pixel
    // whose camera ray hits the matte sphere casts exactly one shadow ray.
    let eye = world("matte").camera.p0;
    let world = world_lit(
        "matte",
        Light {
            name: None,
            kind: LightKind::Point { position: eye },
            color: glam::Vec3::ONE,
            intensity: 10.0,
        },
    );
    assert_eq!(
        world.camera.p0, eye,
        "lights do not move the framing camera"
    );
    let options = RenderOptions::default();
    let hit = hits(&world, &options);
    assert!(hit > 100, "the sphere fills part of the image ({hit})");
    let mut film = Film::new(world.camera.w, world.camera.h);
    film.add_pass(&world, &options);
    assert_eq!(film.rays(), 40 * 30 + hit);
}
