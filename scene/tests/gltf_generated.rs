//! glTF files generated here (JSON with serde_json, binary data by hand,
//! written to a temporary folder), each built to check one property of the
//! loader: index widths, instancing, transforms, normals, buffers in every
//! storage, textures, materials, cameras, lights, unsupported features and
//! broken files. Expected values are worked out by hand in the comments.

use glam::{Mat4, Vec2, Vec3};
use scene::{BaseMaterial, LightKind, ModelError, ModelFile, Wrap, load_model};
use serde_json::{Value, json};
use std::f32::consts::FRAC_1_SQRT_2;
use std::path::{Path, PathBuf};

mod gltf_common;

use gltf_common::*;

fn load(path: &Path) -> ModelFile {
    load_model(path).unwrap_or_else(|e| panic!("must load: {e}"))
}

fn load_err(path: &Path) -> ModelError {
    match load_model(path) {
        Ok(m) => panic!("expected an error, loaded {} meshes", m.meshes.len()),
        Err(e) => e,
    }
}

#[track_caller]
fn assert_contains(text: &str, parts: &[&str]) {
    for part in parts {
        assert!(text.contains(part), "{text:?} lacks {part:?}");
    }
}

#[test]
fn indices_of_8_16_and_32_bits_give_the_same_two_triangles() {
    let dir = TempDir::new("widths");
    for (component, name) in [(BYTE, "u8"), (SHORT, "u16"), (INT, "u32")] {
        let mut b = Builder::default();
        let position = b.vec3s(&QUAD);
        let indices = b.indices(&QUAD_INDICES, component);
        let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
        let model = load(&b.write(doc, Storage::DataUri, &dir, &format!("{name}.gltf")));
        assert_eq!(model.meshes.len(), 1, "{name}");
        assert_eq!(
            model.meshes[0].triangles,
            vec![[0, 1, 2], [0, 2, 3]],
            "{name}"
        );
        assert_eq!(
            model.meshes[0].positions[2],
            Vec3::new(1.0, 1.0, 0.0),
            "{name}"
        );
        assert_eq!(model.drawn_triangles(), 2);
        assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    }
}

#[test]
fn non_indexed_triangles_take_vertices_three_by_three() {
    let dir = TempDir::new("non-indexed");
    let mut b = Builder::default();
    let expanded: Vec<[f32; 3]> = QUAD_INDICES.iter().map(|&i| QUAD[i as usize]).collect();
    let position = b.vec3s(&expanded);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "mode": 4}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "flat.gltf"));
    assert_eq!(model.meshes[0].triangles, vec![[0, 1, 2], [3, 4, 5]]);
    assert_eq!(model.meshes[0].positions.len(), 6);
    assert_eq!(model.bounds(), Some((Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))));
}

#[test]
fn position_min_max_are_optional_for_raylab() {
    let dir = TempDir::new("no-minmax");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let accessor = b.accessors[position].as_object_mut().expect("object");
    accessor.remove("min");
    accessor.remove("max");
    let indices = b.indices(&QUAD_INDICES, BYTE);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "no-minmax.gltf"));
    assert_eq!(model.bounds(), Some((Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))));
}

#[test]
fn a_primitive_without_position_is_skipped_with_one_warning() {
    let dir = TempDir::new("no-position");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let normal = b.vec3s(&[[0.0, 0.0, 1.0]; 4]);
    let doc = json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"NORMAL": normal}},
            {"attributes": {"NORMAL": normal}},
            {"attributes": {"POSITION": position}, "mode": 6},
        ]}],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "no-position.gltf"));
    assert_eq!(model.meshes.len(), 1);
    assert_eq!(model.drawn_triangles(), 2);
    assert_eq!(model.warnings.len(), 1, "{:?}", model.warnings);
    assert_contains(&model.warnings[0], &["without a POSITION", "skipped"]);
}

