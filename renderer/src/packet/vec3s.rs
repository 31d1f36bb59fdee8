//! Sixteen 3D vectors as three lanes of coordinates.

use super::{FloatLanes, MaskLanes, WIDTH};
use glam::Vec3;
use std::ops::{Add, Mul, Neg, Sub};

/// [`WIDTH`](crate::simd::WIDTH) vectors, one per lane: their x, y and z coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3s<F> {
    /// The lanes' x coordinates.
    pub x: F,
    /// The lanes' y coordinates.
    pub y: F,
    /// The lanes' z coordinates.
    pub z: F,
}

impl<F: FloatLanes> Vec3s<F> {
    /// Every lane zero.
    pub const ZERO: Self = Self {
        x: F::ZERO,
        y: F::ZERO,
        z: F::ZERO,
    };

    /// The vector with coordinates `x`, `y`, `z` lane by lane.
    #[inline(always)]
    pub fn new(x: F, y: F, z: F) -> Self {
        Self { x, y, z }
    }

    /// `v` in every lane.
    #[inline(always)]
    pub fn splat(v: Vec3) -> Self {
        Self::new(F::splat(v.x), F::splat(v.y), F::splat(v.z))
    }

    /// The lanes' vectors from sixteen `Vec3`s.
    #[inline(always)]
    pub fn from_lanes(lanes: &[Vec3; WIDTH]) -> Self {
        Self::new(
            F::from_array(std::array::from_fn::<f32, WIDTH, _>(|k| lanes[k].x)),
            F::from_array(std::array::from_fn::<f32, WIDTH, _>(|k| lanes[k].y)),
            F::from_array(std::array::from_fn::<f32, WIDTH, _>(|k| lanes[k].z)),
        )
    }

    /// The sixteen vectors as `Vec3`s.
    #[inline(always)]
    pub fn to_lanes(self) -> [Vec3; WIDTH] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|k| Vec3::new(x[k], y[k], z[k]))
    }

    /// The vector of lane `k`.
    #[inline(always)]
    pub fn lane(self, k: usize) -> Vec3 {
        Vec3::new(
            self.x.as_array()[k],
            self.y.as_array()[k],
            self.z.as_array()[k],
        )
    }

    /// Replaces lane `k`'s vector by `v`.
    #[inline(always)]
    pub fn set_lane(&mut self, k: usize, v: Vec3) {
        self.x.as_mut_array()[k] = v.x;
        self.y.as_mut_array()[k] = v.y;
        self.z.as_mut_array()[k] = v.z;
    }

    /// The dot product, lane by lane, summed x, then y, then z (as glam's `Vec3::dot`).
    #[inline(always)]
    pub fn dot(self, o: Self) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// The cross product, lane by lane (as glam's `Vec3::cross`).
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - o.y * self.z,
            self.z * o.x - o.z * self.x,
            self.x * o.y - o.x * self.y,
        )
    }

    /// The squared length, lane by lane.
    #[inline(always)]
    pub fn length_squared(self) -> F {
        self.dot(self)
    }

    /// The vector scaled to unit length (as glam's `Vec3::normalize`:
    /// multiplied by the reciprocal of the length).
    #[inline(always)]
    pub fn normalize(self) -> Self {
        self * (F::ONE / self.length_squared().sqrt())
    }

    /// Lane by lane, the product of the coordinates with `o`'s.
    #[inline(always)]
    pub fn mul_lanes(self, o: Self) -> Self {
        Self::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }

    /// The largest coordinate of each lane.
    #[inline(always)]
    pub fn max_element(self) -> F {
        self.x.max(self.y).max(self.z)
    }

    /// The coordinates' magnitudes.
    #[inline(always)]
    pub fn abs(self) -> Self {
        Self::new(self.x.abs(), self.y.abs(), self.z.abs())
    }

    /// The lanes whose vector is not zero (any coordinate ≠ 0, NaN
    /// included, as `Vec3 != Vec3::ZERO`).
    #[inline(always)]
    pub fn nonzero(self) -> F::Mask {
        self.x.simd_ne(F::ZERO) | self.y.simd_ne(F::ZERO) | self.z.simd_ne(F::ZERO)
    }

    /// Each coordinate divided by the lane's number (as `Vec3 / f32`).
    #[inline(always)]
    pub fn div_lanes(self, s: F) -> Self {
        Self::new(self.x / s, self.y / s, self.z / s)
    }

    /// Lane by lane, `self` where `mask` is set, `other` elsewhere.
    #[inline(always)]
    pub fn select(mask: F::Mask, a: Self, b: Self) -> Self {
        Self::new(
            mask.select(a.x, b.x),
            mask.select(a.y, b.y),
            mask.select(a.z, b.z),
        )
    }
}

impl<F: FloatLanes> Add for Vec3s<F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<F: FloatLanes> Sub for Vec3s<F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<F: FloatLanes> Neg for Vec3s<F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

/// Each lane's vector scaled by that lane's number.
impl<F: FloatLanes> Mul<F> for Vec3s<F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: F) -> Self {
        Vec3s::new(self.x * s, self.y * s, self.z * s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::{WithLanes, first_lanes, on_every_lane_type};

    fn sample_vectors(shift: f32) -> [Vec3; WIDTH] {
        std::array::from_fn(|k| {
            let k = k as f32 + shift;
            Vec3::new(0.3 * k - 1.0, 1.7 - 0.21 * k * k, 0.5 + 0.9 * k)
        })
    }

    #[derive(Clone)]
    struct LaneOperationsEqualGlams;

    impl WithLanes for LaneOperationsEqualGlams {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            let (a, b) = (sample_vectors(0.0), sample_vectors(0.37));
            let (pa, pb) = (Vec3s::<F>::from_lanes(&a), Vec3s::<F>::from_lanes(&b));
            let (dot, cross, norm) = (pa.dot(pb).to_array(), pa.cross(pb), pa.normalize());
            for k in 0..WIDTH {
                assert_eq!(dot[k].to_bits(), a[k].dot(b[k]).to_bits(), "dot, lane {k}");
                assert_eq!(cross.lane(k), a[k].cross(b[k]), "cross, lane {k}");
                assert_eq!(norm.lane(k), a[k].normalize(), "normalize, lane {k}");
                assert_eq!((pa - pb).lane(k), a[k] - b[k]);
                assert_eq!((pa * pb.x).lane(k), a[k] * b[k].x);
                assert_eq!(pa.div_lanes(pb.y).lane(k), a[k] / b[k].y);
                assert_eq!(pa.max_element().to_array()[k], a[k].max_element());
            }
            assert_eq!(pa.to_lanes(), a);
            let picked = Vec3s::select(first_lanes::<F>(2), pa, pb);
            for k in 0..WIDTH {
                assert_eq!(picked.lane(k), if k < 2 { a[k] } else { b[k] });
            }
        }
    }

    #[test]
    fn lane_operations_equal_glams_bit_for_bit_with_every_lane_type() {
        on_every_lane_type(LaneOperationsEqualGlams);
    }
}
