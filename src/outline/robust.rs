//! The render checks that look past tiny-skia's exact pixels: the path moved by
//! [`super::ROBUST_SHIFT`] sideways (where Skia's fixed point in Chromium, or a cut at a
//! tile, may round an edge to the other side of a pixel centre) and with its curves finely
//! flattened (renderers that subdivide curves more finely), besides as it is
//! ([`super::render_check`]).

use super::render_check::{
    draws_right, fill_window_moved, has_curves, misplaced_pixels, pixels_at, EdgeClipping,
    PathBounds, Reference, Window,
};
use super::scan;
use super::sure::Known;
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// Whether the closed loop `M anchor lp Z` paints no pixel centre: filled by tiny-skia alone,
/// in a window of its own and in Chromium's tiles ([`super::tiles`]); when `robust`, also
/// moved by [`super::ROBUST_SHIFT`] sideways (first: where the plain fill is wrong the moved
/// one mostly is too) and with its curves finely flattened ([`finely_flattened`]). A change
/// to a path whose loop (the new commands, then the old ones backwards) paints nothing
/// changes no pixel: tiny-skia and Skia sum each edge's crossings by itself, and a command
/// drawn both ways cancels. Small loops of lines are settled without a fill where they can
/// be ([`super::sure`]).
pub(crate) fn loop_paints_nothing(
    anchor: Point,
    lp: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<Rect>,
    robust: bool,
) -> bool {
    match super::sure::classify(anchor, lp, canvas) {
        Known::Paints => false,
        Known::PaintsNothing => true,
        Known::Unknown => filled_paints_nothing(anchor, lp, clipping, canvas, robust),
    }
}

/// [`loop_paints_nothing`] by its fills alone.
pub(super) fn filled_paints_nothing(
    anchor: Point,
    lp: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<Rect>,
    robust: bool,
) -> bool {
    // The empty reference at the anchor: the window is the loop's.
    let nothing = Reference::new(anchor, &[]);
    let moved = |d: f64| {
        let v = kurbo::Vec2::new(d, 0.0);
        let moved: Vec<PathCommand> = lp.iter().map(|c| c.translated(v)).collect();
        draws_right(&nothing, anchor + v, &moved, clipping, canvas)
    };
    let shift = super::ROBUST_SHIFT;
    let right = if robust {
        match moved_draw_right(&nothing, anchor, lp, shift, clipping, canvas) {
            Some(right) => right,
            None => {
                moved(shift) && moved(-shift) && draws_right(&nothing, anchor, lp, clipping, canvas)
            }
        }
    } else {
        draws_right(&nothing, anchor, lp, clipping, canvas)
    };
    right
        && super::tiles::misplaced_in_tiles(&nothing, anchor, lp, canvas).is_empty()
        && (!robust
            || finely_flattened(anchor, lp)
                .is_none_or(|fine| draws_right(&nothing, anchor, &fine, EdgeClipping::Never, None)))
}

/// Largest distance (pixels) of the polyline [`finely_flattened`] draws to the true curves.
pub const FINE_FLATTENING: f64 = 0.01;

/// How far (px) [`cubic_paints_nothing`] moves a cubic's control points: Skia's fixed point
/// differs from tiny-skia's, and Chromium cuts paths at its tiles (the polygons' smoothed
/// cubics, 27 shared samples, conic: 11 pixels differed in Chromium with 1/64 px, 10 with
/// 1/32 px, 9 with the polygons alone).
pub(crate) const NUDGE: f64 = 1.0 / 32.0;

/// Whether a change that draws the cubic `cubic` paints nothing, also with its control points
/// moved by [`NUDGE`] each way along both axes: `paints_nothing(c, robust)` checks the change
/// drawn with the cubic `c`, the robust checks of [`loop_paints_nothing`] when `robust` (only
/// for the cubic as it is). Every check must pass, so their order only sets the work: the
/// moved cubics (one fill each) go first, left first, before the cubic as it is (three moved
/// fills, tiles, the fine flattening). Counted on the 27 shared samples (conic): of the 3 486
/// smoothed polygons' cubics checked 2 101 failed, the moves (−,−), (−,+), (+,−), (+,+)
/// 1 516, 1 346, 1 294 and 1 092 times, the cubic as it is alone 62; of the runs' 3 198
/// cubics 1 374 failed, 1 227 of them moved, 83 only as they are. False for a command that is
/// not a cubic.
pub(crate) fn cubic_paints_nothing(
    cubic: PathCommand,
    paints_nothing: impl Fn(PathCommand, bool) -> bool,
) -> bool {
    let PathCommand::Cubic(p1, p2, e) = cubic else {
        return false;
    };
    [
        (-NUDGE, -NUDGE),
        (-NUDGE, NUDGE),
        (NUDGE, -NUDGE),
        (NUDGE, NUDGE),
    ]
    .into_iter()
    .all(|(dx, dy)| {
        let d = kurbo::Vec2::new(dx, dy);
        paints_nothing(PathCommand::Cubic(p1 + d, p2 + d, e), false)
    }) && paints_nothing(cubic, true)
}

