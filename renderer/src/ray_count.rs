//! Counting rays traced (camera, secondary and shadow rays alike), for the
//! rays-per-second figure: one thread-local counter per thread, bumped by
//! every intersection query, read around each band of a pass.

use std::cell::Cell;

thread_local! {
    static RAYS: Cell<u64> = const { Cell::new(0) };
}

/// Counts one ray traced on this thread.
#[inline]
pub fn count_ray() {
    RAYS.with(|r| r.set(r.get() + 1));
}

/// Rays traced on this thread so far (compare two readings for a count).
pub fn rays_on_this_thread() -> u64 {
    RAYS.with(Cell::get)
}
