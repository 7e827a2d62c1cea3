//! Largest-margin directions and small certificates: float GJK runs to convergence, for
//! drawing (the border curve as far as possible from the pixel centres) and for readable
//! equations. Neither is a decision of the recognizer; certificates are re-checked exactly.

use super::exact::{reduce_by_gcd, verify_certificate};
use super::float::{power_of_two_scale, FLOAT_PARAMS};
use super::gjk::{gjk, GjkOutcome, GjkParams};
use super::lifted::LiftedSet;
use super::planar::line_margin_direction;
use super::relative::relative_into;
use super::simplex::Simplex;
use super::support::{FloatSupport, Sets, SupportMap};
use super::{conditioning::LinearMap, Certificate};
use crate::model::Basis;

/// Lifts `points − origin` into a set, raising `max_abs` to bound the liftings. Returns
/// `None` on overflow or a point (or origin) not of the basis' point dimension.
fn lift_points<P: AsRef<[i64]>>(
    basis: &dyn Basis,
    origin: &[i64],
    points: &[P],
    max_abs: &mut [i64],
) -> Option<LiftedSet> {
    let (pd, n) = (basis.point_dim(), basis.dim());
    let mut set = LiftedSet::with_capacity(pd, n, points.len());
    let mut f = vec![0; n];
    let mut rel = vec![0; pd];
    for p in points {
        let p = p.as_ref();
        if p.len() != pd || origin.len() != pd {
            return None;
        }
        relative_into(p, origin, &mut rel)?;
        basis.lift(&rel, &mut f)?;
        for (m, v) in max_abs.iter_mut().zip(&f) {
            *m = (*m).max(v.saturating_abs());
        }
        set.push(&rel, &f);
    }
    Some(set)
}

/// Relative gap at which the largest-margin run stops: its support point `s` along the
/// closest point `x` has `x·s ≥ (1 − MARGIN_GAP) ‖x‖²`, and since the largest margin lies
/// between `x·s / ‖x‖` and `‖x‖`, the margin found is within 0.1% of the largest, which no
/// drawing can tell apart. The minor cycle keeps the decision's rounding tolerance
/// ([`FLOAT_PARAMS`]`.eps`): a run that drops vertices whose weight is below 1e-3 stalls
/// without a direction on some pieces. 27 shared samples, against a gap of 1e-12: conic
/// 8 516 → 8 511 commands, the other models' the same, 0.2% fewer instructions.
const MARGIN_GAP: f64 = 1e-3;

/// The float GJK run to convergence in coordinates scaled by `scale`: the direction of
/// largest margin, unscaled (or, when the run stalls, its last separating direction). `None`
/// if the sets are not (numerically) separated. With `hint` (a direction in the lifted
/// coordinates), the run starts from the pair of points tightest along it instead of an
/// arbitrary one: the margin found is the same within [`MARGIN_GAP`], the direction may
/// differ by as much.
fn largest_margin_direction(
    sets: Sets<'_>,
    scale: &[f64],
    hint: Option<&[i64]>,
) -> Option<Vec<f64>> {
    let map = LinearMap::diagonal(scale);
    let mut y = Vec::with_capacity(scale.len());
    let mut support = FloatSupport {
        sets,
        map: &map,
        y: &mut y,
    };
    let mut simplex = Simplex::default();
    if let Some(a) = hint.filter(|a| a.len() == scale.len() && a.iter().any(|&v| v != 0)) {
        // a·F = Σ (aᵢ / sᵢ)(sᵢ Fᵢ): the hint's direction in the scaled coordinates.
        let d: Vec<f64> = a.iter().zip(scale).map(|(&v, s)| v as f64 / s).collect();
        if let Some(v) = support.support_point(&d, Vec::new()) {
            simplex.reset_to(v);
        }
    }
    let params = GjkParams {
        first_separation: false,
        gap: MARGIN_GAP,
        ..FLOAT_PARAMS
    };
    let direction = match gjk(&mut support, &mut simplex, &params).outcome {
        GjkOutcome::Separated { direction, .. } => direction,
        // A run can stall short of the 1e-12 relative gap (near-degenerate sets, such as a
        // conic piece turning a right-angled corner: the comb's teeth stalled at 1e-9)
        // while its closest point already separates the sets: keep it when its support
        // point lies strictly beyond the origin. Its margin is then below the largest (on
        // the samples and a comb, within a relative gap of 1e-3 for 927 of 951 stalled
        // runs, up to 0.1 for the rest), but far from the certificate's, and the exporter checks the
        // clearance it leaves anyway.
        GjkOutcome::Stalled => {
            let x = simplex.point(scale.len())?;
            let s = support.support_point(&x, Vec::new())?;
            let xs: f64 = x.iter().zip(&s.point).map(|(a, b)| a * b).sum();
            if !(xs > 0.0 && x.iter().all(|v| v.is_finite())) {
                return None;
            }
            x
        }
        _ => return None,
    };
    Some(map.pull_back(&direction))
}

