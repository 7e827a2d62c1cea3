//! Piecewise cubic Bézier fits of a trace, within a measured distance of the true curve.

use super::command::PathCommand;
use super::path::LevelPath;
use super::polynomial::Polynomial;
use super::power::PowerCubic;
use super::solve::distance_bound;
use super::trace::Trace;
use kurbo::{CubicBez, ParamCurve};

/// Cubic candidates over the trace points `i..=j`, both with the end tangents of the trace:
/// the Hermite cubic with tangent lengths a third of the arc length, and (when it is well
/// posed) the least-squares one whose two tangent lengths minimise the squared distances to
/// the trace points at their chord-length parameters (Schneider's method).
fn candidates(trace: &Trace, i: usize, j: usize) -> Vec<CubicBez> {
    let pts = &trace.pts[i..=j];
    let mut cum = Vec::with_capacity(pts.len());
    let mut len = 0.0;
    cum.push(0.0);
    for w in pts.windows(2) {
        len += (w[1] - w[0]).hypot();
        cum.push(len);
    }
    let (p0, p3) = (pts[0], pts[pts.len() - 1]);
    let (t0, t1) = (trace.tans[i], -trace.tans[j]);
    // (Room for both: growing it by one was 0.3% of a glyph's instructions.)
    let mut out = Vec::with_capacity(2);
    out.push(CubicBez::new(
        p0,
        p0 + t0 * (len / 3.0),
        p3 + t1 * (len / 3.0),
        p3,
    ));
    if pts.len() < 4 || len <= 0.0 {
        return out;
    }
    let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (p, &l) in pts.iter().zip(&cum) {
        let t = l / len;
        let mt = 1.0 - t;
        let (b0, b1, b2, b3) = (mt * mt * mt, 3.0 * t * mt * mt, 3.0 * t * t * mt, t * t * t);
        let (a1, a2) = (t0 * b1, t1 * b2);
        c00 += a1.dot(a1);
        c01 += a1.dot(a2);
        c11 += a2.dot(a2);
        let r = *p - (p0.to_vec2() * (b0 + b1) + p3.to_vec2() * (b2 + b3)).to_point();
        x0 += r.dot(a1);
        x1 += r.dot(a2);
    }
    let det = c00 * c11 - c01 * c01;
    if det.abs() > 1e-12 * c00 * c11 {
        let alpha = (x0 * c11 - x1 * c01) / det;
        let beta = (c00 * x1 - c01 * x0) / det;
        if alpha > 1e-3 * len && beta > 1e-3 * len && alpha < len && beta < len {
            out.push(CubicBez::new(p0, p0 + t0 * alpha, p3 + t1 * beta, p3));
        }
    }
    out
}

/// An upper bound on the distance between a cubic and the curve, in both directions: from
/// cubic samples to the curve (the point of the curve that Newton steps along the gradient
/// reach from the sample), and from the trace points `i..=j` to the cubic (the point of the
/// cubic that Newton's method on `(B(t) − p)·B′(t) = 0` reaches from the previous trace
/// point's parameter). Both are distances to actual points of the other curve, hence upper
/// bounds of the true distances; for the small distances a fit accepts they are within
/// `O(d²κ)` of them.
///
/// Stops early, returning a value above `cutoff`, once the bound exceeds `cutoff`.
fn cubic_error(
    poly: &Polynomial,
    c: &CubicBez,
    trace: &Trace,
    i: usize,
    j: usize,
    tol: f64,
    cutoff: f64,
) -> f64 {
    let mut err: f64 = 0.0;
    // 23 samples at k/24, the coarse ones first (a bad fit is usually worst mid-way, so
    // the cutoff is met early).
    const ORDER: [u8; 23] = [
        12, 6, 18, 3, 9, 15, 21, 1, 2, 4, 5, 7, 8, 10, 11, 13, 14, 16, 17, 19, 20, 22, 23,
    ];
    for k in ORDER {
        let s = c.eval(f64::from(k) / 24.0);
        match distance_bound(poly, s, 4.0 * tol + 1.0) {
            Some(d) => err = err.max(d),
            None => return f64::INFINITY,
        }
        if err > cutoff {
            return err;
        }
    }
    // Trace points, at most about 64 of them, evenly spread, in order along the cubic; the
    // power form for cheap B, B′ and B″.
    let w = PowerCubic::new(c);
    let p0 = w.p0;
    let stride = ((j - i) / 64).max(1);
    let mut t = 0.0;
    for &p in trace.pts[i + 1..j].iter().step_by(stride) {
        let q = p.to_vec2() - p0;
        let mut best = f64::INFINITY;
        let mut u: f64 = t;
        for _ in 0..8 {
            let r = w.offset(u) - q;
            let d = r.hypot2();
            if d < best {
                best = d;
                t = u;
            }
            if d <= err * err {
                break; // this point cannot raise the maximum
            }
            let v1 = w.deriv(u);
            let v2 = w.second_deriv(u);
            let g = r.dot(v1);
            let h = v1.hypot2() + r.dot(v2);
            let next = if h > 0.0 {
                u - g / h
            } else {
                u - g.signum() * 0.05
            };
            let next = next.clamp(0.0, 1.0);
            if (next - u).abs() <= 1e-9 {
                break;
            }
            u = next;
        }
        err = err.max(best.sqrt());
        if err > cutoff {
            return err;
        }
    }
    err
}

