//! The pixels tiny-skia draws wrong for one contour's path: one fill of the path and the
//! contour's crack polygon reversed (see [`misplaced_pixels`]), by tiny-skia itself or,
//! where it would not clip the path, by its own arithmetic ([`super::scan`]); tiny-skia's own
//! fills are in [`super::mask_fill`].

use super::mask_fill;
use super::scan;
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// How tiny-skia will treat the edges of the document's one `<path>` (every contour).
///
/// tiny-skia (as Skia) draws curves differently when the path's bounds, rounded out by
/// about half a pixel, leave the pixmap: its edge clipper then cuts every cubic at its x and
/// y extrema, and quadratics at theirs, before subdividing, which moves the chords. Lines
/// are only cut where they cross the pixmap's border.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EdgeClipping {
    /// The document's path stays well inside the pixmap: curves are subdivided whole.
    Never,
    /// The document's path reaches the pixmap's border: curves are cut at their extrema.
    Always,
    /// Not known: a curved path must be drawn right both ways.
    #[default]
    Unknown,
}

impl EdgeClipping {
    /// The two ways of drawing curves (unclipped, clipped) this asks to check.
    fn modes(self) -> &'static [bool] {
        match self {
            EdgeClipping::Never => &[false],
            EdgeClipping::Always => &[true],
            EdgeClipping::Unknown => &[false, true],
        }
    }
}

/// What a contour's path must paint: its crack polygon (pixel edges, each once, meeting only
/// at corners), which winds its orientation `s` round exactly the pixels the contour
/// encloses and 0 round every other pixel.
pub(crate) struct Reference {
    /// The polygon's first point.
    pub(super) start: Point,
    /// The polygon's vertices after `start`, in order.
    pub(super) vertices: Vec<Point>,
    /// The least coordinates of its points.
    pub(super) lo: Point,
    /// The largest coordinates of its points.
    pub(super) hi: Point,
}

