//! Reading an environment map: an OpenEXR or Radiance HDR file decoded to
//! linear RGB, refused with a reason when it is missing, corrupt, not HDR,
//! absurdly large or holds a value that is not a finite, non-negative radiance.

use crate::bounded_read::read_limited;
use crate::model::EnvImage;
use image::ImageFormat;
use std::path::Path;

/// The largest file read as an environment map (as for a glTF model's files).
const MAX_FILE_BYTES: usize = 1 << 30;

/// The most texels a map may decode to (2^26, as a glTF file's textures:
/// an 8192 × 8192 map; 768 MiB as linear RGB).
pub const MAX_TEXELS: u64 = 1 << 26;

/// The map in the file at `path`, or why it cannot be one.
pub fn load_sky_map(path: &Path) -> Result<EnvImage, String> {
    let bytes = read_limited(path, MAX_FILE_BYTES)?;
    let format = match image::guess_format(&bytes) {
        Ok(format @ (ImageFormat::OpenExr | ImageFormat::Hdr)) => format,
        Ok(other) => {
            return Err(format!(
                "it is a {other:?} image; an environment map must be high dynamic range, \
                 OpenEXR (.exr) or Radiance HDR (.hdr)"
            ));
        }
        Err(_) => {
            return Err(
                "it is neither an OpenEXR (.exr) nor a Radiance HDR (.hdr) image".to_string(),
            );
        }
    };
    let cannot = |e: image::ImageError| format!("cannot decode its {format:?} data: {e}");
    let reader = || image::ImageReader::with_format(std::io::Cursor::new(&bytes), format);
    let (width, height) = reader().into_dimensions().map_err(cannot)?;
    let texels = u64::from(width) * u64::from(height);
    if texels == 0 {
        return Err(format!("it is {width} × {height} pixels: empty"));
    }
    if texels > MAX_TEXELS {
        return Err(format!(
            "it is {width} × {height} pixels, more than the {MAX_TEXELS} raylab decodes \
             (8192 × 8192); scale it down"
        ));
    }
    let decoded = reader().decode().map_err(cannot)?.into_rgb32f();
    let (width, height) = decoded.dimensions();
    let texels: Vec<[f32; 3]> = decoded
        .into_raw()
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    if let Some(i) = texels
        .iter()
        .position(|t| t.iter().any(|c| !c.is_finite() || *c < 0.0))
    {
        let (x, y) = (i % width as usize, i / width as usize);
        let [r, g, b] = texels[i];
        return Err(format!(
            "pixel ({x}, {y}) is ({r}, {g}, {b}); radiance must be finite and not negative"
        ));
    }
    Ok(EnvImage {
        path: path.to_path_buf(),
        width,
        height,
        texels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// A Radiance HDR file of `width × height` pixels from `pixel(x, y)`.
    fn hdr_file(
        dir: &Path,
        name: &str,
        width: u32,
        height: u32,
        pixel: impl Fn(u32, u32) -> [f32; 3],
    ) -> std::path::PathBuf {
        let path = dir.join(name);
        let pixels: Vec<image::Rgb<f32>> = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| image::Rgb(pixel(x, y)))
            .collect();
        let file = std::fs::File::create(&path).expect("a new file");
        image::codecs::hdr::HdrEncoder::new(file)
            .encode(&pixels, width as usize, height as usize)
            .expect("written");
        path
    }

    #[test]
    fn an_hdr_file_loads_row_by_row_from_the_top() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        // Powers of two survive RGBE's shared exponent exactly.
        let path = hdr_file(dir.path(), "sky.hdr", 3, 2, |x, y| {
            [x as f32, y as f32 * 4.0, 0.5]
        });
        let map = load_sky_map(&path).expect("a valid map");
        assert_eq!((map.width, map.height), (3, 2));
        assert_eq!(map.texel(2, 0), [2.0, 0.0, 0.5]);
        assert_eq!(map.texel(1, 1), [1.0, 4.0, 0.5]);
    }

    #[test]
    fn a_missing_file_says_it_cannot_be_read() {
        let err = load_sky_map(Path::new("/nonexistent/sky.exr")).expect_err("refused");
        assert!(err.contains("cannot read"), "{err}");
    }

    #[test]
    fn a_png_is_refused_as_not_high_dynamic_range() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("sky.png");
        image::RgbImage::new(4, 2).save(&path).expect("written");
        let err = load_sky_map(&path).expect_err("refused");
        assert!(
            err.contains("Png") && err.contains("high dynamic range"),
            "{err}"
        );
    }

    #[test]
    fn a_corrupt_file_says_it_cannot_be_decoded() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("sky.hdr");
        let mut file = std::fs::File::create(&path).expect("a new file");
        file.write_all(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n\x02\x02")
            .expect("written");
        let err = load_sky_map(&path).expect_err("refused");
        assert!(err.contains("cannot decode"), "{err}");
    }

    #[test]
    fn a_map_claiming_too_many_pixels_is_refused_before_decoding() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("huge.hdr");
        std::fs::write(
            &path,
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 20000\n",
        )
        .expect("written");
        let err = load_sky_map(&path).expect_err("refused");
        assert!(
            err.contains("20000 × 20000") && err.contains("scale it down"),
            "{err}"
        );
    }

    #[test]
    fn a_nan_in_an_exr_names_its_pixel() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("sky.exr");
        exr::prelude::write_rgb_file(&path, 4, 2, |x, y| {
            if (x, y) == (3, 1) {
                (f32::NAN, 0.0, 0.0)
            } else {
                (1.0, 1.0, 1.0)
            }
        })
        .expect("written");
        let err = load_sky_map(&path).expect_err("refused");
        assert!(
            err.contains("pixel (3, 1)") && err.contains("finite"),
            "{err}"
        );
    }

    #[test]
    fn an_exr_loads_its_linear_values_exactly() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("sky.exr");
        exr::prelude::write_rgb_file(&path, 4, 2, |x, y| {
            (x as f32 * 0.25, y as f32 * 7.5, 123.25)
        })
        .expect("written");
        let map = load_sky_map(&path).expect("a valid map");
        assert_eq!(map.texel(3, 1), [0.75, 7.5, 123.25]);
    }
}
