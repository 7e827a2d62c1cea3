//! Fewer commands along smooth stretches: a run of consecutive commands (the polygons that
//! replaced curves, the cubics through them) drawn as one cubic that the renderer draws the
//! same.
//!
//! A crack of the contour lies between a pixel centre of the shape and one of the
//! background; a curve separates the two when it crosses the segment between them. So the
//! cubic `B` from `A` to `E` that replaces a run must pass each crack's middle `T` within
//! `tol = ½ |sin θ|` px across the curve (θ between the curve and that segment; a glancing
//! crossing leaves little room), and so must the `N = 2^k` chords tiny-skia and Skia draw it
//! with, between its points at `t = i / N` (`k` from how far its control points stray from
//! its chord, [`chord_shift`]). Both are linear in the control points `P1`, `P2`:
//!
//! ```text
//! B(u)  = (1−u)³ A + 3u(1−u)² P1 + 3u²(1−u) P2 + u³ E,
//! Bₙ(u) = (1 − f) B(i/N) + f B((i+1)/N),   i + f = u N,
//! min over P1, P2 of  max over the cracks of  |n · (B(u) − T)| / tol,  |n · (Bₙ(u) − T)| / tol,
//! ```
//!
//! (`n` the normal of the contour there, `u` the crack's parameter on the curve), which a
//! few rounds of Lawson's reweighted least squares approach ([`Fit::fit`]); the parameters are
//! then moved to the cracks' nearest points on the curve and the chord count updated, and
//! the cubic fitted again. A fit that stays within every tolerance is snapped to the grid
//! and kept only where it changes no pixel, as [`super::smooth`]'s crossing cubics are: the
//! loop from the cubic back along the run paints nothing, also moved by 1/64 px, in
//! Chromium's tiles, finely flattened, and with the control points moved by 1/32 px (Skia's
//! fixed point); its chord estimate, and those of the parts the renderers cut it into (at
//! its extrema and at the sides of Chromium's tiles, see [`super::chops`]), are clear of
//! the bounds where the renderer would draw a different number of chords, and it does not
//! loop. Runs turn by at most
//! [`super::smooth::MAX_TURN_DEGREES`] at each vertex, so no corner of the shape is rounded,
//! and the path is first made to start at its sharpest corner (runs do not wrap round its
//! start). From each command on, runs are fitted one command longer while they fit; the
//! longest that fit are checked in the renderer first, then shorter ones. A fit is refitted
//! until it is within every tolerance and drawn in the chords it was fitted with, at most
//! [`FIT_ROUNDS`] times.

use super::builder::{on_segment, Builder};
use super::chops::drawn_parts;
use super::cracks::Cracks;
use super::cubic_fit::{reparametrize, Fit, Sample};
use super::render_check::{EdgeClipping, PathBounds};
use super::robust::{cubic_paints_nothing, loop_paints_nothing};
use super::smooth::{chord_estimate, MAX_TURN_DEGREES};
use super::tiles::{cutting_clips, loop_paints_nothing_in_tiles_moved};
use crate::curve::PathCommand;
use kurbo::{CubicBez, Point, Vec2};

/// Most commands one cubic replaces: bounds the loops' length and the fits' work. 6 and 8
/// gave byte-identical SVGs (43 images, four models, 400² noise, colour, smooth; an
/// observation, not a guarantee), 6 with 1% fewer instructions; 12 the same commands as 8,
/// 5 two commands more (27 shared samples, conic; measured when the lengths tried from a
/// command were doubled while they fit, then bisected).
///
/// The lengths are now tried one longer at a time. Doubling tried four commands after two
/// that fit, and mostly in vain: the starts where two fit and then neither four nor three
/// took 35% of the fits' work (by run length, 26 small shared samples, conic). In order,
/// 35 commands more (8 321), 712 bytes more, 4.0% fewer instructions; also across a step
/// where a run up to it does not fit ([`MAX_STEP`]), 5 commands more than doubling (8 291),
/// 86 bytes more, 3.1% fewer instructions, and no notch where a step ends a run.
const MAX_RUN: usize = 6;

/// Longest command (px, end to end) that is a step of the contour: a run that does not fit
/// up to one is tried across it too (see [`absorb_runs`]). A pixel's side, or its diagonal.
const MAX_STEP: f64 = 1.5;

