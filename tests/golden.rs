//! Golden images: each shipped scene rendered small must match its reviewed
//! picture in tests/golden/ within a tolerance. After a deliberate change,
//! regenerate with `UPDATE_GOLDEN=1 cargo test -p raylab --test golden`, look
//! at every new PNG, and commit them.

mod support;

use support::{asset, read_png, render, root};

/// Largest mean absolute channel difference, in 8-bit levels.
const MEAN_TOLERANCE: f64 = 0.5;
/// Largest share of channels differing by more than 8 levels.
const OUTLIER_SHARE: f64 = 0.002;

#[test]
fn shipped_scenes_match_their_golden_images() {
    let dir = tempfile::tempdir().expect("tempdir");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut failures = Vec::new();
    for name in ["seed", "primitives", "cornell", "glass"] {
        let out = dir.path().join(format!("{name}.png"));
        render(
            &asset(&format!("{name}.xml")),
            &out,
            &["--width", "160", "--height", "100", "--spp", "4"],
        );
        let golden_path = root().join("tests/golden").join(format!("{name}.png"));
        if update {
            std::fs::copy(&out, &golden_path).expect("update golden");
            continue;
        }
        let (got, want) = (read_png(&out), read_png(&golden_path));
        assert_eq!(got.dimensions(), want.dimensions(), "{name}");
        let diffs: Vec<u8> = got
            .as_raw()
            .iter()
            .zip(want.as_raw())
            .map(|(a, b)| a.abs_diff(*b))
            .collect();
        let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
        let outliers = diffs.iter().filter(|&&d| d > 8).count() as f64 / diffs.len() as f64;
        if mean > MEAN_TOLERANCE || outliers > OUTLIER_SHARE {
            let kept = root().join("tests/golden").join(format!("{name}.new.png"));
            std::fs::copy(&out, &kept).expect("keep");
            failures.push(format!(
                "{name}: mean diff {mean:.3}, outliers {:.3}% (new image at {})",
                outliers * 100.0,
                kept.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "golden images differ:\n{}",
        failures.join("\n")
    );
}
