//! Reading files with a bound on what is allocated: a hostile file that is
//! huge, or a device that never ends, is refused or cut, never read whole.

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

/// The first `limit` bytes of the file at `path` (all of it when shorter).
pub(crate) fn read_prefix(path: &Path, limit: usize) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read the file: {e}"))?;
    let size = file.metadata().map_or(0, |m| m.len());
    let mut bytes = Vec::with_capacity(size.min(limit as u64) as usize);
    file.take(limit as u64)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    Ok(bytes)
}
