//! The traversal stack: a fixed array on the program stack, spilling to the
//! heap only for pathologically deep trees, so traversal never allocates in
//! practice and never overflows.

use arrayvec::ArrayVec;

/// A LIFO stack of `T` with `INLINE` entries in place. The inline entries
/// are not initialised up front ([`ArrayVec`]), so starting a traversal
/// costs nothing however large `INLINE` is.
pub(crate) struct Stack<T: Copy, const INLINE: usize> {
    /// The bottom `INLINE` entries.
    inline: ArrayVec<T, INLINE>,
    /// Entries pushed while `inline` was full (they are the top of the stack).
    spill: Vec<T>,
}

impl<T: Copy, const INLINE: usize> Stack<T, INLINE> {
    /// An empty stack (no allocation).
    #[inline(always)]
    pub(crate) fn new() -> Self {
        Self {
            inline: ArrayVec::new(),
            spill: Vec::new(),
        }
    }

    /// Empties the stack (keeps its storage).
    #[inline(always)]
    pub(crate) fn clear(&mut self) {
        self.inline.clear();
        self.spill.clear();
    }

    /// Pushes `v` on top.
    #[inline(always)]
    pub(crate) fn push(&mut self, v: T) {
        if let Err(full) = self.inline.try_push(v) {
            self.spill.push(full.element());
        }
    }

    /// Removes and returns the top entry.
    #[inline(always)]
    pub(crate) fn pop(&mut self) -> Option<T> {
        if self.spill.is_empty() {
            self.inline.pop()
        } else {
            self.spill.pop()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stack_is_lifo_across_the_spill_boundary() {
        let mut s = Stack::<u32, 64>::new();
        for v in 0..200 {
            s.push(v);
        }
        for v in (0..200).rev() {
            assert_eq!(s.pop(), Some(v));
        }
        assert_eq!(s.pop(), None);
    }
}
