//! Rough glass's GGX lobes on lanes: `RoughDielectric::eval`, `pdf` and
//! `sample` (Walter et al. 2007) lane by lane, with the same operations in
//! the same order, so a lane's numbers are the scalar ones bit for bit.
//! wo is above the surface in the local frame; η = η_i / η_t per lane.

use super::delta::{fresnel_dielectric, refract};
use super::glossy::{ggx_d, ggx_g1, sample_visible};
use crate::packet::{FloatLanes, MaskLanes, Vec3s};

/// Rough glass, one per lane.
#[derive(Clone, Copy)]
pub(super) struct RoughDielectrics<F: FloatLanes> {
    /// GGX α per lane.
    pub(super) alpha: F,
    /// η = η_incident / η_transmitted on the side the ray came from.
    pub(super) eta: F,
    /// The transmission tint.
    pub(super) tint: Vec3s<F>,
}

/// What `RoughDielectric::lobe` finds for each lane.
struct Lobes<F: FloatLanes> {
    /// Lanes where a microfacet connects wo and wi (`Some`).
    found: F::Mask,
    /// The microfacet normal h (z ≥ 0).
    h: Vec3s<F>,
    /// F(wo·h).
    fresnel: F,
    /// Lanes where wi is on wo's side.
    reflect: F::Mask,
}

impl<F: FloatLanes> RoughDielectrics<F> {
    /// `RoughDielectric::lobe(wo, wi)`.
    #[inline(always)]
    fn lobe(&self, wo: Vec3s<F>, wi: Vec3s<F>) -> Lobes<F> {
        let reflect = wi.z.simd_gt(F::ZERO);
        let sum = Vec3s::select(reflect, wo + wi, -(wo * self.eta + wi));
        // glam's normalize_or_zero.
        let rcp = F::ONE / sum.length_squared().sqrt();
        let usable = rcp.is_finite() & rcp.simd_gt(F::ZERO);
        let h = Vec3s::select(usable, sum * rcp, Vec3s::ZERO);
        let h = Vec3s::select(h.z.simd_lt(F::ZERO), -h, h);
        let cos_oh = wo.dot(h);
        let in_front = wi.dot(h).simd_gt(F::ZERO);
        // (wi · h > 0) == reflect.
        let sides_agree = !(in_front ^ reflect);
        let found = !(wo.z.simd_le(F::ZERO) | wi.z.simd_eq(F::ZERO))
            & h.nonzero()
            & cos_oh.simd_gt(F::ZERO)
            & sides_agree;
        Lobes {
            found,
            h,
            fresnel: fresnel_dielectric(cos_oh, self.eta),
            reflect,
        }
    }

    /// `refraction_jacobian(wo, wi, h)`: |wi·h| / (η wo·h + wi·h)².
    #[inline(always)]
    fn jacobian(&self, wo: Vec3s<F>, wi: Vec3s<F>, h: Vec3s<F>) -> F {
        let denom = self.eta * wo.dot(h) + wi.dot(h);
        wi.dot(h).abs() / (denom * denom)
    }

    /// `RoughDielectric::eval(wo, wi)` and `pdf(wo, wi)`.
    #[inline(always)]
    pub(super) fn eval_pdf(&self, wo: Vec3s<F>, wi: Vec3s<F>) -> (Vec3s<F>, F) {
        let Lobes {
            found,
            h,
            fresnel,
            reflect,
        } = self.lobe(wo, wi);
        let alpha = self.alpha;
        let (d, g1_wo) = (ggx_d(alpha, h), ggx_g1(alpha, wo));
        let dg = d * g1_wo * ggx_g1(alpha, wi);
        let cos_oh = wo.dot(h);
        let jacobian = self.jacobian(wo, wi, h);
        let reflected = fresnel * dg / (F::splat(4.0) * wo.z);
        let refracted = (F::ONE - fresnel) * dg * cos_oh * jacobian / wo.z;
        let f = Vec3s::select(
            reflect,
            Vec3s::new(reflected, reflected, reflected),
            self.tint * (refracted * self.eta * self.eta),
        );
        // Ggx::visible_pdf(wo, h).
        let visible = (wo.z.simd_le(F::ZERO) | cos_oh.simd_le(F::ZERO))
            .select(F::ZERO, g1_wo * cos_oh * d / wo.z);
        let pdf = reflect.select(
            fresnel * visible / (F::splat(4.0) * cos_oh),
            (F::ONE - fresnel) * visible * jacobian,
        );
        (
            Vec3s::select(found, f, Vec3s::ZERO),
            found.select(pdf, F::ZERO),
        )
    }

