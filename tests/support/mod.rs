//! Helpers shared by the end-to-end tests: run the real `raylab` binary.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace's root folder.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A path inside `assets/scenes/`.
pub fn asset(name: &str) -> PathBuf {
    root().join("assets/scenes").join(name)
}

/// Runs `raylab` with `args` and returns its output.
pub fn raylab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .output()
        .expect("raylab runs")
}

/// Runs `raylab` with `args`, panics with its output if it fails, and
/// returns what it printed on stdout.
pub fn raylab_ok(args: &[&str]) -> String {
    let output = raylab(args);
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "raylab {args:?} failed:\n{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

/// Runs `raylab render` and panics with its stderr if it fails.
pub fn render(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "render",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
    ];
    args.extend_from_slice(extra);
    let output = raylab(&args);
    assert!(
        output.status.success(),
        "raylab {args:?} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// Reads an 8-bit RGB PNG.
pub fn read_png(path: &Path) -> image::RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
}
