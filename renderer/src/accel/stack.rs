//! The traversal stack: a fixed array on the program stack, spilling to the
//! heap only for pathologically deep trees, so traversal never allocates in
//! practice and never overflows.

/// A LIFO stack of `T` with `INLINE` entries in place (each traversal
/// initialises them, so keep `INLINE` near the trees' depth).
pub(crate) struct Stack<T: Copy + Default, const INLINE: usize> {
    /// The first `INLINE` entries.
    inline: [T; INLINE],
    /// How many of `inline` are in use.
    len: usize,
    /// Entries pushed while `inline` was full (they are the top of the stack).
    spill: Vec<T>,
}

impl<T: Copy + Default, const INLINE: usize> Stack<T, INLINE> {
    /// An empty stack (no allocation).
    #[inline(always)]
    pub(crate) fn new() -> Self {
        Self {
            inline: [T::default(); INLINE],
            len: 0,
            spill: Vec::new(),
        }
    }

    /// Empties the stack (keeps its storage, so no entry is written).
    #[inline(always)]
    pub(crate) fn clear(&mut self) {
        self.len = 0;
        self.spill.clear();
    }

    /// Pushes `v` on top.
    #[inline(always)]
    pub(crate) fn push(&mut self, v: T) {
        if self.len < INLINE {
            self.inline[self.len] = v;
            self.len += 1;
        } else {
            self.spill.push(v);
        }
    }

    /// Removes and returns the top entry.
    #[inline(always)]
    pub(crate) fn pop(&mut self) -> Option<T> {
        if self.len < INLINE || self.spill.is_empty() {
            if self.len == 0 {
                return None;
            }
            self.len -= 1;
            Some(self.inline[self.len])
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
