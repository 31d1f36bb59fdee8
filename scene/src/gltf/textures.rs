//! Base-colour textures: the image (PNG or JPEG; in a buffer view, a
//! `data:` URI or a file) decoded to RGBA8 sRGB texels, with the sampler's
//! wrap modes. Filters are not kept: raylab samples as it chooses.

use super::buffers::{Buffers, MAX_FILE_BYTES, read_uri};
use super::warnings::Warnings;
use crate::model::model_file::{Texture, Wrap};
use ::gltf::texture::WrappingMode;
use image::ImageFormat;
use std::path::Path;
use std::sync::Arc;

/// A decoded image: width, height and RGBA8 sRGB texels row by row from the top.
pub(super) type Texels = (u32, u32, Arc<[[u8; 4]]>);

/// The wrap mode raylab uses for a glTF one.
pub(super) fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
    }
}

/// The (u, v) wrap modes of a texture's sampler.
pub(super) fn wraps(texture: &::gltf::Texture) -> (Wrap, Wrap) {
    let sampler = texture.sampler();
    (wrap(sampler.wrap_s()), wrap(sampler.wrap_t()))
}

/// Decodes `image` to RGBA8 texels, or `None` with a warning when its format
/// is not PNG or JPEG. A missing or corrupt image is an error. The image's
/// JSON is read directly: the `gltf` crate panics on a bufferView without
/// mimeType or an image with neither uri nor bufferView.
pub(super) fn decode(
    doc: &::gltf::Document,
    image: &::gltf::Image,
    buffers: &Buffers,
    base: &Path,
    warnings: &mut Warnings,
) -> Result<Option<Texels>, String> {
    let name = match image.name() {
        Some(name) => format!("image {} \"{name}\"", image.index()),
        None => format!("image {}", image.index()),
    };
    let json = doc
        .as_json()
        .images
        .get(image.index())
        .ok_or_else(|| format!("{name} does not exist"))?;
    let mime = json.mime_type.as_ref().map(|m| m.0.as_str());
    let view = json.buffer_view.and_then(|v| doc.views().nth(v.value()));
    let bytes = match (view, &json.uri) {
        (Some(view), _) => buffers
            .view(&view)
            .map_err(|e| format!("{name}: {e}"))?
            .to_vec(),
        (None, Some(uri)) => {
            read_uri(uri, base, MAX_FILE_BYTES).map_err(|e| format!("{name}: {e}"))?
        }
        (None, None) => return Err(format!("{name} has neither a uri nor a bufferView")),
    };
    let format = match image::guess_format(&bytes) {
        Ok(format @ (ImageFormat::Png | ImageFormat::Jpeg)) => format,
        other => {
            let what = match (other, mime) {
                (Ok(format), _) => format!("{format:?}"),
                (Err(_), Some(mime)) => mime.to_owned(),
                (Err(_), None) => "an unknown format".to_owned(),
            };
            warnings.once(&format!("image format {what}"), || {
                format!("{name} is in {what}, which raylab does not decode (only PNG and JPEG): textures using it are ignored")
            });
            return Ok(None);
        }
    };
    let cannot = |e: image::ImageError| format!("{name}: cannot decode its {format:?} data: {e}");
    let reader = || image::ImageReader::with_format(std::io::Cursor::new(&bytes), format);
    // The header's size is taken from the file's allowance before decoding.
    let (width, height) = reader().into_dimensions().map_err(cannot)?;
    buffers
        .take_texels(u64::from(width) * u64::from(height), bytes.len())
        .map_err(|e| format!("{name} ({width} × {height}): {e}"))?;
    let decoded = reader().decode().map_err(cannot)?.into_rgba8();
    let (width, height) = decoded.dimensions();
    let texels = decoded
        .into_raw()
        .chunks_exact(4)
        .map(|t| [t[0], t[1], t[2], t[3]])
        .collect();
    Ok(Some((width, height, texels)))
}

/// A [`Texture`] from decoded texels and wrap modes.
pub(super) fn texture((width, height, texels): Texels, (wrap_u, wrap_v): (Wrap, Wrap)) -> Texture {
    Texture {
        width,
        height,
        texels,
        wrap_u,
        wrap_v,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_modes_map_one_to_one() {
        assert_eq!(wrap(WrappingMode::Repeat), Wrap::Repeat);
        assert_eq!(wrap(WrappingMode::MirroredRepeat), Wrap::MirroredRepeat);
        assert_eq!(wrap(WrappingMode::ClampToEdge), Wrap::ClampToEdge);
    }
}
