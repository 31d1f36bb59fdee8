//! Error measures of an image against a reference (linear RGB, same size).

use glam::Vec3;

/// The relative MSE's guard in the denominator: (x − ref)² / (ref² + ε).
pub const REL_MSE_EPSILON: f64 = 0.01;

/// Relative mean squared error: the mean over pixels and channels of
/// (x − ref)² / (ref² + 0.01), as `assets/reference/README.md` defines it.
/// Non-finite pixels count as black.
pub fn rel_mse(image: &[Vec3], reference: &[Vec3]) -> f64 {
    assert_eq!(image.len(), reference.len(), "images of different sizes");
    mean_over_channels(image, reference, |x, r| {
        let d = x - r;
        d * d / (r * r + REL_MSE_EPSILON)
    })
}

/// Root mean squared error over pixels and channels.
pub fn rmse(image: &[Vec3], reference: &[Vec3]) -> f64 {
    assert_eq!(image.len(), reference.len(), "images of different sizes");
    mean_over_channels(image, reference, |x, r| (x - r) * (x - r)).sqrt()
}

fn mean_over_channels(image: &[Vec3], reference: &[Vec3], term: impl Fn(f64, f64) -> f64) -> f64 {
    if image.is_empty() {
        return 0.0;
    }
    let finite = |v: f32| if v.is_finite() { f64::from(v) } else { 0.0 };
    let sum: f64 = image
        .iter()
        .zip(reference)
        .map(|(x, r)| {
            (0..3)
                .map(|c| term(finite(x[c]), finite(r[c])))
                .sum::<f64>()
        })
        .sum();
    sum / (3 * image.len()) as f64
}

/// The image averaged over `block` × `block` squares (the last row and
/// column of blocks may be partial): an estimate with `block²` times fewer
/// pixels and as many times less variance, for comparing short renders
/// with a reference without their noise hiding a bias.
pub fn downsample(image: &[Vec3], width: u32, height: u32, block: u32) -> (Vec<Vec3>, u32, u32) {
    let (w, h) = (width.div_ceil(block), height.div_ceil(block));
    let mut sum = vec![Vec3::ZERO; (w * h) as usize];
    let mut count = vec![0u32; (w * h) as usize];
    for j in 0..height {
        for i in 0..width {
            let k = ((j / block) * w + i / block) as usize;
            sum[k] += image[(j * width + i) as usize];
            count[k] += 1;
        }
    }
    let out = sum
        .into_iter()
        .zip(count)
        .map(|(s, n)| s / n.max(1) as f32)
        .collect();
    (out, w, h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_zero_error() {
        let a = vec![Vec3::new(0.1, 2.0, 0.5); 6];
        assert_eq!(rel_mse(&a, &a), 0.0);
        assert_eq!(rmse(&a, &a), 0.0);
    }

    #[test]
    fn relative_error_of_a_ten_percent_offset_on_white_is_about_one_percent() {
        let reference = vec![Vec3::ONE; 4];
        let image = vec![Vec3::splat(1.1); 4];
        let e = rel_mse(&image, &reference);
        assert!((e - 0.01 / 1.01).abs() < 1e-7, "{e}");
    }

    #[test]
    fn downsampling_averages_blocks_including_partial_ones() {
        let image: Vec<Vec3> = (0..6).map(|k| Vec3::splat(k as f32)).collect();
        let (small, w, h) = downsample(&image, 3, 2, 2);
        assert_eq!((w, h), (2, 1));
        assert_eq!(small, vec![Vec3::splat(2.0), Vec3::splat(3.5)]);
    }
}
