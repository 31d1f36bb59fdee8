//! Random numbers that depend only on (seed, pixel, sample index), so images
//! are identical for any thread count and any one sample can be re-traced.
//!
//! Two kinds of stream: independent numbers (PCG32), and Owen-scrambled
//! Sobol points (Burley 2020, through the `sobol_burley` crate), where the
//! samples of one pixel fill their dimensions evenly — the k-th sample
//! avoids the places the first k − 1 already covered — so the error falls
//! faster than 1/√n wherever the integrand is smooth enough to notice.

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
const DRAWS_PER_BOUNCE: u32 = 5;
/// The camera's draw: the jitter (x, y) within the pixel.
const CAMERA_DRAWS: u32 = 1;
/// Draws taken from the Sobol sequence: the camera's jitter and the first
/// hit's light and BSDF samples. Later draws are independent numbers: on the
/// Cornell box, Sobol draws for every bounce gave no lower error at equal
/// spp than for the first bounce alone, and each costs ~30 ns against a
/// ~1.3 µs path (`raylab chart … --methods path,path-sobol`).
const SOBOL_DRAWS: u32 = CAMERA_DRAWS + DRAWS_PER_BOUNCE;
/// The sequence length `sobol_burley` supports; later indices go on in a
/// fresh scramble.
const SOBOL_LENGTH: u32 = 1 << 16;

/// A per-sample random stream.
#[derive(Clone)]
pub struct Sampler {
    source: Source,
}

#[derive(Clone)]
enum Source {
    Independent(Pcg32),
    Sobol(SobolStream),
}

/// Sample `index` of one pixel's scrambled Sobol sequence. Every draw — a
/// number or a 2D point — takes the first one or two Sobol dimensions of
/// its own scramble (Burley's padding), so each 2D point set is a (0, 2)
/// sequence and separate draws are decorrelated at random.
#[derive(Clone)]
struct SobolStream {
    index: u32,
    pixel_seed: u64,
    /// The next draw.
    draw: u32,
    /// Independent numbers for the draws past [`SOBOL_DRAWS`].
    tail: Pcg32,
}

impl SobolStream {
    /// The next draw's first `N` (1 or 2) numbers: Sobol dimensions 0..N of
    /// the draw's own scramble, or independent numbers past [`SOBOL_DRAWS`]
    /// (two of them whatever `N`, so that later draws do not depend on it).
    #[inline]
    fn next_draw<const N: usize>(&mut self) -> [f32; N] {
        if self.draw >= SOBOL_DRAWS {
            self.draw += 1;
            let x = uniform(self.tail.next_u32());
            let y = uniform(self.tail.next_u32());
            return std::array::from_fn(|d| [x, y][d]);
        }
        // Indices past the crate's length go on in another scramble.
        let lap = u64::from(self.index / SOBOL_LENGTH);
        let seed = mix(self.pixel_seed ^ mix(u64::from(self.draw) | lap << 32)) as u32;
        self.draw += 1;
        owen_sobol::<N>(self.index % SOBOL_LENGTH, seed)
    }
}

/// Dimensions 0..N of sample `index` of the Owen-scrambled Sobol sequence
/// of `seed`: `sobol_burley::sample(index, d, seed)` for each d, with the
/// index shuffled once for all of them and the unscrambled Sobol point read
/// from [`SobolBytes`] (the crate's own parts otherwise, so the numbers are
/// the same bit for bit; checked by a test).
#[inline]
fn owen_sobol<const N: usize>(index: u32, seed: u32) -> [f32; N] {
    use sobol_burley::parts::{hash, owen_scramble_rev, u32_to_f32_norm};
    /// The crate's per-dimension scramble constants (dimensions 0–3).
    const DIMENSION_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
    let seed = seed.wrapping_mul(0x9c8f_2d3b);
    let bytes = SobolBytes::get();
    std::array::from_fn(|d| {
        let sobol_rev = bytes.sobol_rev(shuffled_rev, d);
        let scrambled = owen_scramble_rev(sobol_rev, hash(seed ^ DIMENSION_KEYS[d]));
        u32_to_f32_norm(scrambled.reverse_bits())
    })
}

