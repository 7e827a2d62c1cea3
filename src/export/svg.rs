//! SVG export of a [`Decomposition`]: one closed subpath per contour, along the exact border
//! curves of its pieces.
//!
//! # The border curve of a piece
//! A piece with a non-zero certificate is drawn along its level curve `f = c`,
//! `c = `[`boundary_level`] (see [`crate::level`]): its inlier centres have `f < c` and its
//! RIGHT (background) outlier centres `f > c`, so a rasterizer sampling pixel centres puts
//! the piece's pixels inside and the background beside it outside. The curve is drawn by
//! [`level_curve_path`], with the piece's pixel centres as guide: lines give `L`, circles and
//! ellipses exact `A` arcs (with rotation), parabolas exact `Q`, hyperbolas, degenerate
//! conics and higher degrees cubic `C` fitted within [`SvgOptions::tolerance`].
//!
//! # Joins
//! Consecutive pieces `k` and `k+1` (and the last with the first: contours are closed) meet
//! at a junction near their adjacent end pixels `a = p_last(k)`, `b = p_first(k+1)`; let
//! `m` be the middle of their centres.
//! * Both pieces have curves: the junction is their intersection closest to `m` within
//!   [`JUNCTION_MAX_DISTANCE`] ([`intersect_near`]); piece `k` ends there and piece `k+1`
//!   starts there.
//! * Otherwise (no intersection that close, e.g. nearly parallel lines, or a neighbour
//!   without curve): piece `k` ends at the projection of `m` on its curve, piece `k+1` starts
//!   at the projection of `m` on its own, and a straight segment bridges the two.
//! * A contour of one piece with a curve runs once round that curve, from and back to the
//!   projection of `m` (the closing junction between its last and first points).
//!
//! # Fallback: pixel cracks
//! Pieces without equation (the zero certificate of 1–2-pixel pieces), pieces whose
//! polynomial cannot be built, whose curve passes closer than the minimum clearance
//! ([`SvgOptions::min_clearance`]) to a pixel centre, whose curve does not come within
//! [`JUNCTION_MAX_DISTANCE`] of a junction, or whose curve [`level_curve_path`] cannot draw
//! or that strays farther than [`STRAY_MARGIN`] from the piece's pixels, are drawn along the
//! *cracks* of their pixels (a straight run of cracks as one line): for each pixel, the
//! sides it shares with the 4-neighbours on the RIGHT of
//! the walk (between the directions to the next and to the previous point, turning
//! clockwise), which border tracing guarantees to be background. Those sides are exactly the
//! pixel border, so these pixels are inside and their background neighbours outside. The
//! reason of every fallback is counted ([`FallbackCounts`]). A one-pixel contour is its
//! pixel's unit square.
//!
//! # Orientation and fill rule
//! Each contour is one closed subpath in tracing order: outer borders counter-clockwise on
//! screen, hole borders clockwise (the foreground is always on the left). With the
//! `nonzero` fill rule the foreground gets winding number ±1 and holes 0, and nested shapes
//! in holes get ±1 again. `nonzero` is preferred over `evenodd` because subpaths of the
//! same orientation that overlap slightly (curves of nearby borders crossing near a thin
//! background gap, or a bridge segment folding back) stay filled instead of cancelling out.
//!
//! # The document
//! `<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="W" height="H"
//! viewBox="0 0 W H">` with the image size in pixels (one user unit = one pixel, pixel
//! `(x, y)` = the square `[x, x+1] × [y, y+1]`), holding one `<path d="…" fill="…"
//! fill-rule="nonzero"/>` with all contours (none for an image without foreground), and
//! nothing else. Numbers have at most [`SvgOptions::precision`] decimals, trailing zeros
//! stripped; all commands are absolute.

use super::winding::RowWinding;
use crate::contour::Contour;
use crate::curve::{intersect_near, level_curve_path, project, PathCommand, Polynomial};
use crate::decompose::OutlierRule;
use crate::decompose::{neighbour_sides, Decomposition, Piece};
use crate::level::border_polynomial;
use crate::model::Basis;
use crate::pixel::{Pixel, PixelSet};
use kurbo::{BezPath, PathEl, Point};
use rayon::prelude::*;
use std::fmt::Write as _;

/// Largest distance (pixels) from the middle of two adjacent end pixels' centres to the
/// junction of their pieces' curves, or to the projection used instead.
pub const JUNCTION_MAX_DISTANCE: f64 = 1.5;

/// A piece's curve between its junctions must stay within this distance (pixels) of the
/// bounding box of the piece's pixels, or the piece falls back to its cracks: a level curve
/// may run far from the pixels where no outlier holds it (e.g. round a huge circle when the
/// whole contour is one piece).
pub const STRAY_MARGIN: f64 = 2.0;

/// Contours drawn per parallel group by [`svg_document`]: only one group's drawings are
/// held at a time besides the document.
const CONTOURS_PER_GROUP: usize = 4096;

