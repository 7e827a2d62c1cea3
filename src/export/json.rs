//! The decomposition as JSON (`layertrace-decomposition/2`): contours, pieces, equations.
//!
//! ```text
//! {"format": "layertrace-decomposition/2", "width": W, "height": H,
//!  "threshold": 128, "invert": false, "model": "conic", "cover": "greedy",
//!  "basis": ["x^2","x*y","y^2","x","y","1"],
//!  "contours": [
//!   {"hole": false, "points": [[x,y], ...],
//!    "pieces": [{"first": 0, "last": 17, "origin": [x0,y0], "coefficients": [...], "lower": l, "upper": u, "kind": "ellipse"},
//!     {"first": 17, ...}]},
//!   {"hole": true, ...}
//!  ]}
//! ```
//!
//! One contour per line, its pieces from the next line on, one per line; compact
//! otherwise. The documents are derived `Serialize` types written by serde_json, the lines
//! laid out by the crate's `export::json_layout`.
//!
//! A piece that ended before a point that might have extended it has a `"cut"` member
//! after `"kind"`: `"budget"` (its work budget ran out, see [`crate::WorkBudget`]) or
//! `"undecided"`.
//!
//! `"cover"` names the cover the pieces form ([`crate::Cover`]): `"greedy"` (the paper's)
//! or `"optimal"` (the fewest pieces; a closed contour's `points` may then start elsewhere
//! than where tracing started, at the first cut).
//!
//! `f(x, y) = Σ coefficients[i] · basis_i(x − x0, y − y0)`; every inlier has
//! `lower ≤ f ≤ upper`, the RIGHT outliers are strictly above `upper` and the LEFT ones
//! strictly below `lower`. All these numbers are exact integers (the constant's coefficient
//! is 0), so the inequalities hold exactly on the decimals written. Each piece's equation is
//! the smallest of the recognizer's certificate and [`small_certificate`]'s (checked
//! exactly on the piece's own sets): `-5x - 8y` with `0 ≤ f ≤ 7` rather than whatever
//! scale the incremental recognizer's rounding left.

use super::json_layout::{to_text, Break, Layout, List};
use crate::decompose::{piece_outliers, Decomposition, Outliers};
use crate::level::piece_kind;
use crate::recognize::small_certificate;
use serde::Serialize;

/// What the JSON records besides the decomposition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JsonHeader {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The numeric threshold used (foreground = luma < threshold, before inversion).
    pub threshold: u8,
    /// Whether foreground and background were swapped.
    pub invert: bool,
}

/// A `layertrace-decomposition/2` document.
#[derive(Serialize)]
struct DecompositionDoc {
    format: &'static str,
    width: u32,
    height: u32,
    threshold: u8,
    invert: bool,
    model: String,
    cover: &'static str,
    basis: Vec<String>,
    contours: Vec<ContourDoc>,
}

/// One contour: its points and its pieces.
#[derive(Serialize)]
pub(crate) struct ContourDoc {
    hole: bool,
    points: Vec<[i64; 2]>,
    pieces: Vec<PieceDoc>,
}

/// One piece and its equation.
#[derive(Serialize)]
struct PieceDoc {
    first: usize,
    last: usize,
    origin: [i64; 2],
    /// The certificate's, then the constant's 0.
    coefficients: Vec<i64>,
    lower: i128,
    upper: i128,
    kind: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    cut: Option<&'static str>,
}

/// A list of contours in the object `parent`: one contour per line, indented by two spaces
/// (the same in every document; [`PIECES_BREAK`] and [`PIECES_LIST`] lay out its pieces).
pub(crate) const fn contours_list(parent: &'static str) -> List {
    List {
        parent,
        key: "contours",
        line: "\n  ",
        first: true,
        close: "\n ",
    }
}

/// The line break before a contour's `"pieces"`.
pub(crate) const PIECES_BREAK: Break = Break {
    parent: "contours",
    key: "pieces",
    line: "\n   ",
};

/// One piece per line.
pub(crate) const PIECES_LIST: List = List {
    parent: "contours",
    key: "pieces",
    line: "\n    ",
    first: false,
    close: "",
};

/// A top-level member on a new line.
pub(crate) const fn top_break(key: &'static str) -> Break {
    Break {
        parent: "",
        key,
        line: "\n ",
    }
}

const DECOMPOSITION: Layout = Layout {
    breaks: &[
        top_break("threshold"),
        top_break("basis"),
        top_break("contours"),
        PIECES_BREAK,
    ],
    lists: &[contours_list(""), PIECES_LIST],
};

/// The basis' function names, in coefficient order.
pub(crate) fn basis_names(model: crate::model::Model) -> Vec<String> {
    let basis = model.basis();
    crate::model::Basis::names(&basis)
}

