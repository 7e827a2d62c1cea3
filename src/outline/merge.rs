//! Fewer vertices: consecutive straight segments of an exact drawing merged into one where
//! the renderer draws the same pixels.
//!
//! The polygons that replace curves (digital straight segments, halves of them, bridges
//! between pieces) meet at vertices chosen piece by piece; the renderer only needs the
//! drawing to keep each pixel centre on its side. So the vertex `v` between two lines
//! `u → v → w` can go when the closed loop `u → w → v → u` paints nothing: the winding of
//! the path changes by that loop's winding, edge by edge (tiny-skia and Skia rasterize each
//! line edge by itself), so a loop that paints no pixel centre changes no pixel. A chain
//! `u → v₁ → … → vₖ → w` becomes `u → w` the same way, its loop going back through every
//! dropped vertex. A short bridge `v₁ → v₂` between two lines `u → v₁` and `v₂ → w` (where
//! two pieces' polygons meet off each other's line) becomes one vertex `x` — the corner
//! where the lines cross, or on a step between parallel edges the step's middle or a foot
//! of it on either line — when the loop `u → x → w → v₂ → v₁ → u` paints nothing. The loop
//! is checked as the contour is: filled by tiny-skia in a window of its own, also moved by
//! [`super::ROBUST_SHIFT`] sideways, and in Chromium's tiles ([`super::tiles`]). Lines
//! only: they are drawn the same at any origin (see [`super::render_check`]), curves are
//! not.

use super::render_check::EdgeClipping;
use super::robust::loop_paints_nothing;
use crate::curve::PathCommand;
use kurbo::Point;

/// Most vertices one merged segment may drop: bounds the loops' length (and so the work of
/// each check) on long runs of nearly collinear segments.
const MAX_DROPPED: usize = 8;

/// The closed path `M start commands Z` with vertices between consecutive lines dropped
/// and short bridges between lines collapsed to one vertex (on the `grid`) where the renderer
/// draws the same pixels (see the module documentation), in passes
/// until none goes: a merge makes new neighbours, which the next pass tries (27 shared
/// samples, conic: 11 339 commands after one pass, 11 123 after two, no change after).
/// The start vertex stays (dropping it too saved 4 commands there). Returns `None` if no
/// vertex can go.
pub(crate) fn merge_lines(
    start: Point,
    commands: &[PathCommand],
    canvas: Option<kurbo::Rect>,
    grid: u8,
) -> Option<Vec<PathCommand>> {
    let mut current = commands.to_vec();
    // Lines made by the last pass; the first pass tries every pair.
    let mut fresh = vec![true; current.len()];
    let mut any = false;
    for _ in 0..MAX_PASSES {
        let mut changed = false;
        if let Some((next, next_fresh)) = merge_pass(start, &current, &fresh, canvas) {
            (current, fresh) = (next, next_fresh);
            changed = true;
        }
        if let Some((next, next_fresh)) = collapse_bridges(start, &current, canvas, grid) {
            (current, fresh) = (next, next_fresh);
            changed = true;
        }
        if !changed {
            break;
        }
        any = true;
    }
    any.then_some(current)
}

/// Longest bridge (px) [`collapse_bridges`] replaces by one vertex.
const MAX_BRIDGE: f64 = 1.5;

