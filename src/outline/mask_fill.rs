//! tiny-skia's own fill of a contour's path and its reference reversed, in a mask the size
//! of the render check's window (where [`super::scan`] does not apply: the path has arcs,
//! coordinates too far away, or a cubic on which tiny-skia's edge clipper panics), with the
//! masks' buffers reused.

use super::render_check::{Reference, Window};
use crate::curve::PathCommand;
use kurbo::Point;
use std::cell::RefCell;

thread_local! {
    /// Buffers of finished renders, reused by the next ones on the same thread. A contour's
    /// window is often above malloc's mmap threshold (128 KiB), and a fresh mapping costs a
    /// page fault per 4 KiB: 12% of the whole run on the shared samples before they were
    /// reused.
    static SPARE: RefCell<Vec<Vec<u8>>> = const { RefCell::new(Vec::new()) };
}

/// Most buffers kept per thread, and the largest kept (bytes): a huge contour's windows are
/// rare, and keeping them would hold their memory to the end of the run (at most 24 MiB
/// per thread).
const SPARE_COUNT: usize = 6;
const SPARE_MAX_BYTES: usize = 1 << 22;

/// How many times as long as asked a spare buffer may be and still be cut to the length
/// asked (else it stays for longer windows): a buffer cut short is zeroed again over the
/// rest of its length when it grows back, and a window of one of Chromium's 256-px tiles
/// after a small window re-zeroed up to 64 KiB (memset under `painted_in`: 42 M
/// instructions on the 3000² sample).
const SPARE_SLACK: usize = 4;

/// Spare buffers up to this length (bytes) are cut to any shorter length: zeroing them
/// again costs little.
const SPARE_SMALL: usize = 4096;

/// `len` zero bytes, in a reused buffer when one is spare. Spare buffers are zero over their
/// length (see [`take_painted`]), so only a longer tail is written. The buffer is the
/// shortest spare one at least `len` long and at most [`SPARE_SLACK`] times as long (or at
/// most [`SPARE_SMALL`] bytes), else the longest spare one shorter than `len`, grown, else a
/// fresh one (when every spare one is longer still, or there is none).
fn zeroed(len: usize) -> Vec<u8> {
    let spare = SPARE.with(|s| {
        let mut s = s.borrow_mut();
        let limit = len.saturating_mul(SPARE_SLACK).max(SPARE_SMALL);
        let cut = s
            .iter()
            .enumerate()
            .filter(|(_, v)| v.len() >= len && v.len() <= limit)
            .min_by_key(|(_, v)| v.len());
        let grown = || {
            s.iter()
                .enumerate()
                .filter(|(_, v)| v.len() < len)
                .max_by_key(|(_, v)| v.len())
        };
        let pick = cut.or_else(grown).map(|(i, _)| i);
        pick.map(|i| s.swap_remove(i))
    });
    let mut v = spare.unwrap_or_default();
    if v.len() >= len {
        v.truncate(len);
    } else {
        v.resize(len, 0);
    }
    v
}

/// Gives a buffer, zero over its whole length, back for [`zeroed`] to reuse; when
/// [`SPARE_COUNT`] are kept already, the shortest of them and it goes.
fn recycle(v: Vec<u8>) {
    if v.capacity() == 0 || v.capacity() > SPARE_MAX_BYTES {
        return;
    }
    SPARE.with(|s| {
        let mut s = s.borrow_mut();
        s.push(v);
        if s.len() > SPARE_COUNT {
            let shortest = s
                .iter()
                .enumerate()
                .min_by_key(|(_, v)| v.len())
                .map(|(i, _)| i);
            if let Some(i) = shortest {
                s.swap_remove(i);
            }
        }
    });
}

