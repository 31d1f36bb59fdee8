//! Recovery files: the working scene of a window with unsaved changes,
//! written by [`super::autosave`] so that a crash loses at most a few
//! seconds of work, and found again on the next start.
//!
//! Each raylab process writes `recovery-PID.xml` in the recovery folder
//! (several windows may run at once); a file whose process is no longer
//! running was left by a crash. The file is the scene's XML
//! (`scene::write_string`) after one header line naming the scene file the
//! work belongs to: `<!-- raylab recovery of: /path/scene.xml -->`, or
//! `<!-- raylab recovery of a new scene -->`. Its modification time is when
//! it was autosaved.

use scene::Scene;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// The environment variable that overrides the recovery folder.
pub const DIR_VARIABLE: &str = "RAYLAB_RECOVERY_DIR";

/// The recovery folder: `$RAYLAB_RECOVERY_DIR` when set, else `recovery`
/// in eframe's storage folder for `app_id` (on Linux
/// `~/.local/share/raylab/recovery`).
pub fn default_dir(app_id: &str) -> Option<PathBuf> {
    match std::env::var_os(DIR_VARIABLE) {
        Some(dir) if !dir.is_empty() => Some(PathBuf::from(dir)),
        _ => eframe::storage_dir(app_id).map(|d| d.join("recovery")),
    }
}

/// The recovery file of process `pid` in `dir`.
pub fn file_of(dir: &Path, pid: u32) -> PathBuf {
    dir.join(format!("recovery-{pid}.xml"))
}

/// The process a recovery file belongs to, from its name.
fn pid_of(file: &Path) -> Option<u32> {
    file.file_name()?
        .to_str()?
        .strip_prefix("recovery-")?
        .strip_suffix(".xml")?
        .parse()
        .ok()
}

/// True while process `pid` runs. Linux answers through `/proc`; elsewhere
/// every other process counts as gone, so with two windows open on such a
/// system the second may offer the first's work.
fn is_running(pid: u32) -> bool {
    if pid == std::process::id() {
        // Asked at start, before this process wrote anything: the file is
        // an earlier process's that had the same id.
        return false;
    }
    cfg!(target_os = "linux") && Path::new("/proc").join(pid.to_string()).exists()
}

/// A recovery file left by a raylab that is no longer running.
#[derive(Clone, Debug, PartialEq)]
pub struct Left {
    /// The recovery file.
    pub file: PathBuf,
    /// The scene file the work belongs to; `None` for a new scene.
    pub source: Option<PathBuf>,
    /// When it was autosaved.
    pub autosaved: SystemTime,
}

/// The recovery files in `dir` whose process is no longer running, newest first.
pub fn left_behind(dir: &Path) -> Vec<Left> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut left: Vec<Left> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|file| pid_of(file).is_some_and(|pid| !is_running(pid)))
        .filter_map(|file| {
            let autosaved = std::fs::metadata(&file).ok()?.modified().ok()?;
            let source = read_header(&file)?;
            Some(Left {
                file,
                source,
                autosaved,
            })
        })
        .collect();
    left.sort_by_key(|l| std::cmp::Reverse(l.autosaved));
    left
}

/// Writes `scene`, the unsaved work on `source` (`None`: a new scene), to
/// the recovery file `file` atomically. Model paths of a new scene are made
/// absolute; a scene with a file keeps them relative to its folder, where
/// [`read`] resolves them.
pub fn write(file: &Path, scene: &Scene, source: Option<&Path>) -> std::io::Result<()> {
    let text = match source {
        Some(_) => scene::write_string(scene),
        None => {
            let mut scene = scene.clone();
            super::document::rebase_file_sources(&mut scene, file);
            scene::write_string(&scene)
        }
    };
    if let Some(dir) = file.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let text = format!("{}\n{text}", header(source));
    crate::io::atomic_file::replace(file, text.as_bytes())
}

/// Reads a recovery file: the scene and the file it belongs to. Mesh
/// sources resolve from that file's folder, as when it was open.
pub fn read(file: &Path) -> Result<(Scene, Option<PathBuf>), String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let source = text
        .lines()
        .next()
        .and_then(parse_header)
        .ok_or_else(|| format!("{}: not a raylab recovery file", file.display()))?;
    let label = source.as_deref().unwrap_or(file).display().to_string();
    let scene = scene::read_str(&text, &label).map_err(|e| e.to_string())?;
    Ok((scene, source))
}

/// The source named by `file`'s header line.
fn read_header(file: &Path) -> Option<Option<PathBuf>> {
    use std::io::BufRead;
    let mut line = String::new();
    std::io::BufReader::new(std::fs::File::open(file).ok()?)
        .read_line(&mut line)
        .ok()?;
    parse_header(line.trim_end())
}

const HEADER: &str = "<!-- raylab recovery of: ";
const HEADER_NEW: &str = "<!-- raylab recovery of a new scene -->";

/// The header line naming `source`.
fn header(source: Option<&Path>) -> String {
    match source {
        Some(path) => {
            let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
            format!("{HEADER}{} -->", encode(&path))
        }
        None => HEADER_NEW.to_owned(),
    }
}

/// The source a header line names (`Some(None)` for a new scene).
fn parse_header(line: &str) -> Option<Option<PathBuf>> {
    if line == HEADER_NEW {
        return Some(None);
    }
    let encoded = line.strip_prefix(HEADER)?.strip_suffix(" -->")?;
    decode(encoded).map(Some)
}