#[test]
fn ignored_material_parts_are_warned_once_each() {
    let dir = TempDir::new("material-parts");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, BYTE);
    let (png, _) = png_3x2();
    let image = b.view(&png, None);
    let material = json!({
        "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.3,
                                 "metallicRoughnessTexture": {"index": 0}},
        "normalTexture": {"index": 0},
        "occlusionTexture": {"index": 0},
        "emissiveTexture": {"index": 0},
        "emissiveFactor": [1.0, 1.0, 1.0],
        "alphaMode": "BLEND",
    });
    let doc = json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": position}, "indices": indices, "material": 0},
            {"attributes": {"POSITION": position}, "indices": indices, "material": 1},
        ]}],
        "materials": [material.clone(), material],
        "textures": [{"source": 0}],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "parts.gltf"));
    let w = &model.warnings;
    for part in [
        "metallic-roughness textures",
        "normal maps",
        "occlusion textures",
        "emissive textures",
        "alphaMode",
    ] {
        let n = w.iter().filter(|m| m.contains(part)).count();
        assert_eq!(n, 1, "{part} warned {n} times in {w:#?}");
    }
    assert_eq!(w.len(), 5, "{w:#?}");
    let m = model.materials[0].material;
    assert_eq!(m.base, BaseMaterial::Plastic);
    assert_eq!(m.emission, Vec3::ZERO, "emissive texture: no emission");
    assert!(
        model.textures.is_empty(),
        "only base-colour textures are decoded"
    );
}

#[test]
fn strips_and_fans_become_triangle_lists() {
    let dir = TempDir::new("strips");
    for (mode, expected) in [
        (5, vec![[0, 1, 2], [2, 1, 3]]),
        (6, vec![[1, 2, 0], [2, 3, 0]]),
    ] {
        let mut b = Builder::default();
        let position = b.vec3s(&QUAD);
        let indices = b.indices(&[0, 1, 2, 3], SHORT);
        let doc = one_mesh(
            json!({"attributes": {"POSITION": position}, "indices": indices, "mode": mode}),
        );
        let model = load(&b.write(doc, Storage::DataUri, &dir, &format!("mode{mode}.gltf")));
        assert_eq!(model.meshes[0].triangles, expected, "mode {mode}");
    }
}

#[test]
fn a_mesh_used_by_two_nodes_is_loaded_once_and_instanced_twice() {
    let dir = TempDir::new("instances");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    let doc = json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0, "name": "left"}, {"mesh": 0, "translation": [3.0, 0.0, 0.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "indices": indices}]}],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "two.gltf"));
    assert_eq!(model.meshes.len(), 1, "one shared mesh");
    assert_eq!(model.instances.len(), 2);
    assert_eq!((model.instances[0].mesh, model.instances[1].mesh), (0, 0));
    assert_eq!(model.instances[0].name, "left");
    assert_eq!(model.instances[1].name, "node 1");
    assert_eq!(
        model.instances[1].model_from_mesh,
        Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0))
    );
    assert_eq!(model.drawn_triangles(), 4);
    assert_eq!(model.bounds(), Some((Vec3::ZERO, Vec3::new(4.0, 1.0, 0.0))));
}

#[test]
fn a_child_matrix_applies_before_its_parents_trs() {
    let dir = TempDir::new("hierarchy");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, BYTE);
    // Parent: translate (10, 0, 0) · rotate 90° about z · scale 2.
    // Child: the column-major matrix of a translation by (1, 0, 0).
    let doc = json!({
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"children": [1], "translation": [10.0, 0.0, 0.0],
             "rotation": [0.0, 0.0, FRAC_1_SQRT_2, FRAC_1_SQRT_2], "scale": [2.0, 2.0, 2.0]},
            {"mesh": 0, "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0]},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "indices": indices}]}],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "tree.gltf"));
    let m = model.instances[0].model_from_mesh;
    // The origin: child → (1,0,0), ×2 → (2,0,0), 90° about z → (0,2,0), +10 x → (10,2,0).
    assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(10.0, 2.0, 0.0)).length() < 1e-5);
    // The quad: x 1..2, y 0..1 → x 2..4, y 0..2 → x −2..0, y 2..4 → x 8..10, y 2..4.
    let (lo, hi) = model.bounds().expect("bounds");
    assert!((lo - Vec3::new(8.0, 2.0, 0.0)).length() < 1e-5, "{lo}");
    assert!((hi - Vec3::new(10.0, 4.0, 0.0)).length() < 1e-5, "{hi}");
    // Normals stay in mesh space: +z.
    assert!(model.meshes[0].normals.iter().all(|n| *n == Vec3::Z));
}

