//! Indices of pixels, regions and runs: `u32` when an image allows it, else `u64`.

/// An index of a pixel, a region or a run: `u32` when the image allows it (half the
/// memory), else `u64`.
pub(crate) trait Index: Copy + Eq {
    /// Index 0.
    const ZERO: Self;
    /// `i` as an index (`i` must fit).
    fn new(i: usize) -> Self;
    /// The index as a `usize`.
    fn get(self) -> usize;
}

impl Index for u32 {
    const ZERO: u32 = 0;
    #[inline]
    fn new(i: usize) -> u32 {
        i as u32
    }
    #[inline]
    fn get(self) -> usize {
        self as usize
    }
}

impl Index for u64 {
    const ZERO: u64 = 0;
    #[inline]
    fn new(i: usize) -> u64 {
        i as u64
    }
    #[inline]
    fn get(self) -> usize {
        self as usize
    }
}
