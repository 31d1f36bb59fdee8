//! Replacing a file so that it is never half written: the new content goes
//! to a temporary file in the same folder, is flushed and synced to disk,
//! and is then renamed over the target in one step. A failure at any point
//! leaves the target as it was and no temporary file behind.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The backup of `path` kept by [`replace_keeping_backup`]: the same name
/// with `.bak` appended (`scene.xml` → `scene.xml.bak`).
pub fn backup_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".bak");
    PathBuf::from(name)
}

/// Replaces `path` with `bytes` atomically (see the module comment).
pub fn replace(path: &Path, bytes: &[u8]) -> io::Result<()> {
    replace_with(path, false, &mut |w| w.write_all(bytes))
}

/// Replaces `path` with `bytes` atomically, first keeping the file it
/// replaces as [`backup_path`] (itself replaced atomically).
pub fn replace_keeping_backup(path: &Path, bytes: &[u8]) -> io::Result<()> {
    replace_with(path, true, &mut |w| w.write_all(bytes))
}

/// Replaces `path` with what `write` writes, atomically; with `backup`, the
/// old file (if any) is first copied to [`backup_path`]. A link is followed:
/// the file it points to is replaced, the link stays.
///
/// Order: the new content is written and synced to a temporary file first
/// (the step that fails on a full disk); only then is the backup made and
/// the temporary file renamed over the target, and the folder synced.
pub fn replace_with(
    path: &Path,
    backup: bool,
    write: &mut dyn FnMut(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let folder = match target.parent() {
        Some(f) if !f.as_os_str().is_empty() => f.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let old = std::fs::metadata(&target).ok().filter(|m| m.is_file());
    let mut temporary = temporary_in(&folder, &target)?;
    if let Some(old) = &old {
        // Keep the replaced file's permissions (not the temporary file's 0600).
        temporary.as_file().set_permissions(old.permissions())?;
    }
    {
        let mut writer = io::BufWriter::new(temporary.as_file_mut());
        write(&mut writer)?;
        writer.flush()?;
    }
    temporary.as_file().sync_all()?;
    if backup && old.is_some() {
        let mut source = File::open(&target)?;
        replace_with(&backup_path(&target), false, &mut |w| {
            io::copy(&mut source, w).map(|_| ())
        })?;
    }
    temporary.persist(&target).map_err(|e| e.error)?;
    // Make the rename itself durable; not every system can sync a folder.
    if let Ok(dir) = File::open(&folder) {
        let _ = dir.sync_all();
    }
    Ok(())
}

/// A hidden temporary file beside `target` (`.NAME.XXXXXX.tmp`), readable
/// as a new file would be (0666 less the umask) rather than tempfile's 0600.
fn temporary_in(folder: &Path, target: &Path) -> io::Result<tempfile::NamedTempFile> {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(folder)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that accepts `room` bytes, then fails as a full disk does.
    struct FullDisk<'w> {
        inner: &'w mut dyn Write,
        room: usize,
    }

    impl Write for FullDisk<'_> {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.room == 0 {
                return Err(io::Error::from(io::ErrorKind::StorageFull));
            }
            let n = buf.len().min(self.room);
            self.room -= n;
            self.inner.write(&buf[..n])
        }

        fn flush(&mut self) -> io::Result<()> {
            self.inner.flush()
        }
    }

    /// The names in `dir`, sorted.
    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("list")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn saving_over_a_file_puts_the_new_content_in_it_and_the_old_in_the_backup() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.xml");
        std::fs::write(&path, "old").expect("write");
        replace_keeping_backup(&path, b"new").expect("saved");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "new");
        let backup = dir.path().join("scene.xml.bak");
        assert_eq!(backup_path(&path), backup);
        assert_eq!(std::fs::read_to_string(&backup).expect("read"), "old");
        replace_keeping_backup(&path, b"newer").expect("saved");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "newer");
        assert_eq!(std::fs::read_to_string(&backup).expect("read"), "new");
        assert_eq!(names(dir.path()), ["scene.xml", "scene.xml.bak"]);
    }

    #[test]
    fn saving_a_new_file_makes_no_backup() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.xml");
        replace_keeping_backup(&path, b"first").expect("saved");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "first");
        assert_eq!(names(dir.path()), ["scene.xml"]);
    }

    #[test]
    fn a_disk_filling_up_mid_write_leaves_the_old_file_byte_identical_and_no_temporary_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.xml");
        let old = b"<scene>\n  <sphere/>\n</scene>\n";
        std::fs::write(&path, old).expect("write");
        let new = vec![b'x'; 100_000];
        let error = replace_with(&path, true, &mut |w| {
            FullDisk {
                inner: w,
                room: 5000,
            }
            .write_all(&new)
        })
        .expect_err("the disk is full");
        assert_eq!(error.kind(), io::ErrorKind::StorageFull);
        assert_eq!(std::fs::read(&path).expect("read"), old);
        assert_eq!(names(dir.path()), ["scene.xml"], "no temporary, no backup");
    }

    #[cfg(unix)]
    #[test]
    fn a_read_only_folder_refuses_the_save_and_keeps_the_old_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.xml");
        std::fs::write(&path, "old").expect("write");
        let set_mode = |mode| {
            std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(mode))
                .expect("chmod")
        };
        set_mode(0o555);
        // Root writes into read-only folders: the full-disk test covers it.
        let probe = dir.path().join("probe");
        if std::fs::write(&probe, "").is_ok() {
            let _ = std::fs::remove_file(&probe);
            set_mode(0o755);
            return;
        }
        let result = replace_keeping_backup(&path, b"new");
        set_mode(0o755);
        assert!(result.is_err());
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "old");
        assert_eq!(names(dir.path()), ["scene.xml"]);
    }

    #[cfg(unix)]
    #[test]
    fn replacing_a_file_keeps_its_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.xml");
        std::fs::write(&path, "old").expect("write");
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o640)).expect("chmod");
        replace(&path, b"new").expect("saved");
        let mode = std::fs::metadata(&path).expect("stat").permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
    }

    #[cfg(unix)]
    #[test]
    fn saving_through_a_link_replaces_the_file_it_points_to() {
        let dir = tempfile::tempdir().expect("temp dir");
        let real = dir.path().join("real.xml");
        let link = dir.path().join("link.xml");
        std::fs::write(&real, "old").expect("write");
        std::os::unix::fs::symlink(&real, &link).expect("symlink");
        replace_keeping_backup(&link, b"new").expect("saved");
        assert!(std::fs::symlink_metadata(&link).expect("stat").is_symlink());
        assert_eq!(std::fs::read_to_string(&real).expect("read"), "new");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("real.xml.bak")).expect("read"),
            "old"
        );
    }
}
