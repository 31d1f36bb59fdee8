//! FLIP, NVIDIA's perceptual difference of two images (LDR-FLIP, through
//! the `nv-flip` bindings to the reference implementation): the mean of its
//! per-pixel error map, 0 for identical pictures and at most 1. Both
//! images are compared as shown — linear radiance clamped and sRGB-encoded
//! to 8 bits, as raylab writes PNGs — at FLIP's default 67 pixels per degree
//! (a 0.7 m wide 4K monitor seen from 0.7 m).

use glam::Vec3;
use nv_flip::{DEFAULT_PIXELS_PER_DEGREE, FlipImageRgb8, FlipPool};
use renderer::display::srgb::linear_to_srgb8;

/// A reference picture, encoded once, to measure images against.
pub struct FlipReference {
    picture: FlipImageRgb8,
    width: u32,
    height: u32,
}

/// Linear radiance as FLIP's 8-bit sRGB picture.
fn picture(pixels: &[Vec3], width: u32, height: u32) -> FlipImageRgb8 {
    let bytes: Vec<u8> = pixels.iter().flat_map(|&c| linear_to_srgb8(c)).collect();
    FlipImageRgb8::with_data(width, height, &bytes)
}

impl FlipReference {
    /// The reference `pixels` (linear RGB, `width` × `height`, row by row from the top).
    pub fn new(pixels: &[Vec3], width: u32, height: u32) -> Self {
        assert_eq!(pixels.len(), width as usize * height as usize);
        Self {
            picture: picture(pixels, width, height),
            width,
            height,
        }
    }

    /// The mean FLIP error of `image` (the reference's size) against the reference.
    pub fn mean_error(&self, image: &[Vec3]) -> f64 {
        assert_eq!(image.len(), self.width as usize * self.height as usize);
        let test = picture(image, self.width, self.height);
        let map = nv_flip::flip(self.picture.clone(), test, DEFAULT_PIXELS_PER_DEGREE);
        f64::from(FlipPool::from_image(&map).mean())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(w: u32, h: u32, contrast: f32) -> Vec<Vec3> {
        (0..w * h)
            .map(|k| {
                let (i, j) = (k % w, k / w);
                Vec3::splat(if (i / 4 + j / 4) % 2 == 0 {
                    0.5 + contrast
                } else {
                    0.5 - contrast
                })
            })
            .collect()
    }

    #[test]
    fn identical_images_have_no_flip_error() {
        let image = checker(32, 24, 0.3);
        assert_eq!(FlipReference::new(&image, 32, 24).mean_error(&image), 0.0);
    }

    #[test]
    fn flip_error_grows_with_the_difference_and_stays_at_most_one() {
        let reference = FlipReference::new(&checker(32, 24, 0.3), 32, 24);
        let near = reference.mean_error(&checker(32, 24, 0.25));
        let far = reference.mean_error(&checker(32, 24, 0.0));
        assert!(0.0 < near && near < far && far <= 1.0, "{near} {far}");
    }
}
