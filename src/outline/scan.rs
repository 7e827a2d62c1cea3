//! tiny-skia's fill of a path in its mask, without anti-aliasing, computed with tiny-skia's
//! own arithmetic but without its edge list, pipeline and mask: the render check's fills
//! ([`super::render_check::painted_in`]) but for arcs and absurd coordinates.
//!
//! Where tiny-skia clips the path (its bounds, rounded out, leave the mask, or curves are
//! drawn the clipped way), every edge goes through a port of its edge clipper first
//! ([`super::scan_edges`]).
//!
//! The edges' row crossings come from [`super::edges`], with tiny-skia's fixed point. The
//! scan walker (`walk_edges`) takes a row's edges by x and, for the nonzero rule,
//! paints the runs `[round(xa), round(xb))` over which the running sum of their windings
//! is not zero, `round` being `(x + 0x8000) >> 16`: pixel `i` of the row is painted exactly
//! when the windings of the edges with `round(x) ≤ i` do not sum to zero. (Merging vertical
//! lines at the same x, `combine_vertical`, keeps those sums.) So the painted pixels follow
//! from each edge's rows and rounded x alone. The tests below compare with tiny-skia's own
//! fills on random paths.

use super::edges::{Crossing, Crossings, Tag};
use super::render_check::{PathBounds, Reference, Window};
use super::scan_edges::{clips, contained, Draw, Moved, Stop, CUBIC, QUAD};
use crate::curve::PathCommand;
use kurbo::Point;
use tiny_skia_path::Point as SkPoint;

/// Largest window (pixels each way) filled here: tiny-skia draws a larger mask in pieces of
/// 8191 px (its `DrawTiler`), each with its own clip; and 16.16 coordinates stay far from
/// `i32`'s range.
const MAX_WINDOW: i64 = 8191;

/// The row-major indices, in the window `win`, of the pixels tiny-skia paints filling the
/// path `M start commands Z` followed by `reference` reversed (see
/// [`super::render_check::painted_in`]), curves drawn `clipped` or not. Where tiny-skia
/// clips the path ([`super::scan_edges::clips`], or `clipped`), each edge is clipped to
/// the window as its edge clipper clips it ([`super::line_clip`], [`super::curve_clip`]):
/// the path may leave the window (Chromium's tiles and the document's edge cut contours
/// so).
///
/// Returns `None` for an arc, a point (control points included) not finite or more than
/// [`MAX_CLIPPED`] px from the window's corner, a window over [`MAX_WINDOW`] pixels, and
/// where tiny-skia's edge clipper would panic (see [`super::curve_clip::clip_cubic`]).
pub(super) fn painted(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    clipped: bool,
) -> Option<Vec<usize>> {
    let [plain, _, _] = scanned(reference, start, commands, win, clipped, None)?;
    Some(plain)
}

/// [`painted`] three times from one set of edges: the path as it is, then moved by `shift`
/// px sideways, then by `−shift` (the reference stays), each in the same window `win` — as
/// three calls of [`painted`] with the moved paths give them, when the moved paths have that
/// window too.
///
/// A line moved by `k/64` px (`shift`; `k` whole) is the same edge `k/64` px aside: its ends
/// in 26.6 fixed point move by `k` exactly and its slope and rows stay, so each row crossing
/// moves by `k · 2^10` in 16.16. So does a quadratic or cubic that is not cut where it
/// turns (its forward differences are differences of its points), but one that is cut is
/// cut in `f32` at points whose rounding depends on where it lies: those are scanned once
/// for each fill. The reference's crossings are shared as they are.
///
/// The moved fills are scanned first, then the path as it is; with `first_only`, the first
/// that paints a pixel ends the scan (the fills after it are left empty).
///
/// Each fill is clipped where tiny-skia clips its path; an edge that a clipped fill cuts
/// (it comes within a pixel of the window's sides) or that the fills do not draw alike is
/// scanned once for each fill.
///
/// Returns `None` where [`painted`] would for any of the three paths, and when a moved
/// point is not the point moved exactly in `f32` (off the 1/64 grid, or `shift` not a
/// multiple of 1/64).
pub(super) fn painted_moved(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    clipped: bool,
    shift: f64,
    first_only: bool,
) -> Option<[Vec<usize>; 3]> {
    scanned(
        reference,
        start,
        commands,
        win,
        clipped,
        Some((shift, first_only)),
    )
}

