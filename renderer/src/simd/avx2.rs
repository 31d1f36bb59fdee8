//! [`FloatLanes`] in two AVX registers (eight lanes each), for CPUs with
//! AVX2, chosen at run time by [`super::dispatch`].
//!
//! The operations are `std::arch` intrinsics, which are only sound on a CPU
//! that has the instructions. Soundness rests on one invariant: **a value
//! of [`Avx2`] or [`Avx2Ints`] only comes into existence on such a CPU.**
//! Values are made only by the trait's constructors, and those are only
//! reached through [`Avx2Token::run`], whose token exists only once
//! `is_x86_feature_detected!` has confirmed AVX2 (the constants are plain
//! bit patterns, made without any instruction). Every `unsafe` block below
//! relies on this.
//!
//! Each operation is the AVX form of the one `wide` uses for SSE, applied
//! to each half, so all lane types give the same bits.

#![allow(unsafe_code)]

use super::x86_methods::{
    x86_abs, x86_comparisons, x86_is_finite, x86_is_nan, x86_max_min, x86_neg_not,
};
use super::{FloatLanes, IntLanes, MaskLanes, WIDTH, WithLanes};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

/// Proof that this CPU has AVX2: made only by [`Avx2Token::detect`].
#[derive(Clone, Copy, Debug)]
pub struct Avx2Token(());

impl Avx2Token {
    /// The token, when this CPU has AVX2.
    #[inline]
    pub fn detect() -> Option<Self> {
        is_x86_feature_detected!("avx2").then_some(Self(()))
    }

    /// Runs `job` with [`Avx2`] lanes, compiled for AVX2.
    #[inline]
    pub fn run<W: WithLanes>(self, job: W) -> W::Output {
        // SAFETY: the token exists, so this CPU has AVX2.
        unsafe { run_avx2(job) }
    }
}

/// `job` with AVX2 lanes, in a function compiled for AVX2 so that the
/// intrinsics inline into it.
#[target_feature(enable = "avx2")]
fn run_avx2<W: WithLanes>(job: W) -> W::Output {
    job.run::<Avx2>()
}

/// Sixteen `f32`s in two AVX registers, lanes 0–7 in the first.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Avx2([__m256; 2]);

/// Sixteen `i32`s in two AVX registers, lanes 0–7 in the first.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Avx2Ints([__m256i; 2]);

/// `$body` once per register: for each half, `$x` (and `$y`) bound to that
/// half of `$a` (and `$b`); the two results as the halves of an array.
macro_rules! per_half {
    ($x:ident = $a:expr; $body:expr) => {{
        let a = $a;
        [
            {
                let $x = a[0];
                $body
            },
            {
                let $x = a[1];
                $body
            },
        ]
    }};
    ($x:ident = $a:expr, $y:ident = $b:expr; $body:expr) => {{
        let (a, b) = ($a, $b);
        [
            {
                let ($x, $y) = (a[0], b[0]);
                $body
            },
            {
                let ($x, $y) = (a[1], b[1]);
                $body
            },
        ]
    }};
}

/// A constant's bit pattern as lanes: no instruction runs.
const fn bits(x: f32) -> Avx2 {
    // SAFETY: `[__m256; 2]` is sixteen `f32`s; any bit pattern is valid.
    Avx2(unsafe { std::mem::transmute::<[f32; WIDTH], [__m256; 2]>([x; WIDTH]) })
}

impl PartialEq for Avx2 {
    fn eq(&self, o: &Self) -> bool {
        self.to_array() == o.to_array()
    }
}

impl PartialEq for Avx2Ints {
    fn eq(&self, o: &Self) -> bool {
        self.to_array() == o.to_array()
    }
}

macro_rules! binary {
    ($lanes:ident, $trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for $lanes {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                // SAFETY: the lanes exist, so this CPU has AVX2 (module invariant).
                Self(per_half!(x = self.0, y = o.0; unsafe { $intrinsic(x, y) }))
            }
        }
    };
}

