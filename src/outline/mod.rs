//! Outline: the closed path of each contour, from the border curves of its pieces, exact as
//! renderers draw it.
//!
//! # The border curve of a piece
//! A piece with a non-zero certificate is drawn along its level curve (see
//! [`crate::level::border_polynomial`]): its pixel centres on one side, the centres of the
//! background pixels beside it on the other, so a renderer sampling pixel centres puts the
//! piece's pixels inside and the background outside. The curve is drawn by
//! [`crate::curve::level_curve_path`]: lines give `L`, parabolas exact `Q`, circles and
//! ellipses exact arcs turned into cubics here (see [`builder`]), other curves cubics fitted
//! within the tolerance. Consecutive pieces meet at the intersection of their curves, or
//! are bridged (see [`joins`]).
//!
//! # Exact in the renderer
//! Every point is written on a grid of `2^-grid` px (at most 1/64 px, the vertex grid of
//! tiny-skia and Skia), and each contour's path is filled with tiny-skia itself
//! ([`render_check`]): where a contour pixel or the background beside it lands on the wrong
//! side — the renderer cuts curves into chords, rounds vertices — the pieces there are
//! *refined* ([`stretch`]): a curve becomes its exact polygon of digital straight segments
//! (one `L` each), a straight segment that still fails is halved, down to one or two pixels
//! drawn along their cracks. Rounds repeat until the renderer draws every point right, also
//! with the whole path moved by 1/64 px sideways (`ROBUST_SHIFT`: Skia's cuts at
//! Chromium's tile borders move edges that much), and as Chromium draws the document opened
//! at 1:1, tile by tile ([`tiles`]). So
//! cracks remain only where the input has one-pixel features, and curves remain wherever
//! the renderer draws them right. Last, the corners inside the pixel staircases those
//! cracks leave are cut ([`corners`]): half-pixel chamfers that keep every pixel centre on
//! its side, so a lone pixel becomes a diamond and a one-pixel spur a spike. Then vertices
//! between lines that change no pixel go ([`merge`]), and runs of commands along gentle
//! turns become single cubics fitted through the cracks they follow, where the renderer
//! draws them the same ([`absorb`]; not for the line model, whose drawing stays straight).
//!
//! # Orientation
//! Outer borders run counter-clockwise on screen, hole borders clockwise (the foreground
//! on the left); with the `nonzero` fill rule the foreground has winding ±1, holes 0.

mod absorb;
mod band_cells;
mod band_path;
mod band_polygon;
mod builder;
mod chops;
mod coarse;
mod corners;
mod cracks;
mod cubic_fit;
mod curve_clip;
mod cut;
mod edges;
mod extrema;
mod joins;
mod line_clip;
mod mask_fill;
mod merge;
mod nearest;
mod partition;
mod path;
mod path64;
mod render_check;
mod robust;
mod scan;
mod scan_edges;
mod segment_memo;
mod separation;
mod shapes;
mod smooth;
pub(crate) mod staircase;
mod stretch;
mod sure;
pub(crate) mod tiles;
mod vertices;

pub(crate) use band_path::band_contour_path;
pub(crate) use cut::{cut, Loop};
pub(crate) use partition::{corner, loop_path, reverse};
pub use partition::{BorderSource, Partition, PartitionBorder};
pub use path::{CommandCounts, ContourPath, FallbackCounts, JoinCounts};
pub use render_check::EdgeClipping;
pub(crate) use shapes::{ShapeKey, ShapeMemo};
pub(crate) use staircase::has_staircase;

use crate::contour::Contour;
use crate::decompose::Piece;
use crate::model::Basis;
use absorb::absorb_runs;
use builder::Builder;
use coarse::coarse_cracks;
use corners::cut_staircase_corners;
pub(crate) use cracks::{crack_polyline, crack_polyline_into};
use cracks::{pieces_valid, Cracks};
use joins::{build, Memo};
use merge::merge_lines;
use nearest::{nearest_points, points_near};
use render_check::{has_curves, misplaced_pixels, Reference};
use robust::{finely_flattened, misplaced_moved_then_plain};
use smooth::smooth_polygon;
use stretch::{Drawing, Stretch, Stretcher, Unused};
use tiles::misplaced_in_tiles;

