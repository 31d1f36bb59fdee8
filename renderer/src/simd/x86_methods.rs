//! [`super::FloatLanes`] methods (and `Neg`, `Not`) that the x86 lane types ([`super::avx2`],
//! [`super::avx512`]) write the same way from their own `compare::<P>` (a
//! `_CMP_*` predicate giving a mask), `is_nan`, `fast_max`, `fast_min`,
//! `blend` and the constant `bits(x)`: one text, so the two cannot drift.
//! Invoked inside each type's `impl FloatLanes`, where those names resolve.

/// The six comparisons, as masks: ordered and quiet, but `!=`, which is
/// true where either side is NaN.
macro_rules! x86_comparisons {
    () => {
        #[inline(always)]
        fn simd_lt(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_LT_OQ>(o)
        }
        #[inline(always)]
        fn simd_le(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_LE_OQ>(o)
        }
        #[inline(always)]
        fn simd_gt(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_GT_OQ>(o)
        }
        #[inline(always)]
        fn simd_ge(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_GE_OQ>(o)
        }
        #[inline(always)]
        fn simd_eq(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_EQ_OQ>(o)
        }
        #[inline(always)]
        fn simd_ne(self, o: Self) -> Self::Mask {
            self.compare::<_CMP_NEQ_UQ>(o)
        }
    };
}

/// `max` and `min` as `f32::max` / `f32::min`: `maxps` / `minps` return
/// their second operand where either is NaN, so a NaN `o` gives `self`.
macro_rules! x86_max_min {
    () => {
        #[inline(always)]
        fn max(self, o: Self) -> Self {
            o.is_nan().select(self, self.fast_max(o))
        }
        #[inline(always)]
        fn min(self, o: Self) -> Self {
            o.is_nan().select(self, self.fast_min(o))
        }
    };
}

/// `abs`: the sign bit cleared.
macro_rules! x86_abs {
    () => {
        #[inline(always)]
        fn abs(self) -> Self {
            self & bits(f32::from_bits(i32::MAX as u32))
        }
    };
}

/// `is_finite`: |x| < ∞ is false for infinities and NaN alone.
macro_rules! x86_is_finite {
    () => {
        #[inline(always)]
        fn is_finite(self) -> Self::Mask {
            self.abs().simd_lt(Self::INFINITY)
        }
    };
}

/// `is_nan`, a mask of the NaN lanes (unordered with themselves), for the
/// type's inherent `impl`.
macro_rules! x86_is_nan {
    () => {
        /// Mask of the NaN lanes.
        #[inline(always)]
        fn is_nan(self) -> <Self as FloatLanes>::Mask {
            self.compare::<_CMP_UNORD_Q>(self)
        }
    };
}

/// `-x` (the sign bit flipped) and `!mask` (every bit flipped) for `$lanes`.
macro_rules! x86_neg_not {
    ($lanes:ident) => {
        impl Neg for $lanes {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                self ^ bits(-0.0)
            }
        }

        impl Not for $lanes {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                self ^ bits(f32::from_bits(u32::MAX))
            }
        }
    };
}

pub(super) use {x86_abs, x86_comparisons, x86_is_finite, x86_is_nan, x86_max_min, x86_neg_not};
