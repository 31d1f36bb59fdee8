//! Adaptive sampling: once every pixel has [`Adaptive::MIN_SAMPLES`], a
//! pixel whose estimated relative error is below the threshold — and whose
//! eight neighbours' are too — stops receiving samples, so that the passes
//! spend their rays where the image is still noisy.
//!
//! A pixel's relative error is estimated from its own samples: the standard
//! error of its mean luminance over the mean (`√(Var[mean]) / mean`, see
//! [`PixelStats::relative_variance`](crate::film::pixel_stats::PixelStats::relative_variance)).
//! That estimate is itself noisy — a pixel whose few samples all missed a
//! small light looks converged — so the neighbourhood must agree, and a
//! stopped pixel starts again when a neighbour's estimate grows.

/// Adaptive sampling's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// The relative error (standard error of the mean over the mean
    /// luminance) below which a pixel stops receiving samples.
    pub threshold: f32,
}

impl Adaptive {
    /// Samples every pixel gets before any may stop.
    pub const MIN_SAMPLES: u32 = 16;
    /// The threshold the app and the chart use unless told otherwise: 2%.
    pub const DEFAULT_THRESHOLD: f32 = 0.02;
}

impl Default for Adaptive {
    fn default() -> Self {
        Self {
            threshold: Self::DEFAULT_THRESHOLD,
        }
    }
}

/// Which pixels of a `width` × `height` image still need samples: those
/// where the largest relative variance over the 3 × 3 neighbourhood is at
/// or above `threshold²` (NaN counts as above). `relative_variance` is row by row from the top.
pub fn pixels_needing_samples(
    width: usize,
    height: usize,
    relative_variance: &[f32],
    threshold: f32,
) -> Vec<bool> {
    let limit = threshold * threshold;
    let above: Vec<bool> = relative_variance.iter().map(|&v| !(v < limit)).collect();
    // Dilate: a pixel needs samples when any neighbour is above the limit.
    let mut rows = vec![false; width * height];
    for j in 0..height {
        for i in 0..width {
            let row = &above[j * width..(j + 1) * width];
            rows[j * width + i] = row[i.saturating_sub(1)..(i + 2).min(width)]
                .iter()
                .any(|&a| a);
        }
    }
    let mut needing = vec![false; width * height];
    for j in 0..height {
        for i in 0..width {
            needing[j * width + i] =
                (j.saturating_sub(1)..(j + 2).min(height)).any(|r| rows[r * width + i]);
        }
    }
    needing
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_noisy_pixel_keeps_itself_and_its_neighbours_sampling() {
        let (w, h) = (5, 4);
        let mut variance = vec![0.0f32; w * h];
        variance[2 * w + 3] = 0.01; // error 10% at (3, 2)
        let needing = pixels_needing_samples(w, h, &variance, 0.02);
        for j in 0..h {
            for i in 0..w {
                let near = i.abs_diff(3) <= 1 && j.abs_diff(2) <= 1;
                assert_eq!(needing[j * w + i], near, "({i}, {j})");
            }
        }
    }

    #[test]
    fn pixels_below_the_threshold_stop_and_nan_never_does() {
        let variance = [0.02f32 * 0.02 * 0.99, 0.02 * 0.02 * 1.01, f32::NAN];
        let one_pixel = |v: f32| pixels_needing_samples(1, 1, &[v], 0.02)[0];
        assert!(!one_pixel(variance[0]));
        assert!(one_pixel(variance[1]));
        assert!(one_pixel(variance[2]));
    }
}
