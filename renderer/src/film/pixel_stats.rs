//! What the film keeps per pixel beside the colour sum, for the variance and
//! cost heatmaps: a running mean and sum of squared deviations of the
//! samples' luminance (Welford's update, so that identical samples give a
//! variance of exactly zero), and the shape tests the samples cost.

/// Below this mean luminance the relative variance divides by this floor
/// instead, so that nearly black pixels do not blow up (their variance is
/// shown relative to a just-visible grey).
pub const LUMINANCE_FLOOR: f32 = 1.0e-3;

/// One pixel's running statistics (all zero: no samples).
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
pub struct PixelStats {
    /// Mean luminance of the samples so far.
    mean: f32,
    /// Sum of squared deviations from the mean (Welford's M2).
    m2: f32,
    /// Shape tests spent on every sample so far, discarded ones included.
    cost: u64,
}

impl PixelStats {
    /// Adds a finite sample of luminance `y`; `inv_count` is 1 / (samples
    /// including this one).
    #[inline]
    pub fn add(&mut self, y: f32, inv_count: f32) {
        let delta = y - self.mean;
        self.mean += delta * inv_count;
        self.m2 += delta * (y - self.mean);
    }

    /// Adds the shape tests one sample cost.
    #[inline]
    pub fn add_cost(&mut self, tests: u64) {
        self.cost += tests;
    }

    /// The relative variance of the pixel's mean after `n` samples:
    /// (s² / n) / max(mean, [`LUMINANCE_FLOOR`])², with s² the unbiased sample
    /// variance of the luminance. `None` below two samples.
    pub fn relative_variance(&self, n: u32) -> Option<f32> {
        if n < 2 {
            return None;
        }
        let n = n as f32;
        let variance_of_mean = (self.m2 / (n - 1.0)).max(0.0) / n;
        let mean = self.mean.abs().max(LUMINANCE_FLOOR);
        Some(variance_of_mean / (mean * mean))
    }

    /// Shape tests per sample after `n` samples.
    pub fn cost_per_sample(&self, n: u32) -> f32 {
        self.cost as f32 / n.max(1) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_samples_have_exactly_zero_variance() {
        let mut s = PixelStats::default();
        for n in 1..=100u32 {
            s.add(0.123_456_7, 1.0 / n as f32);
        }
        assert_eq!(s.relative_variance(100), Some(0.0));
    }

    #[test]
    fn two_values_give_the_textbook_variance_of_the_mean() {
        // Samples 1 and 3: mean 2, s² = 2, variance of the mean 1, relative 1/4.
        let mut s = PixelStats::default();
        s.add(1.0, 1.0);
        s.add(3.0, 0.5);
        assert_eq!(s.relative_variance(2), Some(0.25));
        assert_eq!(s.relative_variance(1), None);
    }

    #[test]
    fn black_pixels_divide_by_the_floor() {
        let mut s = PixelStats::default();
        s.add(0.0, 1.0);
        s.add(0.0, 0.5);
        assert_eq!(s.relative_variance(2), Some(0.0));
    }
}
