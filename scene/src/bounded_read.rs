//! Reading files with a bound on what is allocated: a hostile file that is
//! huge is refused or cut, never read whole, and only regular files are read
//! (a device such as `/dev/zero` never ends, and a pipe can block forever).

use std::path::Path;

/// The file at `path`, refused when it is longer than `limit` bytes (or
/// never ends, like a device) rather than allocated whole.
pub(crate) fn read_limited(path: &Path, limit: usize) -> Result<Vec<u8>, String> {
    let bytes = read_prefix(path, limit.saturating_add(1))?;
    if bytes.len() > limit {
        return Err(format!(
            "the file is larger than the {limit} bytes raylab reads from it"
        ));
    }
    Ok(bytes)
}

/// The first `limit` bytes of the regular file at `path` (all of it when
/// shorter); a folder, device or pipe is refused before it is opened.
pub(crate) fn read_prefix(path: &Path, limit: usize) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let cannot = |e: std::io::Error| format!("cannot read the file: {e}");
    let not_a_file = || {
        "it is not a regular file (a folder, device or pipe), so raylab does not read it"
            .to_string()
    };
    // Checked before opening too: opening a pipe waits for a writer.
    if !std::fs::metadata(path).map_err(cannot)?.is_file() {
        return Err(not_a_file());
    }
    let file = std::fs::File::open(path).map_err(cannot)?;
    let metadata = file.metadata().map_err(cannot)?;
    if !metadata.is_file() {
        return Err(not_a_file());
    }
    let mut bytes = Vec::with_capacity(metadata.len().min(limit as u64) as usize);
    file.take(limit as u64)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_folders_are_refused_without_reading() {
        for path in ["/dev/zero", "/dev/null", "/"] {
            let error = read_limited(Path::new(path), 1 << 30).expect_err(path);
            assert!(error.contains("not a regular file"), "{path}: {error}");
        }
    }

    #[test]
    fn a_prefix_stops_at_the_limit_and_a_longer_file_is_refused() {
        let path = std::env::temp_dir().join(format!("raylab-bounded-{}", std::process::id()));
        std::fs::write(&path, b"0123456789").expect("write");
        assert_eq!(read_prefix(&path, 4).as_deref(), Ok(&b"0123"[..]));
        assert_eq!(read_limited(&path, 10).as_deref(), Ok(&b"0123456789"[..]));
        let error = read_limited(&path, 9).expect_err("10 bytes > 9");
        assert!(error.contains("larger than the 9 bytes"), "{error}");
        std::fs::remove_file(&path).expect("remove");
    }
}
