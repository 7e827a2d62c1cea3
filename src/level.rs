//! The level curve of a piece: from an exact certificate to a polynomial in SVG space.
//!
//! A piece's certificate says `below < lower ≤ f(p) ≤ upper < above` with
//! `f(p) = Σ a_k f_k(p − origin)`: inliers inside the layer, RIGHT outliers above, LEFT
//! outliers below. Contours are traced with the foreground on their left, so the RIGHT side
//! is the background beside the piece and the border between foreground and background is
//! the level curve `f = c` for a level `c` strictly between `upper` and `above`
//! ([`boundary_level`]: the middle of that gap).
//!
//! Pixel `(x, y)` is the unit square `[x, x+1] × [y, y+1]` of SVG space, with centre
//! `(x + 0.5, y + 0.5)`: the polynomial is moved there ([`level_polynomial`]). The pixel
//! centres of the piece then satisfy `f ≤ upper < c` and those of its RIGHT outliers
//! `f ≥ above > c`, so the curve passes between every inlier centre and every background
//! centre beside it — which is what a rasterizer sampling pixel centres needs to reproduce
//! the pixels along the piece.

use crate::curve::{CurveKind, Polynomial, MAX_DEGREE};
use crate::decompose::{piece_outliers, OutlierRule, Outliers, Piece};
use crate::model::Basis;
use crate::pixel::Pixel;
use crate::recognize::{max_margin_direction_from, Certificate};
use kurbo::Point;

/// The level `c` of the border curve: the middle of the gap between the layer and its RIGHT
/// outliers, `(upper + above) / 2`. Without RIGHT outliers, half the layer's width (at least
/// one half) above `upper`.
///
/// ```
/// use layertrace::{boundary_level, decompose, trace, Convention, Mask, Model, OutlierRule};
/// let mask = Mask::from_ascii(
///     "........
///      .######.
///      .######.
///      ........",
/// );
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// for piece in &d.pieces[0] {
///     let c = &piece.certificate;
///     let level = boundary_level(c);
///     // Between the layer and the outliers on its right, when there are some.
///     if let Some(above) = c.extremes.above {
///         assert!(c.extremes.upper as f64 <= level && level <= above as f64);
///     }
/// }
/// ```
pub fn boundary_level(c: &Certificate) -> f64 {
    match c.extremes.above {
        Some(above) => (c.extremes.upper as f64 + above as f64) / 2.0,
        None => {
            c.extremes.upper as f64 + ((c.extremes.upper - c.extremes.lower) as f64).max(1.0) / 2.0
        }
    }
}

/// The polynomial `f − level` in SVG coordinates (pixel centres at half-integers), with
/// coefficients divided by their largest magnitude.
///
/// Returns `None` if the basis is not polynomial in two variables, its degree exceeds
/// [`MAX_DEGREE`], or every coefficient is zero.
///
/// ```
/// use kurbo::Point;
/// use layertrace::{decompose, level_polynomial, trace, Convention, Mask, Model, OutlierRule};
/// let mask = Mask::from_ascii(
///     "..........
///      .########.
///      .########.
///      ..........",
/// );
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let basis = Model::Line.basis();
/// let piece = &d.pieces[0][0];
/// let c = &piece.certificate;
/// let f = level_polynomial(&basis, c, c.extremes.lower as f64).unwrap();
/// // Every pixel centre of the piece lies on the positive side of `f − lower`, or on it.
/// for p in &d.contours[0].points[piece.first..=piece.last] {
///     let centre = Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5);
///     assert!(f.eval(centre) >= -1e-9);
/// }
/// ```
pub fn level_polynomial(basis: &dyn Basis, c: &Certificate, level: f64) -> Option<Polynomial> {
    let a: Vec<f64> = c.coefficients.iter().map(|&v| v as f64).collect();
    polynomial_of(basis, &c.origin, &a, level)
}

