//! The decomposition as JSON (`layertrace-decomposition/2`): contours, pieces, equations.
//!
//! ```text
//! {"format": "layertrace-decomposition/2", "width": W, "height": H,
//!  "threshold": 128, "invert": false, "model": "conic", "cover": "greedy",
//!  "basis": ["x^2","x*y","y^2","x","y","1"],
//!  "contours": [{"hole": false, "points": [[x,y], ...],
//!                "pieces": [{"first": 0, "last": 17, "origin": [x0,y0],
//!                              "coefficients": [...], "lower": l, "upper": u,
//!                              "kind": "ellipse"}]}]}
//! ```
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

use crate::decompose::{piece_outliers, Decomposition, Outliers};
use crate::level::piece_kind;
use crate::recognize::small_certificate;
use std::fmt::Write as _;

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

pub(crate) fn quote(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".to_string())
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
    let basis = d.model.basis();
    let basis_ref: &dyn crate::model::Basis = &basis;
    let mut s = String::new();
    let names: Vec<String> = basis_ref.names().iter().map(|n| quote(n)).collect();
    // Writing to a String cannot fail.
    let _ = write!(
        s,
        "{{\"format\": \"layertrace-decomposition/2\", \"width\": {}, \"height\": {},\n \"threshold\": {}, \"invert\": {}, \"model\": {}, \"cover\": {},\n \"basis\": [{}],\n \"contours\": [",
        header.width,
        header.height,
        header.threshold,
        header.invert,
        quote(&d.model.name()),
        quote(d.cover.name()),
        names.join(",")
    );
    write_contours(d, 0, &mut s);
    s.push_str("\n ]}\n");
    s
}

/// Appends the contours of `d`, each with its pieces (the members of `"contours"`, one
/// contour per line, each line starting with a newline and two spaces), every point and
/// origin moved by `-margin` in x and y (the equations, taken at the origin, are the same).
pub(crate) fn write_contours(d: &Decomposition, margin: i64, s: &mut String) {
    let basis = d.model.basis();
    let basis_ref: &dyn crate::model::Basis = &basis;
    for (ci, (c, pieces)) in d.contours.iter().zip(&d.pieces).enumerate() {
        if ci > 0 {
            s.push(',');
        }
        let _ = write!(s, "\n  {{\"hole\": {}, \"points\": [", c.hole);
        for (i, p) in c.points.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            let _ = write!(
                s,
                "[{},{}]",
                i64::from(p.x) - margin,
                i64::from(p.y) - margin
            );
        }
        s.push_str("],\n   \"pieces\": [");
        for (k, p) in pieces.iter().enumerate() {
            if k > 0 {
                s.push_str(",\n    ");
            }
            let xy = |q: &crate::pixel::Pixel| vec![i64::from(q.x), i64::from(q.y)];
            let Outliers { right, left } = piece_outliers(&c.points, p.first, p.last, d.rule);
            let small = small_certificate(
                basis_ref,
                &p.certificate,
                &c.points[p.first..=p.last]
                    .iter()
                    .map(xy)
                    .collect::<Vec<_>>(),
                &right.iter().map(xy).collect::<Vec<_>>(),
                &left.iter().map(xy).collect::<Vec<_>>(),
            );
            let cert = &small;
            let coefficients: Vec<String> = cert
                .coefficients
                .iter()
                .map(|v| v.to_string())
                .chain(std::iter::once("0".to_string()))
                .collect();
            let _ = write!(
                s,
                "{{\"first\": {}, \"last\": {}, \"origin\": [{},{}], \"coefficients\": [{}], \"lower\": {}, \"upper\": {}, \"kind\": \"{}\"}}",
                p.first,
                p.last,
                cert.origin.first().copied().unwrap_or(0) - margin,
                cert.origin.get(1).copied().unwrap_or(0) - margin,
                coefficients.join(","),
                cert.extremes.lower,
                cert.extremes.upper,
                piece_kind(basis_ref, cert).name()
            );
            if let Some(cut) = p.cut {
                s.pop();
                let _ = write!(s, ", \"cut\": \"{}\"}}", cut.name());
            }
        }
        s.push_str("]}");
    }
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

/// The JSON text of a colour vectorization (`layertrace-colour/1`): the header of
/// [`decomposition_json`] without `threshold` and `invert`, then `"layout"` and the regions
/// in drawing order, each with its colour and the contours of its layer, written as in
/// `layertrace-decomposition/2`:
///
/// ```text
/// {"format": "layertrace-colour/1", "width": W, "height": H, "layout": "stack",
///  "model": "conic", "cover": "greedy", "basis": [...],
///  "regions": [
///   {"colour": "#rrggbb", "pixels": N, "contours": [{"hole": ..., "points": ..., "pieces": ...}]}]}
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
    let mut s = colour_header(model, cover, width, height, layout);
    for (k, r) in regions.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        let _ = write!(
            s,
            "\n {{\"colour\": {}, \"pixels\": {}, \"contours\": [",
            quote(r.colour),
            r.pixels
        );
        write_contours(r.decomposition, r.margin, &mut s);
        s.push_str("\n ]}");
    }
    s.push_str("\n ]}\n");
    s
}

/// The opening of a `layertrace-colour/1` document, up to the `"regions"` list's `[`.
pub(crate) fn colour_header(
    model: crate::model::Model,
    cover: crate::decompose::Cover,
    width: u32,
    height: u32,
    layout: &str,
) -> String {
    let basis = model.basis();
    let basis_ref: &dyn crate::model::Basis = &basis;
    let names: Vec<String> = basis_ref.names().iter().map(|n| quote(n)).collect();
    let mut s = String::new();
    let _ = write!(
        s,
        "{{\"format\": \"layertrace-colour/1\", \"width\": {width}, \"height\": {height}, \"layout\": {},\n \"model\": {}, \"cover\": {},\n \"basis\": [{}],\n \"regions\": [",
        quote(layout),
        quote(&model.name()),
        quote(cover.name()),
        names.join(",")
    );
    s
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
