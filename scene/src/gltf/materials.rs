//! glTF materials → raylab's built-in materials.
//!
//! raylab shades with a few fixed models (Lambert, a GGX or Blinn-Phong
//! highlight, rough or smooth conductors, rough or smooth glass), so a glTF
//! metallic-roughness material becomes the closest of them. Rules are tried
//! top to bottom; every colour is taken as glTF stores it (linear RGB; alpha
//! is ignored).
//!
//! | glTF material | raylab material | parameters |
//! |---|---|---|
//! | `KHR_materials_transmission` factor > 0 | Glass | `color` = baseColorFactor (tint); `ior` = `KHR_materials_ior` (1.5 when absent or outside 1 to 10); `roughness` = roughnessFactor (a GGX rough dielectric, α = roughness², in the path tracer) |
//! | metallicFactor ≥ 0.5 | Metal (Schlick Fresnel from the base colour toward white, glTF's own metal BRDF) | `color` = baseColorFactor; `roughness` = roughnessFactor (a GGX rough conductor, α = roughness², in the path tracer) |
//! | roughnessFactor > 0.75 (a dielectric) | Matte (Lambert) | `color` = baseColorFactor. So rough a surface shows no mirror image and no sharp highlight. |
//! | otherwise (a dielectric) | Plastic (Lambert + Blinn-Phong) | `color` = baseColorFactor; `shininess` = 2/α² − 2 with α = roughness², clamped to [1, 10000] (the Blinn-Phong exponent whose lobe matches a microfacet distribution of that roughness: roughness 0.75 gives 4.3, 0.5 gives 30, 0.2 gives 1248; the path tracer turns it back into that GGX α); `specular` = 0.04, a glTF dielectric's reflectance F0 (the renderer normalises the lobe by (n + 8)/8π, so its width and peak already follow roughness while its energy stays F0); `reflectivity` = 0.04 when roughness < 0.1 (a mirror-smooth dielectric reflects its surroundings at F0), else 0 |
//! | every material | | `emission` = emissiveFactor × `KHR_materials_emissive_strength` (1 when absent), as radiance; 0 when the material has an emissiveTexture (not supported, and the factor alone would make the whole surface glow) |
//! | a primitive without material | Matte, light grey 0.8 | glTF's default is white, metallic 1, roughness 1, which the rows above make a white matte of albedo 1: a perfect reflector that blows out under raylab's lights. Raylab's own default matte (0.8) keeps the neutral clay look such files are meant to have. |
//!
//! The base-colour texture (TEXCOORD_0) multiplies `color`. Ignored and
//! reported once each: metallic-roughness, normal, occlusion and emissive
//! textures, textures on other texture-coordinate sets, and alpha modes
//! (MASK, BLEND: surfaces are drawn opaque).

use super::warnings::Warnings;
use crate::materials::builtin;
use crate::model::BaseMaterial;
use crate::model::Material;
use glam::Vec3;

/// Roughness above which a dielectric is matte.
pub(super) const MATTE_ROUGHNESS: f32 = 0.75;
/// Metallic factor from which a material is metal.
pub(super) const METAL_METALLIC: f32 = 0.5;
/// Reflectance at normal incidence of glTF's dielectrics.
pub(super) const DIELECTRIC_F0: f32 = 0.04;
/// Dielectric roughness below which the surface is mirror-smooth.
pub(super) const SMOOTH_ROUGHNESS: f32 = 0.1;

/// The glTF material parameters the mapping reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Pbr {
    /// baseColorFactor (RGB, linear).
    pub base_color: Vec3,
    /// metallicFactor.
    pub metallic: f32,
    /// roughnessFactor.
    pub roughness: f32,
    /// KHR_materials_transmission's transmissionFactor (0 without it).
    pub transmission: f32,
    /// KHR_materials_ior's ior, if given.
    pub ior: Option<f32>,
    /// emissiveFactor (RGB, linear).
    pub emissive: Vec3,
    /// KHR_materials_emissive_strength (1 without it).
    pub emissive_strength: f32,
    /// Whether an emissiveTexture is given.
    pub emissive_texture: bool,
}

