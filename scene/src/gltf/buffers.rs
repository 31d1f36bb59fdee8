//! Buffer data: the GLB's BIN chunk, `data:` URIs and external files
//! (relative to the model file), and checked slices of buffer views; and
//! what the file may decode from them (accessor elements, image texels), in
//! proportion to its size, so a small file cannot ask for gigabytes.

use super::warnings::MESHOPT;
use ::gltf::Document;
use ::gltf::buffer::{Data, Source, View};
use std::cell::Cell;
use std::path::{Path, PathBuf};

/// Every buffer's bytes, and what the file may still decode. `None` only for
/// a buffer without data that the meshopt extension leaves as a fallback:
/// reading from it is skipped.
#[derive(Debug)]
pub(super) struct Buffers {
    data: Vec<Option<Vec<u8>>>,
    /// How many more accessor elements this file may decode; see
    /// [`Buffers::take_elements`].
    elements_left: Cell<usize>,
    /// How many more image texels this file may decode, before what each
    /// image's own bytes allow; see [`Buffers::take_texels`].
    texels_left: Cell<u64>,
}

/// Image texels any file may decode beyond [`TEXELS_PER_IMAGE_BYTE`] per
/// byte of its images (2^26: four 4096² textures, 256 MiB as RGBA8).
const TEXELS_ALLOWED: u64 = 1 << 26;

/// Texels an image may decode to per byte of its encoded data: 256 bytes of
/// RGBA8 per byte, far beyond what PNG or JPEG achieves on real textures,
/// but a flat colour compresses about 1000:1.
const TEXELS_PER_IMAGE_BYTE: u64 = 64;

/// Accessor elements any file may decode beyond [`ELEMENTS_PER_BUFFER_BYTE`]
/// per byte of its buffers (2^20: a million-vertex mesh).
const ELEMENTS_ALLOWED: usize = 1 << 20;

/// Accessor elements a file may decode per byte of its buffers. An element
/// takes at least one byte, so a file whose accessors are each read once
/// uses at most one per byte; the rest allows accessors that several
/// primitives share.
const ELEMENTS_PER_BUFFER_BYTE: usize = 4;

/// Loads every buffer of `doc`; external files are looked up beside `base`.
pub(super) fn load(doc: &Document, base: &Path, blob: Option<Vec<u8>>) -> Result<Buffers, String> {
    let meshopt = doc.extensions_used().any(|e| e == MESHOPT);
    let mut blob = blob;
    let mut data = Vec::with_capacity(doc.buffers().len());
    for buffer in doc.buffers() {
        let name = match buffer.name() {
            Some(name) => format!("buffer {} \"{name}\"", buffer.index()),
            None => format!("buffer {}", buffer.index()),
        };
        let bytes = match buffer.source() {
            _ if buffer.length() > MAX_FILE_BYTES => {
                return Err(format!(
                    "{name} claims {} bytes, more than the {MAX_FILE_BYTES} raylab reads",
                    buffer.length()
                ));
            }
            // A buffer needs only its byteLength; the rest of its file is never read.
            Source::Uri(uri) => {
                read_uri(uri, base, buffer.length()).map_err(|e| format!("{name}: {e}"))?
            }
            // Only the first buffer may be the GLB's BIN chunk.
            Source::Bin if buffer.index() == 0 && blob.is_some() => blob.take().unwrap_or_default(),
            Source::Bin if meshopt => {
                data.push(None);
                continue;
            }
            Source::Bin => {
                return Err(format!(
                    "{name} has no uri and is not the binary chunk of a .glb, so its data is missing"
                ));
            }
        };
        if bytes.len() < buffer.length() {
            return Err(format!(
                "{name} should hold {} bytes but its data has only {}",
                buffer.length(),
                bytes.len()
            ));
        }
        data.push(Some(bytes));
    }
    let buffer_bytes: usize = data.iter().flatten().map(Vec::len).sum();
    let allowed =
        ELEMENTS_ALLOWED.saturating_add(buffer_bytes.saturating_mul(ELEMENTS_PER_BUFFER_BYTE));
    Ok(Buffers {
        data,
        elements_left: Cell::new(allowed),
        texels_left: Cell::new(TEXELS_ALLOWED),
    })
}

