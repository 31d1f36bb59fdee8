//! The Khronos glTF sample models in `../shared/gltf` beside the workspace
//! (not in the repository; licences in that folder's README): each loads,
//! and its triangle counts, bounds, camera, materials, textures and warnings
//! match what the file says.
//!
//! Expectations are computed here independently of the loader: from the
//! README's numbers, and from the JSON read with serde_json (accessor
//! min/max, node transforms, and positions decoded from the base64 buffers
//! by a decoder in this file). When the folder is missing (a CI machine
//! without it) every test prints a note and passes.

use glam::{Mat4, Quat, Vec3};
use scene::{BaseMaterial, ModelFile, Wrap, load_model};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The samples folder, or `None` (with a note) when it is not there.
fn samples() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/gltf");
    if dir.exists() {
        Some(dir)
    } else {
        println!(
            "note: {} is missing; skipping the glTF sample tests",
            dir.display()
        );
        None
    }
}

fn load(name: &str) -> Option<(ModelFile, Expected)> {
    let path = samples()?.join(name);
    let model = load_model(&path).unwrap_or_else(|e| panic!("{name} must load: {e}"));
    Some((model, Expected::from_json(&path)))
}

/// What the JSON says, computed without the loader.
#[derive(Debug)]
struct Expected {
    /// Index count / 3 over all primitives, each mesh once.
    triangles: usize,
    /// The same, each mesh counted once per node that uses it.
    drawn: usize,
    /// The accessor min/max boxes' corners through the node matrices.
    minmax_bounds: (Vec3, Vec3),
    /// Every decoded position through its node matrix.
    exact_bounds: (Vec3, Vec3),
}

impl Expected {
    fn from_json(path: &Path) -> Self {
        let json: Value =
            serde_json::from_str(&std::fs::read_to_string(path).expect("readable")).expect("json");
        let buffers: Vec<Vec<u8>> = json["buffers"]
            .as_array()
            .expect("buffers")
            .iter()
            .map(|b| {
                let uri = b["uri"].as_str().expect("embedded");
                base64(uri.split_once(";base64,").expect("data uri").1)
            })
            .collect();
        let mesh_triangles = |mesh: &Value| -> usize {
            mesh["primitives"]
                .as_array()
                .expect("primitives")
                .iter()
                .map(|p| {
                    let indices = p["indices"].as_u64().expect("indexed") as usize;
                    json["accessors"][indices]["count"].as_u64().expect("count") as usize / 3
                })
                .sum()
        };
        let triangles = json["meshes"]
            .as_array()
            .expect("meshes")
            .iter()
            .map(mesh_triangles)
            .sum();

        let mut drawn = 0;
        let mut minmax: Option<(Vec3, Vec3)> = None;
        let mut exact: Option<(Vec3, Vec3)> = None;
        let grow = |b: &mut Option<(Vec3, Vec3)>, p: Vec3| {
            *b = Some(match *b {
                None => (p, p),
                Some((lo, hi)) => (lo.min(p), hi.max(p)),
            })
        };
        let scene = json["scene"].as_u64().unwrap_or(0) as usize;
        let mut stack: Vec<(usize, Mat4)> = json["scenes"][scene]["nodes"]
            .as_array()
            .expect("scene nodes")
            .iter()
            .map(|n| (n.as_u64().expect("index") as usize, Mat4::IDENTITY))
            .collect();
        while let Some((index, parent)) = stack.pop() {
            let node = &json["nodes"][index];
            let world = parent * node_matrix(node);
            if let Some(mesh) = node["mesh"].as_u64() {
                let mesh = &json["meshes"][mesh as usize];
                drawn += mesh_triangles(mesh);
                for p in mesh["primitives"].as_array().expect("primitives") {
                    let position = &json["accessors"]
                        [p["attributes"]["POSITION"].as_u64().expect("POSITION") as usize];
                    let (lo, hi) = (vec3(&position["min"]), vec3(&position["max"]));
                    for corner in 0..8 {
                        let c = Vec3::new(
                            if corner & 1 == 0 { lo.x } else { hi.x },
                            if corner & 2 == 0 { lo.y } else { hi.y },
                            if corner & 4 == 0 { lo.z } else { hi.z },
                        );
                        grow(&mut minmax, world.transform_point3(c));
                    }
                    for v in decode_vec3(&json, position, &buffers) {
                        grow(&mut exact, world.transform_point3(v));
                    }
                }
            }
            for child in node["children"].as_array().into_iter().flatten() {
                stack.push((child.as_u64().expect("child") as usize, world));
            }
        }
        Expected {
            triangles,
            drawn,
            minmax_bounds: minmax.expect("something drawn"),
            exact_bounds: exact.expect("something drawn"),
        }
    }
}