/// [`painted`] (`shift` `None`: one fill, the other two empty) or [`painted_moved`], with
/// the thread's buffers.
fn scanned(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    clipped: bool,
    shift: Option<(f64, bool)>,
) -> Option<[Vec<usize>; 3]> {
    SCRATCH.with(|cell| {
        let mut scratch = cell.take();
        let (d, first_only) = shift.unwrap_or((0.0, false));
        let scan = Scan {
            reference,
            start,
            commands,
            win,
            clipped,
            shift: d,
            first_only,
        };
        let painted = match shift {
            None => painted_with::<1>(&mut scratch, scan),
            Some(_) => painted_with::<3>(&mut scratch, scan),
        };
        if scratch.out.capacity() <= MAX_KEPT {
            cell.replace(scratch);
        }
        painted
    })
}

/// Farthest a point of a path may lie from the window's corner (px) for the scan to clip
/// it: far from where tiny-skia gives up (bounds spanning about 2^31 px).
const MAX_CLIPPED: f64 = 1e9;

/// Most crossings whose buffers [`SCRATCH`] keeps: a huge contour's would hold their
/// memory to the end of the run.
const MAX_KEPT: usize = 1 << 16;

/// The buffers of [`painted`], reused by the next fill on the same thread (five
/// allocations per fill were 3% of the instructions on 400² noise).
#[derive(Default)]
struct Scratch {
    /// The crossings as the edges give them.
    out: Vec<Crossing>,
    /// Where each row's crossings start in `by_row` (one more than the rows).
    starts: Vec<usize>,
    /// The next free place of each row in `by_row`.
    next: Vec<usize>,
    /// `(x, winding, tag)` of the crossings, row by row.
    by_row: Vec<(i32, i8, Tag)>,
    /// One row's `(round(x), winding)` in one fill.
    line: Vec<(i32, i8)>,
}

thread_local! {
    /// The buffers of the last fill on this thread.
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// What [`painted_with`] scans.
struct Scan<'a> {
    reference: &'a Reference,
    start: Point,
    commands: &'a [PathCommand],
    win: &'a Window,
    /// Curves drawn the clipped way.
    clipped: bool,
    /// How far the moved fills move the path (px).
    shift: f64,
    /// Whether the first moved fill that paints a pixel ends the scan.
    first_only: bool,
}

