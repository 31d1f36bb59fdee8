//! Large arrays of the acceleration structure on 2 MiB pages where the
//! system grants them (Linux transparent huge pages; in `madvise` mode, as
//! on the machines we measure on, only memory that asks gets them). Embree
//! asks the same for its BVH memory. Measured on the
//! million-triangle knot with a throw-away timer, against no advice in the
//! same run: `MeshBvh::build` on 2 threads 0.163-0.165 s -> 0.153-0.158
//! (fewer page faults while the arrays are first written; `raylab bench`,
//! in separate runs, did not show it within its noise); incoherent closest
//! hits on 1 thread 2.0 -> 2.1-2.2 Mrays/s (fewer TLB misses); primary
//! rays +1-2%.
//!
//! The first such array also fixes glibc's threshold for giving an
//! allocation its own mapping ([`keep_large_allocations_out_of_the_heap`]),
//! so that a build's transient arrays go back to the system when freed.
#![allow(unsafe_code)]

/// Bytes of one huge page.
const HUGE_PAGE: usize = 2 << 20;

/// An empty vector with room for `capacity` items, whose storage the kernel
/// is asked to back with huge pages (only the whole 2 MiB pages inside it:
/// a small vector is left as it is).
pub fn with_capacity<T>(capacity: usize) -> Vec<T> {
    keep_large_allocations_out_of_the_heap();
    let v = Vec::with_capacity(capacity);
    if let Some((start, len)) = whole_huge_pages(v.as_ptr() as usize, v.capacity() * size_of::<T>())
    {
        advise(start, len);
    }
    v
}

/// Allocations of at least this many bytes get their own mapping from
/// glibc's malloc, returned to the system when freed.
const OWN_MAPPING: usize = 4 << 20;

/// Free memory glibc's heaps keep rather than give back: twice
/// [`OWN_MAPPING`], the relation glibc's own adjustment keeps. Fixing the
/// mapping threshold stops that adjustment, which would leave this at its
/// 128 KiB default: then every batch's scratch vectors (`World::
/// intersect_batch`, 100–200 KiB) were given back and faulted in again,
/// and batched primary rays on the knot fell from 27.3 to 18.2 Mrays/s.
const KEPT_FREE: usize = 2 * OWN_MAPPING;

/// Fixes glibc's threshold for giving an allocation its own mapping at
/// [`OWN_MAPPING`], and so the free memory its heaps keep at [`KEPT_FREE`]
/// (once per process, at the first large array; the setting is the
/// process's). Left to itself, glibc raises the threshold
/// to the size of each mapped block freed, up to 32 MiB (`mallopt(3)`),
/// after which a BVH build's transient arrays (a million triangles' boxes:
/// 30.5 MiB) are served from its heaps, which need not give freed memory
/// back. Measured with the thousand-random-edits load test of the
/// million-triangle knot (the whole `raylab` test binary, run repeatedly):
/// with leaves of four packs it ended 38 MiB higher than half-way in 4 of
/// 16 runs (0 of 14 with leaves of two); with the threshold fixed (at
/// 128 KiB or 4 MiB through glibc's environment variable, 13 runs, and
/// here with [`KEPT_FREE`], 8 runs) every run stayed flat.
fn keep_large_allocations_out_of_the_heap() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        static ONCE: std::sync::Once = std::sync::Once::new();
        // SAFETY: mallopt only changes a tuning parameter of the
        // allocator (it is thread-safe and changes no allocation made).
        ONCE.call_once(|| unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, OWN_MAPPING as libc::c_int);
            libc::mallopt(libc::M_TRIM_THRESHOLD, KEPT_FREE as libc::c_int);
        });
    }
}

/// The whole huge pages inside the bytes [start, start + len): (first
/// byte, length), or `None` when there is none.
fn whole_huge_pages(start: usize, len: usize) -> Option<(usize, usize)> {
    let first = start.checked_next_multiple_of(HUGE_PAGE)?;
    let end = start.checked_add(len)? / HUGE_PAGE * HUGE_PAGE;
    (end > first).then(|| (first, end - first))
}

/// Asks for huge pages over [start, start + len) (a hint: the kernel may
/// refuse it, which changes nothing but speed).
#[cfg(target_os = "linux")]
fn advise(start: usize, len: usize) {
    // SAFETY: the range lies inside a live allocation of the caller's
    // vector; MADV_HUGEPAGE changes how its memory is backed, never what
    // it holds, and needs no particular state of it.
    unsafe {
        libc::madvise(start as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_start: usize, _len: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_whole_huge_pages_inside_the_range_are_advised() {
        const P: usize = HUGE_PAGE;
        // Aligned at both ends: all of it.
        assert_eq!(whole_huge_pages(4 * P, 3 * P), Some((4 * P, 3 * P)));
        // Unaligned: the interior pages only.
        assert_eq!(whole_huge_pages(4 * P + 8, 3 * P), Some((5 * P, 2 * P)));
        // Smaller than a page, or straddling one boundary: nothing.
        assert_eq!(whole_huge_pages(4 * P + 8, P / 2), None);
        assert_eq!(whole_huge_pages(5 * P - 8, P), None);
        // At the top of the address space: no overflow.
        assert_eq!(whole_huge_pages(usize::MAX - 8, 4), None);
        assert_eq!(whole_huge_pages(usize::MAX - P, 2 * P), None);
    }

    #[test]
    fn the_vector_is_empty_with_the_capacity_asked_for() {
        let v: Vec<[f32; 8]> = with_capacity(1 << 20);
        assert!(v.is_empty() && v.capacity() >= 1 << 20);
        let small: Vec<u8> = with_capacity(10);
        assert!(small.is_empty() && small.capacity() >= 10);
    }
}
