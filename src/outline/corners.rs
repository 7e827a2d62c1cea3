//! Staircase corners cut: the corners inside a pixel staircase of a drawing replaced by
//! chamfers, which keep every pixel centre on its side.
//!
//! A staircase (see [`super::staircase`]) is a run of short axis-aligned steps; where the
//! input has one-pixel features (a lone pixel, a one-pixel spur or notch, the end of a
//! one-pixel line) the exact drawing follows pixel cracks there, and zoomed in it shows
//! square teeth. Each corner `v` between two steps of such a run is cut: the path goes from
//! `u' = v + c_in·(u − v)/|u − v|` straight to `w' = v + c_out·(w − v)/|w − v|` instead of
//! through `v`, with `c = min(½, |leg|/2)` on each leg (rounded down to the grid), so two
//! cuts on one leg meet at most at its middle.
//!
//! **Exact by construction.** Replacing `u' → v → w'` by `u' → w'` changes the winding
//! number only inside the triangle `u' v w'`. A corner is cut only when that closed triangle
//! holds no pixel centre, so no renderer that samples pixel centres (crispEdges) fills a
//! pixel differently. For a crack corner (integer `v`, legs of at least one pixel) the
//! triangle lies in the half-pixel square at the corner, whose far corner is the pixel
//! centre: the chamfer passes `√2/4 ≈ 0.354` px from it. A unit step cut at both ends
//! disappears, so a staircase of unit steps becomes the straight line through the steps'
//! middles (collinear points are merged): one diagonal `L` instead of many.

use super::staircase::{step, Step, MIN_RUN};
use crate::curve::PathCommand;
use kurbo::{Point, Vec2};

/// Largest cut (pixels) along each leg of a corner.
pub const MAX_CUT: f64 = 0.5;

/// True when the closed triangle `a b c` holds a pixel centre (`(i + ½, j + ½)`), within
/// a margin of 1e-9 px.
fn holds_centre(a: Point, b: Point, c: Point) -> bool {
    let x0 = a.x.min(b.x).min(c.x);
    let x1 = a.x.max(b.x).max(c.x);
    let y0 = a.y.min(b.y).min(c.y);
    let y1 = a.y.max(b.y).max(c.y);
    let cross = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
    let area = cross(a, b, c);
    let mut i = (x0 - 0.5).ceil();
    while i + 0.5 <= x1 {
        let mut j = (y0 - 0.5).ceil();
        while j + 0.5 <= y1 {
            let p = Point::new(i + 0.5, j + 0.5);
            let s = [cross(a, b, p), cross(b, c, p), cross(c, a, p)];
            if s.iter().all(|&v| v * area.signum() >= -1e-9) {
                return true;
            }
            j += 1.0;
        }
        i += 1.0;
    }
    false
}

/// The cut along a leg of length `len`: `min(½, len/2)` rounded down to a multiple of
/// `2^-grid`; 0 when the grid is too coarse.
fn cut_length(len: f64, grid: u8) -> f64 {
    let scale = f64::from(1u32 << grid.min(30));
    ((MAX_CUT.min(len / 2.0)) * scale).floor() / scale
}

