//! SVG export: the contour paths of a [`Decomposition`] (see [`crate::outline`]) written as
//! `<path>` elements.
//!
//! # The document
//! `<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="W" height="H"
//! viewBox="0 0 W H">` with the image size in pixels (one user unit = one pixel, pixel
//! `(x, y)` = the square `[x, x+1] × [y, y+1]`), holding `<path fill="…"
//! fill-rule="nonzero" d="…"/>` elements (none for an image without foreground) and
//! nothing else: each outer border with its holes in the same one, the groups that lie well
//! inside one of Chromium's raster tiles in a path of that tile (one path on most pages
//! under 512 px), the rest in one path first (see [`groups`](super::groups): neither
//! resvg nor Chromium clips a path inside a tile, so its curves are checked one way).
//! Every number is a multiple of `2^-grid` ([`SvgOptions::grid`]) written exactly (at most
//! `grid` decimals, trailing zeros and leading zeros stripped); each contour starts with an
//! absolute `M`, the other commands are relative (`l`, `h`, `v`, `q`, `c`; see
//! [`path_text`](super::path_text)); there is no `A` (arcs are written as the cubics the
//! outline checked).
//!
//! # Fill rule
//! Outer borders run counter-clockwise on screen, holes clockwise. `nonzero` is preferred
//! over `evenodd` because subpaths of the same orientation that overlap slightly (curves of
//! nearby borders crossing near a thin background gap, or a bridge segment folding back)
//! stay filled instead of cancelling out.

use super::groups::{tiles_of_groups, Tile};
use super::path_text::{drop_closing_line, write_path_data, xml_escape};
use crate::bitmap::Band;
use crate::contour::largest_first;
use crate::decompose::Decomposition;
use crate::outline::{
    band_contour_path, contour_path, has_staircase, CommandCounts, ContourPath, EdgeClipping,
    FallbackCounts, JoinCounts, OutlineOptions, ShapeKey, ShapeMemo, MAX_GRID,
};
use rayon::prelude::*;
use std::collections::{BTreeMap, HashMap, HashSet};
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
    /// A curve piece (not a line) of fewer contour points than this is drawn as its exact
    /// polygon, joined to its neighbours' and smoothed with them, without trying the curve.
    /// Default [`DEFAULT_MIN_CURVE_POINTS`](crate::DEFAULT_MIN_CURVE_POINTS) (12:
    /// on a shorter piece the curve's command saves nothing); 0 tries every curve (with
    /// `max_curve_points` 0).
    pub min_curve_points: usize,
    /// A curve piece (not a line) of more contour points than this is drawn as its exact
    /// polygon, smoothed with its neighbours' and drawn in runs' cubics, without trying the
    /// curve. Default [`DEFAULT_MAX_CURVE_POINTS`](crate::DEFAULT_MAX_CURVE_POINTS) (24:
    /// longer curves seldom pass the render check, and the runs' cubics draw them in fewer
    /// commands); 0 sets no limit.
    pub max_curve_points: usize,
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
            min_curve_points: crate::outline::DEFAULT_MIN_CURVE_POINTS,
            max_curve_points: crate::outline::DEFAULT_MAX_CURVE_POINTS,
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

/// The SVG document of a decomposition of a `width` × `height` image: `<path>` elements
/// with `fill-rule="nonzero"` (each outer border with its holes in the same one; the groups
/// well inside one of Chromium's raster tiles in a path of that tile, which no renderer
/// clips, the others in one path first), outer borders counter-clockwise, holes clockwise,
/// width, height and viewBox the image size in pixels.
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
    let paths = document_paths(d, &outline, width, height, band, done);
    let header = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{width}\" \
         height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n"
    );
    let mut svg = header;
    for p in paths.iter().filter(|p| !p.data.is_empty()) {
        let _ = write!(
            svg,
            "<path fill=\"{}\" fill-rule=\"nonzero\" d=\"",
            xml_escape(&opts.fill)
        );
        svg.push_str(&p.data);
        svg.push_str("\"/>\n");
    }
    svg.push_str("</svg>\n");
    let mut out = empty_output(svg);
    for p in &paths {
        out.add(p);
    }
    out
}