impl Reference {
    /// The reference of the closed polygon `M start commands Z` (lines only; other commands
    /// count by their end point).
    pub(crate) fn new(start: Point, commands: &[PathCommand]) -> Reference {
        let vertices: Vec<Point> = commands.iter().map(|c| c.end()).collect();
        let (mut lo, mut hi) = (start, start);
        for &p in &vertices {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        Reference {
            start,
            vertices,
            lo,
            hi,
        }
    }
}

/// The pixels whose centre the closed path `M start commands Z` winds round differently from
/// `reference` (nonzero rule: 0 outside the reference, its orientation `s` inside), as
/// tiny-skia draws it without anti-aliasing (resvg under `shape-rendering="crispEdges"`),
/// with curves cut as `clipping` says (both ways for [`EdgeClipping::Unknown`]), within
/// the document's pixmap `canvas` (in the contour's coordinates; `None`: far away).
///
/// # One fill
/// A path can paint the right pixels alone and still be wrong in the document: a twisted
/// lobe (a self-crossing) winds `−s` round the pixels it covers, a curl `2s`; a lone nonzero
/// fill paints them like the rest, but in the document they add to the windings of the
/// other contours instead of cancelling them (a hole's path meeting its outer border's). The
/// winding is what must be compared, and it is additive: tiny-skia's scan converter rounds
/// each edge's crossing of a scanline by itself and sums the edges' directions left of each
/// pixel centre. So the path and the reference *reversed*, filled together, wind
/// `w_path − w_reference` round every centre, and the pixels painted are exactly those where
/// the two differ. The mask covers both with two pixels to spare (the scan converter keeps
/// clipping off only when the conservatively rounded bounds are inside the mask). For lines
/// tiny-skia's results do not change under a translation by whole pixels (their arithmetic
/// is on differences and on 26.6 fixed point); a quadratic or cubic is first cut at its y
/// extrema in `f32`, whose rounding depends on the origin, so its pixels may differ by a
/// 1/64-px rounding between the window and the document (measured: 224 of 200 000 random
/// cubic loops on a 3000-px page; see BENCHMARKS.md, *Tile sizes*). The
/// check with the path moved by [`super::ROBUST_SHIFT`] covers such rounding in practice.
/// Points are on the 1/64 grid ([`super::builder`]), exact in `f32`.
///
/// A path that cannot be filled (not finite, too large for tiny-skia's fixed point) is wrong
/// at every pixel of the window.
pub(crate) fn misplaced_pixels(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Vec<Pixel> {
    match fill_window(reference, start, commands, clipping, canvas) {
        Some((win, modes)) => painted_in(reference, start, commands, &win, modes),
        None => Vec::new(),
    }
}

/// Whether [`misplaced_pixels`] is empty: the ways of drawing curves are filled one at a
/// time, and the first that misplaces a pixel ends the check.
pub(crate) fn draws_right(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> bool {
    fill_window(reference, start, commands, clipping, canvas).is_none_or(|(win, modes)| {
        modes
            .iter()
            .all(|&m| painted_in(reference, start, commands, &win, &[m]).is_empty())
    })
}

/// The window [`misplaced_pixels`] fills and the ways of drawing curves it fills them in;
/// `None` when the window is outside the document's pixmap `canvas` (nothing is drawn).
fn fill_window(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Option<(Window, &'static [bool])> {
    let path = PathBounds::of(start, commands);
    fill_window_moved(
        reference,
        &path,
        0.0,
        has_curves(commands),
        clipping,
        canvas,
    )
}

/// [`fill_window`] of the path of bounds `path` moved by `shift` px sideways (the reference
/// stays), `curves` whether it has any.
pub(super) fn fill_window_moved(
    reference: &Reference,
    path: &PathBounds,
    shift: f64,
    curves: bool,
    clipping: EdgeClipping,
    canvas: Option<Rect>,
) -> Option<(Window, &'static [bool])> {
    let mut win = Window::around(reference, path, shift);
    // The window ends at the pixmap's border: tiny-skia clips the path there as it does in
    // the document (a curve crossing the border is cut at the crossing, which moves its
    // chords), and pixels outside are never drawn.
    if let Some(c) = canvas {
        win = win.within(Window::inside(c))?;
    }
    let modes = if curves { clipping.modes() } else { &[false] };
    Some((win, modes))
}

/// Whether any command is not a line: tiny-skia draws lines one way only, whatever its edge
/// clipper does to curves.
pub(crate) fn has_curves(commands: &[PathCommand]) -> bool {
    commands.iter().any(|c| !matches!(c, PathCommand::Line(_)))
}

/// The least and largest coordinates of the points of a path `M start commands Z`, control
/// points included (an arc, which the builder does not make, by its whole ellipse); not a
/// number where no point has one.
#[derive(Clone, Copy, Debug)]
pub(super) struct PathBounds {
    /// The least coordinates.
    pub(super) lo: Point,
    /// The largest coordinates.
    pub(super) hi: Point,
}

impl PathBounds {
    /// The bounds of `M start commands Z`.
    pub(super) fn of(start: Point, commands: &[PathCommand]) -> PathBounds {
        let (mut lo, mut hi) = (start, start);
        let mut grow = |p: Point| {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        };
        for c in commands {
            match *c {
                PathCommand::Line(p) => grow(p),
                PathCommand::Quad(a, p) => {
                    grow(a);
                    grow(p);
                }
                PathCommand::Cubic(a, b, p) => {
                    grow(a);
                    grow(b);
                    grow(p);
                }
                PathCommand::Arc(a) => {
                    let r = a.radii.x.abs().max(a.radii.y.abs());
                    grow(a.to - kurbo::Vec2::new(r, r) * 2.0);
                    grow(a.to + kurbo::Vec2::new(r, r) * 2.0);
                }
            }
        }
        PathBounds { lo, hi }
    }
}

/// A rectangle of whole pixels: columns `x0..x1`, rows `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Window {
    pub(super) x0: i64,
    pub(super) y0: i64,
    pub(super) x1: i64,
    pub(super) y1: i64,
}

impl Window {
    /// The pixels round the path `M start commands Z` and `reference`, with two to spare
    /// on every side (the scan converter keeps clipping off only when the conservatively
    /// rounded bounds are inside the mask).
    pub(super) fn round(reference: &Reference, start: Point, commands: &[PathCommand]) -> Window {
        Window::around(reference, &PathBounds::of(start, commands), 0.0)
    }

    /// [`Window::round`] of the path of bounds `path` moved by `shift` px sideways (the
    /// reference stays).
    pub(super) fn around(reference: &Reference, path: &PathBounds, shift: f64) -> Window {
        // (Adding `shift` to the least and the largest x is adding it to every x: rounding
        // is monotonic.)
        let mut lo = Point::new(
            reference.lo.x.min(path.lo.x + shift),
            reference.lo.y.min(path.lo.y),
        );
        let mut hi = Point::new(
            reference.hi.x.max(path.hi.x + shift),
            reference.hi.y.max(path.hi.y),
        );
        if !(lo.x.is_finite() && lo.y.is_finite() && hi.x.is_finite() && hi.y.is_finite()) {
            lo = reference.lo;
            hi = reference.hi;
        }
        Window {
            x0: lo.x.floor() as i64 - 2,
            y0: lo.y.floor() as i64 - 2,
            x1: hi.x.ceil() as i64 + 2,
            y1: hi.y.ceil() as i64 + 2,
        }
    }

    /// The whole pixels inside `r`.
    pub(super) fn inside(r: Rect) -> Window {
        Window {
            x0: r.x0.ceil() as i64,
            y0: r.y0.ceil() as i64,
            x1: r.x1.floor() as i64,
            y1: r.y1.floor() as i64,
        }
    }

    /// The pixels of both; `None` when they share none.
    pub(super) fn within(self, other: Window) -> Option<Window> {
        let w = Window {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (w.x0 < w.x1 && w.y0 < w.y1).then_some(w)
    }

    /// The least window holding both.
    pub(super) fn union(self, other: Window) -> Window {
        Window {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }

    /// Whether every pixel of `self` is in `other`.
    pub(super) fn is_in(self, other: Window) -> bool {
        self.x0 >= other.x0 && self.y0 >= other.y0 && self.x1 <= other.x1 && self.y1 <= other.y1
    }

    /// Whether pixel `(x, y)` is in the window.
    pub(super) fn contains(self, x: i64, y: i64) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    /// Every pixel of the window.
    fn pixels(self) -> Vec<Pixel> {
        let mut all = Vec::new();
        for y in self.y0..self.y1 {
            for x in self.x0..self.x1 {
                if let (Ok(px), Ok(py)) = (i32::try_from(x), i32::try_from(y)) {
                    all.push(Pixel::new(px, py));
                }
            }
        }
        all
    }
}

/// The pixels of `win` whose centre the path and `reference` wind round differently (see
/// [`misplaced_pixels`]), as tiny-skia draws them into a mask that is exactly `win` (its
/// edge clipper cuts every edge crossing the window's border there), for each way of
/// drawing curves in `modes` (`true`: clipped). Every pixel of the window when tiny-skia
/// cannot fill the path.
pub(super) fn painted_in(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    modes: &[bool],
) -> Vec<Pixel> {
    // Computed as tiny-skia computes them where the path stays inside the window (see
    // `scan`: the same pixels, without building a mask), else filled by tiny-skia.
    painted_by(reference, start, commands, win, modes, true)
}

/// [`painted_in`], every mode filled by tiny-skia itself (for the tests of [`scan`]).
#[cfg(test)]
pub(super) fn painted_by_tiny_skia(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    modes: &[bool],
) -> Vec<Pixel> {
    painted_by(reference, start, commands, win, modes, false)
}

/// [`painted_in`], with [`scan::painted`] where it applies when `scanned`, else by tiny-skia.
fn painted_by(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    win: &Window,
    modes: &[bool],
    scanned: bool,
) -> Vec<Pixel> {
    // Indices (row-major in the window) of the painted pixels, of every mode.
    let mut painted_at: Vec<usize> = Vec::new();
    for &clipped in modes {
        let at = scanned
            .then(|| scan::painted(reference, start, commands, win, clipped))
            .flatten();
        match at {
            Some(at) => painted_at.extend(at),
            None => {
                if !mask_fill::painted(reference, start, commands, win, clipped, &mut painted_at) {
                    return win.pixels();
                }
            }
        }
    }
    if modes.len() > 1 {
        painted_at.sort_unstable();
        painted_at.dedup();
    }
    pixels_at(win, painted_at)
}

/// The pixels of `win` at the row-major indices `at`.
pub(super) fn pixels_at(win: &Window, at: Vec<usize>) -> Vec<Pixel> {
    let w = (win.x1 - win.x0) as usize;
    at.into_iter()
        .filter_map(|at| {
            let (x, y) = (win.x0 + (at % w) as i64, win.y0 + (at / w) as i64);
            Some(Pixel::new(i32::try_from(x).ok()?, i32::try_from(y).ok()?))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// The pixels the path paints alone: misplaced against an empty reference.
    fn painted(start: Point, cmds: &[PathCommand]) -> BTreeSet<(i32, i32)> {
        let nothing = Reference::new(start, &[]);
        misplaced_pixels(&nothing, start, cmds, EdgeClipping::Never, None)
            .into_iter()
            .map(|q| (q.x, q.y))
            .collect()
    }

    /// Pixel centres strictly inside a polygon are painted, those outside are not (no centre
    /// on an edge here).
    #[test]
    fn polygon_paints_the_centres_inside() {
        let start = p(0.0, 0.0);
        let cmds = [
            PathCommand::Line(p(0.0, 5.0)),
            PathCommand::Line(p(7.25, 5.0)),
            PathCommand::Line(p(3.0, 0.0)),
        ];
        let got = painted(start, &cmds);
        for y in -3..9 {
            for x in -3..12 {
                let c = p(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let inside = c.y > 0.0 && c.y < 5.0 && c.x > 0.0 && {
                    // Right edge from (3, 0) to (7.25, 5).
                    let t = c.y / 5.0;
                    c.x < 3.0 + 4.25 * t
                };
                assert_eq!(got.contains(&(x, y)), inside, "({x}, {y})");
            }
        }
    }

    /// A far-off translation does not change what is painted relative to the path.
    #[test]
    fn translation_invariant() {
        let cmds = |d: f64| {
            vec![
                PathCommand::Cubic(p(d + 3.0, d + 9.0), p(d + 9.0, d + 11.0), p(d + 12.0, d)),
                PathCommand::Line(p(d + 5.0, d - 1.5)),
            ]
        };
        let a = painted(p(0.0, 0.0), &cmds(0.0));
        let b: BTreeSet<(i32, i32)> = painted(p(4000.0, 4000.0), &cmds(4000.0))
            .into_iter()
            .map(|(x, y)| (x - 4000, y - 4000))
            .collect();
        assert_eq!(a, b);
        assert!(a.len() > 30, "{}", a.len());
    }

    /// Winding of a path round each pixel centre of a window, classed the slow way: filled
    /// alone (winding not 0) and with a rectangle round the window wound `−s` (winding not
    /// `s`), as two separate tiny-skia fills. 0: winding 0, 1: winding `s`, 2: other.
    fn classes(start: Point, cmds: &[PathCommand], s: f32, win: (i32, i32, u32, u32)) -> Vec<u8> {
        let (x0, y0, w, h) = win;
        let build = |frame: bool| {
            let mut pb = tiny_skia::PathBuilder::new();
            let f = |q: Point| ((q.x - f64::from(x0)) as f32, (q.y - f64::from(y0)) as f32);
            let (x, y) = f(start);
            pb.move_to(x, y);
            for c in cmds {
                match *c {
                    PathCommand::Line(q) => {
                        let (x, y) = f(q);
                        pb.line_to(x, y);
                    }
                    PathCommand::Cubic(a, b, q) => {
                        let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(q));
                        pb.cubic_to(ax, ay, bx, by, x, y);
                    }
                    _ => unreachable!(),
                }
            }
            pb.close();
            if frame {
                let (w, h) = (w as f32, h as f32);
                pb.move_to(0.0, 0.0);
                if s > 0.0 {
                    pb.line_to(w, 0.0);
                    pb.line_to(w, h);
                    pb.line_to(0.0, h);
                } else {
                    pb.line_to(0.0, h);
                    pb.line_to(w, h);
                    pb.line_to(w, 0.0);
                }
                pb.close();
            }
            let mut m = tiny_skia::Mask::new(w, h).unwrap();
            let path = pb.finish().unwrap();
            m.fill_path(
                &path,
                tiny_skia::FillRule::Winding,
                false,
                tiny_skia::Transform::identity(),
            );
            m.take()
        };
        let (alone, framed) = (build(false), build(true));
        alone
            .iter()
            .zip(&framed)
            .map(|(&a, &f)| match (a != 0, f != 0) {
                (false, _) => 0,
                (true, false) => 1,
                (true, true) => 2,
            })
            .collect()
    }

    /// The one fill of path and reversed reference marks exactly the pixels where the two
    /// fills per path class path and reference differently — for paths that are right, that
    /// twist (a lobe wound the other way), that curl (wound twice), and that miss or add
    /// pixels, with lines and cubics.
    #[test]
    fn one_fill_finds_what_two_fills_per_path_find() {
        // Reference: a 10 × 8 pixel block at (2, 3), counter-clockwise on screen.
        let rs = p(2.0, 3.0);
        let rc = [
            PathCommand::Line(p(2.0, 11.0)),
            PathCommand::Line(p(12.0, 11.0)),
            PathCommand::Line(p(12.0, 3.0)),
        ];
        let reference = Reference::new(rs, &rc);
        let paths: Vec<(Point, Vec<PathCommand>)> = vec![
            // Exactly the block, through other vertices.
            (
                p(2.1, 2.9),
                vec![
                    PathCommand::Line(p(1.9, 11.2)),
                    PathCommand::Line(p(12.3, 10.9)),
                    PathCommand::Line(p(11.8, 3.1)),
                ],
            ),
            // Twisted: a figure of eight over the block.
            (
                p(2.0, 3.0),
                vec![
                    PathCommand::Line(p(2.0, 11.0)),
                    PathCommand::Line(p(12.0, 3.0)),
                    PathCommand::Line(p(12.0, 11.0)),
                ],
            ),
            // Curled: round the block twice.
            (
                p(2.0, 3.0),
                vec![
                    PathCommand::Line(p(2.0, 11.0)),
                    PathCommand::Line(p(12.0, 11.0)),
                    PathCommand::Line(p(12.0, 3.0)),
                    PathCommand::Line(p(2.0, 3.0)),
                    PathCommand::Line(p(2.0, 11.0)),
                    PathCommand::Line(p(12.0, 11.0)),
                    PathCommand::Line(p(12.0, 3.0)),
                ],
            ),
            // Wound the wrong way.
            (p(2.0, 3.0), rc.iter().rev().copied().collect::<Vec<_>>()),
            // A cubic bulging out on one side and a dent on another.
            (
                p(2.0, 3.0),
                vec![
                    PathCommand::Cubic(p(-1.0, 5.0), p(-1.0, 9.0), p(2.0, 11.0)),
                    PathCommand::Line(p(12.0, 11.0)),
                    PathCommand::Cubic(p(8.0, 8.0), p(8.0, 6.0), p(12.0, 3.0)),
                ],
            ),
        ];
        let win = (-4, -3, 24, 20);
        let expected_ref = classes(rs, &rc, 1.0, win);
        let mut differing_somewhere = 0;
        for (k, (start, cmds)) in paths.iter().enumerate() {
            let got: BTreeSet<(i32, i32)> =
                misplaced_pixels(&reference, *start, cmds, EdgeClipping::Never, None)
                    .into_iter()
                    .map(|q| (q.x, q.y))
                    .collect();
            let cls = classes(*start, cmds, 1.0, win);
            let mut want = BTreeSet::new();
            for (i, (&a, &b)) in cls.iter().zip(&expected_ref).enumerate() {
                if a != b {
                    want.insert((win.0 + (i as i32) % 24, win.1 + (i as i32) / 24));
                }
            }
            assert_eq!(got, want, "path {k}");
            differing_somewhere += usize::from(!want.is_empty());
        }
        // Every path but the first is wrong somewhere.
        assert_eq!(differing_somewhere, paths.len() - 1);
    }
}