/// [`scanned`] with the buffers of `scratch`: `FILLS` 1 (the path as it is) or 3 (also
/// moved by `±shift`). Each fill whose path tiny-skia clips ([`clips`]) has every edge
/// clipped as its edge clipper clips it ([`clip_line`], [`super::curve_clip`]), points
/// outside the window allowed.
fn painted_with<const FILLS: usize>(
    scratch: &mut Scratch,
    scan: Scan<'_>,
) -> Option<[Vec<usize>; 3]> {
    let Scan {
        reference,
        start,
        commands,
        win,
        clipped,
        shift,
        first_only,
    } = scan;
    let (w, h) = (win.x1 - win.x0, win.y1 - win.y0);
    if !(1..=MAX_WINDOW).contains(&w) || !(1..=MAX_WINDOW).contains(&h) {
        return None;
    }
    let (dx, dy) = (win.x0 as f64, win.y0 as f64);
    // The fills: the path as it is, then moved by ±shift (k/64 px, k · 2^10 in 16.16).
    let k64 = {
        let k = shift * 64.0;
        (k.fract() == 0.0 && k.abs() <= 64.0).then_some(k as i32)?
    };
    let d = [0.0, f64::from(k64) / 64.0, -f64::from(k64) / 64.0];
    let offsets = [0, k64 << 10, -(k64 << 10)];
    let (wf, hf) = (w as f32, h as f32);
    // As `difference_path` hands the points to tiny-skia (a moved path is moved first).
    // (Far within `f32`'s range: tiny-skia fills nothing where the path's bounds in whole
    // pixels overflow `i32`, or its coordinates are near `f32::MAX`.) With `guard`, a point
    // outside the region where tiny-skia leaves a path unclipped ([`contained`]) stops the
    // scan.
    let at = |p: Point, guard: bool| -> Result<SkPoint, Stop> {
        let (x, y) = (p.x - dx, p.y - dy);
        if !(x.abs() <= MAX_CLIPPED && y.abs() <= MAX_CLIPPED) {
            return Err(Stop::GiveUp);
        }
        let q = SkPoint::from_xy(x as f32, y as f32);
        if guard && !(contained(q.x, wf) && contained(q.y, hf)) {
            return Err(Stop::Clips);
        }
        Ok(q)
    };
    let moved = |p: Point, guard: bool| -> Result<Moved, Stop> {
        let plain = at(p, guard)?;
        let mut out = [plain; 3];
        for k in 1..FILLS {
            let x = (p.x + d[k]) - dx;
            if x.abs() > MAX_CLIPPED || f64::from(x as f32) != f64::from(plain.x) + d[k] {
                return Err(Stop::GiveUp);
            }
            out[k].x = x as f32;
            if guard && !contained(out[k].x, wf) {
                return Err(Stop::Clips);
            }
        }
        Ok(out)
    };
    // The edges of every fill, each fill clipped where `clip` says (one at least: scans that
    // clip none are `build_plain`'s).
    let build = |edges: &mut Crossings, clip: [bool; 3]| -> Result<(), Stop> {
        let draw = Draw::new(FILLS, clip, (wf, hf));
        let first = moved(start, false)?;
        let mut pen = first;
        for c in commands {
            pen = match *c {
                PathCommand::Line(p) => {
                    let q = moved(p, false)?;
                    draw.line(edges, [pen, q], Tag::SHARED);
                    q
                }
                PathCommand::Quad(a, p) => {
                    let (a, q) = (moved(a, false)?, moved(p, false)?);
                    if !draw.curve(edges, [pen, a, q], &QUAD) {
                        return Err(Stop::GiveUp);
                    }
                    q
                }
                PathCommand::Cubic(a, b, p) => {
                    let (a, b, q) = (moved(a, false)?, moved(b, false)?, moved(p, false)?);
                    if !draw.curve(edges, [pen, a, b, q], &CUBIC) {
                        return Err(Stop::GiveUp);
                    }
                    q
                }
                PathCommand::Arc(_) => return Err(Stop::GiveUp),
            };
        }
        draw.line(edges, [pen, first], Tag::SHARED);
        // The reference reversed: from its start through its vertices backwards, closed.
        let rstart = at(reference.start, false)?;
        let mut pen = rstart;
        for &p in reference.vertices.iter().rev() {
            let q = at(p, false)?;
            draw.line(edges, [[pen; 3], [q; 3]], Tag::FIXED);
            pen = q;
        }
        draw.line(edges, [[pen; 3], [rstart; 3]], Tag::FIXED);
        Ok(())
    };
    // The edges of every fill, none clipped, as directly as before the clipper's port: a
    // point that would make tiny-skia clip a fill stops the scan ([`Stop::Clips`]).
    let build_plain = |edges: &mut Crossings| -> Result<(), Stop> {
        let first = moved(start, true)?;
        let mut pen = first;
        for c in commands {
            pen = match *c {
                PathCommand::Line(p) => {
                    let q = moved(p, true)?;
                    edges.line(pen[0], q[0]);
                    q
                }
                PathCommand::Quad(a, p) => {
                    let (a, q) = (moved(a, true)?, moved(p, true)?);
                    edges.quad_in_fills(|k| [pen[k], a[k], q[k]], FILLS);
                    q
                }
                PathCommand::Cubic(a, b, p) => {
                    let (a, b, q) = (moved(a, true)?, moved(b, true)?, moved(p, true)?);
                    edges.cubic_in_fills(|k| [pen[k], a[k], b[k], q[k]], FILLS);
                    q
                }
                PathCommand::Arc(_) => return Err(Stop::GiveUp),
            };
        }
        edges.line(pen[0], first[0]);
        edges.tag = Tag::FIXED;
        let rstart = at(reference.start, true)?;
        let mut pen = rstart;
        for &p in reference.vertices.iter().rev() {
            let q = at(p, true)?;
            edges.line(pen, q);
            pen = q;
        }
        edges.line(pen, rstart);
        Ok(())
    };
    scratch.out.clear();
    let mut edges = Crossings {
        out: std::mem::take(&mut scratch.out),
        height: h as i32,
        tag: Tag::SHARED,
        x_chops: clipped,
    };
    // Drawn the clipped way, `mask_fill`'s sliver outside the mask makes tiny-skia clip
    // every fill. Else a fill is clipped where its path's bounds leave the mask: rarely, so
    // the edges are first built unclipped, and built again, each fill clipped where its
    // bounds say ([`clips`]), when a point lies where tiny-skia would clip.
    let built = if clipped {
        build(&mut edges, [true; 3])
    } else {
        match build_plain(&mut edges) {
            Err(Stop::Clips) => {
                edges.out.clear();
                edges.tag = Tag::SHARED;
                let PathBounds { lo, hi } = PathBounds::of(start, commands);
                let mut clip = [false; 3];
                for (k, c) in clip.iter_mut().enumerate().take(FILLS) {
                    let (lo, hi) = (Point::new(lo.x + d[k], lo.y), Point::new(hi.x + d[k], hi.y));
                    *c = clips(
                        [lo, hi, reference.lo, reference.hi]
                            .map(|p| SkPoint::from_xy((p.x - dx) as f32, (p.y - dy) as f32)),
                        (w, h),
                    );
                }
                build(&mut edges, clip)
            }
            built => built,
        }
    };
    built.ok()?;
    // By row (a counting sort: a large contour's crack polygon crosses thousands of rows a
    // few times each), then by x within each row.
    scratch.out = edges.out;
    let crossings = &scratch.out;
    let starts = &mut scratch.starts;
    starts.clear();
    starts.resize(h as usize + 1, 0);
    for c in crossings {
        starts[c.row as usize + 1] += 1;
    }
    // (The running sum in a register: adding to the entry just stored waited for it.)
    let mut sum = 0;
    for s in starts.iter_mut() {
        sum += *s;
        *s = sum;
    }
    let next = &mut scratch.next;
    next.clear();
    next.extend_from_slice(starts);
    // Every place below the crossings' count is written once: the buffer is only grown,
    // never cleared and zeroed again.
    let by_row = &mut scratch.by_row;
    if by_row.len() < crossings.len() {
        by_row.resize(crossings.len(), (0, 0, Tag(0)));
    }
    let by_row = &mut by_row[..crossings.len()];
    // One fill: each crossing rounded once, each row sorted in place.
    let round = |x: i32| x.wrapping_add(0x8000) >> 16;
    for c in crossings {
        let k = &mut next[c.row as usize];
        by_row[*k] = (if FILLS == 1 { round(c.x) } else { c.x }, c.winding, c.tag);
        *k += 1;
    }
    // Runs of each row in order: the indices come out sorted.
    let mut painted: [Vec<usize>; 3] = Default::default();
    if FILLS == 1 {
        for (row, span) in starts.windows(2).enumerate() {
            let crossings = &mut by_row[span[0]..span[1]];
            if !crossings.is_empty() {
                sort_row(crossings, |&(at, _, _)| at);
                let runs = crossings.iter().map(|&(at, winding, _)| (at, winding));
                paint_runs(runs, row * w as usize, w as i32, &mut painted[0]);
            }
        }
        return Some(painted);
    }
    // The moved fills first, each over every row: the first that paints a pixel may end
    // the check.
    let line = &mut scratch.line;
    for fill in [1, 2, 0] {
        let bit = 1 << fill;
        for (row, span) in starts.windows(2).enumerate() {
            let crossings = &by_row[span[0]..span[1]];
            if crossings.is_empty() {
                continue;
            }
            line.clear();
            for &(x, winding, tag) in crossings {
                if tag.0 & bit != 0 {
                    let x = if tag.0 & Tag::MOVES != 0 {
                        x.wrapping_add(offsets[fill])
                    } else {
                        x
                    };
                    line.push((round(x), winding));
                }
            }
            sort_row(line, |&(at, _)| at);
            paint_runs(
                line.iter().copied(),
                row * w as usize,
                w as i32,
                &mut painted[fill],
            );
        }
        if first_only && !painted[fill].is_empty() {
            break;
        }
    }
    Some(painted)
}