/// The closed path `M start commands Z` with the corners inside its staircases cut (see
/// the module documentation), on the grid of `2^-grid` px.
///
/// Returns `None` if no corner is cut (no staircase, or none that can be cut on the grid).
pub(crate) fn cut_staircase_corners(
    start: Point,
    commands: &[PathCommand],
    grid: u8,
) -> Option<(Point, Vec<PathCommand>)> {
    if commands.is_empty() {
        return None;
    }
    // The closed loop as edges `from → cmd`; the closing segment made explicit.
    let mut edges: Vec<(Point, PathCommand)> = Vec::with_capacity(commands.len() + 1);
    let mut pen = start;
    for c in commands {
        edges.push((pen, *c));
        pen = c.end();
    }
    if pen != start {
        edges.push((pen, PathCommand::Line(start)));
    }
    let m = edges.len();
    let axis: Vec<Option<Step>> = edges
        .iter()
        .map(|(from, c)| match c {
            PathCommand::Line(to) => step(*from, *to),
            _ => None,
        })
        .collect();
    // `joined[i]`: edges i and i + 1 are consecutive steps of one run (alternating axes).
    let joined: Vec<bool> = (0..m)
        .map(|i| match (axis[i], axis[(i + 1) % m]) {
            (Some(a), Some(b)) => a != b,
            _ => false,
        })
        .collect();
    // Corners to cut: between the steps of cyclic runs of at least MIN_RUN steps.
    let mut cut = vec![false; m];
    if joined.iter().all(|&j| j) {
        cut.iter_mut().for_each(|c| *c = true);
    } else {
        let first_break = joined.iter().position(|&j| !j)?;
        let mut i = 0;
        while i < m {
            let s = (first_break + 1 + i) % m;
            // A run starting at edge s: edges s, s+1, … while joined.
            let mut len = 1;
            while joined[(s + len - 1) % m] {
                len += 1;
            }
            if axis[s].is_some() && len as u64 >= MIN_RUN {
                for k in 0..len - 1 {
                    cut[(s + k) % m] = true;
                }
            }
            i += len;
        }
    }
    // Corner i is the end of edge i (the start of edge i + 1).
    let end = |i: usize| edges[i].1.end();
    let mut cuts: Vec<Option<(Point, Point)>> = vec![None; m];
    for i in 0..m {
        if !cut[i] {
            continue;
        }
        let v = end(i);
        let u = edges[i].0;
        let w = end((i + 1) % m);
        let (a, b) = (u - v, w - v);
        let (ca, cb) = (cut_length(a.hypot(), grid), cut_length(b.hypot(), grid));
        if ca <= 0.0 || cb <= 0.0 {
            continue;
        }
        let unit = |d: Vec2| d / d.hypot();
        let (u2, w2) = (v + unit(a) * ca, v + unit(b) * cb);
        if !holds_centre(u2, v, w2) {
            cuts[i] = Some((u2, w2));
        }
    }
    if cuts.iter().all(Option::is_none) {
        return None;
    }
    // The new loop's points; `made[k]`: point k was made by a cut (may be merged away when
    // collinear with its neighbours).
    let mut pts: Vec<(PathCommand, bool)> = Vec::with_capacity(m + 8);
    for (i, (_, c)) in edges.iter().enumerate() {
        match cuts[i] {
            Some((u2, w2)) => {
                pts.push((PathCommand::Line(u2), true));
                pts.push((PathCommand::Line(w2), true));
            }
            None => pts.push((*c, false)),
        }
    }
    // Drop repeated points (a unit step cut at both ends), then made points on the segment
    // between their neighbours.
    let mut out: Vec<(PathCommand, bool)> = Vec::with_capacity(pts.len());
    for p in pts {
        if let (PathCommand::Line(q), Some(last)) = (p.0, out.last_mut()) {
            if last.0.end() == q {
                last.1 |= p.1;
                continue;
            }
        }
        out.push(p);
    }
    // The loop closes on itself: a repeated last point goes too.
    while out.len() > 1 && out[out.len() - 1].0.end() == out[0].0.end() {
        if let PathCommand::Line(_) = out[out.len() - 1].0 {
            let made = out.pop().expect("len > 1").1;
            out[0].1 |= made;
        } else {
            break;
        }
    }
    let n = out.len();
    let mut keep = vec![true; n];
    for k in 0..n {
        let PathCommand::Line(q) = out[k].0 else {
            continue;
        };
        let next = &out[(k + 1) % n].0;
        if !out[k].1 || !matches!(next, PathCommand::Line(_)) {
            continue;
        }
        // The previous kept point.
        let mut p = (k + n - 1) % n;
        while !keep[p] {
            p = (p + n - 1) % n;
        }
        let (a, r) = (out[p].0.end(), next.end());
        let (d1, d2) = (q - a, r - q);
        if d1.cross(d2).abs() <= 1e-12 && d1.dot(d2) > 0.0 {
            keep[k] = false;
        }
    }
    let kept: Vec<PathCommand> = out
        .iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(c, _)| c.0)
        .collect();
    // Start at the last command's end; the loop's last command returns there.
    let start = kept.last()?.end();
    Some((start, kept))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outline::staircase::has_staircase;

    fn lines(pts: &[(f64, f64)]) -> Vec<PathCommand> {
        pts.iter()
            .map(|&(x, y)| PathCommand::Line(Point::new(x, y)))
            .collect()
    }

    /// A lone pixel becomes the diamond through its sides' middles.
    #[test]
    fn a_lone_pixel_becomes_a_diamond() {
        let cmds = lines(&[(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        let (start, cut) = cut_staircase_corners(Point::ZERO, &cmds, 4).unwrap();
        let mut pts: Vec<(f64, f64)> = cut.iter().map(|c| (c.end().x, c.end().y)).collect();
        pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(pts, [(0.0, 0.5), (0.5, 0.0), (0.5, 1.0), (1.0, 0.5)]);
        assert_eq!(cut.last().unwrap().end(), start);
        assert!(!has_staircase(start, &cut));
        // Integer coordinates only: nothing can be cut.
        assert!(cut_staircase_corners(Point::ZERO, &cmds, 0).is_none());
    }

    /// A staircase of unit steps becomes one diagonal line through the steps' middles.
    #[test]
    fn unit_steps_become_one_diagonal() {
        // Steps down-right from (0, 0) to (4, 4), then back along two long edges.
        let mut pts = Vec::new();
        for k in 0..4 {
            let k = f64::from(k);
            pts.push((k + 1.0, k));
            pts.push((k + 1.0, k + 1.0));
        }
        pts.push((0.0, 4.0));
        let cmds = lines(&pts);
        let (start, cut) = cut_staircase_corners(Point::ZERO, &cmds, 4).unwrap();
        assert!(!has_staircase(start, &cut));
        // (0, 0) → first half step, one diagonal to the last half step, the corner (4, 4)
        // and the long edges.
        assert!(cut.len() <= 5, "{cut:?}");
        let diagonal = cut
            .iter()
            .scan(start, |pen, c| {
                let from = std::mem::replace(pen, c.end());
                Some((c.end() - from).hypot())
            })
            .fold(0.0f64, f64::max);
        assert!(diagonal > 4.0, "one long diagonal: {cut:?}");
    }

    /// Winding number of the closed polyline `pts` round `p`.
    fn winding(pts: &[Point], p: Point) -> i32 {
        let mut w = 0;
        for k in 0..pts.len() {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            if a.y <= p.y && b.y > p.y && (b - a).cross(p - a) > 0.0 {
                w += 1;
            } else if a.y > p.y && b.y <= p.y && (b - a).cross(p - a) < 0.0 {
                w -= 1;
            }
        }
        w
    }

    proptest::proptest! {
        /// Random loops of half-pixel steps (axis-aligned, short or long, and diagonal moves):
        /// cutting changes the winding number at no pixel centre (taken just off it) and writes
        /// points on the grid; on pixel corners it leaves no staircase.
        #[test]
        fn no_pixel_centre_changes_side(
            moves in proptest::collection::vec((0u8..8, 1i32..=4, proptest::bool::ANY), 3..40),
            (sx, sy) in (0i32..2, 0i32..2),
        ) {
            // Mostly alternating axis steps (staircases), some repeated axes and diagonals;
            // lengths in half pixels, from a corner or a half-pixel position.
            let start = Point::new(10.0 + 0.5 * f64::from(sx), 10.0 + 0.5 * f64::from(sy));
            let mut pen = start;
            let mut cmds = Vec::new();
            let mut horizontal = true;
            for &(kind, len, sign) in &moves {
                let l = f64::from(len) * if sign { 0.5 } else { -0.5 };
                let d = match kind {
                    0..=5 => {
                        horizontal = !horizontal;
                        if horizontal { Vec2::new(l, 0.0) } else { Vec2::new(0.0, l) }
                    }
                    6 => if horizontal { Vec2::new(l, 0.0) } else { Vec2::new(0.0, l) },
                    _ => Vec2::new(l, l.abs()),
                };
                pen += d;
                cmds.push(PathCommand::Line(pen));
            }
            let before: Vec<Point> = std::iter::once(start).chain(cmds.iter().map(|c| c.end())).collect();
            if let Some((s, cut)) = cut_staircase_corners(start, &cmds, 4) {
                let after: Vec<Point> = std::iter::once(s).chain(cut.iter().map(|c| c.end())).collect();
                for p in &after {
                    proptest::prop_assert_eq!((p.x * 16.0).fract(), 0.0);
                    proptest::prop_assert_eq!((p.y * 16.0).fract(), 0.0);
                }
                // On pixel corners (crack drawings) every corner of a staircase is cut.
                if before.iter().all(|p| p.x.fract() == 0.0 && p.y.fract() == 0.0) {
                    proptest::prop_assert!(!has_staircase(s, &cut), "{:?}", cut);
                }
                for i in -5..30 {
                    for j in -5..30 {
                        // Just off the centre: a centre on the path is decided by where
                        // the path lies next to it, as renderers' tie rules do.
                        let p = Point::new(f64::from(i) + 0.5 + 1e-7, f64::from(j) + 0.5 + 1.3e-7);
                        proptest::prop_assert_eq!(winding(&before, p), winding(&after, p), "{:?}", p);
                    }
                }
            } else {
                // Nothing cut: no staircase, or none whose corners can be cut.
                let integer = before.iter().all(|p| p.x.fract() == 0.0 && p.y.fract() == 0.0);
                proptest::prop_assert!(!integer || !has_staircase(start, &cmds), "{:?}", cmds);
            }
        }
    }
}
