//! Traces of a curve between two points: polylines on the curve with unit tangents, from a
//! hyperbola's parametrisation or by marching along the curve.

use super::conic::HyperbolaParams;
use super::path::{ENDPOINT_MAX_DISTANCE, GUIDE_MAX_DISTANCE};
use super::polynomial::Polynomial;
use super::solve::{conic_foot, newton_to_curve, project, unit_tangent};
use crate::pixel::{Pixel, PixelMap};
use kurbo::{Line, ParamCurveNearest, Point, Vec2};
use std::f64::consts::PI;

/// Largest step (in pixels) of the numerical tracer used by
/// [`level_curve_path`](super::level_curve_path).
const TRACE_STEP: f64 = 0.25;

/// Largest arc length between consecutive points of a hyperbola's trace
/// ([`hyperbola_trace`]), in pixels.
const HYPERBOLA_STEP: f64 = 0.25;

/// Largest turn of the tangent between consecutive points of a hyperbola's trace, in
/// radians.
const HYPERBOLA_TURN: f64 = 0.1;

/// A traced polyline on the curve with unit tangents in the direction of travel.
pub(super) struct Trace {
    pub(super) pts: Vec<Point>,
    pub(super) tans: Vec<Vec2>,
}

/// The trace of a hyperbola arc from its parametrisation `centre + R(θ)(σ a cosh s, b sinh s)`
/// (as [`Conic::hyperbola_params`](super::Conic::hyperbola_params) gives it), with points at most [`HYPERBOLA_STEP`] apart in arc length
/// and [`HYPERBOLA_TURN`] in direction, and exact tangents, instead of marching along the
/// curve: between two points of one branch the arc
/// is unique. The parameter of a point of the curve is `asinh(v / b)`, `v` its coordinate
/// along the conjugate axis.
///
/// Returns `None` (the caller then marches with [`trace_curve`]) where the parametrisation
/// is not precise (coordinates beyond 1e8 px, or the middle trace point more than 1e-6 px
/// off the curve, as for huge, nearly parabolic hyperbolas), where `from == to`, or where a
/// guide point does not lie along the arc: its point of the curve ([`conic_foot`], else
/// [`project`]) must be within [`GUIDE_MAX_DISTANCE`], on the branch, and within
/// 1 + 2 [`GUIDE_MAX_DISTANCE`] px of arc length of the arc; or where the trace needs more
/// than four times the points of an arc of 3 times the guide's path plus 20 px (a safety
/// cap, as the marcher's).
#[allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x <= y)` also rejects NaN.
pub(super) fn hyperbola_trace(
    poly: &Polynomial,
    HyperbolaParams {
        centre,
        semi_axes: semi,
        rotation: angle,
    }: HyperbolaParams,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Trace> {
    if from == to {
        return None;
    }
    let (axis, across) = (Vec2::from_angle(angle), Vec2::from_angle(angle).turn_90());
    let (a, b) = (semi.x, semi.y);
    let local = |p: Point| ((p - centre).dot(axis), (p - centre).dot(across));
    let (u0, v0) = local(from);
    let (u1, v1) = local(to);
    let sigma = if u0 + u1 >= 0.0 { 1.0 } else { -1.0 };
    let (s0, s1) = ((v0 / b).asinh(), (v1 / b).asinh());
    let reach = centre.to_vec2().hypot() + a * s0.abs().max(s1.abs()).cosh();
    if !(reach <= 1e8) {
        return None;
    }
    let dir = if s1 >= s0 { 1.0 } else { -1.0 };
    // Speed |P′(s)| and unit tangent from (sinh s, cosh s).
    let speed = |(sh, ch): (f64, f64)| ((a * sh).powi(2) + (b * ch).powi(2)).sqrt();
    let tangent = |(sh, ch): (f64, f64)| {
        let t = axis * (sigma * a * sh) + across * (b * ch);
        t * (dir / t.hypot())
    };
    let sinh_cosh = |s: f64| (s.sinh(), s.cosh());
    let (lo, hi) = (s0.min(s1), s0.max(s1));
    for &g in guide {
        let q = match conic_foot(poly, g) {
            Some((d, q)) if d <= GUIDE_MAX_DISTANCE => q,
            _ => project(poly, g, GUIDE_MAX_DISTANCE)?,
        };
        let (u, v) = local(q);
        let sq = (v / b).asinh();
        let slack = (1.0 + 2.0 * GUIDE_MAX_DISTANCE) / speed(sinh_cosh(sq));
        if u * sigma < 0.0 || sq < lo - slack || sq > hi + slack {
            return None;
        }
    }
    // As in trace_curve, no arc longer than 3 times the guide's path plus 20 px; the
    // branch turns by less than π in all.
    let max_len = 3.0 * guide_length(from, guide, to) + 20.0;
    let max_points = (4.0 * (max_len / HYPERBOLA_STEP + PI / HYPERBOLA_TURN)) as usize + 2;
    let mut pts = vec![from];
    let mut tans = vec![tangent(sinh_cosh(s0))];
    // Steps in s: the arc length is ∫|P′| ds and the tangent turns by ∫ ab / |P′|² ds, with
    // the speed |P′(s)| = |(a sinh s, b cosh s)| monotonic on each side of the vertex
    // (s = 0): bounding by the speeds at both ends of a step (or at the vertex, if the
    // step crosses it) keeps it within
    // HYPERBOLA_STEP of length and HYPERBOLA_TURN of turn. e = exp(s) is carried by
    // multiplication, for cosh and sinh without further calls.
    let (mut s, mut e) = (s0, s0.exp());
    let from_exp = |e: f64| (0.5 * (e - 1.0 / e), 0.5 * (e + 1.0 / e));
    let speed_at = |e: f64| speed(from_exp(e));
    let step_for =
        |fast: f64, slow: f64| (HYPERBOLA_STEP / fast).min(HYPERBOLA_TURN * slow * slow / (a * b));
    loop {
        if pts.len() > max_points {
            return None;
        }
        let v = speed_at(e);
        let trial = step_for(v, v);
        let v_far = speed_at(e * (dir * trial).exp());
        // Across the vertex the slowest point is the vertex, where |P′| = b.
        let crosses = s * (s + dir * trial) <= 0.0;
        let slow = if crosses { b } else { v.min(v_far) };
        let ds = step_for(v.max(v_far), slow);
        // The rest in one step if it fits, else in two halves if it fits in two.
        let rest = (s1 - s) * dir;
        if !(rest > ds) {
            break;
        }
        let ds = if rest < 2.0 * ds { 0.5 * rest } else { ds };
        s += dir * ds;
        e *= (dir * ds).exp();
        let (sh, ch) = from_exp(e);
        pts.push(centre + axis * (sigma * a * ch) + across * (b * sh));
        tans.push(tangent((sh, ch)));
    }
    if pts.len() > 2 && !(poly.distance_estimate(pts[pts.len() / 2]) <= 1e-6) {
        return None;
    }
    pts.push(to);
    tans.push(tangent(sinh_cosh(s1)));
    Some(Trace { pts, tans })
}

/// Length of the polyline `from`, `guide…`, `to`.
fn guide_length(from: Point, guide: &[Point], to: Point) -> f64 {
    let mut len = 0.0;
    let mut prev = from;
    for &p in guide.iter().chain(std::iter::once(&to)) {
        len += (p - prev).hypot();
        prev = p;
    }
    len
}

/// Distance from `p` to the segment `[a, b]` (a point when `a == b`), by kurbo's nearest
/// point of a [`Line`].
pub(super) fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    Line::new(a, b).nearest(p, 0.0).distance_sq.sqrt()
}

