//! The exact polygon's short straight segments remembered by the steps that decided them:
//! noise and halftones grow the same few segments (a pixel or two) tens of thousands of
//! times.
//!
//! [`Stretcher::polygon`](super::stretch::Stretcher::polygon) grows a segment from point `i`
//! adding points while the exact separation of its sides holds; what point `k` adds are the
//! pixels beside it, from `p_{k−1}`, `p_k` and `p_{k+1}`. So a segment that failed at point
//! `f` was decided by the points `p_{i−1} … p_{f+1}` alone, and one that reached the end of
//! the stretch `last` by `p_{i−1} … p_{last+1}` and the fact that it ends there; its
//! largest-margin line and that line's clearance are computed relative to `p_i`, from the
//! same relative pixels. A memo keyed by those steps (3 bits each: the contour is
//! 8-connected; the end flag) returns the segment's last point, line and clearance bit for
//! bit. As in the greedy's memo (`decompose::greedy_memo`), the steps are looked up one at a
//! time and the first hit is the answer: a stored failure ends every segment that starts
//! with its steps, and one that reached its stretch's end is only looked up where the
//! stretch ends at the same step.

use crate::pixel::Pixel;
use crate::steps::{key, key_of, step, StepMap, MAX_STEPS};
use std::cell::RefCell;

/// Segments kept on one thread before the memo starts again: bounds its memory (a few MB).
const MAX_ENTRIES: usize = 1 << 16;

/// A segment's line: its direction and level relative to its first point (see
/// [`MarginDirection`](crate::recognize::MarginDirection): the line basis has two
/// coefficients), and the line's clearance from the segment's side pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct SegmentLine {
    /// The largest-margin direction.
    pub direction: [f64; 2],
    /// The level half-way between the two sides.
    pub level: f64,
    /// Smallest first-order distance (px) from the line to the side pixels' centres.
    pub clearance: f64,
}

/// A segment found in (or given to) the memo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Segment {
    /// Index of its last point.
    pub last: usize,
    /// Its line, `None` when its sides have none.
    pub line: Option<SegmentLine>,
}

/// A remembered segment: its length after its first point, and its line.
struct Grown {
    extra: u8,
    line: Option<SegmentLine>,
}

thread_local! {
    /// The segments grown on this thread, by the steps that decided them.
    static MEMO: RefCell<StepMap<Grown>> = RefCell::new(StepMap::new(MAX_ENTRIES));
}

/// The point `t ≤ n + 1` places after `p_{i−1}` (`i < n`) on the closed contour `points`.
fn after_previous(points: &[Pixel], i: usize, t: usize) -> Pixel {
    let n = points.len();
    let k = i + t + n - 1;
    points[if k >= 2 * n {
        k - 2 * n
    } else if k >= n {
        k - n
    } else {
        k
    }]
}

/// The segment of `points` from `i` within the stretch ending at `last`, if remembered.
pub(super) fn find(points: &[Pixel], i: usize, last: usize) -> Option<Segment> {
    MEMO.with(|memo| {
        let memo = memo.borrow();
        // Steps to `p_{last+1}`: `last − i + 2`; none longer than the memo's longest.
        let most = (last + 2 - i).min(memo.longest());
        let mut bits = 0u64;
        let mut prev = after_previous(points, i, 0);
        for m in 1..=most {
            let p = after_previous(points, i, m);
            bits |= step(prev, p)? << (3 * (m - 1));
            prev = p;
            let hit = memo.get(key(bits, m, false)).or_else(|| {
                (m == last + 2 - i)
                    .then(|| memo.get(key(bits, m, true)))
                    .flatten()
            });
            if let Some(g) = hit {
                return Some(Segment {
                    last: i + usize::from(g.extra),
                    line: g.line,
                });
            }
        }
        None
    })
}

/// Remembers `segment`, grown from `i` within the stretch ending at `last`, when it is short
/// enough: `failed_at` the point that broke the separation (the one after its last, or `i`
/// itself when even that point alone broke it), `None` when its growth ended at `last`.
pub(super) fn keep(
    points: &[Pixel],
    i: usize,
    last: usize,
    segment: &Segment,
    failed_at: Option<usize>,
) {
    // The steps from `p_{i−1}` to the point after the one that decided.
    let m = match failed_at {
        Some(f) => f + 2 - i,
        None => last + 2 - i,
    };
    if m > MAX_STEPS {
        return;
    }
    let run = (0..=m).map(|t| after_previous(points, i, t));
    let Some(k) = key_of(run, failed_at.is_none()) else {
        return;
    };
    MEMO.with(|memo| {
        memo.borrow_mut().insert(
            k,
            Grown {
                extra: (segment.last - i) as u8,
                line: segment.line,
            },
        );
    });
}

/// Forgets every segment of this thread (for tests that compare with fresh growth).
#[cfg(test)]
pub(super) fn clear() {
    MEMO.with(|memo| memo.borrow_mut().clear());
}

#[cfg(test)]
mod tests {
    use super::super::stretch::Stretcher;
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use proptest::prelude::*;

    /// The fields of a polygon's stretches that drawing uses.
    fn drawn(points: &[Pixel], first: usize, last: usize) -> Vec<String> {
        Stretcher::new(points, 0.5)
            .polygon(first, last)
            .iter()
            .map(|s| {
                format!(
                    "{} {} {:?} {:?} {}",
                    s.first, s.last, s.drawing, s.poly, s.tolerance
                )
            })
            .collect()
    }

    proptest! {
        /// Random noise: each contour's polygon grown afresh, and grown again after the
        /// same contour elsewhere filled the memo, are the same (lines and all), for
        /// stretches of the contour starting and ending anywhere.
        #[test]
        fn remembered_segments_are_the_segments(
            bits in prop::collection::vec(any::<bool>(), 16 * 16),
            shift in (1i32..500, 1i32..500),
            cut in 0usize..8,
            start in 0usize..8,
        ) {
            let mask = Mask::from_fn(16, 16, |x, y| bits[(y * 16 + x) as usize]);
            for c in trace(&mask, Convention::Default) {
                let points = &c.points;
                let n = points.len();
                // A stretch that ends early (its end flag) or starts late (the point
                // before it inside the contour) too.
                let last = n - 1 - cut.min(n - 1);
                let first = start.min(last);
                clear();
                let fresh = drawn(points, first, last);
                clear();
                let moved: Vec<Pixel> =
                    points.iter().map(|p| Pixel::new(p.x + shift.0, p.y + shift.1)).collect();
                drawn(&moved, first, last);
                let remembered = drawn(points, first, last);
                prop_assert_eq!(fresh, remembered);
            }
        }
    }
}
