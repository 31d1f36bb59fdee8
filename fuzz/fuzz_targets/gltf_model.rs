//! Fuzzes the glTF importer, `scene::load_model_bytes`, with the input as the
//! whole file (JSON `.gltf`, or `.glb` when it starts with `glTF`).
//!
//! Property: any bytes give a model or a `ModelError`, never a panic, an
//! allocation over libFuzzer's `-malloc_limit_mb` or a timeout; an error is
//! one line. The file sits in a folder that does not exist, so relative
//! buffer and image URIs fail to open (data: URIs and the GLB BIN chunk work).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let path = Path::new("/nonexistent-fuzz-dir/fuzz.gltf");
    if let Err(e) = scene::load_model_bytes(bytes.to_vec(), path) {
        let shown = e.to_string();
        assert!(!shown.contains('\n'), "error spans lines: {shown:?}");
    }
});