/// A path as comment text: bytes outside printable ASCII, `%`, and a `-`
/// that would make `--` or end the text become `%XX` (a comment cannot
/// hold `--`), so every path round-trips, non-UTF-8 ones included.
fn encode(path: &Path) -> String {
    let bytes = path_bytes(path);
    let mut out = String::new();
    for (k, &b) in bytes.iter().enumerate() {
        let dash_escaped = b == b'-' && (out.ends_with('-') || k + 1 == bytes.len());
        if b == b'%' || !(0x20..0x7f).contains(&b) || dash_escaped {
            out.push_str(&format!("%{b:02X}"));
        } else {
            out.push(char::from(b));
        }
    }
    out
}

/// The path [`encode`] encoded.
fn decode(text: &str) -> Option<PathBuf> {
    let mut bytes = Vec::new();
    let mut rest = text.as_bytes();
    while let Some((&b, tail)) = rest.split_first() {
        if b == b'%' {
            let hex = std::str::from_utf8(tail.get(..2)?).ok()?;
            bytes.push(u8::from_str_radix(hex, 16).ok()?);
            rest = &tail[2..];
        } else {
            bytes.push(b);
            rest = tail;
        }
    }
    Some(path_from_bytes(bytes))
}

#[cfg(unix)]
fn path_bytes(path: &Path) -> Vec<u8> {
    use std::os::unix::ffi::OsStrExt;
    path.as_os_str().as_bytes().to_vec()
}

#[cfg(not(unix))]
fn path_bytes(path: &Path) -> Vec<u8> {
    path.to_string_lossy().into_owned().into_bytes()
}

#[cfg(unix)]
fn path_from_bytes(bytes: Vec<u8>) -> PathBuf {
    use std::os::unix::ffi::OsStringExt;
    PathBuf::from(std::ffi::OsString::from_vec(bytes))
}

#[cfg(not(unix))]
fn path_from_bytes(bytes: Vec<u8>) -> PathBuf {
    PathBuf::from(String::from_utf8_lossy(&bytes).into_owned())
}

/// How long ago `then` was, for a person: "12 s ago", "5 min ago", "3 h 20 min ago", "2 days ago".
pub fn age(now: SystemTime, then: SystemTime) -> String {
    let s = now.duration_since(then).unwrap_or(Duration::ZERO).as_secs();
    match s {
        0..60 => format!("{s} s ago"),
        60..3600 => format!("{} min ago", s / 60),
        3600..86400 => format!("{} h {} min ago", s / 3600, s % 3600 / 60),
        _ => format!("{} days ago", s / 86400),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_round_trip_through_the_header_even_with_dashes_and_odd_bytes() {
        for path in [
            "/home/a/my--scene-.xml",
            "/tmp/100% done/-x-/scene.xml",
            "/tmp/ünïcode/scène.xml",
        ] {
            let line = header(Some(Path::new(path)));
            let inner = line
                .strip_prefix("<!--")
                .and_then(|l| l.strip_suffix("-->"))
                .expect("a comment");
            assert!(!inner.contains("--"), "{line}");
            assert!(!inner.trim_end().ends_with('-'), "{line}");
            assert_eq!(parse_header(&line), Some(Some(PathBuf::from(path))));
        }
        assert_eq!(parse_header(&header(None)), Some(None));
        assert_eq!(parse_header("<scene>"), None);
    }

    #[test]
    fn only_files_of_processes_that_are_gone_are_left_behind() {
        let dir = tempfile::tempdir().expect("temp dir");
        let scene = Scene::default();
        // Linux's largest process id is 2^22: this one never runs.
        let gone = file_of(dir.path(), 999_999_999);
        write(&gone, &scene, None).expect("written");
        // The parent of this test process (cargo or a shell) is running.
        #[cfg(target_os = "linux")]
        {
            let running = std::os::unix::process::parent_id();
            write(&file_of(dir.path(), running), &scene, None).expect("written");
        }
        std::fs::write(dir.path().join("notes.xml"), "<scene/>").expect("write");
        let left = left_behind(dir.path());
        assert_eq!(left.len(), 1, "{left:?}");
        assert_eq!(left[0].file, gone);
        assert_eq!(left[0].source, None);
    }

    /// One triangle, (0,0,0) (1,0,0) (0,1,0), its buffer inline.
    const TRIANGLE_GLTF: &str = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"scene":0,
        "nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
            "min":[0,0,0],"max":[1,1,0]}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}"#;

    #[test]
    fn a_recovered_scene_still_finds_its_model_beside_the_original_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let project = dir.path().join("project");
        std::fs::create_dir(&project).expect("mkdir");
        std::fs::write(project.join("box.gltf"), TRIANGLE_GLTF).expect("write model");
        let original = project.join("scene.xml");
        std::fs::write(&original, "<scene>\n  <mesh src=\"box.gltf\"/>\n</scene>\n")
            .expect("write scene");
        let mut scene = scene::read_file(&original).expect("reads");
        scene.camera.theta_deg = 21.0;
        let recovery = file_of(&dir.path().join("recovery"), 999_999_999);
        write(&recovery, &scene, Some(&original)).expect("written");
        let (recovered, source) = read(&recovery).expect("reads back");
        assert_eq!(source.as_deref(), Some(original.as_path()));
        assert_eq!(recovered, scene);
        scene::resolve(&recovered).expect("the model is found and loads");
    }

    #[test]
    fn ages_read_in_the_largest_sensible_unit() {
        let t = SystemTime::UNIX_EPOCH + Duration::from_secs(1_000_000);
        let after = |s| t + Duration::from_secs(s);
        assert_eq!(age(after(12), t), "12 s ago");
        assert_eq!(age(after(300), t), "5 min ago");
        assert_eq!(age(after(3 * 3600 + 20 * 60), t), "3 h 20 min ago");
        assert_eq!(age(after(2 * 86400 + 5), t), "2 days ago");
        assert_eq!(age(t, after(5)), "0 s ago", "a clock set back");
    }
}