/// Runs that fit, from one command on, checked in the renderer (longest first; 27 shared
/// samples, conic: 7 811 drawing commands checking one, 7 639 checking three).
const MAX_CHECKED: usize = 3;

/// How far (1/64 px) a cubic's chord estimate must stay from a bound where the renderer
/// changes its number of chords: Skia rounds the control points a little differently.
const CHORD_MARGIN: i64 = 8;

/// How far (1/64 px) the chord estimate of a part of a cubic, cut at an extremum or a
/// clip, must stay from a bound of [`chord_shift`]: the renderers compute the cut in
/// different floating point (the part that cost 2 pixels in Chromium, sil_kangaroo, was at
/// the bound). A smaller margin than the whole cubic's [`CHORD_MARGIN`]: 27 shared samples,
/// conic, 8 621 commands with 2, 8 688 with 8.
const PART_MARGIN: i64 = 2;

/// Commands shorter than this (px) from end to end have no direction of their own: the turn
/// across them is measured between their neighbours.
const MIN_DIRECTED: f64 = 1.0;

/// Cracks whose tolerance is below this (px: the contour runs nearly along the segment
/// between their pixel centres) are left out of the fit; the renderer check sees them.
const MIN_TOLERANCE: f64 = 0.02;

/// How many chords (`2^shift`) tiny-skia and Skia cut a y-monotonic cubic into, from its
/// [`chord_estimate`] `d` in 1/64 px (`diff_to_shift(dx, dy, 2) + 1` of their `edge.rs`,
/// capped at 6): two below 48, four below 240, eight below 1008, and so on.
fn chord_shift(d: i64) -> u32 {
    let dist = (d.max(0) + 16) >> 5;
    (((64 - dist.leading_zeros()) >> 1) + 1).min(6)
}

/// Whether `d` lies at least `margin` from a bound of [`chord_shift`].
fn clear_of_bounds(d: i64, margin: i64) -> bool {
    chord_shift(d - margin) == chord_shift(d + margin)
}

/// The start and end directions of a command from `from`; `None` for one shorter than
/// [`MIN_DIRECTED`].
fn directions(from: Point, c: &PathCommand) -> Option<(Vec2, Vec2)> {
    let end = c.end();
    if (end - from).hypot() < MIN_DIRECTED {
        return None;
    }
    let unit = |v: Vec2| {
        let h = v.hypot();
        (h > 1e-9).then(|| v / h)
    };
    let (first, last) = match *c {
        PathCommand::Line(_) => (end, from),
        PathCommand::Quad(q, _) => (q, q),
        PathCommand::Cubic(p1, p2, _) => (
            if p1 == from { p2 } else { p1 },
            if p2 == end { p1 } else { p2 },
        ),
        PathCommand::Arc(_) => return None,
    };
    Some((unit(first - from)?, unit(end - last)?))
}

/// The loop from `a` along `cubic`, then back along `cmds` (from `a`) to `a`.
fn difference_loop(a: Point, cubic: PathCommand, cmds: &[PathCommand]) -> Vec<PathCommand> {
    let mut lp = Vec::with_capacity(cmds.len() + 1);
    lp.push(cubic);
    for (i, c) in cmds.iter().enumerate().rev() {
        // Where command `i` starts.
        let from = match i {
            0 => a,
            _ => cmds[i - 1].end(),
        };
        lp.push(match *c {
            PathCommand::Quad(q, _) => PathCommand::Quad(q, from),
            PathCommand::Cubic(p1, p2, _) => PathCommand::Cubic(p2, p1, from),
            _ => PathCommand::Line(from),
        });
    }
    lp
}