#[test]
fn missing_normals_are_area_weighted_and_given_ones_are_normalised() {
    let dir = TempDir::new("normals");
    // Triangle A (0,1,2) faces +z with area 1/2; triangle B (0,1,3) faces +y
    // with area 1. Vertices 0 and 1 share both: (0,0,1)·1 + (0,2,0)·1 → (0,2,1)/√5.
    let mut b = Builder::default();
    let position = b.vec3s(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, -2.0],
    ]);
    let indices = b.indices(&[0, 1, 2, 0, 1, 3], SHORT);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "computed.gltf"));
    let n = &model.meshes[0].normals;
    let shared = Vec3::new(0.0, 2.0, 1.0) / 5f32.sqrt();
    assert!(
        (n[0] - shared).length() < 1e-6 && (n[1] - shared).length() < 1e-6,
        "{n:?}"
    );
    assert_eq!((n[2], n[3]), (Vec3::Z, Vec3::Y));

    let mut b = Builder::default();
    let position = b.vec3s(&QUAD[..3]);
    let normal = b.vec3s(&[[0.0, 0.0, 2.0], [0.0, 3.0, 4.0], [0.0, 0.0, -0.5]]);
    let doc = one_mesh(json!({"attributes": {"POSITION": position, "NORMAL": normal}}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "given.gltf"));
    let n = &model.meshes[0].normals;
    assert_eq!(n[0], Vec3::Z);
    assert!((n[1] - Vec3::new(0.0, 0.6, 0.8)).length() < 1e-6);
    assert_eq!(n[2], Vec3::NEG_Z, "the file's direction is kept");
}

#[test]
fn an_external_bin_buffer_is_read_beside_the_gltf_with_u16_texcoords() {
    let dir = TempDir::new("external");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, INT);
    let uv_bytes: Vec<u8> = [0u16, 0, 65535, 0, 65535, 65535, 0, 32768]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let uv_view = b.view(&uv_bytes, None);
    let uv = b.accessor(Some(uv_view), SHORT, 4, "VEC2", json!({"normalized": true}));
    let doc = one_mesh(
        json!({"attributes": {"POSITION": position, "TEXCOORD_0": uv}, "indices": indices}),
    );
    // A space in the file name: the URI percent-encodes it.
    let path = b.write(
        doc,
        Storage::External("quad data.bin", "quad%20data.bin"),
        &dir,
        "external.gltf",
    );
    let model = load(&path);
    assert_eq!(model.meshes[0].positions[1], Vec3::X);
    let uvs = &model.meshes[0].uvs;
    assert_eq!(&uvs[..3], &[Vec2::ZERO, Vec2::X, Vec2::ONE]);
    assert!((uvs[3].y - 32768.0 / 65535.0).abs() < 1e-7);

    // The same file without its .bin: an error naming the buffer and the path.
    std::fs::remove_file(dir.join("quad data.bin")).expect("remove");
    let e = load_err(&path);
    assert_contains(
        &e.to_string(),
        &["external.gltf", "buffer 0", "quad data.bin", "cannot read"],
    );
}

/// A 3×2 PNG whose texels are all different.
fn png_3x2() -> (Vec<u8>, Vec<[u8; 4]>) {
    let texels: Vec<[u8; 4]> = (0..6u8)
        .map(|i| [40 * i, 255 - 40 * i, 7 * i, 255])
        .collect();
    let mut image = image::RgbaImage::new(3, 2);
    for (i, p) in image.pixels_mut().enumerate() {
        *p = image::Rgba(texels[i]);
    }
    let mut png = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut png, image::ImageFormat::Png)
        .expect("encode png");
    (png.into_inner(), texels)
}