fn vec3(v: &Value) -> Vec3 {
    let f = |i: usize| v[i].as_f64().expect("number") as f32;
    Vec3::new(f(0), f(1), f(2))
}

/// A node's local matrix: `matrix` (column-major) or T · R · S.
fn node_matrix(node: &Value) -> Mat4 {
    if let Some(m) = node["matrix"].as_array() {
        let m: Vec<f32> = m
            .iter()
            .map(|x| x.as_f64().expect("number") as f32)
            .collect();
        return Mat4::from_cols_slice(&m);
    }
    let t = node.get("translation").map_or(Vec3::ZERO, vec3);
    let s = node.get("scale").map_or(Vec3::ONE, vec3);
    let r = node.get("rotation").map_or(Quat::IDENTITY, |q| {
        let f = |i: usize| q[i].as_f64().expect("number") as f32;
        Quat::from_xyzw(f(0), f(1), f(2), f(3)).normalize()
    });
    Mat4::from_translation(t) * Mat4::from_quat(r) * Mat4::from_scale(s)
}

/// The float VEC3 elements of `accessor`.
fn decode_vec3(json: &Value, accessor: &Value, buffers: &[Vec<u8>]) -> Vec<Vec3> {
    assert_eq!(accessor["componentType"], 5126, "float positions");
    let view = &json["bufferViews"][accessor["bufferView"].as_u64().expect("view") as usize];
    let data = &buffers[view["buffer"].as_u64().expect("buffer") as usize];
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + accessor["byteOffset"].as_u64().unwrap_or(0) as usize;
    let stride = view["byteStride"].as_u64().unwrap_or(12) as usize;
    let f = |at: usize| f32::from_le_bytes(data[at..at + 4].try_into().expect("4 bytes"));
    (0..accessor["count"].as_u64().expect("count") as usize)
        .map(|i| {
            let at = start + i * stride;
            Vec3::new(f(at), f(at + 4), f(at + 8))
        })
        .collect()
}

/// Standard base64 (RFC 4648), padding optional.
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: {c}"),
        }
    };
    let digits: Vec<u32> = text.bytes().filter(|&c| c != b'=').map(value).collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for group in digits.chunks(4) {
        let mut n = 0u32;
        for (i, d) in group.iter().enumerate() {
            n |= d << (18 - 6 * i);
        }
        out.extend_from_slice(&n.to_be_bytes()[1..group.len()]);
    }
    out
}

#[track_caller]
fn assert_near(a: Vec3, b: Vec3, tolerance: f32, what: &str) {
    assert!(
        (a - b).abs().max_element() <= tolerance,
        "{what}: {a} vs {b} (tolerance {tolerance})"
    );
}

/// Counts and bounds against the README and the JSON; warnings as expected.
#[track_caller]
fn check_geometry(model: &ModelFile, expected: &Expected, triangles: usize, drawn: usize) {
    let own: usize = model.meshes.iter().map(|m| m.triangles.len()).sum();
    assert_eq!(own, triangles, "triangles, each mesh once (README)");
    assert_eq!(own, expected.triangles, "triangles, each mesh once (JSON)");
    assert_eq!(model.drawn_triangles(), drawn, "drawn triangles (README)");
    assert_eq!(model.drawn_triangles(), expected.drawn, "drawn (JSON)");
    let (lo, hi) = model.bounds().expect("something drawn");
    let size = (expected.exact_bounds.1 - expected.exact_bounds.0).max_element();
    let tolerance = 1e-5 * size.max(1.0);
    assert_near(
        lo,
        expected.exact_bounds.0,
        tolerance,
        "bounds min (decoded)",
    );
    assert_near(
        hi,
        expected.exact_bounds.1,
        tolerance,
        "bounds max (decoded)",
    );
    // Inside the box of the accessors' stated min/max corners.
    let (mlo, mhi) = expected.minmax_bounds;
    assert!(
        lo.cmpge(mlo - tolerance).all() && hi.cmple(mhi + tolerance).all(),
        "bounds {lo}..{hi} outside the min/max box {mlo}..{mhi}"
    );
    for mesh in &model.meshes {
        assert_eq!(
            mesh.normals.len(),
            mesh.positions.len(),
            "a normal per vertex"
        );
        assert!(
            mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4),
            "unit normals"
        );
    }
}

