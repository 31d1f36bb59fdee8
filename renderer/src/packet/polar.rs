//! [`crate::geometry::polar`] and `geometry::warp::sin_cos_quarter` on
//! lanes, bit for bit: the same reductions and polynomials, each branch a
//! selection.

use crate::geometry::polar::{ATAN_TERMS, TAN_PI_8};
use crate::geometry::warp::{COS_TERMS, SIN_TERMS};
use crate::simd::{FloatLanes, MaskLanes};
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// atan2(y, x) in each lane, as [`crate::geometry::polar::atan2`] rounds it.
#[inline(always)]
pub fn atan2s<F: FloatLanes>(y: F, x: F) -> F {
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    let a = hi.simd_gt(F::ZERO).select(lo / hi, F::ZERO);
    let reduced = a.simd_gt(F::splat(TAN_PI_8));
    let b = reduced.select((a - F::ONE) / (a + F::ONE), a);
    let s = b * b;
    let p = F::splat(ATAN_TERMS[4]) + s * F::splat(ATAN_TERMS[5]);
    let p = F::splat(ATAN_TERMS[3]) + s * p;
    let p = F::splat(ATAN_TERMS[2]) + s * p;
    let p = F::splat(ATAN_TERMS[1]) + s * p;
    let p = F::splat(ATAN_TERMS[0]) + s * p;
    let r = b * p;
    let r = reduced.select(F::splat(FRAC_PI_4) + r, r);
    let r = ay.simd_gt(ax).select(F::splat(FRAC_PI_2) - r, r);
    let r = x.simd_lt(F::ZERO).select(F::splat(PI) - r, r);
    y.is_sign_negative().select(-r, r)
}

/// `geometry::warp::sin_cos_quarter` in each lane (|a| ≤ π/4).
#[inline(always)]
pub fn sin_cos_quarters<F: FloatLanes>(a: F) -> (F, F) {
    let x2 = a * a;
    let s = F::splat(SIN_TERMS[3]) + x2 * F::splat(SIN_TERMS[4]);
    let s = F::splat(SIN_TERMS[2]) + x2 * s;
    let s = F::splat(SIN_TERMS[1]) + x2 * s;
    let s = F::splat(SIN_TERMS[0]) + x2 * s;
    let c = F::splat(COS_TERMS[4]) + x2 * F::splat(COS_TERMS[5]);
    let c = F::splat(COS_TERMS[3]) + x2 * c;
    let c = F::splat(COS_TERMS[2]) + x2 * c;
    let c = F::splat(COS_TERMS[1]) + x2 * c;
    let c = F::splat(COS_TERMS[0]) + x2 * c;
    (a * s, c)
}

/// [`crate::geometry::polar::sin_cos_turns`] in each lane.
#[inline(always)]
pub fn sin_cos_turns_lanes<F: FloatLanes>(t: F) -> (F, F) {
    let quarters = F::splat(4.0) * t;
    let q = (quarters + F::splat(0.5)).floor();
    let (s, c) = sin_cos_quarters((quarters - q) * F::splat(FRAC_PI_2));
    let quadrant = q - F::splat(4.0) * (q * F::splat(0.25)).floor();
    let (one, two) = (quadrant.simd_eq(F::ONE), quadrant.simd_eq(F::splat(2.0)));
    let three = !quadrant.simd_eq(F::ZERO) & !one & !two;
    let sin = one.select(c, s);
    let sin = two.select(-s, sin);
    let sin = three.select(-c, sin);
    let cos = one.select(-s, c);
    let cos = two.select(-c, cos);
    let cos = three.select(s, cos);
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polar::{atan2, sin_cos_turns};
    use crate::simd::{WIDTH, WithLanes, on_every_lane_type};

    #[derive(Clone)]
    struct ArcTangents;

    impl WithLanes for ArcTangents {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            // Every octant, the axes, zeros of both signs, tiny and huge.
            let mut cases = vec![(0.0f32, 0.0f32), (-0.0, 0.0), (0.0, -0.0), (-0.0, -1.0)];
            for k in 0..4000 {
                let a = k as f32 * 0.0123 - 24.0;
                let l = [1e-30f32, 0.5, 3.0, 1e30][k % 4];
                cases.push((a.sin() * l, a.cos() * l));
            }
            cases.extend([(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0), (1.0, 1.0)]);
            for chunk in cases.chunks(WIDTH) {
                let mut y = [0.0; WIDTH];
                let mut x = [1.0; WIDTH];
                for (k, &(yk, xk)) in chunk.iter().enumerate() {
                    (y[k], x[k]) = (yk, xk);
                }
                let lanes = atan2s(F::from_array(y), F::from_array(x)).to_array();
                for k in 0..WIDTH {
                    let scalar = atan2(y[k], x[k]);
                    assert_eq!(
                        lanes[k].to_bits(),
                        scalar.to_bits(),
                        "atan2({}, {})",
                        y[k],
                        x[k]
                    );
                }
            }
        }
    }

    #[test]
    fn lanes_equal_the_scalar_arc_tangent_bit_for_bit() {
        on_every_lane_type(ArcTangents);
    }

    #[derive(Clone)]
    struct Turns;

    impl WithLanes for Turns {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            let ts: Vec<f32> = (0..4000)
                .map(|k| -2.0 + k as f32 * 0.001_1)
                .chain([0.0, -0.0, 0.125, 0.25, 0.375, 0.5, 0.75, 1.0, 0.999_999_9])
                .collect();
            for chunk in ts.chunks(WIDTH) {
                let mut t = [0.0; WIDTH];
                t[..chunk.len()].copy_from_slice(chunk);
                let (s, c) = sin_cos_turns_lanes(F::from_array(t));
                let (s, c) = (s.to_array(), c.to_array());
                for (k, &t) in t.iter().enumerate() {
                    let (ss, cs) = sin_cos_turns(t);
                    assert_eq!(s[k].to_bits(), ss.to_bits(), "sin of {t} turns");
                    assert_eq!(c[k].to_bits(), cs.to_bits(), "cos of {t} turns");
                }
            }
        }
    }

    #[test]
    fn lanes_equal_the_scalar_sine_and_cosine_of_turns_bit_for_bit() {
        on_every_lane_type(Turns);
    }
}
