//! Filling in every default: materials, placement, camera framing, lighting.

use crate::InvalidScene;
use crate::layout::{self, Aabb};
use crate::materials;
use crate::model::{Light, LightKind, Scene, Shape, Sky};
use crate::resolved::{Geometry, ResolvedCamera, ResolvedObject, ResolvedScene};
use glam::Vec3;

/// The scene with every default decided:
/// - objects without a position rest on the floor side by side ([`layout::place`]);
/// - no eye or toward → a camera that frames all finite objects from the front, slightly above;
/// - no light, nothing emissive and no sky → a key light plus soft ambient light;
/// - no sky → a black background (`sky` zero).
pub fn resolve(scene: &Scene) -> Result<ResolvedScene, InvalidScene> {
    let floor_y = scene
        .objects
        .iter()
        .find_map(|o| match o.shape {
            Shape::Floor { y } => Some(y),
            _ => None,
        })
        .unwrap_or(0.0);
    let shapes: Vec<&Shape> = scene.objects.iter().map(|o| &o.shape).collect();
    let geometries = layout::place(&shapes, floor_y);

    let mut objects = Vec::with_capacity(scene.objects.len());
    for (index, (object, geometry)) in scene.objects.iter().zip(geometries).enumerate() {
        let base = materials::named(&scene.materials, object.material.as_deref())
            .map_err(|e| InvalidScene(format!("{} {}: {}", object.shape.tag(), index + 1, e.0)))?;
        let mut geometry = geometry;
        if let Geometry::Mesh { file_materials, .. } = &mut geometry {
            // A <mesh> that names a material or sets a parameter is painted
            // with it; otherwise the file's own materials show.
            *file_materials = object.material.is_none() && object.params.is_empty();
        }
        objects.push(ResolvedObject {
            name: object
                .name
                .clone()
                .unwrap_or_else(|| format!("{} {}", object.shape.tag(), index + 1)),
            geometry,
            material: materials::apply(base, &object.params),
        });
    }

    let finite = objects
        .iter()
        .filter_map(|o| layout::bounds(&o.geometry))
        .fold(Aabb::EMPTY, Aabb::union);
    let focus = if finite.is_empty() {
        Aabb {
            min: Vec3::new(-1.0, floor_y, -1.0),
            max: Vec3::new(1.0, floor_y + 2.0, 1.0),
        }
    } else {
        finite
    };

    let camera = frame_camera(scene, &focus);
    let emissive = objects
        .iter()
        .any(|o| o.material.emission.max_element() > 0.0);
    let lights = if scene.lights.is_empty() && !emissive && scene.sky.is_none() {
        default_lights(&focus)
    } else {
        scene.lights.clone()
    };
    Ok(ResolvedScene {
        camera,
        lights,
        sky: scene.sky.clone().unwrap_or_else(Sky::black),
        objects,
    })
}

/// The scene's camera with P0 and t decided: a missing t looks at the focus
/// box's centre; a missing P0 backs away along t until the box fits.
fn frame_camera(scene: &Scene, focus: &Aabb) -> ResolvedCamera {
    let cam = &scene.camera;
    let center = focus.center();
    let aspect = cam.width as f32 / cam.height as f32;
    let (eye, toward) = match (cam.eye, cam.toward) {
        (Some(eye), Some(toward)) => (eye, toward),
        (Some(eye), None) => {
            let toward = center - eye;
            (
                eye,
                if toward.length() > 0.0 {
                    toward
                } else {
                    layout::DEFAULT_TOWARD
                },
            )
        }
        (None, toward) => {
            let toward = toward.unwrap_or(layout::DEFAULT_TOWARD);
            let t = toward.normalize_or(Vec3::NEG_Z);
            let distance = layout::framing_distance(focus, t, cam.up, cam.theta_deg, aspect);
            (center - distance * t, toward)
        }
    };
    ResolvedCamera {
        eye,
        toward,
        up: cam.up,
        theta_deg: cam.theta_deg,
        d: cam.d,
        width: cam.width,
        height: cam.height,
    }
}

