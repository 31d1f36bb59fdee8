//! Writing images: PNG as 8-bit sRGB, EXR as linear float32.

use anyhow::{Context, Result, bail};
use exr::prelude::*;
use glam::Vec3;
use std::path::Path;

/// The image formats `raylab render` writes, chosen by the file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// 8-bit sRGB PNG.
    Png,
    /// Linear float32 OpenEXR.
    Exr,
}

impl Format {
    /// The format for `path`'s extension, or an error naming the accepted ones.
    pub fn from_path(path: &Path) -> Result<Format> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Format::Png),
            Some("exr") => Ok(Format::Exr),
            _ => bail!(
                "{}: unknown image format; expected a .png or .exr file name",
                path.display()
            ),
        }
    }
}

/// Writes linear RGB pixels (row 0 at the top) as an 8-bit sRGB PNG.
pub fn write_png(path: &Path, width: u32, height: u32, pixels: &[Vec3]) -> Result<()> {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|&c| renderer::film::linear_to_srgb8(c))
        .collect();
    image::save_buffer(path, &bytes, width, height, image::ExtendedColorType::Rgb8)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes float channels (interleaved per pixel, row 0 at the top) as a
/// float32 EXR with the given channel names, e.g. `["R", "G", "B"]` or `["Z"]`.
pub fn write_exr(
    path: &Path,
    width: u32,
    height: u32,
    names: &[&str],
    values: &[f32],
) -> Result<()> {
    let count = names.len();
    let channels: Vec<AnyChannel<FlatSamples>> = names
        .iter()
        .enumerate()
        .map(|(c, name)| {
            let samples = values.iter().skip(c).step_by(count).copied().collect();
            AnyChannel::new(*name, FlatSamples::F32(samples))
        })
        .collect();
    let layer = Layer::new(
        (width as usize, height as usize),
        LayerAttributes::named("raylab"),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    Image::from_layer(layer)
        .write()
        .to_file(path)
        .with_context(|| format!("cannot write {}", path.display()))
}
