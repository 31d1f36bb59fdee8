//! glTF models end to end: the Khronos samples in ../shared/gltf (when that
//! folder exists; they are not ours to ship) render directly and inside a
//! scene's `<mesh>`, and a model placed by `<mesh>` lands where its
//! transform says.

mod support;

use std::path::PathBuf;
use support::{raylab, read_png, render, root};

/// The sample folder beside the workspace, if this machine has it.
fn samples() -> Option<PathBuf> {
    let dir = root().join("../shared/gltf");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "note: {} is missing; glTF sample tests skipped",
            dir.display()
        );
        None
    }
}

/// Pixels that differ clearly from the leftmost pixel of their row: the
/// background there (a model opened on its own sits in the middle, before
/// the studio's gradient, which changes from row to row).
fn covered(image: &image::RgbImage) -> usize {
    model_pixels(image).len()
}

/// The pixels [`covered`] counts.
fn model_pixels(image: &image::RgbImage) -> Vec<image::Rgb<u8>> {
    image
        .enumerate_pixels()
        .filter(|(_, y, p)| {
            let background = image.get_pixel(0, *y);
            p.0.iter()
                .zip(background.0)
                .any(|(&a, b)| a.abs_diff(b) > 8)
        })
        .map(|(_, _, p)| *p)
        .collect()
}

#[test]
fn a_model_without_lights_is_lit_by_the_studio_in_both_integrators() {
    let Some(dir) = samples() else { return };
    let out = tempfile::tempdir().expect("tempdir");
    for integrator in ["whitted", "path"] {
        let png = out.path().join(format!("duck-{integrator}.png"));
        render(
            &dir.join("Duck.gltf"),
            &png,
            &[
                "--width",
                "96",
                "--height",
                "72",
                "--spp",
                "16",
                "--integrator",
                integrator,
            ],
        );
        let image = read_png(&png);
        let model = model_pixels(&image);
        assert!(
            model.len() > 96 * 72 / 25,
            "{integrator}: the duck covers {}",
            model.len()
        );
        // Mostly lit, not mostly black: the mean sRGB level of its pixels.
        let mean = model
            .iter()
            .map(|p| f64::from(p.0[0]) + f64::from(p.0[1]) + f64::from(p.0[2]))
            .sum::<f64>()
            / (3.0 * model.len() as f64);
        let dark = model.iter().filter(|p| p.0.iter().all(|&c| c < 20)).count();
        assert!(
            mean > 80.0 && dark * 10 < model.len(),
            "{integrator}: the duck's mean level {mean:.0}, {dark} of {} pixels near black",
            model.len()
        );
    }
}

#[test]
fn every_sample_model_renders_directly_and_shows_itself() {
    let Some(dir) = samples() else { return };
    let out = tempfile::tempdir().expect("tempdir");
    for name in [
        "Box",
        "BoxTextured",
        "Duck",
        "Cameras",
        "OrientationTest",
        "SimpleMeshes",
    ] {
        let png = out.path().join(format!("{name}.png"));
        render(
            &dir.join(format!("{name}.gltf")),
            &png,
            &["--width", "64", "--height", "48", "--spp", "1"],
        );
        let image = read_png(&png);
        let n = covered(&image);
        assert!(n > 64 * 48 / 50, "{name}: only {n} pixels show the model");
    }
}

#[test]
fn a_mesh_element_places_the_model_relative_to_the_scene_file() {
    let Some(dir) = samples() else { return };
    let out = tempfile::tempdir().expect("tempdir");
    // The scene lives elsewhere and names the model by a relative path.
    let models = out.path().join("models");
    std::fs::create_dir(&models).expect("mkdir");
    std::fs::copy(dir.join("Box.gltf"), models.join("Box.gltf")).expect("copy");
    let scene = out.path().join("scene.xml");
    let eye = r#"<camera eye="0 0 6" toward="0 0 -1" width="64" height="48"/>"#;
    let write = |translate: &str| {
        std::fs::write(
            &scene,
            format!(r#"<scene>{eye}<mesh src="models/Box.gltf" translate="{translate}"/></scene>"#),
        )
        .expect("write scene");
    };
    let column_of_mass = |translate: &str| {
        write(translate);
        let png = out.path().join("placed.png");
        render(&scene, &png, &["--spp", "1"]);
        let image = read_png(&png);
        let background = *image.get_pixel(0, 0);
        let (sum, count) = image
            .enumerate_pixels()
            .filter(|(_, _, p)| **p != background)
            .fold((0u64, 0u64), |(s, c), (x, _, _)| (s + u64::from(x), c + 1));
        assert!(count > 20, "the box shows at {translate}");
        sum as f64 / count as f64
    };
    let centre = column_of_mass("0 0 0");
    let right = column_of_mass("1.5 0 0");
    assert!((centre - 31.5).abs() < 2.0, "centred: {centre}");
    assert!(right > centre + 8.0, "moved right: {centre} → {right}");
}

#[test]
fn a_broken_model_is_an_error_naming_the_file_and_the_scene_position() {
    let out = tempfile::tempdir().expect("tempdir");
    std::fs::write(out.path().join("broken.gltf"), "{ not json").expect("write");
    let scene = out.path().join("scene.xml");
    std::fs::write(&scene, "<scene>\n  <mesh src=\"broken.gltf\"/>\n</scene>\n").expect("write");
    let output = raylab(&[
        "render",
        scene.to_str().expect("utf-8"),
        "-o",
        out.path().join("x.png").to_str().expect("utf-8"),
    ]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("scene.xml:2:14"), "{stderr}");
    assert!(stderr.contains("broken.gltf"), "{stderr}");
}
