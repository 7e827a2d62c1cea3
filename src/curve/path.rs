//! [`level_curve_path`]: the part of a level curve between two points as SVG path commands,
//! exact where the curve allows it, fitted cubics otherwise.

use super::arcs::{ellipse_path, flat_arc, parabola_path};
use super::command::PathCommand;
use super::fit::fit_cubics;
use super::kind::CurveKind;
use super::polynomial::Polynomial;
use super::trace::{hyperbola_trace, trace_curve};
use kurbo::{Point, Vec2};

/// Guide points farther than this (in pixels) from the curve make [`level_curve_path`] fail.
pub const GUIDE_MAX_DISTANCE: f64 = 2.0;

/// `from` and `to` farther than this (in pixels) from the curve make [`level_curve_path`] fail.
pub(super) const ENDPOINT_MAX_DISTANCE: f64 = 0.01;

/// A drawing of part of a level curve: its commands and how far they stray from the curve.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelPath {
    /// The commands, from the start point given (the `M` is the caller's).
    pub commands: Vec<PathCommand>,
    /// The measured largest distance between the commands and the true curve (0 for the
    /// exact forms: lines, circular and elliptical arcs, parabola arcs).
    pub max_error: f64,
}

impl LevelPath {
    fn exact(commands: Vec<PathCommand>) -> LevelPath {
        LevelPath {
            commands,
            max_error: 0.0,
        }
    }
}

