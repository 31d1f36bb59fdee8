//! The hostile-file corpus (tests/hostile) through the real program: `raylab
//! render` refuses each bad file with one line naming it and exit code 2, never
//! a panic; each hostile-but-valid file renders, with both integrators, to an
//! image without a NaN or infinite pixel and without discarded samples.

mod support;

use support::{raylab, root};

/// (corpus file, expected error text or `loads`), from expected.tsv.
fn corpus() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(root().join("tests/hostile/expected.tsv"))
        .expect("tests/hostile/expected.tsv");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .filter_map(|l| l.split_once('\t'))
        .map(|(f, e)| (f.to_owned(), e.to_owned()))
        .collect()
}

/// Every value of the EXR's channels.
fn exr_values(path: &std::path::Path) -> Vec<f32> {
    use exr::prelude::*;
    let image = read_all_flat_layers_from_file(path).expect("reads the EXR");
    image.layer_data[0]
        .channel_data
        .list
        .iter()
        .flat_map(|c| c.sample_data.values_as_f32())
        .collect()
}

#[test]
fn hostile_files_are_one_line_errors_or_render_finite_images() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut failures = Vec::new();
    for (file, expected) in corpus() {
        let path = root().join("tests/hostile").join(&file);
        let integrators: &[&str] = if expected == "loads" {
            &["path", "whitted"]
        } else {
            &["path"]
        };
        for integrator in integrators {
            let out = dir.path().join("out.exr");
            let _ = std::fs::remove_file(&out);
            let args = [
                "render",
                path.to_str().expect("utf-8"),
                "-o",
                out.to_str().expect("utf-8"),
                "--width",
                "16",
                "--height",
                "12",
                "--spp",
                "4",
                "--integrator",
                integrator,
            ];
            let output = raylab(&args);
            let stderr = String::from_utf8_lossy(&output.stderr);
            let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
            let name = path
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or_default();
            if stderr.contains("panicked") {
                failures.push(format!("{file}: panicked: {stderr}"));
            } else if expected == "loads" {
                if !output.status.success() {
                    failures.push(format!("{file} ({integrator}): failed: {stderr}"));
                } else if stderr.contains("NaN or infinite") {
                    failures.push(format!(
                        "{file} ({integrator}): discarded samples: {stderr}"
                    ));
                } else if let Some(bad) = exr_values(&out).into_iter().find(|v| !v.is_finite()) {
                    failures.push(format!("{file} ({integrator}): pixel value {bad}"));
                }
            } else if output.status.code() != Some(2) {
                failures.push(format!(
                    "{file}: exit {:?}, expected 2: {stderr}",
                    output.status
                ));
            } else if errors.len() != 1 || !errors[0].contains(name) {
                failures.push(format!(
                    "{file}: expected one error line naming it: {stderr}"
                ));
            } else if out.exists() {
                failures.push(format!("{file}: wrote an image for a refused file"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
