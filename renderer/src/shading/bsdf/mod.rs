//! BSDFs of the path tracer: every built-in material as a physically based
//! scattering function that conserves energy, with importance sampling.
//! Mirror, metal and glass with `roughness` > 0 become GGX microfacet
//! surfaces (α = roughness²), as Mitsuba 3's `roughconductor` and
//! `roughdielectric`.
//!
//! Directions are local to the shading frame turned to the side the ray came
//! from (see [`ShadingFrame`]): `wo` (toward the previous vertex) always has
//! z > 0. `eval` returns f · |cos θ_i| of the non-delta parts, `pdf` their
//! density in solid angle, and `sample` draws wi from the whole BSDF.

pub mod dielectric;
pub mod ggx;
pub mod lambert;
pub mod prepared;
pub mod rough_conductor;
pub mod rough_dielectric;
pub mod shading_frame;

pub use prepared::PreparedBsdf;
pub use shading_frame::ShadingFrame;

use crate::shading::optics::fresnel_schlick;
use ggx::Ggx;
use glam::{Vec2, Vec3};
use lambert::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use rough_conductor::RoughConductor;
use rough_dielectric::RoughDielectric;
use scene::Material;
use std::f32::consts::FRAC_1_PI;

/// A scattering function at one shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf {
    /// matte, plastic and marble: a Lambertian base, a white GGX highlight
    /// and a mirror, mixed by weights that sum to one.
    Layered(Layered),
    /// mirror (reflectance = colour) and metal (Schlick's Fresnel from the
    /// colour toward white): a smooth conductor, a delta reflection.
    Conductor {
        /// Reflectance at normal incidence.
        f0: Vec3,
        /// Whether the reflectance rises toward white at grazing angles (metal).
        schlick: bool,
    },
    /// glass: a smooth dielectric, reflecting or refracting by Fresnel.
    Dielectric(dielectric::SmoothDielectric),
    /// mirror and metal with roughness: a GGX microfacet conductor.
    RoughConductor(RoughConductor),
    /// glass with roughness: a GGX microfacet dielectric that reflects and
    /// refracts.
    RoughDielectric(RoughDielectric),
}

/// The mixture of [`Bsdf::Layered`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layered {
    /// The Lambertian lobe's albedo.
    pub albedo: Vec3,
    /// Weight of the Lambertian lobe.
    pub diffuse: f32,
    /// Weight of the white GGX highlight.
    pub glossy: f32,
    /// Weight of the mirror.
    pub mirror: f32,
    /// The highlight's microfacets.
    pub ggx: Ggx,
}

/// One direction drawn by [`Bsdf::sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction toward the next vertex (local).
    pub wi: Vec3,
    /// f · |cos θ_i| / pdf: what the path throughput is multiplied by.
    pub weight: Vec3,
    /// The density of the non-delta parts at wi (0 for a delta lobe).
    pub pdf: f32,
    /// The lobe wi was drawn from; [`Lobe::Specular`] is a delta lobe
    /// (mirror or smooth glass): no light sample could have found wi, so
    /// emission it hits counts in full.
    pub lobe: Lobe,
    /// The factor η² by which refraction scaled `weight` (radiance is
    /// compressed into a smaller solid angle); 1 for reflection.
    pub radiance_scale: f32,
}

/// Which part of a BSDF a sampled direction came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Lobe {
    /// The Lambertian base (cosine-weighted hemisphere).
    Diffuse,
    /// A GGX microfacet lobe: a highlight, rough metal or rough glass.
    Glossy,
    /// A delta lobe: mirror reflection or smooth refraction.
    Specular,
}

/// A conductor's reflectance where light meets it at `cos` to the normal:
/// Schlick's rise toward white at grazing angles (metal), or `f0` at every
/// angle (mirror).
pub(crate) fn conductor_reflectance(f0: Vec3, schlick: bool, cos: f32) -> Vec3 {
    if schlick {
        fresnel_schlick(cos, f0)
    } else {
        f0
    }
}

impl BsdfSample {
    /// wi drawn through the non-delta lobe `lobe` with density `pdf` (of
    /// all non-delta lobes together), where the BSDF gives f · |cos θ_i| =
    /// `f_cos`; `None` when the density is zero.
    pub fn scattered(
        lobe: Lobe,
        wi: Vec3,
        f_cos: Vec3,
        pdf: f32,
        radiance_scale: f32,
    ) -> Option<Self> {
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            weight: f_cos / pdf,
            pdf,
            lobe,
            radiance_scale,
        })
    }

    /// Whether wi came from a delta lobe (mirror or smooth glass).
    pub fn is_delta(&self) -> bool {
        self.lobe == Lobe::Specular
    }
}