#[test]
fn a_glb_loads_its_bin_chunk_and_a_png_texture_with_its_wrap_modes() {
    let dir = TempDir::new("glb");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    // TEXCOORD_0 as normalised unsigned bytes: 255 → 1, 51 → 0.2.
    let uv_view = b.view(&[0, 0, 255, 0, 255, 255, 0, 51], None);
    let uv = b.accessor(Some(uv_view), BYTE, 4, "VEC2", json!({"normalized": true}));
    let (png, texels) = png_3x2();
    let image_view = b.view(&png, None);
    let doc = json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position, "TEXCOORD_0": uv}, "indices": indices, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [0.5, 1.0, 1.0, 1.0], "metallicFactor": 0.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "images": [{"bufferView": image_view, "mimeType": "image/png"}],
        "samplers": [{"wrapS": 33071, "wrapT": 33648}],
    });
    let path = b.write(doc, Storage::Glb, &dir, "textured.glb");
    let model = load(&path);
    assert_eq!(model.meshes[0].triangles.len(), 2);
    assert_eq!(model.meshes[0].uvs[3], Vec2::new(0.0, 0.2));
    assert_eq!(model.textures.len(), 1);
    let t = &model.textures[0];
    assert_eq!((t.width, t.height), (3, 2));
    assert_eq!(*t.texels, *texels, "row 0 first, as stored");
    assert_eq!(
        (t.wrap_u, t.wrap_v),
        (Wrap::ClampToEdge, Wrap::MirroredRepeat)
    );
    let m = model.materials[0];
    assert_eq!(m.base_color_texture, Some(0));
    assert_eq!(
        m.material.color,
        Vec3::new(0.5, 1.0, 1.0),
        "the factor, linear as stored"
    );
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn a_sparse_accessor_substitutes_its_values() {
    let dir = TempDir::new("sparse");
    let mut b = Builder::default();
    let base: Vec<u8> = QUAD
        .iter()
        .flatten()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let base_view = b.view(&base, None);
    let sparse_indices = b.view(&[2u8], None);
    let sparse_values: Vec<u8> = [5.0f32, 5.0, 0.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let sparse_values = b.view(&sparse_values, None);
    let position = b.accessor(
        Some(base_view),
        FLOAT,
        4,
        "VEC3",
        json!({"min": [0.0, 0.0, 0.0], "max": [5.0, 5.0, 0.0], "sparse": {
            "count": 1,
            "indices": {"bufferView": sparse_indices, "componentType": BYTE},
            "values": {"bufferView": sparse_values}}}),
    );
    let indices = b.indices(&QUAD_INDICES, SHORT);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "sparse.gltf"));
    assert_eq!(model.meshes[0].positions[2], Vec3::new(5.0, 5.0, 0.0));
    assert_eq!(model.meshes[0].positions[3], Vec3::Y, "untouched");

    // Without a bufferView the base is zeros: vertices 1 and 2 substituted.
    let mut b = Builder::default();
    let sparse_indices = b.view(&[1u8, 2], None);
    let sparse_values: Vec<u8> = [1.0f32, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let sparse_values = b.view(&sparse_values, None);
    let position = b.accessor(
        None,
        FLOAT,
        3,
        "VEC3",
        json!({"min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0], "sparse": {
            "count": 2,
            "indices": {"bufferView": sparse_indices, "componentType": BYTE},
            "values": {"bufferView": sparse_values}}}),
    );
    let doc = one_mesh(json!({"attributes": {"POSITION": position}}));
    let model = load(&b.write(doc, Storage::DataUri, &dir, "zeros.gltf"));
    assert_eq!(
        model.meshes[0].positions,
        vec![Vec3::ZERO, Vec3::X, Vec3::Y]
    );
}

#[test]
fn accessors_without_a_buffer_view_share_one_allowance_per_file() {
    // A file may decode 2^20 accessor elements plus 4 per byte of its
    // buffers: here 2^20 + 4 × 48 (the quad's positions). Two meshes of
    // zeros (no bufferView) take exactly that; a third mesh is one too many.
    let dir = TempDir::new("viewless");
    let mut b = Builder::default();
    let quad = b.vec3s(&QUAD);
    let half = ((1 << 20) + 4 * 48) / 2;
    let zeros = b.accessor(None, FLOAT, half, "VEC3", json!({}));
    let strip =
        |position| json!({"primitives": [{"attributes": {"POSITION": position}, "mode": 5}]});
    let doc = |meshes: Vec<Value>| {
        let nodes: Vec<Value> = (0..meshes.len()).map(|i| json!({"mesh": i})).collect();
        json!({"scenes": [{"nodes": (0..meshes.len()).collect::<Vec<_>>()}], "nodes": nodes, "meshes": meshes})
    };
    let b2 = b.clone();
    let model = load(&b.write(
        doc(vec![strip(zeros), strip(zeros)]),
        Storage::DataUri,
        &dir,
        "two.gltf",
    ));
    assert_eq!(model.meshes.len(), 2);
    assert_eq!(model.meshes[1].positions.len(), half);

    let path = b2.write(
        doc(vec![strip(zeros), strip(zeros), strip(quad)]),
        Storage::DataUri,
        &dir,
        "three.gltf",
    );
    let error = load_err(&path).to_string();
    assert_contains(
        &error,
        &[
            "mesh 2, primitive 0, POSITION: accessor 0: its 4 elements would exceed",
            "(0 elements left",
        ],
    );
}

