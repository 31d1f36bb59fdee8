//! Random numbers that depend only on (seed, pixel, sample index), so images
//! are identical for any thread count and any one sample can be re-traced.
//!
//! A pixel sample's numbers are counter-based: draw `d` of a sample (a
//! number or a 2D point, [`BounceDraw`] lays them out per bounce) is a pure
//! function of the sample's keys and `d`, with no state carried from one
//! draw to the next. Two kinds: independent numbers (a hash of the keys and
//! the draw, [`independent_bits`]), and Owen-scrambled Sobol points (Burley
//! 2020, through the `sobol_burley` crate), where the samples of one pixel
//! fill their dimensions evenly — the k-th sample avoids the places the
//! first k − 1 already covered — so the error falls faster than 1/√n
//! wherever the integrand is smooth enough to notice.
//!
//! Being pure 32-bit integer functions, the same numbers are computed eight
//! lanes at a time by the wavefront tracer ([`lanes`]), bit for bit. A
//! general-purpose stream (PCG32, [`Sampler::for_sample`]) serves tests and
//! diagnostics that want many numbers in a row.

pub(crate) mod lanes;

use glam::{Vec2, Vec3};
use rand_core::Rng;
use rand_pcg::Pcg32;

/// How the random numbers of a pixel's samples are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sampling {
    /// Independent uniform numbers: every sample on its own.
    #[default]
    Independent,
    /// Owen-scrambled Sobol points, scrambled afresh for every pixel: a
    /// pixel's samples are stratified in every number and every 2D point
    /// of the camera ray and the first bounce (the jitter, a point on a
    /// light, a direction); deeper bounces draw independent numbers.
    Sobol,
}

/// Where a bounce's numbers start (the Sobol stream gives every bounce the
/// same layout, so each use of a number gets its own evenly filled
/// dimension, whichever lights and lobes the path met before).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BounceDraw {
    /// Light sampling: which emitter (1 number), then a point on it (2).
    Light = 0,
    /// BSDF sampling: which lobe (1), a direction (2), then Russian roulette (1).
    Scatter = 2,
}

/// Draws given to each bounce (see [`BounceDraw`]): a draw is one
/// number or one 2D point.
pub(crate) const DRAWS_PER_BOUNCE: u32 = 5;
/// The camera's draw: the jitter (x, y) within the pixel.
pub(crate) const CAMERA_DRAWS: u32 = 1;
/// Draws taken from the Sobol sequence: the camera's jitter and the first
/// hit's light and BSDF samples. Later draws are independent numbers: on the
/// Cornell box, Sobol draws for every bounce gave no lower error at equal
/// spp than for the first bounce alone, and each costs ~30 ns against a
/// ~1.3 µs path (`raylab chart … --methods path,path-sobol`).
pub(crate) const SOBOL_DRAWS: u32 = CAMERA_DRAWS + DRAWS_PER_BOUNCE;
/// The sequence length `sobol_burley` supports; later indices go on in a
/// fresh scramble.
const SOBOL_LENGTH: u32 = 1 << 16;

/// A random stream: a pixel sample's numbers, or a general-purpose one.
#[derive(Clone)]
pub struct Sampler {
    source: Source,
}

#[derive(Clone)]
enum Source {
    /// Numbers in a row from PCG32 ([`Sampler::for_sample`]).
    General(Pcg32),
    /// A pixel sample's draws ([`Sampler::for_pixel_sample`]).
    Pixel(PixelStream),
}

/// The numbers of one pixel sample: what they are computed from, and the
/// next draw. Each draw — a number or a 2D point — is
/// - with Sobol sampling, before [`SOBOL_DRAWS`]: the first one or two
///   Sobol dimensions of sample `index` of the draw's own scramble of the
///   pixel's sequence (Burley's padding), so each 2D point set is a (0, 2)
///   sequence and separate draws are decorrelated at random;
/// - otherwise two independent numbers hashed from `keys` and the draw
///   (the first alone when one number is asked for).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PixelStream {
    /// The sample's own keys, for its independent numbers.
    pub(crate) keys: [u32; 2],
    /// The pixel's key, from which each Sobol draw's scramble is hashed.
    pub(crate) pixel_key: u32,
    /// The sample's index k in its pixel's Sobol sequence.
    pub(crate) index: u32,
    /// Whether the first [`SOBOL_DRAWS`] draws are Sobol points.
    pub(crate) sobol: bool,
    /// The next draw.
    draw: u32,
}

