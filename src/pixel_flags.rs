//! Flags on the pixels of a small box: the pixel sets of one stretch of a contour without
//! hashing.

use crate::pixel::{Pixel, PixelSet};

/// A byte of flags for every pixel of a box around a stretch of contour (row-major): the
/// sets a stretch builds over its points and their 4-neighbours (its points, the outliers on
/// either side already listed) answer by an index instead of a hash.
pub(crate) struct PixelFlags {
    /// The box's top-left pixel (wrapping: offsets are taken modulo 2³²).
    x0: i32,
    y0: i32,
    w: usize,
    h: usize,
    /// The flags of a box of at most [`INLINE`] pixels (most stretches: no allocation).
    inline: [u8; INLINE],
    /// The flags of a larger box; empty otherwise.
    heap: Vec<u8>,
}

/// Most pixels of a box whose flags [`PixelFlags`] keeps in itself.
const INLINE: usize = 128;

/// Most bytes per point [`PixelFlags::around`] gives a box: a stretch along a diagonal has a
/// box that grows as the square of its length, and beyond this a hash set costs less.
const BYTES_PER_POINT: usize = 64;

/// The box every stretch may have, however short.
const MIN_BYTES: usize = 256;

impl PixelFlags {
    /// No flags, on the box of `points` grown by one pixel on every side (so that it holds
    /// their 4-neighbours). Returns `None` if `points` is empty or that box has more than
    /// [`BYTES_PER_POINT`] pixels per point (and more than [`MIN_BYTES`]).
    pub(crate) fn around(points: &[Pixel]) -> Option<PixelFlags> {
        let first = points.first()?;
        let (mut x0, mut y0, mut x1, mut y1) = (first.x, first.y, first.x, first.y);
        for p in points {
            x0 = x0.min(p.x);
            y0 = y0.min(p.y);
            x1 = x1.max(p.x);
            y1 = y1.max(p.y);
        }
        let w = usize::try_from(i64::from(x1) - i64::from(x0) + 3).ok()?;
        let h = usize::try_from(i64::from(y1) - i64::from(y0) + 3).ok()?;
        let area = w.checked_mul(h)?;
        if area > (BYTES_PER_POINT.saturating_mul(points.len())).max(MIN_BYTES) {
            return None;
        }
        Some(PixelFlags {
            x0: x0.wrapping_sub(1),
            y0: y0.wrapping_sub(1),
            w,
            h,
            inline: [0; INLINE],
            heap: if area > INLINE {
                vec![0; area]
            } else {
                Vec::new()
            },
        })
    }

    /// The flags, row by row.
    fn flags(&self) -> &[u8] {
        if self.heap.is_empty() {
            &self.inline
        } else {
            &self.heap
        }
    }

    /// [`PixelFlags::flags`], to change.
    fn flags_mut(&mut self) -> &mut [u8] {
        if self.heap.is_empty() {
            &mut self.inline
        } else {
            &mut self.heap
        }
    }

    /// The place of `p`; `None` outside the box.
    fn index(&self, p: Pixel) -> Option<usize> {
        // (Left of or above the box, the wrapped offset is far beyond its size.)
        let dx = p.x.wrapping_sub(self.x0) as u32 as usize;
        let dy = p.y.wrapping_sub(self.y0) as u32 as usize;
        (dx < self.w && dy < self.h).then(|| dy * self.w + dx)
    }

    /// True when `p` has every bit of `flag` (a pixel outside the box has none).
    pub(crate) fn has(&self, p: Pixel, flag: u8) -> bool {
        self.index(p)
            .is_some_and(|i| self.flags()[i] & flag == flag)
    }

    /// Gives `p` the bits of `flag`; true when it did not have them all. A pixel outside
    /// the box keeps no flag and is always new (the callers only flag their points and
    /// the 4-neighbours of those).
    pub(crate) fn set(&mut self, p: Pixel, flag: u8) -> bool {
        debug_assert!(self.index(p).is_some(), "{p:?} outside the box");
        match self.index(p) {
            Some(i) => {
                let f = &mut self.flags_mut()[i];
                let new = *f & flag != flag;
                *f |= flag;
                new
            }
            None => true,
        }
    }
}

