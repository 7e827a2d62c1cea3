//! SVG export: the contour paths of a [`Decomposition`] (see [`crate::outline`]) written as
//! one `<path>`.
//!
//! # The document
//! `<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="W" height="H"
//! viewBox="0 0 W H">` with the image size in pixels (one user unit = one pixel, pixel
//! `(x, y)` = the square `[x, x+1] × [y, y+1]`), holding one `<path d="…" fill="…"
//! fill-rule="nonzero"/>` with all contours (none for an image without foreground), and
//! nothing else. Every number is a multiple of `2^-grid` ([`SvgOptions::grid`]) written
//! exactly (at most `grid` decimals, trailing zeros and leading zeros stripped); each
//! contour starts with an absolute `M`, the other commands are relative (`l`, `h`, `v`,
//! `q`, `c`; see `write_path_data`); there is no `A` (arcs are written as the cubics the
//! outline checked).
//!
//! # Fill rule
//! Outer borders run counter-clockwise on screen, holes clockwise. `nonzero` is preferred
//! over `evenodd` because subpaths of the same orientation that overlap slightly (curves of
//! nearby borders crossing near a thin background gap, or a bridge segment folding back)
//! stay filled instead of cancelling out.

use crate::bitmap::Band;
use crate::contour::largest_first;
use crate::curve::PathCommand;
use crate::decompose::Decomposition;
use crate::outline::tiles::one_tile;
use crate::outline::{
    band_contour_path, contour_path, has_staircase, CommandCounts, ContourPath, EdgeClipping,
    FallbackCounts, JoinCounts, OutlineOptions, ShapeKey, ShapeMemo, MAX_GRID,
};
use kurbo::Point;
use rayon::prelude::*;
use std::fmt::Write as _;

/// Contours drawn per parallel group by [`svg_document`]: only one group's drawings are
/// held at a time besides the document.
const CONTOURS_PER_GROUP: usize = 4096;

/// How [`svg_document`] writes the SVG.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgOptions {
    /// The `fill` attribute of the path (XML-escaped on output). Default `black`.
    pub fill: String,
    /// Coordinates are multiples of `2^-grid` pixel, written exactly; at most 6 (1/64 px,
    /// the vertex grid of tiny-skia and Skia), larger values act as 6. Default 4 (1/16 px:
    /// at most four decimals).
    pub grid: u8,
    /// Largest distance (pixels) of fitted cubic Béziers to the true curve (hyperbolas,
    /// degenerate conics, degree > 2). Default 0.05; values below 0.001 act as 0.001, and
    /// non-finite or non-positive ones as the default.
    pub tolerance: f64,
    /// A curve piece (not a line) whose border curve passes closer than this (pixels) to a
    /// pixel centre is drawn as its exact polygon without trying the curve. Default 1/32 (such curves
    /// practically never pass the render check); 0 tries every curve. Negative or NaN
    /// values mean the default.
    pub min_clearance: f64,
    /// Keep the square corners of one-pixel features (lone pixels, one-pixel spurs and
    /// notches), for pixel art. Default `false`: the corners inside a pixel staircase are
    /// cut by half a pixel (a lone pixel becomes a diamond), which changes no pixel.
    pub square_corners: bool,
}

