//! A rough conductor's GGX lobe on lanes: its value, density and visible-
//! normal sample, each the scalar code's arithmetic lane by lane
//! (`RoughConductor::eval`, `pdf` and `sample`; `Ggx::d`, `g1`,
//! `reflection_half` and `sample_visible`; `optics::reflect`), so a lane's
//! numbers are the scalar ones bit for bit. The angle's cosine and sine
//! are libm's, lane by lane.

use super::delta::fresnel_schlick;
use crate::packet::{FloatLanes, MaskLanes, Vec3s, WIDTH, lane_set};
use glam::Vec3;
use std::f32::consts::PI;

/// Rough conductors, one per lane: GGX's α, the reflectance f0 and whether
/// it follows Schlick's approximation.
#[derive(Clone, Copy)]
pub(super) struct RoughConductors<F: FloatLanes> {
    /// α per lane.
    pub(super) alpha: F,
    /// f0 per lane.
    pub(super) f0: Vec3s<F>,
    /// Lanes whose reflectance rises toward white at grazing angles (metal).
    pub(super) schlick: F::Mask,
}

impl<F: FloatLanes> RoughConductors<F> {
    /// `Ggx::d(h)`.
    #[inline(always)]
    fn d(&self, h: Vec3s<F>) -> F {
        ggx_d(self.alpha, h)
    }

    /// `Ggx::g1(v)`.
    #[inline(always)]
    fn g1(&self, v: Vec3s<F>) -> F {
        ggx_g1(self.alpha, v)
    }

    /// `Ggx::reflection_half(wo, wi)`: the half vector where both lie above
    /// the surface and it is not zero (its mask, and the vector).
    #[inline(always)]
    fn half(wo: Vec3s<F>, wi: Vec3s<F>) -> (F::Mask, Vec3s<F>) {
        reflection_half(wo, wi)
    }

    /// `RoughConductor::eval(wo, wi)` and `pdf(wo, wi)`: f · cos θ_i and the
    /// density of sampling wi.
    #[inline(always)]
    pub(super) fn eval_pdf(&self, wo: Vec3s<F>, wi: Vec3s<F>) -> (Vec3s<F>, F) {
        let (found, h) = Self::half(wo, wi);
        let (d, g1_wo) = (self.d(h), self.g1(wo));
        let four_cos_o = F::splat(4.0) * wo.z;
        let cos = wo.dot(h);
        let reflectance = Vec3s::select(self.schlick, fresnel_schlick(cos, self.f0), self.f0);
        let f = reflectance * (d * g1_wo * self.g1(wi) / four_cos_o);
        let pdf = g1_wo * d / four_cos_o;
        (
            Vec3s::select(found, f, Vec3s::ZERO),
            found.select(pdf, F::ZERO),
        )
    }

    /// `RoughConductor::sample(wo, u)` in the lanes of `lanes`: wi reflected
    /// about a visible micronormal, with f · cos θ_i and the density (a lane
    /// whose density is not positive carries nothing).
    #[inline(always)]
    pub(super) fn sample(
        &self,
        lanes: F::Mask,
        wo: Vec3s<F>,
        u: [F; 2],
    ) -> (Vec3s<F>, Vec3s<F>, F) {
        let h = sample_visible(self.alpha, lanes, wo, u);
        // optics::reflect(−wo, h) = d − 2 (d · h) h.
        let d = -wo;
        let wi = d - h * (F::splat(2.0) * d.dot(h));
        let (f, pdf) = self.eval_pdf(wo, wi);
        (wi, f, pdf)
    }
}

/// `Ggx::reflection_half(wo, wi)`: the half vector where both lie above the
/// surface and it is not zero (its mask, and the vector).
#[inline(always)]
fn reflection_half<F: FloatLanes>(wo: Vec3s<F>, wi: Vec3s<F>) -> (F::Mask, Vec3s<F>) {
    let sum = wo + wi;
    // glam's normalize_or_zero: 1/‖sum‖ must be finite and positive.
    let rcp = F::ONE / sum.length_squared().sqrt();
    let h = sum * rcp;
    let found = !(wo.z.simd_le(F::ZERO) | wi.z.simd_le(F::ZERO))
        & rcp.is_finite()
        & rcp.simd_gt(F::ZERO)
        & h.nonzero();
    (found, h)
}

