//! Fixed-capacity ring buffer: keeps the latest `N` samples, no heap.
//!
//! The capture loop pushes every sample; once the buffer is full each push overwrites
//! the oldest one, so after the impact the buffer holds the last `N / ODR` seconds of
//! the stroke. [`RingBuffer::make_contiguous`] then rotates the storage in place
//! (oldest first) so the estimator can read it as one slice, without a second buffer.

/// A ring of `N` values of `T`, oldest overwritten first.
#[derive(Clone, Debug)]
pub struct RingBuffer<T, const N: usize> {
    buf: [T; N],
    /// Index of the oldest element.
    head: usize,
    len: usize,
}

impl<T: Copy, const N: usize> RingBuffer<T, N> {
    /// An empty buffer; `fill` only initialises the storage (usable in a `static`).
    pub const fn new(fill: T) -> Self {
        Self {
            buf: [fill; N],
            head: 0,
            len: 0,
        }
    }

    /// Capacity `N`.
    pub const fn capacity(&self) -> usize {
        N
    }

    /// Number of values held.
    pub const fn len(&self) -> usize {
        self.len
    }

    /// `true` when no value is held.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `true` when the next [`RingBuffer::push`] overwrites the oldest value.
    pub const fn is_full(&self) -> bool {
        self.len == N
    }

