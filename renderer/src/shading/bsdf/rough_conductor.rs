//! A rough conductor (metal with roughness > 0): a GGX microfacet
//! reflection, f = F(wo·h) D(h) G1(wo) G1(wi) / (4 cos θ_o cos θ_i), sampled
//! through the normals visible from wo, as Mitsuba 3's `roughconductor`.

use super::ggx::Ggx;
use super::{BsdfSample, Lobe};
use crate::shading::optics::reflect;
use glam::{Vec2, Vec3};

/// Metal or mirror with a GGX microsurface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughConductor {
    /// Reflectance at normal incidence.
    pub f0: Vec3,
    /// Whether the reflectance rises toward white at grazing angles
    /// (Schlick, metal); a mirror reflects `f0` at every angle.
    pub schlick: bool,
    /// The microfacets.
    pub ggx: Ggx,
}

impl RoughConductor {
    /// The Fresnel reflectance of a microfacet met at `cos` = wo·h.
    fn fresnel(&self, cos: f32) -> Vec3 {
        super::conductor_reflectance(self.f0, self.schlick, cos)
    }

    /// f(wo, wi) · cos θ_i.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let Some(h) = Ggx::reflection_half(wo, wi) else {
            return Vec3::ZERO;
        };
        let g = self.ggx;
        self.fresnel(wo.dot(h)) * (g.d(h) * g.g1(wo) * g.g1(wi) / (4.0 * wo.z))
    }

    /// The density with which [`RoughConductor::sample`] draws wi:
    /// D_wo(h) / (4 wo·h) = G1(wo) D(h) / (4 cos θ_o).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(h) = Ggx::reflection_half(wo, wi) else {
            return 0.0;
        };
        self.ggx.g1(wo) * self.ggx.d(h) / (4.0 * wo.z)
    }

    /// wi reflected about a visible micronormal; `None` below the surface.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        let h = self.ggx.sample_visible(wo, u);
        let wi = reflect(-wo, h);
        BsdfSample::scattered(Lobe::Glossy, wi, self.eval(wo, wi), self.pdf(wo, wi), 1.0)
    }
}