/// The JSON text of a decomposition (one contour per line, compact otherwise).
///
/// ```
/// use layertrace::{decompose, decomposition_json, trace, Convention, JsonHeader, Mask, Model};
/// use layertrace::OutlierRule;
/// let mask = Mask::from_ascii("......\n.####.\n.####.\n......");
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let header = JsonHeader { width: 6, height: 4, threshold: 128, invert: false };
/// let text = decomposition_json(&d, &header);
/// let v: serde_json::Value = serde_json::from_str(&text).unwrap();
/// assert_eq!(v["model"], "line");
/// let pieces = v["contours"][0]["pieces"].as_array().unwrap();
/// assert_eq!(pieces.len(), d.pieces[0].len());
/// // Each piece's equation: one integer coefficient per basis function (x, y, 1).
/// assert!(pieces.iter().all(|p| p["coefficients"].as_array().unwrap().len() == 3));
/// ```
pub fn decomposition_json(d: &Decomposition, header: &JsonHeader) -> String {
    let doc = DecompositionDoc {
        format: "layertrace-decomposition/2",
        width: header.width,
        height: header.height,
        threshold: header.threshold,
        invert: header.invert,
        model: d.model.name(),
        cover: d.cover.name(),
        basis: basis_names(d.model),
        contours: contours(d, 0),
    };
    to_text(&doc, &DECOMPOSITION)
}

/// The contours of `d`, each with its pieces, every point and origin moved by `-margin` in
/// x and y (the equations, taken at the origin, are the same).
pub(crate) fn contours(d: &Decomposition, margin: i64) -> Vec<ContourDoc> {
    let basis = d.model.basis();
    let basis_ref: &dyn crate::model::Basis = &basis;
    let xy = |q: &crate::pixel::Pixel| vec![i64::from(q.x), i64::from(q.y)];
    let moved = |q: &crate::pixel::Pixel| [i64::from(q.x) - margin, i64::from(q.y) - margin];
    d.contours
        .iter()
        .zip(&d.pieces)
        .map(|(c, pieces)| ContourDoc {
            hole: c.hole,
            points: c.points.iter().map(moved).collect(),
            pieces: pieces
                .iter()
                .map(|p| {
                    let Outliers { right, left } =
                        piece_outliers(&c.points, p.first, p.last, d.rule);
                    let cert = small_certificate(
                        basis_ref,
                        &p.certificate,
                        &c.points[p.first..=p.last]
                            .iter()
                            .map(xy)
                            .collect::<Vec<_>>(),
                        &right.iter().map(xy).collect::<Vec<_>>(),
                        &left.iter().map(xy).collect::<Vec<_>>(),
                    );
                    PieceDoc {
                        first: p.first,
                        last: p.last,
                        origin: [
                            cert.origin.first().copied().unwrap_or(0) - margin,
                            cert.origin.get(1).copied().unwrap_or(0) - margin,
                        ],
                        coefficients: cert.coefficients.iter().copied().chain([0]).collect(),
                        lower: cert.extremes.lower,
                        upper: cert.extremes.upper,
                        kind: piece_kind(basis_ref, &cert).name(),
                        cut: p.cut.map(|c| c.name()),
                    }
                })
                .collect(),
        })
        .collect()
}

/// One region of a colour image: its colour, its pixel count, and the decomposition of the
/// borders that draw it (see [`colour_json`]).
#[derive(Clone, Copy, Debug)]
pub struct JsonRegion<'a> {
    /// `#rrggbb`.
    pub colour: &'a str,
    /// Pixels of the region.
    pub pixels: u64,
    /// The borders drawn for it.
    pub decomposition: &'a Decomposition,
    /// The margin of the decomposition's coordinates: its pixel `(x + margin, y + margin)`
    /// is the image's `(x, y)`. The JSON is written in image coordinates.
    pub margin: i64,
}

/// A `layertrace-colour/1` document; `R` is its regions' type (the stack's or the
/// partition's) and `B` its borders' (the partition's only).
#[derive(Serialize)]
pub(crate) struct ColourDoc<'a, R, B> {
    pub(crate) format: &'static str,
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) layout: &'a str,
    pub(crate) model: String,
    pub(crate) cover: &'static str,
    pub(crate) basis: Vec<String>,
    pub(crate) regions: Vec<R>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) borders: Option<Vec<B>>,
}

/// A region of the `stack` layout.
#[derive(Serialize)]
struct StackRegionDoc<'a> {
    colour: &'a str,
    pixels: u64,
    contours: Vec<ContourDoc>,
}