/// The polynomial `Σ a_k f_k(p − origin) − level` in SVG coordinates, coefficients divided
/// by their largest magnitude. Returns `None` as [`level_polynomial`] does.
pub fn polynomial_of(
    basis: &dyn Basis,
    origin: &[i64],
    a: &[f64],
    level: f64,
) -> Option<Polynomial> {
    if basis.point_dim() != 2 || origin.len() != 2 || a.len() != basis.dim() {
        return None;
    }
    let functions = crate::model::terms_of(basis)?;
    let terms: usize = functions.iter().map(Vec::len).sum();
    // On the stack for the models' few terms (two allocations per call were 0.5% of the
    // instructions on noise, where every short segment asks for its line).
    let (mut on_stack_m, mut on_stack_c) = ([(0u32, 0u32); STACK_TERMS], [0.0f64; STACK_TERMS]);
    let mut on_heap: (Vec<(u32, u32)>, Vec<f64>);
    let (monomials, coefficients): (&mut [(u32, u32)], &mut [f64]) = if terms <= STACK_TERMS {
        (&mut on_stack_m[..], &mut on_stack_c[..])
    } else {
        on_heap = (vec![(0, 0); terms], vec![0.0; terms]);
        (&mut on_heap.0[..], &mut on_heap.1[..])
    };
    let mut used = 0;
    for (f, &a) in functions.iter().zip(a) {
        if a == 0.0 || !a.is_finite() {
            continue;
        }
        for (k, e) in f {
            if e.len() != 2 || e[0] + e[1] > MAX_DEGREE {
                return None;
            }
            monomials[used] = (e[0], e[1]);
            coefficients[used] = a * *k as f64;
            used += 1;
        }
    }
    let (monomials, coefficients) = (&monomials[..used], &mut coefficients[..used]);
    let scale = coefficients.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if scale == 0.0 {
        return None;
    }
    coefficients.iter_mut().for_each(|v| *v /= scale);
    let origin = Point::new(origin[0] as f64 + 0.5, origin[1] as f64 + 0.5);
    Polynomial::from_local(monomials, coefficients, origin, level / scale)
}

/// Most terms of a basis whose [`polynomial_of`] keeps them on the stack.
const STACK_TERMS: usize = 32;

/// The border curve of a piece for drawing: the level curve, half-way between the two
/// sides, of the direction of largest margin separating the piece's pixels and LEFT
/// outliers (the foreground side) from its RIGHT outliers (the background beside it). A
/// certificate separates them too, but with whatever margin its rounding left — often a
/// thousandth of a pixel — while pixel-exact rendering wants the curve well clear of every
/// pixel centre. Falls back to the certificate's [`boundary_level`] curve when no
/// separation is found (e.g. no RIGHT outlier). Returns the curve and its clearance: the
/// smallest first-order distance (pixels) from it to the centres of the piece's pixels and
/// RIGHT outliers, which bounds how far a drawing of it may stray.
pub fn border_polynomial(
    basis: &dyn Basis,
    points: &[Pixel],
    piece: &Piece,
    rule: OutlierRule,
) -> Option<(Polynomial, f64)> {
    let Outliers { right, left } = piece_outliers(points, piece.first, piece.last, rule);
    let xy = |p: &Pixel| [i64::from(p.x), i64::from(p.y)];
    let mut low: Vec<[i64; 2]> = points[piece.first..=piece.last].iter().map(xy).collect();
    low.extend(left.iter().map(xy));
    let high: Vec<[i64; 2]> = right.iter().map(xy).collect();
    let origin = &piece.certificate.origin;
    let poly = match max_margin_direction_from(
        basis,
        origin,
        &low,
        &high,
        true,
        Some(&piece.certificate.coefficients),
    ) {
        Some(m) => polynomial_of(basis, origin, &m.direction, m.level),
        None => level_polynomial(
            basis,
            &piece.certificate,
            boundary_level(&piece.certificate),
        ),
    }?;
    // The clearance: the smallest first-order distance |f| / |∇f| from the curve to the
    // centres of the piece's pixels and of the background pixels beside it.
    let clearance = points[piece.first..=piece.last]
        .iter()
        .chain(&right)
        .map(|p| poly.distance_estimate(Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5)))
        .fold(f64::INFINITY, f64::min);
    Some((poly, clearance))
}