/// The white GGX highlights of layered BSDFs (plastic, marble), one per
/// lane: `Ggx::reflection`, `reflection_pdf` and `sample_reflection` with
/// α per lane, each the scalar arithmetic lane by lane.
#[derive(Clone, Copy)]
pub(super) struct Highlights<F: FloatLanes> {
    /// α per lane.
    pub(super) alpha: F,
}

impl<F: FloatLanes> Highlights<F> {
    /// `Ggx::reflection(wo, wi)` and `Ggx::reflection_pdf(wo, wi)`: the
    /// white lobe's f · cos θ_i and the density with which
    /// [`Highlights::sample`] draws wi.
    #[inline(always)]
    pub(super) fn eval_pdf(&self, wo: Vec3s<F>, wi: Vec3s<F>) -> (F, F) {
        let (found, h) = reflection_half(wo, wi);
        let d = ggx_d(self.alpha, h);
        let f = d * ggx_g1(self.alpha, wo) * ggx_g1(self.alpha, wi) / (F::splat(4.0) * wo.z);
        let cos_oh = wo.dot(h);
        let pdf = d * h.z / (F::splat(4.0) * cos_oh);
        (
            found.select(f, F::ZERO),
            (found & cos_oh.simd_gt(F::ZERO)).select(pdf, F::ZERO),
        )
    }

    /// `Ggx::sample_reflection(wo, u)` in the lanes of `lanes`: wi reflected
    /// about a micronormal drawn with density D(h) cos θ_h (`Ggx::sample_h`),
    /// and the lanes where it lies above the surface (the others draw none).
    #[inline(always)]
    pub(super) fn sample(
        &self,
        lanes: F::Mask,
        wo: Vec3s<F>,
        [ux, uy]: [F; 2],
    ) -> (Vec3s<F>, F::Mask) {
        let tan2 = self.alpha * self.alpha * ux / (F::ONE - ux).max(F::splat(1.0e-7));
        let cos = F::ONE / (F::ONE + tan2).sqrt();
        let sin = (F::ONE - cos * cos).max(F::ZERO).sqrt();
        let (cos_phi, sin_phi) = turn(lanes, uy);
        let h = Vec3s::new(sin * cos_phi, sin * sin_phi, cos);
        // optics::reflect(−wo, h) = d − 2 (d · h) h.
        let d = -wo;
        let wi = d - h * (F::splat(2.0) * d.dot(h));
        (wi, lanes & wi.z.simd_gt(F::ZERO))
    }
}

/// cos φ and sin φ of φ = 2π u in the lanes of `lanes` (1 and 0 in the
/// others): libm's cosine and sine, lane by lane, as the scalar code calls
/// them.
#[inline(always)]
fn turn<F: FloatLanes>(lanes: F::Mask, u: F) -> (F, F) {
    let angles = (F::splat(2.0 * PI) * u).to_array();
    let (mut cos, mut sin) = ([1.0f32; WIDTH], [0.0f32; WIDTH]);
    for k in 0..WIDTH {
        if lane_set(lanes, k) {
            (cos[k], sin[k]) = (angles[k].cos(), angles[k].sin());
        }
    }
    (F::from_array(cos), F::from_array(sin))
}

/// `Ggx::d(h)` with α per lane: the density of micronormals h, 0 below
/// the surface.
#[inline(always)]
pub(super) fn ggx_d<F: FloatLanes>(alpha: F, h: Vec3s<F>) -> F {
    let a2 = alpha * alpha;
    let k = h.z * h.z * (a2 - F::ONE) + F::ONE;
    h.z.simd_le(F::ZERO)
        .select(F::ZERO, a2 / (F::splat(PI) * k * k))
}

/// `Ggx::g1(v)` with α per lane: Smith's shadowing of direction v.
#[inline(always)]
pub(super) fn ggx_g1<F: FloatLanes>(alpha: F, v: Vec3s<F>) -> F {
    let cos2 = v.z * v.z;
    let tan2 = ((F::ONE - cos2) / cos2).max(F::ZERO);
    let g = F::splat(2.0) / (F::ONE + (F::ONE + alpha * alpha * tan2).sqrt());
    cos2.simd_le(F::ZERO).select(F::ZERO, g)
}