impl Pbr {
    /// The parameters of a glTF material, defaults filled in.
    pub(super) fn of(material: &::gltf::Material) -> Self {
        let pbr = material.pbr_metallic_roughness();
        let [r, g, b, _alpha] = pbr.base_color_factor();
        Self {
            base_color: Vec3::new(r, g, b),
            metallic: pbr.metallic_factor(),
            roughness: pbr.roughness_factor(),
            transmission: material
                .transmission()
                .map_or(0.0, |t| t.transmission_factor()),
            ior: material.ior(),
            emissive: Vec3::from_array(material.emissive_factor()),
            emissive_strength: material.emissive_strength().unwrap_or(1.0),
            emissive_texture: material.emissive_texture().is_some(),
        }
    }
}

/// The raylab material for `p`, by the table in this module's documentation.
pub(super) fn map(p: &Pbr) -> Material {
    let color = p.base_color.clamp(Vec3::ZERO, Vec3::splat(f32::MAX));
    let roughness = p.roughness.clamp(0.0, 1.0);
    let mut material = if p.transmission > 0.0 {
        Material {
            color,
            ior: p
                .ior
                .filter(|ior| (1.0..=10.0).contains(ior))
                .unwrap_or(1.5),
            roughness,
            ..builtin(BaseMaterial::Glass)
        }
    } else if p.metallic >= METAL_METALLIC {
        Material {
            color,
            roughness,
            ..builtin(BaseMaterial::Metal)
        }
    } else if roughness > MATTE_ROUGHNESS {
        Material {
            color,
            ..builtin(BaseMaterial::Matte)
        }
    } else {
        Material {
            color,
            shininess: blinn_phong_exponent(roughness),
            specular: DIELECTRIC_F0,
            reflectivity: if roughness < SMOOTH_ROUGHNESS {
                DIELECTRIC_F0
            } else {
                0.0
            },
            ..builtin(BaseMaterial::Plastic)
        }
    };
    if !p.emissive_texture {
        material.emission = (p.emissive * p.emissive_strength.max(0.0)).max(Vec3::ZERO);
    }
    material
}

/// The Blinn-Phong exponent 2/α² − 2 for α = roughness², clamped to [1, 10000].
pub(super) fn blinn_phong_exponent(roughness: f32) -> f32 {
    let alpha = roughness * roughness;
    let exponent = 2.0 / (alpha * alpha).max(1e-12) - 2.0;
    exponent.clamp(1.0, 10_000.0)
}

/// The material of primitives that have none (see the table above).
pub(super) fn default_material() -> Material {
    builtin(BaseMaterial::Matte)
}