#[test]
fn an_accessor_shared_by_a_hundred_primitives_loads() {
    let dir = TempDir::new("shared");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    let primitive = json!({"attributes": {"POSITION": position}, "indices": indices});
    let mut doc = one_mesh(primitive.clone());
    doc["meshes"][0]["primitives"] = json!(vec![primitive; 100]);
    let model = load(&b.write(doc, Storage::DataUri, &dir, "shared.gltf"));
    assert_eq!(model.meshes.len(), 100);
    assert_eq!(model.drawn_triangles(), 200);
}

#[test]
fn unsupported_features_are_each_warned_once_and_the_rest_loads() {
    let dir = TempDir::new("unsupported");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    // Draco primitives: accessors without a bufferView.
    let draco_position = b.accessor(
        None,
        FLOAT,
        4,
        "VEC3",
        json!({"min": [0, 0, 0], "max": [1, 1, 0]}),
    );
    let draco_indices = b.accessor(None, SHORT, 6, "SCALAR", json!({}));
    let draco = json!({"attributes": {"POSITION": draco_position}, "indices": draco_indices,
        "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}});
    // A one-key animation of node 0's translation.
    let time_view = b.view(&0f32.to_le_bytes(), None);
    let time = b.accessor(
        Some(time_view),
        FLOAT,
        1,
        "SCALAR",
        json!({"min": [0.0], "max": [0.0]}),
    );
    let moved = b.vec3s(&[[0.0, 1.0, 0.0]]);
    let doc = json!({
        "extensionsUsed": ["KHR_draco_mesh_compression", "KHR_texture_transform", "VENDOR_sparkles"],
        "extensionsRequired": ["KHR_draco_mesh_compression"],
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 1},
            {"mesh": 1, "translation": [0.0, 0.0, 1.0]},
            {"mesh": 2, "skin": 0},
        ],
        "skins": [{"joints": [0]}],
        "animations": [{"samplers": [{"input": time, "output": moved}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}],
        "meshes": [
            {"primitives": [draco.clone(), draco,
                            {"attributes": {"POSITION": position}, "indices": indices}]},
            {"primitives": [{"attributes": {"POSITION": position}, "mode": 0},
                            {"attributes": {"POSITION": position}, "indices": indices, "mode": 1}]},
            {"primitives": [{"attributes": {"POSITION": position}, "indices": indices,
                             "targets": [{"POSITION": position}]}]},
        ],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "unsupported.gltf"));
    // The plain primitive of mesh 0 and the morphed one of mesh 2 load.
    assert_eq!(model.meshes.len(), 2);
    assert_eq!(model.drawn_triangles(), 4);
    let w = &model.warnings;
    for feature in [
        "KHR_draco_mesh_compression",
        "KHR_texture_transform",
        "VENDOR_sparkles",
        "point and line",
        "animations",
        "skins",
        "morph targets",
    ] {
        let n = w.iter().filter(|m| m.contains(feature)).count();
        assert_eq!(n, 1, "{feature} warned {n} times in {w:#?}");
    }
    assert_eq!(w.len(), 7, "{w:#?}");
    let draco = w.iter().find(|m| m.contains("draco")).expect("draco");
    assert_contains(draco, &["required extension", "skipped"]);
}

#[test]
fn materials_map_by_the_documented_table() {
    let dir = TempDir::new("materials");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    let primitive = |material: Option<usize>| {
        let mut p = json!({"attributes": {"POSITION": position}, "indices": indices});
        if let Some(m) = material {
            p["material"] = json!(m);
        }
        p
    };
    let doc = json!({
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [primitive(Some(0)), primitive(Some(1)), primitive(Some(2)), primitive(Some(3)), primitive(None)]}],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.8, 0.3, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.2}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 1.0, 0.9, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.33}}},
            {"pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.5},
             "emissiveFactor": [1.0, 0.5, 0.0],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}},
        ],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "materials.gltf"));
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    let m: Vec<_> = model
        .instances
        .iter()
        .map(|i| model.materials[i.material as usize].material)
        .collect();
    assert_eq!(m.len(), 5);
    assert_eq!(
        (m[0].base, m[0].color),
        (BaseMaterial::Metal, Vec3::new(1.0, 0.8, 0.3))
    );
    assert_eq!(
        (m[1].base, m[1].ior, m[1].color),
        (BaseMaterial::Glass, 1.33, Vec3::new(0.9, 1.0, 0.9))
    );
    assert_eq!(m[2].base, BaseMaterial::Plastic);
    assert!((m[2].shininess - 30.0).abs() < 1e-3, "2/0.25² − 2");
    assert_eq!(m[2].color, Vec3::ONE, "glTF's default base colour");
    assert_eq!(m[2].emission, Vec3::new(4.0, 2.0, 0.0), "factor × strength");
    assert_eq!(
        (m[3].base, m[3].color),
        (BaseMaterial::Matte, Vec3::new(0.2, 0.3, 0.4))
    );
    assert_eq!(
        (m[4].base, m[4].color),
        (BaseMaterial::Matte, Vec3::splat(0.8)),
        "no material"
    );
    // One raylab material per glTF material, plus the default.
    assert_eq!(model.materials.len(), 5);
}