/// Appends to `painted_at` the indices (row-major in `win`) of the pixels tiny-skia itself
/// paints filling the path and `reference` reversed in a mask that is exactly `win`, curves
/// drawn `clipped` or not (see [`super::render_check::painted_in`]); false when tiny-skia
/// cannot fill the path.
pub(super) fn painted(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    clipped: bool,
    painted_at: &mut Vec<usize>,
) -> bool {
    let (width, height) = (win.x1 - win.x0, win.y1 - win.y0);
    let size = u32::try_from(width)
        .ok()
        .zip(u32::try_from(height).ok())
        .and_then(|(w, h)| tiny_skia::IntSize::from_wh(w, h));
    let Some(size) = size else {
        return false;
    };
    let len = (width * height) as usize;
    let origin = (win.x0 as f64, win.y0 as f64);
    let mask = (width as f32, height as f32);
    let path = difference_path(reference, start, commands, origin, clipped, Some(mask))
        .filter(|p| {
            let b = p.bounds();
            let nothing = tiny_skia_path::SCALAR_NEARLY_ZERO;
            b.width() > nothing && b.height() > nothing
        })
        .or_else(|| difference_path(reference, start, commands, origin, clipped, None));
    let painted = path.and_then(|path| {
        let mut mask = tiny_skia::Mask::from_vec(zeroed(len), size)?;
        mask.fill_path(
            &path,
            tiny_skia::FillRule::Winding,
            false,
            tiny_skia::Transform::identity(),
        );
        Some(mask.take())
    });
    let Some(mut painted) = painted else {
        return false;
    };
    take_painted(&mut painted, painted_at);
    recycle(painted);
    true
}

/// Appends the indices of the non-zero bytes of `mask` to `at`, in order, and zeroes them:
/// the buffer goes back to [`recycle`] all zero without being written whole (a fill paints
/// few pixels of its window).
fn take_painted(mask: &mut [u8], at: &mut Vec<usize>) {
    // Blocks of 64 bytes tested by an OR without early exit, which the compiler
    // vectorizes (a byte-by-byte `all` was three quarters of this function's own time).
    for (block, bytes) in mask.chunks_mut(64).enumerate() {
        if bytes.iter().fold(0u8, |a, &b| a | b) == 0 {
            continue;
        }
        for (k, b) in bytes.iter_mut().enumerate() {
            if *b != 0 {
                at.push(block * 64 + k);
                *b = 0;
            }
        }
    }
}

/// The path translated by `(−dx, −dy)` (whole pixels: exact for grid points) as tiny-skia's,
/// followed by `reference` reversed, and — for the `clipped` way of drawing curves — a flat
/// sliver just outside the window, which paints nothing but puts the path's bounds outside
/// the mask, so that tiny-skia runs its edge clipper on every edge. With `mask` (its width
/// and height), the runs of segments wholly beyond one side of the mask are drawn as one
/// line each ([`Collapsing`]). `None` when tiny-skia refuses the path (not finite).
fn difference_path(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    (dx, dy): (f64, f64),
    clipped: bool,
    mask: Option<(f32, f32)>,
) -> Option<tiny_skia::Path> {
    let f = |p: Point| ((p.x - dx) as f32, (p.y - dy) as f32);
    let verbs = commands.len() + reference.vertices.len() + 6;
    let mut pb = Collapsing {
        pb: tiny_skia::PathBuilder::with_capacity(verbs, verbs * 3),
        mask,
        pen: (0.0, 0.0),
        run: 0,
    };
    pb.move_to(f(start));
    let mut pen = start;
    for c in commands {
        match *c {
            PathCommand::Line(p) => pb.segment(Segment::Line(f(p))),
            PathCommand::Quad(a, p) => pb.segment(Segment::Quad(f(a), f(p))),
            PathCommand::Cubic(a, b, p) => pb.segment(Segment::Cubic(f(a), f(b), f(p))),
            PathCommand::Arc(_) => {
                for el in c.to_path_els(pen) {
                    match el {
                        kurbo::PathEl::CurveTo(a, b, p) => {
                            pb.segment(Segment::Cubic(f(a), f(b), f(p)));
                        }
                        kurbo::PathEl::LineTo(p) => pb.segment(Segment::Line(f(p))),
                        _ => {}
                    }
                }
            }
        }
        pen = c.end();
    }
    pb.close();
    pb.move_to(f(reference.start));
    for &p in reference.vertices.iter().rev() {
        pb.segment(Segment::Line(f(p)));
    }
    pb.close();
    let mut pb = pb.pb;
    if clipped {
        pb.move_to(-1.0, -1.0);
        pb.line_to(-0.5, -1.0);
        pb.close();
    }
    pb.finish()
}

