//! Shared vertices of consecutive straight segments of the exact polygon.
//!
//! Two digital straight segments drawn along their largest-margin lines often do not meet
//! near their junction: consecutive lines of a gently curving border are nearly parallel
//! and cross pixels away. Bridging the two line ends with a short segment costs a command
//! and draws a notch. Instead both segments may end at one shared vertex `V` off their
//! lines, as long as each segment, now from its start vertex to `V` (or from `V` to its end
//! vertex), still has its pixel centres and the foreground beside them strictly on one side
//! and the background beside them strictly on the other ([`separates`], exact for points
//! on the grid). Candidates, in order: half-way between the two line ends, the crossing of
//! the lines (up to 4 px away), the pixel corner between the two end pixels, either line
//! end. The render check has the last word.

use super::cracks::{centre, crack_polyline};
use crate::decompose::neighbour_sides;
use crate::pixel::{Pixel, PixelSet};
use kurbo::Point;

/// Largest distance (pixels) from the junction of the crossing of two segments' lines tried
/// as their shared vertex.
const MAX_CROSSING_DISTANCE: f64 = 4.0;

/// The centres a segment must separate: its pixels and the foreground beside them (`low`),
/// the background beside them (`high`).
pub(crate) struct Sides {
    low: Vec<Point>,
    high: Vec<Point>,
}

impl Sides {
    /// The sides of the points `first..=last` of a closed contour.
    pub(crate) fn of(points: &[Pixel], first: usize, last: usize) -> Sides {
        let (low, high) = side_pixels(points, first, last);
        Sides {
            low: low.into_iter().map(centre).collect(),
            high: high.into_iter().map(centre).collect(),
        }
    }
}

/// The pixels a drawing of the points `first..=last` of a closed contour must keep apart:
/// those points and the foreground beside them (`low`, first the points in order), and the
/// background beside every one of them, the two ends included (`high`), each once.
pub(crate) fn side_pixels(points: &[Pixel], first: usize, last: usize) -> (Vec<Pixel>, Vec<Pixel>) {
    let n = points.len();
    let len = last + 1 - first;
    let with = |c: usize| PixelSet::with_capacity_and_hasher(c, Default::default());
    let mut inliers = with(len);
    inliers.extend(points[first..=last].iter().copied());
    let (mut low, mut high) = (Vec::with_capacity(2 * len), Vec::with_capacity(len + 4));
    let (mut seen_up, mut seen_low) = (with(len + 4), with(len));
    for k in first..=last {
        low.push(points[k]);
        let (prev, next) = (points[(k + n - 1) % n], points[(k + 1) % n]);
        if let Some(sides) = neighbour_sides(prev, points[k], next) {
            for (q, right, left) in sides {
                if inliers.contains(&q) {
                    continue;
                }
                if right && seen_up.insert(q) {
                    high.push(q);
                }
                if left && !right && seen_low.insert(q) {
                    low.push(q);
                }
            }
        }
    }
    (low, high)
}

/// True when the segment `u → v` has every `low` centre strictly on one side of its line
/// and every `high` centre strictly on the other, counting only the centres whose
/// projection falls on the segment (the others are the neighbouring segments' to
/// separate). With grid points the signs are exact.
pub(crate) fn separates(u: Point, v: Point, sides: &Sides) -> bool {
    let d = v - u;
    let len2 = d.hypot2();
    if len2 == 0.0 {
        return false;
    }
    let on_span = |p: &Point| {
        let t = (*p - u).dot(d);
        (0.0..=len2).contains(&t)
    };
    let side = |p: &Point| d.cross(*p - u);
    // Along its row, a centre within 1/64 px of the line counts as on it.
    let clear = d.y.abs() / 64.0;
    let (mut low_sign, mut high_sign) = (0.0f64, 0.0f64);
    for p in sides.low.iter().filter(|p| on_span(p)) {
        let s = side(p);
        if s.abs() <= clear || s * low_sign < 0.0 {
            return false;
        }
        low_sign = s.signum();
    }
    for p in sides.high.iter().filter(|p| on_span(p)) {
        let s = side(p);
        if s.abs() <= clear || s * high_sign < 0.0 || s * low_sign > 0.0 {
            return false;
        }
        high_sign = s.signum();
    }
    true
}

/// The shared vertex of segment `j` (from `u`, its start vertex) and segment `k` (to `w`,
/// its end vertex) at their junction between contour points `a` (last of `j`) and `b`
/// (first of `k`), where `j` ends at `end_j` and `k` starts at `start_k` on their own lines;
/// `snap` puts candidates on the grid. `None` when no candidate keeps both separating.
#[allow(clippy::too_many_arguments)]
pub(crate) fn shared_vertex(
    points: &[Pixel],
    a: usize,
    b: usize,
    u: Point,
    end_j: Point,
    start_k: Point,
    w: Point,
    sides_j: &Sides,
    sides_k: &Sides,
    snap: impl Fn(Point) -> Point,
) -> Option<Point> {
    let corner = match (
        crack_polyline(points, a, a).last().copied(),
        crack_polyline(points, b, b).first().copied(),
    ) {
        (Some(p), Some(q)) => Some(p.midpoint(q)),
        _ => None,
    };
    // Where the two segments' lines cross, if not far beyond the junction.
    let crossing = {
        let (d1, d2) = (end_j - u, w - start_k);
        let den = d1.cross(d2);
        (den != 0.0)
            .then(|| {
                let t = (start_k - u).cross(d2) / den;
                u + d1 * t
            })
            .filter(|x| (*x - end_j.midpoint(start_k)).hypot() <= MAX_CROSSING_DISTANCE)
    };
    let candidates = [
        Some(end_j.midpoint(start_k)),
        crossing,
        corner,
        Some(end_j),
        Some(start_k),
    ];
    candidates
        .into_iter()
        .flatten()
        .map(snap)
        .find(|&v| separates(u, v, sides_j) && separates(v, w, sides_k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separation_counts_only_the_span() {
        let sides = Sides {
            low: vec![
                Point::new(0.5, 0.5),
                Point::new(1.5, 0.5),
                Point::new(9.5, 1.5),
            ],
            high: vec![Point::new(0.5, 1.5), Point::new(1.5, 1.5)],
        };
        // y = 1 from x = 0 to 2: low above, high below; (9.5, 1.5) is off the span.
        assert!(separates(
            Point::new(0.0, 1.0),
            Point::new(2.0, 1.0),
            &sides
        ));
        // Through a centre: not strict.
        assert!(!separates(
            Point::new(-0.5, 0.5),
            Point::new(2.5, 0.5),
            &sides
        ));
        // A vertical line 1/128 px right of a centre is too close (Chromium's tile cuts
        // move edges by about 1/64 px along the rows); 1/32 px is enough.
        let column = Sides {
            low: vec![Point::new(0.5, 1.5)],
            high: vec![Point::new(1.5, 2.5)],
        };
        let at = |x: f64| separates(Point::new(x, 0.0), Point::new(x, 4.0), &column);
        assert!(!at(0.5 + 1.0 / 128.0));
        assert!(at(0.5 + 1.0 / 32.0));
        // Tilted so that (1.5, 1.5) is above it.
        assert!(!separates(
            Point::new(0.0, 1.0),
            Point::new(2.0, 1.8),
            &sides
        ));
    }
}