/// Finest grid: tiny-skia and Skia round vertices to 1/64 px.
pub const MAX_GRID: u8 = 6;

/// Default minimum clearance (pixels) of a curve to the pixel centres beside it: tiny-skia's
/// chords stray up to about 1/8 px from a curve, so closer curves practically never pass the
/// render check (measured on the 27 shared samples, conic: 21 commands more of 14 229 than
/// trying them all) and trying them costs 7% of the work.
pub const DEFAULT_MIN_CLEARANCE: f64 = 1.0 / 32.0;

/// Default fewest contour points of a curve piece drawn along its curve: a shorter one is
/// drawn as its exact polygon, which joins its neighbours' and is smoothed with them. Along
/// fewer than a dozen pixels the curve's own command saves nothing: 27 shared samples, conic, 8 499
/// commands and 190 374 bytes when every curve is tried, 8 353 and 180 772 with 12 (and 2.2%
/// fewer instructions; 400² random noise, whose pieces are mostly short: 0.81 → 0.48 s);
/// 24 gave 8 279 commands but a pointed top and no dip where the ear meets the bowl on the
/// 120-px glyph g.
pub const DEFAULT_MIN_CURVE_POINTS: usize = 12;

/// Default most contour points of a curve piece drawn along its curve: a longer one is drawn
/// as its exact polygon, smoothed with its neighbours' and drawn in runs' cubics, without
/// its border curve being found. Long curves seldom pass the render check (27 shared samples,
/// conic: 91 kept of the 865 tried on pieces of 24 points or more, against 214 of 760 on
/// 12 to 23), and the runs' cubics draw their polygons' gentle turns in fewer commands: with
/// 24, 8 282 commands and 179 887 bytes instead of 8 318 and 181 605, 10.7% fewer
/// instructions (6.3% in the border curves alone), about as many sharp turns (turns over
/// 30° between consecutive commands: 4 213 against 4 219). The short pieces' curves stay:
/// they hold features that a polygon draws as a corner (the dip where the 120-px glyph g's
/// link meets its bowl). 16 gave 8 262 commands but more sharp turns (4 247); 48, 8 323
/// commands for half the saving.
pub const DEFAULT_MAX_CURVE_POINTS: usize = 24;

/// How [`contour_path`] draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutlineOptions {
    /// Largest distance (pixels) of fitted cubics to their curve; at least 0.001.
    pub tolerance: f64,
    /// Curve pieces (not lines) whose curve passes closer than this (pixels) to a pixel
    /// centre are drawn as their polygon without trying the curve. Default 1/32 px; 0 lets the
    /// renderer check decide for every curve.
    pub min_clearance: f64,
    /// Curve pieces (not lines) of fewer contour points than this are drawn as their polygon
    /// without trying the curve. Default [`DEFAULT_MIN_CURVE_POINTS`]; 0 tries every curve
    /// (with `max_curve_points` 0).
    pub min_curve_points: usize,
    /// Curve pieces (not lines) of more contour points than this are drawn as their polygon
    /// without trying the curve. Default [`DEFAULT_MAX_CURVE_POINTS`]; 0 sets no limit.
    pub max_curve_points: usize,
    /// Points are multiples of `2^-grid` px; at most [`MAX_GRID`].
    pub grid: u8,
    /// Whether tiny-skia will cut the document's curves at their extrema (its edge clipper
    /// runs when the document's path reaches the pixmap's border); [`EdgeClipping::Unknown`]
    /// checks curves both ways.
    pub clipping: EdgeClipping,
    /// The document's pixmap in the contours' coordinates (whole pixels), or `None` when
    /// every path stays well inside it. A path that crosses its border is checked as
    /// tiny-skia draws it there: its edge clipper cuts a curve where it crosses the border,
    /// which moves the chords of what remains; pixels outside are not checked.
    pub canvas: Option<kurbo::Rect>,
    /// Keep the square corners of one-pixel features (pixel art): the corners inside pixel
    /// staircases are not cut (see [`contour_path`]). Default `false`.
    pub square_corners: bool,
    /// Drop the vertices between lines that change no pixel, and draw runs of commands along
    /// gentle turns as single cubics where that changes no pixel (see [`contour_path`]).
    /// Default `true`; the colour layouts keep their commands: a merged edge draws the same
    /// pixel centres in crispEdges but not the same anti-aliased coverage, which the stack's
    /// overlaps rely on, and the partition cuts shared borders at vertices that must stay.
    pub merge_lines: bool,
}