/// The cubic from `a` through the cracks `cmds` passes (see the module documentation),
/// snapped to the grid, before the renderer check. Returns `None` when no cubic found
/// passes every crack within its tolerance, or it loops, or its chord count is uncertain.
fn fitted_cubic(
    a: Point,
    cmds: &[PathCommand],
    cracks: &Cracks,
    snap: &Builder,
) -> Option<PathCommand> {
    let e = cmds.last()?.end();
    // The run's length along its control polygons (at least its curves' length).
    let mut run_length = 0.0;
    let mut pen = a;
    for c in cmds {
        run_length += match *c {
            PathCommand::Quad(q, e) => (q - pen).hypot() + (e - q).hypot(),
            PathCommand::Cubic(p1, p2, e) => {
                (p1 - pen).hypot() + (p2 - p1).hypot() + (e - p2).hypot()
            }
            _ => (c.end() - pen).hypot(),
        };
        pen = c.end();
    }
    // A crack path is at most √2 times as long as the curve it follows.
    let max_steps = (1.5 * run_length) as usize + 3;
    let target = cracks.between(a, e, max_steps)?;
    let mut lengths = Vec::with_capacity(target.len());
    let mut total = 0.0;
    for w in target.windows(2) {
        total += (w[1] - w[0]).hypot();
        lengths.push(total);
    }
    if total < 2.0 * MIN_DIRECTED {
        return None;
    }
    // The cracks' middles, at their fraction of the run's length; the contour's direction
    // there from four cracks before to four after.
    let last = target.len() - 1;
    let mut samples: Vec<Sample> = Vec::with_capacity(last);
    samples.extend((1..last).filter_map(|k| {
        let p = target[k];
        let along = target[(k + 4).min(last)] - target[k.saturating_sub(4)];
        let along = along / along.hypot().max(1e-9);
        // The segment between the pixel centres beside the crack.
        // (Crack middles are on the half-pixel grid: the test is exact.)
        let across = if p.y == p.y as i64 as f64 {
            Vec2::new(0.0, 1.0)
        } else {
            Vec2::new(1.0, 0.0)
        };
        let tol = 0.5 * along.cross(across).abs();
        (tol >= MIN_TOLERANCE).then_some(Sample {
            u: lengths[k - 1] / total,
            u0: lengths[k - 1] / total,
            t: p,
            normal: Vec2::new(-along.y, along.x),
            tol,
        })
    }));
    // First the curve alone, by plain least squares: a start for the chord count.
    let mut fits = Fit::new(a, e, &samples);
    let (mut control, first) = fits.fit(&samples, 0, 1)?;
    if first > GIVE_UP_FIRST {
        return None;
    }
    let mut chords = 0;
    let mut worst = f64::INFINITY;
    // Fitted again with the chords of the last fit, at the curve's nearest parameters.
    for round in 0..FIT_ROUNDS {
        chords = 1u32 << chord_shift(chord_estimate(a, control[0], control[1], e));
        reparametrize(
            &CubicBez::new(a, control[0], control[1], e),
            &mut samples,
            round == 0,
        );
        (control, worst) = fits.fit(&samples, chords, LAWSON_SCHEDULE[round])?;
        if GIVE_UP.get(round).is_some_and(|&limit| worst > limit) {
            return None;
        }
        // Settled: within every tolerance, and drawn in the chords it was fitted with.
        if worst <= MAX_WORST
            && 1u32 << chord_shift(chord_estimate(a, control[0], control[1], e)) == chords
        {
            break;
        }
    }
    if worst > MAX_WORST {
        return None;
    }
    let [p1, p2] = [snap.snap(control[0]), snap.snap(control[1])];
    let d = chord_estimate(a, p1, p2, e);
    if 1u32 << chord_shift(d) != chords || !clear_of_bounds(d, CHORD_MARGIN) {
        return None;
    }
    // Control points ahead of the ends along the chord, within its reach: the cubic does not
    // loop.
    let chord = e - a;
    let reach = chord.hypot();
    if (p1 - a).dot(chord) <= 0.0
        || (e - p2).dot(chord) <= 0.0
        || (p1 - a).hypot() >= reach
        || (e - p2).hypot() >= reach
    {
        return None;
    }
    Some(PathCommand::Cubic(p1, p2, e))
}

/// Largest ratio of a fit's distance to a crack's middle to its tolerance: a margin for
/// renderers that cut curves a little differently from tiny-skia.
const MAX_WORST: f64 = 1.0;

/// Rounds of [`fitted_cubic`]'s fit after the first, at most: a fit within every tolerance
/// whose chord count stays is not refitted (27 shared samples, conic, with the runs checked
/// shorter: 8 715 commands after two rounds, 8 621 after three, 8 594 after four for 4%
/// more instructions; refitting settled fits too gave 8 752).
const FIT_ROUNDS: usize = 3;