impl PixelStream {
    /// The numbers of sample `sample` of pixel (i, j) for render seed
    /// `seed`, drawn as `sampling` says, at draw 0.
    pub(crate) fn new(sampling: Sampling, seed: u64, i: u32, j: u32, sample: u32) -> Self {
        let pixel = ((j as u64) << 32) | i as u64;
        let keys = mix(mix(seed ^ mix(pixel)) ^ u64::from(sample));
        Self {
            keys: [keys as u32, (keys >> 32) as u32],
            pixel_key: mix(mix(seed) ^ mix(pixel ^ 0x2545_f491_4f6c_dd1d)) as u32,
            index: sample,
            sobol: sampling == Sampling::Sobol,
            draw: 0,
        }
    }

    /// Draw `draw`'s first `N` (1 or 2) numbers.
    #[inline]
    fn numbers<const N: usize>(&self, draw: u32) -> [f32; N] {
        if self.sobol && draw < SOBOL_DRAWS {
            let (index, scramble) = sobol_index_and_scramble(self.pixel_key, self.index, draw);
            return owen_sobol::<N>(index, scramble);
        }
        std::array::from_fn(|c| uniform(independent_bits(self.keys, 2 * draw + c as u32)))
    }

    /// The next draw's first `N` numbers.
    #[inline]
    fn next_draw<const N: usize>(&mut self) -> [f32; N] {
        let numbers = self.numbers::<N>(self.draw);
        self.draw += 1;
        numbers
    }
}

/// Chris Wellons' `lowbias32`: a bijective 32-bit mix in which every input
/// bit changes every output bit with probability close to ½.
#[inline(always)]
pub(crate) fn lowbias32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// The 2^32·φ step of a Weyl sequence: consecutive counters land far apart.
pub(crate) const GOLDEN: u32 = 0x9e37_79b9;

/// Independent number `n` (draw d's numbers are 2d and 2d + 1) of the
/// sample whose keys are `keys`: the 64 bits of key decide the whole
/// stream, so two samples share their numbers only if both keys agree.
#[inline(always)]
pub(crate) fn independent_bits(keys: [u32; 2], n: u32) -> u32 {
    lowbias32(keys[0] ^ lowbias32(keys[1].wrapping_add(n.wrapping_mul(GOLDEN))))
}

/// Where Sobol draw `draw` of sample `index` of a pixel (key `pixel_key`)
/// is read: the index within the crate's sequence length, and the draw's
/// scramble. Indices past the length go on in another scramble.
#[inline(always)]
pub(crate) fn sobol_index_and_scramble(pixel_key: u32, index: u32, draw: u32) -> (u32, u32) {
    let lap = index / SOBOL_LENGTH;
    let scramble = lowbias32(pixel_key ^ lowbias32(draw ^ lap.wrapping_mul(GOLDEN)));
    (index % SOBOL_LENGTH, scramble)
}

/// Dimensions 0..N of sample `index` of the Owen-scrambled Sobol sequence
/// of `seed`: `sobol_burley::sample(index, d, seed)` for each d, with the
/// index shuffled once for all of them and the unscrambled Sobol point from
/// [`sobol_rev_2d`] (the crate's own parts otherwise, so the numbers are
/// the same bit for bit; checked by a test).
#[inline]
pub(crate) fn owen_sobol<const N: usize>(index: u32, seed: u32) -> [f32; N] {
    use sobol_burley::parts::{hash, owen_scramble_rev, u32_to_f32_norm};
    const { assert!(N <= 2, "Sobol draws have one or two dimensions") };
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ SHUFFLE_KEY));
    let seed = seed.wrapping_mul(DIMENSION_SEED_FACTOR);
    let points = sobol_rev_2d(shuffled_rev);
    std::array::from_fn(|d| {
        let scrambled = owen_scramble_rev(points[d], hash(seed ^ DIMENSION_KEYS[d]));
        u32_to_f32_norm(scrambled.reverse_bits())
    })
}

/// The crate's per-dimension scramble constants (dimensions 0–3).
pub(crate) const DIMENSION_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];
/// The crate's scramble constant of the index shuffle.
pub(crate) const SHUFFLE_KEY: u32 = 0x79c6_8e4a;
/// The crate's multiplier of the seed before the dimensions' scrambles.
pub(crate) const DIMENSION_SEED_FACTOR: u32 = 0x9c8f_2d3b;

