//! Saving the rendered image: full resolution, PNG (8-bit sRGB, the camera
//! and scene file in text chunks) or EXR (linear float), and copying it to
//! the clipboard. PNG and the clipboard take the picture as shown, in its
//! display mode; EXR always takes the linear colour.

use crate::io::output::{self, Format, Provenance};
use renderer::display::Display;
use renderer::progressive::{RenderedFrame, Step};
use std::path::Path;

/// The file name suggested for an image of `scene_name` (its extension
/// dropped) at the frame's step, with the display mode unless it is the
/// colour: `seed-64spp.png`, `seed-64spp-cost.png`.
pub fn default_file_name(scene_name: &str, step: Step, display: Display) -> String {
    let stem = Path::new(scene_name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "untitled".to_owned());
    let mode = match display {
        Display::Color => String::new(),
        other => {
            let word = other.label().split([' ', '(']).next().unwrap_or_default();
            format!("-{}", word.to_lowercase())
        }
    };
    match step {
        Step::Passes { spp } => format!("{stem}-{spp}spp{mode}.png"),
        Step::Preview { stride } => format!("{stem}-preview{stride}{mode}.png"),
    }
}

/// Samples per pixel of a frame (0 for a preview).
pub fn spp_of(step: Step) -> u32 {
    match step {
        Step::Passes { spp } => spp,
        Step::Preview { .. } => 0,
    }
}

/// Writes `frame` to `path` as PNG (the picture shown) or EXR (the linear
/// colour), chosen by the extension.
pub fn save(path: &Path, frame: &RenderedFrame, provenance: &Provenance) -> anyhow::Result<()> {
    let (w, h) = (frame.width, frame.height);
    match Format::from_path(path)? {
        Format::Png => {
            let bytes: Vec<u8> = frame
                .srgba8
                .iter()
                .flat_map(|p| [p[0], p[1], p[2]])
                .collect();
            let provenance = provenance
                .clone()
                .with_display(frame.legend.display)
                .with_view(match frame.legend.display {
                    renderer::display::Display::Color => frame.view,
                    _ => scene::View::default(),
                });
            output::write_png_srgb8(path, w, h, &bytes, &provenance)
        }
        Format::Exr => {
            let values: Vec<f32> = frame
                .linear_image()
                .iter()
                .flat_map(|p| p.to_array())
                .collect();
            output::write_exr(path, w, h, &["R", "G", "B"], &values, provenance)
        }
    }
}

/// The frame as the 8-bit sRGB picture shown on screen (the texture and the clipboard).
pub fn color_image(frame: &RenderedFrame) -> egui::ColorImage {
    let pixels = frame
        .srgba8
        .iter()
        .map(|&[r, g, b, a]| egui::Color32::from_rgba_premultiplied(r, g, b, a))
        .collect();
    egui::ColorImage::new([frame.width as usize, frame.height as usize], pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_name_is_the_scene_name_and_the_samples() {
        assert_eq!(
            default_file_name("seed.xml", Step::Passes { spp: 64 }, Display::Color),
            "seed-64spp.png"
        );
        assert_eq!(
            default_file_name("untitled", Step::Preview { stride: 8 }, Display::Color),
            "untitled-preview8.png"
        );
        assert_eq!(
            default_file_name("seed.xml", Step::Passes { spp: 4 }, Display::Cost),
            "seed-4spp-cost.png"
        );
    }
}
