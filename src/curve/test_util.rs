//! Helpers shared by the curve tests: assertions, proptest strategies, test curves and their
//! parametrisations, and the checks of a fitted path.

use super::command::PathCommand;
use super::conic::Conic;
use super::kind::CurveKind;
use super::path::{level_curve_path, LevelPath};
use super::polynomial::Polynomial;
use super::solve::project;
use super::trace::segment_distance;
use kurbo::{Arc, CubicBez, ParamCurve, Point, QuadBez, Vec2};
use proptest::prelude::*;

#[track_caller]
pub(super) fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual}, expected {expected} (difference {}, tolerance {tol})",
        (actual - expected).abs()
    );
}

#[track_caller]
pub(super) fn assert_le(value: f64, bound: f64, what: &str) {
    assert!(value <= bound, "{what}: got {value}, bound {bound}");
}

#[track_caller]
pub(super) fn assert_point_close(actual: Point, expected: Point, tol: f64, what: &str) {
    let d = (actual - expected).hypot();
    assert!(
        d <= tol,
        "{what}: got {actual:?}, expected {expected:?} (distance {d}, tolerance {tol})"
    );
}

/// The ellipse with centre `c`, radii `rx, ry`, rotation `th`, times `scale`.
pub(super) fn ellipse_conic(c: Point, rx: f64, ry: f64, th: f64, scale: f64) -> Conic {
    let (s, co) = th.sin_cos();
    let (ia, ib) = (1.0 / (rx * rx), 1.0 / (ry * ry));
    let a = co * co * ia + s * s * ib;
    let b = 2.0 * co * s * (ia - ib);
    let cc = s * s * ia + co * co * ib;
    let d = -2.0 * a * c.x - b * c.y;
    let e = -b * c.x - 2.0 * cc * c.y;
    let f = a * c.x * c.x + b * c.x * c.y + cc * c.y * c.y - 1.0;
    Conic::new(
        a * scale,
        b * scale,
        cc * scale,
        d * scale,
        e * scale,
        f * scale,
    )
}

/// The point of parameter `phi` of the ellipse with centre `c`, radii `rx, ry`, rotation `th`.
pub(super) fn ellipse_point(c: Point, rx: f64, ry: f64, th: f64, phi: f64) -> Point {
    Arc::new(c, (rx, ry), phi, 0.0, th).eval(0.0)
}

pub(super) fn round_conic(k: Conic) -> Conic {
    Conic::new(
        k.a.round(),
        k.b.round(),
        k.c.round(),
        k.d.round(),
        k.e.round(),
        k.f.round(),
    )
}

/// Points of the path every `1/n` of each command's parameter (arcs via kurbo).
pub(super) fn sample_path(start: Point, cmds: &[PathCommand], n: usize) -> Vec<Point> {
    let mut out = vec![start];
    let mut cur = start;
    for cmd in cmds {
        for k in 1..=n {
            let t = k as f64 / n as f64;
            out.push(match *cmd {
                PathCommand::Line(p) => cur.lerp(p, t),
                PathCommand::Quad(c, p) => QuadBez::new(cur, c, p).eval(t),
                PathCommand::Cubic(c1, c2, p) => CubicBez::new(cur, c1, c2, p).eval(t),
                PathCommand::Arc(a) => Arc::from_svg_arc(&a).unwrap().eval(t),
            });
        }
        cur = cmd.end();
    }
    out
}

