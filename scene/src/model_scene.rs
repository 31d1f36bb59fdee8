//! Opening a model file (glTF) on its own: a scene with the model at the
//! origin, the file's first camera and its lights.

use crate::SceneError;
use crate::gltf::load_model;
use crate::model::{
    Camera, Light, LightKind, MeshSource, Object, STUDIO_KEY_DIRECTION, Scene, Shape, Sky,
};
use glam::Vec3;
use std::path::Path;
use std::sync::Arc;

/// True for paths raylab opens as a model file rather than a scene file
/// (`.gltf`, `.glb`, any letter case).
pub fn is_model_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Reads a scene file, or makes a scene around a model file ([`is_model_path`]).
pub fn read_any(path: &Path) -> Result<Scene, SceneError> {
    if is_model_path(path) {
        read_model_scene(path)
    } else {
        crate::read_file(path)
    }
}

/// The irradiance (W/m²) of the studio's key light.
const STUDIO_KEY_IRRADIANCE: f32 = 1.5;

/// The scene for a model file: one `<mesh>` at the origin (unscaled,
/// unrotated), viewed through the file's first perspective camera (P0, t, u,
/// θ = yfov / 2; the image keeps raylab's default height and takes the
/// file's aspect ratio) and lit by the file's lights. A file without a
/// camera is framed, and one that brings no light (no punctual light, no
/// emissive material) is lit by raylab's studio environment
/// ([`Sky::studio`]) and a key light from its softbox.
pub fn read_model_scene(path: &Path) -> Result<Scene, SceneError> {
    let model = load_model(path).map_err(|e| SceneError {
        file: path.display().to_string(),
        line: 1,
        column: 1,
        message: e.message,
    })?;
    let mut camera = Camera::default();
    if let Some(c) = model.cameras.first() {
        camera.eye = Some(c.eye);
        camera.toward = Some(c.toward);
        camera.up = c.up;
        camera.theta_deg = c.theta_deg;
        if let Some(aspect) = c.aspect.filter(|a| a.is_finite() && *a > 0.0) {
            let width = (camera.height as f32 * aspect).round();
            camera.width = (width as u32).clamp(1, Camera::MAX_SIZE);
        }
    }
    let src = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let name = path.file_stem().map(|n| n.to_string_lossy().into_owned());
    // A model that brings no light of its own is shown as glTF viewers show
    // it: in a studio environment, with a key light from its softbox (which
    // gives Whitted, whose sky is only a background and an ambient term,
    // shading and shadows).
    let unlit = model.lights.is_empty()
        && model
            .materials
            .iter()
            .all(|m| m.material.emission == Vec3::ZERO);
    let (lights, sky) = if unlit {
        let key = Light {
            name: Some("studio key light".into()),
            kind: LightKind::Directional {
                direction: -STUDIO_KEY_DIRECTION,
            },
            color: Vec3::ONE,
            intensity: STUDIO_KEY_IRRADIANCE,
        };
        (vec![key], Some(Sky::studio()))
    } else {
        (model.lights.clone(), None)
    };
    Ok(Scene {
        camera,
        lights,
        sky,
        materials: Vec::new(),
        objects: vec![Object {
            name,
            shape: Shape::Mesh {
                source: MeshSource {
                    src,
                    model: Arc::new(model),
                },
                translate: Some(Vec3::ZERO),
                rotate: Vec3::ZERO,
                scale: Vec3::ONE,
            },
            material: None,
            params: Default::default(),
        }],
        view: Default::default(),
    })
}

impl Scene {
    /// Every model file the scene uses, once each, with what it reported as
    /// unsupported (for printing once after loading).
    pub fn model_warnings(&self) -> Vec<(String, Vec<String>)> {
        let mut seen: Vec<(String, Vec<String>)> = Vec::new();
        for object in &self.objects {
            if let Shape::Mesh { source, .. } = &object.shape
                && !source.model.warnings.is_empty()
                && !seen.iter().any(|(src, _)| *src == source.src)
            {
                seen.push((source.src.clone(), source.model.warnings.clone()));
            }
        }
        seen
    }
}