/// A separating direction of `a·F` and the level between the two sets it separates: `a·F <
/// level` on one set, `> level` on the other (in `f64`).
#[derive(Clone, Debug, PartialEq)]
pub struct MarginDirection {
    /// `a`, one coefficient per basis function.
    pub direction: Vec<f64>,
    /// Half-way between the two sets' extreme values of `a·F`.
    pub level: f64,
}

/// The separating direction of largest margin between `low` and `high` point sets (relative
/// to `origin`), and the level half-way between them: `a·F(p) < level` on `low`,
/// `> level` on `high`, in `f64`. Not a certificate: a drawing aid for exporters, which want
/// the border curve as far as possible from the pixel centres on either side.
///
/// With `scaled`, the margin is measured after scaling each lifted coordinate to magnitude
/// about one (as the recognizer does); otherwise in the lifted coordinates themselves (for
/// the line basis, the Euclidean distance in the image).
///
/// Returns `None` if either set is empty, a lifting overflows, or no separation is found.
///
/// ```
/// use layertrace::{max_margin_direction, MarginDirection, Model};
/// // Points below the diagonal and points above it.
/// let low = [[3i64, 0], [5, 1], [6, 2]];
/// let high = [[0i64, 3], [1, 5], [2, 6]];
/// let m: MarginDirection = max_margin_direction(&Model::Line.basis(), &[0, 0], &low, &high, false).unwrap();
/// let value = |p: &[i64; 2]| m.direction[0] * p[0] as f64 + m.direction[1] * p[1] as f64;
/// assert!(low.iter().all(|p| value(p) < m.level) && high.iter().all(|p| value(p) > m.level));
/// ```
pub fn max_margin_direction<P: AsRef<[i64]>>(
    basis: &dyn Basis,
    origin: &[i64],
    low: &[P],
    high: &[P],
    scaled: bool,
) -> Option<MarginDirection> {
    max_margin_direction_from(basis, origin, low, high, scaled, None)
}

/// [`max_margin_direction`] started from the pair of points tightest along `hint`, a
/// separating direction (coefficients of the basis functions), when given.
pub(crate) fn max_margin_direction_from<P: AsRef<[i64]>>(
    basis: &dyn Basis,
    origin: &[i64],
    low: &[P],
    high: &[P],
    scaled: bool,
    hint: Option<&[i64]>,
) -> Option<MarginDirection> {
    let (pd, n) = (basis.point_dim(), basis.dim());
    if low.is_empty()
        || high.is_empty()
        || origin.len() != pd
        || low.iter().chain(high).any(|p| p.as_ref().len() != pd)
    {
        return None;
    }
    if !scaled && is_line_basis(basis) {
        return planar_margin(origin, low, high);
    }
    let mut max_abs = vec![0i64; n];
    let low_set = lift_points(basis, origin, low, &mut max_abs)?;
    let high_set = lift_points(basis, origin, high, &mut max_abs)?;
    let empty = LiftedSet::new(pd, n);
    let scale = if scaled {
        power_of_two_scale(&max_abs)
    } else {
        vec![1.0; n]
    };
    let sets = Sets {
        inliers: &low_set,
        upper: &high_set,
        lower: &empty,
    };
    let y = largest_margin_direction(sets, &scale, hint)?;
    let value = |row: &[f64]| row.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>();
    let top = low_set
        .float_rows()
        .map(value)
        .fold(f64::NEG_INFINITY, f64::max);
    let bottom = high_set
        .float_rows()
        .map(value)
        .fold(f64::INFINITY, f64::min);
    (top < bottom).then(|| MarginDirection {
        direction: y,
        level: (top + bottom) / 2.0,
    })
}

