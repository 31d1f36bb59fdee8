//! A rough dielectric interface (glass with roughness > 0): GGX microfacets
//! that reflect or refract by their own Fresnel reflectance (Walter et al.
//! 2007, "Microfacet models for refraction through rough surfaces"), sampled
//! through the normals visible from wo, as Mitsuba 3's `roughdielectric`.
//!
//! In the local frame wo is above the surface (z > 0) and η = η_i / η_t is
//! the ratio of the indices on wo's side and the other. Reflection (wi.z > 0)
//! has the half vector h = (wo + wi)/|·|; refraction (wi.z < 0) the
//! generalised one h ∝ −(η wo + wi), turned up.

use super::BsdfSample;
use super::ggx::Ggx;
use crate::shading::optics::{fresnel_dielectric, reflect, refract};
use glam::{Vec2, Vec3};

/// Rough glass as a ray meets it from one side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDielectric {
    /// η = η_incident / η_transmitted on the side the ray came from.
    pub eta: f32,
    /// Transmission tint (white for clear glass).
    pub tint: Vec3,
    /// The microfacets.
    pub ggx: Ggx,
}

/// The parts of f(wo, wi) and its density that eval and pdf share.
struct Lobe {
    /// The microfacet normal (z > 0).
    h: Vec3,
    /// F(wo·h), the microfacet's reflectance.
    fresnel: f32,
    /// Whether wi is on wo's side.
    reflect: bool,
}

impl RoughDielectric {
    /// The half vector of wo and wi and the microfacet's Fresnel
    /// reflectance; `None` for a pair no microfacet connects (grazing, or
    /// wo or wi behind the microfacet).
    fn lobe(&self, wo: Vec3, wi: Vec3) -> Option<Lobe> {
        if wo.z <= 0.0 || wi.z == 0.0 {
            return None;
        }
        let reflect = wi.z > 0.0;
        let h = if reflect {
            wo + wi
        } else {
            -(self.eta * wo + wi)
        };
        let h = h.normalize_or_zero();
        let h = if h.z < 0.0 { -h } else { h };
        // wo in front of the microfacet; wi in front (reflection) or behind (refraction).
        if h == Vec3::ZERO || wo.dot(h) <= 0.0 || (wi.dot(h) > 0.0) != reflect {
            return None;
        }
        Some(Lobe {
            h,
            fresnel: fresnel_dielectric(wo.dot(h), self.eta),
            reflect,
        })
    }

    /// |∂h/∂wi| of refraction: |wi·h| / (η wo·h + wi·h)².
    fn refraction_jacobian(&self, wo: Vec3, wi: Vec3, h: Vec3) -> f32 {
        let denom = self.eta * wo.dot(h) + wi.dot(h);
        wi.dot(h).abs() / (denom * denom)
    }

    /// f(wo, wi) · |cos θ_i|, refraction scaled by η² for radiance (as the
    /// smooth glass does) and tinted.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let Some(Lobe {
            h,
            fresnel,
            reflect,
        }) = self.lobe(wo, wi)
        else {
            return Vec3::ZERO;
        };
        let g = self.ggx;
        let dg = g.d(h) * g.g1(wo) * g.g1(wi);
        if reflect {
            Vec3::splat(fresnel * dg / (4.0 * wo.z))
        } else {
            // Walter's f_t · |cos θ_i| = (1 − F) D G |wo·h| |∂h/∂wi| / cos θ_o · η².
            let f = (1.0 - fresnel) * dg * wo.dot(h) * self.refraction_jacobian(wo, wi, h) / wo.z;
            self.tint * (f * self.eta * self.eta)
        }
    }

    /// The density with which [`RoughDielectric::sample`] draws wi: the
    /// visible normal's density D_wo(h), times the Jacobian of h → wi, times
    /// the chance F or 1 − F of reflecting or refracting at h.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(Lobe {
            h,
            fresnel,
            reflect,
        }) = self.lobe(wo, wi)
        else {
            return 0.0;
        };
        let visible = self.ggx.visible_pdf(wo, h);
        if reflect {
            fresnel * visible / (4.0 * wo.dot(h))
        } else {
            (1.0 - fresnel) * visible * self.refraction_jacobian(wo, wi, h)
        }
    }

    /// Draws a visible micronormal, then reflects with probability F(wo·h)
    /// or refracts through it; `None` when wi ends on the wrong side.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let h = self.ggx.sample_visible(wo, u);
        let cos_oh = wo.dot(h);
        if cos_oh <= 0.0 {
            return None;
        }
        let fresnel = fresnel_dielectric(cos_oh, self.eta);
        let reflects = u_lobe < fresnel;
        let (wi, radiance_scale) = if reflects {
            (reflect(-wo, h), 1.0)
        } else {
            // F = 1 on total internal reflection, so refraction exists here
            // but for rounding.
            (refract(-wo, h, self.eta)?, self.eta * self.eta)
        };
        // A microfacet can reflect below the surface or refract above it:
        // such a wi is lost (the other lobe's density does not describe it).
        if (wi.z > 0.0) != reflects {
            return None;
        }
        BsdfSample::scattered(
            super::Lobe::Glossy,
            wi,
            self.eval(wo, wi),
            self.pdf(wo, wi),
            radiance_scale,
        )
    }
}