/// A segment of a path in tiny-skia's `f32` coordinates, after the pen.
#[derive(Clone, Copy)]
enum Segment {
    Line((f32, f32)),
    Quad((f32, f32), (f32, f32)),
    Cubic((f32, f32), (f32, f32), (f32, f32)),
}

impl Segment {
    /// The segment's last point.
    fn end(self) -> (f32, f32) {
        match self {
            Segment::Line(p) | Segment::Quad(_, p) | Segment::Cubic(_, _, p) => p,
        }
    }

    /// The sides of the mask `[0, w] × [0, h]` beyond which (or on which) the segment lies
    /// wholly, its control points and the pen `from` included: bits [`ABOVE`], [`BELOW`],
    /// [`LEFT`], [`RIGHT`] (none for a point not a number).
    fn beyond(self, from: (f32, f32), (w, h): (f32, f32)) -> u8 {
        let mut sides = ABOVE | BELOW | LEFT | RIGHT;
        let bit = |holds: bool, side: u8| if holds { side } else { 0 };
        let mut side = |(x, y): (f32, f32)| {
            // (Each comparison false for a number that is not one.)
            sides &= bit(y <= 0.0, ABOVE)
                | bit(y >= h, BELOW)
                | bit(x <= 0.0, LEFT)
                | bit(x >= w, RIGHT);
        };
        side(from);
        match self {
            Segment::Line(p) => side(p),
            Segment::Quad(a, p) => {
                side(a);
                side(p);
            }
            Segment::Cubic(a, b, p) => {
                side(a);
                side(b);
                side(p);
            }
        }
        sides
    }
}

/// Sides of the mask for [`Segment::beyond`].
const ABOVE: u8 = 1;
const BELOW: u8 = 2;
const LEFT: u8 = 4;
const RIGHT: u8 = 8;

/// A path builder that draws each run of consecutive segments lying wholly beyond one side
/// of the mask as one line from the run's start to its end: what tiny-skia's edge clipper
/// (which runs whenever a point lies beyond, see `edge_clipper.rs` and `line_clipper.rs`)
/// makes of either paints the same pixels, and a long contour cut by a small window (a
/// tile of Chromium's, [`super::tiles`]) leaves the clipper few edges.
///
/// - Above or below: the clipper drops every such line and curve.
/// - Right: each becomes vertical lines on the mask's right side (tiny-skia does not cull
///   them), whose crossings round to the column after the last: no pixel of the mask
///   counts them.
/// - Left: each monotonic part becomes the vertical line on the left side between its ends'
///   heights clamped to the mask (its cuts at the top and bottom are set there exactly). The
///   parts of a run share their ends, so in every row their windings sum to the winding of
///   the line between the run's ends, which the clipper makes the same way.
///
/// Where the path's bounds shrink to nothing wide or high tiny-skia fills nothing; the
/// caller then builds the path without collapsing.
struct Collapsing {
    pb: tiny_skia::PathBuilder,
    /// The mask's width and height; `None`: nothing is collapsed.
    mask: Option<(f32, f32)>,
    /// The pen (the end of the pending run while there is one).
    pen: (f32, f32),
    /// The sides every segment of the pending run lies beyond; 0 when none is pending.
    run: u8,
}

impl Collapsing {
    fn move_to(&mut self, p: (f32, f32)) {
        self.flush();
        self.pb.move_to(p.0, p.1);
        self.pen = p;
    }

    fn segment(&mut self, s: Segment) {
        let sides = self.mask.map_or(0, |m| s.beyond(self.pen, m));
        if self.run & sides != 0 {
            self.run &= sides;
        } else {
            self.flush();
            if sides != 0 {
                self.run = sides;
            } else {
                match s {
                    Segment::Line((x, y)) => self.pb.line_to(x, y),
                    Segment::Quad((ax, ay), (x, y)) => self.pb.quad_to(ax, ay, x, y),
                    Segment::Cubic((ax, ay), (bx, by), (x, y)) => {
                        self.pb.cubic_to(ax, ay, bx, by, x, y);
                    }
                }
            }
        }
        self.pen = s.end();
    }

    /// Draws the pending run as its line.
    fn flush(&mut self) {
        if self.run != 0 {
            self.pb.line_to(self.pen.0, self.pen.1);
            self.run = 0;
        }
    }