impl Default for SvgOptions {
    fn default() -> SvgOptions {
        SvgOptions {
            fill: "black".into(),
            grid: OutlineOptions::default().grid,
            tolerance: 0.05,
            min_clearance: crate::outline::DEFAULT_MIN_CLEARANCE,
            square_corners: false,
        }
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

/// Appends the decimal digits of `n`, zero-padded to `width` digits (without the
/// formatting machinery: a large SVG writes millions of numbers).
fn push_digits(mut n: u64, width: usize, s: &mut String) {
    let mut buf = [0u8; 20];
    let mut k = buf.len();
    while n > 0 || buf.len() - k < width {
        k -= 1;
        buf[k] = b'0' + (n % 10) as u8;
        n /= 10;
    }
    s.extend(buf[k..].iter().map(|&b| char::from(b)));
}

/// Formats `v` with at most `precision` decimals, trailing zeros stripped, no `-0` (also
/// the number writer of the PDF and EPS exports).
pub(crate) fn number(v: f64, precision: usize, s: &mut String) {
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
            push_digits(int, 1, s);
            if frac != 0 {
                let mut digits = precision;
                while frac % 10 == 0 {
                    frac /= 10;
                    digits -= 1;
                }
                s.push('.');
                push_digits(frac, digits, s);
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

/// Appends one number, separated from what precedes it by a space unless a command letter
/// or its own minus sign separates it.
fn push_number(v: f64, precision: usize, after_number: bool, s: &mut String) {
    let start = s.len();
    number(v, precision, s);
    // No leading zero: `.5`, `-.25` (most relative coordinates are below one pixel).
    let sign = usize::from(s[start..].starts_with('-'));
    if s[start + sign..].starts_with("0.") {
        s.remove(start + sign);
    }
    if after_number && sign == 0 {
        s.insert(start, ' ');
    }
}

/// Appends the path data (`M … Z`) of one contour, compactly: coordinates relative to the
/// pen (`l`, `h`, `v`, `q`, `c`; `M` and `A` absolute), a command letter only when it
/// changes, a space only where no minus sign separates two numbers, and no final line back
/// to the start (`Z` draws it).
///
/// Exact: every point is on the 2^-grid grid, so each difference is a dyadic number with at
/// most `precision` decimals, written exactly, and the sum a renderer forms again (in `f64`
/// in usvg, in `f32` in Skia: exact below 2^24 grid units) is the point itself.
///
/// Every absolute point (`M`, `A`) is written moved by `-shift` in x and y (an integer
/// shift keeps the points exact and the relative numbers the same).
pub(crate) fn write_path_data(cp: &ContourPath, precision: usize, shift: f64, s: &mut String) {
    if cp.commands.is_empty() {
        return;
    }
    let moved = |p: Point| Point::new(p.x - shift, p.y - shift);
    s.push('M');
    point(moved(cp.start), precision, s);
    let mut pen = cp.start;
    let mut last = 'M';
    for c in &cp.commands {
        // (letter, relative numbers)
        let mut nums = [0.0f64; 6];
        let (letter, count) = match *c {
            PathCommand::Line(p) => {
                let d = p - pen;
                if d.y == 0.0 {
                    nums[0] = d.x;
                    ('h', 1)
                } else if d.x == 0.0 {
                    nums[0] = d.y;
                    ('v', 1)
                } else {
                    nums[..2].copy_from_slice(&[d.x, d.y]);
                    ('l', 2)
                }
            }
            PathCommand::Quad(c1, p) => {
                let (a, b) = (c1 - pen, p - pen);
                nums[..4].copy_from_slice(&[a.x, a.y, b.x, b.y]);
                ('q', 4)
            }
            PathCommand::Cubic(c1, c2, p) => {
                let (a, b, e) = (c1 - pen, c2 - pen, p - pen);
                nums.copy_from_slice(&[a.x, a.y, b.x, b.y, e.x, e.y]);
                ('c', 6)
            }
            PathCommand::Arc(a) => {
                s.push('A');
                number(a.radii.x, precision, s);
                s.push(' ');
                number(a.radii.y, precision, s);
                s.push(' ');
                number(a.x_rotation.to_degrees().rem_euclid(360.0), precision, s);
                let _ = write!(s, " {} {} ", u8::from(a.large_arc), u8::from(a.sweep));
                point(moved(a.to), precision, s);
                pen = a.to;
                last = 'A';
                continue;
            }
        };
        let repeat = letter == last;
        if !repeat {
            s.push(letter);
        }
        for (k, &v) in nums[..count].iter().enumerate() {
            push_number(v, precision, repeat || k > 0, s);
        }
        last = letter;
        pen = c.end();
    }
    s.push('Z');
}

/// Drops a final line back to the start: `Z` draws it.
pub(crate) fn drop_closing_line(cp: &mut ContourPath) {
    if cp.commands.len() > 2 && cp.commands.last() == Some(&PathCommand::Line(cp.start)) {
        cp.commands.pop();
    }
}

/// Escapes the five XML special characters of an attribute value.
pub(crate) fn xml_escape(v: &str) -> String {
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
///
/// ```
/// use layertrace::{decompose, svg_document, trace, Convention, Mask, Model, OutlierRule};
/// use layertrace::SvgOptions;
/// let mask = Mask::from_ascii("......\n.####.\n.#..#.\n.####.\n......");
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let out = svg_document(&d, 6, 5, &SvgOptions::default());
/// assert!(out.svg.starts_with("<svg") || out.svg.starts_with("<?xml"));
/// // One outer border and one hole: two closed subpaths.
/// assert_eq!((out.commands.move_to, out.commands.close), (2, 2));
/// ```
pub fn svg_document(d: &Decomposition, width: u32, height: u32, opts: &SvgOptions) -> SvgOutput {
    svg_document_reporting(d, width, height, opts, None, &|_| {})
}

/// The smooth SVG document of a decomposition of `mask`: every contour drawn with curves
/// through the border band of `band` (the pixels within ν of `mask`'s border) instead of
/// along its pieces, so that every pixel resvg (crispEdges) draws differently from `mask`
/// is within ν of the border. The pieces are not used (only the contours).
///
/// ```
/// use layertrace::{decompose, fidelity, smooth_svg_document, trace, Band, Convention, Mask,
///                  Model, OutlierRule, SvgOptions};
///
/// let mask = Mask::from_fn(40, 40, |x, y| {
///     let (dx, dy) = (x as f64 - 19.5, y as f64 - 19.5);
///     dx * dx + dy * dy <= 15.0 * 15.0
/// });
/// let band = Band::new(&mask, 1.0).unwrap();
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let svg = smooth_svg_document(&d, &band, 40, 40, &SvgOptions::default());
/// let report = fidelity(&svg.svg, &mask).unwrap();
/// assert!(svg.commands.cubic > 0 && svg.commands.line == 0);
/// println!("{} px differ, all within 1 px of the border", report.differing);
/// ```
pub fn smooth_svg_document(
    d: &Decomposition,
    band: &Band,
    width: u32,
    height: u32,
    opts: &SvgOptions,
) -> SvgOutput {
    svg_document_reporting(d, width, height, opts, Some(band), &|_| {})
}

/// [`svg_document`], calling `done` with the number of contours drawn so far after each
/// group of them.
pub(crate) fn svg_document_reporting(
    d: &Decomposition,
    width: u32,
    height: u32,
    opts: &SvgOptions,
    band: Option<&Band>,
    done: &(dyn Fn(usize) + Sync),
) -> SvgOutput {
    let outline = outline_options(opts, width, height, 0);
    // Where neither resvg nor Chromium will clip the document's path, curves need only be
    // right as drawn whole (see `unclipped`); if a point strayed within a pixel of the
    // border after all, the document is drawn again checking both ways.
    let paths = if unclipped(d, width, height) {
        let never = OutlineOptions {
            clipping: EdgeClipping::Never,
            ..outline
        };
        let paths = path_data(d, &never, band, 0, done);
        if paths.bounds.is_none_or(|b| {
            b.x0 >= 1.0
                && b.y0 >= 1.0
                && b.x1 <= f64::from(width) - 1.0
                && b.y1 <= f64::from(height) - 1.0
        }) {
            paths
        } else {
            // Progress was told once already: the bar stays full while this (rare, and on
            // a page under 512 px short) second drawing runs.
            path_data(d, &outline, band, 0, &|_| {})
        }
    } else {
        path_data(d, &outline, band, 0, done)
    };
    let header = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{width}\" \
         height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n"
    );
    let mut svg = header;
    if !paths.data.is_empty() {
        let _ = write!(
            svg,
            "<path fill=\"{}\" fill-rule=\"nonzero\" d=\"",
            xml_escape(&opts.fill)
        );
        svg.push_str(&paths.data);
        svg.push_str("\"/>\n");
    }
    svg.push_str("</svg>\n");
    paths.into_output(svg)
}

/// Fewest pixels between every contour pixel and the image border for [`unclipped`]:
/// curves stay within 2 px of their pixels' squares (checked after drawing).
const UNCLIPPED_MARGIN: i32 = 3;

/// Whether the `width` × `height` document of `d` is drawn by resvg and by Chromium (the
/// SVG opened as the page at 1:1) without their edge clippers, which cut curves at their
/// extrema before subdividing them: the page is drawn in one tile ([`one_tile`]; a
/// page of several tiles has its path clipped by each), and every contour pixel lies at
/// least [`UNCLIPPED_MARGIN`] pixels inside the border, so that the path's bounds, rounded
/// out by about half a pixel (tiny-skia's and Skia's `conservative_round_to_int`), stay
/// inside the pixmap. The caller checks those bounds after drawing. (tiny-skia's own tiles,
/// above 8191 px, are far beyond a page of one Chromium tile.)
fn unclipped(d: &Decomposition, width: u32, height: u32) -> bool {
    let m = UNCLIPPED_MARGIN;
    one_tile(i64::from(width), i64::from(height))
        && d.contours.iter().flat_map(|c| &c.points).all(|p| {
            p.x >= m
                && p.y >= m
                && i64::from(p.x) + i64::from(m) < i64::from(width)
                && i64::from(p.y) + i64::from(m) < i64::from(height)
        })
}

/// The outline options of [`SvgOptions`] for a `width` × `height` document whose contours
/// are in the coordinates of the image padded by `margin` pixels.
pub(crate) fn outline_options(
    opts: &SvgOptions,
    width: u32,
    height: u32,
    margin: u32,
) -> OutlineOptions {
    let m = f64::from(margin);
    let grid = opts.grid.min(MAX_GRID);
    OutlineOptions {
        tolerance: opts.tolerance,
        min_clearance: if opts.min_clearance >= 0.0 {
            opts.min_clearance
        } else {
            SvgOptions::default().min_clearance
        },
        grid,
        // Curves are checked in both of tiny-skia's edge modes even where resvg will not
        // clip the document: Chromium draws large paths tile by tile, each tile clipping
        // them. Checking the unclipped mode alone when every contour lay 3 px inside the
        // image left 26 px wrong in Chromium on the 27 shared samples instead of 12 (conic),
        // for 14% less time. The SVG document narrows this to the unclipped mode on pages
        // drawn in one tile (see `unclipped`).
        clipping: EdgeClipping::Unknown,
        canvas: Some(kurbo::Rect::new(
            m,
            m,
            m + f64::from(width),
            m + f64::from(height),
        )),
        square_corners: opts.square_corners,
        merge_lines: true,
    }
}

/// The path data of every contour of a decomposition, and what went into it.
pub(crate) struct PathData {
    /// The `d` attribute's value (empty without contours).
    pub(crate) data: String,
    /// The bounds of every point written ([`ContourPath::point_bounds`]), before the shift.
    bounds: Option<kurbo::Rect>,
    commands: CommandCounts,
    max_fit_error: f64,
    fallbacks: FallbackCounts,
    joins: JoinCounts,
}

impl PathData {
    /// The [`SvgOutput`] of the document `svg` drawn with these paths alone.
    pub(crate) fn into_output(self, svg: String) -> SvgOutput {
        let mut out = empty_output(svg);
        out.add(&self);
        out
    }
}

/// An [`SvgOutput`] of `svg` with no command counted.
pub(crate) fn empty_output(svg: String) -> SvgOutput {
    SvgOutput {
        svg,
        commands: CommandCounts::default(),
        max_fit_error: 0.0,
        fallbacks: 0,
        fallback_reasons: FallbackCounts::default(),
        joins: JoinCounts::default(),
    }
}

impl SvgOutput {
    /// Counts the commands, fallbacks and joins of `paths` in this output.
    pub(crate) fn add(&mut self, paths: &PathData) {
        self.commands += &paths.commands;
        self.fallback_reasons += &paths.fallbacks;
        self.fallbacks = self.fallback_reasons.total();
        self.joins += &paths.joins;
        self.max_fit_error = self.max_fit_error.max(paths.max_fit_error);
    }
}

/// One contour's drawing once written: its path data, its counts, its path without the
/// commands (the fallbacks, joins and fit error it reports), and the bounds of its points.
struct Written {
    data: String,
    counts: CommandCounts,
    path: ContourPath,
    bounds: Option<kurbo::Rect>,
}

/// Draws every contour of `d` (see [`crate::outline`]; with `band`, smooth within it) and
/// writes its path data, moved by
/// `-shift` pixels in x and y, calling `done` with the number of contours drawn so far
/// after each group of them.
pub(crate) fn path_data(
    d: &Decomposition,
    outline: &OutlineOptions,
    band: Option<&Band>,
    shift: u32,
    done: &(dyn Fn(usize) + Sync),
) -> PathData {
    let shift = f64::from(shift);
    let basis = d.model.basis();
    // Multiples of 2^-grid have at most `grid` decimals: written exactly.
    let precision = usize::from(outline.grid);
    let mut commands = CommandCounts::default();
    let mut fallbacks = FallbackCounts::default();
    let mut joins = JoinCounts::default();
    let mut max_fit_error = 0.0f64;
    let mut bounds: Option<kurbo::Rect> = None;
    let empty = Vec::new();
    let mut svg = String::new();
    // Contours are drawn independently, in parallel, a group at a time (only the group's
    // path data is held besides the document); appended in order, so the document does not
    // depend on the number of threads.
    // Tiny contours are drawn once per shape (see `ShapeMemo`: at most 65 536 shapes are
    // held, 33 MB in all on 2000² noise); not with a band, whose drawing depends on the
    // mask round the contour.
    let mut memo = ShapeMemo::default();
    for (g, group) in d.contours.chunks(CONTOURS_PER_GROUP).enumerate() {
        let pieces_of = |k: usize| d.pieces.get(g * CONTOURS_PER_GROUP + k).unwrap_or(&empty);
        let keys: Vec<Option<ShapeKey>> = group
            .iter()
            .enumerate()
            .map(|(k, c)| {
                (band.is_none() && !memo.is_full())
                    .then(|| ShapeKey::of(c, pieces_of(k), outline.canvas))
                    .flatten()
            })
            .collect();
        let mut new_shapes: Vec<usize> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for (k, key) in keys.iter().enumerate() {
            if let Some(key) = key {
                if !memo.contains(key) && seen.insert(key) {
                    new_shapes.push(k);
                }
            }
        }
        let drawn: Vec<ContourPath> = new_shapes
            .par_iter()
            .map(|&k| contour_path(&group[k], pieces_of(k), &basis, outline))
            .collect();
        for (&k, path) in new_shapes.iter().zip(&drawn) {
            if let Some(key) = &keys[k] {
                memo.insert(key.clone(), &group[k], path);
            }
        }
        // Largest contours first, one contour per job: no thread is left alone with a
        // large contour at the end (the 3000² sample's drawing on 2 threads: 79 -> 75 ms,
        // 146 ms on one; 1000² noise: 1.54 -> 1.39 s). The parts go back in the contours'
        // order.
        let mut parts: Vec<(usize, Written)> = largest_first(group)
            .par_iter()
            .with_max_len(1)
            .map(|&k| {
                let contour = &group[k];
                let pieces = pieces_of(k);
                let exact = || {
                    keys[k]
                        .as_ref()
                        .and_then(|key| memo.drawing(key, contour))
                        .unwrap_or_else(|| contour_path(contour, pieces, &basis, outline))
                };
                let mut cp = match band {
                    // The exact drawing meets the band's guarantee too: the one with fewer
                    // commands, unless the exact one has a pixel staircase.
                    Some(band) => {
                        let exact = exact();
                        let smooth = band_contour_path(contour, band, outline);
                        if smooth.counts().total() <= exact.counts().total()
                            || has_staircase(exact.start, &exact.commands)
                        {
                            smooth
                        } else {
                            exact
                        }
                    }
                    None => exact(),
                };
                drop_closing_line(&mut cp);
                let mut data = String::new();
                write_path_data(&cp, precision, shift, &mut data);
                // Only the counts and bounds are kept: the commands are written.
                let written = Written {
                    data,
                    counts: cp.counts(),
                    bounds: cp.point_bounds(),
                    path: ContourPath {
                        commands: Vec::new(),
                        ..cp
                    },
                };
                (k, written)
            })
            .collect();
        parts.sort_unstable_by_key(|&(k, _)| k);
        done(g * CONTOURS_PER_GROUP + group.len());
        for (_, w) in parts {
            let Written {
                data,
                counts,
                path: cp,
                bounds: b,
            } = w;
            bounds = match (bounds, b) {
                (Some(a), Some(b)) => Some(a.union(b)),
                (a, b) => a.or(b),
            };
            commands += &counts;
            fallbacks += &cp.fallbacks;
            joins += &cp.joins;
            max_fit_error = max_fit_error.max(cp.max_fit_error);
            svg.push_str(&data);
        }
    }
    PathData {
        data: svg,
        bounds,
        commands,
        max_fit_error,
        fallbacks,
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
    fn single_pixel_is_a_diamond() {
        let mask = Mask::from_ascii("...\n.#.\n...");
        let d = decompose(
            trace(&mask, Convention::Default),
            Model::Line,
            OutlierRule::NotInPiece,
        );
        let out = svg_document(&d, 3, 3, &SvgOptions::default());
        // Its square with the corners cut; relative, compact, the closing line left to `Z`.
        assert!(
            out.svg.contains("d=\"M2 1.5l-.5-.5-.5 .5 .5 .5Z\""),
            "{}",
            out.svg
        );
        assert_eq!(fidelity(&out.svg, &mask).unwrap().differing, 0);
    }

    /// Curves are checked unclipped only on pages Chromium draws in one tile whose contours
    /// keep clear of the border; the drawing is exact in resvg either way.
    #[test]
    fn unclipped_only_on_one_tile_pages_clear_of_the_border() {
        let disc = |w: u32, h: u32, cx: f64, cy: f64| {
            Mask::from_fn(w, h, move |x, y| {
                (f64::from(x) + 0.5 - cx).hypot(f64::from(y) + 0.5 - cy) <= 12.3
            })
        };
        for (w, h, cx, cy, expected) in [
            (60, 50, 30.0, 25.0, true),
            (60, 50, 13.5, 25.0, false),
            (60, 50, 30.0, 36.0, false),
            (600, 50, 30.0, 25.0, false),
            (50, 600, 25.0, 30.0, false),
        ] {
            let mask = disc(w, h, cx, cy);
            let d = decompose(
                trace(&mask, Convention::Default),
                Model::Conic,
                OutlierRule::NotInPiece,
            );
            assert_eq!(unclipped(&d, w, h), expected, "{w}x{h} at ({cx}, {cy})");
            let out = svg_document(&d, w, h, &SvgOptions::default());
            assert!(out.commands.cubic > 0, "{}", out.svg);
            assert_eq!(
                fidelity(&out.svg, &mask).unwrap().differing,
                0,
                "{}",
                out.svg
            );
        }
    }

    /// Curved shapes far from the border and cut by it (where resvg clips the document's
    /// edges) are exact in resvg.
    #[test]
    fn curves_near_and_far_from_the_border() {
        // A rounded arch (a half disc on a rectangle) at least 20 px from the border, and
        // the same cut by the left border.
        let shape = |cx: f64| {
            Mask::from_fn(80, 60, move |x, y| {
                let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - 30.0);
                let r = 17.6;
                dx.hypot(dy) <= r || (dx.abs() < r && dy > 0.0 && dy < r)
            })
        };
        let mut curves = 0;
        for model in [Model::Circle, Model::Conic] {
            for cx in [40.0, 4.0] {
                let mask = shape(cx);
                let d = decompose(
                    trace(&mask, Convention::Default),
                    model,
                    OutlierRule::NotInPiece,
                );
                let (w, h) = (mask.width(), mask.height());
                let out = svg_document(&d, w, h, &SvgOptions::default());
                curves += out.commands.cubic + out.commands.quad;
                let r = fidelity(&out.svg, &mask).unwrap();
                assert_eq!(r.differing, 0, "{model}: {r:?}\n{}", out.svg);
            }
        }
        assert!(curves >= 4, "{curves}");
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
        // Exact as resvg draws the SVG, for every model and grid.
        for (model, grid) in [
            (Model::Line, 6),
            (Model::Circle, 4),
            (Model::Conic, 3),
            (Model::Circle, 0),
        ] {
            let d = decompose(
                trace(&mask, Convention::Default),
                model,
                OutlierRule::NotInPiece,
            );
            let opts = SvgOptions {
                grid,
                ..SvgOptions::default()
            };
            let out = svg_document(&d, mask.width(), mask.height(), &opts);
            assert_eq!((out.commands.move_to, out.commands.close), (3, 3));
            assert_eq!(out.commands.arc, 0);
            let r = fidelity(&out.svg, &mask).unwrap();
            assert_eq!(r.differing, 0, "{model} grid {grid}: {r:?}\n{}", out.svg);
        }
    }
}