/// Rounds of Lawson's reweighting ([`Fit::fit`]) in each round of [`fitted_cubic`]'s fit. The
/// best of a fit's first few rounds is kept, and few rounds do best (27 shared samples,
/// conic, the same number in every round: 7 904 drawing commands after one, 7 566 after
/// three, 7 742 after thirty: the later rounds' fits lean on fewer cracks and pass the
/// renderer check less often). The first round's fit mostly sets the chord count and the
/// parameters of the next, and the last decides:
/// 27 shared samples, conic, against three rounds each (8 355 commands, 180 848 bytes):
/// `[2, 2, 4]` 8 318 commands, 181 628 bytes, 1.7% fewer instructions; `[2, 3, 4]` 8 313,
/// 180 980, 0.8% fewer; `[2, 2, 3]` 8 326, 181 757, 2.3% fewer. 0 px in resvg for each.
/// One round first (plain least squares; `[1, 2, 4]`: 8 316 commands, 3.1% fewer) settles
/// fits that pass every crack off the true curve: 0.61 px off a disc of radius 6 drawn as
/// one circle piece (`tests/svg_fidelity.rs`, at most 0.55).
const LAWSON_SCHEDULE: [usize; FIT_ROUNDS] = [2, 2, 4];

/// A first fit (plain least squares, the curve alone) this far beyond its tolerances is
/// given up: the rounds after it never brought one from beyond 2.5 within them (27 shared
/// samples, conic: the same 8 529 commands for 1.2% fewer instructions at 2.5 and 0.8%
/// at 3; 8 531 at 2). Then 3; with the runs tried one longer at a time, 1.5: 14 commands
/// more (8 305), 197 bytes more, 1.6% fewer instructions (2 and 1.75 gave 0.4% and 0.7%
/// for 3 and 4 commands more).
const GIVE_UP_FIRST: f64 = 1.5;

/// A fit this far beyond its tolerances after the round of its index, before the last, is
/// given up. 2 after the first round saved 2% of the instructions for 5 commands more over
/// the 27 shared samples. After the second round few fits still come within their
/// tolerances: on the 3000² sample 16 of the 1 429 beyond 1.2 (63 of 2 069 after the first
/// round); 27 shared samples, conic, 1.2 there instead of 2: 2.0% fewer instructions for 2
/// commands more (8 355), 1.1: 2.7% and 7 more, 1.3: 1.4% and 2 more.
const GIVE_UP: [f64; FIT_ROUNDS - 1] = [2.0, 1.2];

/// Whether drawing `cubic` from `a` instead of `cmds` changes no pixel, also with its
/// control points moved by [`super::robust::NUDGE`] (see the module documentation).
fn changes_nothing(
    a: Point,
    cubic: PathCommand,
    cmds: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<kurbo::Rect>,
) -> bool {
    let PathCommand::Cubic(p1, p2, e) = cubic else {
        return false;
    };
    // Every part the renderers draw in chords of its own has a chord estimate clear of the
    // bounds where their number changes (see `chops`): cut at its extrema, and where the
    // document's edge or one of Chromium's tiles clips it.
    let bez = CubicBez::new(a, p1, p2, e);
    let clear = |parts: Vec<CubicBez>, origin: Point| {
        let o = origin.to_vec2();
        parts.iter().all(|q| {
            clear_of_bounds(
                chord_estimate(q.p0 - o, q.p1 - o, q.p2 - o, q.p3 - o),
                PART_MARGIN,
            )
        })
    };
    let bounds = kurbo::Rect::from_points(a, e).union_pt(p1).union_pt(p2);
    let clips = cutting_clips(bounds, canvas);
    if !clear(drawn_parts(bez, None), Point::ZERO)
        || (clipping != EdgeClipping::Never
            && !clear(drawn_parts(bez, canvas.or(Some(bounds))), Point::ZERO))
        || !clips
            .iter()
            .all(|clip| clear(drawn_parts(bez, Some(*clip)), clip.origin()))
    {
        return false;
    }
    // Then the pixels: the loop from the cubic back along the run paints nothing, also
    // moved (up and down too where a tile cuts the cubic), and with the control points
    // nudged.
    (clips.is_empty()
        || loop_paints_nothing_in_tiles_moved(a, &difference_loop(a, cubic, cmds), canvas))
        && cubic_paints_nothing(cubic, |c, robust| {
            loop_paints_nothing(a, &difference_loop(a, c, cmds), clipping, canvas, robust)
        })
}