/// `sobol_burley::parts::sobol_rev(index_rev, d)` of dimensions d = 0 and
/// 1, computed in a few steps that never branch. The crate reads the top 16
/// bits of the reversed index, that is the index i < 2^16 itself, and XORs
/// the generator matrix's columns for i's set bits; its loop takes a
/// data-dependent number of steps, each waiting on the last, and ends in a
/// mispredicted branch (~20% of a path-traced Cornell pass once). Here
/// dimension 0's point, reversed, is i (van der Corput), and dimension 1's
/// is i times Pascal's triangle mod 2 ([`pascal_mod2`]). Checked against
/// the crate for every index.
#[inline(always)]
pub(crate) fn sobol_rev_2d(index_rev: u32) -> [u32; 2] {
    let index = (index_rev & 0xffff_0000).reverse_bits();
    [index, pascal_mod2(index)]
}

/// The shifts and masks of [`pascal_mod2`]: at step s, the bits j that
/// lack bit s (of their position) take in bit j + s.
pub(crate) const PASCAL_STEPS: [(u32, u32); 4] = [
    (1, 0x5555_5555),
    (2, 0x3333_3333),
    (4, 0x0f0f_0f0f),
    (8, 0x00ff_00ff),
];

/// The 16-bit `x` times Pascal's triangle mod 2 (Sobol's second
/// dimension): bit j of the result is the XOR of the bits k of `x` whose
/// position contains j's (k & j = j), one step per bit of the position.
#[inline(always)]
pub(crate) fn pascal_mod2(mut x: u32) -> u32 {
    for (shift, mask) in PASCAL_STEPS {
        x ^= (x >> shift) & mask;
    }
    x
}

/// 24 random mantissa bits as a number in [0, 1): exactly representable, never 1.0.
#[inline]
pub(crate) fn uniform(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// SplitMix64's finaliser: decorrelates neighbouring integers.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// A general-purpose stream (PCG32) of numbers in a row, seeded by
    /// (`seed`, i, j, `sample`), for tests and diagnostics.
    pub fn for_sample(seed: u64, i: u32, j: u32, sample: u32) -> Self {
        let pixel = ((j as u64) << 32) | i as u64;
        let state = mix(mix(seed ^ mix(pixel)) ^ sample as u64);
        Self {
            source: Source::General(Pcg32::new(state, mix(pixel ^ 0x5851_f42d_4c95_7f2d))),
        }
    }

    /// The stream of sample `sample` of pixel (i, j) drawn as `sampling` says.
    pub fn for_pixel_sample(sampling: Sampling, seed: u64, i: u32, j: u32, sample: u32) -> Self {
        Self {
            source: Source::Pixel(PixelStream::new(sampling, seed, i, j, sample)),
        }
    }

    /// The pixel stream `stream` at draw 0.
    pub(crate) fn from_pixel_stream(stream: PixelStream) -> Self {
        Self {
            source: Source::Pixel(PixelStream { draw: 0, ..stream }),
        }
    }

    /// Moves to the numbers of bounce `depth` (0 at the camera ray's hit),
    /// at `at` within them. A general-purpose stream just goes on.
    #[inline]
    pub fn seek_bounce(&mut self, depth: u32, at: BounceDraw) {
        if let Source::Pixel(stream) = &mut self.source {
            stream.draw = bounce_draw(depth, at);
        }
    }

    /// Moves to the environment's light sample of bounce `depth`
    /// ([`environment_draw`]). A general-purpose stream just goes on.
    #[inline]
    pub fn seek_environment(&mut self, depth: u32) {
        if let Source::Pixel(stream) = &mut self.source {
            stream.draw = environment_draw(depth);
        }
    }

    /// A uniform number in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        match &mut self.source {
            Source::General(rng) => uniform(rng.next_u32()),
            Source::Pixel(stream) => stream.next_draw::<1>()[0],
        }
    }

    /// A uniformly distributed unit vector (uniform on the sphere).
    pub fn next_direction(&mut self) -> Vec3 {
        let u = self.next_2d();
        let z = 2.0 * u.x - 1.0;
        let phi = std::f32::consts::TAU * u.y;
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(s * phi.cos(), z, s * phi.sin())
    }

    /// A uniform point in [0, 1)².
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        match &mut self.source {
            Source::General(_) => {
                let x = self.next_f32();
                Vec2::new(x, self.next_f32())
            }
            Source::Pixel(stream) => {
                let [x, y] = stream.next_draw::<2>();
                Vec2::new(x, y)
            }
        }
    }
}