    /// Forget every value (the storage is not cleared).
    pub fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }

    /// Append `value`; when full, overwrite the oldest value and return it. With `N = 0`
    /// nothing is stored and `value` itself is returned.
    pub fn push(&mut self, value: T) -> Option<T> {
        if N == 0 {
            return Some(value);
        }
        if self.len < N {
            if let Some(slot) = self.buf.get_mut((self.head + self.len) % N) {
                *slot = value;
                self.len += 1;
            }
            None
        } else {
            let old = self
                .buf
                .get_mut(self.head)
                .map(|slot| core::mem::replace(slot, value));
            self.head = (self.head + 1) % N;
            old
        }
    }

    /// Append `value` only if there is room; otherwise hand it back (heapless style).
    pub fn try_push(&mut self, value: T) -> Result<(), T> {
        if self.len < N {
            self.push(value);
            Ok(())
        } else {
            Err(value)
        }
    }

    /// The `i`-th value, oldest first (`0` = oldest).
    pub fn get(&self, i: usize) -> Option<T> {
        if i < self.len {
            self.buf.get((self.head + i) % N).copied()
        } else {
            None
        }
    }

    /// The newest value.
    pub fn latest(&self) -> Option<T> {
        match self.len {
            0 => None,
            n => self.get(n - 1),
        }
    }

    /// The held values as two slices, oldest first: `first` then `second`.
    pub fn as_slices(&self) -> (&[T], &[T]) {
        // `get` keeps this free of panic paths; `head < N` and `len <= N` always hold.
        let end = self.head + self.len;
        if end <= N {
            (self.buf.get(self.head..end).unwrap_or(&[]), &[])
        } else {
            (
                self.buf.get(self.head..).unwrap_or(&[]),
                self.buf.get(..end - N).unwrap_or(&[]),
            )
        }
    }

    /// Iterate over the held values, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = T> + '_ {
        let (a, b) = self.as_slices();
        a.iter().chain(b.iter()).copied()
    }

    /// Rotate the storage in place so the values are contiguous, oldest first, and return
    /// them. `O(N)` moves, no extra memory; later pushes continue correctly.
    pub fn make_contiguous(&mut self) -> &[T] {
        if N > 0 && self.head != 0 {
            self.buf.rotate_left(self.head % N);
            self.head = 0;
        }
        self.buf.get(..self.len).unwrap_or(&[])
    }

    /// Copy the held values, oldest first, into `out`; returns how many were copied
    /// (at most `out.len()`).
    pub fn copy_to(&self, out: &mut [T]) -> usize {
        let mut n = 0;
        for (slot, value) in out.iter_mut().zip(self.iter()) {
            *slot = value;
            n += 1;
        }
        n
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::collections::VecDeque;
    use std::vec::Vec;

    use super::*;
    use proptest::prelude::*;

    #[test]
    fn fills_then_wraps_overwriting_the_oldest() {
        let mut r = RingBuffer::<u32, 4>::new(0);
        assert!(r.is_empty());
        assert_eq!(r.capacity(), 4);
        for v in 1..=4 {
            assert_eq!(r.push(v), None);
        }
        assert!(r.is_full());
        assert_eq!(r.iter().collect::<Vec<_>>(), [1, 2, 3, 4]);
        assert_eq!(r.push(5), Some(1));
        assert_eq!(r.push(6), Some(2));
        assert_eq!(r.len(), 4);
        assert_eq!(r.iter().collect::<Vec<_>>(), [3, 4, 5, 6]);
        assert_eq!(r.get(0), Some(3));
        assert_eq!(r.get(3), Some(6));
        assert_eq!(r.get(4), None);
        assert_eq!(r.latest(), Some(6));
        let (a, b) = r.as_slices();
        assert_eq!((a, b), (&[3, 4][..], &[5, 6][..]));
    }

    #[test]
    fn make_contiguous_rotates_in_place_and_keeps_working() {
        let mut r = RingBuffer::<i16, 5>::new(0);
        for v in 0..12 {
            r.push(v);
        }
        assert_eq!(r.make_contiguous(), &[7, 8, 9, 10, 11]);
        assert_eq!(r.as_slices().1.len(), 0);
        r.push(12);
        assert_eq!(r.iter().collect::<Vec<_>>(), [8, 9, 10, 11, 12]);
        assert_eq!(r.make_contiguous(), &[8, 9, 10, 11, 12]);
    }

    #[test]
    fn try_push_refuses_when_full_and_clear_empties() {
        let mut r = RingBuffer::<u8, 2>::new(0);
        assert_eq!(r.try_push(1), Ok(()));
        assert_eq!(r.try_push(2), Ok(()));
        assert_eq!(r.try_push(3), Err(3));
        assert_eq!(r.iter().collect::<Vec<_>>(), [1, 2]);
        r.clear();
        assert!(r.is_empty());
        assert_eq!(r.latest(), None);
        assert_eq!(r.make_contiguous(), &[] as &[u8]);
    }

    #[test]
    fn zero_capacity_never_panics() {
        let mut r = RingBuffer::<u8, 0>::new(0);
        assert_eq!(r.push(7), Some(7));
        assert_eq!(r.try_push(7), Err(7));
        assert_eq!(r.len(), 0);
        assert_eq!(r.get(0), None);
        assert_eq!(r.make_contiguous(), &[] as &[u8]);
        assert_eq!(r.copy_to(&mut [0u8; 3]), 0);
    }

    #[test]
    fn copy_to_is_bounded_by_the_output() {
        let mut r = RingBuffer::<u8, 4>::new(0);
        for v in 0..6 {
            r.push(v);
        }
        let mut small = [0u8; 3];
        assert_eq!(r.copy_to(&mut small), 3);
        assert_eq!(small, [2, 3, 4]);
        let mut big = [9u8; 6];
        assert_eq!(r.copy_to(&mut big), 4);
        assert_eq!(big, [2, 3, 4, 5, 9, 9]);
    }

    proptest! {
        /// Against `VecDeque` as the model: same contents after any push sequence,
        /// with occasional `make_contiguous` and `clear`.
        #[test]
        fn behaves_like_a_bounded_deque(ops in proptest::collection::vec(0u16..1000, 0..200)) {
            let mut ring = RingBuffer::<u16, 7>::new(0);
            let mut model = VecDeque::new();
            for op in ops {
                match op % 50 {
                    0 => {
                        ring.clear();
                        model.clear();
                    }
                    1 => {
                        let got: Vec<u16> = ring.make_contiguous().to_vec();
                        prop_assert_eq!(got, model.iter().copied().collect::<Vec<_>>());
                    }
                    _ => {
                        let evicted = ring.push(op);
                        model.push_back(op);
                        let expected = if model.len() > 7 { model.pop_front() } else { None };
                        prop_assert_eq!(evicted, expected);
                    }
                }
                prop_assert_eq!(ring.len(), model.len());
                prop_assert_eq!(ring.iter().collect::<Vec<_>>(), model.iter().copied().collect::<Vec<_>>());
                prop_assert_eq!(ring.latest(), model.back().copied());
            }
        }
    }
}
