//! Tiny contours drawn once per shape: the many small contours of noise, halftones and
//! dotted lines (10 363 contours of at most 32 points in a 400² noise image, of 1 895 shapes)
//! are drawn once per shape and translated.
//!
//! # Why a translated drawing is exact
//! The shape is the contour's points relative to its first one and its pieces, certificates
//! included (also relative to that point). What [`contour_path`](super::contour_path)
//! *checks* depends on nothing else: the pieces' outliers come from consecutive points, the
//! render check compares with the contour's own crack polygon in a window moved by whole
//! pixels, and tiny-skia's results do not change under such a move (see
//! [`super::render_check`]: exactly so for lines; for a curve, up to the `f32` rounding of
//! its cuts at y extrema, which the check with the path moved by 1/64 px covers in
//! practice). The drawing is made at the shape's first contour (in document
//! order, whatever the number of threads) and moved by whole pixels to the others; every
//! point stays on the `2^-grid` grid, where the move is exact in `f64` and in tiny-skia's
//! fixed point, so each copy is exact in tiny-skia where it lands. (A drawing made afresh
//! at another place may differ in floating-point detail, since the curves are expanded at
//! absolute coordinates: it would be another exact drawing.) Contours near the border of
//! the document's pixmap are drawn where they are: there tiny-skia clips the path at the
//! border, which no move preserves.

use rustc_hash::FxHashMap as HashMap;

use kurbo::{Point, Vec2};

use super::path::ContourPath;
use super::tiles::clear_of_tile_cuts;
use crate::contour::{Contour, TINY_POINTS};
use crate::curve::PathCommand;
use crate::decompose::Piece;

/// Most shapes kept (give or take a group of contours): beyond, new shapes are drawn where
/// they are. Bounds the memory of an
/// image whose tiny contours are all different: a drawing of at most 32 points takes a few
/// hundred bytes (the memo held 33 MB on 2000² noise, against 350 MB for the whole run).
const MAX_SHAPES: usize = 1 << 16;

/// Distance (pixels) from the pixmap's border (and from the lines where Chromium's tiles cut
/// paths, see [`super::tiles`]) within which a tiny contour is not memoized:
/// its drawing stays within 2 px of its pixels ([`super::joins::STRAY_MARGIN`]) and the
/// render check looks 2 px farther, so beyond 5 px the border plays no part.
const CANVAS_MARGIN: f64 = 6.0;

/// What decides a tiny contour's drawing: its points relative to the first one, whether it
/// is a hole, and its pieces (bounds and certificates, origins relative to that point).
///
/// Written as one list of numbers, each list length-prefixed, so that equal lists are equal
/// shapes (one allocation per key: noise makes hundreds of thousands of keys). Hashed once,
/// when made: a key is looked up three or four times (2000² noise spent 3% of its time
/// hashing keys anew), so [`Hash`] writes that hash only, and equal keys have equal hashes
/// since it is computed from the list that [`PartialEq`] compares.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ShapeKey {
    /// FxHash of `data`.
    hash: u64,
    /// Hole, points, pieces (see [`ShapeKey::of`]).
    data: Vec<i64>,
}

impl std::hash::Hash for ShapeKey {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        state.write_u64(self.hash);
    }
}

/// Appends `v` to a key's list as two numbers.
fn push_i128(data: &mut Vec<i64>, v: i128) {
    data.push((v >> 64) as i64);
    data.push(v as i64);
}

/// Appends `v` to a key's list as three numbers (`0, 0, 0` for `None`).
fn push_option(data: &mut Vec<i64>, v: Option<i128>) {
    data.push(i64::from(v.is_some()));
    push_i128(data, v.unwrap_or(0));
}

impl ShapeKey {
    /// The key of a tiny contour (see [`Contour::tiny_shape`]); `None` for a larger (or
    /// empty) one, one within [`CANVAS_MARGIN`] of the border of `canvas` (the document's
    /// pixmap, see [`OutlineOptions::canvas`](super::OutlineOptions::canvas)), or one with
    /// a piece that is not planar.
    ///
    /// The list: whether it is a hole; the number of points and each one's `x, y` relative
    /// to the first; the number of pieces and for each its `first, last`, its origin
    /// relative to the first point, the number of its coefficients and the coefficients,
    /// and its extremes (each `i128` as two numbers, an `Option` behind a flag).
    pub(crate) fn of(
        contour: &Contour,
        pieces: &[Piece],
        canvas: Option<kurbo::Rect>,
    ) -> Option<ShapeKey> {
        let first = *contour.points.first()?;
        if contour.points.len() > TINY_POINTS {
            return None;
        }
        if let Some(c) = canvas {
            let inner = c.inset(-CANVAS_MARGIN);
            let inside = contour.points.iter().all(|p| {
                let (x, y) = (f64::from(p.x), f64::from(p.y));
                x >= inner.x0 && y >= inner.y0 && x + 1.0 <= inner.x1 && y + 1.0 <= inner.y1
            });
            if !inside {
                return None;
            }
        }
        // Nor near the lines where Chromium's tiles cut paths.
        let [x0, y0, x1, y1] = contour.pixel_box()?;
        if !clear_of_tile_cuts(x0, y0, x1, y1, canvas, CANVAS_MARGIN as i64) {
            return None;
        }
        let (fx, fy) = (i64::from(first.x), i64::from(first.y));
        let len = |n: usize| i64::try_from(n).ok();
        let coefficients: usize = pieces
            .iter()
            .map(|p| p.certificate.coefficients.len())
            .sum();
        let mut data =
            Vec::with_capacity(2 + 2 * contour.points.len() + 1 + 15 * pieces.len() + coefficients);
        data.push(i64::from(contour.hole));
        data.push(len(contour.points.len())?);
        for p in &contour.points {
            data.extend([i64::from(p.x) - fx, i64::from(p.y) - fy]);
        }
        data.push(len(pieces.len())?);
        for p in pieces {
            // (Planar pieces only: their origins are points of the plane.)
            let [ox, oy] = *p.certificate.origin.as_slice() else {
                return None;
            };
            let c = &p.certificate.coefficients;
            data.extend([len(p.first)?, len(p.last)?]);
            data.extend([ox.wrapping_sub(fx), oy.wrapping_sub(fy), len(c.len())?]);
            data.extend_from_slice(c);
            let e = &p.certificate.extremes;
            push_i128(&mut data, e.lower);
            push_i128(&mut data, e.upper);
            push_option(&mut data, e.above);
            push_option(&mut data, e.below);
        }
        let hash = {
            use std::hash::{Hash, Hasher};
            let mut h = rustc_hash::FxHasher::default();
            data.hash(&mut h);
            h.finish()
        };
        Some(ShapeKey { hash, data })
    }
}