impl Default for OutlineOptions {
    fn default() -> OutlineOptions {
        OutlineOptions {
            tolerance: 0.05,
            min_clearance: DEFAULT_MIN_CLEARANCE,
            min_curve_points: DEFAULT_MIN_CURVE_POINTS,
            max_curve_points: DEFAULT_MAX_CURVE_POINTS,
            grid: 4,
            clipping: EdgeClipping::Unknown,
            canvas: None,
            square_corners: false,
            merge_lines: true,
        }
    }
}

/// Fewest edges of a crack polygon replaced by its coarse stand-in in render checks: on
/// smaller ones, building it costs more than the fills save (27 shared samples).
const MIN_COARSE_CRACKS: usize = 256;

/// Most rounds of drawing, render check and refinement per contour. Refinement halves the
/// stretches that fail, so a stretch of `L` points reaches one or two points after about
/// `log2 L` rounds.
const MAX_ROUNDS: usize = 40;

/// Sideways move (px) under which a drawing must stay exact: Chromium cuts paths at the
/// borders of its raster tiles and rounds the new ends to 1/64 px, which moves an
/// edge's crossing of a row of pixel centres by up to about that much. Where the document
/// is the page, the cuts themselves are checked ([`tiles`]); where a page puts a document
/// embedded in it is unknown, hence this move as well.
pub(crate) const ROBUST_SHIFT: f64 = 1.0 / 64.0;

/// The whole contour along its cracks.
fn cracks_path(points: &[crate::pixel::Pixel]) -> ContourPath {
    cracks_path_through(&crack_polyline(points, 0, points.len().saturating_sub(1)))
}

/// What a contour's drawings are checked against: its crack polygon, and the coarse
/// stand-in filled in its place where it has one (see [`coarse`]).
struct References {
    /// The crack polygon.
    cracks: Reference,
    /// The coarse stand-in, filled by tiny-skia exactly like the cracks with far fewer
    /// edges to set up in every fill.
    coarse: Option<Reference>,
}

impl References {
    /// The references of the contour through the crack corners `polyline`.
    fn new(polyline: &[kurbo::Point]) -> References {
        let c = cracks_path_through(polyline);
        let cracks = Reference::new(c.start, &c.commands);
        let coarse = (c.commands.len() >= MIN_COARSE_CRACKS)
            .then(|| coarse_cracks(c.start, &c.commands))
            .flatten()
            .map(|(start, coarse)| {
                debug_assert!(
                    misplaced_pixels(&cracks, start, &coarse, EdgeClipping::Never, None).is_empty(),
                    "the coarse crack polygon fills differently"
                );
                Reference::new(start, &coarse)
            });
        References { cracks, coarse }
    }

    /// The reference to fill: the coarse stand-in, else the cracks.
    fn fill(&self) -> &Reference {
        self.coarse.as_ref().unwrap_or(&self.cracks)
    }
}

/// The whole contour along its cracks, from its crack corners `polyline`
/// ([`crack_polyline`]).
fn cracks_path_through(polyline: &[kurbo::Point]) -> ContourPath {
    let mut b = Builder::with_capacity(0, polyline.len());
    b.polyline(polyline);
    let (start, commands) = b.into_commands();
    ContourPath {
        start: start.unwrap_or_default(),
        commands,
        ..ContourPath::default()
    }
}

