//! The binary foreground mask, one bit per pixel.

/// A binary image: each pixel is foreground (`true`) or background (`false`).
///
/// Pixels are stored as one bit each, row by row.
#[derive(Clone, PartialEq, Eq)]
pub struct Mask {
    width: u32,
    height: u32,
    bits: Vec<u64>,
}

impl std::fmt::Debug for Mask {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Mask {}x{}", self.width, self.height)?;
        if u64::from(self.width) * u64::from(self.height) <= 4096 {
            write!(f, "\n{}", self.to_ascii())?;
        }
        Ok(())
    }
}

impl Mask {
    /// An all-background mask of `width` × `height` pixels (allocates `width * height` bits).
    pub fn new(width: u32, height: u32) -> Mask {
        let n = u64::from(width) * u64::from(height);
        let words = usize::try_from(n.div_ceil(64)).unwrap_or(usize::MAX);
        Mask {
            width,
            height,
            bits: vec![0; words],
        }
    }

    /// An all-background mask, or `None` if its bits cannot be allocated (instead of aborting).
    pub(crate) fn try_new(width: u32, height: u32) -> Option<Mask> {
        let n = u64::from(width) * u64::from(height);
        let words = usize::try_from(n.div_ceil(64)).ok()?;
        let mut bits = Vec::new();
        bits.try_reserve_exact(words).ok()?;
        bits.resize(words, 0);
        Some(Mask {
            width,
            height,
            bits,
        })
    }

    /// Bytes taken by the bits of a `width` × `height` mask.
    pub(crate) fn bytes_for(width: u32, height: u32) -> u64 {
        (u64::from(width) * u64::from(height)).div_ceil(64) * 8
    }

    /// Sets the pixel of row-major index `i` to foreground (ignored past the last pixel).
    #[inline]
    pub(crate) fn set_index(&mut self, i: usize) {
        if let Some(w) = self.bits.get_mut(i / 64) {
            *w |= 1 << (i % 64);
        }
    }

    /// Sets to foreground the pixels of row-major indices `start + b` for the bits `b` set in
    /// `word`, as [`Mask::set_index`] sets them one by one: 64 pixels with two word updates.
    #[inline]
    pub(crate) fn set_word_at(&mut self, start: usize, word: u64) {
        let (q, r) = (start / 64, start % 64);
        if let Some(w) = self.bits.get_mut(q) {
            *w |= word << r;
        }
        if r != 0 {
            if let Some(w) = self.bits.get_mut(q + 1) {
                *w |= word >> (64 - r);
            }
        }
    }

    /// True iff the pixel of row-major index `i` is foreground (false past the last pixel).
    #[inline]
    pub(crate) fn get_index(&self, i: usize) -> bool {
        self.bits
            .get(i / 64)
            .is_some_and(|w| (w >> (i % 64)) & 1 == 1)
    }

    /// Swaps foreground and background at row-major index `i` (ignored past the last
    /// pixel).
    #[inline]
    pub(crate) fn flip_index(&mut self, i: usize) {
        if i < self.width as usize * self.height as usize {
            if let Some(w) = self.bits.get_mut(i / 64) {
                *w ^= 1 << (i % 64);
            }
        }
    }

    /// A mask whose pixel `(x, y)` is foreground iff `f(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> bool) -> Mask {
        let mut m = Mask::new(width, height);
        for y in 0..height {
            for x in 0..width {
                if f(x, y) {
                    m.set(i64::from(x), i64::from(y), true);
                }
            }
        }
        m
    }

    /// Builds a mask from ASCII art, for tests and examples.
    ///
    /// Each non-blank line is one row (leading and trailing whitespace is ignored, so indented
    /// raw strings work); `#`, `X`, `x`, `1` and `@` are foreground, any other character is
    /// background. The width is the longest row; shorter rows are padded with background.
    ///
    /// ```
    /// let m = layertrace::Mask::from_ascii("#..\n.##");
    /// assert_eq!((m.width(), m.height(), m.count_foreground()), (3, 2, 3));
    /// assert!(m.get(0, 0) && !m.get(1, 0) && m.get(2, 1));
    /// ```
    pub fn from_ascii(art: &str) -> Mask {
        let rows: Vec<Vec<char>> = art
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .map(|l| l.chars().collect())
            .collect();
        let width = rows.iter().map(Vec::len).max().unwrap_or(0);
        let width = u32::try_from(width).unwrap_or(u32::MAX);
        let height = u32::try_from(rows.len()).unwrap_or(u32::MAX);
        let mut m = Mask::new(width, height);
        for (y, row) in rows.iter().enumerate() {
            for (x, &c) in row.iter().enumerate() {
                if matches!(c, '#' | 'X' | 'x' | '1' | '@') {
                    m.set(x as i64, y as i64, true);
                }
            }
        }
        m
    }

    /// The mask as ASCII art (`#` foreground, `.` background, one line per row), the inverse
    /// of [`Mask::from_ascii`].
    pub fn to_ascii(&self) -> String {
        let mut s = String::new();
        for y in 0..i64::from(self.height) {
            for x in 0..i64::from(self.width) {
                s.push(if self.get(x, y) { '#' } else { '.' });
            }
            s.push('\n');
        }
        s
    }

    /// Width in pixels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    #[inline]
    fn index(&self, x: i64, y: i64) -> Option<usize> {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return None;
        }
        usize::try_from(y as u64 * u64::from(self.width) + x as u64).ok()
    }

    /// True iff `(x, y)` is inside the image and foreground; everything outside is background.
    #[inline]
    pub fn get(&self, x: i64, y: i64) -> bool {
        match self.index(x, y) {
            Some(i) => self
                .bits
                .get(i / 64)
                .is_some_and(|w| (w >> (i % 64)) & 1 == 1),
            None => false,
        }
    }

    /// Sets pixel `(x, y)` to foreground (`true`) or background; ignored outside the image.
    #[inline]
    pub fn set(&mut self, x: i64, y: i64, value: bool) {
        if let Some(i) = self.index(x, y) {
            if let Some(w) = self.bits.get_mut(i / 64) {
                if value {
                    *w |= 1 << (i % 64);
                } else {
                    *w &= !(1 << (i % 64));
                }
            }
        }
    }

    /// Number of foreground pixels.
    pub fn count_foreground(&self) -> u64 {
        // Bits past the last pixel are never set, so whole words can be counted.
        self.bits.iter().map(|w| u64::from(w.count_ones())).sum()
    }

    /// The 64 pixels from row-major index `i` on (bit `k` = pixel `i + k`), background past
    /// the last pixel.
    #[inline]
    pub(crate) fn bits_at(&self, i: usize) -> u64 {
        let (q, r) = (i / 64, i % 64);
        let lo = self.bits.get(q).copied().unwrap_or(0) >> r;
        if r == 0 {
            lo
        } else {
            lo | (self.bits.get(q + 1).copied().unwrap_or(0) << (64 - r))
        }
    }
}