/// The first draw of the environment's light samples: one 2D point per
/// bounce from here on (`ENVIRONMENT_DRAWS + depth`), apart from the
/// bounces' own draws so that a scene without a sky draws exactly the
/// numbers it drew before there was one. Past [`SOBOL_DRAWS`], so they are
/// independent numbers.
const ENVIRONMENT_DRAWS: u32 = 1 << 28;

/// The draw of the environment's light sample at bounce `depth`.
#[inline(always)]
pub(crate) fn environment_draw(depth: u32) -> u32 {
    ENVIRONMENT_DRAWS + depth
}

/// The index of the first draw of `at` at bounce `depth`.
#[inline(always)]
pub(crate) fn bounce_draw(depth: u32, at: BounceDraw) -> u32 {
    CAMERA_DRAWS + depth * DRAWS_PER_BOUNCE + at as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computed_sobol_points_are_the_crates_for_every_index() {
        for index in 0..1u32 << 16 {
            let rev = index.reverse_bits() | 0x1234; // low bits are ignored
            for d in 0..2 {
                assert_eq!(
                    sobol_rev_2d(rev)[d],
                    sobol_burley::parts::sobol_rev(rev, d as u32),
                    "index {index} dimension {d}"
                );
            }
        }
    }

    #[test]
    fn owen_sobol_is_the_crates_sample_4d_bit_for_bit() {
        let mut rng = Pcg32::new(3, 5);
        for _ in 0..20_000 {
            let (index, seed) = (rng.next_u32() % SOBOL_LENGTH, rng.next_u32());
            let four = sobol_burley::sample_4d(index, 0, seed);
            let two = owen_sobol::<2>(index, seed);
            let one = owen_sobol::<1>(index, seed);
            assert_eq!(two.map(f32::to_bits), [four[0], four[1]].map(f32::to_bits));
            assert_eq!(one[0].to_bits(), four[0].to_bits());
        }
    }

    fn first_numbers(mut sampler: Sampler, n: usize) -> Vec<f32> {
        (0..n).map(|_| sampler.next_f32()).collect()
    }

    #[test]
    fn same_pixel_and_sample_give_the_same_numbers() {
        for sampling in [Sampling::Independent, Sampling::Sobol] {
            let a = first_numbers(Sampler::for_pixel_sample(sampling, 7, 3, 4, 5), 6);
            let b = first_numbers(Sampler::for_pixel_sample(sampling, 7, 3, 4, 5), 6);
            assert_eq!(a, b, "{sampling:?}");
            let c = Sampler::for_pixel_sample(sampling, 7, 3, 4, 6).next_f32();
            assert_ne!(a[0], c, "{sampling:?}");
            let other_pixel = Sampler::for_pixel_sample(sampling, 7, 4, 4, 5).next_f32();
            assert_ne!(a[0], other_pixel, "{sampling:?}");
        }
    }

    #[test]
    fn numbers_are_in_the_unit_interval_and_roughly_uniform() {
        for sampling in [Sampling::Independent, Sampling::Sobol] {
            let mut sum = 0.0;
            let n = 10_000;
            for k in 0..n {
                let x = Sampler::for_pixel_sample(sampling, 1, k, 0, 0).next_f32();
                assert!((0.0..1.0).contains(&x));
                sum += x as f64;
            }
            assert!((sum / n as f64 - 0.5).abs() < 0.01, "{sampling:?}");
        }
    }

    /// The count of the `n` × `n` cells of [0, 1)² that hold none of the points.
    fn empty_cells(points: &[Vec2], n: usize) -> usize {
        let mut filled = vec![false; n * n];
        for p in points {
            filled[(p.y * n as f32) as usize * n + (p.x * n as f32) as usize] = true;
        }
        filled.iter().filter(|&&f| !f).count()
    }

    #[test]
    fn a_pixels_sobol_samples_fill_every_stratum_where_independent_ones_leave_gaps() {
        // 256 samples of one pixel against a 16 × 16 grid: the Sobol points
        // are (0, m, 2)-net points, one per cell, in each 2D draw.
        for (depth, at) in [(0, BounceDraw::Light), (0, BounceDraw::Scatter)] {
            let points = |sampling| -> Vec<Vec2> {
                (0..256)
                    .map(|k| {
                        let mut s = Sampler::for_pixel_sample(sampling, 9, 5, 7, k);
                        s.seek_bounce(depth, at);
                        if at == BounceDraw::Light {
                            s.next_f32();
                        }
                        s.next_2d()
                    })
                    .collect()
            };
            assert_eq!(empty_cells(&points(Sampling::Sobol), 16), 0);
            // Independent points leave about 256 / e ≈ 94 cells empty.
            let gaps = empty_cells(&points(Sampling::Independent), 16);
            assert!(gaps > 60, "{gaps}");
        }
        let camera: Vec<Vec2> = (0..1024)
            .map(|k| Sampler::for_pixel_sample(Sampling::Sobol, 0, 0, 0, k).next_2d())
            .collect();
        assert_eq!(empty_cells(&camera, 32), 0);
    }

    #[test]
    fn sobol_samples_past_the_sequence_length_go_on_in_the_unit_interval() {
        let a = Sampler::for_pixel_sample(Sampling::Sobol, 0, 0, 0, 3).next_f32();
        let b = Sampler::for_pixel_sample(Sampling::Sobol, 0, 0, 0, SOBOL_LENGTH + 3).next_f32();
        assert!((0.0..1.0).contains(&b));
        assert_ne!(a, b);
    }

    #[test]
    fn counter_based_numbers_are_uniform_in_2d_and_uncorrelated_between_draws() {
        // 16 384 samples of one pixel (and of neighbouring pixels), draws
        // past the Sobol ones: each 2D draw fills a 16 × 16 grid evenly
        // (chi-square), and no number is correlated with any other of the
        // same sample.
        let n = 16_384;
        let streams: Vec<PixelStream> = (0..n)
            .map(|k| PixelStream::new(Sampling::Sobol, 1, k % 3, 0, k / 3))
            .collect();
        let numbers =
            |draw: u32| -> Vec<[f32; 2]> { streams.iter().map(|s| s.numbers::<2>(draw)).collect() };
        let draws: Vec<Vec<[f32; 2]>> = (SOBOL_DRAWS..SOBOL_DRAWS + 12).map(numbers).collect();
        for points in &draws {
            let mut cells = [0u32; 256];
            for p in points {
                cells[(p[1] * 16.0) as usize * 16 + (p[0] * 16.0) as usize] += 1;
            }
            let expected = n as f64 / 256.0;
            let chi2: f64 = cells
                .iter()
                .map(|&c| (c as f64 - expected).powi(2) / expected)
                .sum();
            // 255 degrees of freedom: mean 255, standard deviation 22.6.
            assert!(chi2 < 255.0 + 5.0 * 22.6, "chi-square {chi2}");
        }
        let column = |d: usize, c: usize| -> Vec<f64> {
            draws[d].iter().map(|p| f64::from(p[c]) - 0.5).collect()
        };
        for a in 0..draws.len() * 2 {
            for b in a + 1..draws.len() * 2 {
                let (x, y) = (column(a / 2, a % 2), column(b / 2, b % 2));
                let covariance: f64 = x.iter().zip(&y).map(|(x, y)| x * y).sum::<f64>() / n as f64;
                // Correlation = covariance / (1/12); its noise is 1/√n ≈ 0.008.
                assert!(
                    (covariance * 12.0).abs() < 0.04,
                    "numbers {a} and {b}: correlation {}",
                    covariance * 12.0
                );
            }
        }
    }

    #[test]
    fn seeking_lands_on_the_same_numbers_as_reading_through() {
        let mut read = Sampler::for_pixel_sample(Sampling::Sobol, 2, 1, 1, 17);
        let through: Vec<f32> = (0..SOBOL_DRAWS).map(|_| read.next_f32()).collect();
        let mut seek = Sampler::for_pixel_sample(Sampling::Sobol, 2, 1, 1, 17);
        seek.seek_bounce(0, BounceDraw::Scatter);
        let at = (CAMERA_DRAWS + BounceDraw::Scatter as u32) as usize;
        assert_eq!(seek.next_f32(), through[at]);
        assert_eq!(seek.next_f32(), through[at + 1]);
    }

    #[test]
    fn a_pixels_sobol_numbers_are_stratified_in_every_draw() {
        // 64 samples against 64 intervals: one in each, for each Sobol draw.
        for draw in 0..SOBOL_DRAWS {
            let mut filled = [false; 64];
            for k in 0..64 {
                let mut s = Sampler::for_pixel_sample(Sampling::Sobol, 4, 2, 3, k);
                for _ in 0..draw {
                    s.next_f32();
                }
                filled[(s.next_f32() * 64.0) as usize] = true;
            }
            assert!(filled.iter().all(|&f| f), "draw {draw}");
        }
    }
}
