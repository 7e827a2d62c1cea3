//! Cutting a stretch out of closed outlines: the part of a region's drawn border between two
//! crack corners, for a border shared by two regions (`--layout partition`).
//!
//! A closed outline (see [`contour_path`](super::contour_path)) passes within about
//! `√2 / 2` px of each crack corner of its contour, between the pixel centres around it.
//! [`cut`] finds the points of the outlines nearest to the two corners, keeps the pair whose
//! stretch (walked forward, the region on its left) is as long as the border's cracks
//! suggest, and returns that stretch with a line from the first corner to it and from it to
//! the second corner, so that it begins and ends exactly at the corners. Nothing here
//! guarantees the stretch is right for the pixels: the caller renders and checks it.

use crate::curve::PathCommand;
use kurbo::{ParamCurve, ParamCurveArclen, ParamCurveNearest, PathEl, PathSeg, Point, Rect, Shape};

/// Farthest (pixels) an outline may pass from a corner to be cut there.
const NEAR: f64 = 0.8;

/// A stretch found so far: its score, its loop, its two ends `(segment, t)`.
type Found = (f64, usize, (usize, f64), (usize, f64));

/// Accuracy of arc lengths and nearest points.
const ACCURACY: f64 = 1e-4;

/// One closed outline as segments, with the arc length before each.
#[derive(Clone, Debug)]
pub(crate) struct Loop {
    segs: Vec<PathSeg>,
    /// `prefix[i]`: length of the segments before `i`; the last entry the total.
    prefix: Vec<f64>,
    bounds: Rect,
}

impl Loop {
    /// The closed outline `M start commands Z` (a closing line added when needed).
    pub(crate) fn new(start: Point, commands: &[PathCommand]) -> Loop {
        let mut segs = Vec::with_capacity(commands.len() + 1);
        let mut pen = start;
        for c in commands {
            for el in c.to_path_els(pen) {
                let seg = match el {
                    PathEl::LineTo(p) => PathSeg::Line(kurbo::Line::new(pen, p)),
                    PathEl::QuadTo(a, p) => PathSeg::Quad(kurbo::QuadBez::new(pen, a, p)),
                    PathEl::CurveTo(a, b, p) => PathSeg::Cubic(kurbo::CubicBez::new(pen, a, b, p)),
                    _ => continue,
                };
                pen = seg.end();
                segs.push(seg);
            }
        }
        if pen != start {
            segs.push(PathSeg::Line(kurbo::Line::new(pen, start)));
        }
        let mut prefix = Vec::with_capacity(segs.len() + 1);
        let mut total = 0.0;
        let mut bounds = Rect::from_points(start, start);
        for s in &segs {
            prefix.push(total);
            total += s.arclen(ACCURACY);
            bounds = bounds.union(s.bounding_box());
        }
        prefix.push(total);
        Loop {
            segs,
            prefix,
            bounds,
        }
    }

    fn total(&self) -> f64 {
        *self.prefix.last().unwrap_or(&0.0)
    }

    /// Arc length from the start to `(segment, t)`.
    fn position(&self, i: usize, t: f64) -> f64 {
        self.prefix[i] + self.segs[i].subsegment(0.0..t).arclen(ACCURACY)
    }

    /// The points `(segment, t, distance)` of the outline within [`NEAR`] of `p`, the
    /// nearest of each segment.
    fn near(&self, p: Point) -> Vec<(usize, f64, f64)> {
        if !self.bounds.inflate(NEAR, NEAR).contains(p) {
            return Vec::new();
        }
        let mut out = Vec::new();
        for (i, s) in self.segs.iter().enumerate() {
            if !s.bounding_box().inflate(NEAR, NEAR).contains(p) {
                continue;
            }
            let n = s.nearest(p, ACCURACY);
            let d = n.distance_sq.sqrt();
            if d <= NEAR {
                out.push((i, n.t, d));
            }
        }
        out
    }

    /// The segments from `(i0, t0)` forward to `(i1, t1)`; all the way round when they are
    /// the same point.
    fn stretch(&self, (i0, t0): (usize, f64), (i1, t1): (usize, f64)) -> Vec<PathSeg> {
        let n = self.segs.len();
        let mut out = Vec::new();
        if i0 == i1 && t1 > t0 {
            out.push(self.segs[i0].subsegment(t0..t1));
        } else {
            out.push(self.segs[i0].subsegment(t0..1.0));
            let mut i = (i0 + 1) % n;
            while i != i1 {
                out.push(self.segs[i]);
                i = (i + 1) % n;
            }
            out.push(self.segs[i1].subsegment(0.0..t1));
        }
        out.retain(|s| s.arclen(ACCURACY) > 1e-6);
        out
    }
}

