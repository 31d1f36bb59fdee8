//! KHR_lights_punctual → raylab lights.
//!
//! Units: glTF gives point and spot intensity in candela (lm/sr) and
//! directional intensity in lux (lm/m²); raylab's `intensity × color` is
//! radiant intensity (W/sr) for a point light and irradiance (W/m²) for a
//! directional one. raylab renders in relative units with no luminous
//! efficacy, so the numbers are taken over unchanged (1 cd → 1 W/sr,
//! 1 lx → 1 W/m²): the same geometry, falloff and colour, and a glTF scene lit
//! for a physically based viewer keeps its relative light balance. (Such a
//! scene may be lit for an exposure, e.g. a 100 000 lx sun, and then renders
//! far brighter than raylab's own defaults of 60 W/sr and 2 W/m².)
//!
//! Point lights sit at the node's origin; directional lights shine along the
//! node's −z. Spot lights become point lights (their cone is ignored, with a
//! warning), and `range` is ignored (raylab's point lights fall off as 1/d²
//! without a cut-off).

use super::warnings::Warnings;
use crate::model::{Light, LightKind};
use ::gltf::khr_lights_punctual::Kind;
use glam::{Mat4, Vec3};

/// The light `light` on a node with world transform `world`, or `None`
/// (reported) when its transform gives it no direction.
pub(super) fn light(
    light: &::gltf::khr_lights_punctual::Light,
    node_name: &str,
    world: &Mat4,
    warnings: &mut Warnings,
) -> Option<Light> {
    let name = light.name().unwrap_or(node_name).to_owned();
    let position = world.transform_point3(Vec3::ZERO);
    let kind = match light.kind() {
        Kind::Point => LightKind::Point { position },
        Kind::Spot { .. } => {
            warnings.once("spot lights", || {
                format!("spot lights are not supported: \"{name}\" (and any other spot light) becomes a point light at the same place; its cone is ignored")
            });
            LightKind::Point { position }
        }
        Kind::Directional => {
            let Some(direction) = world.transform_vector3(Vec3::NEG_Z).try_normalize() else {
                warnings.once("degenerate lights", || {
                    format!("directional light \"{name}\" has a degenerate node transform and is skipped")
                });
                return None;
            };
            LightKind::Directional { direction }
        }
    };
    if light.range().is_some() {
        warnings.once("light range", || {
            "light range is not supported: point lights fall off as 1/d² without a cut-off".into()
        });
    }
    Some(Light {
        name: Some(name),
        kind,
        color: Vec3::from_array(light.color()).max(Vec3::ZERO),
        intensity: light.intensity().max(0.0),
    })
}
