//! Counting intersection work for the cost heatmap: one thread-local
//! counter of shape tests (calls of a shape's intersection routine, whether
//! its bounding sphere or its exact test answers), read around each sample.
//!
//! The rule, exact for the brute-force [`World`](crate::world::World): a
//! closest-hit query tests every shape (N per ray); a shadow query tests
//! shapes in object order up to and including the first occluder (N when
//! nothing occludes).

use std::cell::Cell;

thread_local! {
    static TESTS: Cell<u64> = const { Cell::new(0) };
}

/// Counts `n` shape tests on this thread (one thread-local add per ray).
#[inline]
pub fn count_shape_tests(n: usize) {
    TESTS.with(|t| t.set(t.get() + n as u64));
}

/// Shape tests counted on this thread so far (compare two readings for a count).
#[inline]
pub fn shape_tests_on_this_thread() -> u64 {
    TESTS.with(Cell::get)
}