/// One pass of [`merge_lines`] over short bridges between lines: where two lines
/// `u → v₁` and `v₂ → w` are joined by a short line `v₁ → v₂` (where two pieces' polygons
/// met off each other's line: a notch of a pixel or less), the bridge goes and both lines
/// run on to one vertex `x` ([`bridge_corners`], snapped to the `grid`), when the loop
/// `u → x → w → v₂ → v₁ → u` paints nothing. Returns the commands and which of them changed,
/// or `None` if no bridge went.
fn collapse_bridges(
    start: Point,
    commands: &[PathCommand],
    canvas: Option<kurbo::Rect>,
    grid: u8,
) -> Option<(Vec<PathCommand>, Vec<bool>)> {
    let n = commands.len();
    if n <= MIN_COMMANDS {
        return None;
    }
    let snap = super::builder::Builder::new(grid);
    let mut out: Vec<PathCommand> = Vec::with_capacity(n);
    let mut out_fresh: Vec<bool> = Vec::with_capacity(n);
    let mut removed = 0;
    let mut pen = start;
    let mut i = 0;
    while i < n {
        let c = commands[i];
        // `c` is the line `u → v₁` (u = pen), then the bridge and the line `v₂ → w`.
        let corner = match (c, commands.get(i + 1), commands.get(i + 2)) {
            (PathCommand::Line(v1), Some(&PathCommand::Line(v2)), Some(&PathCommand::Line(w)))
                if n - removed > MIN_COMMANDS =>
            {
                bridge_corners(pen, v1, v2, w, &snap)
                    .into_iter()
                    .find(|&x| {
                        let lp = [
                            PathCommand::Line(x),
                            PathCommand::Line(w),
                            PathCommand::Line(v2),
                            PathCommand::Line(v1),
                            PathCommand::Line(pen),
                        ];
                        loop_paints_nothing(pen, &lp, EdgeClipping::Never, canvas, true)
                    })
            }
            _ => None,
        };
        match corner {
            Some(x) => {
                out.push(PathCommand::Line(x));
                out.push(commands[i + 2]);
                out_fresh.extend([true, true]);
                removed += 1;
                pen = commands[i + 2].end();
                i += 3;
            }
            None => {
                out.push(c);
                out_fresh.push(false);
                pen = c.end();
                i += 1;
            }
        }
    }
    (removed > 0).then_some((out, out_fresh))
}

/// The corners that may replace the short bridge `v₁ → v₂` (at most [`MAX_BRIDGE`] px, both
/// lines longer) between the lines `u → v₁` and `v₂ → w`, snapped, in the order tried: where
/// the lines cross, when that lies within twice the bridge's length of it; else, when the
/// lines run side by side (a step between two parallel edges), the bridge's middle and the
/// feet of each end on the other line. Each ahead of `u` and before `w`.
fn bridge_corners(
    u: Point,
    v1: Point,
    v2: Point,
    w: Point,
    snap: &super::builder::Builder,
) -> Vec<Point> {
    let (a, b) = (v1 - u, w - v2);
    let bridge = (v2 - v1).hypot();
    if bridge > MAX_BRIDGE || a.hypot() <= bridge || b.hypot() <= bridge {
        return Vec::new();
    }
    let mut out = Vec::new();
    // u + s a = v₂ + t b.
    let den = a.cross(b);
    if den.abs() >= 1e-9 * a.hypot() * b.hypot() {
        let x = u + a * ((v2 - u).cross(b) / den);
        if (x - v1.midpoint(v2)).hypot() <= 2.0 * bridge {
            out.push(x);
        }
    }
    if out.is_empty() && a.dot(b) > 0.0 {
        let foot = |p: Point, o: Point, d: kurbo::Vec2| o + d * ((p - o).dot(d) / d.hypot2());
        out.extend([v1.midpoint(v2), foot(v2, u, a), foot(v1, v2, b)]);
    }
    out.into_iter()
        .map(|x| snap.snap(x))
        .filter(|&x| (x - u).dot(a) > 0.0 && (w - x).dot(b) > 0.0 && x != u && x != w)
        .collect()
}

/// Fewest commands a path is merged down to: a lone pixel keeps its diamond (four lines
/// through the middles of its sides, see [`super::corners`]), not a lopsided triangle.
const MIN_COMMANDS: usize = 4;

/// Most passes of [`merge_lines`] (two sufficed on every shared sample before bridges were
/// collapsed too).
const MAX_PASSES: usize = 4;

