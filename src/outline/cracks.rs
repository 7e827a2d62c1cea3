//! Pixel cracks: the sides a contour pixel shares with the background beside it, the exact
//! drawing of pieces without a usable curve.

use crate::decompose::Piece;
use crate::pixel::Pixel;
use kurbo::Point;
use rustc_hash::FxHashMap as HashMap;
use std::cell::OnceCell;

/// The centre of a pixel in SVG space.
pub(crate) fn centre(p: Pixel) -> Point {
    Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5)
}

/// The side of pixel `p` facing the 4-direction `d` (0 right, 2 down, 4 left, 6 up),
/// traversed with the pixel on its left (counter-clockwise on screen).
fn side(p: Pixel, d: u8) -> [Point; 2] {
    let (x, y) = (f64::from(p.x), f64::from(p.y));
    match d {
        0 => [Point::new(x + 1.0, y + 1.0), Point::new(x + 1.0, y)],
        6 => [Point::new(x + 1.0, y), Point::new(x, y)],
        4 => [Point::new(x, y), Point::new(x, y + 1.0)],
        _ => [Point::new(x, y + 1.0), Point::new(x + 1.0, y + 1.0)],
    }
}

/// The 8-directions from `cur` between `prev` and `next`, in the order [`crack_corners`]
/// goes round (see there), in the first `count` entries: the even ones (0 right, 2 down,
/// 4 left, 6 up) are the sides it draws.
// (Inlined: it runs for every pixel of every crack polyline.)
#[inline(always)]
fn crack_sides(prev: Option<Pixel>, cur: Pixel, next: Option<Pixel>) -> ([u8; 8], usize) {
    // At most 7 directions (no allocation: this runs for every pixel of every junction).
    let mut dirs = [0u8; 8];
    let count = match (
        prev.and_then(|p| cur.direction_to(p)),
        next.and_then(|q| cur.direction_to(q)),
    ) {
        (Some(a), Some(b)) => {
            let span = match (a + 8 - b) % 8 {
                0 => 8,
                s => s,
            };
            for k in 1..span {
                dirs[usize::from(k - 1)] = (a + 8 - k) % 8;
            }
            usize::from(span - 1)
        }
        _ => {
            dirs[..4].copy_from_slice(&[6, 4, 2, 0]);
            4
        }
    };
    (dirs, count)
}

/// The crack corners of `cur` between `prev` and `next`: its sides facing the 4-neighbours on
/// the right of the walk, counter-clockwise on screen from the side after `prev` to the side
/// before `next`. A U-turn (`prev == next`) gives every side but the one facing them; `None`
/// for `prev`/`next` (no neighbours: one-pixel contour) or non-adjacent input gives the whole
/// square.
fn crack_corners(prev: Option<Pixel>, cur: Pixel, next: Option<Pixel>, out: &mut Vec<Point>) {
    let (dirs, count) = crack_sides(prev, cur, next);
    for &d in dirs[..count].iter().filter(|&&d| d % 2 == 0) {
        for q in side(cur, d) {
            if out.last() != Some(&q) {
                out.push(q);
            }
        }
    }
}

/// The neighbours of pixel `i` along a closed contour of `points` (`None` for a one-pixel
/// contour).
fn neighbours(points: &[Pixel], i: usize) -> (Option<Pixel>, Option<Pixel>) {
    let n = points.len();
    if n == 1 {
        (None, None)
    } else {
        (Some(points[(i + n - 1) % n]), Some(points[(i + 1) % n]))
    }
}

/// Crack corners of the pixels `first..=last` of a closed contour.
pub(crate) fn crack_polyline(points: &[Pixel], first: usize, last: usize) -> Vec<Point> {
    let mut out = Vec::new();
    crack_polyline_into(points, first, last, &mut out);
    out
}

