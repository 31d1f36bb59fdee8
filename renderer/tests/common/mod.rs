//! What several test files share: loading the scenes that ship with raylab,
//! and scenes with a known answer. Each test file uses some of them.
#![allow(dead_code)]

use glam::Vec3;
use renderer::World;
use scene::{Camera, Light, LightKind, MaterialParams, Object, Scene, Shape};
use std::path::Path;

/// `assets/FOLDER/NAME` (a shipped or reference scene) at `width` × `height`.
pub fn asset_world(folder: &str, name: &str, width: u32, height: u32) -> World {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(folder)
        .join(name);
    let mut scene = scene::read_file(&path).expect("a shipped scene parses");
    scene.camera.width = width;
    scene.camera.height = height;
    World::from_scene(&scene).expect("a shipped scene is valid")
}

/// A clear (white) glass sphere of radius 1 at the origin, seen whole by a
/// `size` × `size` camera on +z, under nothing but an ambient light of
/// radiance `sky` (what every ray leaving the scene sees).
pub fn glass_sphere_under_sky(sky: f32, size: u32) -> World {
    let scene = Scene {
        camera: Camera {
            eye: Some(Vec3::new(0.0, 0.0, 4.0)),
            toward: Some(Vec3::NEG_Z),
            theta_deg: 20.0,
            width: size,
            height: size,
            ..Default::default()
        },
        lights: vec![Light {
            name: None,
            kind: LightKind::Ambient,
            color: Vec3::ONE,
            intensity: sky,
        }],
        objects: vec![Object {
            name: None,
            shape: Shape::Sphere {
                center: Some(Vec3::ZERO),
                radius: 1.0,
            },
            material: Some("glass".into()),
            params: MaterialParams {
                color: Some(Vec3::ONE),
                ..Default::default()
            },
        }],
        ..Default::default()
    };
    World::from_scene(&scene).expect("a valid scene")
}
