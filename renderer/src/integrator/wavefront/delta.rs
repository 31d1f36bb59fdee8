//! The delta lobes on lanes: a smooth conductor's reflection (tinted by
//! Schlick's approximation for metal) and smooth glass's choice between
//! Fresnel reflection and Snell refraction. Each is the scalar code's
//! arithmetic lane by lane (`Bsdf::sample`, `SmoothDielectric::sample`,
//! `optics::fresnel_dielectric`, `optics::refract`,
//! `optics::fresnel_schlick`), so a lane's direction and weight are the
//! scalar sample's bit for bit.

use crate::packet::{FloatLanes, MaskLanes, Vec3s};
use glam::Vec3;

/// Directions drawn from delta lobes, in local shading coordinates.
pub(super) struct DeltaSamples<F: FloatLanes> {
    /// wi.
    pub(super) wi: Vec3s<F>,
    /// The throughput's factor.
    pub(super) weight: Vec3s<F>,
    /// The radiance's scaling across the interface (η² when refracted, else 1).
    pub(super) radiance_scale: F,
}

/// wo mirrored about the normal: (−x, −y, z).
#[inline(always)]
pub(super) fn mirrored<F: FloatLanes>(wo: Vec3s<F>) -> Vec3s<F> {
    Vec3s::new(-wo.x, -wo.y, wo.z)
}

/// `x.clamp(0, 1)` lane by lane (a NaN stays NaN, as `f32::clamp` keeps it).
#[inline(always)]
fn clamp_unit<F: FloatLanes>(x: F) -> F {
    let x = x.simd_lt(F::ZERO).select(F::ZERO, x);
    x.simd_gt(F::ONE).select(F::ONE, x)
}

/// `optics::fresnel_schlick(cos, f0)`: f0 + (1 − f0) m with
/// m = (1 − clamp(cos))⁵ formed as x · (x²)².
#[inline(always)]
pub(super) fn fresnel_schlick<F: FloatLanes>(cos: F, f0: Vec3s<F>) -> Vec3s<F> {
    let x = F::ONE - clamp_unit(cos);
    let x2 = x * x;
    let m = x * (x2 * x2);
    f0 + (Vec3s::splat(Vec3::ONE) - f0) * m
}

/// `fresnel_dielectric(cos_i, eta)`: the unpolarised reflectance, 1 on
/// total internal reflection.
#[inline(always)]
pub(super) fn fresnel_dielectric<F: FloatLanes>(cos_i: F, eta: F) -> F {
    let cos_i = clamp_unit(cos_i);
    let sin2_t = eta * eta * (F::ONE - cos_i * cos_i);
    let cos_t = (F::ONE - sin2_t).sqrt();
    let r_parallel = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let r_perpendicular = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let fresnel = F::splat(0.5) * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
    sin2_t.simd_ge(F::ONE).select(F::ONE, fresnel)
}

/// `optics::refract(dir, n, η)` lane by lane: the lanes of total internal
/// reflection (where the scalar code gives `None`), and the refracted
/// direction elsewhere.
#[inline(always)]
pub(super) fn refract<F: FloatLanes>(dir: Vec3s<F>, n: Vec3s<F>, eta: F) -> (F::Mask, Vec3s<F>) {
    let cos_i = -dir.dot(n);
    let sin2_t = eta * eta * (F::ONE - cos_i * cos_i).max(F::ZERO);
    let cos_t = (F::ONE - sin2_t).sqrt();
    (
        sin2_t.simd_ge(F::ONE),
        (dir * eta + n * (eta * cos_i - cos_t)).normalize(),
    )
}