/// The sets a stretch of a closed contour builds over its points and their 4-neighbours:
/// its points, and the neighbours on its right and on its left listed so far. On flags
/// over the stretch's box where that box is small for the stretch, else hash sets.
pub(crate) enum StretchSets {
    /// Bits [`POINT`], [`RIGHT`], [`LEFT`] of each pixel of the box.
    Flags(PixelFlags),
    /// The points, the neighbours on the right, the neighbours on the left.
    Hashed(PixelSet, PixelSet, PixelSet),
}

/// The flags of [`StretchSets::Flags`].
const POINT: u8 = 1;
const RIGHT: u8 = 2;
const LEFT: u8 = 4;

impl StretchSets {
    /// The sets of the stretch `points`, no neighbour listed yet.
    pub(crate) fn of(points: &[Pixel]) -> StretchSets {
        match PixelFlags::around(points) {
            Some(mut flags) => {
                for &p in points {
                    flags.set(p, POINT);
                }
                StretchSets::Flags(flags)
            }
            None => {
                let with = |c: usize| PixelSet::with_capacity_and_hasher(c, Default::default());
                let mut own = with(points.len());
                own.extend(points.iter().copied());
                StretchSets::Hashed(own, with(points.len() + 4), with(points.len()))
            }
        }
    }

    /// True when `q` is one of the stretch's points.
    pub(crate) fn is_point(&self, q: Pixel) -> bool {
        match self {
            StretchSets::Flags(f) => f.has(q, POINT),
            StretchSets::Hashed(own, _, _) => own.contains(&q),
        }
    }

    /// Lists `q` (a point or a 4-neighbour of one) on the right; true if it was not yet.
    pub(crate) fn first_right(&mut self, q: Pixel) -> bool {
        match self {
            StretchSets::Flags(f) => f.set(q, RIGHT),
            StretchSets::Hashed(_, right, _) => right.insert(q),
        }
    }

    /// Lists `q` (a point or a 4-neighbour of one) on the left; true if it was not yet.
    pub(crate) fn first_left(&mut self, q: Pixel) -> bool {
        match self {
            StretchSets::Flags(f) => f.set(q, LEFT),
            StretchSets::Hashed(_, _, left) => left.insert(q),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Inside the box of the points and their 4-neighbours, one flag behaves as a hash
        /// set: `set` answers as `insert`, `has` as `contains`.
        #[test]
        fn a_flag_is_a_set(
            steps in prop::collection::vec(0u8..8, 1..60),
            start in (-1000i32..1000, -1000i32..1000),
            queries in prop::collection::vec((0usize..60, 0u8..5), 0..200),
        ) {
            // An 8-connected walk, as a stretch of contour.
            let mut points = vec![Pixel::new(start.0, start.1)];
            for d in steps {
                let p = *points.last().unwrap();
                let (dx, dy) = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)][d as usize];
                points.push(Pixel::new(p.x + dx, p.y + dy));
            }
            let span = |f: fn(&Pixel) -> i32| {
                let v = points.iter().map(f);
                (v.clone().max().unwrap() - v.min().unwrap() + 3) as usize
            };
            let area = span(|p| p.x) * span(|p| p.y);
            let Some(mut flags) = PixelFlags::around(&points) else {
                // Only boxes too large for their points are refused.
                prop_assert!(area > (BYTES_PER_POINT * points.len()).max(MIN_BYTES));
                return Ok(());
            };
            prop_assert!(area <= (BYTES_PER_POINT * points.len()).max(MIN_BYTES));
            let mut set = PixelSet::default();
            for (k, side) in queries {
                let p = points[k % points.len()];
                // The point itself or one of its 4-neighbours.
                let q = if side == 4 { p } else { p.neighbours4()[side as usize] };
                prop_assert_eq!(flags.has(q, 2), set.contains(&q));
                prop_assert_eq!(flags.set(q, 2), set.insert(q));
                prop_assert!(flags.has(q, 2));
                prop_assert!(!flags.has(q, 1));
            }
        }
    }

    #[test]
    fn a_long_diagonal_is_left_to_hashing() {
        let diagonal: Vec<Pixel> = (0..1000).map(|i| Pixel::new(i, i)).collect();
        assert!(PixelFlags::around(&diagonal).is_none());
        let row: Vec<Pixel> = (0..1000).map(|i| Pixel::new(i, 7)).collect();
        assert!(PixelFlags::around(&row).is_some());
        assert!(PixelFlags::around(&[]).is_none());
    }
}
