//! The exact forms of [`level_curve_path`](super::level_curve_path): elliptical arcs, chords
//! of nearly flat arcs, and parabola arcs as quadratic Béziers.

use super::command::PathCommand;
use super::conic::{Conic, EllipseParams};
use super::path::GUIDE_MAX_DISTANCE;
use super::trace::segment_distance;
use kurbo::{ParamCurveNearest, Point, QuadBez, SvgArc, Vec2};
use std::f64::consts::{PI, TAU};

/// A circle or ellipse so large next to the piece that the chord `from → to` is within
/// `tolerance` of the arc: returns the bound on their distance, the sagitta
/// `ρ − √(ρ² − c²/4)` for the chord length `c` and the smallest radius of curvature
/// `ρ = b²/a`.
///
/// Such curves come from nearly straight pieces (radii of 10⁴–10²² px), where the angles an
/// exact arc needs lose their precision. Only when the chord is not empty and shorter than
/// `ρ`, every guide point lies beside it — within [`GUIDE_MAX_DISTANCE`] of the segment,
/// and projecting onto its line within one pixel of its ends — and the guide path is no
/// longer than `1.5 c + 2`, so that the piece runs along the short arc; returns `None`
/// otherwise (in particular for a piece that goes round a small curve).
pub(super) fn flat_arc(
    conic: &Conic,
    from: Point,
    to: Point,
    guide: &[Point],
    tolerance: f64,
) -> Option<f64> {
    let radii = conic.ellipse_params()?.radii;
    let (a, b) = (radii.x.max(radii.y), radii.x.min(radii.y));
    let rho = b * b / a;
    let chord = to - from;
    let c = chord.hypot();
    if !(c > 0.0 && c < rho) {
        return None;
    }
    // ρ − √(ρ² − c²/4), without the cancellation.
    let sagitta = c * c / 4.0 / (rho + (rho * rho - c * c / 4.0).sqrt());
    let beside = guide.iter().all(|&g| {
        let along = (g - from).dot(chord) / c;
        (-1.0..=c + 1.0).contains(&along) && segment_distance(g, from, to) <= GUIDE_MAX_DISTANCE
    });
    // A pixel path along a chord is at most √2 times as long (plus its ends); one that goes
    // round a small curve is far longer.
    let mut length = 0.0;
    let mut prev = from;
    for &g in guide.iter().chain(std::iter::once(&to)) {
        length += (g - prev).hypot();
        prev = g;
    }
    let along_chord = length <= 1.5 * c + 2.0;
    (sagitta <= tolerance && beside && along_chord).then_some(sagitta)
}

