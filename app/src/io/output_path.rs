//! Names of files raylab writes: where raylab picks the name it picks one
//! that is free (`NAME.png`, `NAME-2.png`, `NAME-3.png`, …), so no earlier
//! result is overwritten; where the user named the file, replacing it is
//! what they asked for, and raylab says so.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// `base` with `.ext` appended (`base` may hold dots of its own).
fn with_ext(base: &Path, ext: &str) -> PathBuf {
    let mut name: OsString = base.as_os_str().to_owned();
    name.push(".");
    name.push(ext);
    PathBuf::from(name)
}

/// The first of `base`, `base-2`, `base-3`, … for which no `base.EXT`
/// (the extension appended) exists for any of `extensions`: for outputs
/// written as several files.
fn free_stem(base: &Path, extensions: &[&str]) -> PathBuf {
    first_free(base, |b| extensions.iter().any(|e| with_ext(b, e).exists()))
}

/// `path` when no file has its name, else the first free one of
/// `NAME-2.EXT`, `NAME-3.EXT`, ….
pub fn free_file(path: &Path) -> PathBuf {
    match (path.file_stem(), path.extension().and_then(|e| e.to_str())) {
        (Some(stem), Some(ext)) => with_ext(&free_stem(&path.with_file_name(stem), &[ext]), ext),
        _ => first_free(path, Path::exists),
    }
}

/// The first of `base`, `base-2`, `base-3`, … that is not `taken`.
fn first_free(base: &Path, taken: impl Fn(&Path) -> bool) -> PathBuf {
    if !taken(base) {
        return base.to_path_buf();
    }
    (2u64..)
        .map(|n| {
            let mut name = base.as_os_str().to_owned();
            name.push(format!("-{n}"));
            PathBuf::from(name)
        })
        .find(|b| !taken(b))
        .unwrap_or_else(|| base.to_path_buf())
}

/// The CSV and PNG of a command that writes both (`raylab chart`,
/// `raylab stability`): `output` with those extensions when the user named it
/// (saying on stderr which files it replaces), else the first free pair
/// `default.csv`/`default.png`, `default-2.csv`/`default-2.png`, ….
pub fn csv_and_png(output: Option<&Path>, default: &str) -> (PathBuf, PathBuf) {
    match output {
        Some(output) => {
            let (csv, png) = (output.with_extension("csv"), output.with_extension("png"));
            note_replacing(&[&csv, &png]);
            (csv, png)
        }
        // The names free_stem found free: the extensions appended, as it checked them.
        None => {
            let stem = free_stem(Path::new(default), &["csv", "png"]);
            (with_ext(&stem, "csv"), with_ext(&stem, "png"))
        }
    }
}

/// Says on stderr which of `paths`, named by the user, are about to be replaced.
fn note_replacing(paths: &[&Path]) {
    for path in paths.iter().filter(|p| p.is_file()) {
        eprintln!("note: replacing the existing {}", path.display());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_taken_name_gets_the_first_free_number() {
        let dir = tempfile::tempdir().expect("temp dir");
        let shot = dir.path().join("seed-64spp.png");
        assert_eq!(free_file(&shot), shot, "free: kept");
        std::fs::write(&shot, "").expect("write");
        assert_eq!(free_file(&shot), dir.path().join("seed-64spp-2.png"));
        std::fs::write(dir.path().join("seed-64spp-2.png"), "").expect("write");
        assert_eq!(free_file(&shot), dir.path().join("seed-64spp-3.png"));
        // Another extension of the same name does not count.
        let exr = dir.path().join("seed-64spp.exr");
        assert_eq!(free_file(&exr), exr);
    }

    #[test]
    fn a_stem_is_free_only_when_every_extension_is() {
        let dir = tempfile::tempdir().expect("temp dir");
        let base = dir.path().join("chart.v1");
        assert_eq!(free_stem(&base, &["csv", "png"]), base);
        std::fs::write(dir.path().join("chart.v1.png"), "").expect("write");
        assert_eq!(
            free_stem(&base, &["csv", "png"]),
            dir.path().join("chart.v1-2")
        );
    }
}