/// [`misplaced_when_moved`], then [`misplaced_pixels`] when that is empty: the pixels the
/// first of the path moved by `shift`, by `−shift` and as it is that misplaces any gets
/// wrong. One scan for the three where it gives what the three fills give (see
/// [`moved_fills`]).
pub(crate) fn misplaced_moved_then_plain(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    shift: f64,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Vec<Pixel> {
    if let Some([plain, right, left]) =
        moved_fills(reference, start, commands, shift, clipping, canvas)
    {
        return [right, left, plain]
            .into_iter()
            .find(|wrong| !wrong.is_empty())
            .unwrap_or_default();
    }
    let wrong = misplaced_when_moved(reference, start, commands, shift, clipping, canvas);
    if !wrong.is_empty() {
        return wrong;
    }
    misplaced_pixels(reference, start, commands, clipping, canvas)
}

/// [`misplaced_pixels`] of the path as it is, moved by `shift` px sideways and by `−shift`,
/// from one scan ([`scan::painted_moved`]; the fills after the first moved one that
/// misplaces a pixel are left empty) — when the three paths have the same window, curves
/// are drawn one way and that scan applies; `None` otherwise (the caller fills them one by
/// one).
fn moved_fills(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    shift: f64,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Option<[Vec<Pixel>; 3]> {
    let (win, modes) = moved_window(reference, start, commands, shift, clipping, canvas)?;
    if modes.len() != 1 {
        return None;
    }
    let fills = scan::painted_moved(reference, start, commands, &win, modes[0], shift, true)?;
    Some(fills.map(|at| pixels_at(&win, at)))
}

/// Whether the path as it is and moved by `±shift` each paints no pixel `reference` does
/// not (as [`draws_right`] of each): `None` where one scan of each way of drawing curves
/// does not give what their fills give (see [`moved_fills`]).
fn moved_draw_right(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    shift: f64,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Option<bool> {
    let (win, modes) = moved_window(reference, start, commands, shift, clipping, canvas)?;
    for &clipped in modes {
        let fills = scan::painted_moved(reference, start, commands, &win, clipped, shift, true)?;
        if fills.iter().any(|at| !at.is_empty()) {
            return Some(false);
        }
    }
    Some(true)
}

/// The window and the ways of drawing curves that the path as it is and moved by `±shift`
/// share ([`fill_window_moved`]); `None` when nothing of the path as it is is drawn, or the
/// windows differ and the path is not [`on_grid`] lines (the caller fills the three one by
/// one).
///
/// Lines whose points, and the reference's, lie on the 1/64 px grid are filled the same in
/// any window that holds them with room to spare: moving the window's origin by whole
/// pixels moves every point exactly in `f32` and in tiny-skia's fixed point, and so every
/// row crossing by whole pixels. Then the three share the least window holding theirs
/// (a path along pixel edges, such as a speck's, has windows one pixel apart when moved).
fn moved_window(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    shift: f64,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Option<(Window, &'static [bool])> {
    let (path, curves) = (PathBounds::of(start, commands), has_curves(commands));
    let window = |d: f64| fill_window_moved(reference, &path, d, curves, clipping, canvas);
    let (shared, modes) = window(0.0)?;
    let (right, _) = window(shift)?;
    let (left, _) = window(-shift)?;
    if right == shared && left == shared {
        return Some((shared, modes));
    }
    (!curves && on_grid(reference, start, commands))
        .then(|| (shared.union(right).union(left), modes))
}

/// Whether every point of `M start commands Z` and of `reference` is a multiple of 1/64 px
/// below 2^16 px in size (exact in `f32` wherever a window puts the origin).
fn on_grid(reference: &Reference, start: Point, commands: &[PathCommand]) -> bool {
    let exact = |p: Point| {
        [p.x, p.y]
            .iter()
            .all(|v| (v * 64.0).fract() == 0.0 && v.abs() < 65536.0)
    };
    exact(start)
        && commands.iter().all(|c| exact(c.end()))
        && exact(reference.start)
        && reference.vertices.iter().all(|&p| exact(p))
}

/// [`misplaced_pixels`] of the path moved by `shift` px sideways, then by `-shift`: the
/// pixels the first move that misplaces any gets wrong (empty when neither does).
fn misplaced_when_moved(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    shift: f64,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Vec<Pixel> {
    for d in [shift, -shift] {
        let v = kurbo::Vec2::new(d, 0.0);
        let moved: Vec<PathCommand> = commands.iter().map(|c| c.translated(v)).collect();
        let wrong = misplaced_pixels(reference, start + v, &moved, clipping, canvas);
        if !wrong.is_empty() {
            return wrong;
        }
    }
    Vec::new()
}

/// The path with its curves flattened within [`FINE_FLATTENING`]: what a renderer more
/// precise than tiny-skia draws. A path both this and tiny-skia's chords draw exactly is
/// drawn exactly by renderers in between (Skia's versions in browsers subdivide curves a
/// little differently), not only by tiny-skia. `None` when the path has no curve.
pub(crate) fn finely_flattened(start: Point, commands: &[PathCommand]) -> Option<Vec<PathCommand>> {
    if !has_curves(commands) {
        return None;
    }
    let mut out = Vec::with_capacity(commands.len() * 4);
    let mut path = kurbo::BezPath::new();
    path.move_to(start);
    let mut pen = start;
    for c in commands {
        c.push_path_els(pen, &mut path);
        pen = c.end();
    }
    kurbo::flatten(path, FINE_FLATTENING, |el| {
        if let kurbo::PathEl::LineTo(p) = el {
            out.push(PathCommand::Line(p));
        }
    });
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A polygon of lines through `points` (px, plus `off`), its start the first.
    fn polygon(points: &[(i32, i32)], off: f64) -> (Point, Vec<PathCommand>) {
        let p = |&(x, y): &(i32, i32)| Point::new(f64::from(x) / 4.0 + off, f64::from(y) / 4.0);
        let commands = points[1..]
            .iter()
            .map(|q| PathCommand::Line(p(q)))
            .collect();
        (p(&points[0]), commands)
    }

    proptest! {
        /// Lines on the grid whose moved windows differ (along pixel edges, as specks and
        /// pixel art are drawn) are checked in one scan of the least window holding the
        /// three, and give what three fills in their own windows give.
        #[test]
        fn lines_moved_in_a_shared_window_fill_as_in_their_own(
            path in prop::collection::vec((0i32..48, 0i32..48), 3..9),
            refp in prop::collection::vec((0i32..12, 0i32..12), 3..8),
            off in prop::sample::select(vec![0.0, 3.0, 0.25, 1.0 / 64.0]),
            k in 1u8..3,
        ) {
            let (start, commands) = polygon(&path, off);
            let (rs, rc) = polygon(&refp.iter().map(|&(x, y)| (4 * x, 4 * y)).collect::<Vec<_>>(), 0.0);
            let reference = Reference::new(rs, &rc);
            let shift = f64::from(k) / 64.0;
            let (one_scan, each) = (
                misplaced_moved_then_plain(&reference, start, &commands, shift, EdgeClipping::Never, None),
                {
                    let moved = misplaced_when_moved(&reference, start, &commands, shift, EdgeClipping::Never, None);
                    if moved.is_empty() {
                        misplaced_pixels(&reference, start, &commands, EdgeClipping::Never, None)
                    } else {
                        moved
                    }
                },
            );
            prop_assert_eq!(one_scan, each);
        }
    }

    #[test]
    fn a_speck_moved_shares_one_window() {
        // A pixel's square: moved left, its window starts a pixel further left.
        let start = Point::new(3.0, 3.0);
        let square = [(4.0, 3.0), (4.0, 4.0), (3.0, 4.0), (3.0, 3.0)]
            .map(|(x, y)| PathCommand::Line(Point::new(x, y)));
        let nothing = Reference::new(start, &[]);
        let shift = super::super::ROBUST_SHIFT;
        let (win, modes) = moved_window(&nothing, start, &square, shift, EdgeClipping::Never, None)
            .expect("one window");
        assert_eq!(modes, &[false]);
        // It holds the three windows.
        let path = PathBounds::of(start, &square);
        for d in [0.0, shift, -shift] {
            let (own, _) =
                fill_window_moved(&nothing, &path, d, false, EdgeClipping::Never, None).unwrap();
            assert!(own.is_in(win));
        }
        // Not on the grid: each in its own window.
        let off = square.map(|c| c.translated(kurbo::Vec2::new(0.001, 0.0)));
        assert!(moved_window(&nothing, start, &off, shift, EdgeClipping::Never, None).is_none());
        // The square paints its pixel, moved either way too.
        assert!(!loop_paints_nothing(
            start,
            &square,
            EdgeClipping::Never,
            None,
            true
        ));
        assert!(
            moved_draw_right(&nothing, start, &square, shift, EdgeClipping::Never, None)
                == Some(false)
        );
    }
}