/// The closed path of one contour decomposed into `pieces` described in `basis`, exact in
/// tiny-skia (see the module documentation).
///
/// ```
/// use layertrace::{contour_path, decompose, trace, Convention, Mask, Model, OutlierRule};
/// use layertrace::OutlineOptions;
/// let mask = Mask::from_ascii(
///     "........
///      ..####..
///      .######.
///      .######.
///      ..####..
///      ........",
/// );
/// let d = decompose(trace(&mask, Convention::Default), Model::Conic, OutlierRule::NotInPiece);
/// let basis = Model::Conic.basis();
/// let path = contour_path(&d.contours[0], &d.pieces[0], &basis, &OutlineOptions::default());
/// assert!(!path.commands.is_empty());
/// // Every point is on the grid of 2^-grid pixels.
/// let grid = f64::from(1u32 << OutlineOptions::default().grid);
/// assert_eq!((path.start.x * grid).fract(), 0.0);
/// ```
pub fn contour_path(
    contour: &Contour,
    pieces: &[Piece],
    basis: &dyn Basis,
    opts: &OutlineOptions,
) -> ContourPath {
    let (mut references, mut polyline) = (None, None);
    let mut path = exact_path(contour, pieces, basis, opts, &mut references, &mut polyline);
    // Where one-pixel features leave a staircase, its corners are cut (no pixel changes).
    if !opts.square_corners {
        if let Some((start, commands)) =
            cut_staircase_corners(path.start, &path.commands, opts.grid.min(MAX_GRID))
        {
            path.start = start;
            path.commands = commands;
        }
    }
    // Then vertices between lines that change no pixel go (the cut corners' too).
    if opts.merge_lines {
        if let Some(merged) = merge_lines(
            path.start,
            &path.commands,
            opts.canvas,
            opts.grid.min(MAX_GRID),
        ) {
            // A merge may join a cut corner's chamfer to its neighbour and bring a step of a
            // staircase back: such merges are not kept.
            if !has_staircase(path.start, &merged) || has_staircase(path.start, &path.commands) {
                path.commands = merged;
            }
        }
        // And runs along gentle turns become single cubics (the line model stays straight).
        // (A path of fewer than three commands has no run: see `absorb_runs`.)
        let n = contour.points.len();
        if n > 1
            && path.commands.len() >= 3
            && basis.dim() > crate::model::Model::line_basis().dim()
        {
            let polyline =
                polyline.get_or_insert_with(|| crack_polyline(&contour.points, 0, n - 1));
            let cracks = Cracks::new(polyline);
            if let Some(absorbed) = absorb_runs(
                path.start,
                &path.commands,
                &cracks,
                opts.grid.min(MAX_GRID),
                opts.clipping,
                opts.canvas,
            ) {
                // Each run's loop paints nothing, but the whole path is checked as a contour
                // is: tiny-skia cuts curves at their extrema in `f32`, whose rounding depends
                // on the origin (one pixel of 24 random ellipses in a test).
                let refs = references.get_or_insert_with(|| References::new(polyline));
                if misplaced_anywhere(refs.fill(), &refs.cracks, absorbed.0, &absorbed.1, opts)
                    .is_empty()
                {
                    (path.start, path.commands) = absorbed;
                }
            }
        }
    }
    path
}