/// True for the basis `(x, y)` of lines in the plane.
fn is_line_basis(basis: &dyn Basis) -> bool {
    // (Compared term by term: a literal of the expected terms allocated five vectors on
    // every call.)
    let is = |t: &crate::model::Terms, e: [u32; 2]| matches!(t.as_slice(), [(1, x)] if *x == e);
    basis.point_dim() == 2
        && basis.dim() == 2
        && crate::model::terms_of(basis)
            .is_some_and(|f| matches!(&*f, [a, b] if is(a, [1, 0]) && is(b, [0, 1])))
}

/// [`max_margin_direction`] for the line basis, from the convex hulls
/// ([`line_margin_direction`]).
fn planar_margin<P: AsRef<[i64]>>(
    origin: &[i64],
    low: &[P],
    high: &[P],
) -> Option<MarginDirection> {
    // (A loop into a vector of the set's length: collected into an `Option`, the vector
    // grew by reallocation.)
    let rel = |set: &[P]| -> Option<Vec<[i64; 2]>> {
        let mut out = Vec::with_capacity(set.len());
        for p in set {
            let p = p.as_ref();
            out.push([p[0].checked_sub(origin[0])?, p[1].checked_sub(origin[1])?]);
        }
        Some(out)
    };
    line_margin_direction(&rel(low)?, &rel(high)?)
}