binary!(Avx2, Add, add, _mm256_add_ps);
binary!(Avx2, Sub, sub, _mm256_sub_ps);
binary!(Avx2, Mul, mul, _mm256_mul_ps);
binary!(Avx2, Div, div, _mm256_div_ps);
binary!(Avx2, BitAnd, bitand, _mm256_and_ps);
binary!(Avx2, BitOr, bitor, _mm256_or_ps);
binary!(Avx2, BitXor, bitxor, _mm256_xor_ps);
binary!(Avx2Ints, Add, add, _mm256_add_epi32);
// The low 32 bits of each product (wrapping).
binary!(Avx2Ints, Mul, mul, _mm256_mullo_epi32);
binary!(Avx2Ints, BitAnd, bitand, _mm256_and_si256);
binary!(Avx2Ints, BitOr, bitor, _mm256_or_si256);
binary!(Avx2Ints, BitXor, bitxor, _mm256_xor_si256);

x86_neg_not!(Avx2);

impl Avx2 {
    /// The comparison `P` (a `_CMP_*` predicate) lane by lane.
    #[inline(always)]
    fn compare<const P: i32>(self, o: Self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0, y = o.0; unsafe { _mm256_cmp_ps::<P>(x, y) }))
    }

    x86_is_nan!();
}

/// A mask of [`Avx2`] lanes is the vector itself: all bits set in a lane
/// that is set (what `blendvps` and `movemask` read).
impl MaskLanes for Avx2 {
    const NONE: Self = bits(0.0);
    #[inline(always)]
    fn from_bitmask(bits: u32) -> Self {
        // Lane k keeps bit k of the splatted bits and compares it with
        // itself. (Written out, not through a closure: a closure might not
        // be inlined into the AVX2 function, and each intrinsic would be a call.)
        // SAFETY: module invariant.
        Self(unsafe {
            let splat = _mm256_set1_epi32(bits as i32);
            let low = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let high = _mm256_slli_epi32::<8>(low);
            [
                _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(splat, low), low)),
                _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(splat, high), high)),
            ]
        })
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        // SAFETY: module invariant.
        let [low, high] = per_half!(x = self.0; unsafe { _mm256_movemask_ps(x) as u32 });
        low | high << 8
    }
    #[inline(always)]
    fn any(self) -> bool {
        // A sign bit set in either half: one movemask of their union.
        // SAFETY: module invariant.
        unsafe { _mm256_movemask_ps(_mm256_or_ps(self.0[0], self.0[1])) != 0 }
    }
    #[inline(always)]
    fn all(self) -> bool {
        // SAFETY: module invariant.
        unsafe { _mm256_movemask_ps(_mm256_and_ps(self.0[0], self.0[1])) == 0xff }
    }
}

impl FloatLanes for Avx2 {
    type Ints = Avx2Ints;
    type Mask = Avx2;
    const ZERO: Self = bits(0.0);
    const ONE: Self = bits(1.0);
    const INFINITY: Self = bits(f32::INFINITY);
    const NEG_INFINITY: Self = bits(f32::NEG_INFINITY);