impl Bsdf {
    /// The BSDF of `material` where its colour is `color` (the albedo of
    /// matte, plastic and marble — marble's texture at the point —, the
    /// reflectance of mirror and metal, the tint of glass); `front` tells
    /// whether the ray arrived on the outer side (glass: whether it enters).
    /// A renderer prepares each material once ([`PreparedBsdf`]) instead.
    pub fn new(material: &Material, color: Vec3, front: bool) -> Bsdf {
        PreparedBsdf::new(material).at(color, front)
    }

    /// Whether any part is not a delta lobe, so that sampling a light helps.
    pub fn has_smooth(&self) -> bool {
        match self {
            Bsdf::Layered(l) => l.diffuse + l.glossy > 0.0,
            Bsdf::Conductor { .. } | Bsdf::Dielectric(_) => false,
            Bsdf::RoughConductor(_) | Bsdf::RoughDielectric(_) => true,
        }
    }

    /// Whether a non-delta part scatters light through the surface, so that
    /// a light behind it can be sampled.
    pub fn transmits(&self) -> bool {
        matches!(self, Bsdf::RoughDielectric(_))
    }

    /// f(wo, wi) · |cos θ_i| of the non-delta parts.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self {
            Bsdf::Layered(l) => {
                if wi.z <= 0.0 || wo.z <= 0.0 {
                    return Vec3::ZERO;
                }
                let diffuse = l.albedo * (l.diffuse * FRAC_1_PI * wi.z);
                // Matte has no highlight: skip its microfacet terms.
                if l.glossy > 0.0 {
                    diffuse + Vec3::splat(l.glossy * l.ggx.reflection(wo, wi))
                } else {
                    diffuse
                }
            }
            Bsdf::RoughConductor(c) => c.eval(wo, wi),
            Bsdf::RoughDielectric(d) => d.eval(wo, wi),
            Bsdf::Conductor { .. } | Bsdf::Dielectric(_) => Vec3::ZERO,
        }
    }

    /// The density in solid angle with which [`Bsdf::sample`] draws wi
    /// through a non-delta lobe.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Bsdf::Layered(l) => {
                if wi.z <= 0.0 || wo.z <= 0.0 {
                    return 0.0;
                }
                let diffuse = l.diffuse * cosine_hemisphere_pdf(wi);
                if l.glossy > 0.0 {
                    diffuse + l.glossy * l.ggx.reflection_pdf(wo, wi)
                } else {
                    diffuse
                }
            }
            Bsdf::RoughConductor(c) => c.pdf(wo, wi),
            Bsdf::RoughDielectric(d) => d.pdf(wo, wi),
            Bsdf::Conductor { .. } | Bsdf::Dielectric(_) => 0.0,
        }
    }

    /// Draws wi for `wo` from the two uniform numbers `u_lobe` (which lobe)
    /// and `u` (where in it); `None` when the sample carries no light.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let mirrored = Vec3::new(-wo.x, -wo.y, wo.z);
        match *self {
            Bsdf::Layered(l) => {
                let (lobe, wi) = if u_lobe < l.mirror {
                    return Some(BsdfSample {
                        wi: mirrored,
                        weight: Vec3::ONE,
                        pdf: 0.0,
                        lobe: Lobe::Specular,
                        radiance_scale: 1.0,
                    });
                } else if u_lobe < l.mirror + l.glossy {
                    (Lobe::Glossy, l.ggx.sample_reflection(wo, u)?)
                } else {
                    (Lobe::Diffuse, sample_cosine_hemisphere(u))
                };
                BsdfSample::scattered(lobe, wi, self.eval(wo, wi), self.pdf(wo, wi), 1.0)
            }
            Bsdf::Conductor { f0, schlick } => Some(BsdfSample {
                wi: mirrored,
                weight: conductor_reflectance(f0, schlick, wo.z),
                pdf: 0.0,
                lobe: Lobe::Specular,
                radiance_scale: 1.0,
            }),
            Bsdf::Dielectric(glass) => Some(glass.sample(wo, u_lobe)),
            Bsdf::RoughConductor(c) => c.sample(wo, u),
            Bsdf::RoughDielectric(d) => d.sample(wo, u_lobe, u),
        }
    }
}

#[cfg(test)]
mod tests;
