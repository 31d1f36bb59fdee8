//! Angles of directions and directions of angles, in plain arithmetic: the
//! arc tangent of y / x by quadrant and a polynomial, and the sine and
//! cosine of a fraction of a turn. An environment map needs them for every
//! ray that leaves the scene and every direction drawn from it; the library
//! `atan2f`, `acosf` and `sincosf` are a call each (a fifth of a
//! path-traced pass under a map), and spelled out here the wavefront
//! repeats them on SIMD lanes bit for bit.

use super::warp::sin_cos_quarter;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// tan(π/8): above it the arc tangent's argument is reduced by
/// atan a = π/4 + atan((a − 1)/(a + 1)).
pub(crate) const TAN_PI_8: f32 = 0.414_213_57;

/// atan(b) / b ≈ Σ ATAN_TERMS[k] · b^(2k) for |b| ≤ tan(π/8): a fit of
/// least maximum relative error (Lawson's iteration on 2,000 Chebyshev
/// nodes, in f64, rounded to f32). The f32 evaluation is within 1.02 ulp of
/// atan over the range (checked by a test against f64).
pub(crate) const ATAN_TERMS: [f32; 6] = [
    1.0,
    -0.333_333_08,
    0.199_982_37,
    -0.142_404_3,
    0.105_757_94,
    -0.060_401_864,
];

/// atan2(y, x): the angle of the point (x, y) from the +x axis, in
/// (−π, π], within a few ulp of the library's (a test bounds it against
/// f64). The ratio of the smaller to the larger coordinate is reduced to
/// |b| ≤ tan(π/8), its arc tangent is a polynomial, and the octant puts the
/// angle back. (0, 0) gives 0.
#[inline(always)]
pub fn atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    let a = if hi > 0.0 { lo / hi } else { 0.0 };
    let reduced = a > TAN_PI_8;
    let b = if reduced { (a - 1.0) / (a + 1.0) } else { a };
    let s = b * b;
    let p = ATAN_TERMS[4] + s * ATAN_TERMS[5];
    let p = ATAN_TERMS[3] + s * p;
    let p = ATAN_TERMS[2] + s * p;
    let p = ATAN_TERMS[1] + s * p;
    let p = ATAN_TERMS[0] + s * p;
    let r = b * p;
    let r = if reduced { FRAC_PI_4 + r } else { r };
    let r = if ay > ax { FRAC_PI_2 - r } else { r };
    let r = if x < 0.0 { PI - r } else { r };
    if y.is_sign_negative() { -r } else { r }
}

/// (sin 2πt, cos 2πt) for t in turns (any finite t; accurate for the
/// |t| ≲ 10³ an azimuth uses): the nearest quarter turn q = ⌊4t + ½⌋ is
/// taken off exactly, the rest (within ±π/4) goes through
/// [`sin_cos_quarter`], and q's quadrant (q mod 4, found in floats so that
/// lanes find it alike) swaps and signs the pair.
#[inline(always)]
pub fn sin_cos_turns(t: f32) -> (f32, f32) {
    let quarters = 4.0 * t;
    let q = (quarters + 0.5).floor();
    let (s, c) = sin_cos_quarter((quarters - q) * FRAC_PI_2);
    let quadrant = q - 4.0 * (q * 0.25).floor();
    if quadrant == 0.0 {
        (s, c)
    } else if quadrant == 1.0 {
        (c, -s)
    } else if quadrant == 2.0 {
        (-s, -c)
    } else {
        (-c, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance of `got` from the f64 value `want` in ulp of `want`'s
    /// f32 neighbourhood (at least the smallest normal's ulp).
    fn ulps(got: f32, want: f64) -> f64 {
        let ulp = f64::from(f32::EPSILON) * want.abs().max(f64::from(f32::MIN_POSITIVE));
        (f64::from(got) - want).abs() / ulp
    }

    #[test]
    fn the_arc_tangent_polynomial_is_within_one_ulp_over_its_range() {
        let n = 200_000;
        let mut worst = 0.0f64;
        for k in 1..=n {
            let b = TAN_PI_8 * k as f32 / n as f32;
            let s = b * b;
            let mut p = ATAN_TERMS[5];
            for &c in ATAN_TERMS[..5].iter().rev() {
                p = c + s * p;
            }
            worst = worst.max(ulps(b * p, f64::from(b).atan()));
        }
        assert!(worst <= 1.05, "{worst} ulp");
    }

    #[test]
    fn atan2_is_within_four_ulp_of_f64_all_around_the_circle() {
        // Angles of every size of coordinate, both signs, the axes and the
        // octant boundaries, and lengths from tiny to huge.
        let n = 100_000;
        let mut worst = 0.0f64;
        for k in 0..n {
            let angle =
                -std::f64::consts::PI + std::f64::consts::TAU * (k as f64 + 0.37) / n as f64;
            for length in [1e-30f64, 1e-3, 1.0, 7.5e4, 1e30] {
                let (y, x) = ((angle.sin() * length) as f32, (angle.cos() * length) as f32);
                let want = f64::from(y).atan2(f64::from(x));
                let got = atan2(y, x);
                // Near ±π both are right; compare on the circle.
                let diff = (f64::from(got) - want).abs();
                let diff = diff.min((diff - std::f64::consts::TAU).abs());
                let ulp = f64::from(f32::EPSILON) * want.abs().max(1e-30);
                worst = worst.max(diff / ulp);
            }
        }
        assert!(worst <= 4.0, "{worst} ulp");
        for (y, x, want) in [
            (0.0f32, 1.0f32, 0.0f32),
            (1.0, 0.0, FRAC_PI_2),
            (0.0, -1.0, PI),
            (-1.0, 0.0, -FRAC_PI_2),
            (1.0, 1.0, FRAC_PI_4),
            (-1.0, -1.0, -3.0 * FRAC_PI_4),
            (0.0, 0.0, 0.0),
        ] {
            assert!(
                (atan2(y, x) - want).abs() <= 2.0 * f32::EPSILON * want.abs(),
                "({y}, {x})"
            );
        }
    }

    #[test]
    fn sine_and_cosine_of_turns_are_within_three_ulp_of_f64() {
        let n = 100_000;
        for k in 0..=n {
            let t = -1.5 + 3.0 * k as f32 / n as f32;
            let (s, c) = sin_cos_turns(t);
            let (s64, c64) = (std::f64::consts::TAU * f64::from(t)).sin_cos();
            // Absolute: near a zero of either, a relative bound is meaningless.
            assert!(
                (f64::from(s) - s64).abs() <= 3.0 * f64::from(f32::EPSILON),
                "sin of {t} turns: {s} vs {s64}"
            );
            assert!(
                (f64::from(c) - c64).abs() <= 3.0 * f64::from(f32::EPSILON),
                "cos of {t} turns: {c} vs {c64}"
            );
        }
    }
}