#[test]
fn box_has_12_triangles_under_a_z_up_to_y_up_matrix_and_a_red_material() {
    let Some((model, expected)) = load("Box.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 12, 12);
    // The root matrix turns z-up into y-up; the cube is ±0.5 either way.
    assert_eq!(model.bounds(), Some((Vec3::splat(-0.5), Vec3::splat(0.5))));
    assert_eq!(
        expected.minmax_bounds,
        (Vec3::splat(-0.5), Vec3::splat(0.5))
    );
    assert_eq!(model.materials.len(), 1);
    // baseColorFactor 0.8 0 0 with glTF's default metallic 1, roughness 1:
    // a rough red metal, as glTF's viewers show it.
    let m = model.materials[0];
    assert_eq!(m.material.base, BaseMaterial::Metal);
    assert_eq!(m.material.roughness, 1.0);
    assert_near(m.material.color, Vec3::new(0.8, 0.0, 0.0), 1e-6, "colour");
    assert_eq!(m.base_color_texture, None);
    assert!(model.cameras.is_empty() && model.lights.is_empty());
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn box_textured_decodes_its_211_pixel_png_with_repeat_wrap() {
    let Some((model, expected)) = load("BoxTextured.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 12, 12);
    assert_eq!(model.textures.len(), 1);
    let t = &model.textures[0];
    assert_eq!((t.width, t.height), (211, 211));
    assert_eq!(t.texels.len(), 211 * 211);
    assert_eq!((t.wrap_u, t.wrap_v), (Wrap::Repeat, Wrap::Repeat));
    assert!(
        t.texels.iter().any(|p| p != &t.texels[0]),
        "the logo is not one flat colour"
    );
    assert_eq!(model.materials[0].base_color_texture, Some(0));
    // TEXCOORD_0 reaches u = 6 (accessor max), so the texture repeats.
    let uvs = &model.meshes[0].uvs;
    assert_eq!(uvs.len(), 24);
    assert_eq!(uvs.iter().map(|uv| uv.x).fold(0.0, f32::max), 6.0);
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn duck_has_4212_triangles_a_512_texture_and_a_camera_with_aspect_1_5() {
    let Some((model, expected)) = load("Duck.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 4212, 4212);
    assert_eq!(model.meshes[0].positions.len(), 2399);
    assert_eq!(model.meshes[0].uvs.len(), 2399);
    let t = &model.textures[0];
    assert_eq!((t.width, t.height, t.wrap_u), (512, 512, Wrap::Repeat));
    // metallicFactor 0, roughness 1 (default): matte, textured.
    assert_eq!(model.materials[0].material.base, BaseMaterial::Matte);
    assert_eq!(model.materials[0].base_color_texture, Some(0));

    assert_eq!(model.cameras.len(), 1);
    let c = &model.cameras[0];
    assert_eq!(c.aspect, Some(1.5));
    assert!((c.theta_deg - (0.660_592_56_f32 / 2.0).to_degrees()).abs() < 1e-4);
    // The camera node's matrix, under the root's 0.01 scale.
    assert_near(c.eye, Vec3::new(4.001_13, 4.632_64, -4.310_78), 1e-4, "eye");
    assert_near(
        c.toward,
        -Vec3::new(0.536_475_06, 0.621_147_8, -0.571_288),
        1e-5,
        "toward = −z",
    );
    assert_near(
        c.up,
        Vec3::new(-0.425_204_9, 0.783_693_4, 0.452_797_3),
        1e-5,
        "up = +y",
    );
    // And it looks at the duck.
    let (lo, hi) = model.bounds().expect("bounds");
    let to_duck = ((lo + hi) / 2.0 - c.eye).normalize();
    assert!(to_duck.dot(c.toward) > 0.95, "{}", to_duck.dot(c.toward));
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn cameras_keeps_the_perspective_camera_and_warns_once_about_the_orthographic_one() {
    let Some((model, expected)) = load("Cameras.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 2, 2);
    assert_eq!(model.cameras.len(), 1);
    let c = &model.cameras[0];
    assert_eq!(c.eye, Vec3::new(0.5, 0.5, 3.0));
    assert_eq!((c.toward, c.up), (Vec3::NEG_Z, Vec3::Y));
    assert!((c.theta_deg - 0.35f32.to_degrees()).abs() < 1e-5);
    assert_eq!(c.aspect, Some(1.0));
    assert_eq!(model.warnings.len(), 1, "{:?}", model.warnings);
    assert!(model.warnings[0].contains("orthographic"));
    // No material: the documented default, light grey matte.
    assert_eq!(model.materials.len(), 1);
    assert_eq!(model.materials[0].material.base, BaseMaterial::Matte);
    assert_eq!(model.materials[0].material.color, Vec3::splat(0.8));
    // POSITION only: normals are computed from the faces, +z for this quad
    // before the node's rotation.
    assert!(model.meshes[0].normals.iter().all(|n| *n == Vec3::Z));
}

#[test]
fn simple_meshes_shares_one_mesh_between_two_nodes() {
    let Some((model, expected)) = load("SimpleMeshes.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 1, 2);
    assert_eq!(model.meshes.len(), 1);
    assert_eq!(model.instances.len(), 2);
    assert!(model.instances.iter().all(|i| i.mesh == 0));
    assert_eq!(model.instances[0].model_from_mesh, Mat4::IDENTITY);
    assert_eq!(
        model.instances[1].model_from_mesh,
        Mat4::from_translation(Vec3::X)
    );
    assert_eq!(model.instances[1].name, "node 1");
    assert_eq!(model.bounds(), Some((Vec3::ZERO, Vec3::new(2.0, 1.0, 0.0))));
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn orientation_test_places_13_meshes_through_trs_and_matrix_nodes() {
    let Some((model, expected)) = load("OrientationTest.gltf") else {
        return;
    };
    check_geometry(&model, &expected, 524, 524);
    assert_eq!(model.meshes.len(), 13);
    assert_eq!(model.instances.len(), 13);
    assert_eq!(model.materials.len(), 7);
    // Instances follow the scene's node order: node 5 "ArrowZ2" first.
    assert_eq!(model.instances[0].name, "ArrowZ2");
    let arrow_x1 = model
        .instances
        .iter()
        .find(|i| i.name == "ArrowX1")
        .expect("ArrowX1");
    assert_near(
        arrow_x1.model_from_mesh.w_axis.truncate(),
        Vec3::new(5.0, 0.0, 0.0),
        1e-6,
        "ArrowX1 translation",
    );
    // BaseMaterial: roughness 0.5, metallic 1 by default → metal.
    let by_color = |c: Vec3| {
        model
            .materials
            .iter()
            .find(|m| (m.material.color - c).abs().max_element() < 1e-5)
            .unwrap_or_else(|| panic!("a material of colour {c}"))
    };
    let base = by_color(Vec3::new(0.340_194, 0.678_103, 1.0));
    assert_eq!(base.material.base, BaseMaterial::Metal);
    // MatX1: metallic 0.4, roughness 0.2 → plastic, exponent 2/0.04² − 2.
    let x1 = by_color(Vec3::new(0.8, 0.0, 0.0));
    assert_eq!(x1.material.base, BaseMaterial::Plastic);
    assert!(
        (x1.material.shininess - 1248.0).abs() < 0.5,
        "{}",
        x1.material.shininess
    );
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

/// A model opened on its own that brings no light is lit by the studio
/// environment and its key light; the scene saves with the built-in map's name.
#[test]
fn a_model_without_lights_opens_in_the_studio() {
    let Some(dir) = samples() else { return };
    let scene = scene::read_any(&dir.join("Box.gltf")).expect("Box.gltf opens");
    let sky = scene.sky.clone().expect("the studio sky");
    assert_eq!(
        sky.map.as_ref().map(|m| m.src.as_str()),
        Some(scene::STUDIO_MAP)
    );
    assert_eq!(scene.lights.len(), 1);
    match scene.lights[0].kind {
        scene::LightKind::Directional { direction } => {
            assert!((direction + scene::STUDIO_KEY_DIRECTION).length() < 1e-6);
        }
        ref other => panic!("a directional key light, got {other:?}"),
    }
    assert!(scene::write_string(&scene).contains(r#"<sky map="raylab:studio"/>"#));
}
