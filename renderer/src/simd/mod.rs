//! The sixteen-lane number types the packet code is written over, and the
//! choice among them at run time.
//!
//! [`FloatLanes`] is what the packet code needs of [`WIDTH`] `f32`s:
//! arithmetic, comparisons giving masks ([`MaskLanes`]: one flag per lane)
//! and selection by mask. Three types implement it:
//!
//! - [`Portable`], `wide`'s `f32x16`, which compiles for whatever the build
//!   targets (four SSE registers on baseline x86-64);
//! - on x86-64, [`avx2::Avx2`], two AVX registers, usable only on a CPU
//!   that has AVX2;
//! - on x86-64, [`avx512::Avx512`], one AVX-512 register, usable only on a
//!   CPU that has AVX-512 F, BW and DQ.
//!
//! [`dispatch`] runs a computation with the widest one this CPU has (or a
//! narrower one named by `RAYLAB_LANES`, see [`LaneType::chosen`]).
//!
//! All implement every operation as the same IEEE operation lane by lane
//! (no fused multiply–add), so they give the same bits, and a test holds
//! them to it: an image does not depend on the CPU it was rendered on.

#[cfg(target_arch = "x86_64")]
pub mod avx2;
#[cfg(target_arch = "x86_64")]
pub mod avx512;
mod lane_type;
mod portable;
#[cfg(target_arch = "x86_64")]
mod x86_methods;

pub use lane_type::LaneType;

pub use portable::Portable;

use std::fmt::Debug;
use std::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

/// Lanes in a packet.
pub const WIDTH: usize = 16;

/// [`WIDTH`] flags, one per lane: where a comparison held. Each lane type
/// keeps them its own way: the portable and AVX2 types as vectors (all
/// bits set in a lane that is set), AVX-512 in a mask register
/// (`__mmask16`), so that its comparisons and selections need no
/// conversion and masks do not take vector registers.
pub trait MaskLanes:
    Copy
    + Debug
    + Send
    + Sync
    + 'static
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
    + Not<Output = Self>
{
    /// No lane set.
    const NONE: Self;
    /// The mask with lane k set where bit k of `bits` is.
    fn from_bitmask(bits: u32) -> Self;
    /// Bit k set where lane k is.
    fn to_bitmask(self) -> u32;
    /// Whether any lane is set.
    fn any(self) -> bool;
    /// Whether every lane is set.
    fn all(self) -> bool;
    /// The mask `if_true` in the lanes set, `if_false` elsewhere.
    #[inline(always)]
    fn select_mask(self, if_true: Self, if_false: Self) -> Self {
        (self & if_true) | (!self & if_false)
    }
    /// `if_true` in the lanes set, `if_false` elsewhere.
    #[inline(always)]
    fn select<F: FloatLanes<Mask = Self>>(self, if_true: F, if_false: F) -> F {
        F::blend(self, if_true, if_false)
    }
}

