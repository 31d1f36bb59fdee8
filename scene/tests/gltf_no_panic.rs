//! Damaged glTF files never panic the loader: every truncation of a small
//! .glb and many random byte changes to a .glb and a .gltf give a model or a
//! `ModelError`, nothing else.

mod gltf_common;

use gltf_common::*;
use scene::load_model;
use serde_json::json;

/// A small textured, indexed, normal-carrying model with a camera.
fn sample(storage: Storage, dir: &TempDir, name: &str) -> Vec<u8> {
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let normal = b.vec3s(&[[0.0, 0.0, 1.0]; 4]);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    // Interleaved-style stride: 2 bytes of data every 4.
    let uv_view = b.view(
        &[0, 0, 9, 9, 255, 0, 9, 9, 255, 255, 9, 9, 0, 255, 9, 9],
        Some(4),
    );
    let uv = b.accessor(Some(uv_view), BYTE, 4, "VEC2", json!({"normalized": true}));
    let mut png = std::io::Cursor::new(Vec::new());
    image::RgbaImage::from_pixel(2, 2, image::Rgba([200, 100, 50, 255]))
        .write_to(&mut png, image::ImageFormat::Png)
        .expect("png");
    let image = b.view(png.get_ref(), None);
    let doc = json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1, 2], "rotation": [0.0, 0.0, 0.6, 0.8]}, {"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv}, "indices": indices, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "roughnessFactor": 0.4, "metallicFactor": 0.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 33071}],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
    });
    let path = b.write(doc, storage, dir, name);
    std::fs::read(path).expect("written")
}

/// xorshift64*: a fixed sequence, so failures repeat.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n
    }
}

#[test]
fn every_truncation_of_a_glb_loads_or_fails_cleanly() {
    let dir = TempDir::new("truncate");
    let bytes = sample(Storage::Glb, &dir, "whole.glb");
    if let Err(e) = load_model(&dir.join("whole.glb")) {
        panic!("the whole file must load: {e}");
    }
    let path = dir.join("cut.glb");
    for len in 0..bytes.len() {
        std::fs::write(&path, &bytes[..len]).expect("write");
        if let Err(e) = load_model(&path) {
            assert!(!e.message.is_empty());
        }
    }
}

#[test]
fn random_byte_changes_load_or_fail_cleanly() {
    let dir = TempDir::new("mutate");
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut errors = 0;
    for (storage, name) in [(Storage::Glb, "m.glb"), (Storage::DataUri, "m.gltf")] {
        let bytes = sample(storage, &dir, name);
        let path = dir.join(name);
        for _ in 0..1500 {
            let mut damaged = bytes.clone();
            for _ in 0..1 + rng.below(4) {
                let at = rng.below(damaged.len());
                damaged[at] = match rng.below(4) {
                    0 => 0,
                    1 => 0xff,
                    2 => damaged[at] ^ (1 << rng.below(8)),
                    _ => b"0123456789:,[]{}\"-e."[rng.below(20)],
                };
            }
            std::fs::write(&path, &damaged).expect("write");
            if load_model(&path).is_err() {
                errors += 1;
            }
        }
    }
    // Most changes break something; some land in padding or image bytes.
    assert!(
        errors > 300,
        "only {errors} of 3000 damaged files were refused"
    );
}