/// `SmoothDielectric::sample(wo, u)` lane by lane, with η and the tint per
/// lane: reflection when u < F (or on total internal reflection), else
/// `refract(−wo, +z, η)` with weight tint · η².
#[inline(always)]
pub(super) fn dielectric_samples<F: FloatLanes>(
    wo: Vec3s<F>,
    eta: F,
    tint: Vec3s<F>,
    u: F,
) -> DeltaSamples<F> {
    let reflects = u.simd_lt(fresnel_dielectric(wo.z, eta));
    let (internal, refracted) = refract(-wo, Vec3s::splat(Vec3::Z), eta);
    let reflects = reflects | internal;
    let scale = eta * eta;
    DeltaSamples {
        wi: Vec3s::select(reflects, mirrored(wo), refracted),
        weight: Vec3s::select(reflects, Vec3s::splat(Vec3::ONE), tint * scale),
        radiance_scale: reflects.select(F::ONE, scale),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::packet::WIDTH;
    use crate::shading::bsdf::{Bsdf, dielectric::SmoothDielectric};
    use crate::shading::optics;
    use crate::simd::{WithLanes, on_every_lane_type};

    /// Local directions worth testing: random ones over the sphere, and
    /// grazing, normal and exactly tangent ones.
    fn directions(count: usize) -> Vec<Vec3> {
        let mut rng = Sampler::for_sample(11, 0, 0, 0);
        let mut out = vec![
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, -0.999_999, 0.001_414),
            Vec3::new(1.0, 0.0, -0.0),
        ];
        while out.len() < count {
            out.push(rng.next_direction());
        }
        out
    }

    /// Lanes `F` against the scalar code for every direction, each η of
    /// `etas` and a spread of lobe numbers u: glass's wi, weight and
    /// radiance scale, and a metal's Schlick reflectance.
    #[derive(Clone)]
    struct Compare(Vec<Vec3>, Vec<f32>);

    impl WithLanes for Compare {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            let tint = Vec3::new(0.9, 0.7, 0.4);
            let mut refracted = 0;
            for (c, chunk) in self.0.chunks_exact(WIDTH).enumerate() {
                let wo = Vec3s::<F>::from_lanes(chunk.try_into().expect("WIDTH lanes"));
                for &eta in &self.1 {
                    let u: [f32; WIDTH] =
                        std::array::from_fn(|k| ((c * 7 + k * 3) % 10) as f32 / 10.0);
                    let got =
                        dielectric_samples(wo, F::splat(eta), Vec3s::splat(tint), F::from_array(u));
                    for (k, &w) in chunk.iter().enumerate() {
                        let want = SmoothDielectric { eta, tint }.sample(w, u[k]);
                        let context = format!("wo {w:?} η {eta} u {}", u[k]);
                        assert_eq!(bits(got.wi.lane(k)), bits(want.wi), "wi, {context}");
                        assert_eq!(
                            bits(got.weight.lane(k)),
                            bits(want.weight),
                            "weight, {context}"
                        );
                        assert_eq!(
                            got.radiance_scale.as_array()[k].to_bits(),
                            want.radiance_scale.to_bits(),
                            "scale, {context}"
                        );
                        refracted += usize::from(want.radiance_scale != 1.0);
                    }
                }
                let f0 = Vec3::new(0.95, 0.64, 0.54);
                let schlick = fresnel_schlick(wo.z, Vec3s::splat(f0));
                for (k, &w) in chunk.iter().enumerate() {
                    let metal = Bsdf::Conductor { f0, schlick: true };
                    let want = metal
                        .sample(w, 0.5, glam::Vec2::ZERO)
                        .expect("a reflection");
                    assert_eq!(bits(schlick.lane(k)), bits(want.weight), "metal at {w:?}");
                    assert_eq!(bits(mirrored(wo).lane(k)), bits(want.wi), "mirror at {w:?}");
                    let plain = optics::fresnel_schlick(w.z, f0);
                    assert_eq!(bits(schlick.lane(k)), bits(plain));
                }
            }
            refracted
        }
    }

    #[test]
    fn glass_and_metal_lobes_equal_the_scalar_samples_bit_for_bit() {
        let etas = vec![1.0 / 1.5, 1.5, 1.0, 1.0 / 2.4, 1.33];
        for refracted in on_every_lane_type(Compare(directions(4096), etas)) {
            assert!(
                refracted > 3000,
                "too few refractions to mean anything: {refracted}"
            );
        }
    }
}