/// A `w` × `h` test mask of noise: each pixel foreground with probability `density` %
/// (xorshift from `seed`), the same mask for the same arguments.
#[cfg(test)]
pub(crate) fn random_mask(w: u32, h: u32, seed: u64, density: u64) -> Mask {
    let mut s = seed | 1;
    Mask::from_fn(w, h, |_, _| {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s % 100 < density
    })
}

/// An 80 × 80 test mask: the 4 × 3 blob `bits` (row-major) at `(8, 8)` and again at a place
/// derived from each offset, the copies at least 2 pixels apart and 8 from the border (for
/// the tests of the per-shape memos of the decomposition and the outline, which draws
/// shapes near the border where they are).
#[cfg(test)]
pub(crate) fn repeated_blob(bits: &[bool], offsets: &[(u32, u32)]) -> Mask {
    let blob = |u: u32, v: u32| u < 4 && v < 3 && bits[(v * 4 + u) as usize];
    let mut origins = vec![(8u32, 8u32)];
    origins.extend(
        offsets
            .iter()
            .map(|&(x, y)| (8 + 6 * (x / 6 + 1), 8 + 5 * (y / 5))),
    );
    Mask::from_fn(80, 80, |x, y| {
        origins
            .iter()
            .any(|&(ox, oy)| x >= ox && y >= oy && blob(x - ox, y - oy))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// `set_word_at` sets the pixels of its word's bits, as `set_index` does one by one.
        #[test]
        fn words_set_the_pixels_of_their_bits(
            w in 1u32..150,
            h in 1u32..5,
            start in 0usize..800,
            word in any::<u64>(),
        ) {
            let (mut by_word, mut by_pixel) = (Mask::new(w, h), Mask::new(w, h));
            by_word.set_word_at(start, word);
            for b in 0..64 {
                if word >> b & 1 == 1 {
                    by_pixel.set_index(start + b);
                }
            }
            prop_assert_eq!(&by_word.bits, &by_pixel.bits);
        }

        /// `bits_at` and `count_foreground` agree with pixel-by-pixel `get` and `set`.
        #[test]
        fn word_access_matches_pixels(
            w in 1u32..150,
            h in 1u32..5,
            seed in any::<u64>(),
            a in 0usize..800,
        ) {
            let mut m = Mask::new(w, h);
            let mut s = seed | 1;
            for y in 0..i64::from(h) {
                for x in 0..i64::from(w) {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    m.set(x, y, s & 1 == 1);
                }
            }
            let n = (w * h) as usize;
            let pixel = |m: &Mask, i: usize| {
                i < n && m.get((i % w as usize) as i64, (i / w as usize) as i64)
            };
            let a = a % n;
            let word = m.bits_at(a);
            for k in 0..64 {
                prop_assert_eq!((word >> k) & 1 == 1, pixel(&m, a + k), "bit {} from {}", k, a);
            }
            prop_assert_eq!(m.count_foreground(), (0..n).filter(|&i| pixel(&m, i)).count() as u64);
        }
    }

    #[test]
    fn mask_basics() {
        let m = Mask::from_ascii(
            "
            #..
            .##
            ",
        );
        assert_eq!((m.width(), m.height()), (3, 2));
        assert_eq!(m.count_foreground(), 3);
        assert!(m.get(0, 0) && m.get(1, 1) && m.get(2, 1));
        assert!(!m.get(1, 0) && !m.get(-1, 0) && !m.get(0, -1) && !m.get(3, 1) && !m.get(0, 2));
        assert_eq!(Mask::from_ascii(&m.to_ascii()), m);
        let mut n = Mask::new(70, 3);
        n.set(69, 2, true);
        n.set(70, 2, true); // outside: ignored
        n.set(-1, 0, true);
        assert_eq!(n.count_foreground(), 1);
        n.set(69, 2, false);
        assert_eq!(n.count_foreground(), 0);
        let f = Mask::from_fn(5, 4, |x, y| (x + y) % 2 == 0);
        assert_eq!(f.count_foreground(), 10);
        assert!(f.get(4, 0) && !f.get(4, 1));
    }
}