/// [`crack_polyline`] into `out`'s buffer (cleared first).
pub(crate) fn crack_polyline_into(
    points: &[Pixel],
    first: usize,
    last: usize,
    out: &mut Vec<Point>,
) {
    out.clear();
    let n = points.len();
    if n == 0 {
        return;
    }
    out.reserve(4 * (last.min(n - 1) + 1).saturating_sub(first) + 4);
    for i in first..=last.min(n - 1) {
        let (prev, next) = neighbours(points, i);
        crack_corners(prev, points[i], next, out);
    }
}

/// The first point of [`crack_polyline`]`(points, first, last)`, without building it: the
/// first corner of the first of those pixels that has a crack. `None` when none has.
pub(crate) fn first_crack_corner(points: &[Pixel], first: usize, last: usize) -> Option<Point> {
    let last = last.min(points.len().checked_sub(1)?);
    (first..=last).find_map(|i| {
        let (prev, next) = neighbours(points, i);
        let (dirs, count) = crack_sides(prev, points[i], next);
        let d = dirs[..count].iter().find(|&&d| d % 2 == 0)?;
        Some(side(points[i], *d)[0])
    })
}

/// The last point of [`crack_polyline`]`(points, first, last)`, without building it: the
/// last corner of the last of those pixels that has a crack (a corner the polyline drops as
/// a repeat equals the one before it). `None` when none has.
pub(crate) fn last_crack_corner(points: &[Pixel], first: usize, last: usize) -> Option<Point> {
    let last = last.min(points.len().checked_sub(1)?);
    (first..=last).rev().find_map(|i| {
        let (prev, next) = neighbours(points, i);
        let (dirs, count) = crack_sides(prev, points[i], next);
        let d = dirs[..count].iter().rev().find(|&&d| d % 2 == 0)?;
        Some(side(points[i], *d)[1])
    })
}

/// True when the pieces cover `0..n` consecutively.
pub(crate) fn pieces_valid(n: usize, pieces: &[Piece]) -> bool {
    let mut next = 0;
    for p in pieces {
        if p.first != next || p.last < p.first || p.last >= n {
            return false;
        }
        next = p.last + 1;
    }
    next == n && !pieces.is_empty()
}

/// A contour's crack polygon in unit steps, for the fit's target: the middles of its cracks
/// lie half-way between each pixel centre of the contour and the background centre beside
/// it, where a curve separating them has the most room.
pub(crate) struct Cracks {
    /// The corners, one unit step apart; the last steps back to the first.
    corners: Vec<Point>,
    /// The corners by integer point, built at the first [`Cracks::near`] (many contours
    /// have no run to fit).
    index: OnceCell<CornerIndex>,
}

/// The corners of a [`Cracks`] at each integer point, as chains through one array: no
/// vector per point (a contour's corners are mostly at different points).
struct CornerIndex {
    /// The first corner at each integer point.
    head: HashMap<(i64, i64), u32>,
    /// The next corner at the same point as each corner, in increasing order; [`END`] after
    /// the last.
    next: Vec<u32>,
}

/// The end of a chain of [`CornerIndex`].
const END: u32 = u32::MAX;

impl CornerIndex {
    /// The index of `corners`: chains in increasing order, built from the last corner back.
    fn new(corners: &[Point]) -> CornerIndex {
        let mut head: HashMap<(i64, i64), u32> =
            HashMap::with_capacity_and_hasher(corners.len(), Default::default());
        let mut next = vec![END; corners.len()];
        for (i, p) in corners.iter().enumerate().rev() {
            let key = (p.x.round() as i64, p.y.round() as i64);
            // (More corners than `u32` holds would not fit in memory as points.)
            if let Some(first) = head.insert(key, i as u32) {
                next[i] = first;
            }
        }
        CornerIndex { head, next }
    }

    /// The corners at the integer point `key`, in increasing order.
    fn at(&self, key: (i64, i64)) -> impl Iterator<Item = usize> + '_ {
        let first = self.head.get(&key).copied().unwrap_or(END);
        std::iter::successors((first != END).then_some(first), |&i| {
            let n = self.next[i as usize];
            (n != END).then_some(n)
        })
        .map(|i| i as usize)
    }
}