/// The line from `a` to the end of `cubic` when `cubic` is straight: both control points
/// exactly on the segment between its ends (all on the grid, so the test is exact). Returns
/// `None` for any other command.
fn straight(a: Point, cubic: PathCommand) -> Option<PathCommand> {
    let PathCommand::Cubic(p1, p2, e) = cubic else {
        return None;
    };
    ((e - a).hypot2() > 0.0 && on_segment(a, e, p1) && on_segment(a, e, p2))
        .then_some(PathCommand::Line(e))
}

/// Whether drawing `line` from `a` instead of `cmds` changes no pixel: the loop from the
/// line back along the run paints nothing, robustly and in Chromium's tiles, as a merge of
/// lines is checked ([`super::merge`]).
fn line_changes_nothing(
    a: Point,
    line: PathCommand,
    cmds: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<kurbo::Rect>,
) -> bool {
    let lp = difference_loop(a, line, cmds);
    // (The line ends where the run does: the run's bounds are the loop's.)
    let PathBounds { lo, hi } = PathBounds::of(a, cmds);
    (cutting_clips(kurbo::Rect::from_points(lo, hi), canvas).is_empty()
        || loop_paints_nothing_in_tiles_moved(a, &lp, canvas))
        && loop_paints_nothing(a, &lp, clipping, canvas, true)
}

/// The closed path `M start commands Z` with runs of two or more commands along gentle turns
/// drawn as one cubic each where that changes no pixel (see the module documentation); the
/// start vertex stays. Returns `None` if no run is replaced.
pub(crate) fn absorb_runs(
    start: Point,
    commands: &[PathCommand],
    cracks: &Cracks,
    grid: u8,
    clipping: EdgeClipping,
    canvas: Option<kurbo::Rect>,
) -> Option<(Point, Vec<PathCommand>)> {
    let n = commands.len();
    if n < 3 {
        return None;
    }
    let vertex = |j: usize| if j == 0 { start } else { commands[j - 1].end() };
    let mut dirs: Vec<Option<(Vec2, Vec2)>> = (0..n)
        .map(|j| directions(vertex(j), &commands[j]))
        .collect();
    // The path starts at its sharpest corner, which no run crosses anyway (when it is
    // closed by its last command, not by `Z` alone; each command keeps its start, so its
    // directions stay).
    let closed = commands[n - 1].end() == start;
    let sharpest = if closed {
        let turn = |j: usize| match (dirs[(j + n - 1) % n], dirs[j]) {
            (Some((_, inc)), Some((out, _))) => inc.dot(out),
            _ => 1.0,
        };
        (0..n)
            .min_by(|&i, &k| turn(i).total_cmp(&turn(k)))
            .unwrap_or(0)
    } else {
        0
    };
    let start = vertex(sharpest);
    let mut commands = commands.to_vec();
    commands.rotate_left(sharpest);
    dirs.rotate_left(sharpest);
    let commands = &commands[..];
    let snap = Builder::new(grid);
    let vertex = |j: usize| if j == 0 { start } else { commands[j - 1].end() };
    let cos_max = MAX_TURN_DEGREES.to_radians().cos();
    let mut out = Vec::with_capacity(n);
    let mut j = 0;
    let mut any = false;
    while j < n {
        // The longest run from `j` allowed: gentle turns, no arc, at least two commands
        // left.
        let mut limit = 1;
        let mut heading = dirs[j].map(|d| d.1);
        while limit < MAX_RUN && j + limit < n && limit + 2 <= n {
            let k = j + limit;
            if matches!(commands[k], PathCommand::Arc(_)) {
                break;
            }
            if let Some((first, last)) = dirs[k] {
                if heading.is_some_and(|h| h.dot(first) < cos_max) {
                    break;
                }
                heading = Some(last);
            }
            limit += 1;
        }
        // The runs from `j` tried, (length, cubic if it fits), longer by one command while
        // they fit: the cubics kept are mostly of two or three commands, and a longer run
        // rarely fits where a shorter one does not.
        let fit = |len: usize| {
            (dirs[j..j + len].iter().any(Option::is_some))
                .then(|| fitted_cubic(vertex(j), &commands[j..j + len], cracks, &snap))
                .flatten()
        };
        let mut tried: Vec<(usize, Option<PathCommand>)> = Vec::new();
        let mut len = 2;
        while len <= limit {
            let mut cubic = fit(len);
            tried.push((len, cubic));
            // Where two commands do not fit, or the run ends on a step (a command of at
            // most [`MAX_STEP`]), one more is tried too: a cubic across a step often fits
            // where none up to it does, and without it the step stays a notch.
            let k = j + len - 1;
            let step = (commands[k].end() - vertex(k)).hypot2() <= MAX_STEP * MAX_STEP;
            if cubic.is_none() && len < limit && (len == 2 || step) {
                len += 1;
                cubic = fit(len);
                tried.push((len, cubic));
            }
            if cubic.is_none() {
                break;
            }
            len += 1;
        }
        // The longest first; where they change pixels, shorter ones, down to two commands,
        // [`MAX_CHECKED`] in all.
        let best = tried
            .iter()
            .rev()
            .filter_map(|&(len, c)| Some((len, c?)))
            .take(MAX_CHECKED)
            .find(|&(len, c)| {
                changes_nothing(vertex(j), c, &commands[j..j + len], clipping, canvas)
            });
        match best {
            Some((len, c)) => {
                // A straight cubic is written as its line where that changes no pixel
                // either (fewer bytes, and no curve where there is none).
                let c = straight(vertex(j), c)
                    .filter(|&line| {
                        line_changes_nothing(
                            vertex(j),
                            line,
                            &commands[j..j + len],
                            clipping,
                            canvas,
                        )
                    })
                    .unwrap_or(c);
                out.push(c);
                j += len;
                any = true;
            }
            None => {
                out.push(commands[j]);
                j += 1;
            }
        }
    }
    any.then_some((start, out))
}

