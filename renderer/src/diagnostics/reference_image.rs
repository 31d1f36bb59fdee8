//! Reference images: a linear RGB EXR read back to compare renders with.

use glam::Vec3;
use std::path::Path;

/// Why a reference image cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ReferenceError {
    /// The file is not a readable RGB EXR.
    #[error("{path}: cannot read as an RGB EXR image: {source}")]
    Read {
        /// The file.
        path: String,
        /// What the EXR reader said.
        source: exr::error::Error,
    },
    /// The file holds NaN or infinite values.
    #[error("{0}: the reference has NaN or infinite pixels")]
    NotFinite(String),
    /// It is not the size of the render.
    #[error(
        "{path}: the reference is {}×{} pixels, the render {}×{}",
        found.0, found.1, expected.0, expected.1
    )]
    Size {
        /// The file.
        path: String,
        /// The reference's (width, height).
        found: (u32, u32),
        /// The render's (width, height).
        expected: (u32, u32),
    },
}

/// A linear RGB image, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row by row from the top.
    pub pixels: Vec<Vec3>,
}

/// Reads the first RGB(A) layer of an EXR file (alpha is ignored).
pub fn read_exr_rgb(path: &Path) -> Result<LinearImage, ReferenceError> {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |resolution, _| {
            (
                resolution.width(),
                vec![Vec3::ZERO; resolution.width() * resolution.height()],
            )
        },
        |(width, pixels): &mut (usize, Vec<Vec3>),
         position,
         (r, g, b, _a): (f32, f32, f32, f32)| {
            pixels[position.y() * *width + position.x()] = Vec3::new(r, g, b);
        },
    )
    .map_err(|source| ReferenceError::Read {
        path: path.display().to_string(),
        source,
    })?;
    let size = image.layer_data.size;
    let (_, pixels) = image.layer_data.channel_data.pixels;
    let (width, height) = (size.width() as u32, size.height() as u32);
    if pixels.iter().any(|p| !p.is_finite()) {
        return Err(ReferenceError::NotFinite(path.display().to_string()));
    }
    Ok(LinearImage {
        width,
        height,
        pixels,
    })
}

impl LinearImage {
    /// An error unless the image is `width` × `height`.
    pub fn check_size(&self, path: &Path, width: u32, height: u32) -> Result<(), ReferenceError> {
        if (self.width, self.height) != (width, height) {
            return Err(ReferenceError::Size {
                path: path.display().to_string(),
                found: (self.width, self.height),
                expected: (width, height),
            });
        }
        Ok(())
    }
}
