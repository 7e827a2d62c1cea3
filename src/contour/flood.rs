//! The bit-parallel span flood fill that marks each component (8-connected foreground,
//! 4-connected background) and says whether it touches the image border.
//!
//! Hand-written rather than taken from a crate: it works on the mask's bit rows, 64 pixels
//! per step, which a generic flood fill over a pixel accessor cannot.

use super::fg;
use crate::bitmap::Mask;
use crate::pixel::Pixel;

/// A "visited" bit per pixel.
pub(super) struct Visited(pub(super) Mask);

/// The low `k` bits set (`1 ≤ k ≤ 64`).
#[inline]
pub(super) fn low_bits(k: usize) -> u64 {
    if k >= 64 {
        u64::MAX
    } else {
        (1u64 << k) - 1
    }
}

/// The pixels a flood of value `value` may still enter, 64 at a time: bit `k` of
/// `same(i)` is set iff pixel `i + k` (row-major) has the value and is not visited.
struct Unvisited<'a> {
    mask: &'a Mask,
    visited: &'a Mask,
    value: bool,
}

impl Unvisited<'_> {
    #[inline]
    fn same(&self, i: usize) -> u64 {
        let m = self.mask.bits_at(i);
        let m = if self.value { m } else { !m };
        m & !self.visited.bits_at(i)
    }

    /// The first `x` of the run of `same` pixels of row `row` (starting at row-major index
    /// `base`) that ends at `x0` (itself `same`).
    fn run_start(&self, base: usize, x0: usize) -> usize {
        let mut left = x0;
        while left > 0 {
            let k = left.min(64);
            // Bit 63 of `w` is pixel left − 1, bit 64 − k pixel left − k.
            let w = self.same(base + left - k) << (64 - k);
            let ones = (w.leading_ones() as usize).min(k);
            left -= ones;
            if ones < k {
                break;
            }
        }
        left
    }

    /// The last `x` of the run of `same` pixels starting at `x0` in a row of width `w`.
    fn run_end(&self, base: usize, x0: usize, w: usize) -> usize {
        let mut right = x0;
        while right + 1 < w {
            let k = (w - 1 - right).min(64);
            let bits = self.same(base + right + 1) & low_bits(k);
            let ones = (bits.trailing_ones() as usize).min(k);
            right += ones;
            if ones < k {
                break;
            }
        }
        right
    }
}

/// Marks the component of `start` (8-connected if foreground, 4-connected otherwise) as
/// visited; returns true when it touches the image border.
///
/// Span filling: each stack entry is a seed pixel; its whole horizontal run of unvisited
/// pixels of the same value is marked at once, and the rows above and below are scanned over
/// the run (widened by one pixel on each side for 8-connectivity) for new seeds, one per
/// run. Runs are found and marked 64 pixels at a time on the bit rows of the mask.
pub(super) fn flood(
    mask: &Mask,
    visited: &mut Visited,
    start: Pixel,
    stack: &mut Vec<Pixel>,
) -> bool {
    let value = fg(mask, start);
    let (w, h) = (mask.width() as usize, mask.height() as usize);
    let reach = usize::from(value); // 8-connected foreground reaches diagonally
    let mut touches = false;
    stack.clear();
    stack.push(start);
    while let Some(p) = stack.pop() {
        let (x, y) = (p.x as usize, p.y as usize);
        let base = y * w;
        let u = Unvisited {
            mask,
            visited: &visited.0,
            value,
        };
        if u.same(base + x) & 1 == 0 {
            continue;
        }
        let left = u.run_start(base, x);
        let right = u.run_end(base, x, w);
        visited.0.set_range(base + left, base + right);
        if y == 0 || y == h - 1 || left == 0 || right == w - 1 {
            touches = true;
        }
        let u = Unvisited {
            mask,
            visited: &visited.0,
            value,
        };
        for ny in [y.wrapping_sub(1), y + 1] {
            if ny >= h {
                continue; // also y − 1 below row 0 (wrapped)
            }
            let nbase = ny * w;
            let (from, to) = (left.saturating_sub(reach), (right + reach).min(w - 1));
            // One seed per run: the set bits of `same` whose left neighbour (within the
            // scanned span) is not set.
            let mut prev = 0u64;
            let mut xx = from;
            while xx <= to {
                let k = (to - xx + 1).min(64);
                let bits = u.same(nbase + xx) & low_bits(k);
                let mut starts = bits & !((bits << 1) | prev);
                while starts != 0 {
                    let j = starts.trailing_zeros() as usize;
                    stack.push(Pixel::new((xx + j) as i32, ny as i32));
                    starts &= starts - 1;
                }
                prev = (bits >> (k - 1)) & 1;
                xx += k;
            }
        }
    }
    touches
}