    #[inline(always)]
    fn splat(x: f32) -> Self {
        // SAFETY: module invariant.
        let half = unsafe { _mm256_set1_ps(x) };
        Self([half, half])
    }
    #[inline(always)]
    fn from_array(lanes: [f32; WIDTH]) -> Self {
        // SAFETY: module invariant; the loads read lanes 0–7 and 8–15 of `lanes`.
        Self(unsafe {
            [
                _mm256_loadu_ps(lanes.as_ptr()),
                _mm256_loadu_ps(lanes.as_ptr().add(8)),
            ]
        })
    }
    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        *self.as_array()
    }
    #[inline(always)]
    fn as_array(&self) -> &[f32; WIDTH] {
        // SAFETY: `Avx2` is a transparent `[__m256; 2]`, sixteen `f32`s in
        // lane order, and the array's alignment (4) is less than its (32).
        unsafe { &*(self as *const Self).cast::<[f32; WIDTH]>() }
    }
    #[inline(always)]
    fn as_mut_array(&mut self) -> &mut [f32; WIDTH] {
        // SAFETY: as `as_array`; every bit pattern is a valid `f32`.
        unsafe { &mut *(self as *mut Self).cast::<[f32; WIDTH]>() }
    }
    x86_comparisons!();
    #[inline(always)]
    fn blend(mask: Self, if_true: Self, if_false: Self) -> Self {
        let (t, f) = (if_true.0, if_false.0);
        // SAFETY: module invariant.
        Self(unsafe {
            [
                _mm256_blendv_ps(f[0], t[0], mask.0[0]),
                _mm256_blendv_ps(f[1], t[1], mask.0[1]),
            ]
        })
    }
    x86_max_min!();
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0, y = o.0; unsafe { _mm256_max_ps(x, y) }))
    }
    #[inline(always)]
    fn fast_min(self, o: Self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0, y = o.0; unsafe { _mm256_min_ps(x, y) }))
    }
    x86_abs!();
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0; unsafe { _mm256_sqrt_ps(x) }))
    }
    #[inline(always)]
    fn floor(self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0; unsafe {
            _mm256_round_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(x)
        }))
    }
    x86_is_finite!();
    #[inline(always)]
    fn is_sign_negative(self) -> Self {
        // SAFETY: module invariant; an arithmetic shift copies the sign bit over the lane.
        Self(per_half!(x = self.0; unsafe {
            _mm256_castsi256_ps(_mm256_srai_epi32::<31>(_mm256_castps_si256(x)))
        }))
    }
    #[inline(always)]
    fn bits(self) -> Avx2Ints {
        // SAFETY: module invariant.
        Avx2Ints(per_half!(x = self.0; unsafe { _mm256_castps_si256(x) }))
    }
    #[inline(always)]
    fn trunc_to_ints(self) -> Avx2Ints {
        // SAFETY: module invariant.
        Avx2Ints(per_half!(x = self.0; unsafe { _mm256_cvttps_epi32(x) }))
    }
    #[inline(always)]
    fn gather_from(table: &[f32], index: Avx2Ints) -> Self {
        let last = super::last_index(table.len());
        // SAFETY: module invariant; the unsigned minimum keeps every index
        // in 0..=last, inside the table.
        Self(per_half!(i = index.0; unsafe {
            let i = _mm256_min_epu32(i, _mm256_set1_epi32(last));
            _mm256_i32gather_ps::<4>(table.as_ptr(), i)
        }))
    }
}

/// Each 4-bit value with its bits in reverse order.
const NIBBLE_REVERSED: [u8; 16] = [
    0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf,
];

impl IntLanes for Avx2Ints {
    type Floats = Avx2;