/// The pixels the path `M start commands Z` draws wrong against `reference` (the contour's
/// crack polygon or its coarse stand-in; `cracks` the crack polygon itself), by the first
/// check that finds any: moved by [`ROBUST_SHIFT`], plain, both ways of drawing curves,
/// in Chromium's tiles, finely flattened. Empty when the path is exact. A path of lines
/// whose every fill is known without one ([`sure::path_misplaced`]) is not filled.
fn misplaced_anywhere(
    reference: &Reference,
    cracks: &Reference,
    start: kurbo::Point,
    commands: &[crate::curve::PathCommand],
    opts: &OutlineOptions,
) -> Vec<crate::pixel::Pixel> {
    // A path of lines clear of every pixel centre is wrong exactly where it winds otherwise
    // than the cracks, without a fill (on 400² noise, 2 477 of the 3 889 checks of paths of
    // lines are exact so, and 682 wrong). The fills would give the same pixels against the
    // coarse stand-in, which tiny-skia fills winding for winding like the cracks.
    if let Some(wrong) = sure::path_misplaced(cracks, start, commands, opts.canvas) {
        return wrong;
    }
    misplaced_when_filled(reference, cracks, start, commands, opts)
}

/// [`misplaced_anywhere`] by the fills alone.
fn misplaced_when_filled(
    reference: &Reference,
    cracks: &Reference,
    start: kurbo::Point,
    commands: &[crate::curve::PathCommand],
    opts: &OutlineOptions,
) -> Vec<crate::pixel::Pixel> {
    // Unknown clipping draws curves both ways; the second way is only tried once the first
    // draws every pixel right (what it finds then is remedied in the next round): one fill
    // per round instead of two.
    let first_way = match opts.clipping {
        EdgeClipping::Unknown => EdgeClipping::Never,
        known => known,
    };
    // Moved by 1/64 px sideways first: no edge may cross a row of pixel centres within
    // 1/64 px of a centre, where Skia's fixed point (Chromium) may round it to the other
    // side. Where the plain fill is wrong the moved one mostly is too, and it also finds
    // the fragile places, so one round remedies both (27 shared samples, conic: 4% fewer
    // rounds, 5% fewer instructions in all).
    let mut wrong = misplaced_moved_then_plain(
        reference,
        start,
        commands,
        ROBUST_SHIFT,
        first_way,
        opts.canvas,
    );
    // (A path without curves was just filled: lines are drawn the same both ways.)
    if wrong.is_empty() && first_way != opts.clipping && has_curves(commands) {
        wrong = misplaced_pixels(
            reference,
            start,
            commands,
            EdgeClipping::Always,
            opts.canvas,
        );
    }
    if wrong.is_empty() {
        // Exact in Chromium's tiles too, where they cut the path (see `tiles`); against the
        // cracks themselves, which a cut at a whole pixel leaves as they are (the coarse
        // stand-in's slanted edges would be tilted too).
        wrong = misplaced_in_tiles(cracks, start, commands, opts.canvas);
    }
    if wrong.is_empty() {
        // Exact in tiny-skia; also with the true curves (other renderers).
        if let Some(fine) = finely_flattened(start, commands) {
            wrong = misplaced_pixels(reference, start, &fine, EdgeClipping::Never, None);
        }
    }
    wrong
}