impl Buffers {
    /// Takes `count` elements from what this file may still decode, or says
    /// why not. Every accessor read takes its count, so memory stays in
    /// proportion to the file even when accessors without a buffer view
    /// (zeros, whose count nothing in the file bounds) or one accessor read
    /// by thousands of primitives ask for more.
    pub(super) fn take_elements(&self, count: usize) -> Result<(), String> {
        let left = self.elements_left.get();
        if count > left {
            return Err(format!(
                "its {count} elements would exceed what raylab decodes from a file of this size ({left} elements left of {ELEMENTS_ALLOWED} plus {ELEMENTS_PER_BUFFER_BYTE} per byte of its buffers)"
            ));
        }
        self.elements_left.set(left - count);
        Ok(())
    }

    /// Takes `texels` from what this file may still decode, for an image of
    /// `encoded` bytes (which adds [`TEXELS_PER_IMAGE_BYTE`] per byte), or
    /// says why not: a small image that claims or compresses to a huge one,
    /// or many such images, cannot make the file allocate gigabytes.
    pub(super) fn take_texels(&self, texels: u64, encoded: usize) -> Result<(), String> {
        let own = (encoded as u64).saturating_mul(TEXELS_PER_IMAGE_BYTE);
        let left = self.texels_left.get();
        let Some(rest) = left.saturating_add(own).checked_sub(texels) else {
            return Err(format!(
                "its {texels} texels would exceed what raylab decodes from images of this size ({left} texels left of {TEXELS_ALLOWED}, plus {TEXELS_PER_IMAGE_BYTE} per byte of each image)"
            ));
        };
        self.texels_left.set(rest.min(left));
        Ok(())
    }

    /// Whether the buffer holds data (false for a meshopt fallback buffer).
    pub(super) fn has_data(&self, buffer: usize) -> bool {
        matches!(self.data.get(buffer), Some(Some(_)))
    }

    /// The bytes of `view`, checked against its buffer.
    pub(super) fn view(&self, view: &View) -> Result<&[u8], String> {
        let buffer = view.buffer().index();
        let bytes = self
            .data
            .get(buffer)
            .and_then(Option::as_deref)
            .ok_or_else(|| {
                format!(
                    "bufferView {} reads buffer {buffer}, which has no data",
                    view.index()
                )
            })?;
        view.offset()
            .checked_add(view.length())
            .and_then(|end| bytes.get(view.offset()..end))
            .ok_or_else(|| {
                format!(
                    "bufferView {} (bytes {}..{}) lies outside buffer {buffer} ({} bytes)",
                    view.index(),
                    view.offset(),
                    view.offset().saturating_add(view.length()),
                    bytes.len()
                )
            })
    }
}

/// The bytes a URI names: a base64 `data:` URI, or a file relative to `base`
/// (percent-encoded as URIs are), or a `file:` URI, of which only the first
/// `limit` bytes are read. Network URIs are refused, never fetched.
pub(super) fn read_uri(uri: &str, base: &Path, limit: usize) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, payload)) = rest.split_once(";base64,") else {
            return Err(
                "its data: URI is not base64-encoded (only \";base64,\" data URIs are supported)"
                    .into(),
            );
        };
        let Data(mut bytes) = Data::from_source(Source::Uri(uri), None)
            .map_err(|e| format!("its data: URI is not valid base64: {e}"))?;
        // The crate pads to a multiple of 4 bytes; keep exactly the decoded length.
        let decoded = payload.trim_end_matches('=').len() * 3 / 4;
        bytes.truncate(decoded);
        return Ok(bytes);
    }
    let path = file_path(uri, base)?;
    crate::bounded_read::read_prefix(&path, limit)
        .map_err(|e| format!("\"{}\": {e}", path.display()))
}

/// The most bytes raylab reads from one model, buffer or image file (1 GiB):
/// a file that claims more is refused before anything that size is allocated.
pub(super) const MAX_FILE_BYTES: usize = 1 << 30;