/// The paths of a `width` × `height` document: the groups of contours (an outer border and
/// its holes) that lie well inside one of Chromium's raster tiles in a path of that tile,
/// drawn with their curves checked unclipped only (neither resvg nor Chromium clips such a
/// path, see [`groups`](super::groups)), the others in one path first, checked both ways.
/// A group whose drawing strays within a pixel of its tile's side after all is drawn
/// again the other way, at the end of that first path. Within each path the contours are
/// in the document's order (the strays' after the others).
fn document_paths(
    d: &Decomposition,
    outline: &OutlineOptions,
    width: u32,
    height: u32,
    band: Option<&Band>,
    done: &(dyn Fn(usize) + Sync),
) -> Vec<PathData> {
    let Some(groups) = tiles_of_groups(&d.contours, width, height) else {
        return vec![path_data(d, outline, band, 0, done)];
    };
    let never = OutlineOptions {
        clipping: EdgeClipping::Never,
        ..*outline
    };
    let mut rest = PathData::default();
    let mut held: BTreeMap<Tile, Vec<(usize, Written)>> = BTreeMap::new();
    draw_contours(
        d,
        &[*outline, never],
        &|k| Some(usize::from(groups.tile[k].is_some())),
        band,
        0,
        done,
        &mut |k, w| match groups.tile[k] {
            Some(t) => held.entry(t).or_default().push((k, w)),
            None => rest.push(w),
        },
    );
    // Each group's bounds, against its tile's.
    let mut bounds: HashMap<usize, Option<kurbo::Rect>> = HashMap::new();
    for (k, w) in held.values().flatten() {
        let b = bounds.entry(groups.outer[*k]).or_default();
        *b = union(*b, w.bounds);
    }
    let strays: HashSet<usize> = bounds
        .into_iter()
        .filter(|&(o, b)| b.is_some_and(|b| groups.tile[o].is_some_and(|t| !t.holds(b))))
        .map(|(o, _)| o)
        .collect();
    let mut paths = Vec::with_capacity(held.len() + 1);
    for (_, contours) in held {
        let mut p = PathData::default();
        for (k, w) in contours {
            if !strays.contains(&groups.outer[k]) {
                p.push(w);
            }
        }
        paths.push(p);
    }
    if !strays.is_empty() {
        // Progress was told once already: the bar stays full while these (rare) drawings
        // run.
        draw_contours(
            d,
            std::slice::from_ref(outline),
            &|k| strays.contains(&groups.outer[k]).then_some(0),
            band,
            0,
            &|_| {},
            &mut |_, w| rest.push(w),
        );
    }
    paths.insert(0, rest);
    paths
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
        min_curve_points: opts.min_curve_points,
        max_curve_points: opts.max_curve_points,
        grid,
        // Curves are checked in both of tiny-skia's edge modes even where resvg will not
        // clip the document: Chromium draws large paths tile by tile, each tile clipping
        // them. Checking the unclipped mode alone when every contour lay 3 px inside the
        // image left 26 px wrong in Chromium on the 27 shared samples instead of 12 (conic),
        // for 14% less time. The SVG document narrows this to the unclipped mode for the
        // groups of contours it writes in a path of their tile's own (see `document_paths`).
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

/// What the drawings of some contours add to a document's counts.
#[derive(Clone, Debug, Default)]
struct Tally {
    commands: CommandCounts,
    max_fit_error: f64,
    fallbacks: FallbackCounts,
    joins: JoinCounts,
}

impl Tally {
    /// Counts one contour's drawing.
    fn add(&mut self, w: &Written) {
        self.commands += &w.counts;
        self.fallbacks += &w.path.fallbacks;
        self.joins += &w.path.joins;
        self.max_fit_error = self.max_fit_error.max(w.path.max_fit_error);
    }
}

/// Bounds of two sets of points, either empty.
fn union(a: Option<kurbo::Rect>, b: Option<kurbo::Rect>) -> Option<kurbo::Rect> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.union(b)),
        (a, b) => a.or(b),
    }
}

/// The path data of every contour of a decomposition, and what went into it.
#[derive(Default)]
pub(crate) struct PathData {
    /// The `d` attribute's value (empty without contours).
    pub(crate) data: String,
    /// The bounds of every point written ([`ContourPath::point_bounds`]), before the shift.
    bounds: Option<kurbo::Rect>,
    tally: Tally,
}