/// One pass of [`merge_lines`] from the first command on: each line is merged into the line
/// before it while the loop through the vertices dropped so far paints nothing. A pair of
/// lines neither of which the last pass made (`fresh`) is not tried again: the loop that
/// failed then is the same. Returns the commands and which of them are new merges, or
/// `None` if nothing merged.
fn merge_pass(
    start: Point,
    commands: &[PathCommand],
    fresh: &[bool],
    canvas: Option<kurbo::Rect>,
) -> Option<(Vec<PathCommand>, Vec<bool>)> {
    // The loop `anchor → w → dropped reversed → anchor` paints nothing (built in one
    // buffer for the pass).
    let mut lp: Vec<PathCommand> = Vec::new();
    let mut paints_nothing = |anchor: Point, w: Point, dropped: &[Point]| {
        lp.clear();
        lp.push(PathCommand::Line(w));
        lp.extend(dropped.iter().rev().map(|&p| PathCommand::Line(p)));
        lp.push(PathCommand::Line(anchor));
        loop_paints_nothing(anchor, &lp, EdgeClipping::Never, canvas, true)
    };
    let mut out: Vec<PathCommand> = Vec::with_capacity(commands.len());
    let mut out_fresh: Vec<bool> = Vec::with_capacity(commands.len());
    // The start of the last line written (its anchor), the vertices it dropped, and whether
    // it was fresh before this pass.
    let mut anchor: Option<Point> = None;
    let mut dropped: Vec<Point> = Vec::new();
    let mut last_was_fresh = false;
    let mut merged = false;
    // At most this many commands go, so that at least `MIN_COMMANDS` stay.
    let excess = commands.len().saturating_sub(MIN_COMMANDS);
    let mut removed = 0;
    let mut pen = start;
    for (c, &is_fresh) in commands.iter().zip(fresh) {
        let PathCommand::Line(w) = *c else {
            out.push(*c);
            out_fresh.push(false);
            anchor = None;
            pen = c.end();
            continue;
        };
        if let (Some(a), Some(PathCommand::Line(v))) = (anchor, out.last().copied()) {
            let worth = is_fresh || last_was_fresh || !dropped.is_empty();
            if worth && dropped.len() < MAX_DROPPED && w != a {
                dropped.push(v);
                if removed < excess && paints_nothing(a, w, &dropped) {
                    *out.last_mut().expect("a line was written") = PathCommand::Line(w);
                    *out_fresh.last_mut().expect("a line was written") = true;
                    merged = true;
                    removed += 1;
                    pen = w;
                    continue;
                }
                dropped.pop();
            }
        }
        out.push(*c);
        out_fresh.push(false);
        anchor = Some(pen);
        dropped.clear();
        last_was_fresh = is_fresh;
        pen = w;
    }
    merged.then_some((out, out_fresh))
}

