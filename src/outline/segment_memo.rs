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
//! bit. As in the greedy's memo (`decompose::greedy_memo`), no key is a prefix of another,
//! so the steps are looked up one at a time and the first hit is the answer.

use crate::pixel::Pixel;
use crate::recognize::MarginDirection;
use std::cell::RefCell;

/// Most steps of a remembered segment (3 bits each in a `u64` key, with the count and the
/// end flag): segments of up to 16 points.
const MAX_STEPS: usize = 19;

/// Bit of the key where the number of steps starts.
const COUNT_SHIFT: u32 = 3 * MAX_STEPS as u32;

/// Bit of the key that marks a segment that reached the end of its stretch.
const END_BIT: u64 = 1 << (COUNT_SHIFT + 5);

/// Segments kept on one thread before the memo starts again: bounds its memory (a few MB).
const MAX_ENTRIES: usize = 1 << 16;

/// A segment's line: its direction and level relative to its first point, and the line's
/// clearance from the segment's side pixels.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct SegmentLine {
    /// The largest-margin direction and level (see [`MarginDirection`]).
    pub margin: MarginDirection,
    /// Smallest first-order distance (px) from the line to the side pixels' centres.
    pub clearance: f64,
}

/// A segment found in (or given to) the memo.
#[derive(Clone, Debug, PartialEq)]
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
    static MEMO: RefCell<rustc_hash::FxHashMap<u64, Grown>> =
        RefCell::new(rustc_hash::FxHashMap::default());
}

/// The 3-bit code of the step from `a` to `b`; `None` unless they are 8-neighbours.
fn step(a: Pixel, b: Pixel) -> Option<u64> {
    let code = match (
        i64::from(b.x) - i64::from(a.x),
        i64::from(b.y) - i64::from(a.y),
    ) {
        (1, 0) => 0,
        (1, 1) => 1,
        (0, 1) => 2,
        (-1, 1) => 3,
        (-1, 0) => 4,
        (-1, -1) => 5,
        (0, -1) => 6,
        (1, -1) => 7,
        _ => return None,
    };
    Some(code)
}

/// The point `t` places after `p_{i−1}` on the closed contour `points`.
fn after_previous(points: &[Pixel], i: usize, t: usize) -> Pixel {
    let n = points.len();
    points[(i + n - 1 + t) % n]
}

/// The segment of `points` from `i` within the stretch ending at `last`, if remembered.
pub(super) fn find(points: &[Pixel], i: usize, last: usize) -> Option<Segment> {
    // Steps to `p_{last+1}`: `last − i + 2`.
    let most = (last + 2 - i).min(MAX_STEPS);
    MEMO.with(|memo| {
        let memo = memo.borrow();
        if memo.is_empty() {
            return None;
        }
        let mut k = 0u64;
        for m in 1..=most {
            let s = step(
                after_previous(points, i, m - 1),
                after_previous(points, i, m),
            )?;
            k |= s << (3 * (m - 1));
            let counted = k | (m as u64) << COUNT_SHIFT;
            let hit = memo.get(&counted).or_else(|| {
                (m == last + 2 - i)
                    .then(|| memo.get(&(counted | END_BIT)))
                    .flatten()
            });
            if let Some(g) = hit {
                return Some(Segment {
                    last: i + usize::from(g.extra),
                    line: g.line.clone(),
                });
            }
        }
        None
    })
}

/// Remembers `segment`, grown from `i` within the stretch ending at `last`, when it is short
/// enough: `failed_at` the point that broke the separation (`i` itself for a one-point
/// segment, else the one after its last), `None` when its growth ended at `last`.
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
    let mut k = 0u64;
    for t in 1..=m {
        let Some(s) = step(
            after_previous(points, i, t - 1),
            after_previous(points, i, t),
        ) else {
            return;
        };
        k |= s << (3 * (t - 1));
    }
    k |= (m as u64) << COUNT_SHIFT;
    if failed_at.is_none() {
        k |= END_BIT;
    }
    MEMO.with(|memo| {
        let mut memo = memo.borrow_mut();
        if memo.len() >= MAX_ENTRIES {
            memo.clear();
        }
        memo.insert(
            k,
            Grown {
                extra: (segment.last - i) as u8,
                line: segment.line.clone(),
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
        /// same contour elsewhere filled the memo, are the same (lines and all).
        #[test]
        fn remembered_segments_are_the_segments(
            bits in prop::collection::vec(any::<bool>(), 16 * 16),
            shift in (1i32..500, 1i32..500),
            cut in 0usize..8,
        ) {
            let mask = Mask::from_fn(16, 16, |x, y| bits[(y * 16 + x) as usize]);
            for c in trace(&mask, Convention::Default) {
                let points = &c.points;
                let n = points.len();
                // A stretch that ends early too (its end flag).
                let last = n - 1 - cut.min(n - 1);
                clear();
                let fresh = drawn(points, 0, last);
                clear();
                let moved: Vec<Pixel> =
                    points.iter().map(|p| Pixel::new(p.x + shift.0, p.y + shift.1)).collect();
                drawn(&moved, 0, last);
                let remembered = drawn(points, 0, last);
                prop_assert_eq!(fresh, remembered);
            }
        }
    }
}