#[test]
fn cameras_and_lights_take_their_nodes_transforms() {
    let dir = TempDir::new("camera");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, BYTE);
    let s = FRAC_1_SQRT_2;
    let doc = json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "name": "bulb", "intensity": 100.0, "color": [1.0, 0.5, 0.25]},
            {"type": "directional", "intensity": 3.0},
            {"type": "spot", "spot": {"outerConeAngle": 0.5}},
        ]}},
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
        "nodes": [
            {"mesh": 0},
            // 90° about y: −z turns to −x.
            {"camera": 0, "translation": [1.0, 2.0, 3.0], "rotation": [0.0, s, 0.0, s]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.0, 5.0, 0.0]},
            // −90° about x: −z turns to −y (straight down).
            {"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-s, 0.0, 0.0, s], "name": "sun"},
            {"extensions": {"KHR_lights_punctual": {"light": 2}}, "translation": [0.0, 0.0, 7.0]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "indices": indices}]}],
    });
    let path = b.write(doc, Storage::DataUri, &dir, "camera.gltf");
    let model = load(&path);
    let c = &model.cameras[0];
    assert_eq!(c.name, "node 1");
    assert!((c.eye - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
    assert!((c.toward - Vec3::NEG_X).length() < 1e-6, "{}", c.toward);
    assert!((c.up - Vec3::Y).length() < 1e-6, "{}", c.up);
    assert!((c.theta_deg - 0.5f32.to_degrees()).abs() < 1e-5);
    assert_eq!(c.aspect, None);

    assert_eq!(model.lights.len(), 3);
    let bulb = &model.lights[0];
    assert_eq!(bulb.name.as_deref(), Some("bulb"));
    assert_eq!(
        bulb.kind,
        LightKind::Point {
            position: Vec3::new(0.0, 5.0, 0.0)
        }
    );
    assert_eq!(
        (bulb.intensity, bulb.color),
        (100.0, Vec3::new(1.0, 0.5, 0.25))
    );
    let sun = &model.lights[1];
    assert_eq!(sun.name.as_deref(), Some("sun"));
    let LightKind::Directional { direction } = sun.kind else {
        panic!("directional: {:?}", sun.kind)
    };
    assert!((direction - Vec3::NEG_Y).length() < 1e-6, "{direction}");
    assert_eq!((sun.intensity, sun.color), (3.0, Vec3::ONE));
    assert_eq!(
        model.lights[2].kind,
        LightKind::Point {
            position: Vec3::new(0.0, 0.0, 7.0)
        }
    );
    assert_eq!(model.warnings.len(), 1, "{:?}", model.warnings);
    assert_contains(&model.warnings[0], &["spot", "cone is ignored"]);
}

#[test]
fn without_scenes_every_root_node_is_drawn() {
    let dir = TempDir::new("no-scene");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let doc = json!({
        "nodes": [{"mesh": 0, "children": [1]}, {"mesh": 0, "translation": [0.0, 0.0, 1.0]}, {"mesh": 0, "translation": [0.0, 0.0, -1.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "mode": 6}]}],
    });
    let model = load(&b.write(doc, Storage::DataUri, &dir, "loose.gltf"));
    assert_eq!(model.instances.len(), 3, "roots 0 and 2, and 0's child 1");
    assert_eq!(
        model.bounds(),
        Some((Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 1.0, 1.0)))
    );
}