    #[inline(always)]
    fn splat(x: i32) -> Self {
        // SAFETY: module invariant.
        let half = unsafe { _mm256_set1_epi32(x) };
        Self([half, half])
    }
    #[inline(always)]
    fn from_array(lanes: [i32; WIDTH]) -> Self {
        // SAFETY: module invariant; the loads read lanes 0–7 and 8–15 of `lanes`.
        Self(unsafe {
            [
                _mm256_loadu_si256(lanes.as_ptr().cast()),
                _mm256_loadu_si256(lanes.as_ptr().add(8).cast()),
            ]
        })
    }
    #[inline(always)]
    fn to_array(self) -> [i32; WIDTH] {
        // SAFETY: `[__m256i; 2]` is 64 bytes; any bit pattern is a valid `[i32; 16]`.
        unsafe { std::mem::transmute::<[__m256i; 2], [i32; WIDTH]>(self.0) }
    }
    #[inline(always)]
    fn select(mask: Avx2, if_true: Self, if_false: Self) -> Self {
        Avx2Ints::from_floats(Avx2::blend(mask, if_true.floats(), if_false.floats()))
    }
    #[inline(always)]
    fn simd_gt(self, o: Self) -> Avx2 {
        // SAFETY: module invariant.
        Avx2(per_half!(x = self.0, y = o.0; unsafe {
            _mm256_castsi256_ps(_mm256_cmpgt_epi32(x, y))
        }))
    }
    #[inline(always)]
    fn shr<const N: i32>(self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0; unsafe { _mm256_srli_epi32::<N>(x) }))
    }
    #[inline(always)]
    fn shl<const N: i32>(self) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = self.0; unsafe { _mm256_slli_epi32::<N>(x) }))
    }
    #[inline(always)]
    fn to_floats(self) -> Avx2 {
        // SAFETY: module invariant.
        Avx2(per_half!(x = self.0; unsafe { _mm256_cvtepi32_ps(x) }))
    }
    #[inline(always)]
    fn bits_to_floats(self) -> Avx2 {
        self.floats()
    }
    /// By byte shuffles: the lane's bytes in reverse order, then each
    /// byte's two nibbles reversed by table and swapped.
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        // SAFETY: module invariant; the load reads the 16 bytes of `NIBBLE_REVERSED`.
        Self(unsafe {
            let byte_order = _mm256_setr_epi8(
                3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, //
                3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12,
            );
            // A nibble's bits reversed, in both halves, as a byte's low
            // nibble and (shifted; each byte is below 16) as its high one.
            let reversed_low =
                _mm256_broadcastsi128_si256(_mm_loadu_si128(NIBBLE_REVERSED.as_ptr().cast()));
            let reversed_high = _mm256_slli_epi16::<4>(reversed_low);
            let nibble = _mm256_set1_epi8(0x0f);
            per_half!(x = self.0; {
                let bytes = _mm256_shuffle_epi8(x, byte_order);
                let low = _mm256_and_si256(bytes, nibble);
                let high = _mm256_and_si256(_mm256_srli_epi16::<4>(bytes), nibble);
                _mm256_or_si256(
                    _mm256_shuffle_epi8(reversed_high, low),
                    _mm256_shuffle_epi8(reversed_low, high),
                )
            })
        })
    }
    #[inline(always)]
    fn gather<const N: usize>(table: &[i32; N], index: Self) -> Self {
        let mask = const { super::gather_mask::<N>() };
        // SAFETY: module invariant; every index is masked into 0..N, so
        // each lane reads one of the table's N `i32`s.
        Self(per_half!(i = index.0; unsafe {
            let i = _mm256_and_si256(i, _mm256_set1_epi32(mask));
            _mm256_i32gather_epi32::<4>(table.as_ptr(), i)
        }))
    }
    #[inline(always)]
    fn gather_from(table: &[i32], index: Self) -> Self {
        let last = super::last_index(table.len());
        // SAFETY: module invariant; the unsigned minimum keeps every index
        // in 0..=last, inside the table.
        Self(per_half!(i = index.0; unsafe {
            let i = _mm256_min_epu32(i, _mm256_set1_epi32(last));
            _mm256_i32gather_epi32::<4>(table.as_ptr(), i)
        }))
    }
}

impl Avx2Ints {
    /// The same bits as `f32` lanes.
    #[inline(always)]
    fn floats(self) -> Avx2 {
        // SAFETY: module invariant.
        Avx2(per_half!(x = self.0; unsafe { _mm256_castsi256_ps(x) }))
    }

    /// The same bits as `i32` lanes.
    #[inline(always)]
    fn from_floats(lanes: Avx2) -> Self {
        // SAFETY: module invariant.
        Self(per_half!(x = lanes.0; unsafe { _mm256_castps_si256(x) }))
    }
}
