//! The components of a mask (8-connected foreground, 4-connected background) found from its
//! rows' runs joined by a union–find: where each starts in raster order, and which
//! background ones are holes.
//!
//! A flood fill visits every pixel of every component (it was 6 instructions a pixel of the
//! 3000² sample, all before any parallel work); the runs are read from the mask's bit rows
//! 64 pixels at a time, and the work after that is linear in their number.

use crate::bitmap::{Index, Mask};
use crate::pixel::Pixel;

/// A component's first pixel in raster order (smallest `y`, then smallest `x`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Start {
    /// The first pixel.
    pub(super) at: Pixel,
    /// True for a hole (a background component that does not touch the image border),
    /// false for a foreground component.
    pub(super) hole: bool,
}

/// Every foreground component and every hole of `mask`, in raster order of their first
/// pixels (background components touching the border are left out).
///
/// Takes 9 bytes a run (at most one a pixel) while it runs, with `u32` indices (`u64`
/// ones, 13 bytes a run, for images of `u32::MAX` pixels or more), and 12 a start.
pub(super) fn component_starts(mask: &Mask) -> Vec<Start> {
    let pixels = u64::from(mask.width()) * u64::from(mask.height());
    if pixels < u64::from(u32::MAX) {
        starts_with::<u32>(mask)
    } else {
        starts_with::<u64>(mask)
    }
}

/// [`component_starts`] with run indices of type `L` (every run index must fit).
fn starts_with<L: Index>(mask: &Mask) -> Vec<Start> {
    let runs = Runs::<L>::of(mask);
    let n = runs.start.len();
    let mut parent: Vec<L> = (0..n).map(L::new).collect();
    for y in 1..runs.rows() {
        join_rows(&runs, y, &mut parent);
    }
    // Whether each component (at its root) touches the border.
    let h = mask.height() as usize;
    let mut touches = vec![false; n];
    for y in 0..runs.rows() {
        let edge_row = y == 0 || y + 1 == h;
        for i in runs.row[y].get()..runs.row[y + 1].get() {
            let (x0, x1) = runs.span(i, y);
            if edge_row || x0 == 0 || x1 + 1 == runs.width {
                touches[find(&mut parent, i)] = true;
            }
        }
    }
    let mut starts = Vec::new();
    for y in 0..runs.rows() {
        for i in runs.row[y].get()..runs.row[y + 1].get() {
            // The root of a component is its run of least index: its first in raster order.
            if parent[i].get() != i {
                continue;
            }
            let value = runs.value(i);
            if value || !touches[i] {
                let x = runs.start[i] & !VALUE;
                starts.push(Start {
                    at: Pixel::new(x as i32, y as i32),
                    hole: !value,
                });
            }
        }
    }
    starts
}

/// The high bit of a run's start: set for a run of foreground.
const VALUE: u32 = 1 << 31;

/// The maximal runs of equal pixels of every row, in raster order.
struct Runs<L> {
    /// Each run's first `x`, [`VALUE`] set for foreground (widths stay below 2³¹).
    start: Vec<u32>,
    /// The index of the first run of each row, and the number of runs last.
    row: Vec<L>,
    /// The mask's width.
    width: u32,
}

impl<L: Index> Runs<L> {
    /// The runs of `mask`, found 64 pixels at a time: a run starts where a pixel differs
    /// from its left neighbour.
    fn of(mask: &Mask) -> Runs<L> {
        let (w, h) = (mask.width() as usize, mask.height() as usize);
        let mut start = Vec::new();
        let mut row = Vec::with_capacity(h + 1);
        for y in 0..h {
            row.push(L::new(start.len()));
            let base = y * w;
            let mut left = 0u64; // the pixel left of the word, in bit 0
            let mut x = 0;
            while x < w {
                let k = (w - x).min(64);
                let bits = mask.bits_at(base + x) & low_bits(k);
                let mut changes = (bits ^ ((bits << 1) | left)) & low_bits(k);
                if x == 0 {
                    changes |= 1;
                }
                while changes != 0 {
                    let j = changes.trailing_zeros() as usize;
                    let value = if (bits >> j) & 1 == 1 { VALUE } else { 0 };
                    start.push((x + j) as u32 | value);
                    changes &= changes - 1;
                }
                left = (bits >> (k - 1)) & 1;
                x += k;
            }
        }
        row.push(L::new(start.len()));
        Runs {
            start,
            row,
            width: w as u32,
        }
    }

    /// The number of rows.
    fn rows(&self) -> usize {
        self.row.len() - 1
    }

    /// True when run `i` is of foreground.
    #[inline]
    fn value(&self, i: usize) -> bool {
        self.start[i] & VALUE != 0
    }

    /// The first and last `x` of run `i` of row `y`.
    #[inline]
    fn span(&self, i: usize, y: usize) -> (u32, u32) {
        let x0 = self.start[i] & !VALUE;
        let x1 = if i + 1 < self.row[y + 1].get() {
            (self.start[i + 1] & !VALUE) - 1
        } else {
            self.width - 1
        };
        (x0, x1)
    }
}

/// The low `k` bits set (`1 ≤ k ≤ 64`).
#[inline]
fn low_bits(k: usize) -> u64 {
    if k >= 64 {
        u64::MAX
    } else {
        (1u64 << k) - 1
    }
}

/// Joins each run of row `y` with the runs of the same value of row `y − 1` it touches:
/// sharing a column, or (foreground only) a corner.
fn join_rows<L: Index>(runs: &Runs<L>, y: usize, parent: &mut [L]) {
    let (mut i, end_above) = (runs.row[y - 1].get(), runs.row[y].get());
    for j in runs.row[y].get()..runs.row[y + 1].get() {
        let (b0, b1) = runs.span(j, y);
        let value = runs.value(j);
        // The columns of row y − 1 that touch the run.
        let (lo, hi) = if value {
            (b0.saturating_sub(1), b1 + 1)
        } else {
            (b0, b1)
        };
        while i < end_above && runs.span(i, y - 1).1 < lo {
            i += 1;
        }
        let mut k = i;
        while k < end_above && runs.start[k] & !VALUE <= hi {
            if runs.value(k) == value {
                union(parent, k, j);
            }
            k += 1;
        }
    }
}

/// The root of `i`'s set, halving the path on the way.
#[inline]
fn find<L: Index>(parent: &mut [L], mut i: usize) -> usize {
    while parent[i].get() != i {
        let grand = parent[parent[i].get()];
        parent[i] = grand;
        i = grand.get();
    }
    i
}

/// Joins the sets of `a` and `b`: the root of least index becomes the root of both, so a
/// set's root is always its least index.
#[inline]
fn union<L: Index>(parent: &mut [L], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra < rb {
        parent[rb] = L::new(ra);
    } else if rb < ra {
        parent[ra] = L::new(rb);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::random_mask;
    use proptest::prelude::*;

    proptest! {
        /// The `u64` indices of images of `u32::MAX` pixels or more give the starts of the
        /// `u32` ones (which the contour tests check against an independent labelling).
        #[test]
        fn wide_indices_give_the_same_starts(
            w in 1u32..150,
            h in 1u32..12,
            density in 0u64..=100,
            seed in any::<u64>(),
        ) {
            let mask = random_mask(w, h, seed, density);
            prop_assert_eq!(starts_with::<u64>(&mask), starts_with::<u32>(&mask));
        }
    }
}