/// The better of the [`candidates`] over the trace points `i..=j`, with its error bound
/// (see [`cubic_error`]; above `cutoff` only says that no candidate is within `cutoff`).
fn best_fit(
    poly: &Polynomial,
    trace: &Trace,
    i: usize,
    j: usize,
    tol: f64,
    cutoff: f64,
) -> (CubicBez, f64) {
    let mut cands = candidates(trace, i, j).into_iter();
    let first = cands
        .next()
        .unwrap_or_else(|| CubicBez::new(trace.pts[i], trace.pts[i], trace.pts[j], trace.pts[j]));
    let first_err = cubic_error(poly, &first, trace, i, j, tol, cutoff);
    cands.fold((first, first_err), |best, c| {
        let err = cubic_error(poly, &c, trace, i, j, tol, cutoff.min(best.1));
        if err < best.1 {
            (c, err)
        } else {
            best
        }
    })
}

/// Piecewise cubic fit of a trace within `tol`; returns the commands and the maximal error.
///
/// Greedy: from each start, the farthest trace point reachable by one cubic within `tol` is
/// found by galloping then bisection.
///
/// Returns None if a single trace step cannot be fitted within `tol`: where the trace
/// crosses the gap between two branches by a saddle of `f`, its chord is off the curve.
pub(super) fn fit_cubics(poly: &Polynomial, trace: &Trace, tol: f64) -> Option<LevelPath> {
    let n = trace.pts.len();
    let mut out = Vec::new();
    let mut max_err: f64 = 0.0;
    let mut i = 0;
    while i + 1 < n {
        // Gallop: double the reach while one cubic fits, then bisect. Invariant: the fit to
        // `lo` is acceptable (`best`; or lo = i + 1, not yet measured), the fit to `hi` is
        // not.
        let mut lo = i + 1;
        let mut best = None;
        let mut hi = None;
        let mut step = 8;
        // The rest of the trace first: one cubic often suffices for a whole piece, and a
        // failing try stops at the cutoff.
        if n - 1 > i + step {
            let fit = best_fit(poly, trace, i, n - 1, tol, tol);
            if fit.1 <= tol {
                lo = n - 1;
                best = Some(fit);
            } else {
                hi = Some(n - 1);
            }
        }
        while lo < n - 1 && hi.is_none_or(|h| i + step < h) {
            let j = (i + step).min(n - 1);
            let fit = best_fit(poly, trace, i, j, tol, tol);
            if fit.1 <= tol {
                lo = j;
                best = Some(fit);
                step *= 2;
            } else {
                hi = Some(j);
                break;
            }
        }
        if let Some(mut hi) = hi {
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                let fit = best_fit(poly, trace, i, mid, tol, tol);
                if fit.1 <= tol {
                    lo = mid;
                    best = Some(fit);
                } else {
                    hi = mid;
                }
            }
        }
        let best = match best {
            Some(best) => best,
            None => Some(best_fit(poly, trace, i, lo, tol, tol)).filter(|fit| fit.1 <= tol)?,
        };
        let end = lo;
        max_err = max_err.max(best.1);
        out.push(PathCommand::Cubic(best.0.p1, best.0.p2, best.0.p3));
        i = end;
    }
    Some(LevelPath {
        commands: out,
        max_error: max_err,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::solve::unit_tangent;
    use crate::curve::test_util::*;
    use crate::curve::LevelPath;
    use crate::curve::{level_curve_path, Polynomial};
    use kurbo::{Arc, Point, Vec2};
    use proptest::prelude::*;
    use std::f64::consts::{PI, TAU};

    #[test]
    fn hyperbola_fit() {
        // (x' /3)² − (y'/2)² = 1 in pixels×4, rotated by 0.6, centred at (80, 50).
        let (poly, at) = rotated_hyperbola(12.0, 8.0, 0.6, Point::new(80.0, 50.0));
        let mut worst: f64 = 0.0;
        for sign in [1.0, -1.0] {
            let (t0, t1) = (-1.5, 2.0);
            let guide: Vec<Point> = (1..60)
                .map(|j| at(sign, t0 + (t1 - t0) * j as f64 / 60.0))
                .collect();
            let (cmds, measured) = check_fit(&poly, at(sign, t0), at(sign, t1), &guide, 0.05);
            worst = worst.max(measured);
            eprintln!(
                "hyperbola branch {sign}: {} cubics, max distance {measured:e}",
                cmds.len()
            );
        }
        // Different branches.
        assert!(level_curve_path(&poly, at(1.0, 0.0), at(-1.0, 0.0), &[], 0.05).is_none());
        eprintln!("hyperbola fit: worst sampled distance {worst:e}");
    }

    #[test]
    fn a_trace_step_across_a_saddle_is_not_fitted() {
        // x² − y² = 0.01: the branches' vertices (±0.1, 0) face each other across the
        // saddle at the origin; a trace step from one to the other runs 0.1 px off the curve.
        let poly =
            Polynomial::from_local(&[(2, 0), (0, 2)], &[1.0, -1.0], Point::ORIGIN, 0.01).unwrap();
        let (p, q) = (Point::new(-0.1, 0.0), Point::new(0.1, 0.0));
        assert_le(poly.distance_estimate(p), 1e-12, "on the curve");
        let across = Trace {
            pts: vec![p, q],
            tans: vec![Vec2::new(1.0, 0.0); 2],
        };
        assert!(fit_cubics(&poly, &across, 0.05).is_none());
        // The same step is accepted at a tolerance above the gap.
        let LevelPath {
            commands: cmds,
            max_error: err,
        } = fit_cubics(&poly, &across, 0.2).expect("fits at 0.2 px");
        assert_eq!(cmds.len(), 1);
        assert_le(err, 0.2, "stated error");
    }

    #[test]
    fn cubic_fit() {
        let (poly, at) = cubic_curve();
        assert_eq!(poly.degree(), 3);
        let (x0, x1) = (-2.0, 3.0);
        let guide: Vec<Point> = (1..80)
            .map(|j| at(x0 + (x1 - x0) * j as f64 / 80.0))
            .collect();
        let (cmds, measured) = check_fit(&poly, at(x0), at(x1), &guide, 0.05);
        eprintln!(
            "cubic fit: {} cubics, max distance {measured:e}",
            cmds.len()
        );
        // Reverse direction.
        let rev: Vec<Point> = guide.iter().rev().copied().collect();
        let (_, measured) = check_fit(&poly, at(x1), at(x0), &rev, 0.05);
        eprintln!("cubic fit reversed: max distance {measured:e}");
        // No curve near the guide.
        let off = [at(0.0) + Vec2::new(30.0, 0.0)];
        assert!(level_curve_path(&poly, at(x0), at(x1), &off, 0.05).is_none());
    }

    #[test]
    fn quartic_fit_both_ways_and_full_loop() {
        // x⁴ + y⁴ = 20⁴ around (100, 100).
        let origin = Point::new(100.0, 100.0);
        let r = 20.0f64;
        let poly =
            Polynomial::from_local(&[(4, 0), (0, 4)], &[1.0, 1.0], origin, r.powi(4)).unwrap();
        let at = |phi: f64| {
            let (s, c) = phi.sin_cos();
            let k = r / (c.powi(4) + s.powi(4)).powf(0.25);
            origin + Vec2::new(k * c, k * s)
        };
        for (phi0, sweep) in [(0.0, PI / 2.0), (0.0, -1.5 * PI), (1.0, TAU), (2.0, -TAU)] {
            let from = at(phi0);
            let to = at(phi0 + sweep);
            let guide: Vec<Point> = (1..100)
                .map(|j| at(phi0 + sweep * j as f64 / 100.0))
                .collect();
            let (cmds, measured) = check_fit(&poly, from, to, &guide, 0.05);
            let samples = sample_path(from, &cmds, 64);
            // The complementary part is not covered.
            if sweep.abs() < TAU {
                let other = at(phi0 + sweep + sweep.signum() * (TAU - sweep.abs()) / 2.0);
                assert!(min_distance(other, &samples) > 1.0, "wrong way round");
            }
            eprintln!(
                "quartic {phi0} {sweep}: {} cubics, max distance {measured:e}",
                cmds.len()
            );
        }
    }

    /// Pixel-like guide: points of the curve pushed along the normal by `noise` times the
    /// offsets (in [−1, 1], taken in turn), plus points overshooting both ends by half a
    /// pixel.
    fn noisy_guide(poly: &Polynomial, pts: &[Point], noise: f64, offsets: &[f64]) -> Vec<Point> {
        let mut out = Vec::new();
        let first = pts[0];
        let last = pts[pts.len() - 1];
        let t0 = unit_tangent(poly, first).unwrap();
        let t0 = if t0.dot(pts[1] - first) > 0.0 {
            t0
        } else {
            -t0
        };
        out.push(first - t0 * 0.5);
        for (k, &p) in pts[1..pts.len() - 1].iter().enumerate() {
            let n = poly.gradient(p).normalize();
            out.push(p + n * (noise * offsets[k % offsets.len()]));
        }
        let t1 = unit_tangent(poly, last).unwrap();
        let t1 = if t1.dot(last - pts[pts.len() - 2]) > 0.0 {
            t1
        } else {
            -t1
        };
        out.push(last + t1 * 0.5);
        out
    }

    /// Offsets for [`noisy_guide`].
    fn offsets() -> impl Strategy<Value = Vec<f64>> {
        proptest::collection::vec(-1.0..1.0f64, 64)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        #[test]
        fn sextic_far_from_origin_with_noisy_guides(offsets in offsets()) {
            // x⁶ + y⁶ = 10⁶ around (800.5, 600.5): absolute coefficients up to ~1e18.
            let origin = Point::new(800.5, 600.5);
            let r = 10.0f64;
            let poly =
                Polynomial::from_local(&[(6, 0), (0, 6)], &[1.0, 1.0], origin, r.powi(6)).unwrap();
            prop_assert_eq!(poly.degree(), 6);
            let at = |phi: f64| {
                let (s, c) = phi.sin_cos();
                let k = r / (c.powi(6) + s.powi(6)).powf(1.0 / 6.0);
                origin + Vec2::new(k * c, k * s)
            };
            for (phi0, sweep) in [(0.2, 2.0), (0.2, -3.0), (-1.0, TAU)] {
                let exact: Vec<Point> = (0..=60)
                    .map(|j| at(phi0 + sweep * j as f64 / 60.0))
                    .collect();
                let guide = noisy_guide(&poly, &exact, 0.45, &offsets);
                let (cmds, _) = check_fit(&poly, exact[0], exact[60], &guide, 0.05);
                let samples = sample_path(exact[0], &cmds, 64);
                for p in &exact {
                    assert_le(min_distance(*p, &samples), 0.05, "intended part covered");
                }
            }
        }

        #[test]
        fn noisy_guides_on_cubic_and_ellipse(offsets in offsets()) {
            let (poly, at) = cubic_curve();
            let exact: Vec<Point> = (0..=50).map(|j| at(-2.0 + 5.0 * j as f64 / 50.0)).collect();
            let guide = noisy_guide(&poly, &exact, 0.45, &offsets);
            check_fit(&poly, exact[0], exact[50], &guide, 0.05);
            // Ellipse, small and large arcs, guide overshooting both ends.
            let centre = Point::new(30.0, 20.0);
            let k = ellipse_conic(centre, 12.0, 5.0, 0.3, 60.0);
            let epoly = Polynomial::from(k);
            for sweep in [0.4, -0.4, 4.0, -4.0] {
                let exact: Vec<Point> = (0..=30)
                    .map(|j| ellipse_point(centre, 12.0, 5.0, 0.3, 1.0 + sweep * j as f64 / 30.0))
                    .collect();
                let guide = noisy_guide(&epoly, &exact, 0.45, &offsets);
                let LevelPath { commands: cmds, .. } =
                    level_curve_path(&epoly, exact[0], exact[30], &guide, 0.05).unwrap();
                let PathCommand::Arc(svg) = cmds[0] else {
                    panic!("{cmds:?}")
                };
                let arc = Arc::from_svg_arc(&svg).unwrap();
                assert_close(arc.sweep_angle, sweep, 1e-6, "noisy guide sweep");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Arcs of random hyperbolas (traced and fitted by cubics), at tolerances from 0.01
        /// to 0.2 px, with a guide of pixel-like points up to 0.45 px off the curve: the
        /// path ends where asked, its stated error and the distance measured on its samples
        /// are within the tolerance, and the guide's projections lie near it ([`check_fit`]).
        #[test]
        fn hyperbola_fit_error_within_tolerance(
            (a, b) in (3.0..30.0f64, 3.0..30.0f64),
            th in -PI..PI,
            centre in (50.0..150.0f64, 50.0..150.0f64).prop_map(|(x, y)| Point::new(x, y)),
            sign in prop_oneof![Just(1.0), Just(-1.0)],
            t0 in -2.0..1.0f64,
            length in 0.3..2.0f64,
            tolerance in 0.01..0.2f64,
            offsets in offsets(),
        ) {
            let (poly, at) = rotated_hyperbola(a, b, th, centre);
            let t1 = t0 + length;
            let exact: Vec<Point> = (0..=40)
                .map(|j| at(sign, t0 + length * j as f64 / 40.0))
                .collect();
            let guide = noisy_guide(&poly, &exact, 0.45, &offsets);
            check_fit(&poly, at(sign, t0), at(sign, t1), &guide, tolerance);
        }
    }
}