#[test]
fn a_file_that_is_not_gltf_is_a_clear_error() {
    let dir = TempDir::new("broken");
    let not_json = dir.join("notes.gltf");
    std::fs::write(&not_json, "these are not the droids").expect("write");
    let e = load_err(&not_json);
    assert_eq!(e.path, not_json.display().to_string());
    assert_contains(&e.message, &["not a valid glTF 2.0 file", "line 1"]);

    let truncated = dir.join("cut.glb");
    let mut bytes = glb(br#"{"asset":{"version":"2.0"}}"#, &[1, 2, 3, 4]);
    bytes.truncate(bytes.len() - 10);
    std::fs::write(&truncated, bytes).expect("write");
    assert_contains(&load_err(&truncated).message, &["GLB", "length"]);

    let e = load_err(&dir.join("absent.gltf"));
    assert_contains(&e.message, &["cannot read the file"]);

    let dangling = dir.join("dangling.gltf");
    std::fs::write(
        &dangling,
        r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}]}"#,
    )
    .expect("write");
    assert_contains(
        &load_err(&dangling).message,
        &["invalid glTF", "scenes[0].nodes[0]"],
    );

    // An attribute naming a missing accessor (the gltf crate's own check
    // would index out of bounds).
    let missing = dir.join("missing-accessor.gltf");
    std::fs::write(
        &missing,
        r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":9}}]}]}"#,
    )
    .expect("write");
    assert_contains(
        &load_err(&missing).message,
        &[
            "meshes[0].primitives[0].attributes[\"POSITION\"]",
            "accessor 9 does not exist",
        ],
    );
}

#[test]
fn an_out_of_range_index_names_the_mesh_primitive_and_accessor() {
    let dir = TempDir::new("range");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&[0, 1, 2, 0, 2, 7], SHORT);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
    let e = load_err(&b.write(doc, Storage::DataUri, &dir, "range.gltf"));
    assert_contains(
        &e.message,
        &[
            "mesh 0 \"quad\", primitive 0",
            "indices",
            "accessor 1",
            "index 7 at position 5",
            "4 vertices",
        ],
    );
}

#[test]
fn a_nan_position_names_its_vertex() {
    let dir = TempDir::new("nan");
    let mut b = Builder::default();
    let position = b.vec3s(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [f32::NAN, 1.0, 0.0]]);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}}));
    let e = load_err(&b.write(doc, Storage::DataUri, &dir, "nan.gltf"));
    assert_contains(
        &e.message,
        &[
            "mesh 0 \"quad\", primitive 0",
            "POSITION",
            "vertex 2",
            "not finite",
        ],
    );
}

#[test]
fn an_accessor_longer_than_its_buffer_view_is_an_error() {
    let dir = TempDir::new("overrun");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    b.accessors[position]["count"] = json!(40);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}}));
    let e = load_err(&b.write(doc, Storage::DataUri, &dir, "overrun.gltf"));
    assert_contains(
        &e.message,
        &[
            "POSITION",
            "accessor 0",
            "40 elements",
            "do not fit in bufferView 0 (48 bytes)",
        ],
    );
}

#[test]
fn a_node_reached_twice_is_an_error_not_a_hang() {
    let dir = TempDir::new("cycle");
    let b = Builder::default();
    let doc = json!({"scenes": [{"nodes": [0]}], "nodes": [{"children": [1]}, {"children": [0]}]});
    let e = load_err(&b.write(doc, Storage::DataUri, &dir, "cycle.gltf"));
    assert_contains(&e.message, &["node 0 is reached twice"]);
}