impl Cracks {
    /// The crack polygon through the corners `polyline` (closed; axis-aligned steps of
    /// whole pixels).
    pub(crate) fn new(polyline: &[Point]) -> Cracks {
        let mut corners: Vec<Point> = Vec::with_capacity(polyline.len() + 4);
        for w in polyline.windows(2) {
            let steps = (w[1] - w[0]).hypot().round().max(1.0) as usize;
            corners.extend((0..steps).map(|k| w[0].lerp(w[1], k as f64 / steps as f64)));
        }
        if let (Some(&last), Some(&first)) = (polyline.last(), polyline.first()) {
            if last != first {
                corners.push(last);
            }
        }
        Cracks {
            corners,
            index: OnceCell::new(),
        }
    }

    /// The corners within one pixel of `p`.
    pub(super) fn near(&self, p: Point) -> Vec<usize> {
        let index = self.index.get_or_init(|| CornerIndex::new(&self.corners));
        let (x, y) = (p.x.round() as i64, p.y.round() as i64);
        let mut out = Vec::new();
        for dy in -1..=1 {
            for dx in -1..=1 {
                out.extend(
                    index
                        .at((x + dx, y + dy))
                        .filter(|&i| (self.corners[i] - p).hypot() <= 1.0),
                );
            }
        }
        out
    }

    /// The middles of the cracks from a corner near `a` forward to one near `e`, between
    /// `a` and `e`: the shortest such stretch of at least two and at most `max_steps` cracks.
    /// Returns `None` if there is none.
    pub(super) fn between(&self, a: Point, e: Point, max_steps: usize) -> Option<Vec<Point>> {
        let m = self.corners.len();
        let (from, to) = (self.near(a), self.near(e));
        let (ia, steps) = from
            .iter()
            .flat_map(|&i| to.iter().map(move |&j| (i, (j + m - i) % m)))
            .filter(|&(_, d)| (2..=max_steps).contains(&d))
            .min_by_key(|&(_, d)| d)?;
        let mut pts = Vec::with_capacity(steps + 2);
        pts.push(a);
        // (Corner by corner round the polygon, without a division per crack.)
        let mut i = ia;
        for _ in 0..steps {
            let next = if i + 1 == m { 0 } else { i + 1 };
            pts.push(self.corners[i].midpoint(self.corners[next]));
            i = next;
        }
        pts.push(e);
        Some(pts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::random_mask;
    use crate::contour::{trace, Convention};

    #[test]
    fn end_corners_are_the_ends_of_the_polyline() {
        // Every range of every contour of noisy masks (one-pixel contours, U-turns, pixels
        // without a crack of their own) and of both conventions.
        let mut ranges = 0;
        for seed in 1..=6 {
            let mask = random_mask(24, 18, seed, 35 + 5 * seed);
            for convention in [Convention::Default, Convention::Ipol] {
                for c in trace(&mask, convention) {
                    let n = c.points.len();
                    for first in 0..n {
                        for last in first..n.min(first + 12) {
                            let poly = crack_polyline(&c.points, first, last);
                            assert_eq!(
                                first_crack_corner(&c.points, first, last),
                                poly.first().copied()
                            );
                            assert_eq!(
                                last_crack_corner(&c.points, first, last),
                                poly.last().copied()
                            );
                            let mut into = vec![Point::ZERO; 3];
                            crack_polyline_into(&c.points, first, last, &mut into);
                            assert_eq!(into, poly);
                            ranges += 1;
                        }
                    }
                }
            }
        }
        assert!(ranges > 5_000, "{ranges}");
        // Empty ranges and contours give none.
        assert_eq!(first_crack_corner(&[], 0, 0), None);
        assert_eq!(last_crack_corner(&[Pixel { x: 1, y: 1 }], 1, 0), None);
    }
}
