//! [`FloatLanes`] in one AVX-512 register, for CPUs with AVX-512 F, BW and
//! DQ, chosen at run time by [`super::dispatch`].
//!
//! The operations are `std::arch` intrinsics, which are only sound on a CPU
//! that has the instructions. Soundness rests on one invariant: **a value
//! of [`Avx512`] or [`Avx512Ints`] only comes into existence on such a
//! CPU.** Values are made only by the trait's constructors, and those are
//! only reached through [`Avx512Token::run`], whose token exists only once
//! `is_x86_feature_detected!` has confirmed the three extensions (the
//! constants are plain bit patterns, made without any instruction). Every
//! `unsafe` block below relies on this.
//!
//! A mask is a mask register ([`Avx512Mask`], `__mmask16`): comparisons
//! write one and selections read one, with no conversion, and masks do not
//! take the vector registers the lanes' numbers need. (Until 2026-11-27
//! masks were vectors here too, widened by `vpmovm2d` and read back by
//! `vpmovd2m`; the path tracer's AVX-512 function held 69 of the latter.)
//!
//! Each operation is the AVX-512 form of the one [`super::avx2`] uses, so
//! all lane types give the same bits.

#![allow(unsafe_code)]

use super::x86_methods::{
    x86_abs, x86_comparisons, x86_is_finite, x86_is_nan, x86_max_min, x86_neg_not,
};
use super::{FloatLanes, IntLanes, MaskLanes, WIDTH, WithLanes};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

/// Proof that this CPU has AVX-512 F, BW and DQ: made only by
/// [`Avx512Token::detect`].
#[derive(Clone, Copy, Debug)]
pub struct Avx512Token(());

impl Avx512Token {
    /// The token, when this CPU has AVX-512 F, BW and DQ.
    #[inline]
    pub fn detect() -> Option<Self> {
        let has = is_x86_feature_detected!("avx512f")
            && is_x86_feature_detected!("avx512bw")
            && is_x86_feature_detected!("avx512dq");
        has.then_some(Self(()))
    }

    /// Runs `job` with [`Avx512`] lanes, compiled for AVX-512.
    #[inline]
    pub fn run<W: WithLanes>(self, job: W) -> W::Output {
        // SAFETY: the token exists, so this CPU has AVX-512 F, BW and DQ.
        unsafe { run_avx512(job) }
    }
}

/// `job` with AVX-512 lanes, in a function compiled for AVX-512 so that the
/// intrinsics inline into it.
#[target_feature(enable = "avx512f,avx512bw,avx512dq")]
fn run_avx512<W: WithLanes>(job: W) -> W::Output {
    job.run::<Avx512>()
}

/// Sixteen `f32`s in one AVX-512 register.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Avx512(__m512);

/// Sixteen `i32`s in one AVX-512 register.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Avx512Ints(__m512i);

/// A constant's bit pattern as lanes: no instruction runs.
const fn bits(x: f32) -> Avx512 {
    // SAFETY: `__m512` is sixteen `f32`s; any bit pattern is valid.
    Avx512(unsafe { std::mem::transmute::<[f32; WIDTH], __m512>([x; WIDTH]) })
}

impl PartialEq for Avx512 {
    fn eq(&self, o: &Self) -> bool {
        self.to_array() == o.to_array()
    }
}

impl PartialEq for Avx512Ints {
    fn eq(&self, o: &Self) -> bool {
        self.to_array() == o.to_array()
    }
}

/// Sixteen lane flags in a mask register: bit k for lane k. Plain bits (no
/// instruction is needed to make one), so any value is sound anywhere;
/// only the lane types' operations that take one need AVX-512.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(transparent)]
pub struct Avx512Mask(__mmask16);

macro_rules! mask_binary {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for Avx512Mask {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                Self(self.0 $op o.0)
            }
        }
    };
}

mask_binary!(BitAnd, bitand, &);
mask_binary!(BitOr, bitor, |);
mask_binary!(BitXor, bitxor, ^);

impl Not for Avx512Mask {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(!self.0)
    }
}