#[test]
fn json_the_gltf_crate_would_panic_on_is_an_error_or_loads() {
    let dir = TempDir::new("crate-panics");
    // A camera whose type names an object it lacks.
    let b = Builder::default();
    let doc = json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"camera": 0}],
        "cameras": [{"type": "perspective", "orthographic": {"xmag": 1, "ymag": 1, "zfar": 10, "znear": 1}}],
    });
    let e = load_err(&b.write(doc, Storage::DataUri, &dir, "camera.gltf"));
    assert_contains(&e.message, &["camera 0", "no \"perspective\" object"]);

    // An image in a bufferView without mimeType: the PNG is recognised by
    // its signature. An image with neither uri nor bufferView: an error.
    for (image, ok) in [(json!({"bufferView": 2}), true), (json!({}), false)] {
        let mut b = Builder::default();
        let position = b.vec3s(&QUAD);
        let indices = b.indices(&QUAD_INDICES, BYTE);
        let (png, _) = png_3x2();
        assert_eq!(b.view(&png, None), 2);
        let doc = json!({
            "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "indices": indices, "material": 0}]}],
            "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
            "textures": [{"source": 0}],
            "images": [image],
        });
        let path = b.write(doc, Storage::Glb, &dir, "image.glb");
        match load_model(&path) {
            Ok(model) => {
                assert!(ok, "an image without data loaded");
                assert_eq!((model.textures[0].width, model.textures[0].height), (3, 2));
            }
            Err(e) => {
                assert!(!ok, "{e}");
                assert_contains(&e.message, &["image 0", "neither a uri nor a bufferView"]);
            }
        }
    }
}

/// A flat grid of `n × n` quads (2n² triangles) as a .glb with normals.
fn grid_glb(dir: &TempDir, n: u32) -> PathBuf {
    let side = n + 1;
    let mut positions = Vec::with_capacity((side * side) as usize);
    for j in 0..side {
        for i in 0..side {
            positions.push([i as f32, 0.0, j as f32]);
        }
    }
    let mut indices = Vec::with_capacity((6 * n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let v = j * side + i;
            indices.extend_from_slice(&[v, v + side, v + 1, v + 1, v + side, v + side + 1]);
        }
    }
    let mut b = Builder::default();
    let position = b.vec3s(&positions);
    let normals = vec![[0.0, 1.0, 0.0]; positions.len()];
    let normal = b.vec3s(&normals);
    let index = b.indices(&indices, INT);
    let doc =
        one_mesh(json!({"attributes": {"POSITION": position, "NORMAL": normal}, "indices": index}));
    b.write(doc, Storage::Glb, dir, "grid.glb")
}

#[test]
fn a_million_triangle_glb_loads_in_well_under_a_second_in_release() {
    let dir = TempDir::new("million");
    let n = 708; // 2 · 708² = 1,002,528 triangles, 502,681 vertices.
    let path = grid_glb(&dir, n);
    let start = std::time::Instant::now();
    let model = load(&path);
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "loaded {} triangles in {seconds:.3} s",
        model.drawn_triangles()
    );
    assert_eq!(model.drawn_triangles(), 2 * 708 * 708);
    assert_eq!(model.meshes[0].positions.len(), 709 * 709);
    assert_eq!(model.meshes[0].triangles[1], [1, 709, 710]);
    assert_eq!(
        model.bounds(),
        Some((Vec3::ZERO, Vec3::new(708.0, 0.0, 708.0)))
    );
    if !cfg!(debug_assertions) {
        assert!(seconds < 0.5, "{seconds} s");
    }
}

#[test]
fn a_file_named_by_several_mesh_elements_is_loaded_once() {
    let dir = TempDir::new("shared-src");
    let mut b = Builder::default();
    let position = b.vec3s(&QUAD);
    let indices = b.indices(&QUAD_INDICES, SHORT);
    let doc = one_mesh(json!({"attributes": {"POSITION": position}, "indices": indices}));
    b.write(doc, Storage::DataUri, &dir, "quad.gltf");
    let scene_path = dir.join("scene.xml");
    std::fs::write(
        &scene_path,
        r#"<scene><mesh src="quad.gltf"/><mesh src="quad.gltf" translate="2 0 0"/></scene>"#,
    )
    .expect("write scene");
    let scene = scene::read_file(&scene_path).expect("reads");
    let model = |k: usize| match &scene.objects[k].shape {
        scene::Shape::Mesh { source, .. } => source.model.clone(),
        other => panic!("object {k} is a {}", other.tag()),
    };
    assert!(std::sync::Arc::ptr_eq(&model(0), &model(1)));
    // Written back, the scene names the file as it was given.
    let text = scene::write_string(&scene);
    assert_eq!(text.matches(r#"src="quad.gltf""#).count(), 2, "{text}");
}
