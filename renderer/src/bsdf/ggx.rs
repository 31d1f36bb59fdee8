//! The GGX (Trowbridge–Reitz) microfacet distribution with Smith's
//! shadowing, isotropic; directions are local (z along the normal).

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// GGX with roughness α (the distribution's width).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    /// α > 0.
    pub alpha: f32,
}

impl Ggx {
    /// The smallest α used: below it the lobe is numerically a mirror.
    pub const MIN_ALPHA: f32 = 1.0e-3;

    /// GGX with roughness `alpha`, clamped to at least [`Ggx::MIN_ALPHA`].
    pub fn new(alpha: f32) -> Self {
        Self {
            alpha: alpha.max(Self::MIN_ALPHA),
        }
    }

    /// The α matching a Blinn-Phong exponent (Walter et al. 2007: α = √(2 / (n + 2))).
    pub fn from_shininess(shininess: f32) -> Self {
        Self::new((2.0 / (shininess.max(0.0) + 2.0)).sqrt())
    }

    /// D(h), the density of micronormals h (local, h.z > 0).
    pub fn d(&self, h: Vec3) -> f32 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let k = h.z * h.z * (a2 - 1.0) + 1.0;
        a2 / (PI * k * k)
    }

    /// Smith's G1(v) for a direction v (local).
    pub fn g1(&self, v: Vec3) -> f32 {
        let cos2 = v.z * v.z;
        if cos2 <= 0.0 {
            return 0.0;
        }
        let tan2 = ((1.0 - cos2) / cos2).max(0.0);
        2.0 / (1.0 + (1.0 + self.alpha * self.alpha * tan2).sqrt())
    }

    /// Samples a micronormal with density D(h) cos θ_h.
    pub fn sample_h(&self, u: Vec2) -> Vec3 {
        let tan2 = self.alpha * self.alpha * u.x / (1.0 - u.x).max(1.0e-7);
        let cos = 1.0 / (1.0 + tan2).sqrt();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
    }

    /// f · cos θ_i of the white reflection lobe D G / (4 cos θ_o cos θ_i)
    /// (Fresnel 1), for wo and wi both above the surface.
    pub fn reflection(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize_or_zero();
        if h == Vec3::ZERO {
            return 0.0;
        }
        self.d(h) * self.g1(wo) * self.g1(wi) / (4.0 * wo.z)
    }

    /// The density (solid angle) with which [`Ggx::sample_reflection`] picks wi.
    pub fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize_or_zero();
        let cos_oh = wo.dot(h);
        if h == Vec3::ZERO || cos_oh <= 0.0 {
            return 0.0;
        }
        self.d(h) * h.z / (4.0 * cos_oh)
    }

    /// wi reflected about a sampled micronormal; `None` below the surface.
    pub fn sample_reflection(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let h = self.sample_h(u);
        let wi = 2.0 * wo.dot(h) * h - wo;
        (wi.z > 0.0).then_some(wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ D(h) cos θ_h dω_h = 1 (the projected micro-area is the macro-area).
    #[test]
    fn projected_microfacet_area_is_one() {
        for alpha in [0.05f32, 0.3, 0.8] {
            let ggx = Ggx::new(alpha);
            let (nt, np) = (2000, 8);
            let mut sum = 0.0f64;
            for a in 0..nt {
                let theta = (a as f32 + 0.5) / nt as f32 * PI / 2.0;
                for b in 0..np {
                    let phi = (b as f32 + 0.5) / np as f32 * 2.0 * PI;
                    let h = Vec3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    );
                    let d_omega = theta.sin() * (PI / 2.0 / nt as f32) * (2.0 * PI / np as f32);
                    sum += f64::from(ggx.d(h) * h.z * d_omega);
                }
            }
            assert!((sum - 1.0).abs() < 2e-3, "α {alpha}: {sum}");
        }
    }
}
