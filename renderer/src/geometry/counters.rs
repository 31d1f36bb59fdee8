//! Counting the tracer's work, one thread-local counter per kind, bumped by
//! the intersection queries and read around each sample or band of a pass:
//!
//! - **rays** traced (camera, secondary and shadow rays alike), for the
//!   rays-per-second figure: one per [`World`](crate::world::World) query;
//! - **shape tests**, for the cost heatmap: calls of a shape's intersection
//!   routine, whether its bounding sphere or its exact test answers. A
//!   closest-hit query counts every shape or mesh instance the top-level BVH
//!   hands it and every infinite plane; a shadow query stops at the first
//!   occluder.
//!
//! A count is the difference of two readings on one thread.

use std::cell::Cell;
use std::thread::LocalKey;

thread_local! {
    static RAYS: Cell<u64> = const { Cell::new(0) };
    static SHAPE_TESTS: Cell<u64> = const { Cell::new(0) };
}

/// Adds `n` to this thread's `counter`.
#[inline]
fn add(counter: &'static LocalKey<Cell<u64>>, n: u64) {
    counter.with(|c| c.set(c.get() + n));
}

/// Counts one ray traced on this thread.
#[inline]
pub fn count_ray() {
    add(&RAYS, 1);
}

/// Rays traced on this thread so far (compare two readings for a count).
#[inline]
pub fn rays_on_this_thread() -> u64 {
    RAYS.with(Cell::get)
}

/// Counts `n` shape tests on this thread (one thread-local add per ray).
#[inline]
pub fn count_shape_tests(n: usize) {
    add(&SHAPE_TESTS, n as u64);
}

/// Shape tests counted on this thread so far (compare two readings for a count).
#[inline]
pub fn shape_tests_on_this_thread() -> u64 {
    SHAPE_TESTS.with(Cell::get)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_counter_counts_only_its_own_kind_on_its_own_thread() {
        let (rays, tests) = (rays_on_this_thread(), shape_tests_on_this_thread());
        count_ray();
        count_shape_tests(5);
        count_ray();
        assert_eq!(rays_on_this_thread() - rays, 2);
        assert_eq!(shape_tests_on_this_thread() - tests, 5);
        let other = std::thread::spawn(|| (rays_on_this_thread(), shape_tests_on_this_thread()));
        assert_eq!(other.join().expect("thread"), (0, 0));
    }
}
