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
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// Whether the closed loop `M anchor lp Z` paints no pixel centre: filled by tiny-skia alone,
/// in a window of its own and in Chromium's tiles ([`super::tiles`]); when `robust`, also
/// moved by [`super::ROBUST_SHIFT`] sideways (first: where the plain fill is wrong the moved
/// one mostly is too) and with its curves finely flattened ([`finely_flattened`]). A change
/// to a path whose loop (the new commands, then the old ones backwards) paints nothing
/// changes no pixel: tiny-skia and Skia sum each edge's crossings by itself, and a command
/// drawn both ways cancels.
pub(crate) fn loop_paints_nothing(
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
/// share ([`fill_window_moved`]); `None` when they differ or nothing of the path as it is
/// is drawn (the caller fills the three one by one).
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
    let shared = window(0.0)?;
    (window(shift)? == shared && window(-shift)? == shared).then_some(shared)
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
        for el in c.to_path_els(pen) {
            path.push(el);
        }
        pen = c.end();
    }
    kurbo::flatten(path, FINE_FLATTENING, |el| {
        if let kurbo::PathEl::LineTo(p) = el {
            out.push(PathCommand::Line(p));
        }
    });
    Some(out)
}