/// Irradiance the default key light delivers at the scene's centre (W/m²).
const KEY_IRRADIANCE: f32 = 3.0;
/// Radiance of the default ambient light.
const AMBIENT_RADIANCE: f32 = 0.08;

/// A key light up, left and in front of the scene, plus soft ambient light.
fn default_lights(focus: &Aabb) -> Vec<Light> {
    let distance = 2.5 * focus.radius().max(1.0);
    let position = focus.center() + distance * Vec3::new(-0.6, 1.0, 0.8).normalize();
    vec![
        Light {
            name: Some("key light".into()),
            kind: LightKind::Point { position },
            color: Vec3::ONE,
            intensity: KEY_IRRADIANCE * distance * distance,
        },
        Light {
            name: Some("ambient light".into()),
            kind: LightKind::Ambient,
            color: Vec3::ONE,
            intensity: AMBIENT_RADIANCE,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Object, Shape};

    fn object(tag: &str) -> Object {
        Object {
            name: None,
            shape: Shape::default_for_tag(tag).expect("tag"),
            material: None,
            params: Default::default(),
        }
    }

    #[test]
    fn empty_scene_gets_a_camera_and_default_lights() {
        let r = resolve(&Scene::default()).expect("resolves");
        assert_eq!(r.lights.len(), 2);
        assert!(r.camera.toward.z < 0.0 && r.camera.eye.z > 0.0);
    }

    #[test]
    fn default_camera_frames_every_corner_of_every_object() {
        let scene = Scene {
            objects: vec![
                object("cone"),
                object("sphere"),
                object("box"),
                object("floor"),
            ],
            ..Default::default()
        };
        let r = resolve(&scene).expect("resolves");
        let cam = r.camera;
        let t = cam.toward.normalize();
        let u = (cam.up - cam.up.dot(t) * t).normalize();
        let right = t.cross(u);
        let tan_v = cam.theta_deg.to_radians().tan();
        let tan_h = tan_v * cam.width as f32 / cam.height as f32;
        for o in &r.objects {
            let Some(b) = layout::bounds(&o.geometry) else {
                continue;
            };
            for k in 0..8 {
                let corner = Vec3::new(
                    if k & 1 == 0 { b.min.x } else { b.max.x },
                    if k & 2 == 0 { b.min.y } else { b.max.y },
                    if k & 4 == 0 { b.min.z } else { b.max.z },
                ) - cam.eye;
                let depth = corner.dot(t);
                assert!(depth > 0.0, "{} is in front of the camera", o.name);
                assert!(
                    corner.dot(right).abs() <= depth * tan_h,
                    "{} fits horizontally",
                    o.name
                );
                assert!(
                    corner.dot(u).abs() <= depth * tan_v,
                    "{} fits vertically",
                    o.name
                );
            }
        }
    }

    #[test]
    fn emissive_objects_switch_default_lights_off() {
        let mut lamp = object("sphere");
        lamp.params.emission = Some(Vec3::ONE);
        let r = resolve(&Scene {
            objects: vec![lamp],
            ..Default::default()
        })
        .expect("resolves");
        assert!(r.lights.is_empty());
    }

    #[test]
    fn a_sky_switches_default_lights_off() {
        let sky = Vec3::new(0.5, 0.7, 1.0);
        let r = resolve(&Scene {
            sky: Some(Sky::constant(sky)),
            objects: vec![object("sphere")],
            ..Default::default()
        })
        .expect("resolves");
        assert!(r.lights.is_empty());
        assert_eq!(r.sky, Sky::constant(sky));
    }

    #[test]
    fn no_sky_resolves_to_a_black_background() {
        let r = resolve(&Scene::default()).expect("resolves");
        assert_eq!(r.sky, Sky::black());
    }
}