/// Reports the parts of `material` the mapping ignores.
pub(super) fn warn_ignored(material: &::gltf::Material, warnings: &mut Warnings) {
    let pbr = material.pbr_metallic_roughness();
    if pbr.metallic_roughness_texture().is_some() {
        warnings.once("metallicRoughnessTexture", || {
            "metallic-roughness textures are not supported: the metallic and roughness factors alone choose the material".into()
        });
    }
    if material.normal_texture().is_some() {
        warnings.once("normalTexture", || {
            "normal maps are not supported: surfaces are shaded with the interpolated vertex normals".into()
        });
    }
    if material.occlusion_texture().is_some() {
        warnings.once("occlusionTexture", || {
            "occlusion textures are not supported and are ignored".into()
        });
    }
    if material.emissive_texture().is_some() {
        warnings.once("emissiveTexture", || {
            "emissive textures are not supported: materials with one do not emit light".into()
        });
    }
    if pbr.base_color_texture().is_some_and(|t| t.tex_coord() != 0) {
        warnings.once("TEXCOORD_n", || {
            "base-colour textures on texture-coordinate sets other than TEXCOORD_0 are not supported: those materials use their base colour factor alone".into()
        });
    }
    if material.alpha_mode() != ::gltf::material::AlphaMode::Opaque {
        warnings.once("alphaMode", || {
            "transparency by alpha (alphaMode MASK or BLEND) is not supported: surfaces are drawn opaque".into()
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pbr(metallic: f32, roughness: f32) -> Pbr {
        Pbr {
            base_color: Vec3::new(0.8, 0.1, 0.2),
            metallic,
            roughness,
            transmission: 0.0,
            ior: None,
            emissive: Vec3::ZERO,
            emissive_strength: 1.0,
            emissive_texture: false,
        }
    }

    #[test]
    fn exponent_follows_roughness() {
        // α = r², n = 2/α² − 2.
        assert!((blinn_phong_exponent(0.5) - 30.0).abs() < 1e-3);
        assert!((blinn_phong_exponent(0.75) - 4.3210).abs() < 1e-3);
        assert_eq!(blinn_phong_exponent(0.0), 10_000.0, "clamped above");
        assert_eq!(blinn_phong_exponent(1.0), 1.0, "clamped below");
    }

    #[test]
    fn metallic_at_least_half_is_metal_with_the_base_colour() {
        let m = map(&pbr(0.5, 0.3));
        assert_eq!(m.base, BaseMaterial::Metal);
        assert_eq!(m.color, Vec3::new(0.8, 0.1, 0.2));
        assert_eq!(m.reflectivity, 1.0);
        assert_eq!(map(&pbr(0.49, 0.3)).base, BaseMaterial::Plastic);
    }

    #[test]
    fn metals_keep_their_roughness_at_every_value() {
        // Up to glTF's defaults (metallic 1, roughness 1), as COLLADA2GLTF writes them.
        for roughness in [0.0, 0.3, 0.75, 1.0] {
            let m = map(&pbr(1.0, roughness));
            assert_eq!(m.base, BaseMaterial::Metal);
            assert_eq!(m.roughness, roughness);
            assert_eq!(m.color, Vec3::new(0.8, 0.1, 0.2));
        }
        assert_eq!(map(&pbr(1.0, 1.7)).roughness, 1.0, "clamped to [0, 1]");
    }

    #[test]
    fn dielectrics_are_plastic_until_very_rough() {
        let m = map(&pbr(0.0, 0.5));
        assert_eq!(m.base, BaseMaterial::Plastic);
        assert!((m.shininess - 30.0).abs() < 1e-3);
        assert_eq!(m.specular, DIELECTRIC_F0);
        assert_eq!(m.reflectivity, 0.0);
        let smooth = map(&pbr(0.0, 0.05));
        assert_eq!(smooth.reflectivity, DIELECTRIC_F0);
        assert_eq!(smooth.shininess, 10_000.0);
        let rough = map(&pbr(0.0, 0.8));
        assert_eq!(rough.base, BaseMaterial::Matte);
        assert_eq!(rough.color, Vec3::new(0.8, 0.1, 0.2));
        assert_eq!(rough.specular, 0.0);
    }

    #[test]
    fn transmission_is_glass_with_the_given_ior() {
        let glass = Pbr {
            transmission: 1.0,
            ior: Some(1.33),
            ..pbr(0.0, 0.0)
        };
        let m = map(&glass);
        assert_eq!(m.base, BaseMaterial::Glass);
        assert_eq!(m.ior, 1.33);
        assert_eq!(m.roughness, 0.0);
        assert_eq!(
            map(&Pbr {
                roughness: 0.4,
                ..glass
            })
            .roughness,
            0.4
        );
        assert_eq!(m.color, Vec3::new(0.8, 0.1, 0.2));
        assert_eq!(map(&Pbr { ior: None, ..glass }).ior, 1.5);
        assert_eq!(
            map(&Pbr {
                ior: Some(0.0),
                ..glass
            })
            .ior,
            1.5
        );
    }

    #[test]
    fn emission_is_factor_times_strength_unless_textured() {
        let glow = Pbr {
            emissive: Vec3::new(1.0, 0.5, 0.0),
            emissive_strength: 4.0,
            ..pbr(0.0, 1.0)
        };
        assert_eq!(map(&glow).emission, Vec3::new(4.0, 2.0, 0.0));
        assert_eq!(
            map(&Pbr {
                emissive_texture: true,
                ..glow
            })
            .emission,
            Vec3::ZERO
        );
    }

    #[test]
    fn the_default_material_is_light_grey_matte() {
        let m = default_material();
        assert_eq!(m.base, BaseMaterial::Matte);
        assert_eq!(m.color, Vec3::splat(0.8));
    }
}