impl PathData {
    /// Appends one contour's drawing.
    fn push(&mut self, w: Written) {
        self.tally.add(&w);
        self.bounds = union(self.bounds, w.bounds);
        self.data.push_str(&w.data);
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
        self.add_tally(&paths.tally);
    }

    /// Counts the commands, fallbacks and joins of `tally` in this output.
    fn add_tally(&mut self, tally: &Tally) {
        self.commands += &tally.commands;
        self.fallback_reasons += &tally.fallbacks;
        self.fallbacks = self.fallback_reasons.total();
        self.joins += &tally.joins;
        self.max_fit_error = self.max_fit_error.max(tally.max_fit_error);
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
    let mut out = PathData {
        data: String::new(),
        bounds: None,
        tally: Tally::default(),
    };
    draw_contours(
        d,
        std::slice::from_ref(outline),
        &|_| Some(0),
        band,
        shift,
        done,
        &mut |_, w| out.push(w),
    );
    out
}

/// Draws the contours of `d` that `way` gives one of `outlines` (by its index; `None`
/// leaves the contour out), with `band` smooth within it, writes each one's path data
/// moved by `-shift` pixels in x and y and hands it to `sink` with the contour's index, in
/// the contours' order. Calls `done` with the number of contours gone through so far after
/// each group of them.
fn draw_contours(
    d: &Decomposition,
    outlines: &[OutlineOptions],
    way: &(dyn Fn(usize) -> Option<usize> + Sync),
    band: Option<&Band>,
    shift: u32,
    done: &(dyn Fn(usize) + Sync),
    sink: &mut dyn FnMut(usize, Written),
) {
    let shift = f64::from(shift);
    let basis = d.model.basis();
    let Some(first) = outlines.first() else {
        return;
    };
    // Multiples of 2^-grid have at most `grid` decimals: written exactly.
    let precision = usize::from(first.grid);
    let empty = Vec::new();
    // Contours are drawn independently, in parallel, a group at a time (only the group's
    // path data is held besides what `sink` keeps); handed over in order, so the document
    // does not depend on the number of threads.
    // Tiny contours are drawn once per shape and way of drawing (see `ShapeMemo`: at most
    // 65 536 shapes are held per way, 33 MB for one way on 2000² noise); not with a band,
    // whose drawing depends on the mask round the contour.
    let mut memos: Vec<ShapeMemo> = outlines.iter().map(|_| ShapeMemo::default()).collect();
    for (g, group) in d.contours.chunks(CONTOURS_PER_GROUP).enumerate() {
        let base = g * CONTOURS_PER_GROUP;
        let pieces_of = |k: usize| d.pieces.get(base + k).unwrap_or(&empty);
        let ways: Vec<Option<usize>> = (0..group.len())
            .map(|k| way(base + k).filter(|&i| i < outlines.len()))
            .collect();
        let keys: Vec<Option<ShapeKey>> = group
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let i = ways[k]?;
                (band.is_none() && !memos[i].is_full())
                    .then(|| ShapeKey::of(c, pieces_of(k), outlines[i].canvas))
                    .flatten()
            })
            .collect();
        let mut new_shapes: Vec<usize> = Vec::new();
        // (Fx: the std hasher's SipHash of every key took 1.3% of 400² noise's instructions.)
        let mut seen = rustc_hash::FxHashSet::default();
        for (k, key) in keys.iter().enumerate() {
            if let (Some(key), Some(i)) = (key, ways[k]) {
                if !memos[i].contains(key) && seen.insert((i, key)) {
                    new_shapes.push(k);
                }
            }
        }
        let drawn: Vec<ContourPath> = new_shapes
            .par_iter()
            .map(|&k| {
                contour_path(
                    &group[k],
                    pieces_of(k),
                    &basis,
                    &outlines[ways[k].unwrap_or(0)],
                )
            })
            .collect();
        for (&k, path) in new_shapes.iter().zip(&drawn) {
            if let (Some(key), Some(i)) = (&keys[k], ways[k]) {
                memos[i].insert(key.clone(), &group[k], path);
            }
        }
        // Largest contours first, one contour per job: no thread is left alone with a
        // large contour at the end (the 3000² sample's drawing on 2 threads: 79 -> 75 ms,
        // 146 ms on one; 1000² noise: 1.54 -> 1.39 s). The parts go back in the contours'
        // order.
        let order: Vec<usize> = largest_first(group)
            .into_iter()
            .filter(|&k| ways[k].is_some())
            .collect();
        let mut parts: Vec<(usize, Written)> = order
            .par_iter()
            .with_max_len(1)
            .map(|&k| {
                let contour = &group[k];
                let pieces = pieces_of(k);
                let i = ways[k].unwrap_or(0);
                let outline = &outlines[i];
                // Each drawing as written: a closing line goes to `Z` (so that the smooth
                // mode counts commands as the document has them: a smooth drawing that tied
                // with an exact one ending in a closing line was one command longer).
                let exact = || {
                    let mut cp = keys[k]
                        .as_ref()
                        .and_then(|key| memos[i].drawing(key, contour))
                        .unwrap_or_else(|| contour_path(contour, pieces, &basis, outline));
                    drop_closing_line(&mut cp);
                    cp
                };
                let cp = match band {
                    // The exact drawing meets the band's guarantee too: the one with fewer
                    // commands, unless the exact one has a pixel staircase.
                    Some(band) => {
                        let exact = exact();
                        let mut smooth = band_contour_path(contour, band, outline);
                        drop_closing_line(&mut smooth);
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
        done(base + group.len());
        for (k, w) in parts {
            sink(base + k, w);
        }
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

    /// Groups of contours well inside one of Chromium's tiles are written in a path of
    /// that tile's own (their curves checked unclipped only), the others in one path; the
    /// drawing is exact in resvg and in tiny-skia drawing Chromium's tiles either way.
    #[test]
    fn groups_inside_a_tile_get_its_own_path() {
        // Rings (a disc with a hole) of radius 12.3 at the given centres.
        let rings = |w: u32, h: u32, centres: &'static [(f64, f64)]| {
            Mask::from_fn(w, h, move |x, y| {
                centres.iter().any(|&(cx, cy)| {
                    let r = (f64::from(x) + 0.5 - cx).hypot(f64::from(y) + 0.5 - cy);
                    (4.5..=12.3).contains(&r)
                })
            })
        };
        /// A page, its rings' centres, the paths written, the groups a tile holds.
        type Case = (u32, u32, &'static [(f64, f64)], usize, usize);
        let cases: [Case; 7] = [
            (60, 50, &[(30.0, 25.0)], 1, 1),
            // Within 3 px of the border: the one path of the rest.
            (60, 50, &[(13.5, 25.0)], 1, 0),
            (60, 50, &[(30.0, 36.0)], 1, 0),
            // One near the border, one well inside.
            (90, 50, &[(13.5, 25.0), (60.0, 25.0)], 2, 1),
            // Pages of tall or wide tiles.
            (600, 50, &[(30.0, 25.0)], 1, 1),
            (50, 600, &[(25.0, 30.0)], 1, 1),
            // 600²: tiles of 256 px every 254; one ring in each of two tiles, one across
            // the line at 254-256.
            (
                600,
                600,
                &[(100.0, 100.0), (400.0, 100.0), (255.0, 400.0)],
                3,
                2,
            ),
        ];
        for (w, h, centres, paths, held) in cases {
            let mask = rings(w, h, centres);
            let d = decompose(
                trace(&mask, Convention::Default),
                Model::Conic,
                OutlierRule::NotInPiece,
            );
            assert_eq!(d.contours.len(), 2 * centres.len());
            let groups = tiles_of_groups(&d.contours, w, h);
            let tiles: HashSet<Tile> = groups
                .iter()
                .flat_map(|g| g.tile.iter().flatten().copied())
                .collect();
            let groups_held = groups.map_or(0, |g| g.tile.iter().flatten().count() / 2);
            assert_eq!(groups_held, held, "{w}x{h} {centres:?}");
            let out = svg_document(&d, w, h, &SvgOptions::default());
            assert_eq!(out.svg.matches("<path").count(), paths, "{}", out.svg);
            assert_eq!(paths, tiles.len() + usize::from(held < centres.len()));
            assert!(out.commands.cubic > 0, "{}", out.svg);
            assert_eq!(
                fidelity(&out.svg, &mask).unwrap().differing,
                0,
                "{}",
                out.svg
            );
            let tiled = crate::fidelity::rasterize_svg_in_tiles(&out.svg, w, h).unwrap();
            assert_eq!(
                crate::fidelity::compare(&mask, &tiled).differing,
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