/// [`contour_path`] before the corners of its staircases are cut.
///
/// `polyline` (the caller's, `None` at first) holds the contour's [`crack_polyline`] once
/// made, and `references` (the caller's, `None` at first) the contour's [`References`] once a
/// drawing has been checked against them.
fn exact_path(
    contour: &Contour,
    pieces: &[Piece],
    basis: &dyn Basis,
    opts: &OutlineOptions,
    references: &mut Option<References>,
    polyline: &mut Option<Vec<kurbo::Point>>,
) -> ContourPath {
    let points = &contour.points;
    let n = points.len();
    if n <= 1 || !pieces_valid(n, pieces) {
        let mut out = cracks_path(points);
        if n > 1 {
            out.fallbacks.invalid_pieces += 1;
        }
        return out;
    }
    let tolerance = if opts.tolerance.is_finite() && opts.tolerance > 0.0 {
        opts.tolerance.max(1e-3)
    } else {
        OutlineOptions::default().tolerance
    };
    let grid = opts.grid.min(MAX_GRID);
    let mut st = Stretcher::new(points, tolerance);
    // Polygons that replace curves may become renderer-safe cubics; the line model's stay
    // straight.
    let smooth = !st.is_line_basis(basis);
    let mut fallbacks = FallbackCounts::default();
    let mut stretches: Vec<Stretch> = Vec::with_capacity(pieces.len());
    // Consecutive pieces whose curves are unused share one polygon: its segments run across
    // the pieces' ends instead of stopping at each.
    let mut unused_run: Option<(usize, usize)> = None;
    // The sizes (contour points) of the curve pieces whose curve is tried.
    let sizes = opts.min_curve_points..=match opts.max_curve_points {
        0 => usize::MAX,
        most => most,
    };
    for p in pieces {
        let (s, unused) = st.piece(basis, p, opts.min_clearance, &sizes);
        match unused {
            None => {
                if let Some((a, b)) = unused_run.take() {
                    st.polygon_into(a, b, &mut stretches);
                }
                stretches.push(s);
            }
            Some(reason) => {
                match reason {
                    Unused::Thin => fallbacks.thin += 1,
                    Unused::Short => fallbacks.short += 1,
                    Unused::Long => fallbacks.long += 1,
                    Unused::NoPolynomial => fallbacks.no_polynomial += 1,
                    Unused::ZeroCertificate => {}
                }
                unused_run = Some(match unused_run {
                    Some((a, _)) => (a, p.last),
                    None => (p.first, p.last),
                });
            }
        }
    }
    if let Some((a, b)) = unused_run {
        st.polygon_into(a, b, &mut stretches);
    }
    let mut cracked = vec![false; stretches.len()];
    let mut keep_bridge = vec![false; stretches.len()];
    let mut memo = Memo::default();
    for _ in 0..MAX_ROUNDS {
        let built = build(
            points,
            &stretches,
            &cracked,
            &keep_bridge,
            &mut memo,
            grid,
            smooth,
        );
        let m = stretches.len();
        let mut refine = vec![false; m];
        for &k in &built.failed {
            if stretches[k].refinable() {
                refine[k] = true;
                fallbacks.curve += usize::from(stretches[k].drawing == Drawing::Curve);
            }
        }
        let mut changed = refine.iter().any(|&r| r);
        if !changed {
            let path = built.path;
            // Cracks alone are the pixel border itself.
            if stretches.iter().all(|s| s.drawing == Drawing::Cracks) && built.failed.is_empty() {
                return finish(path, &stretches, fallbacks);
            }
            let refs = references.get_or_insert_with(|| {
                References::new(polyline.get_or_insert_with(|| crack_polyline(points, 0, n - 1)))
            });
            let (reference, cracks) = (refs.fill(), &refs.cracks);
            let wrong = misplaced_anywhere(reference, cracks, path.start, &path.commands, opts);
            if wrong.is_empty() {
                let mut path = path;
                if built.smooth.iter().any(|&t| t) {
                    path.commands = smooth_polygon(
                        path.start,
                        &path.commands,
                        &built.smooth,
                        reference,
                        grid,
                        opts.clipping,
                        opts.canvas,
                    );
                }
                return finish(path, &stretches, fallbacks);
            }
            let holding = |q: usize| {
                stretches
                    .partition_point(|s| s.last < q)
                    .min(stretches.len() - 1)
            };
            // Remedies at the contour points nearest to the wrong pixels; if none applies
            // there (a thin part, where another stretch passes by), at every point near
            // them.
            for pass in 0..2 {
                if changed {
                    break;
                }
                let bad = if pass == 0 {
                    nearest_points(points, &wrong)
                } else {
                    points_near(points, &wrong, 2)
                };
                for &i in &bad {
                    // First remedy: bridges back at the shared vertices of the stretches
                    // around `i` (a shared vertex tilts its whole segment).
                    let mut unshared = false;
                    for q in [i + n - 1, i, i + 1] {
                        let k = holding(q % n);
                        for j in [(k + m - 1) % m, k] {
                            if built.shared[j] && !keep_bridge[j] {
                                keep_bridge[j] = true;
                                unshared = true;
                                changed = true;
                            }
                        }
                    }
                    if unshared {
                        continue;
                    }
                    let mut near_refinable = false;
                    for q in [i + n - 1, i, i + 1] {
                        let k = holding(q % n);
                        if stretches[k].refinable() {
                            near_refinable = true;
                            if !refine[k] {
                                refine[k] = true;
                                changed = true;
                                fallbacks.rendered +=
                                    usize::from(stretches[k].drawing == Drawing::Curve);
                            }
                        }
                    }
                    if near_refinable {
                        continue;
                    }
                    // Only cracks and one- or two-point stretches around: draw the end pixels
                    // at the junctions within two points of `i` along their cracks.
                    let cyclic = |p: usize| {
                        let d = p.abs_diff(i);
                        d.min(n - d)
                    };
                    for back in 0..6 {
                        let j = holding((i + n + 2 - back % n) % n);
                        let near =
                            cyclic(stretches[j].last).min(cyclic((stretches[j].last + 1) % n));
                        if near <= 2 && !cracked[j] {
                            cracked[j] = true;
                            changed = true;
                        }
                    }
                }
            }
            if !changed {
                // Nothing left to refine: the contour along its cracks is exact.
                let mut out = cracks_path(points);
                fallbacks.invalid_pieces += 1;
                out.fallbacks = fallbacks;
                return out;
            }
        }
        if refine.iter().any(|&r| r) {
            let mut next = Vec::with_capacity(m + 8);
            let mut next_cracked = Vec::with_capacity(m + 8);
            let mut next_keep = Vec::with_capacity(m + 8);
            let mut k = 0;
            while k < m {
                let s = &stretches[k];
                // Consecutive curves refined together become one polygon (see above).
                let curve_run = |j: usize| refine[j] && stretches[j].drawing == Drawing::Curve;
                let straight = |j: usize| {
                    !refine[j] && !cracked[j] && stretches[j].drawing == Drawing::Straight
                };
                // At most one straight segment before the first curve (the start of the run)
                // and one after the last: the segments farther away would come out the same.
                let lead = usize::from(straight(k) && k + 1 < m && curve_run(k + 1));
                let mut end = k + lead;
                let has_curve = curve_run(end);
                if has_curve {
                    while end + 1 < m && curve_run(end + 1) {
                        end += 1;
                    }
                    if end + 1 < m && straight(end + 1) {
                        end += 1;
                    }
                }
                // What replaces stretches `k..=end` (the last part keeps `end`'s flags).
                let parts = if has_curve && end > k {
                    Some(st.polygon(s.first, stretches[end].last))
                } else {
                    let parts = refine[k].then(|| st.refine(s)).flatten();
                    if parts.is_some() {
                        fallbacks.split += usize::from(s.drawing == Drawing::Straight);
                    }
                    parts
                };
                match parts {
                    Some(parts) => {
                        let last = parts.len() - 1;
                        for (i, p) in parts.into_iter().enumerate() {
                            next.push(p);
                            next_cracked.push(i == last && cracked[end]);
                            next_keep.push(i == last && keep_bridge[end]);
                        }
                    }
                    None => {
                        next.push(s.clone());
                        next_cracked.push(cracked[k]);
                        next_keep.push(keep_bridge[k]);
                    }
                }
                k = end + 1;
            }
            stretches = next;
            cracked = next_cracked;
            keep_bridge = next_keep;
        }
    }
    // Did not converge (not seen): the contour along its cracks is exact.
    let mut out = cracks_path(points);
    fallbacks.invalid_pieces += 1;
    out.fallbacks = fallbacks;
    out
}

/// The path with its fallback counts (one- and two-point stretches counted at the end).
fn finish(
    mut path: ContourPath,
    stretches: &[Stretch],
    mut fallbacks: FallbackCounts,
) -> ContourPath {
    fallbacks.zero_certificate = stretches
        .iter()
        .filter(|s| s.drawing == Drawing::Cracks)
        .count();
    path.fallbacks = fallbacks;
    path
}

#[cfg(test)]
mod tests;
