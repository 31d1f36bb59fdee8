//! Warping uniform numbers onto shapes: the maps that BSDF sampling and
//! light sampling on shapes share.

use glam::Vec2;
use std::f32::consts::FRAC_PI_4;

/// A point of the unit disk from [0, 1)², area-preserving (Shirley–Chiu's
/// concentric map). The angle φ = π/4 · ratio, or π/2 − π/4 · ratio, so its
/// sine and cosine come from [`sin_cos_quarter`] of π/4 · ratio (swapped
/// in the second case): plain arithmetic that the wavefront repeats on
/// SIMD lanes bit for bit, where a library `sinf` would be a call per lane.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let p = 2.0 * u - Vec2::ONE;
    if p == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, swapped, ratio) = if p.x.abs() > p.y.abs() {
        (p.x, false, p.y / p.x)
    } else {
        (p.y, true, p.x / p.y)
    };
    let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * ratio);
    if swapped {
        Vec2::new(r * sin, r * cos)
    } else {
        Vec2::new(r * cos, r * sin)
    }
}

/// Taylor coefficients of sin x / x in x²: 1, −1/3!, 1/5!, −1/7!, 1/9!.
pub(crate) const SIN_TERMS: [f32; 5] =
    [1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];
/// Taylor coefficients of cos x in x²: 1, −1/2!, 1/4!, …, −1/10!.
pub(crate) const COS_TERMS: [f32; 6] = [
    1.0,
    -0.5,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
];

/// (sin a, cos a) for |a| ≤ π/4, by the Taylor series to x⁹ and x¹⁰ in
/// Horner form (truncation below 2·10⁻⁹; within 2 ulp of the true values,
/// checked by a test against f64). The operations are spelled out so that
/// `wavefront`'s lane version rounds identically.
#[inline(always)]
pub fn sin_cos_quarter(a: f32) -> (f32, f32) {
    let x2 = a * a;
    let s = SIN_TERMS[3] + x2 * SIN_TERMS[4];
    let s = SIN_TERMS[2] + x2 * s;
    let s = SIN_TERMS[1] + x2 * s;
    let s = SIN_TERMS[0] + x2 * s;
    let c = COS_TERMS[4] + x2 * COS_TERMS[5];
    let c = COS_TERMS[3] + x2 * c;
    let c = COS_TERMS[2] + x2 * c;
    let c = COS_TERMS[1] + x2 * c;
    let c = COS_TERMS[0] + x2 * c;
    (a * s, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_quarter_is_within_two_ulp_of_f64_over_its_range() {
        let n = 100_000;
        for k in 0..=n {
            let a = std::f32::consts::FRAC_PI_4 * (2.0 * k as f32 / n as f32 - 1.0);
            let (s, c) = sin_cos_quarter(a);
            let (s64, c64) = f64::from(a).sin_cos();
            // An ulp of a value in [2^e, 2^(e+1)) is 2^e · ε; this bound of
            // 2 |x| ε is at least 2 ulp.
            let two_ulp = |x: f64| 2.0 * x.abs() * f64::from(f32::EPSILON);
            assert!(
                (f64::from(s) - s64).abs() <= two_ulp(s64),
                "sin {a}: {s} vs {s64}"
            );
            assert!(
                (f64::from(c) - c64).abs() <= two_ulp(c64),
                "cos {a}: {c} vs {c64}"
            );
        }
    }

    #[test]
    fn disk_points_keep_their_polar_angle_and_radius() {
        // The concentric map's own definition, in f64 with the library's
        // sine and cosine.
        for a in 0..64 {
            for b in 0..64 {
                let u = Vec2::new((a as f32 + 0.3) / 64.0, (b as f32 + 0.7) / 64.0);
                let (px, py) = (2.0 * f64::from(u.x) - 1.0, 2.0 * f64::from(u.y) - 1.0);
                let (r, phi) = if px.abs() > py.abs() {
                    (px, std::f64::consts::FRAC_PI_4 * (py / px))
                } else {
                    (
                        py,
                        std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (px / py),
                    )
                };
                let d = concentric_disk(u);
                assert!((f64::from(d.x) - r * phi.cos()).abs() < 1e-6, "{u}");
                assert!((f64::from(d.y) - r * phi.sin()).abs() < 1e-6, "{u}");
            }
        }
    }

    #[test]
    fn disk_points_stay_inside_the_unit_disk() {
        for a in 0..20 {
            for b in 0..20 {
                let u = Vec2::new(a as f32 / 20.0, b as f32 / 20.0);
                assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
            }
        }
    }
}
