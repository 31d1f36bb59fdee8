//! The pixel streams of eight samples at once, one per SIMD lane: each
//! lane's draw is [`PixelStream`]'s, computed with the same 32-bit integer
//! operations on all lanes together, so the numbers are the scalar
//! stream's bit for bit (a test holds them to it on both lane types).
//!
//! Write lane code here as `#[inline(always)]` functions (see
//! `integrator::wavefront`): they must compile inside the dispatched SIMD
//! function.

use super::{
    DIMENSION_KEYS, DIMENSION_SEED_FACTOR, GOLDEN, PASCAL_STEPS, PixelStream, SHUFFLE_KEY,
    SOBOL_DRAWS, SOBOL_LENGTH,
};
use crate::packet::{FloatLanes, IntLanes, MaskLanes, WIDTH};
use std::marker::PhantomData;

/// Eight pixel streams, one per lane: what their numbers are computed from,
/// kept as arrays (a lane is written alone when it starts a sample, and
/// read as a vector when the lanes draw). The lanes hold no draw counter:
/// the caller names each lane's draw.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StreamLanes<F: FloatLanes> {
    /// [`PixelStream::keys`] of each lane.
    keys: [[i32; WIDTH]; 2],
    /// [`PixelStream::pixel_key`] of each lane.
    pixel_key: [i32; WIDTH],
    /// [`PixelStream::index`] of each lane.
    index: [i32; WIDTH],
    /// Whether the streams draw Sobol points (the same for every lane).
    sobol: bool,
    lanes: PhantomData<F>,
}

impl<F: FloatLanes> StreamLanes<F> {
    /// Lanes of all-zero keys (dead lanes' numbers are never used).
    #[inline(always)]
    pub(crate) fn new() -> Self {
        Self {
            keys: [[0; WIDTH]; 2],
            pixel_key: [0; WIDTH],
            index: [0; WIDTH],
            sobol: false,
            lanes: PhantomData,
        }
    }

    /// Lane `lane` takes the stream `stream` (its draw counter aside).
    #[inline(always)]
    pub(crate) fn set(&mut self, lane: usize, stream: &PixelStream) {
        self.keys[0][lane] = stream.keys[0] as i32;
        self.keys[1][lane] = stream.keys[1] as i32;
        self.pixel_key[lane] = stream.pixel_key as i32;
        self.index[lane] = stream.index as i32;
        self.sobol = stream.sobol;
    }

    /// Lane `lane`'s stream, at draw 0.
    #[inline(always)]
    pub(crate) fn stream(&self, lane: usize) -> PixelStream {
        PixelStream {
            keys: [self.keys[0][lane] as u32, self.keys[1][lane] as u32],
            pixel_key: self.pixel_key[lane] as u32,
            index: self.index[lane] as u32,
            sobol: self.sobol,
            draw: 0,
        }
    }

    /// Both numbers of each lane's draw `draw` (`PixelStream::numbers`).
    /// `draw` is a small non-negative count in every lane.
    #[inline(always)]
    pub(crate) fn numbers(&self, draw: F::Ints) -> (F, F) {
        let [x, y] = self.draw::<2>(draw);
        (x, y)
    }

    /// The number of each lane's one-number draw `draw`.
    #[inline(always)]
    pub(crate) fn number(&self, draw: F::Ints) -> F {
        let [x] = self.draw::<1>(draw);
        x
    }

    /// The first `N` (1 or 2) numbers of each lane's draw `draw`: Sobol
    /// points where the stream draws them, independent numbers elsewhere
    /// (each computed only when some lane takes it).
    #[inline(always)]
    fn draw<const N: usize>(&self, draw: F::Ints) -> [F; N] {
        if !self.sobol {
            return self.independent::<N>(draw);
        }
        let sobol = F::Ints::splat(SOBOL_DRAWS as i32).simd_gt(draw);
        if !sobol.any() {
            return self.independent::<N>(draw);
        }
        let (pixel_key, index) = (
            F::Ints::from_array(self.pixel_key),
            F::Ints::from_array(self.index),
        );
        let mut points = owen_sobol::<F, N>(pixel_key, index, draw);
        if sobol.all() {
            return points;
        }
        let numbers = self.independent::<N>(draw);
        for (point, number) in points.iter_mut().zip(numbers) {
            *point = sobol.select(*point, number);
        }
        points
    }

    /// The first `N` numbers of each lane's independent draw `draw`.
    #[inline(always)]
    fn independent<const N: usize>(&self, draw: F::Ints) -> [F; N] {
        let n = draw.shl::<1>();
        let keys = [
            F::Ints::from_array(self.keys[0]),
            F::Ints::from_array(self.keys[1]),
        ];
        let mut numbers = [F::ZERO; N];
        for (c, number) in numbers.iter_mut().enumerate() {
            *number = uniform::<F>(independent_bits::<F>(keys, n + splat(c as u32)));
        }
        numbers
    }
}

/// [`super::lowbias32`] on lanes.
#[inline(always)]
fn lowbias32<I: IntLanes>(mut x: I) -> I {
    x = x ^ x.shr::<16>();
    x = x * I::splat(0x7feb_352d);
    x = x ^ x.shr::<15>();
    x = x * I::splat(0x846c_a68b_u32 as i32);
    x ^ x.shr::<16>()
}

/// [`super::independent_bits`] on lanes.
#[inline(always)]
fn independent_bits<F: FloatLanes>(keys: [F::Ints; 2], n: F::Ints) -> F::Ints {
    let golden = F::Ints::splat(GOLDEN as i32);
    lowbias32(keys[0] ^ lowbias32(keys[1] + n * golden))
}

