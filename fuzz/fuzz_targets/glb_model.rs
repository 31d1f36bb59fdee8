//! Fuzzes the glTF importer's GLB path with binary buffers: the input is
//! `JSON bytes, a 0 byte, BIN bytes` (JSON text cannot hold a raw 0 byte; no
//! 0 byte: JSON only, no BIN chunk). The target wraps them in a valid GLB
//! container (12-byte header, JSON chunk padded with spaces, BIN chunk padded
//! with zeros), so mutations reach the accessors, buffer views and images in
//! the BIN chunk instead of breaking the container.
//!
//! Property: as `gltf_model`: a model or a one-line `ModelError`, never a
//! panic, an oversized allocation or a timeout.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let (json, bin) = match bytes.iter().position(|&b| b == 0) {
        Some(at) => (&bytes[..at], Some(&bytes[at + 1..])),
        None => (bytes, None),
    };
    let path = Path::new("/nonexistent-fuzz-dir/fuzz.glb");
    if let Err(e) = scene::load_model_bytes(glb(json, bin), path) {
        let shown = e.to_string();
        assert!(!shown.contains('\n'), "error spans lines: {shown:?}");
    }
});

/// A GLB container holding `json` and, if given, `bin`.
fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let mut body = Vec::with_capacity(json.len() + bin.map_or(0, <[u8]>::len) + 24);
    chunk(&mut body, b"JSON", json, b' ');
    if let Some(bin) = bin {
        chunk(&mut body, b"BIN\0", bin, 0);
    }
    let mut out = Vec::with_capacity(12 + body.len());
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(12 + body.len() as u32).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// Appends a chunk (length, kind, data padded to 4 bytes with `pad`).
fn chunk(body: &mut Vec<u8>, kind: &[u8; 4], data: &[u8], pad: u8) {
    let padded = data.len().next_multiple_of(4);
    body.extend_from_slice(&(padded as u32).to_le_bytes());
    body.extend_from_slice(kind);
    body.extend_from_slice(data);
    body.resize(body.len() + padded - data.len(), pad);
}
