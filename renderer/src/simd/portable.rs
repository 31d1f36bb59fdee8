//! [`FloatLanes`] by `wide`: whatever instructions the build targets.

use super::{FloatLanes, IntLanes, MaskLanes, WIDTH};
use wide::{f32x16, i32x16, u32x16};

/// Sixteen `f32`s as `wide::f32x16`: four SSE registers on baseline x86-64,
/// one AVX-512 register where the build enables AVX-512, plain arrays
/// elsewhere.
pub type Portable = f32x16;

/// A mask of [`Portable`] lanes is the vector itself: all bits set in a
/// lane that is set.
impl MaskLanes for f32x16 {
    const NONE: Self = f32x16::ZERO;
    #[inline(always)]
    fn from_bitmask(bits: u32) -> Self {
        f32x16::from(std::array::from_fn::<f32, WIDTH, _>(|k| {
            f32::from_bits(if bits & (1 << k) != 0 { u32::MAX } else { 0 })
        }))
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        f32x16::to_bitmask(self)
    }
    #[inline(always)]
    fn any(self) -> bool {
        f32x16::any(self)
    }
    #[inline(always)]
    fn all(self) -> bool {
        f32x16::all(self)
    }
}

impl FloatLanes for f32x16 {
    type Ints = i32x16;
    type Mask = f32x16;
    const ZERO: Self = f32x16::ZERO;
    const ONE: Self = f32x16::ONE;
    const INFINITY: Self = f32x16::INFINITY;
    const NEG_INFINITY: Self = f32x16::NEG_INFINITY;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        f32x16::splat(x)
    }
    #[inline(always)]
    fn from_array(lanes: [f32; WIDTH]) -> Self {
        f32x16::from(lanes)
    }
    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        f32x16::to_array(self)
    }
    #[inline(always)]
    fn as_array(&self) -> &[f32; WIDTH] {
        f32x16::as_array(self)
    }
    #[inline(always)]
    fn as_mut_array(&mut self) -> &mut [f32; WIDTH] {
        f32x16::as_mut_array(self)
    }
    #[inline(always)]
    fn simd_lt(self, o: Self) -> Self {
        f32x16::simd_lt(self, o)
    }
    #[inline(always)]
    fn simd_le(self, o: Self) -> Self {
        f32x16::simd_le(self, o)
    }
    #[inline(always)]
    fn simd_gt(self, o: Self) -> Self {
        f32x16::simd_gt(self, o)
    }
    #[inline(always)]
    fn simd_ge(self, o: Self) -> Self {
        f32x16::simd_ge(self, o)
    }
    #[inline(always)]
    fn simd_eq(self, o: Self) -> Self {
        f32x16::simd_eq(self, o)
    }
    #[inline(always)]
    fn simd_ne(self, o: Self) -> Self {
        f32x16::simd_ne(self, o)
    }
    #[inline(always)]
    fn blend(mask: Self, if_true: Self, if_false: Self) -> Self {
        f32x16::select(mask, if_true, if_false)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f32x16::max(self, o)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        f32x16::min(self, o)
    }
    #[inline(always)]
    fn fast_max(self, o: Self) -> Self {
        f32x16::fast_max(self, o)
    }
    #[inline(always)]
    fn fast_min(self, o: Self) -> Self {
        f32x16::fast_min(self, o)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32x16::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32x16::sqrt(self)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        f32x16::floor(self)
    }
    #[inline(always)]
    fn is_finite(self) -> Self {
        f32x16::is_finite(self)
    }
    #[inline(always)]
    fn is_sign_negative(self) -> Self {
        f32x16::is_sign_negative(self)
    }
    #[inline(always)]
    fn bits(self) -> i32x16 {
        wide::bytemuck::cast(self)
    }
    #[inline(always)]
    fn trunc_to_ints(self) -> i32x16 {
        f32x16::fast_trunc_int(self)
    }
    #[inline(always)]
    fn gather_from(table: &[f32], index: i32x16) -> Self {
        let last = super::last_index(table.len()) as u32;
        f32x16::from(i32x16::to_array(index).map(|k| table[(k as u32).min(last) as usize]))
    }
}

impl IntLanes for i32x16 {
    type Floats = f32x16;

    #[inline(always)]
    fn splat(x: i32) -> Self {
        i32x16::splat(x)
    }
    #[inline(always)]
    fn from_array(lanes: [i32; WIDTH]) -> Self {
        i32x16::from(lanes)
    }
    #[inline(always)]
    fn to_array(self) -> [i32; WIDTH] {
        i32x16::to_array(self)
    }
    #[inline(always)]
    fn select(mask: f32x16, if_true: Self, if_false: Self) -> Self {
        let m: i32x16 = wide::bytemuck::cast(mask);
        m.select(if_true, if_false)
    }
    #[inline(always)]
    fn simd_gt(self, o: Self) -> f32x16 {
        wide::bytemuck::cast(i32x16::simd_gt(self, o))
    }
    #[inline(always)]
    fn shr<const N: i32>(self) -> Self {
        let unsigned: u32x16 = wide::bytemuck::cast(self);
        wide::bytemuck::cast(unsigned >> N as u32)
    }
    #[inline(always)]
    fn shl<const N: i32>(self) -> Self {
        let unsigned: u32x16 = wide::bytemuck::cast(self);
        wide::bytemuck::cast(unsigned << N as u32)
    }
    #[inline(always)]
    fn to_floats(self) -> f32x16 {
        self.round_float()
    }
    #[inline(always)]
    fn bits_to_floats(self) -> f32x16 {
        wide::bytemuck::cast(self)
    }
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        let mut lanes = self.to_array();
        for lane in &mut lanes {
            *lane = lane.reverse_bits();
        }
        i32x16::from(lanes)
    }
    #[inline(always)]
    fn gather<const N: usize>(table: &[i32; N], index: Self) -> Self {
        let mask = const { super::gather_mask::<N>() };
        let mut lanes = i32x16::to_array(index);
        for lane in &mut lanes {
            *lane = table[(*lane & mask) as usize];
        }
        i32x16::from(lanes)
    }
    #[inline(always)]
    fn gather_from(table: &[i32], index: Self) -> Self {
        let last = super::last_index(table.len()) as u32;
        i32x16::from(i32x16::to_array(index).map(|k| table[(k as u32).min(last) as usize]))
    }
}