/// `sobol_burley::parts::sobol_rev` of dimensions 0 and 1 by two table
/// lookups: the Sobol point is the XOR of the generator matrix's columns
/// for the index's set bits (the top 16 of the reversed index), so it is
/// the XOR of the points of its two bytes. The crate's loop takes a
/// data-dependent number of steps, each waiting on the last, and ends in a
/// mispredicted branch: ~20% of a path-traced Cornell pass with Sobol
/// samples, where this costs two loads.
struct SobolBytes {
    /// [dimension][which byte: 0 the top][byte value] → that byte's Sobol point.
    table: [[[u32; 256]; 2]; 2],
}

impl SobolBytes {
    /// The tables, built on first use.
    #[inline]
    fn get() -> &'static SobolBytes {
        static TABLES: std::sync::OnceLock<Box<SobolBytes>> = std::sync::OnceLock::new();
        TABLES.get_or_init(|| {
            let point = |d: usize, byte: usize, value: u32| {
                sobol_burley::parts::sobol_rev(value << (24 - 8 * byte), d as u32)
            };
            Box::new(SobolBytes {
                table: std::array::from_fn(|d| {
                    std::array::from_fn(|byte| std::array::from_fn(|v| point(d, byte, v as u32)))
                }),
            })
        })
    }

    /// `sobol_rev(index_rev, dimension)` for dimension 0 or 1.
    #[inline(always)]
    fn sobol_rev(&self, index_rev: u32, dimension: usize) -> u32 {
        let t = &self.table[dimension];
        t[0][(index_rev >> 24) as usize] ^ t[1][((index_rev >> 16) & 0xff) as usize]
    }
}

/// 24 random mantissa bits as a number in [0, 1): exactly representable, never 1.0.
#[inline]
fn uniform(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// SplitMix64's finaliser: decorrelates neighbouring integers.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// The independent stream of sample `sample` of pixel (i, j) for render seed `seed`.
    pub fn for_sample(seed: u64, i: u32, j: u32, sample: u32) -> Self {
        let pixel = ((j as u64) << 32) | i as u64;
        let state = mix(mix(seed ^ mix(pixel)) ^ sample as u64);
        Self {
            source: Source::Independent(Pcg32::new(state, mix(pixel ^ 0x5851_f42d_4c95_7f2d))),
        }
    }

    /// The stream of sample `sample` of pixel (i, j) drawn as `sampling` says.
    pub fn for_pixel_sample(sampling: Sampling, seed: u64, i: u32, j: u32, sample: u32) -> Self {
        match sampling {
            Sampling::Independent => Self::for_sample(seed, i, j, sample),
            Sampling::Sobol => {
                let pixel = ((j as u64) << 32) | i as u64;
                Self {
                    source: Source::Sobol(SobolStream {
                        index: sample,
                        pixel_seed: mix(mix(seed) ^ mix(pixel ^ 0x2545_f491_4f6c_dd1d)),
                        draw: 0,
                        tail: Pcg32::new(mix(seed ^ mix(pixel) ^ u64::from(sample)), mix(pixel)),
                    }),
                }
            }
        }
    }

    /// Moves to the numbers of bounce `depth` (0 at the camera ray's hit),
    /// at `at` within them. The independent stream just goes on.
    pub fn seek_bounce(&mut self, depth: u32, at: BounceDraw) {
        if let Source::Sobol(stream) = &mut self.source {
            stream.draw = CAMERA_DRAWS + depth * DRAWS_PER_BOUNCE + at as u32;
        }
    }

    /// A uniform number in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        match &mut self.source {
            Source::Independent(rng) => uniform(rng.next_u32()),
            Source::Sobol(stream) => stream.next_draw::<1>()[0],
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
    pub fn next_2d(&mut self) -> Vec2 {
        match &mut self.source {
            Source::Independent(_) => {
                let x = self.next_f32();
                Vec2::new(x, self.next_f32())
            }
            Source::Sobol(stream) => {
                let [x, y] = stream.next_draw::<2>();
                Vec2::new(x, y)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sobol_points_by_bytes_are_the_crates_for_every_index() {
        let bytes = SobolBytes::get();
        for index in 0..1u32 << 16 {
            let rev = index.reverse_bits() | 0x1234; // low bits are ignored
            for d in 0..2 {
                assert_eq!(
                    bytes.sobol_rev(rev, d),
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