/// How [`svg_document`] writes the SVG.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgOptions {
    /// The `fill` attribute of the path (XML-escaped on output). Default `black`.
    pub fill: String,
    /// Decimals of the numbers written (trailing zeros stripped; at most 12 are used).
    /// Default 3.
    pub precision: u8,
    /// Largest distance (pixels) of fitted cubic Béziers to the true curve (hyperbolas,
    /// degenerate conics, degree > 2). Default 0.05; values below 0.001 act as 0.001, and
    /// non-finite or non-positive ones as the default.
    pub tolerance: f64,
    /// A piece whose border curve passes closer than this (pixels) to a pixel centre, plus
    /// how far rounding to [`precision`](SvgOptions::precision) decimals moves a point
    /// (`√2/2 · 10^−precision`), is drawn along its pixel edges: renderers truncate vertices
    /// to a fixed-point grid (tiny-skia and Skia to 1/64 px) and would paint such a centre
    /// on either side. Default 1/64; 0 draws every curve that the exact checks accept
    /// (smaller files, a few pixels off when rendered); infinity draws every piece along its
    /// pixel edges. Negative or NaN values mean the default.
    pub min_clearance: f64,
}

impl Default for SvgOptions {
    fn default() -> SvgOptions {
        SvgOptions {
            fill: "black".into(),
            precision: 3,
            tolerance: 0.05,
            min_clearance: 1.0 / 64.0,
        }
    }
}

/// Number of path commands of each type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CommandCounts {
    /// `M`: one per contour.
    pub move_to: usize,
    /// `L`: straight pieces, bridges between pieces, crack fallbacks.
    pub line: usize,
    /// `A`: circular and elliptical arcs.
    pub arc: usize,
    /// `Q`: parabola arcs.
    pub quad: usize,
    /// `C`: fitted cubics.
    pub cubic: usize,
    /// `Z`: one per contour.
    pub close: usize,
}

impl CommandCounts {
    /// All commands.
    pub fn total(&self) -> usize {
        self.move_to + self.line + self.arc + self.quad + self.cubic + self.close
    }

    fn add(&mut self, o: &CommandCounts) {
        self.move_to += o.move_to;
        self.line += o.line;
        self.arc += o.arc;
        self.quad += o.quad;
        self.cubic += o.cubic;
        self.close += o.close;
    }
}

/// Pieces drawn along pixel cracks instead of a curve, by reason.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FallbackCounts {
    /// 1–2-pixel pieces with the zero certificate (no equation).
    pub zero_certificate: usize,
    /// [`border_polynomial`] gave no polynomial.
    pub no_polynomial: usize,
    /// The border curve passes closer to a pixel centre than the minimum clearance
    /// ([`SvgOptions::min_clearance`]).
    pub thin: usize,
    /// The curve has no point within [`JUNCTION_MAX_DISTANCE`] of a junction.
    pub junction: usize,
    /// [`level_curve_path`] could not draw the curve between the junctions, or the curve
    /// strays farther than `STRAY_MARGIN` (2 px) from the piece's pixels.
    pub curve: usize,
    /// The pieces did not cover the contour consecutively: the whole contour was drawn along
    /// its cracks (counted once per contour).
    pub invalid_pieces: usize,
}

impl FallbackCounts {
    /// All fallbacks.
    pub fn total(&self) -> usize {
        self.zero_certificate
            + self.no_polynomial
            + self.thin
            + self.junction
            + self.curve
            + self.invalid_pieces
    }

    fn add(&mut self, o: &FallbackCounts) {
        self.zero_certificate += o.zero_certificate;
        self.no_polynomial += o.no_polynomial;
        self.thin += o.thin;
        self.junction += o.junction;
        self.curve += o.curve;
        self.invalid_pieces += o.invalid_pieces;
    }
}

/// How consecutive pieces were joined.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JoinCounts {
    /// At the intersection of the two curves.
    pub intersection: usize,
    /// Otherwise: projections (or crack ends) bridged by a segment when distinct.
    pub bridged: usize,
    /// Repaired: the two end pixels drawn along their cracks (see [`contour_path`]).
    pub cracked: usize,
}

impl JoinCounts {
    fn add(&mut self, o: &JoinCounts) {
        self.intersection += o.intersection;
        self.bridged += o.bridged;
        self.cracked += o.cracked;
    }
}

/// The closed path of one contour, in absolute SVG coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContourPath {
    /// The `M` point. Meaningless when `commands` is empty (a contour without points).
    pub start: Point,
    /// The commands after the `M`; the path is closed after the last one (`Z`).
    pub commands: Vec<PathCommand>,
    /// Largest measured distance of fitted cubics to their curve (0 for exact forms).
    pub max_fit_error: f64,
    /// Pieces drawn along their cracks, by reason.
    pub fallbacks: FallbackCounts,
    /// Joins between consecutive pieces.
    pub joins: JoinCounts,
}

impl ContourPath {
    /// The path as a kurbo [`BezPath`] (arcs approximated by cubics within
    /// [`crate::ARC_FLATTEN_TOLERANCE`]), closed; empty for an empty contour.
    pub fn to_bez_path(&self) -> BezPath {
        let mut path = BezPath::new();
        if self.commands.is_empty() {
            return path;
        }
        path.push(PathEl::MoveTo(self.start));
        let mut pen = self.start;
        for c in &self.commands {
            for el in c.to_path_els(pen) {
                path.push(el);
            }
            pen = c.end();
        }
        path.push(PathEl::ClosePath);
        path
    }

