//! From the file's bytes to a validated glTF document: the GLB container,
//! the JSON, and the `gltf` crate's validation (minus its refusal of
//! required extensions, which raylab reports as warnings instead).

use ::gltf::Document;
use ::gltf::json::validation::{Checked, Error as ValidationError, Validate};

/// A parsed file: the document and, for `.glb`, its BIN chunk.
pub(super) struct Parsed {
    /// The validated document.
    pub doc: Document,
    /// The GLB's binary chunk (buffer 0 when that buffer has no URI).
    pub blob: Option<Vec<u8>>,
}

/// Parses a `.gltf` (JSON) or `.glb` (binary container) file.
pub(super) fn parse(bytes: &[u8]) -> Result<Parsed, String> {
    let (json, blob) = if bytes.starts_with(b"glTF") {
        let glb = split_glb(bytes)?;
        (glb.json, glb.bin.map(<[u8]>::to_vec))
    } else {
        (bytes, None)
    };
    let root: ::gltf::json::Root =
        ::gltf::json::deserialize::from_slice(json).map_err(|e| explain_json_error(json, &e))?;
    let doc = Document::from_json_without_validation(root);
    validate(&doc)?;
    Ok(Parsed { doc, blob })
}

/// The chunks of a GLB file.
#[derive(Debug)]
struct Glb<'a> {
    json: &'a [u8],
    bin: Option<&'a [u8]>,
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a GLB container (12-byte header, a JSON chunk, an optional BIN
/// chunk) with every length checked against the data.
fn split_glb(bytes: &[u8]) -> Result<Glb<'_>, String> {
    let version = u32_at(bytes, 4).ok_or("GLB: the 12-byte header is cut short")?;
    if version != 2 {
        return Err(format!(
            "GLB: container version {version} is not supported (glTF 2.0 uses version 2)"
        ));
    }
    let length = u32_at(bytes, 8).ok_or("GLB: the 12-byte header is cut short")? as usize;
    if length > bytes.len() {
        return Err(format!(
            "GLB: the header gives a length of {length} bytes but the file has {}",
            bytes.len()
        ));
    }
    let bytes = &bytes[..length];
    let mut at = 12;
    let mut chunks = Vec::new();
    while at < bytes.len() {
        let (Some(chunk_length), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(format!("GLB: chunk header at byte {at} is cut short"));
        };
        let start = at + 8;
        let end = start
            .checked_add(chunk_length as usize)
            .filter(|&end| end <= bytes.len())
            .ok_or_else(|| {
                format!(
                    "GLB: chunk at byte {at} claims {chunk_length} bytes, past the end of the file ({} bytes)",
                    bytes.len()
                )
            })?;
        chunks.push((kind.to_le_bytes(), &bytes[start..end]));
        // Chunks start on 4-byte boundaries.
        at = end.next_multiple_of(4);
    }
    let json = match chunks.first().copied() {
        Some(([b'J', b'S', b'O', b'N'], data)) => data,
        Some(_) => return Err("GLB: the first chunk is not the JSON chunk".into()),
        None => return Err("GLB: the file has no JSON chunk".into()),
    };
    let bin = chunks
        .get(1)
        .filter(|(kind, _)| kind == b"BIN\0")
        .map(|&(_, data)| data);
    Ok(Glb { json, bin })
}

/// A JSON error, with a hint when the file is glTF 1.0 or not glTF at all.
fn explain_json_error(json: &[u8], error: &::gltf::json::Error) -> String {
    let version = ::gltf::json::deserialize::from_slice::<::gltf::json::Value>(json)
        .ok()
        .and_then(|v| v.get("asset")?.get("version")?.as_str().map(str::to_owned));
    match version {
        Some(v) if !v.starts_with("2.") => {
            format!("glTF version {v} is not supported (raylab reads glTF 2.0)")
        }
        _ => format!("not a valid glTF 2.0 file: {error}"),
    }
}