/// Exact elliptical arc(s) from `from` to `to`, going the way the guide says.
///
/// The point of parameter φ (`at`) is what `kurbo::Arc::new(centre, radii, φ, 0.0,
/// θ).eval(0.0)` computes, with the same sums: that swap gave byte-identical SVG and JSON on
/// every sample, but the whole sample run measured 1–4% slower in alternating runs, both
/// orders (6.58 → 6.83 s, 6.67 → 6.86 s user), most likely code layout since `at` runs once
/// per full turn; not worth four lines. Its inverse (`angle`) has no kurbo counterpart.
pub(super) fn ellipse_path(
    conic: &Conic,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Vec<PathCommand>> {
    let EllipseParams {
        centre,
        radii,
        rotation: theta,
    } = conic.ellipse_params()?;
    let rot = Vec2::from_angle(theta);
    let angle = |p: Point| {
        let v = p - centre;
        let x = v.dot(rot);
        let y = rot.cross(v);
        (y / radii.y).atan2(x / radii.x)
    };
    let at = |phi: f64| {
        let (s, c) = phi.sin_cos();
        let v = Vec2::new(radii.x * c, radii.y * s);
        centre + Vec2::new(v.x * rot.x - v.y * rot.y, v.x * rot.y + v.y * rot.x)
    };
    let full = (to - from).hypot() <= 1e-9 * (radii.x + radii.y);
    let phi0 = angle(from);
    let phi1 = angle(to);
    let span_pos = if full {
        TAU
    } else {
        (phi1 - phi0).rem_euclid(TAU)
    };
    let wrap = |x: f64| {
        // into (−π, π]
        let r = (x + PI).rem_euclid(TAU) - PI;
        if r == -PI {
            PI
        } else {
            r
        }
    };
    let mut angles = vec![phi0];
    angles.extend(guide.iter().map(|&g| angle(g)));
    angles.push(if full { phi0 } else { phi1 });
    let cost = |dir: f64| {
        let span = if full || dir > 0.0 {
            span_pos
        } else {
            TAU - span_pos
        };
        let mut c = 0.0;
        // Angular distance of guide points outside the arc.
        for &psi in &angles[1..angles.len() - 1] {
            let u = (dir * (psi - phi0)).rem_euclid(TAU);
            if u > span {
                c += (u - span).min(TAU - u);
            }
        }
        // Backward motion between consecutive points (not for the full turn's closing pair).
        for w in angles.windows(2) {
            c += (-dir * wrap(w[1] - w[0])).max(0.0);
        }
        c
    };
    let (cp, cn) = (cost(1.0), cost(-1.0));
    let dir = if (cp - cn).abs() <= 1e-12 {
        if full || span_pos <= PI {
            1.0
        } else {
            -1.0
        }
    } else if cp < cn {
        1.0
    } else {
        -1.0
    };
    let sweep = dir > 0.0;
    if full {
        // Not two half turns: an SVG arc whose chord is a diameter is ill-conditioned.
        let mid = at(phi0 + dir * TAU / 3.0);
        let arc = |a: Point, b: Point, large_arc: bool| {
            PathCommand::Arc(SvgArc {
                from: a,
                to: b,
                radii,
                x_rotation: theta,
                large_arc,
                sweep,
            })
        };
        return Some(vec![arc(from, mid, false), arc(mid, to, true)]);
    }
    let span = if sweep { span_pos } else { TAU - span_pos };
    Some(vec![PathCommand::Arc(SvgArc {
        from,
        to,
        radii,
        x_rotation: theta,
        large_arc: span > PI,
        sweep,
    })])
}

/// The exact quadratic Bézier of the parabola arc from `from` to `to`.
pub(super) fn parabola_path(
    conic: &Conic,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Vec<PathCommand>> {
    if from == to {
        return Some(Vec::new());
    }
    let (g0, g1) = (conic.gradient(from), conic.gradient(to));
    // g0·(Q − from) = 0 and g1·(Q − to) = 0.
    let det = g0.cross(g1);
    if det.abs() <= 1e-14 * g0.hypot() * g1.hypot() {
        return None;
    }
    let (r0, r1) = (g0.dot(from.to_vec2()), g1.dot(to.to_vec2()));
    let ctrl = Point::new((r0 * g1.y - r1 * g0.y) / det, (g0.x * r1 - g1.x * r0) / det);
    if !ctrl.is_finite() {
        return None;
    }
    let quad = QuadBez::new(from, ctrl, to);
    let guide_ok = guide
        .iter()
        .all(|&g| quad.nearest(g, 1e-9).distance_sq <= GUIDE_MAX_DISTANCE * GUIDE_MAX_DISTANCE);
    guide_ok.then(|| vec![PathCommand::Quad(ctrl, to)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use crate::curve::LevelPath;
    use crate::curve::{level_curve_path, project, CurveKind, Polynomial};
    use kurbo::{Arc, ParamCurve, PathEl};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// An arc of a random ellipse (a quarter of them with the rounded integer equation
        /// of the exporter), either way round, with a pixel-like guide up to 0.4 px off the
        /// curve: one exact arc, of the sweep intended, on the conic, near the guide.
        #[test]
        fn ellipse_arcs_go_the_guided_way(
            centre in (20.0..300.0f64, 20.0..300.0f64).prop_map(|(x, y)| Point::new(x, y)),
            (rx, ry) in (3.0..60.0f64, 3.0..60.0f64),
            th in -PI..PI,
            rounded in proptest::bool::weighted(0.25),
            phi0 in -PI..PI,
            magnitude in 0.1..TAU - 0.1,
            positive in proptest::bool::ANY,
            noise in proptest::collection::vec(-0.4..0.4f64, 200),
        ) {
            let k = if rounded {
                round_conic(ellipse_conic(centre, rx, ry, th, 1e6))
            } else {
                ellipse_conic(centre, rx, ry, th, rx * ry)
            };
            let poly = Polynomial::from(k);
            // The intended arc, in the recovered parametrisation (robust to the rounding).
            let EllipseParams {
                centre: c,
                radii: r,
                rotation: a,
            } = k.ellipse_params().unwrap();
            let sweep = if positive { magnitude } else { -magnitude };
            let from = ellipse_point(c, r.x, r.y, a, phi0);
            let to = ellipse_point(c, r.x, r.y, a, phi0 + sweep);
            // Guide: pixel-like points along the intended arc, up to 0.4 px off the curve.
            let n_guide = ((magnitude * r.x.max(r.y)) as usize).clamp(1, 200);
            let guide: Vec<Point> = (0..n_guide)
                .map(|i| {
                    let phi = phi0 + sweep * (i as f64 + 0.5) / n_guide as f64;
                    let p = ellipse_point(c, r.x, r.y, a, phi);
                    p + poly.gradient(p).normalize() * noise[i]
                })
                .collect();
            let LevelPath { commands: cmds, max_error: err } = level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
            if let [PathCommand::Line(end)] = cmds[..] {
                // A short arc of a large ellipse (0.1 rad of radius 27) is drawn as its
                // chord when that is within the tolerance (`flat_arc`).
                prop_assert_eq!(end, to);
                prop_assert!(err > 0.0 && err <= 0.05, "chord error {}", err);
                return Ok(());
            }
            prop_assert_eq!(err, 0.0);
            prop_assert_eq!(cmds.len(), 1);
            let PathCommand::Arc(svg) = cmds[0] else {
                panic!("expected an arc, got {cmds:?}");
            };
            let arc = Arc::from_svg_arc(&svg).unwrap();
            assert_close(
                arc.sweep_angle,
                sweep,
                1e-6,
                "sweep angle (direction and size)",
            );
            for i in 0..=64 {
                let p = arc.eval(i as f64 / 64.0);
                assert_le(poly.distance_estimate(p), 1e-6, "arc sample on the conic");
            }
            let samples = sample_path(from, &cmds, 256);
            for g in &guide {
                assert_le(min_distance(*g, &samples), 0.45, "guide near the arc");
            }
        }
    }

    #[test]
    fn integer_local_ellipse_far_from_origin() {
        // As the exporter builds it: integer coefficients on a local basis centred at a pixel,
        // 9 (x − x0)² − 4 (x − x0)(y − y0) + 6 (y − y0)² + 3 (x − x0) − 2 (y − y0) = 400.
        let origin = Point::new(913.5, 707.5);
        let poly = Polynomial::from_local(
            &[(2, 0), (1, 1), (0, 2), (1, 0), (0, 1)],
            &[9.0, -4.0, 6.0, 3.0, -2.0],
            origin,
            400.0,
        )
        .unwrap();
        let k = poly.as_conic().unwrap();
        assert_eq!(k.classify(), CurveKind::Ellipse);
        let EllipseParams {
            centre: c,
            radii: r,
            rotation: a,
        } = k.ellipse_params().unwrap();
        for sweep in [1.0, -2.5, 5.0] {
            let from = project(&poly, ellipse_point(c, r.x, r.y, a, 0.3), 1e-3).unwrap();
            let to = project(&poly, ellipse_point(c, r.x, r.y, a, 0.3 + sweep), 1e-3).unwrap();
            let guide: Vec<Point> = (1..20)
                .map(|i| ellipse_point(c, r.x, r.y, a, 0.3 + sweep * i as f64 / 20.0))
                .collect();
            let LevelPath { commands: cmds, .. } =
                level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
            let PathCommand::Arc(svg) = cmds[0] else {
                panic!("{cmds:?}")
            };
            let arc = Arc::from_svg_arc(&svg).unwrap();
            assert_close(arc.sweep_angle, sweep, 1e-6, "far ellipse sweep");
            for i in 0..=32 {
                assert_le(
                    poly.distance_estimate(arc.eval(i as f64 / 32.0)),
                    1e-6,
                    "far ellipse arc on curve",
                );
            }
        }
    }

    #[test]
    fn full_turn_emits_two_arcs() {
        let centre = Point::new(50.0, 40.0);
        let k = ellipse_conic(centre, 20.0, 8.0, 0.5, 160.0);
        let poly = Polynomial::from(k);
        let EllipseParams {
            centre: c,
            radii: r,
            rotation: a,
        } = k.ellipse_params().unwrap();
        for dir in [1.0, -1.0] {
            let from = ellipse_point(c, r.x, r.y, a, 1.0);
            let guide: Vec<Point> = (1..40)
                .map(|i| ellipse_point(c, r.x, r.y, a, 1.0 + dir * TAU * i as f64 / 40.0))
                .collect();
            let LevelPath { commands: cmds, .. } =
                level_curve_path(&poly, from, from, &guide, 0.05).unwrap();
            assert_eq!(cmds.len(), 2);
            let mut total = 0.0;
            let mut cur = from;
            for cmd in &cmds {
                let PathCommand::Arc(svg) = *cmd else {
                    panic!("{cmd:?}")
                };
                assert_point_close(svg.from, cur, 1e-12, "arc chaining");
                let arc = Arc::from_svg_arc(&svg).unwrap();
                total += arc.sweep_angle;
                for i in 0..=16 {
                    assert_le(
                        poly.distance_estimate(arc.eval(i as f64 / 16.0)),
                        1e-6,
                        "full turn on conic",
                    );
                }
                cur = svg.to;
            }
            assert_point_close(cur, from, 0.0, "closes");
            assert_close(total, dir * TAU, 1e-9, "total sweep");
            // The kurbo conversion chains as well.
            let els: Vec<PathEl> = cmds.iter().flat_map(|c| c.to_path_els(from)).collect();
            assert!(!els.is_empty());
        }
    }

    #[test]
    fn parabola_gives_exact_quad() {
        let mut worst: f64 = 0.0;
        for (i, th) in [0.0, 0.3, 1.1, 2.0, -2.7].into_iter().enumerate() {
            let v = Point::new(60.0 + i as f64, 30.0);
            let k = rotated_parabola(th, v);
            let poly = Polynomial::from(k);
            let (s, c) = th.sin_cos();
            // Local point (u, u²/4) → absolute.
            let at = |u: f64| {
                let (x, y) = (u, u * u / 4.0);
                v + Vec2::new(c * x - s * y, s * x + c * y)
            };
            let (u0, u1) = (-7.0 + i as f64, 5.0);
            let guide: Vec<Point> = (1..20)
                .map(|j| at(u0 + (u1 - u0) * j as f64 / 20.0))
                .collect();
            let LevelPath {
                commands: cmds,
                max_error: err,
            } = level_curve_path(&poly, at(u0), at(u1), &guide, 0.05).unwrap();
            assert_eq!(err, 0.0);
            assert!(
                matches!(cmds.as_slice(), [PathCommand::Quad(_, p)] if *p == at(u1)),
                "{cmds:?}"
            );
            for p in sample_path(at(u0), &cmds, 64) {
                let rel =
                    poly.eval(p).abs() / (poly.gradient(p).hypot() * (1.0 + p.to_vec2().hypot()));
                worst = worst.max(rel);
                assert_le(rel, 1e-9, "quad sample on parabola (relative)");
            }
            // Guide on another part of the parabola: rejected.
            let far = [at(u1 + 10.0)];
            assert!(level_curve_path(&poly, at(u0), at(u1), &far, 0.05).is_none());
        }
        eprintln!("parabola quads: worst relative |f|/|grad f| {worst:e}");
    }

    /// A huge circle through a short chord is drawn as that chord, within the tolerance; a
    /// piece running round a circle whose ends are close is not.
    #[test]
    fn flat_arcs_become_chords() {
        // The circle of radius r through the origin, centred at (0, r).
        let circle = |r: f64| Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, -2.0 * r, 0.0));
        let from = Point::new(0.0, 0.0);
        let x1: f64 = 40.0;
        let guide: Vec<Point> = (1..40).map(|x| Point::new(f64::from(x), 0.3)).collect();
        // Radius 1e9: the chord to (40, ~0) is within the tolerance.
        let r = 1e9;
        let to = Point::new(x1, r - (r * r - x1 * x1).sqrt());
        let LevelPath {
            commands: cmds,
            max_error: err,
        } = level_curve_path(&circle(r), from, to, &guide, 0.01).unwrap();
        assert_eq!(cmds, vec![PathCommand::Line(to)]);
        assert_le(err, 40.0 * 40.0 / (8.0 * r) * 1.01, "sagitta");
        // Too tight a tolerance for the sagitta of a radius-1000 circle: an exact arc.
        let r = 1000.0;
        let to = Point::new(x1, r - (r * r - x1 * x1).sqrt());
        let LevelPath { commands: cmds, .. } =
            level_curve_path(&circle(r), from, to, &guide, 0.1).unwrap();
        assert!(matches!(cmds[..], [PathCommand::Arc(_)]), "{cmds:?}");
        // Round a circle of radius 10 from (0, 0) back near it: the guide is not beside the
        // chord, so the arc goes round.
        let r = 10.0;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let (from, to) = (at(0.0), at(-0.05));
        let guide: Vec<Point> = (1..60).map(|i| at(f64::from(i) * 0.1)).collect();
        let LevelPath { commands: cmds, .. } =
            level_curve_path(&circle(r), from, to, &guide, 0.05).unwrap();
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
        // Tiny circles, where every point is within 2 px of any chord: once round from a
        // point back to it, and the long way round between two close points.
        let r = 0.9;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let guide: Vec<Point> = (1..20).map(|i| at(f64::from(i) * 0.3)).collect();
        let LevelPath { commands: cmds, .. } =
            level_curve_path(&circle(r), at(0.0), at(0.0), &guide, 0.05).unwrap();
        assert!(!cmds.is_empty(), "a full turn is not an empty path");
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
        let r = 1.0;
        let at = |phi: f64| Point::new(r * phi.sin(), r - r * phi.cos());
        let guide: Vec<Point> = (1..20).map(|i| at(f64::from(i) * 0.3)).collect();
        let LevelPath { commands: cmds, .. } =
            level_curve_path(&circle(r), at(0.0), at(-0.3), &guide, 0.05).unwrap();
        assert!(
            cmds.iter().all(|c| matches!(c, PathCommand::Arc(_))),
            "{cmds:?}"
        );
    }
}