#[cfg(test)]
mod tests {
    use super::super::render_check::{misplaced_pixels, Reference};
    use super::super::{contour_path, cracks_path, merge_lines, OutlineOptions, ROBUST_SHIFT};
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose, OutlierRule};
    use crate::model::Model;
    use proptest::prelude::*;

    #[test]
    fn a_straight_cubic_is_its_line() {
        let p = Point::new;
        let a = p(40.0, 7.0);
        // A one-pixel column's side as `absorb` once wrote it: `c0-1 0-2 0-3`.
        let column = PathCommand::Cubic(p(40.0, 6.0), p(40.0, 5.0), p(40.0, 4.0));
        assert_eq!(straight(a, column), Some(PathCommand::Line(p(40.0, 4.0))));
        // Slanted, control points at the ends: straight too.
        let slanted = PathCommand::Cubic(a, p(46.0, 10.0), p(46.0, 10.0));
        assert_eq!(straight(a, slanted), Some(PathCommand::Line(p(46.0, 10.0))));
        // A control point off the chord by 1/16 px, or on its line beyond an end: a curve.
        let off = PathCommand::Cubic(p(40.0625, 6.0), p(40.0, 5.0), p(40.0, 4.0));
        assert_eq!(straight(a, off), None);
        let beyond = PathCommand::Cubic(p(40.0, 8.0), p(40.0, 5.0), p(40.0, 4.0));
        assert_eq!(straight(a, beyond), None);
        // Not a cubic, or no length.
        assert_eq!(straight(a, PathCommand::Line(p(41.0, 7.0))), None);
        assert_eq!(straight(a, PathCommand::Cubic(a, a, a)), None);
    }

    #[test]
    fn chord_counts_are_tiny_skias() {
        // (estimate, shift) at the bounds of tiny-skia's `diff_to_shift(dx, dy, 2) + 1`.
        for (d, shift) in [
            (0, 1),
            (47, 1),
            (48, 2),
            (239, 2),
            (240, 3),
            (1007, 3),
            (1008, 4),
            (4079, 4),
            (4080, 5),
            (16367, 5),
            (16368, 6),
            (1 << 40, 6),
        ] {
            assert_eq!(chord_shift(d), shift, "estimate {d}");
        }
        assert!(
            !clear_of_bounds(44, CHORD_MARGIN)
                && !clear_of_bounds(245, CHORD_MARGIN)
                && clear_of_bounds(100, CHORD_MARGIN)
        );
    }

    /// A mask of the ellipse with half-axes `rx`, `ry` turned by `angle`, centred at `c`.
    fn ellipse(rx: f64, ry: f64, angle: f64, c: (f64, f64)) -> Mask {
        let size = (2.0 * rx.max(ry) + 8.0).ceil() as u32;
        let mut m = Mask::new(size, size);
        let (s, k) = angle.sin_cos();
        for y in 0..size {
            for x in 0..size {
                let (dx, dy) = (f64::from(x) + 0.5 - c.0, f64::from(y) + 0.5 - c.1);
                let (u, v) = (k * dx + s * dy, -s * dx + k * dy);
                m.set(
                    i64::from(x),
                    i64::from(y),
                    (u / rx).powi(2) + (v / ry).powi(2) < 1.0,
                );
            }
        }
        m
    }

    /// Misplaced pixels of every contour's path of `mask` (conic), filled both ways, and
    /// unclipped when moved by ±1/64 px; and the number of commands.
    fn exactness(mask: &Mask) -> (usize, usize) {
        let d = decompose(
            trace(mask, Convention::Default),
            Model::Conic,
            OutlierRule::NotInPiece,
        );
        let basis = d.model.basis();
        let (mut bad, mut commands) = (0, 0);
        for (c, pieces) in d.contours.iter().zip(&d.pieces) {
            let cp = contour_path(c, pieces, &basis, &OutlineOptions::default());
            commands += cp.commands.len();
            let cracks = cracks_path(&c.points);
            for dx in [0.0, ROBUST_SHIFT, -ROBUST_SHIFT] {
                let v = Vec2::new(dx, 0.0);
                let moved = |cmds: &[PathCommand]| -> Vec<PathCommand> {
                    cmds.iter().map(|c| c.translated(v)).collect()
                };
                let reference = Reference::new(cracks.start + v, &moved(&cracks.commands));
                // Both ways of drawing curves in place; moved, the way a page's document
                // is drawn (as every contour is checked, see `contour_path`).
                let way = if dx == 0.0 {
                    EdgeClipping::Unknown
                } else {
                    EdgeClipping::Never
                };
                bad += misplaced_pixels(&reference, cp.start + v, &moved(&cp.commands), way, None)
                    .len();
            }
        }
        (bad, commands)
    }

    #[test]
    fn long_arcs_become_few_cubics() {
        // A large turned ellipse: its exact polygon is many digital straight segments; runs
        // of them become cubics that the renderer draws the same.
        let mask = ellipse(70.0, 41.0, 0.5, (74.3, 74.8));
        let d = decompose(
            trace(&mask, Convention::Default),
            Model::Conic,
            OutlierRule::NotInPiece,
        );
        let basis = d.model.basis();
        let c = &d.contours[0];
        let plain = OutlineOptions {
            merge_lines: false,
            ..OutlineOptions::default()
        };
        let cp = contour_path(c, &d.pieces[0], &basis, &plain);
        let merged = merge_lines(cp.start, &cp.commands, None, 4).unwrap_or(cp.commands.clone());
        let n = c.points.len();
        let cracks = Cracks::new(&super::super::crack_polyline(&c.points, 0, n - 1));
        let (start, absorbed) =
            absorb_runs(cp.start, &merged, &cracks, 4, EdgeClipping::Unknown, None)
                .expect("runs to absorb");
        // (23 commands become 15 here.)
        assert!(
            absorbed.len() + 4 <= merged.len(),
            "{} commands, {} before",
            absorbed.len(),
            merged.len()
        );
        let reference = cracks_path(&c.points);
        let reference = Reference::new(reference.start, &reference.commands);
        assert!(
            misplaced_pixels(&reference, start, &absorbed, EdgeClipping::Unknown, None).is_empty()
        );
        assert_eq!(exactness(&mask).0, 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// Whatever runs become cubics, the renderer draws every pixel of an ellipse right,
        /// also moved by 1/64 px.
        #[test]
        fn absorbing_changes_no_pixel(
            rx in 4.0f64..40.0, ry in 4.0f64..40.0, angle in 0.0f64..3.2,
            cx in 0.0f64..1.0, cy in 0.0f64..1.0,
        ) {
            let r = rx.max(ry);
            let mask = ellipse(rx, ry, angle, (r + 4.0 + cx, r + 4.0 + cy));
            prop_assert_eq!(exactness(&mask).0, 0);
        }
    }
}