/// `Ggx::sample_visible(wo, u)` with α per lane, in the lanes of `lanes`:
/// a micronormal visible from wo (Heitz 2018).
#[inline(always)]
pub(super) fn sample_visible<F: FloatLanes>(
    alpha: F,
    lanes: F::Mask,
    wo: Vec3s<F>,
    [ux, uy]: [F; 2],
) -> Vec3s<F> {
    let v = Vec3s::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
    let len2 = v.x * v.x + v.y * v.y;
    let tilted = len2.simd_gt(F::ZERO);
    let t1 = Vec3s::select(
        tilted,
        Vec3s::new(-v.y, v.x, F::ZERO).div_lanes(len2.sqrt()),
        Vec3s::splat(Vec3::X),
    );
    let t2 = v.cross(t1);
    let r = ux.sqrt();
    let (cos, sin) = turn(lanes, uy);
    let p1 = r * cos;
    let s = F::splat(0.5) * (F::ONE + v.z);
    let p2 = (F::ONE - s) * (F::ONE - p1 * p1).max(F::ZERO).sqrt() + s * r * sin;
    let n = t1 * p1 + t2 * p2 + v * (F::ONE - p1 * p1 - p2 * p2).max(F::ZERO).sqrt();
    Vec3s::new(alpha * n.x, alpha * n.y, n.z.max(F::splat(1.0e-6))).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::shading::bsdf::ggx::Ggx;
    use crate::shading::bsdf::rough_conductor::RoughConductor;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec2;

    /// Random local directions, a packet's worth at a time, some below the surface,
    /// some grazing, and numbers u.
    fn cases(count: usize) -> Vec<(Vec3, Vec3, Vec2)> {
        let mut rng = Sampler::for_sample(23, 0, 0, 0);
        (0..count)
            .map(|k| {
                let mut wo = rng.next_direction();
                if k % 3 != 0 {
                    wo.z = wo.z.abs();
                }
                if k % 17 == 0 {
                    wo = Vec3::new(wo.x, wo.y, 0.0).normalize_or(Vec3::X);
                }
                let wi = rng.next_direction();
                (wo, wi, rng.next_2d())
            })
            .collect()
    }

    /// Lanes `F` against `RoughConductor` for every case and α.
    #[derive(Clone)]
    struct Compare(Vec<(Vec3, Vec3, Vec2)>);

    impl WithLanes for Compare {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            let mut sampled = 0;
            for (c, chunk) in self.0.chunks_exact(WIDTH).enumerate() {
                let alphas: [f32; WIDTH] =
                    std::array::from_fn(|k| [0.001, 0.05, 0.1225, 0.64, 1.0][(c + k) % 5]);
                let schlick: [bool; WIDTH] = std::array::from_fn(|k| (c + k) % 2 == 0);
                let f0 = Vec3::new(0.95, 0.64, 0.54);
                let lanes = RoughConductors {
                    alpha: F::from_array(alphas),
                    f0: Vec3s::splat(f0),
                    schlick: crate::packet::mask_from::<F>(|k| schlick[k]),
                };
                let wo = Vec3s::<F>::from_lanes(&std::array::from_fn(|k| chunk[k].0));
                let wi = Vec3s::<F>::from_lanes(&std::array::from_fn(|k| chunk[k].1));
                let ux = F::from_array(std::array::from_fn(|k| chunk[k].2.x));
                let uy = F::from_array(std::array::from_fn(|k| chunk[k].2.y));
                let (f, pdf) = lanes.eval_pdf(wo, wi);
                let all = F::from_array([1.0; WIDTH]).simd_gt(F::ZERO);
                let (s_wi, s_f, s_pdf) = lanes.sample(all, wo, [ux, uy]);
                for (k, &(w_o, w_i, u)) in chunk.iter().enumerate() {
                    let scalar = RoughConductor {
                        f0,
                        schlick: schlick[k],
                        ggx: Ggx { alpha: alphas[k] },
                    };
                    let context = format!("wo {w_o:?} wi {w_i:?} α {}", alphas[k]);
                    assert_eq!(bits(f.lane(k)), bits(scalar.eval(w_o, w_i)), "f, {context}");
                    assert_eq!(
                        pdf.as_array()[k].to_bits(),
                        scalar.pdf(w_o, w_i).to_bits(),
                        "pdf, {context}"
                    );
                    if w_o.z > 0.0 {
                        let h = scalar.ggx.sample_visible(w_o, u);
                        let want_wi = crate::shading::optics::reflect(-w_o, h);
                        assert_eq!(bits(s_wi.lane(k)), bits(want_wi), "wi, {context} u {u:?}");
                        assert_eq!(
                            bits(s_f.lane(k)),
                            bits(scalar.eval(w_o, want_wi)),
                            "sampled f, {context}"
                        );
                        assert_eq!(
                            s_pdf.as_array()[k].to_bits(),
                            scalar.pdf(w_o, want_wi).to_bits(),
                            "sampled pdf, {context}"
                        );
                        sampled += usize::from(s_pdf.as_array()[k] > 0.0);
                    }
                }
            }
            sampled
        }
    }

    /// Lanes `F` against `Ggx`'s white reflection lobe for every case and α.
    #[derive(Clone)]
    struct CompareHighlights(Vec<(Vec3, Vec3, Vec2)>);

    impl WithLanes for CompareHighlights {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            let mut reflected = 0;
            for (c, chunk) in self.0.chunks_exact(WIDTH).enumerate() {
                let alphas: [f32; WIDTH] = std::array::from_fn(|k| {
                    // Plastic's and marble's shininess 64 and 80, and others.
                    [0.001, 0.17408, 0.15617, 0.5, 1.0][(c + k) % 5]
                });
                let lanes = Highlights {
                    alpha: F::from_array(alphas),
                };
                let wo = Vec3s::<F>::from_lanes(&std::array::from_fn(|k| chunk[k].0));
                let wi = Vec3s::<F>::from_lanes(&std::array::from_fn(|k| chunk[k].1));
                let ux = F::from_array(std::array::from_fn(|k| chunk[k].2.x));
                let uy = F::from_array(std::array::from_fn(|k| chunk[k].2.y));
                let (f, pdf) = lanes.eval_pdf(wo, wi);
                let all = F::from_array([1.0; WIDTH]).simd_gt(F::ZERO);
                let (s_wi, above) = lanes.sample(all, wo, [ux, uy]);
                for (k, &(w_o, w_i, u)) in chunk.iter().enumerate() {
                    let ggx = Ggx { alpha: alphas[k] };
                    let context = format!("wo {w_o:?} wi {w_i:?} α {}", alphas[k]);
                    assert_eq!(
                        f.as_array()[k].to_bits(),
                        ggx.reflection(w_o, w_i).to_bits(),
                        "f, {context}"
                    );
                    assert_eq!(
                        pdf.as_array()[k].to_bits(),
                        ggx.reflection_pdf(w_o, w_i).to_bits(),
                        "pdf, {context}"
                    );
                    let want = ggx.sample_reflection(w_o, u);
                    assert_eq!(
                        lane_set(above, k),
                        want.is_some(),
                        "drawn, {context} u {u:?}"
                    );
                    if let Some(want) = want {
                        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                        assert_eq!(bits(s_wi.lane(k)), bits(want), "wi, {context} u {u:?}");
                        reflected += 1;
                    }
                }
            }
            reflected
        }
    }

    #[test]
    fn highlight_lanes_equal_the_scalar_lobe_bit_for_bit() {
        for reflected in on_every_lane_type(CompareHighlights(cases(4096))) {
            assert!(
                reflected > 1500,
                "too few samples to mean anything: {reflected}"
            );
        }
    }

    #[test]
    fn rough_conductor_lanes_equal_the_scalar_lobe_bit_for_bit() {
        for sampled in on_every_lane_type(Compare(cases(4096))) {
            assert!(
                sampled > 1500,
                "too few samples to mean anything: {sampled}"
            );
        }
    }
}