    /// `RoughDielectric::sample(wo, u_lobe, u)` in the lanes of `lanes`: wi
    /// reflected or refracted through a visible micronormal, f · |cos θ_i|,
    /// the density (not positive where the scalar code gives `None`) and
    /// the radiance scale.
    #[inline(always)]
    pub(super) fn sample(
        &self,
        lanes: F::Mask,
        wo: Vec3s<F>,
        u_lobe: F,
        u: [F; 2],
    ) -> (Vec3s<F>, Vec3s<F>, F, F) {
        let h = sample_visible(self.alpha, lanes, wo, u);
        let cos_oh = wo.dot(h);
        let reflects = u_lobe.simd_lt(fresnel_dielectric(cos_oh, self.eta));
        let d = -wo;
        let reflected = d - h * (F::splat(2.0) * d.dot(h));
        let (internal, refracted) = refract(d, h, self.eta);
        let wi = Vec3s::select(reflects, reflected, refracted);
        let scale = reflects.select(F::ONE, self.eta * self.eta);
        let valid =
            cos_oh.simd_gt(F::ZERO) & !(!reflects & internal) & !(wi.z.simd_gt(F::ZERO) ^ reflects);
        let (f, pdf) = self.eval_pdf(wo, wi);
        (wi, f, valid.select(pdf, F::ZERO), scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::packet::{WIDTH, mask_from};
    use crate::shading::bsdf::ggx::Ggx;
    use crate::shading::bsdf::rough_dielectric::RoughDielectric;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::{Vec2, Vec3};

    /// Lanes `F` against `RoughDielectric` for random directions (wo above,
    /// wi anywhere), α, η and numbers.
    #[derive(Clone)]
    struct Compare(u64);

    impl WithLanes for Compare {
        type Output = (usize, usize);
        fn run<F: FloatLanes>(self) -> (usize, usize) {
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            let mut rng = Sampler::for_sample(self.0, 0, 0, 0);
            let (mut reflected, mut refracted) = (0, 0);
            for c in 0..600 {
                let mut wo = [Vec3::Z; WIDTH];
                let mut wi = [Vec3::Z; WIDTH];
                let mut u = [Vec2::ZERO; WIDTH];
                let mut u_lobe = [0.0f32; WIDTH];
                for k in 0..WIDTH {
                    let d = rng.next_direction();
                    wo[k] = Vec3::new(d.x, d.y, d.z.abs());
                    wi[k] = rng.next_direction();
                    u[k] = rng.next_2d();
                    u_lobe[k] = rng.next_f32();
                }
                let alphas: [f32; WIDTH] =
                    std::array::from_fn(|k| [0.001, 0.09, 0.3, 0.64, 1.0][(c + k) % 5]);
                let etas: [f32; WIDTH] =
                    std::array::from_fn(|k| [1.0 / 1.5, 1.5, 1.33, 1.0 / 1.33][(c + 3 * k) % 4]);
                let tint = Vec3::new(0.9, 0.8, 0.7);
                let glass = RoughDielectrics {
                    alpha: F::from_array(alphas),
                    eta: F::from_array(etas),
                    tint: Vec3s::splat(tint),
                };
                let (wo_l, wi_l) = (Vec3s::<F>::from_lanes(&wo), Vec3s::<F>::from_lanes(&wi));
                let (f, pdf) = glass.eval_pdf(wo_l, wi_l);
                let ux = F::from_array(u.map(|u| u.x));
                let uy = F::from_array(u.map(|u| u.y));
                let all = mask_from::<F>(|_| true);
                let (s_wi, s_f, s_pdf, s_scale) =
                    glass.sample(all, wo_l, F::from_array(u_lobe), [ux, uy]);
                for k in 0..WIDTH {
                    let scalar = RoughDielectric {
                        eta: etas[k],
                        tint,
                        ggx: Ggx { alpha: alphas[k] },
                    };
                    let context = format!(
                        "wo {:?} wi {:?} α {} η {}",
                        wo[k], wi[k], alphas[k], etas[k]
                    );
                    assert_eq!(
                        bits(f.lane(k)),
                        bits(scalar.eval(wo[k], wi[k])),
                        "f, {context}"
                    );
                    assert_eq!(
                        pdf.as_array()[k].to_bits(),
                        scalar.pdf(wo[k], wi[k]).to_bits(),
                        "pdf, {context}"
                    );
                    let want = scalar.sample(wo[k], u_lobe[k], u[k]);
                    let got_pdf = s_pdf.as_array()[k];
                    match want {
                        Some(w) => {
                            assert_eq!(bits(s_wi.lane(k)), bits(w.wi), "wi, {context}");
                            assert_eq!(
                                got_pdf.to_bits(),
                                w.pdf.to_bits(),
                                "sampled pdf, {context}"
                            );
                            let weight = s_f.lane(k) / got_pdf;
                            assert_eq!(bits(weight), bits(w.weight), "weight, {context}");
                            assert_eq!(s_scale.as_array()[k], w.radiance_scale, "scale, {context}");
                            if w.wi.z > 0.0 {
                                reflected += 1;
                            } else {
                                refracted += 1;
                            }
                        }
                        None => assert!(!(got_pdf > 0.0), "no sample, {context}: pdf {got_pdf}"),
                    }
                }
            }
            (reflected, refracted)
        }
    }

    #[test]
    fn rough_glass_lanes_equal_the_scalar_lobes_bit_for_bit() {
        for (reflected, refracted) in on_every_lane_type(Compare(31)) {
            assert!(
                reflected > 200 && refracted > 1500,
                "{reflected} reflected, {refracted} refracted"
            );
        }
    }
}
