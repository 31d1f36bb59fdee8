//! A material's BSDF with what holds over the whole surface worked out once,
//! when the world is built: the lobe weights, the microfacets' α (a square
//! root for a highlight) and glass's two η. A hit adds only its colour and
//! the side the ray came from ([`PreparedBsdf::at`]).

use super::dielectric::SmoothDielectric;
use super::ggx::Ggx;
use super::rough_conductor::RoughConductor;
use super::rough_dielectric::RoughDielectric;
use super::{Bsdf, Layered};
use glam::Vec3;
use scene::{BaseMaterial, Material};

/// What [`Bsdf::new`] makes of a material before the colour at a hit and
/// the side the ray came from are known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PreparedBsdf {
    /// matte, plastic and marble: [`Layered`] without its albedo.
    Layered {
        /// Weight of the Lambertian lobe.
        diffuse: f32,
        /// Weight of the white GGX highlight.
        glossy: f32,
        /// Weight of the mirror.
        mirror: f32,
        /// The highlight's microfacets.
        ggx: Ggx,
    },
    /// mirror and metal: a smooth or rough conductor without its reflectance.
    Conductor {
        /// Whether the reflectance rises toward white at grazing angles (metal).
        schlick: bool,
        /// The microfacets of a rough one; `None` when smooth.
        ggx: Option<Ggx>,
    },
    /// glass: a smooth or rough dielectric without its tint.
    Dielectric {
        /// η met from outside (1 / ior).
        eta_front: f32,
        /// η met from inside (ior).
        eta_back: f32,
        /// The microfacets of a rough one; `None` when smooth.
        ggx: Option<Ggx>,
    },
}

impl PreparedBsdf {
    /// The parts of `material`'s BSDF that do not depend on the hit.
    pub fn new(material: &Material) -> Self {
        // GGX α = roughness²; below the smallest α the surface is smooth.
        let alpha = material.roughness * material.roughness;
        let ggx = (alpha >= Ggx::MIN_ALPHA).then(|| Ggx::new(alpha));
        match material.base {
            BaseMaterial::Matte | BaseMaterial::Plastic | BaseMaterial::Marble => {
                let mirror = material.reflectivity.clamp(0.0, 1.0);
                let specular = material.specular.clamp(0.0, 1.0);
                PreparedBsdf::Layered {
                    diffuse: (1.0 - mirror) * (1.0 - specular),
                    glossy: (1.0 - mirror) * specular,
                    mirror,
                    ggx: Ggx::from_shininess(material.shininess),
                }
            }
            BaseMaterial::Mirror | BaseMaterial::Metal => PreparedBsdf::Conductor {
                schlick: material.base == BaseMaterial::Metal,
                ggx,
            },
            BaseMaterial::Glass => {
                // The ior is inside; an unusable one is air.
                let ior = if material.ior > 0.0 && material.ior.is_finite() {
                    material.ior
                } else {
                    1.0
                };
                PreparedBsdf::Dielectric {
                    eta_front: 1.0 / ior,
                    eta_back: ior,
                    ggx,
                }
            }
        }
    }

    /// The BSDF at a hit whose colour is `color` (the albedo of matte,
    /// plastic and marble, the reflectance of mirror and metal, the tint of
    /// glass; a texture applied), met from outside when `front`.
    #[inline]
    pub fn at(&self, color: Vec3, front: bool) -> Bsdf {
        match *self {
            PreparedBsdf::Layered {
                diffuse,
                glossy,
                mirror,
                ggx,
            } => Bsdf::Layered(Layered {
                albedo: color,
                diffuse,
                glossy,
                mirror,
                ggx,
            }),
            PreparedBsdf::Conductor { schlick, ggx } => match ggx {
                Some(ggx) => Bsdf::RoughConductor(RoughConductor {
                    f0: color,
                    schlick,
                    ggx,
                }),
                None => Bsdf::Conductor { f0: color, schlick },
            },
            PreparedBsdf::Dielectric {
                eta_front,
                eta_back,
                ggx,
            } => {
                let eta = if front { eta_front } else { eta_back };
                match ggx {
                    Some(ggx) => Bsdf::RoughDielectric(RoughDielectric {
                        eta,
                        tint: color,
                        ggx,
                    }),
                    None => Bsdf::Dielectric(SmoothDielectric { eta, tint: color }),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scene::materials::builtin;

    #[test]
    fn glass_meets_its_ior_from_outside_and_air_from_inside() {
        let glass = Material {
            ior: 1.5,
            ..builtin(BaseMaterial::Glass)
        };
        let eta = |front| match PreparedBsdf::new(&glass).at(Vec3::ONE, front) {
            Bsdf::Dielectric(d) => d.eta,
            other => panic!("{other:?}"),
        };
        assert_eq!((eta(true), eta(false)), (1.0 / 1.5, 1.5));
    }

    #[test]
    fn an_unusable_ior_is_air() {
        for ior in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            let glass = Material {
                ior,
                roughness: 0.5,
                ..builtin(BaseMaterial::Glass)
            };
            for front in [true, false] {
                match PreparedBsdf::new(&glass).at(Vec3::ONE, front) {
                    Bsdf::RoughDielectric(d) => assert_eq!(d.eta, 1.0, "ior {ior}"),
                    other => panic!("{other:?}"),
                }
            }
        }
    }

    #[test]
    fn the_colour_at_the_hit_is_albedo_reflectance_or_tint() {
        let color = Vec3::new(0.1, 0.2, 0.3);
        for base in BaseMaterial::ALL {
            for roughness in [0.0, 0.5] {
                let material = Material {
                    roughness,
                    ..builtin(base)
                };
                let got = match PreparedBsdf::new(&material).at(color, true) {
                    Bsdf::Layered(l) => l.albedo,
                    Bsdf::Conductor { f0, .. } => f0,
                    Bsdf::RoughConductor(c) => c.f0,
                    Bsdf::Dielectric(d) => d.tint,
                    Bsdf::RoughDielectric(d) => d.tint,
                };
                assert_eq!(got, color, "{base:?} roughness {roughness}");
            }
        }
    }

    #[test]
    fn a_highlight_and_roughness_are_prepared_once() {
        let plastic = builtin(BaseMaterial::Plastic);
        let Bsdf::Layered(l) = PreparedBsdf::new(&plastic).at(Vec3::ONE, true) else {
            panic!("plastic is layered");
        };
        assert_eq!(l.ggx, Ggx::from_shininess(plastic.shininess));
        assert!((l.diffuse + l.glossy + l.mirror - 1.0).abs() < 1e-6);
        let metal = Material {
            roughness: 0.5,
            ..builtin(BaseMaterial::Metal)
        };
        let prepared = PreparedBsdf::new(&metal);
        assert_eq!(
            prepared,
            PreparedBsdf::Conductor {
                schlick: true,
                ggx: Some(Ggx::new(0.25))
            }
        );
    }
}