impl MaskLanes for Avx512Mask {
    const NONE: Self = Self(0);
    #[inline(always)]
    fn from_bitmask(bits: u32) -> Self {
        Self(bits as __mmask16)
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        u32::from(self.0)
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0 != 0
    }
    #[inline(always)]
    fn all(self) -> bool {
        self.0 == 0xffff
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for Avx512 {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                // SAFETY: an `Avx512` exists, so this CPU has AVX-512 (module invariant).
                Self(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}

binary!(Add, add, _mm512_add_ps);
binary!(Sub, sub, _mm512_sub_ps);
binary!(Mul, mul, _mm512_mul_ps);
binary!(Div, div, _mm512_div_ps);
binary!(BitAnd, bitand, _mm512_and_ps);
binary!(BitOr, bitor, _mm512_or_ps);
binary!(BitXor, bitxor, _mm512_xor_ps);

x86_neg_not!(Avx512);

impl Avx512 {
    /// The comparison `P` (a `_CMP_*` predicate) lane by lane, as a mask.
    #[inline(always)]
    fn compare<const P: i32>(self, o: Self) -> Avx512Mask {
        // SAFETY: module invariant.
        Avx512Mask(unsafe { _mm512_cmp_ps_mask::<P>(self.0, o.0) })
    }

    x86_is_nan!();
}

impl FloatLanes for Avx512 {
    type Ints = Avx512Ints;
    type Mask = Avx512Mask;
    const ZERO: Self = bits(0.0);
    const ONE: Self = bits(1.0);
    const INFINITY: Self = bits(f32::INFINITY);
    const NEG_INFINITY: Self = bits(f32::NEG_INFINITY);

    #[inline(always)]
    fn splat(x: f32) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_set1_ps(x) })
    }
    #[inline(always)]
    fn from_array(lanes: [f32; WIDTH]) -> Self {
        // SAFETY: module invariant; the load reads the sixteen `f32`s of `lanes`.
        Self(unsafe { _mm512_loadu_ps(lanes.as_ptr()) })
    }
    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        *self.as_array()
    }
    #[inline(always)]
    fn as_array(&self) -> &[f32; WIDTH] {
        // SAFETY: `Avx512` is a transparent `__m512`, sixteen `f32`s, and
        // the array's alignment (4) is less than the register's (64).
        unsafe { &*(self as *const Self).cast::<[f32; WIDTH]>() }
    }
    #[inline(always)]
    fn as_mut_array(&mut self) -> &mut [f32; WIDTH] {
        // SAFETY: as `as_array`; every bit pattern is a valid `f32`.
        unsafe { &mut *(self as *mut Self).cast::<[f32; WIDTH]>() }
    }
    x86_comparisons!();
    #[inline(always)]
    fn blend(mask: Avx512Mask, if_true: Self, if_false: Self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_mask_blend_ps(mask.0, if_false.0, if_true.0) })
    }
    x86_max_min!();
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_max_ps(self.0, o.0) })
    }
    #[inline(always)]
    fn fast_min(self, o: Self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_min_ps(self.0, o.0) })
    }
    x86_abs!();
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn floor(self) -> Self {
        // SAFETY: module invariant; scale 0 (whole numbers), rounding down.
        Self(unsafe {
            _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
    x86_is_finite!();
    #[inline(always)]
    fn is_sign_negative(self) -> Avx512Mask {
        // SAFETY: module invariant (AVX-512 DQ): each lane's sign bit.
        Avx512Mask(unsafe { _mm512_movepi32_mask(_mm512_castps_si512(self.0)) })
    }
    #[inline(always)]
    fn bits(self) -> Avx512Ints {
        // SAFETY: module invariant.
        Avx512Ints(unsafe { _mm512_castps_si512(self.0) })
    }
    #[inline(always)]
    fn trunc_to_ints(self) -> Avx512Ints {
        // SAFETY: module invariant.
        Avx512Ints(unsafe { _mm512_cvttps_epi32(self.0) })
    }
    #[inline(always)]
    fn gather_from(table: &[f32], index: Avx512Ints) -> Self {
        let last = super::last_index(table.len());
        // SAFETY: module invariant; the unsigned minimum keeps every index
        // in 0..=last, inside the table.
        Self(unsafe {
            let index = _mm512_min_epu32(index.0, _mm512_set1_epi32(last));
            _mm512_i32gather_ps::<4>(index, table.as_ptr())
        })
    }
}

/// Each 4-bit value with its bits in reverse order.
const NIBBLE_REVERSED: [u8; 16] = [
    0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf,
];

/// In each 16-byte block, the order that reverses each lane's four bytes.
const BYTE_ORDER: [u8; 16] = [3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12];

impl IntLanes for Avx512Ints {
    type Floats = Avx512;

    #[inline(always)]
    fn splat(x: i32) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_set1_epi32(x) })
    }
    #[inline(always)]
    fn from_array(lanes: [i32; WIDTH]) -> Self {
        // SAFETY: module invariant; the load reads the sixteen `i32`s of `lanes`.
        Self(unsafe { _mm512_loadu_si512(lanes.as_ptr().cast()) })
    }
    #[inline(always)]
    fn to_array(self) -> [i32; WIDTH] {
        // SAFETY: `__m512i` is 64 bytes; any bit pattern is a valid `[i32; 16]`.
        unsafe { std::mem::transmute::<__m512i, [i32; WIDTH]>(self.0) }
    }
    #[inline(always)]
    fn select(mask: Avx512Mask, if_true: Self, if_false: Self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_mask_blend_epi32(mask.0, if_false.0, if_true.0) })
    }
    #[inline(always)]
    fn simd_gt(self, o: Self) -> Avx512Mask {
        // SAFETY: module invariant.
        Avx512Mask(unsafe { _mm512_cmpgt_epi32_mask(self.0, o.0) })
    }
    #[inline(always)]
    fn shr<const N: i32>(self) -> Self {
        // SAFETY: module invariant.
        // (A shift by the splat of a constant compiles to the immediate form.)
        Self(unsafe { _mm512_srlv_epi32(self.0, _mm512_set1_epi32(N)) })
    }
    #[inline(always)]
    fn shl<const N: i32>(self) -> Self {
        // SAFETY: module invariant.
        Self(unsafe { _mm512_sllv_epi32(self.0, _mm512_set1_epi32(N)) })
    }
    #[inline(always)]
    fn to_floats(self) -> Avx512 {
        // SAFETY: module invariant.
        Avx512(unsafe { _mm512_cvtepi32_ps(self.0) })
    }
    #[inline(always)]
    fn bits_to_floats(self) -> Avx512 {
        // SAFETY: module invariant.
        Avx512(unsafe { _mm512_castsi512_ps(self.0) })
    }
    /// By byte shuffles: the lane's bytes in reverse order, then each
    /// byte's two nibbles reversed by table and swapped.
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        // SAFETY: module invariant (AVX-512 BW for the byte shuffles and
        // 16-bit shifts); the loads read the 16 bytes of each table.
        Self(unsafe {
            let byte_order = _mm512_broadcast_i32x4(_mm_loadu_si128(BYTE_ORDER.as_ptr().cast()));
            // A nibble's bits reversed, in every block, as a byte's low
            // nibble and (shifted; each byte is below 16) as its high one.
            let reversed_low =
                _mm512_broadcast_i32x4(_mm_loadu_si128(NIBBLE_REVERSED.as_ptr().cast()));
            let reversed_high = _mm512_slli_epi16::<4>(reversed_low);
            let nibble = _mm512_set1_epi8(0x0f);
            let bytes = _mm512_shuffle_epi8(self.0, byte_order);
            let low = _mm512_and_si512(bytes, nibble);
            let high = _mm512_and_si512(_mm512_srli_epi16::<4>(bytes), nibble);
            _mm512_or_si512(
                _mm512_shuffle_epi8(reversed_high, low),
                _mm512_shuffle_epi8(reversed_low, high),
            )
        })
    }
    #[inline(always)]
    fn gather<const N: usize>(table: &[i32; N], index: Self) -> Self {
        let mask = const { super::gather_mask::<N>() };
        // SAFETY: module invariant; every index is masked into 0..N, so
        // each lane reads one of the table's N `i32`s.
        Self(unsafe {
            let index = _mm512_and_si512(index.0, _mm512_set1_epi32(mask));
            _mm512_i32gather_epi32::<4>(index, table.as_ptr())
        })
    }
    #[inline(always)]
    fn gather_from(table: &[i32], index: Self) -> Self {
        let last = super::last_index(table.len());
        // SAFETY: module invariant; the unsigned minimum keeps every index
        // in 0..=last, inside the table.
        Self(unsafe {
            let index = _mm512_min_epu32(index.0, _mm512_set1_epi32(last));
            _mm512_i32gather_epi32::<4>(index, table.as_ptr())
        })
    }
}

macro_rules! binary_ints {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for Avx512Ints {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                // SAFETY: module invariant.
                Self(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}

binary_ints!(Add, add, _mm512_add_epi32);
// The low 32 bits of each product (wrapping).
binary_ints!(Mul, mul, _mm512_mullo_epi32);
binary_ints!(BitAnd, bitand, _mm512_and_si512);
binary_ints!(BitOr, bitor, _mm512_or_si512);
binary_ints!(BitXor, bitxor, _mm512_xor_si512);