/// [`super::uniform`] on lanes: the top 24 bits, exactly, times 2^−24.
#[inline(always)]
fn uniform<F: FloatLanes>(bits: F::Ints) -> F {
    bits.shr::<8>().to_floats() * F::splat(1.0 / 16_777_216.0)
}

/// `x` in every lane, as bits.
#[inline(always)]
fn splat<I: IntLanes>(x: u32) -> I {
    I::splat(x as i32)
}

/// [`super::pascal_mod2`] on lanes: the same steps, shift by shift.
#[inline(always)]
fn pascal_mod2<I: IntLanes>(mut x: I) -> I {
    const {
        let s = PASCAL_STEPS;
        assert!(s[0].0 == 1 && s[1].0 == 2 && s[2].0 == 4 && s[3].0 == 8);
    };
    x = x ^ (x.shr::<1>() & splat(PASCAL_STEPS[0].1));
    x = x ^ (x.shr::<2>() & splat(PASCAL_STEPS[1].1));
    x = x ^ (x.shr::<4>() & splat(PASCAL_STEPS[2].1));
    x ^ (x.shr::<8>() & splat(PASCAL_STEPS[3].1))
}

/// `sobol_burley::parts::hash` on lanes.
#[inline(always)]
fn hash<I: IntLanes>(x: I) -> I {
    lowbias32(x ^ I::splat(0xe6fe_3beb_u32 as i32))
}

/// `sobol_burley::parts::owen_scramble_rev` on lanes.
#[inline(always)]
fn owen_scramble_rev<I: IntLanes>(mut n_rev: I, scramble: I) -> I {
    n_rev = n_rev ^ (n_rev * I::splat(0x3d20_adea));
    n_rev = n_rev + scramble;
    n_rev = n_rev * (scramble.shr::<16>() | I::splat(1));
    n_rev = n_rev ^ (n_rev * I::splat(0x0552_6c56));
    n_rev ^ (n_rev * I::splat(0x53a2_2864))
}

/// Dimensions 0..N of each lane's Sobol draw `draw`:
/// `sobol_index_and_scramble` then `owen_sobol::<N>`, on lanes.
#[inline(always)]
fn owen_sobol<F: FloatLanes, const N: usize>(
    pixel_key: F::Ints,
    index: F::Ints,
    draw: F::Ints,
) -> [F; N] {
    // `sobol_index_and_scramble`.
    debug_assert_eq!(SOBOL_LENGTH, 1 << 16);
    let lap = index.shr::<16>();
    let scramble = lowbias32(pixel_key ^ lowbias32(draw ^ (lap * splat(GOLDEN))));
    let index = index & splat(SOBOL_LENGTH - 1);
    // `owen_sobol`.
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(scramble ^ splat(SHUFFLE_KEY)));
    let seed = scramble * splat(DIMENSION_SEED_FACTOR);
    const { assert!(N <= 2, "Sobol draws have one or two dimensions") };
    // `sobol_rev_2d`: the index the crate reads, and its Pascal product.
    let unshuffled = (shuffled_rev & splat(0xffff_0000)).reverse_bits();
    let sobol_rev = [unshuffled, pascal_mod2(unshuffled)];
    let mut points = [F::ZERO; N];
    for (d, point) in points.iter_mut().enumerate() {
        let scrambled = owen_scramble_rev(sobol_rev[d], hash(seed ^ splat(DIMENSION_KEYS[d])));
        // `u32_to_f32_norm`: the top 23 bits as the mantissa of [1, 2), minus 1.
        *point =
            (scrambled.reverse_bits().shr::<9>() | splat(0x3f80_0000)).bits_to_floats() - F::ONE;
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampling;
    use crate::simd::{WithLanes, on_every_lane_type};

    /// Every draw 0..40 of 64 pixel samples (both samplings, indices past
    /// the Sobol length among them), from the lanes and from the scalar
    /// streams: the bits of both numbers of each draw.
    #[derive(Clone)]
    struct Compare;

    impl WithLanes for Compare {
        type Output = ();
        #[inline(always)]
        fn run<F: FloatLanes>(self) {
            for sampling in [Sampling::Independent, Sampling::Sobol] {
                for group in 0..8u32 {
                    let streams: [PixelStream; WIDTH] = std::array::from_fn(|k| {
                        let sample = group * 40_000 + k as u32 * 3;
                        PixelStream::new(sampling, 5, group, k as u32, sample)
                    });
                    let mut lanes = StreamLanes::<F>::new();
                    for (k, stream) in streams.iter().enumerate() {
                        lanes.set(k, stream);
                        assert_eq!(lanes.stream(k), *stream);
                    }
                    for first in 0..40u32 {
                        // Each lane at a different draw.
                        let draws: [u32; WIDTH] = std::array::from_fn(|k| (first + k as u32) % 40);
                        let draw_lanes = F::Ints::from_array(draws.map(|d| d as i32));
                        let (x, y) = lanes.numbers(draw_lanes);
                        let single = lanes.number(draw_lanes);
                        for k in 0..WIDTH {
                            let expected = streams[k].numbers::<2>(draws[k]);
                            let got = [x.as_array()[k], y.as_array()[k]];
                            assert_eq!(
                                got.map(f32::to_bits),
                                expected.map(f32::to_bits),
                                "{sampling:?}, lane {k}, draw {}",
                                draws[k]
                            );
                            let one = streams[k].numbers::<1>(draws[k]);
                            assert_eq!(one[0].to_bits(), expected[0].to_bits());
                            assert_eq!(single.as_array()[k].to_bits(), one[0].to_bits());
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn lane_streams_give_the_scalar_streams_numbers_bit_for_bit() {
        on_every_lane_type(Compare);
    }
}