/// The stretch of one of `loops` from corner `from` to corner `to` (the same corner for a
/// closed border: once round the loop), beginning and ending exactly at them (see the
/// module documentation), or `None` when no stretch is within 30% (plus one pixel) of
/// `length` long, or when one leaves `bounds` widened by 1.5 px.
pub(crate) fn cut(
    loops: &[Loop],
    from: Point,
    to: Point,
    length: f64,
    bounds: Rect,
) -> Option<Vec<PathSeg>> {
    let closed = from == to;
    let mut best: Option<Found> = None;
    for (k, l) in loops.iter().enumerate() {
        if l.segs.is_empty() || !l.bounds.inflate(NEAR, NEAR).overlaps(bounds) {
            continue;
        }
        let starts = l.near(from);
        if starts.is_empty() {
            continue;
        }
        let total = l.total();
        if closed {
            let &(i, t, _) = starts
                .iter()
                .min_by(|a, b| a.2.total_cmp(&b.2))
                .expect("not empty");
            let score = (total - length).abs();
            if best.is_none_or(|b| score < b.0) {
                best = Some((score, k, (i, t), (i, t)));
            }
            continue;
        }
        let ends = l.near(to);
        for &(i0, t0, _) in &starts {
            let p0 = l.position(i0, t0);
            for &(i1, t1, _) in &ends {
                let p1 = l.position(i1, t1);
                let along = (p1 - p0).rem_euclid(total);
                let score = (along - length).abs();
                if best.is_none_or(|b| score < b.0) {
                    best = Some((score, k, (i0, t0), (i1, t1)));
                }
            }
        }
    }
    let (score, k, a, b) = best?;
    if score > 0.3 * length + 1.0 {
        return None;
    }
    let l = &loops[k];
    // An open border whose two corners are nearest the same point of the loop is a
    // straight line between them, not the whole loop from that point round to itself.
    let empty =
        !closed && (l.position(b.0, b.1) - l.position(a.0, a.1)).rem_euclid(l.total()) < 1e-9;
    let mut segs = if empty { Vec::new() } else { l.stretch(a, b) };
    if segs.is_empty() {
        segs.push(PathSeg::Line(kurbo::Line::new(from, to)));
    }
    let (first, last) = (segs[0].start(), segs[segs.len() - 1].end());
    if first != from {
        segs.insert(0, PathSeg::Line(kurbo::Line::new(from, first)));
    }
    if last != to {
        segs.push(PathSeg::Line(kurbo::Line::new(last, to)));
    }
    let allowed = bounds.inflate(1.5, 1.5);
    let inside = segs.iter().all(|s| {
        let b = s.bounding_box();
        allowed.contains(b.origin()) && allowed.contains(Point::new(b.x1, b.y1))
    });
    inside.then_some(segs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Loop {
        // A 4 × 4 square drawn counter-clockwise on screen, corners cut off.
        let pts = [
            Point::new(1.0, 0.5),
            Point::new(0.5, 1.0),
            Point::new(0.5, 3.0),
            Point::new(1.0, 3.5),
            Point::new(3.0, 3.5),
            Point::new(3.5, 3.0),
            Point::new(3.5, 1.0),
            Point::new(3.0, 0.5),
        ];
        let commands: Vec<PathCommand> = pts[1..].iter().map(|&p| PathCommand::Line(p)).collect();
        Loop::new(pts[0], &commands)
    }

    #[test]
    fn stretch_between_two_corners() {
        let l = square();
        let bounds = Rect::new(0.0, 0.0, 4.0, 4.0);
        // The left side, from the top-left corner down to the bottom-left one.
        let segs = cut(
            std::slice::from_ref(&l),
            Point::new(0.5, 0.5),
            Point::new(0.5, 3.5),
            3.0,
            bounds,
        )
        .unwrap();
        assert_eq!(segs.first().unwrap().start(), Point::new(0.5, 0.5));
        assert_eq!(segs.last().unwrap().end(), Point::new(0.5, 3.5));
        // Along the left side (never the right one), about as long as asked.
        let len: f64 = segs.iter().map(|s| s.arclen(1e-6)).sum();
        assert!((3.0..4.0).contains(&len), "{len}");
        assert!(segs.iter().all(|s| s.start().x <= 1.0 && s.end().x <= 1.0));
        // Far from what the cracks say: no stretch.
        assert!(cut(
            std::slice::from_ref(&l),
            Point::new(0.5, 0.5),
            Point::new(0.5, 3.5),
            30.0,
            bounds
        )
        .is_none());
    }

    #[test]
    fn corners_nearest_one_point_give_a_line_not_the_loop() {
        let l = square();
        // Both corners of a short open border are nearest the vertex (0.5, 1.0).
        let (from, to) = (Point::new(0.25, 1.0), Point::new(0.4, 1.0));
        let segs = cut(
            std::slice::from_ref(&l),
            from,
            to,
            1.0,
            Rect::new(0.0, 0.0, 4.0, 4.0),
        )
        .unwrap();
        assert_eq!(segs.first().unwrap().start(), from);
        assert_eq!(segs.last().unwrap().end(), to);
        let len: f64 = segs.iter().map(|s| s.arclen(1e-6)).sum();
        assert!(len < 1.0, "{len}: went round the loop");
    }

    #[test]
    fn closed_border_is_the_whole_loop() {
        let l = square();
        let p = Point::new(0.5, 0.5);
        let segs = cut(
            std::slice::from_ref(&l),
            p,
            p,
            11.0,
            Rect::new(0.0, 0.0, 4.0, 4.0),
        )
        .unwrap();
        assert_eq!(segs.first().unwrap().start(), p);
        assert_eq!(segs.last().unwrap().end(), p);
        let len: f64 = segs.iter().map(|s| s.arclen(1e-6)).sum();
        assert!(len > 10.0, "{len}");
    }
}
