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

/// Where an image came from, recorded in the files written: PNG text
/// chunks, an EXR comment.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Provenance {
    /// `(keyword, text)` pairs, e.g. `("raylab:camera", "P0=(…) t=(…) …")`.
    pub entries: Vec<(String, String)>,
}

impl Provenance {
    /// The provenance of a render of `camera` from `scene_file` at `spp` samples per pixel.
    pub fn of_render(camera: &renderer::Camera, scene_file: Option<&Path>, spp: u32) -> Self {
        let v = |v: Vec3| format!("({}, {}, {})", v.x, v.y, v.z);
        let camera_text = format!(
            "P0={} t={} u={} theta={}deg d={} w={} h={}",
            v(camera.p0),
            v(camera.t),
            v(camera.u),
            camera.theta.to_degrees(),
            camera.d,
            camera.w,
            camera.h
        );
        let mut entries = vec![
            (
                "Software".to_owned(),
                format!("raylab {}", env!("CARGO_PKG_VERSION")),
            ),
            ("raylab:camera".to_owned(), camera_text),
            ("raylab:spp".to_owned(), spp.to_string()),
        ];
        if let Some(file) = scene_file {
            let file = std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf());
            entries.push(("raylab:scene".to_owned(), file.display().to_string()));
        }
        Provenance { entries }
    }

    /// Records the exposure and tone curve a picture's colour is shown
    /// with (nothing for the identity view: radiance as rendered, clamped).
    pub fn with_view(mut self, view: scene::View) -> Self {
        if !view.is_identity() {
            let text = format!(
                "exposure={:+} EV tonemap={}",
                view.exposure,
                view.tonemap.name()
            );
            self.entries.push(("raylab:view".to_owned(), text));
        }
        self
    }

    /// Records which diagnostic display a picture shows (nothing for the colour).
    pub fn with_display(mut self, display: renderer::display::Display) -> Self {
        if display != renderer::display::Display::Color {
            let label = display.label().to_owned();
            self.entries.push(("raylab:display".to_owned(), label));
        }
        self
    }

    /// The value recorded under `keyword`.
    pub fn get(&self, keyword: &str) -> Option<&str> {
        self.entries
            .iter()
            .find(|(k, _)| k == keyword)
            .map(|(_, v)| v.as_str())
    }
}

/// Writes linear RGB pixels (row 0 at the top) as an 8-bit sRGB PNG shown
/// through `view` (exposure and tone curve), with `provenance` as UTF-8
/// text chunks.
pub fn write_png(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Vec3],
    view: scene::View,
    provenance: &Provenance,
) -> Result<()> {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|&c| {
            renderer::display::srgb::linear_to_srgb8(renderer::display::view::apply(view, c))
        })
        .collect();
    write_png_srgb8(path, width, height, &bytes, provenance)
}

/// Writes 8-bit sRGB RGB bytes (row 0 at the top, three per pixel) as a PNG,
/// with `provenance` as UTF-8 text chunks: a diagnostic picture as shown.
pub fn write_png_srgb8(
    path: &Path,
    width: u32,
    height: u32,
    bytes: &[u8],
    provenance: &Provenance,
) -> Result<()> {
    let write = || -> std::result::Result<(), png::EncodingError> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut encoder = png::Encoder::new(file, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        for (keyword, text) in &provenance.entries {
            encoder.add_itxt_chunk(keyword.clone(), text.clone())?;
        }
        let mut writer = encoder.write_header()?;
        writer.write_image_data(bytes)?;
        writer.finish()
    };
    write().with_context(|| format!("cannot write {}", path.display()))
}

/// Reads the text chunks of a PNG written by [`write_png`].
#[cfg(test)]
pub fn read_png_provenance(path: &Path) -> Result<Provenance> {
    let file = std::io::BufReader::new(
        std::fs::File::open(path).with_context(|| format!("cannot open {}", path.display()))?,
    );
    let reader = png::Decoder::new(file).read_info()?;
    let info = reader.info();
    let mut entries = Vec::new();
    for chunk in &info.utf8_text {
        entries.push((chunk.keyword.clone(), chunk.get_text()?));
    }
    for chunk in &info.uncompressed_latin1_text {
        entries.push((chunk.keyword.clone(), chunk.text.clone()));
    }
    Ok(Provenance { entries })
}

/// The provenance [`write_exr`] recorded in an EXR's comments ("keyword:
/// text" lines); empty for an EXR without them.
pub fn read_exr_provenance(path: &Path) -> Result<Provenance> {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let comments = meta
        .headers
        .first()
        .and_then(|h| h.own_attributes.comments.as_ref())
        .map(|t| t.to_string())
        .unwrap_or_default();
    let entries = comments
        .lines()
        .filter_map(|line| line.split_once(": "))
        .map(|(k, v)| (k.to_owned(), v.to_owned()))
        .collect();
    Ok(Provenance { entries })
}

/// Writes float channels (interleaved per pixel, row 0 at the top) as a
/// float32 EXR with the given channel names, e.g. `["R", "G", "B"]` or `["Z"]`.
pub fn write_exr(
    path: &Path,
    width: u32,
    height: u32,
    names: &[&str],
    values: &[f32],
    provenance: &Provenance,
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
    let comment: Vec<String> = provenance
        .entries
        .iter()
        .map(|(k, v)| format!("{k}: {v}"))
        .collect();
    let mut attributes = LayerAttributes::named("raylab");
    attributes.comments = Text::new_or_none(comment.join("\n"));
    let layer = Layer::new(
        (width as usize, height as usize),
        attributes,
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    Image::from_layer(layer)
        .write()
        .to_file(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Prints, once per model file, what the scene's model files use that raylab
/// does not support (the rest of each file is loaded).
pub fn warn_about_models(scene: &scene::Scene) {
    for (src, warnings) in scene.model_warnings() {
        for warning in warnings {
            eprintln!("warning: {src}: {warning}");
        }
    }
}