    /// The number of SVG commands of each type (`M` and `Z` included).
    pub fn counts(&self) -> CommandCounts {
        let mut n = CommandCounts::default();
        if self.commands.is_empty() {
            return n;
        }
        n.move_to = 1;
        n.close = 1;
        for c in &self.commands {
            match c {
                PathCommand::Line(_) => n.line += 1,
                PathCommand::Arc(_) => n.arc += 1,
                PathCommand::Quad(..) => n.quad += 1,
                PathCommand::Cubic(..) => n.cubic += 1,
            }
        }
        n
    }
}

/// The SVG document and what went into it.
#[derive(Clone, Debug)]
pub struct SvgOutput {
    /// The document (UTF-8, ends with a newline).
    pub svg: String,
    /// Commands written, by type.
    pub commands: CommandCounts,
    /// Largest measured distance of fitted cubics to their curve (pixels).
    pub max_fit_error: f64,
    /// Number of pieces drawn by a fallback (`fallback_reasons.total()`).
    pub fallbacks: usize,
    /// The fallbacks by reason.
    pub fallback_reasons: FallbackCounts,
    /// Joins between consecutive pieces, by kind.
    pub joins: JoinCounts,
}

/// The centre of a pixel in SVG space.
fn centre(p: Pixel) -> Point {
    Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5)
}

/// The side of pixel `p` facing the 4-direction `d` (0 right, 2 down, 4 left, 6 up),
/// traversed with the pixel on its left (counter-clockwise on screen).
fn side(p: Pixel, d: u8) -> [Point; 2] {
    let (x, y) = (f64::from(p.x), f64::from(p.y));
    match d {
        0 => [Point::new(x + 1.0, y + 1.0), Point::new(x + 1.0, y)],
        6 => [Point::new(x + 1.0, y), Point::new(x, y)],
        4 => [Point::new(x, y), Point::new(x, y + 1.0)],
        _ => [Point::new(x, y + 1.0), Point::new(x + 1.0, y + 1.0)],
    }
}

/// The crack corners of `cur` between `prev` and `next`: its sides facing the 4-neighbours on
/// the right of the walk, counter-clockwise on screen from the side after `prev` to the side
/// before `next`. A U-turn (`prev == next`) gives every side but the one facing them; `None`
/// for `prev`/`next` (no neighbours: one-pixel contour) or non-adjacent input gives the whole
/// square.
fn crack_corners(prev: Option<Pixel>, cur: Pixel, next: Option<Pixel>, out: &mut Vec<Point>) {
    let dirs = match (
        prev.and_then(|p| cur.direction_to(p)),
        next.and_then(|q| cur.direction_to(q)),
    ) {
        (Some(a), Some(b)) => {
            let span = match (a + 8 - b) % 8 {
                0 => 8,
                s => s,
            };
            (1..span).map(|k| (a + 8 - k) % 8).collect::<Vec<u8>>()
        }
        _ => vec![6, 4, 2, 0],
    };
    for d in dirs.into_iter().filter(|d| d % 2 == 0) {
        for q in side(cur, d) {
            if out.last() != Some(&q) {
                out.push(q);
            }
        }
    }
}

/// Crack corners of the pixels `first..=last` of a closed contour.
fn crack_polyline(points: &[Pixel], first: usize, last: usize) -> Vec<Point> {
    let n = points.len();
    let mut out = Vec::new();
    if n == 0 {
        return out;
    }
    for i in first..=last.min(n - 1) {
        let (prev, next) = if n == 1 {
            (None, None)
        } else {
            (Some(points[(i + n - 1) % n]), Some(points[(i + 1) % n]))
        };
        crack_corners(prev, points[i], next, &mut out);
    }
    out
}

/// True when the pieces cover `0..n` consecutively.
fn pieces_valid(n: usize, pieces: &[Piece]) -> bool {
    let mut next = 0;
    for p in pieces {
        if p.first != next || p.last < p.first || p.last >= n {
            return false;
        }
        next = p.last + 1;
    }
    next == n && !pieces.is_empty()
}

/// True when the path from `from` along `cmds` stays within [`STRAY_MARGIN`] of the
/// bounding box of the pixels (squares) of its piece.
fn stays_near(from: Point, cmds: &[PathCommand], pixels: &[Pixel]) -> bool {
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in pixels {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        x0 = x0.min(x);
        y0 = y0.min(y);
        x1 = x1.max(x + 1.0);
        y1 = y1.max(y + 1.0);
    }
    let allowed = kurbo::Rect::new(x0, y0, x1, y1).inflate(STRAY_MARGIN, STRAY_MARGIN);
    let mut path = BezPath::new();
    path.move_to(from);
    let mut pen = from;
    for c in cmds {
        for el in c.to_path_els(pen) {
            path.push(el);
        }
        pen = c.end();
    }
    let b = kurbo::Shape::bounding_box(&path);
    b.x0 >= allowed.x0 && b.y0 >= allowed.y0 && b.x1 <= allowed.x1 && b.y1 <= allowed.y1
}