/// The file a non-data URI names.
fn file_path(uri: &str, base: &Path) -> Result<PathBuf, String> {
    let decoded = percent_decode(uri)?;
    if let Some(rest) = decoded.strip_prefix("file://") {
        return Ok(PathBuf::from(rest));
    }
    if let Some(rest) = decoded.strip_prefix("file:") {
        return Ok(PathBuf::from(rest));
    }
    // A scheme is letters, digits, '+', '-' or '.' before the first ':'
    // (a Windows drive letter would be a single letter).
    if let Some((scheme, _)) = decoded.split_once(':') {
        let is_scheme = scheme.len() > 1
            && scheme
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c));
        if is_scheme {
            return Err(format!(
                "URI scheme \"{scheme}:\" is not supported (only files and data: URIs)"
            ));
        }
    }
    Ok(base.join(decoded))
}

/// Decodes `%XX` escapes; the result must be UTF-8.
fn percent_decode(uri: &str) -> Result<String, String> {
    if !uri.contains('%') {
        return Ok(uri.to_owned());
    }
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("URI \"{uri}\" has a bad %-escape at byte {i}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("URI \"{uri}\" does not decode to UTF-8"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_buffers() -> Buffers {
        Buffers {
            data: Vec::new(),
            elements_left: Cell::new(ELEMENTS_ALLOWED),
            texels_left: Cell::new(TEXELS_ALLOWED),
        }
    }

    #[test]
    fn an_image_decodes_its_own_allowance_and_then_the_files() {
        let b = no_buffers();
        // 1,000 bytes allow 64,000 texels of their own; the pool is untouched.
        b.take_texels(64_000, 1_000).expect("within its own");
        assert_eq!(b.texels_left.get(), TEXELS_ALLOWED);
        // Its own allowance does not carry over to the next image.
        b.take_texels(64_000 + 5, 1_000).expect("5 from the pool");
        assert_eq!(b.texels_left.get(), TEXELS_ALLOWED - 5);
        b.take_texels(TEXELS_ALLOWED - 5, 0)
            .expect("the rest of the pool");
        let e = b.take_texels(1, 0).expect_err("the pool is empty");
        assert!(e.contains("its 1 texels would exceed"), "{e}");
        assert!(e.contains("(0 texels left"), "{e}");
        b.take_texels(64, 1)
            .expect("an image's own allowance still holds");
        assert!(b.take_texels(u64::MAX, 1 << 30).is_err(), "no overflow");
    }

    #[test]
    fn accessor_elements_come_from_one_pool() {
        let b = no_buffers();
        b.take_elements(ELEMENTS_ALLOWED - 1).expect("within");
        b.take_elements(1).expect("the last");
        let e = b.take_elements(1).expect_err("none left");
        assert!(e.contains("its 1 elements would exceed"), "{e}");
    }

    #[test]
    fn data_uris_decode_to_their_exact_length() {
        // "hello" is 5 bytes; the crate pads to 8, read_uri keeps 5.
        let bytes = read_uri(
            "data:application/octet-stream;base64,aGVsbG8=",
            Path::new("."),
            16,
        )
        .expect("valid base64");
        assert_eq!(bytes, b"hello");
        let e = read_uri("data:text/plain,hello", Path::new("."), 16).expect_err("not base64");
        assert!(e.contains("base64"), "{e}");
        assert!(read_uri("data:;base64,@@@@", Path::new("."), 16).is_err());
    }

    #[test]
    fn relative_uris_are_percent_decoded_beside_the_model() {
        assert_eq!(
            file_path("my%20mesh.bin", Path::new("/models")).expect("relative"),
            PathBuf::from("/models/my mesh.bin")
        );
        assert_eq!(
            file_path("file:///tmp/a.bin", Path::new("/models")).expect("file uri"),
            PathBuf::from("/tmp/a.bin")
        );
        let e = file_path("https://example.org/a.bin", Path::new(".")).expect_err("remote");
        assert!(e.contains("https:"), "{e}");
        assert!(percent_decode("bad%zzescape").is_err());
        assert!(percent_decode("cut%2").is_err());
        assert!(percent_decode("%ff%fe").is_err(), "not UTF-8");
    }

    #[test]
    fn missing_files_name_the_path() {
        let e =
            read_uri("no-such-file.bin", Path::new("/nonexistent-dir"), 16).expect_err("missing");
        assert!(e.contains("/nonexistent-dir/no-such-file.bin"), "{e}");
    }
}
