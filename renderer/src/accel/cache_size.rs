//! The size of the CPU's last-level cache, which decides how a mesh's
//! incoherent rays are traced in a batch ([`super::MeshBvh::closest_hits`]):
//! interleaved, to hide the wait for each node while the others compute,
//! when the tree is too large for the cache; one after another when it
//! mostly fits, since interleaving then only adds work.

use std::sync::OnceLock;

/// The last-level cache assumed where the system does not say: a desktop
/// CPU's L3.
const ASSUMED: usize = 8 << 20;

/// Bytes of the largest cache of CPU 0 (its last level), as Linux reports
/// it (`/sys/devices/system/cpu/cpu0/cache/index*/size`); [`ASSUMED`]
/// elsewhere. Read once.
pub fn last_level_cache_bytes() -> usize {
    static BYTES: OnceLock<usize> = OnceLock::new();
    *BYTES.get_or_init(|| from_sysfs().unwrap_or(ASSUMED))
}

/// The largest cache size sysfs lists for CPU 0, if it lists any.
fn from_sysfs() -> Option<usize> {
    std::fs::read_dir("/sys/devices/system/cpu/cpu0/cache")
        .ok()?
        .filter_map(|entry| std::fs::read_to_string(entry.ok()?.path().join("size")).ok())
        .filter_map(|size| parse_size(&size))
        .max()
}

/// A sysfs cache size ("32768K", "1M", "512") in bytes.
fn parse_size(text: &str) -> Option<usize> {
    let text = text.trim();
    let (digits, unit) = match text.strip_suffix(['K', 'M', 'G']) {
        Some(digits) => (digits, &text[digits.len()..]),
        None => (text, ""),
    };
    let shift = match unit {
        "K" => 10,
        "M" => 20,
        "G" => 30,
        _ => 0,
    };
    digits.parse::<usize>().ok()?.checked_mul(1 << shift)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sysfs_sizes_are_read_in_bytes_and_nonsense_is_refused() {
        assert_eq!(parse_size("32768K\n"), Some(32 << 20));
        assert_eq!(parse_size("1M"), Some(1 << 20));
        assert_eq!(parse_size("512"), Some(512));
        assert_eq!(parse_size("2G"), Some(2 << 30));
        assert_eq!(parse_size(""), None);
        assert_eq!(parse_size("K"), None);
        assert_eq!(parse_size("12Q"), None);
    }

    #[test]
    fn the_last_level_cache_is_at_least_a_few_kilobytes() {
        // Whatever this machine reports (or the assumption): a size a
        // cache could have.
        let bytes = last_level_cache_bytes();
        assert!((64 << 10..=4 << 30).contains(&bytes), "{bytes}");
    }
}