/// Marches along the curve from `from` to `to`, passing the projections of the guide points.
pub(super) fn trace_curve(
    poly: &Polynomial,
    from: Point,
    to: Point,
    guide: &[Point],
) -> Option<Trace> {
    let start = project(poly, from, ENDPOINT_MAX_DISTANCE)?;
    let end = project(poly, to, ENDPOINT_MAX_DISTANCE)?;
    let targets: Vec<Point> = guide
        .iter()
        .map(|&g| project(poly, g, GUIDE_MAX_DISTANCE))
        .collect::<Option<_>>()?;
    let guide_len = guide_length(from, guide, to);
    if from == to && targets.is_empty() {
        return Some(Trace {
            pts: vec![from],
            tans: vec![Vec2::ZERO],
        });
    }
    // Guide points close to the ends may project just outside the piece: not required.
    let mut visited: Vec<bool> = targets
        .iter()
        .map(|&w| (w - start).hypot() <= 1.0 || (w - end).hypot() <= 1.0)
        .collect();
    let mut unvisited = visited.iter().filter(|&&v| !v).count();
    // The targets by unit cell, so that each step only looks at the targets near it (a
    // piece may have thousands of them).
    let cell = |p: Point| Pixel::new(p.x.floor() as i32, p.y.floor() as i32);
    let mut grid: PixelMap<Vec<usize>> = PixelMap::default();
    for (k, &w) in targets.iter().enumerate() {
        if !visited[k] {
            grid.entry(cell(w)).or_default().push(k);
        }
    }
    // Initial orientation: towards the first waypoint not too close to the start.
    let first = targets
        .iter()
        .chain(std::iter::once(&end))
        .find(|&&w| (w - start).hypot() > 0.5)
        .or_else(|| {
            targets
                .iter()
                .chain(std::iter::once(&end))
                .max_by(|a, b| (**a - start).hypot().total_cmp(&(**b - start).hypot()))
        })
        .copied()?;
    let towards = first - start;
    let mut t = match unit_tangent(poly, start) {
        Some(t) if t.dot(towards) >= 0.0 => t,
        Some(t) => -t,
        None => towards.normalize(),
    };
    if !t.is_finite() {
        return None;
    }
    let mut pts = vec![from];
    let mut tans = vec![t];
    let mut p = start;
    let mut h = TRACE_STEP;
    let mut travelled = 0.0;
    let max_len = 3.0 * guide_len + 20.0;
    let mut iterations = 0usize;
    loop {
        iterations += 1;
        if travelled > max_len || iterations > 1_000_000 {
            return None;
        }
        let q0 = p + t * h;
        let accepted = newton_to_curve(poly, q0, h).and_then(|q| {
            let tq = match unit_tangent(poly, q) {
                Some(tq) if tq.dot(t) >= 0.0 => tq,
                Some(tq) => -tq,
                None => t,
            };
            let ok =
                (q - q0).hypot() <= 0.3 * h && tq.dot(t) >= 0.3f64.cos() && (q - p).dot(t) > 0.0;
            ok.then_some((q, tq))
        });
        let Some((q, tq)) = accepted else {
            h *= 0.5;
            if h < 1e-9 {
                return None;
            }
            continue;
        };
        let near = (0.2 * h).max(1e-6);
        if unvisited > 0 {
            let (lo, hi) = (
                cell(Point::new(p.x.min(q.x) - near, p.y.min(q.y) - near)),
                cell(Point::new(p.x.max(q.x) + near, p.y.max(q.y) + near)),
            );
            for cy in lo.y..=hi.y {
                for cx in lo.x..=hi.x {
                    let Some(ks) = grid.get(&Pixel::new(cx, cy)) else {
                        continue;
                    };
                    for &k in ks {
                        if !visited[k] && segment_distance(targets[k], p, q) <= near {
                            visited[k] = true;
                            unvisited -= 1;
                        }
                    }
                }
            }
        }
        let step_len = (q - p).hypot();
        if unvisited == 0
            && travelled + step_len >= 0.5 * guide_len
            && segment_distance(end, p, q) <= near
        {
            let t_end = match unit_tangent(poly, end) {
                Some(te) if te.dot(tq) >= 0.0 => te,
                Some(te) => -te,
                None => tq,
            };
            pts.push(to);
            tans.push(t_end);
            return Some(Trace { pts, tans });
        }
        travelled += step_len;
        pts.push(q);
        tans.push(tq);
        p = q;
        t = tq;
        h = (1.5 * h).min(TRACE_STEP);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use crate::curve::LevelPath;
    use crate::curve::{level_curve_path, Conic, CurveKind};
    use std::f64::consts::TAU;

    #[test]
    fn hyperbola_trace_is_on_the_curve_and_fine_enough() {
        // Semi-axes from the glyph_S piece the marching tracer failed on (a ≈ 0.96,
        // b ≈ 1.25, an arc far out along the asymptotes), and a wider one.
        for (a, b, th, t0, t1) in [
            (0.96, 1.25, 2.57, -2.5, 0.4),
            (12.0, 8.0, 0.6, -1.5, 2.0),
            (20.9, 5.1, 0.09, 0.3, -0.8),
        ] {
            let centre = Point::new(40.0, 30.0);
            let (poly, at2) = rotated_hyperbola(a, b, th, centre);
            let params = poly.as_conic().unwrap().hyperbola_params().unwrap();
            let at = |t: f64| at2(1.0, t);
            let guide: Vec<Point> = (1..40)
                .map(|j| at(t0 + (t1 - t0) * j as f64 / 40.0))
                .collect();
            let tr = hyperbola_trace(&poly, params, at(t0), at(t1), &guide).expect("trace");
            assert_point_close(tr.pts[0], at(t0), 0.0, "starts at from");
            assert_point_close(*tr.pts.last().unwrap(), at(t1), 0.0, "ends at to");
            for (k, w) in tr.pts.windows(2).enumerate() {
                assert_le(
                    poly.distance_estimate(w[1]),
                    1e-9,
                    "trace point on the curve",
                );
                assert_le((w[1] - w[0]).hypot(), HYPERBOLA_STEP + 1e-9, "step length");
                let (ta, tb) = (tr.tans[k], tr.tans[k + 1]);
                assert_close(ta.hypot(), 1.0, 1e-12, "unit tangent");
                assert_le(
                    ta.cross(tb).abs().asin(),
                    HYPERBOLA_TURN + 1e-9,
                    "turn per step",
                );
                assert!((w[1] - w[0]).dot(ta) > 0.0, "tangent along the travel");
            }
            // A guide on the other branch, or beyond the arc, is refused.
            let mirrored: Vec<Point> = guide.iter().map(|&g| centre - (g - centre)).collect();
            assert!(hyperbola_trace(&poly, params, at(t0), at(t1), &mirrored).is_none());
            let beyond = [at(t1 + (t1 - t0))];
            assert!(hyperbola_trace(&poly, params, at(t0), at(t1), &beyond).is_none());
            check_fit(&poly, at(t0), at(t1), &guide, 0.05);
        }
    }

    #[test]
    fn line_pair_traced_through_crossing() {
        // (x − y)(x + y) = 0 shifted to (30, 30); follow y = x through the crossing.
        let o = Point::new(30.0, 30.0);
        let poly = Polynomial::from_local(&[(2, 0), (0, 2)], &[1.0, -1.0], o, 0.0).unwrap();
        assert_eq!(poly.as_conic().unwrap().classify(), CurveKind::Degenerate);
        let from = o + Vec2::new(-5.0, -5.0);
        let to = o + Vec2::new(5.0, 5.0);
        let guide: Vec<Point> = (1..10)
            .map(|i| from + Vec2::new(i as f64, i as f64))
            .collect();
        let (_, measured) = check_fit(&poly, from, to, &guide, 0.05);
        assert_le(measured, 1e-6, "straight piece");
        // Empty locus: nothing to trace.
        let empty = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, 1.0));
        assert!(level_curve_path(&empty, Point::ZERO, Point::new(1.0, 0.0), &[], 0.05).is_none());
    }

    #[test]
    fn double_line_and_two_ovals() {
        // (x − y)² = 0: the gradient vanishes on the curve itself.
        let o = Point::new(12.5, 7.5);
        let double =
            Polynomial::from_local(&[(2, 0), (1, 1), (0, 2)], &[1.0, -2.0, 1.0], o, 0.0).unwrap();
        let from = o + Vec2::new(-4.0, -4.0);
        let to = o + Vec2::new(4.0, 4.0);
        let guide: Vec<Point> = (1..8)
            .map(|i| from + Vec2::new(i as f64 + 0.3, i as f64))
            .collect();
        let LevelPath {
            commands: cmds,
            max_error: err,
        } = level_curve_path(&double, from, to, &guide, 0.05).unwrap();
        assert_le(err, 0.05, "double line error");
        assert_point_close(cmds.last().unwrap().end(), to, 0.0, "double line end");
        for p in sample_path(from, &cmds, 32) {
            assert_le(segment_distance(p, from, to), 1e-6, "double line straight");
        }
        // Two circles of radius 2 as one quartic: (x² + y² − 4)((x − 10)² + y² − 4).
        let c1 = Polynomial::from(Conic::new(1.0, 0.0, 1.0, 0.0, 0.0, -4.0));
        let mut terms = Vec::new();
        // (x² + y² − 4)(x² + y² − 20x + 96), expanded.
        let p1 = [(2, 0, 1.0), (0, 2, 1.0), (0, 0, -4.0)];
        let p2 = [(2, 0, 1.0), (0, 2, 1.0), (1, 0, -20.0), (0, 0, 96.0)];
        for &(a1, b1, k1) in &p1 {
            for &(a2, b2, k2) in &p2 {
                terms.push((a1 + a2, b1 + b2, k1 * k2));
            }
        }
        let ovals = Polynomial::new(&terms).unwrap();
        let circle_at = |cx: f64, phi: f64| Point::new(cx + 2.0 * phi.cos(), 2.0 * phi.sin());
        for phi in [0.0, 1.0, 2.5] {
            assert_le(
                ovals.distance_estimate(circle_at(0.0, phi)),
                1e-12,
                "first oval",
            );
            assert_le(
                ovals.distance_estimate(circle_at(10.0, phi)),
                1e-12,
                "second oval",
            );
            assert_le(c1.distance_estimate(circle_at(0.0, phi)), 1e-12, "circle");
        }
        let (from, to) = (circle_at(0.0, 0.0), circle_at(0.0, 2.0));
        let own: Vec<Point> = (1..10).map(|i| circle_at(0.0, 0.2 * i as f64)).collect();
        check_fit(&ovals, from, to, &own, 0.05);
        let other: Vec<Point> = (1..10).map(|i| circle_at(10.0, 0.2 * i as f64)).collect();
        assert!(level_curve_path(&ovals, from, to, &other, 0.05).is_none());
    }

    #[test]
    fn long_sextic_loop_is_fast_enough() {
        // x⁶ + y⁶ = 200⁶ around (400.5, 300.5): a closed curve ~1500 px long.
        let origin = Point::new(400.5, 300.5);
        let r = 200.0f64;
        let poly =
            Polynomial::from_local(&[(6, 0), (0, 6)], &[1.0, 1.0], origin, r.powi(6)).unwrap();
        let at = |phi: f64| {
            let (s, c) = phi.sin_cos();
            origin + Vec2::new(c, s) * (r / (c.powi(6) + s.powi(6)).powf(1.0 / 6.0))
        };
        let guide: Vec<Point> = (1..1200)
            .map(|j| at(0.3 + TAU * j as f64 / 1200.0))
            .collect();
        let start = std::time::Instant::now();
        let (cmds, measured) = check_fit(&poly, at(0.3), at(0.3), &guide, 0.05);
        let elapsed = start.elapsed();
        eprintln!(
            "long sextic loop: {} cubics, max distance {measured:e}, {elapsed:?} (with checks)",
            cmds.len()
        );
        assert!(elapsed.as_secs_f64() < 20.0, "too slow: {elapsed:?}");
    }
}
