//! Perspective cameras → [`ModelCamera`] in the lecture's terms: P0 = the
//! node's origin, t = the node's −z, u = the node's +y, θ = yfov / 2.
//! Orthographic cameras have no counterpart in raylab and are skipped.

use super::warnings::Warnings;
use crate::model::model_file::ModelCamera;
use ::gltf::json::camera::Type;
use ::gltf::json::validation::Checked;
use glam::{Mat4, Vec3};

/// The camera `camera` (its JSON, read directly: the `gltf` crate panics
/// when `type` names a projection object the camera lacks) on a node with
/// world transform `world`, or `None` (reported) when raylab cannot use it.
pub(super) fn camera(
    index: usize,
    camera: &::gltf::json::Camera,
    node_name: &str,
    world: &Mat4,
    warnings: &mut Warnings,
) -> Result<Option<ModelCamera>, String> {
    let name = camera.name.as_deref().unwrap_or(node_name).to_owned();
    let perspective = match (camera.type_, &camera.perspective) {
        (Checked::Valid(Type::Perspective), Some(p)) => p,
        (Checked::Valid(Type::Orthographic), _) => {
            warnings.once("orthographic cameras", || {
                format!("orthographic cameras are not supported: raylab's camera is perspective, so \"{name}\" (and any other orthographic camera) is skipped")
            });
            return Ok(None);
        }
        _ => {
            return Err(format!(
                "camera {index}: its type is perspective but it has no \"perspective\" object"
            ));
        }
    };
    let yfov = perspective.yfov;
    let eye = world.transform_point3(Vec3::ZERO);
    let toward = world.transform_vector3(Vec3::NEG_Z).try_normalize();
    let up = world.transform_vector3(Vec3::Y).try_normalize();
    let usable = yfov > 0.0 && yfov < std::f32::consts::PI && eye.is_finite();
    let (Some(toward), Some(up), true) = (toward, up, usable) else {
        warnings.once("degenerate cameras", || {
            format!("camera \"{name}\" has a field of view outside (0, π) or a degenerate node transform and is skipped")
        });
        return Ok(None);
    };
    Ok(Some(ModelCamera {
        name,
        eye,
        toward,
        up,
        theta_deg: (yfov / 2.0).to_degrees(),
        aspect: perspective.aspect_ratio.filter(|a| *a > 0.0),
    }))
}