/// Builds the path while tracking the pen.
struct Builder {
    start: Option<Point>,
    pen: Point,
    commands: Vec<PathCommand>,
    /// Where the last command began, when it is a line (to merge the next, collinear one).
    line_from: Option<Point>,
}

impl Builder {
    fn new() -> Builder {
        Builder {
            start: None,
            pen: Point::ZERO,
            commands: Vec::new(),
            line_from: None,
        }
    }

    /// A line to `p`; one that continues the previous line in the same direction (exactly:
    /// pixel cracks along a row or column) extends it instead.
    fn goto(&mut self, p: Point) {
        match self.start {
            None => {
                self.start = Some(p);
                self.pen = p;
            }
            Some(_) => {
                if (p - self.pen).hypot() > 1e-9 {
                    let (d0, d1) = (self.pen - self.line_from.unwrap_or(p), p - self.pen);
                    match self.commands.last_mut() {
                        Some(PathCommand::Line(end))
                            if self.line_from.is_some()
                                && d0.cross(d1) == 0.0
                                && d0.dot(d1) > 0.0 =>
                        {
                            *end = p;
                        }
                        _ => {
                            self.line_from = Some(self.pen);
                            self.commands.push(PathCommand::Line(p));
                        }
                    }
                    self.pen = p;
                }
            }
        }
    }

    fn polyline(&mut self, pts: &[Point]) {
        for &p in pts {
            self.goto(p);
        }
    }

    fn extend(&mut self, cmds: Vec<PathCommand>) {
        for c in cmds {
            self.pen = c.end();
            self.commands.push(c);
            self.line_from = None;
        }
    }
}

/// Rounds of [`contour_path`]'s check-and-repair of junctions.
const REPAIR_ROUNDS: usize = 4;