#[cfg(test)]
mod tests {
    use super::super::render_check::{misplaced_pixels, Reference};
    use super::super::ROBUST_SHIFT;
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Merging changes no pixel: the merged polygon fills exactly what the original
        /// fills, also moved by 1/64 px, and has fewer vertices. Polygons: a wobbly circle
        /// of 6 to 40 vertices on the 1/16 grid, many of them nearly collinear.
        #[test]
        fn merging_changes_no_pixel(
            radii in proptest::collection::vec(60u32..64, 6..40),
            cx in 0u32..64, cy in 0u32..64,
        ) {
            let k = radii.len();
            let pts: Vec<Point> = radii
                .iter()
                .enumerate()
                .map(|(i, &r)| {
                    let t = std::f64::consts::TAU * i as f64 / k as f64;
                    let snap = |v: f64| (v * 16.0).round() / 16.0;
                    let r = f64::from(r) / 8.0;
                    Point::new(
                        snap(20.0 + f64::from(cx) / 16.0 + r * t.cos()),
                        snap(20.0 + f64::from(cy) / 16.0 + r * t.sin()),
                    )
                })
                .collect();
            let start = pts[0];
            let cmds: Vec<PathCommand> =
                pts[1..].iter().chain([&start]).map(|&p| PathCommand::Line(p)).collect();
            if let Some(merged) = merge_lines(start, &cmds, None, 4) {
                prop_assert!(merged.len() < cmds.len());
                // Unmoved and moved by ±1/64 px, both the same way.
                for d in [0.0, ROBUST_SHIFT, -ROBUST_SHIFT] {
                    let v = kurbo::Vec2::new(d, 0.0);
                    let moved = |c: &[PathCommand]| -> Vec<PathCommand> {
                        c.iter().map(|c| c.translated(v)).collect()
                    };
                    let reference = Reference::new(start + v, &moved(&cmds));
                    prop_assert!(misplaced_pixels(
                        &reference,
                        start + v,
                        &moved(&merged),
                        EdgeClipping::Never,
                        None
                    )
                    .is_empty());
                }
            }
        }
    }

    fn line(x: f64, y: f64) -> PathCommand {
        PathCommand::Line(Point::new(x, y))
    }

    #[test]
    fn a_bridge_becomes_one_vertex_where_no_pixel_changes() {
        // A square whose top-right corner is cut by a short bridge: both sides run on to
        // the corner, the bridge's triangle holding no pixel centre.
        let start = Point::new(1.0, 1.0);
        let bridged = [
            line(8.5, 1.0),
            line(9.0, 1.5),
            line(9.0, 9.0),
            line(1.0, 9.0),
            line(1.0, 1.0),
        ];
        let (out, fresh) = collapse_bridges(start, &bridged, None, 4).expect("a corner");
        assert_eq!(
            out,
            vec![
                line(9.0, 1.0),
                line(9.0, 9.0),
                line(1.0, 9.0),
                line(1.0, 1.0)
            ]
        );
        assert_eq!(fresh, vec![true, true, false, false]);
        // A longer cut whose triangle holds the centre (8.5, 1.5) stays.
        let cut = [
            line(7.5, 1.0),
            line(9.0, 2.5),
            line(9.0, 9.0),
            line(1.0, 9.0),
            line(1.0, 1.0),
        ];
        assert_eq!(collapse_bridges(start, &cut, None, 4), None);
        // A step between two parallel edges, across the row of centres y = 1.5: one vertex
        // at the step's middle keeps (8.5, 1.5) in and (9.5, 1.5) out.
        let start = Point::new(1.0, 1.25);
        let step = [
            line(9.0, 1.25),
            line(9.5, 1.75),
            line(18.0, 1.75),
            line(18.0, 9.0),
            line(1.0, 9.0),
            line(1.0, 1.25),
        ];
        let (out, _) = collapse_bridges(start, &step, None, 4).expect("a vertex");
        assert_eq!(out[..2], [line(9.25, 1.5), line(18.0, 1.75)]);
    }

    #[test]
    fn collinear_and_clear_vertices_go() {
        // A square drawn with extra vertices on its top, one bent by 0.25 px between pixel
        // centres: the bend changes no pixel, so it goes too.
        let start = Point::new(1.0, 1.0);
        let cmds = [
            line(3.0, 1.0),
            line(6.0, 1.25),
            line(9.0, 1.0),
            line(9.0, 9.0),
            line(5.0, 9.0),
            line(1.0, 9.0),
        ];
        let out = merge_lines(start, &cmds, None, 4).expect("vertices to drop");
        // Two go; the bottom's middle vertex stays, as a path keeps four commands.
        assert_eq!(
            out,
            vec![
                line(9.0, 1.0),
                line(9.0, 9.0),
                line(5.0, 9.0),
                line(1.0, 9.0)
            ]
        );
    }

    #[test]
    fn a_vertex_that_keeps_a_pixel_stays() {
        // The dent down to (5, 2) leaves the centres (4.5, 1.5) and (5.5, 1.5) outside; a
        // straight top would paint them.
        let start = Point::new(1.0, 1.0);
        let cmds = [
            line(5.0, 2.0),
            line(9.0, 1.0),
            line(9.0, 9.0),
            line(1.0, 9.0),
        ];
        assert_eq!(merge_lines(start, &cmds, None, 4), None);
    }

    #[test]
    fn curves_are_left_alone() {
        let start = Point::new(1.0, 1.0);
        let cmds = [
            PathCommand::Cubic(
                Point::new(3.0, 0.0),
                Point::new(6.0, 0.0),
                Point::new(9.0, 1.0),
            ),
            line(9.0, 9.0),
            line(1.0, 9.0),
        ];
        assert_eq!(merge_lines(start, &cmds, None, 4), None);
    }
}
