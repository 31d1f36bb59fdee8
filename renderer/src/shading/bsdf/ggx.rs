//! The GGX (Trowbridge–Reitz) microfacet distribution with Smith's
//! shadowing, isotropic; directions are local (z along the normal).

use crate::shading::optics::reflect;
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

    /// Samples a micronormal visible from `wo` (wo.z > 0; Heitz 2018,
    /// "Sampling the GGX distribution of visible normals"): h has density
    /// [`Ggx::visible_pdf`], so microfacets `wo` cannot see are never drawn.
    pub fn sample_visible(&self, wo: Vec3, u: Vec2) -> Vec3 {
        // The view direction in the stretched space where α = 1.
        let v = Vec3::new(self.alpha * wo.x, self.alpha * wo.y, wo.z).normalize();
        let len2 = v.x * v.x + v.y * v.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-v.y, v.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = v.cross(t1);
        // A point on the projected hemisphere: a disc whose far half is squashed.
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + v.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let n = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * v;
        Vec3::new(self.alpha * n.x, self.alpha * n.y, n.z.max(1.0e-6)).normalize()
    }

    /// D_wo(h) = G1(wo) max(0, wo·h) D(h) / cos θ_o, the density in solid
    /// angle of the micronormals [`Ggx::sample_visible`] draws.
    pub fn visible_pdf(&self, wo: Vec3, h: Vec3) -> f32 {
        let cos_oh = wo.dot(h);
        if wo.z <= 0.0 || cos_oh <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * cos_oh * self.d(h) / wo.z
    }

    /// Samples a micronormal with density D(h) cos θ_h.
    pub fn sample_h(&self, u: Vec2) -> Vec3 {
        let tan2 = self.alpha * self.alpha * u.x / (1.0 - u.x).max(1.0e-7);
        let cos = 1.0 / (1.0 + tan2).sqrt();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
    }

    /// The half vector h = (wo + wi)/|wo + wi| of a reflection, when wo and
    /// wi are both above the surface.
    pub fn reflection_half(wo: Vec3, wi: Vec3) -> Option<Vec3> {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return None;
        }
        let h = (wo + wi).normalize_or_zero();
        (h != Vec3::ZERO).then_some(h)
    }

    /// f · cos θ_i of the white reflection lobe D G / (4 cos θ_o cos θ_i)
    /// (Fresnel 1), for wo and wi both above the surface.
    pub fn reflection(&self, wo: Vec3, wi: Vec3) -> f32 {
        Self::reflection_half(wo, wi).map_or(0.0, |h| {
            self.d(h) * self.g1(wo) * self.g1(wi) / (4.0 * wo.z)
        })
    }

    /// The density (solid angle) with which [`Ggx::sample_reflection`] picks wi.
    pub fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match Self::reflection_half(wo, wi) {
            Some(h) if wo.dot(h) > 0.0 => self.d(h) * h.z / (4.0 * wo.dot(h)),
            _ => 0.0,
        }
    }

    /// wi reflected about a sampled micronormal; `None` below the surface.
    pub fn sample_reflection(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let wi = reflect(-wo, self.sample_h(u));
        (wi.z > 0.0).then_some(wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ f(h) dω_h over the upper hemisphere by the midpoint rule on an
    /// `nt` × `np` grid of (θ, φ).
    fn hemisphere(nt: u32, np: u32, f: impl Fn(Vec3) -> f32) -> f64 {
        let mut sum = 0.0f64;
        for a in 0..nt {
            let theta = (a as f32 + 0.5) / nt as f32 * PI / 2.0;
            let d_omega = theta.sin() * (PI / 2.0 / nt as f32) * (2.0 * PI / np as f32);
            for b in 0..np {
                let phi = (b as f32 + 0.5) / np as f32 * 2.0 * PI;
                let h = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                sum += f64::from(f(h) * d_omega);
            }
        }
        sum
    }

    /// ∫ D_wo(h) dω_h = 1 for every wo: the visible micronormals' density is
    /// normalised (Heitz 2014, eq. 2: the projected visible micro-area is
    /// the macro-area seen from wo).
    #[test]
    fn visible_normal_density_is_normalised() {
        for alpha in [0.05f32, 0.3, 0.8] {
            let ggx = Ggx::new(alpha);
            for cos_o in [1.0f32, 0.6, 0.1] {
                let wo = Vec3::new((1.0 - cos_o * cos_o).sqrt(), 0.0, cos_o);
                let sum = hemisphere(2000, 64, |h| ggx.visible_pdf(wo, h));
                assert!((sum - 1.0).abs() < 3e-3, "α {alpha} cos θ_o {cos_o}: {sum}");
            }
        }
    }

    /// Sampled visible normals face wo, and their mean (a vector tilted
    /// toward wo) matches ∫ h D_wo(h) dω_h computed by quadrature.
    #[test]
    fn sampled_visible_normals_follow_their_density() {
        for alpha in [0.1f32, 0.4, 1.0] {
            let ggx = Ggx::new(alpha);
            let wo = Vec3::new(0.8, 0.0, 0.6);
            let n = 128;
            let mut sampled = glam::DVec3::ZERO;
            for i in 0..n {
                for j in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let h = ggx.sample_visible(wo, u);
                    assert!(h.z > 0.0 && wo.dot(h) >= -1e-5, "h {h} faces away from wo");
                    sampled += h.as_dvec3();
                }
            }
            sampled /= f64::from(n * n);
            let expected = glam::DVec3::new(
                hemisphere(2000, 256, |h| h.x * ggx.visible_pdf(wo, h)),
                hemisphere(2000, 256, |h| h.y * ggx.visible_pdf(wo, h)),
                hemisphere(2000, 256, |h| h.z * ggx.visible_pdf(wo, h)),
            );
            assert!(
                (sampled - expected).abs().max_element() < 2e-3,
                "α {alpha}: {sampled} vs {expected}"
            );
        }
    }

    /// ∫ D(h) cos θ_h dω_h = 1 (the projected micro-area is the macro-area).
    #[test]
    fn projected_microfacet_area_is_one() {
        for alpha in [0.05f32, 0.3, 0.8] {
            let ggx = Ggx::new(alpha);
            let sum = hemisphere(2000, 8, |h| ggx.d(h) * h.z);
            assert!((sum - 1.0).abs() < 2e-3, "α {alpha}: {sum}");
        }
    }
}