/// The closed path of one contour decomposed into `pieces` described in `basis`; fitted
/// cubics stay within `tolerance` pixels of their curve, and pieces whose curve passes
/// closer than `min_clearance` to a pixel centre are drawn along their pixel edges. See the
/// module documentation of `export::svg` (in the source) for joins, fallbacks and the
/// repair of junctions.
pub fn contour_path(
    contour: &Contour,
    pieces: &[Piece],
    basis: &dyn Basis,
    tolerance: f64,
    min_clearance: f64,
) -> ContourPath {
    let points = &contour.points;
    let n = points.len();
    if n <= 1 || !pieces_valid(n, pieces) {
        let mut b = Builder::new();
        b.polyline(&crack_polyline(points, 0, n.saturating_sub(1)));
        let mut out = ContourPath {
            start: b.start.unwrap_or_default(),
            commands: b.commands,
            ..ContourPath::default()
        };
        if n > 1 {
            out.fallbacks.invalid_pieces += 1;
        }
        return out;
    }
    let mut cracked = vec![false; pieces.len()];
    // The border curves do not depend on the repairs: computed once.
    let curves = Curves::new(points, pieces, basis, tolerance, min_clearance);
    let mut memo = Memo::new(pieces.len());
    let mut out = build(points, pieces, &curves, &cracked, &mut memo);
    let on_contour: PixelSet = points.iter().copied().collect();
    for _ in 0..REPAIR_ROUNDS {
        let bad = misplaced_points(contour, &on_contour, &out.to_bez_path());
        let mut changed = false;
        for i in bad {
            // The junctions within two points of `i` along the (cyclic) contour: junction
            // `j` lies between `last` and `last + 1` of piece `j`, so `last` is within
            // `i − 3 ..= i + 2`; the pieces holding those points are found by bisection.
            let cyclic = |p: usize| {
                let d = p.abs_diff(i);
                d.min(n - d)
            };
            for back in 0..6 {
                let p = (i + n + 2 - back % n) % n;
                let j = pieces
                    .partition_point(|piece| piece.last < p)
                    .min(pieces.len() - 1);
                let piece = &pieces[j];
                let near = cyclic(piece.last).min(cyclic((piece.last + 1) % n)) <= 2;
                if near && !cracked[j] {
                    cracked[j] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
        out = build(points, pieces, &curves, &cracked, &mut memo);
    }
    out
}

/// Indices of contour points whose pixel centre, or the centre of one of their RIGHT
/// (background) 4-neighbours, is on the wrong side of the contour's own closed path.
fn misplaced_points(contour: &Contour, on_contour: &PixelSet, path: &BezPath) -> Vec<usize> {
    let points = &contour.points;
    let n = points.len();
    let index = RowWinding::new(path);
    let mut bad = Vec::new();
    // Foreground has winding ≠ 0 inside an outer border and 0 inside a hole border.
    let foreground = |p: Pixel| (index.winding(centre(p)) != 0) != contour.hole;
    for i in 0..n {
        let (prev, cur, next) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
        let mut ok = foreground(cur);
        if let Some(sides) = neighbour_sides(prev, cur, next) {
            for (q, right, _) in sides {
                if right && !on_contour.contains(&q) {
                    ok &= !foreground(q);
                }
            }
        }
        if !ok {
            bad.push(i);
        }
    }
    bad
}

/// The border curve of every piece of a contour, with the fitting tolerance it allows.
struct Curves {
    /// The curve, or `None` (zero certificate, no polynomial, or too thin a clearance).
    polys: Vec<Option<Polynomial>>,
    /// min(tolerance, clearance / 2, clearance − min_clearance), at least 1/1000 px;
    /// `tolerance` without a curve.
    tolerances: Vec<f64>,
    zero_certificate: usize,
    no_polynomial: usize,
    /// Curves dropped for passing closer than the minimum clearance to a pixel centre.
    thin: usize,
}

impl Curves {
    fn new(
        points: &[Pixel],
        pieces: &[Piece],
        basis: &dyn Basis,
        tolerance: f64,
        min_clearance: f64,
    ) -> Curves {
        let mut c = Curves {
            polys: Vec::with_capacity(pieces.len()),
            tolerances: Vec::with_capacity(pieces.len()),
            zero_certificate: 0,
            no_polynomial: 0,
            thin: 0,
        };
        for p in pieces {
            if p.certificate.is_zero() {
                c.zero_certificate += 1;
                c.polys.push(None);
                c.tolerances.push(tolerance);
                continue;
            }
            match border_polynomial(basis, points, p, OutlierRule::NotInPiece) {
                Some((_, clearance)) if clearance < min_clearance => {
                    c.thin += 1;
                    c.polys.push(None);
                    c.tolerances.push(tolerance);
                }
                Some((poly, clearance)) => {
                    // Fitted cubics must not cross a pixel centre, nor come closer to one
                    // than the minimum clearance: stay within half the clearance and within
                    // the clearance left above the minimum (at least 1/1000 px), and never
                    // beyond the asked tolerance.
                    c.polys.push(Some(poly));
                    let room = (clearance / 2.0).min(clearance - min_clearance);
                    c.tolerances.push(room.clamp(1e-3, tolerance.max(1e-3)));
                }
                None => {
                    c.no_polynomial += 1;
                    c.polys.push(None);
                    c.tolerances.push(tolerance);
                }
            }
        }
        c
    }
}

/// A piece's drawing between two end points: its commands and fitting error, or `None`
/// when it falls back to its cracks.
type Drawn = Option<(Vec<PathCommand>, f64)>;

/// What one drawing of a contour computes that the next repair round can reuse: the
/// intersection at each junction (it depends only on the two curves and the junction), and
/// each piece's path between given end points.
struct Memo {
    /// Per junction, once computed: [`intersect_near`]'s answer.
    intersections: Vec<Option<Option<Point>>>,
    /// Per piece, the paths drawn so far, keyed by their end points.
    paths: Vec<Vec<((Point, Point), Drawn)>>,
}

impl Memo {
    fn new(m: usize) -> Memo {
        Memo {
            intersections: vec![None; m],
            paths: vec![Vec::new(); m],
        }
    }
}

/// One drawing of a contour's pieces; `cracked[j]` draws the end pixel of piece `j` and the
/// start pixel of the next one along their cracks (junction `j`).
fn build(
    points: &[Pixel],
    pieces: &[Piece],
    curves: &Curves,
    cracked: &[bool],
    memo: &mut Memo,
) -> ContourPath {
    let mut out = ContourPath::default();
    let mut b = Builder::new();
    let m = pieces.len();
    out.fallbacks.zero_certificate = curves.zero_certificate;
    out.fallbacks.no_polynomial = curves.no_polynomial;
    out.fallbacks.thin = curves.thin;
    let tolerances = &curves.tolerances;
    let mut polys = curves.polys.clone();
    let pixel_cracks = |i: usize| crack_polyline(points, i, i);
    // A piece whose both end pixels are cracked and that has no more than one pixel between
    // them is drawn along its cracks.
    for k in 0..m {
        let head = cracked[(k + m - 1) % m];
        let tail = cracked[k];
        if polys[k].is_some() && head && tail && pieces[k].len() <= 3 {
            polys[k] = None;
            out.fallbacks.junction += 1;
        }
    }
    // A piece's cracks, only built for the pieces drawn along them (a contour of millions
    // of pixels would otherwise build them all, every round).
    let cracks = |k: usize| crack_polyline(points, pieces[k].first, pieces[k].last);
    // Junction j joins piece j (its end) and piece (j + 1) % m (its start).
    let mut ends = vec![Point::ZERO; m];
    let mut starts = vec![Point::ZERO; m];
    loop {
        out.joins = JoinCounts::default();
        let mut failed = Vec::new();
        for j in 0..m {
            let k = (j + 1) % m;
            let a = pieces[j].last;
            let bi = pieces[k].first;
            let mid = centre(points[a]).midpoint(centre(points[bi]));
            let (end_target, start_target) = if cracked[j] {
                out.joins.cracked += 1;
                let ca = pixel_cracks(a);
                let cb = pixel_cracks(bi);
                (
                    ca.first().copied().unwrap_or(mid),
                    cb.last().copied().unwrap_or(mid),
                )
            } else {
                if let (Some(pa), Some(pb)) = (&polys[j], &polys[k]) {
                    if j != k {
                        let x = *memo.intersections[j].get_or_insert_with(|| {
                            intersect_near(pa, pb, mid, JUNCTION_MAX_DISTANCE)
                        });
                        if let Some(x) = x {
                            ends[j] = x;
                            starts[k] = x;
                            out.joins.intersection += 1;
                            continue;
                        }
                    }
                }
                out.joins.bridged += 1;
                (mid, mid)
            };
            match &polys[j] {
                Some(pa) => match project(pa, end_target, JUNCTION_MAX_DISTANCE) {
                    Some(x) => ends[j] = x,
                    None => failed.push(j),
                },
                None => ends[j] = cracks(j).last().copied().unwrap_or(mid),
            }
            match &polys[k] {
                Some(pb) => match project(pb, start_target, JUNCTION_MAX_DISTANCE) {
                    Some(x) => starts[k] = x,
                    None => failed.push(k),
                },
                None => starts[k] = cracks(k).first().copied().unwrap_or(mid),
            }
        }
        if failed.is_empty() {
            break;
        }
        for j in failed {
            if polys[j].take().is_some() {
                out.fallbacks.junction += 1;
            }
        }
    }
    for (k, piece) in pieces.iter().enumerate() {
        let Some(poly) = &polys[k] else {
            b.polyline(&cracks(k));
            continue;
        };
        let head = cracked[(k + m - 1) % m];
        let tail = cracked[k];
        if head {
            b.polyline(&pixel_cracks(piece.first));
        }
        let (from, to) = (starts[k], ends[k]);
        b.goto(from);
        if !(m > 1 || head || tail) || (to - from).hypot() > 1e-9 {
            let known = memo.paths[k].iter().find(|(ends, _)| *ends == (from, to));
            let drawn = match known {
                Some((_, drawn)) => drawn.clone(),
                None => {
                    let guide: Vec<Point> = points[piece.first..=piece.last]
                        .iter()
                        .map(|&p| centre(p))
                        .collect();
                    let drawn = level_curve_path(poly, from, to, &guide, tolerances[k]).filter(
                        |(cmds, _)| stays_near(from, cmds, &points[piece.first..=piece.last]),
                    );
                    memo.paths[k].push(((from, to), drawn.clone()));
                    drawn
                }
            };
            match drawn {
                Some((cmds, err)) => {
                    out.max_fit_error = out.max_fit_error.max(err);
                    b.extend(cmds);
                }
                None => {
                    out.fallbacks.curve += 1;
                    b.polyline(&cracks(k));
                }
            }
        }
        if tail {
            b.polyline(&pixel_cracks(piece.last));
        }
    }
    out.start = b.start.unwrap_or_default();
    out.commands = b.commands;
    out
}

/// Formats `v` with at most `precision` decimals, trailing zeros stripped, no `-0`.
fn number(v: f64, precision: usize, s: &mut String) {
    if !v.is_finite() {
        s.push('0');
        return;
    }
    // Fast path: v·10^p rounded to an integer that f64 holds exactly (the same digits as
    // `format!` except, rarely, for a value within an ulp of a rounding tie).
    if precision <= 9 {
        let scale = 10f64.powi(precision as i32);
        let n = (v * scale).round_ties_even();
        if n.abs() < 9.0e15 {
            let n = n as i64;
            if n < 0 {
                s.push('-');
            }
            let (scale, n) = (scale as u64, n.unsigned_abs());
            let (int, mut frac) = (n / scale, n % scale);
            let _ = write!(s, "{int}");
            if frac != 0 {
                let mut digits = precision;
                while frac % 10 == 0 {
                    frac /= 10;
                    digits -= 1;
                }
                let _ = write!(s, ".{frac:0digits$}");
            }
            return;
        }
    }
    let mut t = format!("{v:.precision$}");
    if t.contains('.') {
        while t.ends_with('0') {
            t.pop();
        }
        if t.ends_with('.') {
            t.pop();
        }
    }
    if t == "-0" {
        t = "0".into();
    }
    s.push_str(&t);
}

fn point(p: Point, precision: usize, s: &mut String) {
    number(p.x, precision, s);
    s.push(' ');
    number(p.y, precision, s);
}

/// Appends the path data (`M … Z`) of one contour.
fn write_path_data(cp: &ContourPath, precision: usize, s: &mut String) {
    if cp.commands.is_empty() {
        return;
    }
    s.push('M');
    point(cp.start, precision, s);
    for c in &cp.commands {
        match *c {
            PathCommand::Line(p) => {
                s.push('L');
                point(p, precision, s);
            }
            PathCommand::Quad(c1, p) => {
                s.push('Q');
                point(c1, precision, s);
                s.push(' ');
                point(p, precision, s);
            }
            PathCommand::Cubic(c1, c2, p) => {
                s.push('C');
                point(c1, precision, s);
                s.push(' ');
                point(c2, precision, s);
                s.push(' ');
                point(p, precision, s);
            }
            PathCommand::Arc(a) => {
                s.push('A');
                number(a.radii.x, precision, s);
                s.push(' ');
                number(a.radii.y, precision, s);
                s.push(' ');
                number(a.x_rotation.to_degrees().rem_euclid(360.0), precision, s);
                let _ = write!(s, " {} {} ", u8::from(a.large_arc), u8::from(a.sweep));
                point(a.to, precision, s);
            }
        }
    }
    s.push('Z');
}

/// Escapes the five XML special characters of an attribute value.
fn xml_escape(v: &str) -> String {
    let mut s = String::with_capacity(v.len());
    for ch in v.chars() {
        match ch {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            c => s.push(c),
        }
    }
    s
}

/// The SVG document of a decomposition of a `width` × `height` image: one `<path>` with
/// `fill-rule="nonzero"`, outer borders counter-clockwise, holes clockwise, width, height
/// and viewBox the image size in pixels.
pub fn svg_document(d: &Decomposition, width: u32, height: u32, opts: &SvgOptions) -> SvgOutput {
    let basis = d.model.basis();
    let precision = usize::from(opts.precision.min(12));
    // Below 1/1000 px a fit is not asked for: that is the floor of the clearance rule.
    let tolerance = if opts.tolerance.is_finite() && opts.tolerance > 0.0 {
        opts.tolerance.max(1e-3)
    } else {
        SvgOptions::default().tolerance
    };
    // The clearance asked for, plus how far rounding the numbers written moves a point.
    let rounding = std::f64::consts::FRAC_1_SQRT_2 * 10f64.powi(-(precision as i32));
    let min_clearance = match opts.min_clearance {
        0.0 => 0.0,
        m if m > 0.0 => m + rounding,
        _ => SvgOptions::default().min_clearance + rounding,
    };
    let mut commands = CommandCounts::default();
    let mut fallbacks = FallbackCounts::default();
    let mut joins = JoinCounts::default();
    let mut max_fit_error = 0.0f64;
    let empty = Vec::new();
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{width}\" \
         height=\"{height}\" viewBox=\"0 0 {width} {height}\">"
    );
    let mut opened = false;
    // Contours are drawn independently, in parallel, a group at a time (only the group's
    // path data is held besides the document); appended in order, so the document does not
    // depend on the number of threads.
    for (g, group) in d.contours.chunks(CONTOURS_PER_GROUP).enumerate() {
        let parts: Vec<(String, CommandCounts, ContourPath)> = group
            .par_iter()
            .enumerate()
            .map(|(k, contour)| {
                let pieces = d.pieces.get(g * CONTOURS_PER_GROUP + k).unwrap_or(&empty);
                let mut cp = contour_path(contour, pieces, &basis, tolerance, min_clearance);
                let mut data = String::new();
                write_path_data(&cp, precision, &mut data);
                // Only the counts are kept: the commands are written.
                let counts = cp.counts();
                cp.commands = Vec::new();
                (data, counts, cp)
            })
            .collect();
        for (data, counts, cp) in parts {
            commands.add(&counts);
            fallbacks.add(&cp.fallbacks);
            joins.add(&cp.joins);
            max_fit_error = max_fit_error.max(cp.max_fit_error);
            if !data.is_empty() {
                if !opened {
                    let _ = write!(
                        svg,
                        "<path fill=\"{}\" fill-rule=\"nonzero\" d=\"",
                        xml_escape(&opts.fill)
                    );
                    opened = true;
                }
                svg.push_str(&data);
            }
        }
    }
    if opened {
        svg.push_str("\"/>\n");
    }
    svg.push_str("</svg>\n");
    SvgOutput {
        svg,
        commands,
        max_fit_error,
        fallbacks: fallbacks.total(),
        fallback_reasons: fallbacks,
        joins,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose, OutlierRule};
    use crate::fidelity::fidelity;
    use crate::model::Model;

    /// The crossing table agrees with kurbo's winding number at pixel centres away from the
    /// path (random closed paths of lines, quads and cubics, self-intersecting included).
    #[test]
    fn row_winding_agrees_with_kurbo() {
        use kurbo::{ParamCurveNearest, Shape};
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut checked = 0;
        for _ in 0..200 {
            let mut path = BezPath::new();
            let mut pt = || Point::new(next() * 20.0, next() * 20.0);
            path.move_to(pt());
            for k in 0..5 {
                match k % 3 {
                    0 => path.line_to(pt()),
                    1 => path.quad_to(pt(), pt()),
                    _ => path.curve_to(pt(), pt(), pt()),
                }
            }
            path.close_path();
            let index = RowWinding::new(&path);
            for y in -1..21 {
                for x in -1..21 {
                    let c = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                    let clear = path
                        .segments()
                        .all(|s| s.nearest(c, 1e-9).distance_sq > 1e-6);
                    if clear {
                        assert_eq!(index.winding(c), path.winding(c), "at {c:?} of {path:?}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 50_000, "only {checked} centres checked");
        // A vertex exactly on a centre line, reached by a line whose evaluation at 1 misses
        // it by an ulp: counted once.
        let mut path = BezPath::new();
        path.move_to((0.0, -0.969_410_016_966_446_5));
        path.line_to((10.0, 3.5));
        path.line_to((10.0, 8.0));
        path.line_to((0.0, 8.0));
        path.close_path();
        let index = RowWinding::new(&path);
        assert_eq!(
            index.winding(Point::new(12.5, 3.5)),
            0,
            "outside, right of the vertex"
        );
        assert_ne!(index.winding(Point::new(5.5, 3.5)), 0, "inside");
    }

    fn num(v: f64, p: usize) -> String {
        let mut s = String::new();
        number(v, p, &mut s);
        s
    }

    #[test]
    fn compact_numbers() {
        assert_eq!(num(1.5, 3), "1.5");
        assert_eq!(num(2.0, 3), "2");
        assert_eq!(num(-0.0001, 3), "0");
        assert_eq!(num(12.34567, 3), "12.346");
        assert_eq!(num(12.34567, 0), "12");
        assert_eq!(num(f64::NAN, 3), "0");
        assert_eq!(num(-3.25, 1), "-3.2");
        assert_eq!(num(-0.05, 3), "-0.05");
        assert_eq!(
            num(1e300, 3),
            format!("{:.3}", 1e300).trim_end_matches(".000")
        );
        // The integer fast path writes what `format!` writes (away from rounding ties).
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 20_000.0;
            for p in [0, 1, 3, 6] {
                let frac = (v * 10f64.powi(p as i32)).abs().fract();
                if (frac - 0.5).abs() < 1e-6 {
                    continue;
                }
                let mut want = format!("{v:.p$}");
                if want.contains('.') {
                    want = want.trim_end_matches('0').trim_end_matches('.').to_string();
                }
                if want == "-0" {
                    want = "0".into();
                }
                assert_eq!(num(v, p), want, "{v} at precision {p}");
            }
        }
        assert_eq!(xml_escape("a\"<b>&'"), "a&quot;&lt;b&gt;&amp;&apos;");
    }

    #[test]
    fn single_pixel_is_its_square() {
        let mask = Mask::from_ascii("...\n.#.\n...");
        let d = decompose(
            trace(&mask, Convention::Default),
            Model::Line,
            OutlierRule::NotInPiece,
        );
        let out = svg_document(&d, 3, 3, &SvgOptions::default());
        assert!(
            out.svg.contains("d=\"M2 1L1 1L1 2L2 2L2 1Z\""),
            "{}",
            out.svg
        );
        assert_eq!(fidelity(&out.svg, &mask).unwrap().differing, 0);
    }

    #[test]
    fn holes_and_shapes() {
        let mask = Mask::from_ascii(
            "..........
             .########.
             .##....##.
             .#..##..#.
             .##....##.
             .########.
             ..........",
        );
        // Differing pixels as resvg draws the SVG, measured: the circle model's 3 come from
        // the renderer's approximations (usvg's arcs to cubics within 0.1 px, tiny-skia's
        // chords); with the arcs flattened within 0.001 px none differed.
        for (model, bound) in [(Model::Line, 0), (Model::Circle, 3), (Model::Conic, 0)] {
            let d = decompose(
                trace(&mask, Convention::Default),
                model,
                OutlierRule::NotInPiece,
            );
            let out = svg_document(&d, mask.width(), mask.height(), &SvgOptions::default());
            assert_eq!((out.commands.move_to, out.commands.close), (3, 3));
            let r = fidelity(&out.svg, &mask).unwrap();
            assert!(r.differing <= bound, "{model}: {r:?}\n{}", out.svg);
        }
    }

    #[test]
    fn bad_pieces_do_not_panic() {
        let mask = Mask::from_ascii("##\n##");
        let mut d = decompose(
            trace(&mask, Convention::Default),
            Model::Line,
            OutlierRule::NotInPiece,
        );
        let basis = d.model.basis();
        for p in d.pieces[0].iter_mut() {
            p.last += 7;
        }
        let cp = contour_path(&d.contours[0], &d.pieces[0], &basis, 0.05, 0.0);
        assert_eq!(cp.fallbacks.invalid_pieces, 1);
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"2\" height=\"2\"><path d=\"{}\"/></svg>",
            cp.to_bez_path().to_svg()
        );
        assert_eq!(fidelity(&svg, &mask).unwrap().differing, 0);
        let empty = Contour {
            points: Vec::new(),
            hole: false,
            closed: true,
        };
        assert!(contour_path(&empty, &[], &basis, 0.05, 0.0)
            .commands
            .is_empty());
        let out = svg_document(
            &d,
            2,
            2,
            &SvgOptions {
                tolerance: f64::NAN,
                ..SvgOptions::default()
            },
        );
        assert!(out.svg.ends_with("</svg>\n"));
    }

    #[test]
    fn collinear_lines_merge_and_turns_do_not() {
        let mut b = Builder::new();
        let p = |x: f64, y: f64| Point::new(x, y);
        b.polyline(&[
            p(0.0, 0.0),
            p(0.0, 1.0),
            p(0.0, 2.0),
            p(0.0, 3.0),
            p(1.0, 3.0),
        ]);
        b.polyline(&[p(2.0, 3.0), p(1.5, 3.0), p(1.5, 4.0)]);
        b.extend(vec![PathCommand::Line(p(1.5, 5.0))]);
        b.goto(p(1.5, 6.0));
        let ends: Vec<Point> = b.commands.iter().map(|c| c.end()).collect();
        // Down the column in one line; the turn, the reversal along the row and the line
        // after a command added whole are kept.
        assert_eq!(
            ends,
            vec![
                p(0.0, 3.0),
                p(2.0, 3.0),
                p(1.5, 3.0),
                p(1.5, 4.0),
                p(1.5, 5.0),
                p(1.5, 6.0)
            ]
        );
    }
}