/// The part of the level curve `poly = 0` from `from` to `to`, as SVG path commands, with the
/// measured maximal distance between the emitted path and the true curve (0 for the exact
/// forms: lines, circular and elliptical arcs, parabola arcs).
///
/// `from` and `to` lie on the curve (within ~1e-6); `guide` are points near the curve (within
/// 2 px), in path order, telling which part of the curve is meant: which way
/// round a closed curve, which branch of a hyperbola. When `from == to` on a closed curve the
/// whole curve is meant (for ellipses two arcs are emitted, of a third and two thirds of a turn; for traced curves the guide must
/// go round).
///
/// * degree 1: one [`PathCommand::Line`];
/// * circle / ellipse: one exact [`PathCommand::Arc`] whose direction is the one agreeing best
///   with the guide (angular distance of the guide points outside the arc plus backward
///   motion between consecutive points; ties go to the shorter arc);
/// * parabola: one exact [`PathCommand::Quad`] whose control point is the intersection of the
///   tangents at `from` and `to`;
/// * hyperbola (same branch), degenerate conics and degree > 2: the curve is traced from
///   `from` to `to` through the guide points' projections (predictor along the tangent,
///   Newton corrector, step ≤ 0.25 px), then fitted by cubic Béziers tangent to the curve at
///   their ends (tangent lengths by least squares, or a third of the arc length, whichever is
///   closer), subdivided until the distance to the true curve, measured both ways at samples
///   with Newton projections, is at most `tolerance`.
///
/// Returns `None` for non-finite input, a non-positive `tolerance`, a constant polynomial,
/// `from`/`to` not on the curve (within 0.01), a guide point whose projection fails or (for
/// parabolas) lies farther than 2 px from the arc, points on different
/// hyperbola branches, a trace that does not reach `to`, or a trace step that no cubic
/// follows within `tolerance` (it jumps the gap between two branches by a saddle).
///
/// ```
/// use kurbo::Point;
/// use layertrace::{level_curve_path, PathCommand, Polynomial};
/// // The circle x² + y² = 25, from (5, 0) to (0, 5) the short way (the guide point says which).
/// let circle = Polynomial::new(&[(2, 0, 1.0), (0, 2, 1.0), (0, 0, -25.0)]).unwrap();
/// let guide = [Point::new(3.5355, 3.5355)];
/// let path =
///     level_curve_path(&circle, Point::new(5.0, 0.0), Point::new(0.0, 5.0), &guide, 0.01).unwrap();
/// // An exact elliptical arc: no fitting error.
/// assert!(matches!(path.commands[..], [PathCommand::Arc(_)]));
/// assert_eq!(path.max_error, 0.0);
/// ```
#[allow(clippy::neg_cmp_op_on_partial_ord)] // `!(d <= max)` also rejects NaN distances.
pub fn level_curve_path(
    poly: &Polynomial,
    from: Point,
    to: Point,
    guide: &[Point],
    tolerance: f64,
) -> Option<LevelPath> {
    if !from.is_finite()
        || !to.is_finite()
        || guide.iter().any(|g| !g.is_finite())
        || tolerance <= 0.0
        || !tolerance.is_finite()
        || !poly.is_finite()
    {
        return None;
    }
    if poly.degree() == 0
        || !(poly.distance_estimate(from) <= ENDPOINT_MAX_DISTANCE)
        || !(poly.distance_estimate(to) <= ENDPOINT_MAX_DISTANCE)
    {
        return None;
    }
    if let Some(conic) = poly.as_conic() {
        match conic.classify() {
            CurveKind::Line => {
                let cmds = if from == to {
                    Vec::new()
                } else {
                    vec![PathCommand::Line(to)]
                };
                return Some(LevelPath::exact(cmds));
            }
            CurveKind::Circle | CurveKind::Ellipse => {
                if let Some(sagitta) = flat_arc(&conic, from, to, guide, tolerance) {
                    let cmds = if from == to {
                        Vec::new()
                    } else {
                        vec![PathCommand::Line(to)]
                    };
                    return Some(LevelPath {
                        commands: cmds,
                        max_error: sagitta,
                    });
                }
                return ellipse_path(&conic, from, to, guide).map(LevelPath::exact);
            }
            CurveKind::Parabola => {
                return parabola_path(&conic, from, to, guide).map(LevelPath::exact)
            }
            CurveKind::Hyperbola => {
                let params = conic.hyperbola_params()?;
                let (centre, axis) = (params.centre, Vec2::from_angle(params.rotation));
                if (from - centre).dot(axis) * (to - centre).dot(axis) < 0.0 {
                    return None; // different branches
                }
                let trace = hyperbola_trace(poly, params, from, to, guide)
                    .or_else(|| trace_curve(poly, from, to, guide))?;
                return fit_cubics(poly, &trace, tolerance);
            }
            // (`classify` never says `Algebraic`.)
            CurveKind::Degenerate | CurveKind::Algebraic => {}
        }
    }
    let trace = trace_curve(poly, from, to, guide)?;
    fit_cubics(poly, &trace, tolerance)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use crate::curve::{intersect_near, project, Conic};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Random polynomials of degree up to 6, random points: the solvers and the path
        /// never panic, and a path found has a finite error and ends at `to`.
        #[test]
        fn random_inputs_do_not_panic(
            terms in proptest::collection::vec((monomial(), -10i32..=10), 1..=10),
            (ox, oy) in (0i32..50, 0i32..50),
            level in -5.0..5.0f64,
            slope in -1.0..1.0f64,
            (nx, ny) in (-3.0..3.0f64, -3.0..3.0f64),
            (tx, ty) in (-3.0..3.0f64, -3.0..3.0f64),
            with_guide in proptest::bool::ANY,
        ) {
            let (monomials, coefficients): (Vec<(u32, u32)>, Vec<f64>) =
                terms.iter().map(|&(m, c)| (m, f64::from(c))).unzip();
            let origin = Point::new(f64::from(ox) + 0.5, f64::from(oy) + 0.5);
            let poly = Polynomial::from_local(&monomials, &coefficients, origin, level).unwrap();
            let q = Polynomial::from_local(&[(1, 0), (0, 1)], &[slope, 1.0], origin, 0.0).unwrap();
            let near = origin + Vec2::new(nx, ny);
            let _ = intersect_near(&poly, &q, near, 2.0);
            let (Some(from), Some(to)) = (
                project(&poly, near, 3.0),
                project(&poly, near + Vec2::new(tx, ty), 3.0),
            ) else {
                return Ok(());
            };
            let guide: Vec<Point> = if with_guide {
                (1..5).map(|i| from.lerp(to, i as f64 / 5.0)).collect()
            } else {
                Vec::new()
            };
            if let Some(LevelPath { commands: cmds, max_error: err }) = level_curve_path(&poly, from, to, &guide, 0.05) {
                prop_assert!(err.is_finite(), "{}", err);
                if let Some(last) = cmds.last() {
                    assert_point_close(last.end(), to, 0.0, "random path end");
                }
            }
        }
    }

    #[test]
    fn huge_inputs_are_refused() {
        let huge = Point::new(1e300, -1e300);
        let line = Polynomial::new(&[(1, 0, 1.0), (0, 0, -1.0)]).unwrap();
        assert!(level_curve_path(&line, huge, huge, &[], 0.05).is_none());
        let _ = project(&line, huge, 1.0);
        let _ = intersect_near(&line, &line, huge, 1.0);
    }

    #[test]
    fn lines_and_bad_input() {
        let line = Polynomial::new(&[(1, 0, 1.0), (0, 1, 1.0), (0, 0, -10.0)]).unwrap();
        let LevelPath {
            commands: cmds,
            max_error: err,
        } = level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            0.05,
        )
        .unwrap();
        assert_eq!(cmds, vec![PathCommand::Line(Point::new(10.0, 0.0))]);
        assert_eq!(err, 0.0);
        let nan = Point::new(f64::NAN, 0.0);
        assert!(level_curve_path(&line, nan, Point::new(10.0, 0.0), &[], 0.05).is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[nan],
            0.05
        )
        .is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            0.0
        )
        .is_none());
        assert!(level_curve_path(
            &line,
            Point::new(0.0, 10.0),
            Point::new(10.0, 0.0),
            &[],
            f64::NAN
        )
        .is_none());
        // Endpoints off the curve.
        let off = Point::new(0.0, 10.5);
        assert!(level_curve_path(&line, off, Point::new(10.0, 0.0), &[], 0.05).is_none());
        let circle = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, -25.0));
        assert!(level_curve_path(
            &circle,
            Point::new(3.0, 4.1),
            Point::new(5.0, 0.0),
            &[],
            0.05
        )
        .is_none());
        let constant = Polynomial::new(&[(0, 0, 1.0)]).unwrap();
        assert!(level_curve_path(&constant, Point::ZERO, Point::ZERO, &[], 0.05).is_none());
        assert!(project(&line, nan, 1.0).is_none());
        assert!(intersect_near(&line, &line, nan, 1.0).is_none());
        assert!(intersect_near(&line, &line, Point::ZERO, f64::INFINITY).is_none());
    }
}
