//! Physical lights, as in pbrt and Mitsuba: a point light's intensity × colour
//! is radiant intensity (W/sr), a directional light's is irradiance (W/m²),
//! an ambient light's is radiance arriving uniformly from every direction.

use glam::Vec3;
use scene::LightKind;

/// A light ready for shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// An isotropic point light.
    Point {
        /// Its position.
        position: Vec3,
        /// Radiant intensity I (W/sr) per channel.
        intensity: Vec3,
    },
    /// A light at infinity.
    Directional {
        /// Unit vector from the surface toward the light.
        to_light: Vec3,
        /// Irradiance E on a surface facing the light (W/m²).
        irradiance: Vec3,
    },
    /// Uniform, unshadowed radiance from every direction (also the background).
    Ambient {
        /// Radiance L_a.
        radiance: Vec3,
    },
}

/// What a light delivers at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit vector from the point toward the light.
    pub to_light: Vec3,
    /// Distance to the light (∞ for directional lights): the shadow ray's t_max.
    pub distance: f32,
    /// Irradiance on a surface facing the light: I / r² or E.
    pub irradiance: Vec3,
}

impl Light {
    /// The light for a scene light.
    pub fn from_scene(light: &scene::Light) -> Light {
        let power = light.color * light.intensity;
        match light.kind {
            LightKind::Point { position } => Light::Point {
                position,
                intensity: power,
            },
            LightKind::Directional { direction } => Light::Directional {
                to_light: -direction.normalize_or(Vec3::NEG_Y),
                irradiance: power,
            },
            LightKind::Ambient => Light::Ambient { radiance: power },
        }
    }

    /// Direction, distance and irradiance at `point`; `None` for ambient light
    /// (and at a point light's own position).
    pub fn sample(&self, point: Vec3) -> Option<LightSample> {
        match *self {
            Light::Point {
                position,
                intensity,
            } => {
                let to = position - point;
                let distance_sq = to.length_squared();
                (distance_sq > 0.0).then(|| {
                    let distance = distance_sq.sqrt();
                    LightSample {
                        to_light: to / distance,
                        distance,
                        irradiance: intensity / distance_sq,
                    }
                })
            }
            Light::Directional {
                to_light,
                irradiance,
            } => Some(LightSample {
                to_light,
                distance: f32::INFINITY,
                irradiance,
            }),
            Light::Ambient { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_light_irradiance_falls_off_with_the_square_of_distance() {
        let light = Light::Point {
            position: Vec3::new(0.0, 4.0, 0.0),
            intensity: Vec3::splat(32.0),
        };
        let s = light.sample(Vec3::ZERO).expect("sample");
        assert_eq!(s.irradiance, Vec3::splat(2.0));
        assert_eq!(s.distance, 4.0);
        assert_eq!(s.to_light, Vec3::Y);
    }
}