/// [`WIDTH`] `f32`s, one per lane.
pub trait FloatLanes:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
    + Not<Output = Self>
{
    /// [`WIDTH`] `i32`s of the same instruction set.
    type Ints: IntLanes<Floats = Self>;
    /// The masks that this type's comparisons give and its selections take.
    type Mask: MaskLanes;

    /// Zero in every lane.
    const ZERO: Self;
    /// One in every lane.
    const ONE: Self;
    /// +∞ in every lane.
    const INFINITY: Self;
    /// −∞ in every lane.
    const NEG_INFINITY: Self;

    /// `x` in every lane.
    fn splat(x: f32) -> Self;
    /// The lanes from an array, lane k from element k.
    fn from_array(lanes: [f32; WIDTH]) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [f32; WIDTH];
    /// The lanes as an array, borrowed.
    fn as_array(&self) -> &[f32; WIDTH];
    /// The lanes as an array, to change in place.
    fn as_mut_array(&mut self) -> &mut [f32; WIDTH];

    /// Mask of `self < o`.
    fn simd_lt(self, o: Self) -> Self::Mask;
    /// Mask of `self <= o`.
    fn simd_le(self, o: Self) -> Self::Mask;
    /// Mask of `self > o`.
    fn simd_gt(self, o: Self) -> Self::Mask;
    /// Mask of `self >= o`.
    fn simd_ge(self, o: Self) -> Self::Mask;
    /// Mask of `self == o`.
    fn simd_eq(self, o: Self) -> Self::Mask;
    /// Mask of `self != o` (true where either is NaN).
    fn simd_ne(self, o: Self) -> Self::Mask;

    /// `if_true` in the lanes of `mask`, `if_false` elsewhere (what
    /// [`MaskLanes::select`] calls).
    fn blend(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;

    /// The larger of each pair, a NaN ignored (as `f32::max`; of +0 and
    /// −0, either may come back).
    fn max(self, o: Self) -> Self;
    /// The smaller of each pair, a NaN ignored (as `f32::min`; of +0 and
    /// −0, either may come back).
    fn min(self, o: Self) -> Self;
    /// `o < self ? self : o` (`maxps`: `o` where either is NaN).
    fn fast_max(self, o: Self) -> Self;
    /// `self < o ? self : o` (`minps`: `o` where either is NaN).
    fn fast_min(self, o: Self) -> Self;
    /// Magnitudes.
    fn abs(self) -> Self;
    /// Correctly rounded square roots.
    fn sqrt(self) -> Self;
    /// Rounded down to integers.
    fn floor(self) -> Self;
    /// Mask of the finite lanes.
    fn is_finite(self) -> Self::Mask;
    /// Mask of the lanes whose sign bit is set (−0 included).
    fn is_sign_negative(self) -> Self::Mask;
    /// The same bits read as `i32`s.
    fn bits(self) -> Self::Ints;
    /// Converted to `i32`, rounded toward zero (`cvttps`: `i32::MIN` in
    /// lanes that are NaN or out of `i32`'s range).
    fn trunc_to_ints(self) -> Self::Ints;
    /// Lane k is `table[min(index_k, len − 1)]`, the index read as a `u32`
    /// (so −1 reads the last entry): no index reads outside the table.
    /// Panics when `table` is empty.
    fn gather_from(table: &[f32], index: Self::Ints) -> Self;
}

/// [`WIDTH`] `i32`s, one per lane (object ids, counters, and as `u32` bits the
/// hashes of the random streams: `+`, `*` and the shifts wrap and treat
/// the lanes as unsigned).
pub trait IntLanes:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Mul<Output = Self>
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
{
    /// The `f32` lanes of the same instruction set, whose masks select these.
    type Floats: FloatLanes<Ints = Self>;

    /// `x` in every lane.
    fn splat(x: i32) -> Self;
    /// The lanes from an array.
    fn from_array(lanes: [i32; WIDTH]) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [i32; WIDTH];
    /// `if_true` where `mask` is set, `if_false` elsewhere.
    fn select(mask: Mask<Self::Floats>, if_true: Self, if_false: Self) -> Self;
    /// Mask of `self > o`.
    fn simd_gt(self, o: Self) -> Mask<Self::Floats>;
    /// Shifted right by `N` bits, zeros shifted in (as `u32 >> N`).
    fn shr<const N: i32>(self) -> Self;
    /// Shifted left by `N` bits.
    fn shl<const N: i32>(self) -> Self;
    /// Converted to `f32`, rounded to nearest (exact below 2^24).
    fn to_floats(self) -> Self::Floats;
    /// The same bits read as `f32`s.
    fn bits_to_floats(self) -> Self::Floats;
    /// Each lane's bits in reverse order (`u32::reverse_bits`).
    fn reverse_bits(self) -> Self;
    /// Lane k is `table[index_k mod N]`: the index's low bits, so that any
    /// index reads inside the table (`N` a power of two).
    fn gather<const N: usize>(table: &[i32; N], index: Self) -> Self;
    /// Lane k is `table[min(index_k, len − 1)]`, the index read as a `u32`
    /// (so −1 reads the last entry): no index reads outside the table.
    /// Panics when `table` is empty.
    fn gather_from(table: &[i32], index: Self) -> Self;
}

/// The last index [`FloatLanes::gather_from`] and [`IntLanes::gather_from`]
/// may read in a table of `len` entries, as the `i32` a gather takes
/// (tables past `i32::MAX` entries are read in their first 2³¹); panics
/// when the table is empty.
#[inline(always)]
pub(crate) fn last_index(len: usize) -> i32 {
    assert!(len > 0, "a gather needs a table to read");
    (len - 1).min(i32::MAX as usize) as i32
}

/// `N − 1`, the mask [`IntLanes::gather`] keeps an index in `table[N]` with;
/// a compile-time error unless `N` is a power of two that `i32` holds.
pub(crate) const fn gather_mask<const N: usize>() -> i32 {
    assert!(N.is_power_of_two() && N <= i32::MAX as usize);
    (N - 1) as i32
}

/// A computation over lanes of any [`FloatLanes`] type, run by
/// [`dispatch`] with the widest this CPU has.
pub trait WithLanes {
    /// What it returns.
    type Output;
    /// Runs it with lanes `F`. Written `#[inline(always)]`, with everything
    /// it calls, so that it is compiled inside [`dispatch`]'s AVX2 or
    /// AVX-512 function.
    fn run<F: FloatLanes>(self) -> Self::Output;
}

/// Runs `job` with the lanes of [`LaneType::chosen`]: the widest this CPU
/// has, unless `RAYLAB_LANES` names a narrower one. All give the same
/// results bit for bit.
#[inline]
pub fn dispatch<W: WithLanes>(job: W) -> W::Output {
    LaneType::chosen().run(job)
}

/// Runs `job` with [`Portable`] lanes whatever the CPU (for tests and
/// measurements of the fallback).
pub fn run_portable<W: WithLanes>(job: W) -> W::Output {
    job.run::<Portable>()
}

/// `job` run with every lane type this CPU has, narrowest first.
#[cfg(test)]
pub(crate) fn on_every_lane_type<W: WithLanes + Clone>(job: W) -> Vec<W::Output> {
    LaneType::available()
        .into_iter()
        .map(|lanes| lanes.run(job.clone()))
        .collect()
}

/// The masks of lanes `F`.
pub type Mask<F> = <F as FloatLanes>::Mask;

/// The mask set in the lanes `k` where `f(k)` holds.
#[inline(always)]
pub fn mask_from<F: FloatLanes>(f: impl Fn(usize) -> bool) -> F::Mask {
    let bits = (0..WIDTH).fold(0u32, |bits, k| bits | (u32::from(f(k)) << k));
    F::Mask::from_bitmask(bits)
}

/// True in the lanes `0..n`: the live lanes of a packet holding `n` items.
#[inline(always)]
pub fn first_lanes<F: FloatLanes>(n: usize) -> F::Mask {
    mask_from::<F>(|k| k < n)
}

/// Whether lane `k` of `mask` is set.
#[inline(always)]
pub fn lane_set<M: MaskLanes>(mask: M, k: usize) -> bool {
    mask.to_bitmask() & (1 << k) != 0
}

#[cfg(test)]
mod tests;