const COLOUR: Layout = Layout {
    breaks: &[
        top_break("model"),
        top_break("basis"),
        top_break("regions"),
        PIECES_BREAK,
    ],
    lists: &[REGIONS_LIST, contours_list("regions"), PIECES_LIST],
};

/// One region per line.
pub(crate) const REGIONS_LIST: List = List {
    parent: "",
    key: "regions",
    line: "\n ",
    first: true,
    close: "\n ",
};

/// The JSON text of a colour vectorization (`layertrace-colour/1`): the header of
/// [`decomposition_json`] without `threshold` and `invert`, then `"layout"` and the regions
/// in drawing order, each with its colour and the contours of its layer, written as in
/// `layertrace-decomposition/2`:
///
/// ```text
/// {"format": "layertrace-colour/1", "width": W, "height": H, "layout": "stack",
///  "model": "conic", "cover": "greedy",
///  "basis": [...],
///  "regions": [
///  {"colour": "#rrggbb", "pixels": N, "contours": [
///   {"hole": false, "points": [[x,y], ...],
///    "pieces": [{...},
///     {...}]}
///  ]}
///  ]}
/// ```
///
/// With the `stack` layout, region `k`'s contours are the borders of its layer: the pixels
/// of its colour and of every colour drawn after it (its own pixels are the layer minus the
/// next region's layer).
pub fn colour_json(
    regions: &[JsonRegion<'_>],
    model: crate::model::Model,
    cover: crate::decompose::Cover,
    width: u32,
    height: u32,
    layout: &str,
) -> String {
    let doc: ColourDoc<_, ()> = ColourDoc {
        format: "layertrace-colour/1",
        width,
        height,
        layout,
        model: model.name(),
        cover: cover.name(),
        basis: basis_names(model),
        regions: regions
            .iter()
            .map(|r| StackRegionDoc {
                colour: r.colour,
                pixels: r.pixels,
                contours: contours(r.decomposition, r.margin),
            })
            .collect(),
        borders: None,
    };
    to_text(&doc, &COLOUR)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose, piece_outliers, OutlierRule, Outliers};
    use crate::model::{Basis, Model};

    /// Parses the JSON back and re-checks every inequality from the numbers written alone.
    #[test]
    fn json_round_trip_holds_exactly() {
        let mask = Mask::from_ascii(
            "
            ..........
            ..######..
            .########.
            .###..###.
            .###..###.
            .########.
            ..######..
            ..........",
        );
        for model in [Model::Line, Model::Circle, Model::Conic, Model::Poly(3)] {
            let d = decompose(
                trace(&mask, Convention::Default),
                model,
                OutlierRule::NotInPiece,
            );
            let header = JsonHeader {
                width: 10,
                height: 8,
                threshold: 128,
                invert: false,
            };
            let text = decomposition_json(&d, &header);
            let v: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
            assert_eq!(v["format"], "layertrace-decomposition/2");
            assert_eq!(v["cover"], "greedy");
            assert_eq!(
                v["basis"].as_array().unwrap().len(),
                model.basis().dim() + 1
            );
            let contours = v["contours"].as_array().unwrap();
            assert_eq!(contours.len(), 2);
            assert_eq!(contours.iter().filter(|c| c["hole"] == true).count(), 1);
            let basis = model.basis();
            for (c, cj) in d.contours.iter().zip(contours) {
                for seg in cj["pieces"].as_array().unwrap() {
                    let first = seg["first"].as_u64().unwrap() as usize;
                    let last = seg["last"].as_u64().unwrap() as usize;
                    let o: Vec<i64> = seg["origin"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_i64().unwrap())
                        .collect();
                    let a: Vec<i128> = seg["coefficients"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_i64().unwrap() as i128)
                        .collect();
                    let (lo, hi) = (
                        seg["lower"].as_i64().unwrap() as i128,
                        seg["upper"].as_i64().unwrap() as i128,
                    );
                    let f = |p: &crate::pixel::Pixel| -> i128 {
                        let mut l = vec![0; basis.dim()];
                        Basis::lift(&basis, &[p.x as i64 - o[0], p.y as i64 - o[1]], &mut l)
                            .unwrap();
                        l.iter().zip(&a).map(|(x, y)| *x as i128 * y).sum::<i128>() + a[a.len() - 1]
                    };
                    for p in &c.points[first..=last] {
                        assert!(lo <= f(p) && f(p) <= hi);
                    }
                    let Outliers { right, left } =
                        piece_outliers(&c.points, first, last, OutlierRule::NotInPiece);
                    assert!(right.iter().all(|p| f(p) > hi));
                    assert!(left.iter().all(|p| f(p) < lo));
                }
            }
        }
    }
}