/// The drawings of the tiny shapes met so far, each with its first point at the origin.
#[derive(Debug, Default)]
pub(crate) struct ShapeMemo {
    drawings: HashMap<ShapeKey, ContourPath>,
}

impl ShapeMemo {
    /// Whether `key`'s drawing is known.
    pub(crate) fn contains(&self, key: &ShapeKey) -> bool {
        self.drawings.contains_key(key)
    }

    /// Whether no more shapes are to be kept (new ones are then drawn where they are).
    pub(crate) fn is_full(&self) -> bool {
        self.drawings.len() >= MAX_SHAPES
    }

    /// Keeps `path`, the drawing of `contour` whose shape is `key`. (The caller stops
    /// asking once [`ShapeMemo::is_full`]: a group of contours started below the bound may
    /// pass it by at most its own size, and then every shape it drew is served from here.)
    pub(crate) fn insert(&mut self, key: ShapeKey, contour: &Contour, path: &ContourPath) {
        let first = contour.points[0];
        let to_origin = -Vec2::new(f64::from(first.x), f64::from(first.y));
        self.drawings.insert(key, translated(path, to_origin));
    }

    /// The drawing of `contour`, whose shape is `key`, if the shape is known.
    pub(crate) fn drawing(&self, key: &ShapeKey, contour: &Contour) -> Option<ContourPath> {
        let path = self.drawings.get(key)?;
        let first = contour.points[0];
        Some(translated(
            path,
            Vec2::new(f64::from(first.x), f64::from(first.y)),
        ))
    }
}

/// `path` moved by `v` (whole pixels: exact for points on the grid).
fn translated(path: &ContourPath, v: Vec2) -> ContourPath {
    let m = |p: Point| p + v;
    ContourPath {
        start: m(path.start),
        commands: path
            .commands
            .iter()
            .map(|c| match *c {
                PathCommand::Line(p) => PathCommand::Line(m(p)),
                PathCommand::Quad(a, p) => PathCommand::Quad(m(a), m(p)),
                PathCommand::Cubic(a, b, p) => PathCommand::Cubic(m(a), m(b), m(p)),
                PathCommand::Arc(mut arc) => {
                    arc.from = m(arc.from);
                    arc.to = m(arc.to);
                    PathCommand::Arc(arc)
                }
            })
            .collect(),
        max_fit_error: path.max_fit_error,
        fallbacks: path.fallbacks,
        joins: path.joins,
    }
}

#[cfg(test)]
mod tests {
    use crate::bitmap::repeated_blob;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose, OutlierRule};
    use crate::export::svg::{svg_document, SvgOptions};
    use crate::fidelity::fidelity;
    use crate::model::Model;
    use proptest::prelude::*;

    proptest! {
        /// A tiny blob repeated far apart: the document draws the copies as translations
        /// of the first drawing, and every copy is exact in resvg where it lands.
        #[test]
        fn translated_drawings_are_exact_where_they_land(
            bits in prop::collection::vec(any::<bool>(), 12),
            offsets in prop::collection::vec((0u32..60, 0u32..60), 1..4),
            model in prop::sample::select(vec![Model::Line, Model::Circle, Model::Conic]),
        ) {
            let mask = repeated_blob(&bits, &offsets);
            let d = decompose(trace(&mask, Convention::Default), model, OutlierRule::NotInPiece);
            let out = svg_document(&d, 80, 80, &SvgOptions::default());
            let r = fidelity(&out.svg, &mask).unwrap();
            prop_assert_eq!(r.differing, 0, "{}", out.svg);
            // The copies are the same drawing: after each subpath's absolute `M x y` the
            // path data is relative, so every copy of a shape writes the same text.
            let copies = 1 + offsets
                .iter()
                .map(|&(x, y)| (x / 6, y / 5))
                .collect::<std::collections::HashSet<_>>()
                .len();
            let data = out.svg.split(" d=\"").nth(1).and_then(|d| d.split('"').next());
            let subpaths: Vec<&str> = data.unwrap_or("").split('M').skip(1).collect();
            let tails: std::collections::HashSet<&str> = subpaths
                .iter()
                .map(|p| p.trim_start_matches(|c: char| c.is_ascii_digit() || c == '.' || c == ' ' || c == '-'))
                .collect();
            prop_assert!(tails.len() * copies <= subpaths.len(), "{}", out.svg);
        }
    }
}
