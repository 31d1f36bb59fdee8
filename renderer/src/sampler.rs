//! Random numbers that depend only on (seed, pixel, sample index), so images
//! are identical for any thread count and any one sample can be re-traced.

use glam::{Vec2, Vec3};
use rand_core::Rng;
use rand_pcg::Pcg32;

/// A per-sample random stream.
pub struct Sampler {
    rng: Pcg32,
}

/// SplitMix64's finaliser: decorrelates neighbouring integers.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// The stream of sample `sample` of pixel (i, j) for render seed `seed`.
    pub fn for_sample(seed: u64, i: u32, j: u32, sample: u32) -> Self {
        let pixel = ((j as u64) << 32) | i as u64;
        let state = mix(mix(seed ^ mix(pixel)) ^ sample as u64);
        Self {
            rng: Pcg32::new(state, mix(pixel ^ 0x5851_f42d_4c95_7f2d)),
        }
    }

    /// A uniform number in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        // 24 random mantissa bits: exactly representable, never 1.0.
        (self.rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// A uniformly distributed unit vector (uniform on the sphere).
    pub fn next_direction(&mut self) -> Vec3 {
        let z = 2.0 * self.next_f32() - 1.0;
        let phi = std::f32::consts::TAU * self.next_f32();
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(s * phi.cos(), z, s * phi.sin())
    }

    /// A uniform point in [0, 1)².
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_f32(), self.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_pixel_and_sample_give_the_same_numbers() {
        let a: Vec<f32> = (0..4)
            .map(|_| 0.0)
            .scan(Sampler::for_sample(7, 3, 4, 5), |s, _| Some(s.next_f32()))
            .collect();
        let b: Vec<f32> = (0..4)
            .map(|_| 0.0)
            .scan(Sampler::for_sample(7, 3, 4, 5), |s, _| Some(s.next_f32()))
            .collect();
        assert_eq!(a, b);
        let c = Sampler::for_sample(7, 3, 4, 6).next_f32();
        assert_ne!(a[0], c);
    }

    #[test]
    fn numbers_are_in_the_unit_interval_and_roughly_uniform() {
        let mut sum = 0.0;
        let n = 10_000;
        for k in 0..n {
            let x = Sampler::for_sample(1, k, 0, 0).next_f32();
            assert!((0.0..1.0).contains(&x));
            sum += x as f64;
        }
        assert!((sum / n as f64 - 0.5).abs() < 0.01);
    }
}
