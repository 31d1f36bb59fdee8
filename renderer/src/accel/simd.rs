//! Running traversal code with the widest SIMD instructions the CPU has,
//! chosen at run time. The node test is written lane by lane over arrays
//! (`[f32; 8]`), which the compiler vectorises for whatever instruction set
//! the enclosing function is compiled for; the triangle test uses `wide`'s
//! four-lane vectors, which get the shorter AVX encodings there. A release
//! build targets baseline x86-64 (SSE2, four lanes), so the same code is
//! compiled a second time with AVX2 enabled (eight lanes) and picked when
//! the CPU has it. The arithmetic is the same either way (no fused
//! multiply–add), so both give the same hits bit for bit.
//!
//! This is the one place in the workspace with `unsafe`: calling a function
//! compiled for AVX2 is only sound on a CPU that has it, which is checked
//! just before.

#![allow(unsafe_code)]

/// `f()`, compiled for AVX2 when this CPU has it, else for the build's
/// baseline. `f` should be `#[inline(always)]` code (a closure calling
/// such functions) so that it is compiled inside the AVX2 function.
#[inline(always)]
pub fn with_widest_simd<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: `avx2` only requires that the CPU supports AVX2, which
        // `is_x86_feature_detected!` has just confirmed.
        return unsafe { avx2(f) };
    }
    f()
}

/// Asks the CPU to start loading the cache lines of `value` (a hint: it
/// never faults and changes nothing), so that a node or leaf the traversal
/// will visit soon is on its way while other work proceeds.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        const LINE: usize = 64;
        let start = (value as *const T).cast::<i8>();
        // `value` need not start on a line, so it touches up to one line
        // more than its size in lines; a fixed count keeps this branch-free
        // (a line past its end, when there is one, is harmless).
        for line in 0..=std::mem::size_of::<T>() / LINE {
            // SAFETY: prefetching is a hint that never faults, whatever the
            // address; these are `value`'s lines and at most one past them.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(line * LINE)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// Calls `f` from a function compiled with AVX2 enabled.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_widest_simd_returns_what_f_returns() {
        let lanes: [f32; 8] = std::array::from_fn(|i| i as f32);
        let sum = with_widest_simd(|| lanes.iter().map(|x| x * 2.0).sum::<f32>());
        assert_eq!(sum, 56.0);
    }
}
