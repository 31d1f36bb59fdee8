//! Helpers for the tests that write glTF files: a builder for one binary
//! buffer with its views and accessors, GLB packing, base64, and a
//! temporary folder.
#![allow(dead_code)]

use serde_json::{Value, json};
use std::path::PathBuf;

pub const BYTE: u32 = 5121;
pub const SHORT: u32 = 5123;
pub const INT: u32 = 5125;
pub const FLOAT: u32 = 5126;

/// A folder of its own under the system's temporary folder, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("raylab-gltf-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temporary folder");
        TempDir(dir)
    }

    pub fn join(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Where the binary buffer goes.
pub enum Storage<'a> {
    /// A base64 `data:` URI in the JSON.
    DataUri,
    /// A file beside the .gltf: (file name, the URI that names it).
    External(&'a str, &'a str),
    /// The BIN chunk of a .glb.
    Glb,
}

/// One binary buffer, its views and accessors, gathered while a test builds.
#[derive(Clone, Default)]
pub struct Builder {
    pub bin: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

impl Builder {
    pub fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view =
            json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(view);
        self.views.len() - 1
    }

    pub fn accessor(
        &mut self,
        view: Option<usize>,
        component: u32,
        count: usize,
        ty: &str,
        extra: Value,
    ) -> usize {
        let mut accessor = json!({"componentType": component, "count": count, "type": ty});
        if let Some(view) = view {
            accessor["bufferView"] = json!(view);
        }
        if let Value::Object(extra) = extra {
            for (k, v) in extra {
                accessor[k] = v;
            }
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    pub fn vec3s(&mut self, values: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        let view = self.view(&bytes, None);
        let finite: Vec<&[f32; 3]> = values
            .iter()
            .filter(|v| v.iter().all(|f| f.is_finite()))
            .collect();
        let min: Vec<f32> = (0..3)
            .map(|i| finite.iter().map(|v| v[i]).fold(f32::MAX, f32::min))
            .collect();
        let max: Vec<f32> = (0..3)
            .map(|i| finite.iter().map(|v| v[i]).fold(f32::MIN, f32::max))
            .collect();
        self.accessor(
            Some(view),
            FLOAT,
            values.len(),
            "VEC3",
            json!({"min": min, "max": max}),
        )
    }

    pub fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = match component {
            BYTE => indices.iter().map(|&i| i as u8).collect(),
            SHORT => indices
                .iter()
                .flat_map(|&i| (i as u16).to_le_bytes())
                .collect(),
            _ => indices.iter().flat_map(|&i| i.to_le_bytes()).collect(),
        };
        let view = self.view(&bytes, None);
        self.accessor(Some(view), component, indices.len(), "SCALAR", json!({}))
    }

    /// Writes `doc` plus this buffer as `name` in `dir`; returns its path.
    pub fn write(self, mut doc: Value, storage: Storage, dir: &TempDir, name: &str) -> PathBuf {
        doc["asset"] = json!({"version": "2.0"});
        doc["bufferViews"] = json!(self.views);
        doc["accessors"] = json!(self.accessors);
        let mut buffer = json!({"byteLength": self.bin.len()});
        match storage {
            Storage::DataUri => {
                buffer["uri"] = json!(format!(
                    "data:application/octet-stream;base64,{}",
                    base64(&self.bin)
                ));
            }
            Storage::External(file, uri) => {
                std::fs::write(dir.join(file), &self.bin).expect("write .bin");
                buffer["uri"] = json!(uri);
            }
            Storage::Glb => {}
        }
        doc["buffers"] = json!([buffer]);
        let path = dir.join(name);
        let text = serde_json::to_vec(&doc).expect("json");
        let bytes = match storage {
            Storage::Glb => glb(&text, &self.bin),
            _ => text,
        };
        std::fs::write(&path, bytes).expect("write model");
        path
    }
}

/// A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded).
pub fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |data: &[u8], with: u8| {
        let mut v = data.to_vec();
        while !v.len().is_multiple_of(4) {
            v.push(with);
        }
        v
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The unit square in the xy-plane, counter-clockwise seen from +z.
pub const QUAD: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];
pub const QUAD_INDICES: [u32; 6] = [0, 1, 2, 0, 2, 3];

/// A document with one mesh of one primitive, drawn by one node.
pub fn one_mesh(primitive: Value) -> Value {
    json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"name": "quad", "primitives": [primitive]}],
    })
}