/// Runs the `gltf` crate's validation (every index in range, every enum
/// known…). Required extensions that the crate does not know are left to
/// [`super::warnings`], which reports them and loads the rest. Accessors
/// without a bufferView, primitives without POSITION and POSITION accessors
/// without min/max, which the crate refuses, are accepted: glTF allows the
/// first two and raylab does not need the third.
fn validate(doc: &Document) -> Result<(), String> {
    let root = doc.as_json();
    if !root.asset.version.starts_with("2.") {
        return Err(format!(
            "glTF version {} is not supported (raylab reads glTF 2.0)",
            root.asset.version
        ));
    }
    // The crate's primitive check indexes `accessors` with POSITION's
    // accessor before checking it exists: check it first.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, accessor) in &primitive.attributes {
                if accessor.value() >= root.accessors.len() {
                    let name = match semantic {
                        Checked::Valid(s) => s.to_string(),
                        Checked::Invalid => "an attribute".into(),
                    };
                    return Err(format!(
                        "invalid glTF: meshes[{m}].primitives[{p}].attributes[\"{name}\"]: accessor {} does not exist (the file has {})",
                        accessor.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    let mut errors = Vec::new();
    root.validate(root, ::gltf::json::Path::new, &mut |path, error| {
        let path = path();
        let required_extension = path.as_str().starts_with("extensionsRequired")
            && error == ValidationError::Unsupported;
        // glTF 2.0 allows an accessor without bufferView (zeros, or data an
        // extension such as Draco provides); the crate insists on one.
        let viewless_accessor = path.as_str().starts_with("accessors[")
            && path.as_str().ends_with("].bufferView")
            && error == ValidationError::Missing;
        // POSITION may be absent (the primitive is skipped) and its min/max
        // are not needed here; the crate requires both.
        let position = path.as_str().contains(".attributes[\"POSITION\"]")
            && matches!(error, ValidationError::Missing | ValidationError::Invalid);
        if !required_extension && !viewless_accessor && !position {
            errors.push(format!("{path}: {error}"));
        }
    });
    if errors.is_empty() {
        return Ok(());
    }
    const SHOWN: usize = 5;
    let more = if errors.len() > SHOWN {
        format!(" (and {} more)", errors.len() - SHOWN)
    } else {
        String::new()
    };
    errors.truncate(SHOWN);
    Err(format!("invalid glTF: {}{more}", errors.join("; ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(chunks: &[(&[u8; 4], &[u8])]) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend_from_slice(&(data.len() as u32).to_le_bytes());
            body.extend_from_slice(*kind);
            body.extend_from_slice(data);
            while body.len() % 4 != 0 {
                body.push(0);
            }
        }
        let mut out = b"glTF".to_vec();
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(12 + body.len() as u32).to_le_bytes());
        out.extend_from_slice(&body);
        out
    }

    #[test]
    fn glb_chunks_are_split_at_their_lengths() {
        let bytes = glb(&[(b"JSON", b"{}  "), (b"BIN\0", &[1, 2, 3])]);
        let glb = split_glb(&bytes).expect("valid container");
        assert_eq!(glb.json, b"{}  ");
        assert_eq!(glb.bin, Some(&[1u8, 2, 3][..]));
    }

    #[test]
    fn glb_lengths_past_the_end_are_errors_not_panics() {
        let mut bytes = glb(&[(b"JSON", b"{}  ")]);
        // Chunk length far beyond the file.
        bytes[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = split_glb(&bytes).expect_err("chunk too long");
        assert!(e.contains("past the end"), "{e}");
        // Header length beyond the file, and a header cut short.
        let mut bytes = glb(&[(b"JSON", b"{}  ")]);
        bytes[8..12].copy_from_slice(&1000u32.to_le_bytes());
        assert!(split_glb(&bytes).expect_err("too long").contains("1000"));
        assert!(split_glb(b"glTF\x02\0").is_err());
        // A BIN chunk first.
        let bytes = glb(&[(b"BIN\0", b"abcd")]);
        assert!(split_glb(&bytes).expect_err("no json").contains("JSON"));
    }

    #[test]
    fn glb_version_1_is_refused_by_name() {
        let mut bytes = glb(&[(b"JSON", b"{}  ")]);
        bytes[4..8].copy_from_slice(&1u32.to_le_bytes());
        assert!(split_glb(&bytes).expect_err("v1").contains("version 1"));
    }

    #[test]
    fn gltf_1_json_is_named_as_such() {
        let e = parse(br#"{"asset": {"version": "1.0"}, "meshes": {"a": {}}}"#)
            .err()
            .expect("glTF 1.0");
        assert!(e.contains("version 1.0"), "{e}");
    }

    #[test]
    fn validation_errors_name_the_json_path() {
        let e = parse(br#"{"asset": {"version": "2.0"}, "scenes": [{"nodes": [3]}]}"#)
            .err()
            .expect("node 3 does not exist");
        assert!(e.contains("scenes[0].nodes[0]"), "{e}");
    }

    #[test]
    fn accessors_without_buffer_views_pass_validation() {
        parse(
            br#"{"asset": {"version": "2.0"},
                "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3"}]}"#,
        )
        .expect("zeros by the glTF spec");
    }

    #[test]
    fn unknown_required_extensions_do_not_fail_validation() {
        let parsed = parse(
            br#"{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_draco_mesh_compression"],
                "extensionsRequired": ["KHR_draco_mesh_compression"]}"#,
        )
        .expect("loads; the extension is warned about elsewhere");
        assert_eq!(parsed.doc.extensions_required().count(), 1);
    }
}