    fn close(&mut self) {
        self.flush();
        self.pb.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The indices of the pixels tiny-skia paints filling `path` in a `w × h` mask.
    fn fill(path: &tiny_skia::Path, w: u32, h: u32) -> Vec<usize> {
        let mut mask = tiny_skia::Mask::new(w, h).expect("a mask");
        mask.fill_path(
            path,
            tiny_skia::FillRule::Winding,
            false,
            tiny_skia::Transform::identity(),
        );
        let mut at = Vec::new();
        take_painted(&mut mask.take(), &mut at);
        at
    }

    proptest! {
        /// Runs beyond the mask's sides drawn as one line each paint what the runs paint,
        /// for random paths of lines, quadratics and cubics (on the 1/16-px grid) and
        /// references, in windows that cut them anywhere, curves clipped or not.
        #[test]
        fn collapsed_runs_paint_the_same(
            path in prop::collection::vec((0u8..3, prop::array::uniform6(-320i32..960)), 1..24),
            refp in prop::collection::vec((-2i32..40, -2i32..40), 3..12),
            x0 in 0i64..30,
            y0 in 0i64..30,
            w in 1i64..24,
            h in 1i64..24,
            clipped in any::<bool>(),
        ) {
            let q = |x: i32, y: i32| Point::new(f64::from(x) / 16.0, f64::from(y) / 16.0);
            let commands: Vec<PathCommand> = path
                .iter()
                .map(|&(k, v)| match k {
                    0 => PathCommand::Line(q(v[0], v[1])),
                    1 => PathCommand::Quad(q(v[0], v[1]), q(v[2], v[3])),
                    _ => PathCommand::Cubic(q(v[0], v[1]), q(v[2], v[3]), q(v[4], v[5])),
                })
                .collect();
            let start = commands[commands.len() - 1].end();
            let r = |&(x, y): &(i32, i32)| Point::new(f64::from(x), f64::from(y));
            let rc: Vec<PathCommand> = refp[1..].iter().map(|p| PathCommand::Line(r(p))).collect();
            let reference = Reference::new(r(&refp[0]), &rc);
            let origin = (x0 as f64, y0 as f64);
            let mask = (w as f32, h as f32);
            let whole = difference_path(&reference, start, &commands, origin, clipped, None)
                .expect("a path");
            let collapsed =
                difference_path(&reference, start, &commands, origin, clipped, Some(mask))
                    .expect("a path");
            let b = collapsed.bounds();
            prop_assume!(b.width() > tiny_skia_path::SCALAR_NEARLY_ZERO
                && b.height() > tiny_skia_path::SCALAR_NEARLY_ZERO);
            let (w, h) = (w as u32, h as u32);
            prop_assert_eq!(fill(&collapsed, w, h), fill(&whole, w, h));
        }
    }

    #[test]
    fn a_contour_round_a_small_window_leaves_few_edges() {
        // A 40-px square crack polygon round a 4-px window inside it: everything but the
        // window's own rows collapses.
        let mut cmds = Vec::new();
        for k in 1..=40 {
            cmds.push(PathCommand::Line(Point::new(f64::from(k), 0.0)));
        }
        for k in 1..=40 {
            cmds.push(PathCommand::Line(Point::new(40.0, f64::from(k))));
        }
        for k in (0..40).rev() {
            cmds.push(PathCommand::Line(Point::new(f64::from(k), 40.0)));
        }
        for k in (0..40).rev() {
            cmds.push(PathCommand::Line(Point::new(0.0, f64::from(k))));
        }
        let nothing = Reference::new(Point::ZERO, &[]);
        let origin = (18.0, 18.0);
        let whole = difference_path(&nothing, Point::ZERO, &cmds, origin, false, None).unwrap();
        let collapsed = difference_path(
            &nothing,
            Point::ZERO,
            &cmds,
            origin,
            false,
            Some((4.0, 4.0)),
        )
        .unwrap();
        assert!(collapsed.len() <= 8, "{} points", collapsed.len());
        assert!(whole.len() > 160);
        // The window lies inside the square: every pixel painted, either way.
        assert_eq!(fill(&collapsed, 4, 4), (0..16).collect::<Vec<_>>());
        assert_eq!(fill(&whole, 4, 4), fill(&collapsed, 4, 4));
    }
}