/// Appends to `painted` the pixels of one row (its first at `base`, `w` wide) over which the
/// running sum of the windings of its crossings `(round(x), winding)`, in order, is not
/// zero: tiny-skia's walker under the nonzero rule.
fn paint_runs(
    crossings: impl Iterator<Item = (i32, i8)>,
    base: usize,
    w: i32,
    painted: &mut Vec<usize>,
) {
    let mut winding = 0i32;
    let mut from = 0;
    for (at, wi) in crossings {
        if winding == 0 {
            from = at;
        }
        winding += i32::from(wi);
        if winding == 0 {
            let (a, b) = (from.clamp(0, w), at.clamp(0, w));
            painted.extend((a..b).map(|x| base + x as usize));
        }
    }
    // As the walker, a run still open at the row's end goes to the window's side (the
    // windings of a closed path's row sum to zero, so it does not happen).
    if winding != 0 {
        let a = from.clamp(0, w);
        painted.extend((a..w).map(|x| base + x as usize));
    }
}

/// Sorts one row's crossings by their pixel boundary `at` (the order of equal ones does not
/// change the runs): by insertion when there are few (most rows of a fill have two to six:
/// the call of `sort_unstable` cost more than the sorting, 1% of the 3000² sample's
/// instructions), else by `sort_unstable_by_key`.
fn sort_row<E: Copy>(line: &mut [E], at: impl Fn(&E) -> i32) {
    if line.len() > 12 {
        line.sort_unstable_by_key(at);
        return;
    }
    for i in 1..line.len() {
        let c = line[i];
        let mut j = i;
        while j > 0 && at(&line[j - 1]) > at(&c) {
            line[j] = line[j - 1];
            j -= 1;
        }
        line[j] = c;
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::render_check::{painted_by_tiny_skia, Reference, Window};
    use super::*;
    use proptest::prelude::*;

    /// A command from random numbers: a line, quadratic or cubic through points of
    /// `0..10 · scale` px (plus `off`) rounded to multiples of `1/grid`.
    fn command(kind: u8, v: [u16; 6], grid: f64, off: f64, scale: f64) -> PathCommand {
        let q = |a: u16, b: u16| {
            let r = |t: u16| (f64::from(t) / 6553.5 * scale * grid).round() / grid + off;
            Point::new(r(a), r(b))
        };
        match kind {
            0 => PathCommand::Line(q(v[0], v[1])),
            1 => PathCommand::Quad(q(v[0], v[1]), q(v[2], v[3])),
            _ => PathCommand::Cubic(q(v[0], v[1]), q(v[2], v[3]), q(v[4], v[5])),
        }
    }

    /// A random path from [`command`]s (its start a line's end) and a random crack-like
    /// reference through whole points moved by `off`.
    fn random_path(
        path: &[(u8, [u16; 6])],
        start: [u16; 2],
        refp: &[(i32, i32)],
        grid: f64,
        off: f64,
        scale: f64,
    ) -> (Point, Vec<PathCommand>, Reference) {
        let commands = path
            .iter()
            .map(|&(k, v)| command(k, v, grid, off, scale))
            .collect();
        let PathCommand::Line(start) =
            command(0, [start[0], start[1], 0, 0, 0, 0], grid, off, scale)
        else {
            unreachable!()
        };
        let r = |&(x, y): &(i32, i32)| Point::new(f64::from(x) + off, f64::from(y) + off);
        let rc: Vec<PathCommand> = refp[1..].iter().map(|p| PathCommand::Line(r(p))).collect();
        (start, commands, Reference::new(r(&refp[0]), &rc))
    }

    /// The row-major indices in `win` of the pixels tiny-skia itself paints filling the
    /// path and `reference` reversed, curves drawn `clipped` or not.
    pub(in crate::outline) fn tiny_skia_indices(
        reference: &Reference,
        start: Point,
        commands: &[PathCommand],
        win: &Window,
        clipped: bool,
    ) -> Vec<usize> {
        let w = (win.x1 - win.x0) as usize;
        painted_by_tiny_skia(reference, start, commands, win, &[clipped])
            .into_iter()
            .map(|p| (i64::from(p.y) - win.y0) as usize * w + (i64::from(p.x) - win.x0) as usize)
            .collect()
    }

    proptest! {
        /// A row comes out in order of its first field, the same crossings, short (by
        /// insertion) or long.
        #[test]
        fn rows_sort_by_their_boundaries(
            line in prop::collection::vec((-5i32..5, prop::sample::select(vec![-1i8, 1]), 0u8..3), 0..30),
        ) {
            let mut sorted = line.clone();
            sort_row(&mut sorted, |&(at, _, _)| at);
            prop_assert!(sorted.windows(2).all(|w| w[0].0 <= w[1].0));
            let (mut a, mut b) = (line, sorted.clone());
            a.sort_unstable();
            b.sort_unstable();
            prop_assert_eq!(a, b);
        }

        /// The same pixels as tiny-skia's own fill, curves drawn clipped or not, for random
        /// paths of lines, quadratics and cubics on the 1/64-px grid and off it, against
        /// random crack-like references; paths up to 3 000 px across reach every curve
        /// subdivision (up to 64 steps) and the long divisions.
        #[test]
        fn same_pixels_as_tiny_skia(
            path in prop::collection::vec((0u8..3, any::<[u16; 6]>()), 1..8),
            start in any::<[u16; 2]>(),
            refp in prop::collection::vec((0i32..10, 0i32..10), 3..8),
            grid in prop::sample::select(vec![1.0, 16.0, 64.0, 100.0, 1000.0]),
            off in prop::sample::select(vec![2.0, 2.3, 41.0]),
            clipped in any::<bool>(),
            scale in prop::sample::select(vec![1.0, 1.0, 30.0, 300.0]),
        ) {
            let (start, commands, reference) = random_path(&path, start, &refp, grid, off, scale);
            let win = Window::round(&reference, start, &commands);
            let ours = painted(&reference, start, &commands, &win, clipped).expect("inside");
            prop_assert_eq!(ours, tiny_skia_indices(&reference, start, &commands, &win, clipped));
        }
    }

    proptest! {
        /// Lines in windows that cut them, against tiny-skia's own fill, for random paths of
        /// lines on the 1/64-px grid and off it, and their references. Drawn plain, in a
        /// window that ends where they do (a contour along the document's edge): tiny-skia
        /// leaves them as they are. Drawn the clipped way (as in Chromium's tiles), in a
        /// window cutting them on any side: the scan clips each line as tiny-skia's edge
        /// clipper does.
        #[test]
        fn lines_cut_by_their_window_as_in_tiny_skia(
            path in prop::collection::vec(any::<[u16; 2]>(), 1..10),
            start in any::<[u16; 2]>(),
            refp in prop::collection::vec((0i32..40, 0i32..40), 3..10),
            grid in prop::sample::select(vec![1.0, 4.0, 64.0, 1000.0]),
            off in prop::sample::select(vec![2.0, 41.0]),
            scale in prop::sample::select(vec![12.0, 40.0, 300.0]),
            clipped in any::<bool>(),
            cut in any::<[u8; 4]>(),
        ) {
            let lines: Vec<(u8, [u16; 6])> = path.iter().map(|&[x, y]| (0, [x, y, 0, 0, 0, 0])).collect();
            let (start, commands, reference) = random_path(&lines, start, &refp, grid, off, scale);
            let round = Window::round(&reference, start, &commands);
            // Plain: the round window less its two spare pixels, whose sides touch the path
            // or the reference. Clipped: each side moved in by up to half the window.
            let (w, h) = (round.x1 - round.x0, round.y1 - round.y0);
            let inset = |c: u8, of: i64| if clipped { i64::from(c) * of / 512 } else { 2 };
            let win = Window {
                x0: round.x0 + inset(cut[0], w),
                y0: round.y0 + inset(cut[1], h),
                x1: round.x1 - inset(cut[2], w),
                y1: round.y1 - inset(cut[3], h),
            };
            prop_assume!(win.x0 < win.x1 && win.y0 < win.y1);
            let ours = painted(&reference, start, &commands, &win, clipped).expect("lines");
            prop_assert_eq!(ours, tiny_skia_indices(&reference, start, &commands, &win, clipped));
        }
    }

    proptest! {
        /// The three fills of one scan are the fills of the path as it is and moved by
        /// `±shift` in the same window, for random paths on the 1/64-px grid (curves cut
        /// where they turn included), clipped or not; with `first_only`, the same up to the
        /// first moved fill that paints, and nothing after it.
        #[test]
        fn moved_fills_are_the_moved_paths_fills(
            path in prop::collection::vec((0u8..3, any::<[u16; 6]>()), 1..8),
            start in any::<[u16; 2]>(),
            refp in prop::collection::vec((0i32..10, 0i32..10), 3..8),
            off in prop::sample::select(vec![2.0, 2.25, 41.0]),
            clipped in any::<bool>(),
            scale in prop::sample::select(vec![1.0, 1.0, 30.0, 300.0]),
            k in 1u8..3,
        ) {
            let (start, commands, reference) = random_path(&path, start, &refp, 64.0, off, scale);
            let win = Window::round(&reference, start, &commands);
            let shift = f64::from(k) / 64.0;
            let expected: Vec<Vec<usize>> = [0.0, shift, -shift]
                .iter()
                .map(|&d| {
                    let v = kurbo::Vec2::new(d, 0.0);
                    let moved: Vec<PathCommand> = commands.iter().map(|c| c.translated(v)).collect();
                    painted(&reference, start + v, &moved, &win, clipped).expect("inside")
                })
                .collect();
            let all = painted_moved(&reference, start, &commands, &win, clipped, shift, false)
                .expect("inside, on the grid");
            prop_assert_eq!(all.to_vec(), expected.clone());
            let first = painted_moved(&reference, start, &commands, &win, clipped, shift, true)
                .expect("inside, on the grid");
            let mut ended = false;
            for fill in [1, 2, 0] {
                if ended {
                    prop_assert!(first[fill].is_empty());
                } else {
                    prop_assert_eq!(&first[fill], &expected[fill]);
                    ended = !expected[fill].is_empty();
                }
            }
        }
    }

    /// A path's start at (5, 5) and a reference of one crack from it.
    fn one_crack() -> (Point, Reference) {
        let start = Point::new(5.0, 5.0);
        let reference = Reference::new(start, &[PathCommand::Line(Point::new(6.0, 5.0))]);
        (start, reference)
    }

    /// The window of `side` × `side` pixels at the origin.
    fn square(side: i64) -> Window {
        Window {
            x0: 0,
            y0: 0,
            x1: side,
            y1: side,
        }
    }

    #[test]
    fn moved_fills_need_a_shift_on_the_grid() {
        let (start, reference) = one_crack();
        let on = [
            PathCommand::Line(Point::new(6.0, 6.5)),
            PathCommand::Line(Point::new(5.0, 6.0)),
        ];
        let win = Window::round(&reference, start, &on);
        assert!(painted_moved(&reference, start, &on, &win, false, 1.0 / 64.0, false).is_some());
        // A shift off the grid moves edges by what 16.16 does not hold.
        assert!(painted_moved(&reference, start, &on, &win, false, 0.01, false).is_none());
    }

    #[test]
    fn lines_too_far_for_tiny_skia_are_left_to_it() {
        let (start, reference) = one_crack();
        let win = square(20);
        let path = |far: f64| {
            [
                PathCommand::Line(Point::new(-far, 12.0)),
                PathCommand::Line(Point::new(15.0, 18.0)),
            ]
        };
        // Clipped as tiny-skia clips it, a million pixels away; left to tiny-skia (which
        // fills nothing) three billion away.
        let near = path(1e6);
        let ours = painted(&reference, start, &near, &win, true).expect("clipped here");
        assert!(!ours.is_empty());
        assert_eq!(
            ours,
            tiny_skia_indices(&reference, start, &near, &win, true)
        );
        assert!(painted(&reference, start, &path(3e9), &win, true).is_none());
    }

    #[test]
    fn arcs_are_left_to_tiny_skia() {
        let (start, reference) = one_crack();
        let win = square(10);
        let inside = [PathCommand::Cubic(
            Point::new(6.0, 6.0),
            Point::new(2.0, 8.0),
            Point::new(5.0, 7.0),
        )];
        assert!(painted(&reference, start, &inside, &win, true).is_some());
        // A control point within a pixel of the window's side: tiny-skia clips it.
        let near = [PathCommand::Quad(
            Point::new(9.5, 6.0),
            Point::new(5.0, 7.0),
        )];
        assert_eq!(
            painted(&reference, start, &near, &win, false).expect("scanned"),
            tiny_skia_indices(&reference, start, &near, &win, false)
        );
        let arc = [PathCommand::Arc(kurbo::SvgArc {
            from: start,
            to: Point::new(5.0, 7.0),
            radii: kurbo::Vec2::new(1.0, 1.0),
            x_rotation: 0.0,
            large_arc: false,
            sweep: true,
        })];
        assert!(painted(&reference, start, &arc, &win, false).is_none());
    }
}