/// The type of the level curve `poly = 0`.
///
/// ```
/// use layertrace::{curve_kind, CurveKind, Polynomial};
/// // x² + y² − 4 = 0: a circle.
/// let circle = Polynomial::new(&[(2, 0, 1.0), (0, 2, 1.0), (0, 0, -4.0)]).unwrap();
/// assert_eq!(curve_kind(Some(&circle)), CurveKind::Circle);
/// assert_eq!(curve_kind(None), CurveKind::Degenerate);
/// ```
pub fn curve_kind(poly: Option<&Polynomial>) -> CurveKind {
    let Some(poly) = poly else {
        return CurveKind::Degenerate;
    };
    if poly.degree() > 2 {
        return CurveKind::Algebraic;
    }
    poly.as_conic()
        .map_or(CurveKind::Degenerate, |c| c.classify())
}

/// The kind of a piece's border curve (at [`boundary_level`]).
///
/// ```
/// use layertrace::{decompose, piece_kind, trace, Convention, CurveKind, Mask, Model, OutlierRule};
/// let mask = Mask::from_fn(40, 40, |x, y| {
///     let (dx, dy) = (f64::from(x) - 19.5, f64::from(y) - 19.5);
///     dx.hypot(dy) < 15.0
/// });
/// let d = decompose(trace(&mask, Convention::Default), Model::Circle, OutlierRule::NotInPiece);
/// let basis = Model::Circle.basis();
/// // A digital disc: its border pieces are circular arcs (or lines, where flat).
/// assert!(d.pieces[0]
///     .iter()
///     .all(|p| matches!(piece_kind(&basis, &p.certificate), CurveKind::Circle | CurveKind::Line)));
/// ```
pub fn piece_kind(basis: &dyn Basis, c: &Certificate) -> CurveKind {
    curve_kind(level_polynomial(basis, c, boundary_level(c)).as_ref())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::recognize::Extremes;

    fn cert(
        origin: [i64; 2],
        coefficients: Vec<i64>,
        lower: i128,
        upper: i128,
        above: i128,
    ) -> Certificate {
        Certificate {
            origin: origin.to_vec(),
            coefficients,
            extremes: Extremes {
                lower,
                upper,
                above: Some(above),
                below: Some(lower - 1),
            },
        }
    }

    #[test]
    fn circle_is_moved_to_pixel_centres() {
        // (u² + v²) − 10u with u = x − 3: centre (3 + 5, 4) in pixel units, i.e. (8.5, 4.5)
        // in SVG space; level 0 → radius 5.
        let c = cert([3, 4], vec![1, -10, 0], -25, 0, 2);
        let p = level_polynomial(&Model::Circle.basis(), &c, 0.0).unwrap();
        for k in 0..8 {
            let t = k as f64 * 0.7;
            let q = Point::new(8.5 + 5.0 * t.cos(), 4.5 + 5.0 * t.sin());
            assert!(p.eval(q).abs() < 1e-9, "f({q:?}) = {}", p.eval(q));
        }
        assert_eq!(curve_kind(Some(&p)), CurveKind::Circle);
        assert_eq!(boundary_level(&c), 1.0);
    }

    #[test]
    fn kinds() {
        let line = cert([0, 0], vec![2, -3], 0, 4, 5);
        assert_eq!(piece_kind(&Model::Line.basis(), &line), CurveKind::Line);
        // x² + 4y² = level > 0 → ellipse; x² − y² → hyperbola; x² − y → parabola.
        let conic = Model::Conic.basis();
        assert_eq!(
            piece_kind(&conic, &cert([5, 5], vec![1, 0, 4, 0, 0], 10, 100, 120)),
            CurveKind::Ellipse
        );
        assert_eq!(
            piece_kind(&conic, &cert([5, 5], vec![1, 0, -1, 0, 0], 10, 100, 120)),
            CurveKind::Hyperbola
        );
        assert_eq!(
            piece_kind(&conic, &cert([5, 5], vec![1, 0, 0, 0, -1], 10, 100, 120)),
            CurveKind::Parabola
        );
        assert_eq!(
            piece_kind(
                &Model::Poly(3).basis(),
                &cert([0, 0], vec![1, 0, 0, 1, 0, 0, 0, 0, 1], 0, 9, 10)
            ),
            CurveKind::Algebraic
        );
        let zero = Certificate {
            origin: vec![0, 0],
            coefficients: vec![0, 0],
            extremes: Extremes {
                lower: 0,
                upper: 0,
                above: None,
                below: None,
            },
        };
        assert_eq!(
            piece_kind(&Model::Line.basis(), &zero),
            CurveKind::Degenerate
        );
    }
}