pub(super) fn min_distance(p: Point, pts: &[Point]) -> f64 {
    pts.windows(2)
        .map(|w| segment_distance(p, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// A monomial `x^a y^b` of degree at most 6, as `(a, b)`.
pub(super) fn monomial() -> impl Strategy<Value = (u32, u32)> {
    (0u32..=6).prop_flat_map(|k| (0..=k).prop_map(move |b| (k - b, b)))
}

/// y' = x'²/4 (focal length 1), rotated by `th`, vertex at `v`, times 4.
pub(super) fn rotated_parabola(th: f64, v: Point) -> Conic {
    // x' = cos(x − vx) + sin(y − vy), y' = −sin(x − vx) + cos(y − vy); x'² − 4 y' = 0.
    let (s, c) = th.sin_cos();
    let poly = Polynomial::from_local(
        &[(2, 0), (1, 1), (0, 2), (1, 0), (0, 1)],
        &[c * c, 2.0 * c * s, s * s, 4.0 * s, -4.0 * c],
        v,
        0.0,
    )
    .unwrap();
    poly.as_conic().unwrap()
}

/// Checks a fitted path: starts at `from`, ends at `to`, samples within `tol` of the curve,
/// guide points near it; returns the measured max distance.
#[track_caller]
pub(super) fn check_fit(
    poly: &Polynomial,
    from: Point,
    to: Point,
    guide: &[Point],
    tol: f64,
) -> (Vec<PathCommand>, f64) {
    let LevelPath {
        commands: cmds,
        max_error: err,
    } = level_curve_path(poly, from, to, guide, tol).expect("path");
    assert_le(err, tol, "reported error");
    assert!(!cmds.is_empty());
    assert!(
        cmds.iter().all(|c| matches!(c, PathCommand::Cubic(..))),
        "{cmds:?}"
    );
    assert_point_close(cmds.last().unwrap().end(), to, 0.0, "path ends at to");
    let samples = sample_path(from, &cmds, 64);
    let mut measured: f64 = 0.0;
    for &p in &samples {
        let q = project(poly, p, 1.0).expect("sample near the curve");
        measured = measured.max((q - p).hypot());
    }
    // The fit measures its error at samples of its own: between them the curve may be a
    // hair farther (0.1122466 px at a tolerance of 0.1122321 on a hyperbola).
    assert_le(
        measured,
        tol * (1.0 + 1e-3),
        "sampled distance to the true curve",
    );
    for g in guide {
        let gp = project(poly, *g, 2.0).unwrap();
        // Guide points near the ends may project just outside the piece.
        if (gp - from).hypot() > 1.0 && (gp - to).hypot() > 1.0 {
            let d = min_distance(gp, &samples);
            assert_le(d, tol + 0.05, "guide projection near the path");
        }
    }
    (cmds, measured)
}

/// The hyperbola `(x′/a)² − (y′/b)² = 1` in the frame rotated by `th` about `centre`,
/// and its parametrisation: branch `sign` (±1), parameter `t`.
pub(super) fn rotated_hyperbola(
    a: f64,
    b: f64,
    th: f64,
    centre: Point,
) -> (Polynomial, impl Fn(f64, f64) -> Point) {
    let (s, c) = th.sin_cos();
    let poly = Polynomial::from_local(
        &[(2, 0), (1, 1), (0, 2)],
        &[
            c * c / (a * a) - s * s / (b * b),
            2.0 * c * s * (1.0 / (a * a) + 1.0 / (b * b)),
            s * s / (a * a) - c * c / (b * b),
        ],
        centre,
        1.0,
    )
    .unwrap();
    assert_eq!(poly.as_conic().unwrap().classify(), CurveKind::Hyperbola);
    let at = move |sign: f64, t: f64| {
        let (x, y) = (sign * a * t.cosh(), b * t.sinh());
        centre + Vec2::new(c * x - s * y, s * x + c * y)
    };
    (poly, at)
}

/// 10 Y² − X³ + 300 X − 5000 = 0, i.e. y² = x³ − 3x + 5 at scale 10, around (50, 60).
pub(super) fn cubic_curve() -> (Polynomial, impl Fn(f64) -> Point) {
    let origin = Point::new(50.0, 60.0);
    let poly = Polynomial::from_local(
        &[(0, 2), (3, 0), (1, 0)],
        &[10.0, -1.0, 300.0],
        origin,
        5000.0,
    )
    .unwrap();
    let at = move |x: f64| origin + Vec2::new(10.0 * x, 10.0 * (x * x * x - 3.0 * x + 5.0).sqrt());
    (poly, at)
}