/// A certificate for the same sets with small coefficients, for people who read the
/// equations: the largest-margin direction (GJK run to convergence) rounded at growing
/// scales, `1, 2, 4, …` for its largest coefficient, the first that verifies exactly, divided
/// by the gcd of its coefficients. Returns `certificate` itself when that gives nothing
/// smaller (or the sets cannot be lifted).
///
/// `certificate` must describe `inliers` with `upper` above and `lower` below.
pub fn small_certificate(
    basis: &dyn Basis,
    certificate: &Certificate,
    inliers: &[Vec<i64>],
    upper: &[Vec<i64>],
    lower: &[Vec<i64>],
) -> Certificate {
    let fallback = certificate.clone();
    let (pd, n) = (basis.point_dim(), basis.dim());
    let origin = &certificate.origin;
    if (upper.is_empty() && lower.is_empty()) || certificate.is_zero() || origin.len() != pd {
        return fallback;
    }
    let mut max_abs = vec![0i64; n];
    let mut fill = |pts: &[Vec<i64>]| lift_points(basis, origin, pts, &mut max_abs);
    let (Some(s), Some(u), Some(l)) = (fill(inliers), fill(upper), fill(lower)) else {
        return fallback;
    };
    let sets = Sets {
        inliers: &s,
        upper: &u,
        lower: &l,
    };
    let Some(y) = largest_margin_direction(sets, &power_of_two_scale(&max_abs), None) else {
        return fallback;
    };
    let ymax = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let old_max = certificate
        .coefficients
        .iter()
        .map(|v| v.unsigned_abs())
        .max()
        .unwrap_or(0);
    if !(ymax.is_finite() && ymax > 0.0) {
        return fallback;
    }
    let mut last: Option<Vec<i64>> = None;
    for k in 0..62 {
        let t = f64::from(k).exp2() / ymax;
        let a: Vec<i64> = y.iter().map(|v| (v * t).round() as i64).collect();
        if a.iter().any(|v| v.unsigned_abs() >= old_max) {
            break;
        }
        if a.iter().all(|&v| v == 0) || last.as_ref() == Some(&a) {
            continue;
        }
        if let Some(e) = verify_certificate(&sets, &a) {
            let (a, e) = reduce_by_gcd(a, e);
            return Certificate {
                origin: origin.clone(),
                coefficients: a,
                extremes: e,
            };
        }
        last = Some(a);
    }
    fallback
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Model, PolynomialBasis};

    #[test]
    fn a_start_from_a_hint_finds_the_same_margin() {
        // The pixels inside a circle of radius r along an arc, and those outside beside
        // them, conic basis: started from the circle's own coefficients, from a direction
        // that separates nothing, or from nowhere, the run finds the same margin (within
        // twice the gap at which it stops).
        let basis = Model::Conic.basis();
        for r in [5i64, 12, 31, 80] {
            let (mut low, mut high) = (Vec::new(), Vec::new());
            for x in 0..=r + 2 {
                for y in 0..=r / 2 {
                    let d = x * x + y * y;
                    if d <= r * r && d > (r - 2) * (r - 2) {
                        low.push([x, y]);
                    } else if d > r * r && d <= (r + 2) * (r + 2) {
                        high.push([x, y]);
                    }
                }
            }
            let mut max_abs = vec![0i64; basis.dim()];
            let (lo, hi) = (
                lift_points(&basis, &[0, 0], &low, &mut max_abs).expect("lifted"),
                lift_points(&basis, &[0, 0], &high, &mut max_abs).expect("lifted"),
            );
            let scale = power_of_two_scale(&max_abs);
            let margin = |m: &MarginDirection| {
                let value = |row: &[f64]| row.iter().zip(&m.direction).map(|(a, b)| a * b).sum();
                let top = lo.float_rows().map(value).fold(f64::NEG_INFINITY, f64::max);
                let bottom = hi.float_rows().map(value).fold(f64::INFINITY, f64::min);
                let norm: f64 = m
                    .direction
                    .iter()
                    .zip(&scale)
                    .map(|(d, s)| (d / s).powi(2))
                    .sum();
                (bottom - top) / norm.sqrt()
            };
            let plain = max_margin_direction(&basis, &[0, 0], &low, &high, true).expect("margin");
            for hint in [[1i64, 0, 1, 0, 0], [0, 0, 0, 1, 0]] {
                let from =
                    max_margin_direction_from(&basis, &[0, 0], &low, &high, true, Some(&hint))
                        .expect("margin");
                let (a, b) = (margin(&plain), margin(&from));
                assert!(a > 0.0 && b > 0.0, "r {r}: {a}, {b}");
                assert!(
                    (a - b).abs() <= 2.0 * MARGIN_GAP * a.max(b),
                    "r {r}: {a}, {b}"
                );
            }
        }
    }

    #[test]
    fn the_line_basis_is_recognized_by_its_terms() {
        assert!(is_line_basis(&Model::Line.basis()));
        assert!(!is_line_basis(&Model::Circle.basis()));
        assert!(!is_line_basis(&Model::Conic.basis()));
        // The same functions in the other order, or scaled, are not `(x, y)`.
        let basis = |f: Vec<crate::model::Terms>| {
            PolynomialBasis::new(2, f, vec!["a".into(), "b".into()]).expect("a basis")
        };
        assert!(is_line_basis(&basis(vec![
            vec![(1, vec![1, 0])],
            vec![(1, vec![0, 1])]
        ])));
        assert!(!is_line_basis(&basis(vec![
            vec![(1, vec![0, 1])],
            vec![(1, vec![1, 0])]
        ])));
        assert!(!is_line_basis(&basis(vec![
            vec![(2, vec![1, 0])],
            vec![(1, vec![0, 1])]
        ])));
    }
}
