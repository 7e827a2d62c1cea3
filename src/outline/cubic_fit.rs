//! The least-squares fit of one cubic through a run's cracks, with the chords the renderer
//! draws it in (the math is in [`super::absorb`]'s documentation): Lawson's reweighted
//! least squares on the two control points, and the samples' parameters moved to their
//! nearest points on the curve between fits.

use crate::curve::PowerCubic;
use kurbo::{CubicBez, ParamCurve, Point, Vec2};

/// The Bernstein weights of `A, P1, P2, E` at `t`.
fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// The weights of `A, P1, P2, E` in the point at the fraction `u` of the cubic's polygon of
/// `chords` chords (between its points at `t = i / chords`).
fn chord_weights(u: f64, chords: u32) -> [f64; 4] {
    let n = f64::from(chords);
    // (Truncated, not `floor`, a library call: the same below `n` once clamped.)
    let i = ((u * n) as i64 as f64).clamp(0.0, n - 1.0);
    let f = u * n - i;
    let (b0, b1) = (bernstein(i / n), bernstein((i + 1.0) / n));
    std::array::from_fn(|k| (1.0 - f) * b0[k] + f * b1[k])
}

/// A crack the cubic must pass: its middle `t`, within `tol` (px) along `normal`; `u` its
/// parameter on the curve, `u0` its fraction of the run's length (kept by the rows along the
/// run, so the control points spread as the run does).
#[derive(Clone, Copy)]
pub(super) struct Sample {
    pub(super) u: f64,
    pub(super) u0: f64,
    pub(super) t: Point,
    pub(super) normal: Vec2,
    pub(super) tol: f64,
}

/// One row `coef · p = rhs` of a fit's system, p = (P1x, P1y, P2x, P2y).
type Row = ([f64; 4], f64);

/// `lhs += w c cᵀ`, `rhs += w c r` (the upper triangle; mirrored before solving).
fn add_row(lhs: &mut [[f64; 4]; 4], rhs: &mut [f64; 4], (c, r): &Row, w: f64) {
    for i in 0..4 {
        let wc = w * c[i];
        for k in i..4 {
            lhs[i][k] += wc * c[k];
        }
        rhs[i] += wc * r;
    }
}

/// The fits of one run's cubic from `a` to `e` through its samples: the rows along the run,
/// which stay while the samples' parameters move, summed once, and buffers for the rows
/// across it, reused by every [`Fit::fit`].
pub(super) struct Fit {
    /// The rows along the run, summed: `lhs` (upper triangle) and `rhs`.
    along: ([[f64; 4]; 4], [f64; 4]),
    /// Each sample's terms of its rows that do not depend on its parameter.
    scaled: Vec<Scaled>,
    /// The rows across the run, per sample (see [`SampleRows`]).
    rows: Vec<SampleRows>,
}

/// A sample's rows across the run, the curve's and (when the fit has chords) the chord's,
/// with their weights and last residuals.
#[derive(Clone, Copy)]
struct SampleRows {
    row: [Across; 2],
    w: [f64; 2],
    res: [f64; 2],
}

/// A row across the run, `c₁ (n · P1) + c₂ (n · P2) = r` with its sample's `n` (over its
/// tolerance): `[c₁, c₂, r]`.
type Across = [f64; 3];

/// The row asking `n · (C − t) = 0` within `tol`, where `C = c₀ A + c₁ P1 + c₂ P2 + c₃ E`.
fn row(a: Point, e: Point, c: [f64; 4], n: Vec2, t: Point, tol: f64) -> Row {
    Scaled::new(a, e, n, t, tol).row(c)
}

/// The terms of a row of [`row`] that do not depend on the weights `c`: `n / tol`, its
/// products `nₓ², nₓ n_y, n_y²`, and `n · t`, `n · A`, `n · E` over `tol`.
#[derive(Clone, Copy)]
struct Scaled {
    n: Vec2,
    nn: [f64; 3],
    t: f64,
    a: f64,
    e: f64,
}

impl Scaled {
    fn new(a: Point, e: Point, n: Vec2, t: Point, tol: f64) -> Scaled {
        let inv = 1.0 / tol;
        let ns = n * inv;
        Scaled {
            n: ns,
            nn: [ns.x * ns.x, ns.x * ns.y, ns.y * ns.y],
            t: n.dot(t.to_vec2()) * inv,
            a: n.dot(a.to_vec2()) * inv,
            e: n.dot(e.to_vec2()) * inv,
        }
    }

    /// The row with the weights `c` of `A, P1, P2, E`.
    fn row(&self, c: [f64; 4]) -> Row {
        let n = self.n;
        (
            [c[1] * n.x, c[1] * n.y, c[2] * n.x, c[2] * n.y],
            self.across(c)[2],
        )
    }

    /// The row with the weights `c` of `A, P1, P2, E`, as an [`Across`].
    #[inline]
    fn across(&self, c: [f64; 4]) -> Across {
        [c[1], c[2], self.t - c[0] * self.a - c[3] * self.e]
    }
}

impl Fit {
    /// The fits from `a` to `e` through `samples` (their `u0`, `t` and `normal`, which the
    /// fits do not change).
    pub(super) fn new(a: Point, e: Point, samples: &[Sample]) -> Fit {
        // Along the run, loosely: fixes the control points where the normals leave them
        // free (a straight run). They keep their weight: summed once.
        let (mut lhs0, mut rhs0) = ([[0.0f64; 4]; 4], [0.0f64; 4]);
        let wa = 1.0 / (samples.len().max(1) * 100) as f64;
        for s in samples {
            let tangent = Vec2::new(-s.normal.y, s.normal.x);
            let r = row(a, e, bernstein(s.u0), tangent, s.t, ALONG_TOLERANCE);
            add_row(&mut lhs0, &mut rhs0, &r, wa);
        }
        Fit {
            along: (lhs0, rhs0),
            scaled: samples
                .iter()
                .map(|s| Scaled::new(a, e, s.normal, s.t, s.tol))
                .collect(),
            rows: Vec::with_capacity(samples.len()),
        }
    }

    /// The control points of the cubic that passes, with its polygon of `chords` chords
    /// (none when 0), nearest to the samples (at their parameters `u`) relative to their
    /// tolerances: the largest `|n · (C(u) − T)| / tol` is reduced by Lawson's reweighted
    /// least squares in `rounds` rounds (see the module documentation). `samples` are those
    /// given to [`Fit::new`], in the same order (only their `u` may have moved). Returns the
    /// control points and that largest ratio, or `None` when the system is singular.
    pub(super) fn fit(
        &mut self,
        samples: &[Sample],
        chords: u32,
        rounds: usize,
    ) -> Option<([Point; 2], f64)> {
        let per = if chords > 0 { 2 } else { 1 };
        let w0 = 1.0 / (per * samples.len()) as f64;
        let rows = &mut self.rows;
        rows.clear();
        for (s, k) in samples.iter().zip(&self.scaled) {
            let chord = if chords > 0 {
                k.across(chord_weights(s.u, chords))
            } else {
                [0.0; 3]
            };
            rows.push(SampleRows {
                row: [k.across(bernstein(s.u)), chord],
                w: [w0; 2],
                res: [0.0; 2],
            });
        }
        let (lhs0, rhs0) = self.along;
        let mut best: Option<([f64; 4], f64)> = None;
        // The factor of the last round's reweighting, applied as the next round sums.
        let mut reweight = None;
        for round in 0..rounds {
            let Sums { blocks, sides } = match (chords > 0, reweight) {
                (true, Some(inv)) => sums::<2, true>(rows, &self.scaled, inv),
                (true, None) => sums::<2, false>(rows, &self.scaled, 0.0),
                (false, Some(inv)) => sums::<1, true>(rows, &self.scaled, inv),
                (false, None) => sums::<1, false>(rows, &self.scaled, 0.0),
            };
            let (mut lhs, mut rhs) = (lhs0, rhs0);
            let [b11, b12, b22] = blocks;
            lhs[0][0] += b11[0];
            lhs[0][1] += b11[1];
            lhs[1][1] += b11[2];
            lhs[0][2] += b12[0];
            lhs[0][3] += b12[1];
            lhs[1][2] += b12[1];
            lhs[1][3] += b12[2];
            lhs[2][2] += b22[0];
            lhs[2][3] += b22[1];
            lhs[3][3] += b22[2];
            for (r, s) in rhs.iter_mut().zip(sides) {
                *r += s;
            }
            for i in 0..4 {
                for k in 0..i {
                    lhs[i][k] = lhs[k][i];
                }
            }
            let p = solve4(lhs, rhs)?;
            let Residuals { worst, total } = if chords > 0 {
                residuals::<2>(rows, &self.scaled, p)
            } else {
                residuals::<1>(rows, &self.scaled, p)
            };
            if best.is_none_or(|(_, b)| worst < b) {
                best = Some((p, worst));
            }
            // (No weights after the last round.)
            if total <= 1e-12 || round + 1 == rounds {
                break;
            }
            reweight = Some(1.0 / total);
        }
        let (p, worst) = best?;
        Some(([Point::new(p[0], p[1]), Point::new(p[2], p[3])], worst))
    }
}

/// The weighted sums of a round of [`Fit::fit`] over the rows across the run: with
/// `c = (c₁ nₓ, c₁ n_y, c₂ nₓ, c₂ n_y)`, `Σ w c cᵀ` has the blocks `Σ w cᵢ cₖ n nᵀ`
/// (`blocks`: `(i, k)` = (1, 1), (1, 2), (2, 2), each as `n nᵀ`'s `xx, xy, yy`), and
/// `Σ w c r` is `sides`.
struct Sums {
    blocks: [[f64; 3]; 3],
    sides: [f64; 4],
}

/// [`Sums`] of the first `PER` rows of each sample of `scaled` (they share its normal),
/// by their weights; with `REWEIGHT`, each weight first multiplied by its residual times
/// `inv` (Lawson's step after a round).
fn sums<const PER: usize, const REWEIGHT: bool>(
    rows: &mut [SampleRows],
    scaled: &[Scaled],
    inv: f64,
) -> Sums {
    let mut blocks = [[0.0f64; 3]; 3];
    let mut sides = [0.0f64; 4];
    for (r, k) in rows.iter_mut().zip(scaled) {
        let (mut s11, mut s12, mut s22, mut r1, mut r2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..PER {
            if REWEIGHT {
                r.w[i] *= r.res[i] * inv;
            }
            let (row, wi) = (r.row[i], r.w[i]);
            let (p, q) = (wi * row[0], wi * row[1]);
            s11 += p * row[0];
            s12 += p * row[1];
            s22 += q * row[1];
            r1 += p * row[2];
            r2 += q * row[2];
        }
        for (block, s) in blocks.iter_mut().zip([s11, s12, s22]) {
            for (b, nn) in block.iter_mut().zip(k.nn) {
                *b += s * nn;
            }
        }
        sides[0] += r1 * k.n.x;
        sides[1] += r1 * k.n.y;
        sides[2] += r2 * k.n.x;
        sides[3] += r2 * k.n.y;
    }
    Sums { blocks, sides }
}

/// The largest residual of a round of [`Fit::fit`] and the sum of the weighted ones.
struct Residuals {
    worst: f64,
    total: f64,
}

/// The residuals `|c₁ (n · P1) + c₂ (n · P2) − r|` of the first `PER` rows of each sample
/// of `scaled` at the control points `p`, kept with the rows.
fn residuals<const PER: usize>(
    rows: &mut [SampleRows],
    scaled: &[Scaled],
    p: [f64; 4],
) -> Residuals {
    let mut worst = 0.0f64;
    let mut total = 0.0;
    for (r, k) in rows.iter_mut().zip(scaled) {
        let (n1, n2) = (k.n.x * p[0] + k.n.y * p[1], k.n.x * p[2] + k.n.y * p[3]);
        for i in 0..PER {
            let row = r.row[i];
            let res = (row[0] * n1 + row[1] * n2 - row[2]).abs();
            r.res[i] = res;
            // (Not `max`, whose NaN handling lengthens the loop's dependency chain; a NaN
            // is skipped either way.)
            if res > worst {
                worst = res;
            }
            total += r.w[i] * res;
        }
    }
    Residuals { worst, total }
}

/// Tolerance (px) of the rows along the run in [`Fit`].
const ALONG_TOLERANCE: f64 = 4.0;

/// Solves `m x = r` (Gaussian elimination with partial pivoting); `None` if singular.
fn solve4(mut m: [[f64; 4]; 4], mut r: [f64; 4]) -> Option<[f64; 4]> {
    let scale = m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &k| m[i][col].abs().total_cmp(&m[k][col].abs()))?;
        if m[piv][col].abs() <= 1e-12 * scale {
            return None;
        }
        m.swap(col, piv);
        r.swap(col, piv);
        for i in col + 1..4 {
            let f = m[i][col] / m[col][col];
            for k in col..4 {
                m[i][k] -= f * m[col][k];
            }
            r[i] -= f * r[col];
        }
    }
    let mut x = [0.0; 4];
    for i in (0..4).rev() {
        let s: f64 = (i + 1..4).map(|k| m[i][k] * x[k]).sum();
        x[i] = (r[i] - s) / m[i][i];
    }
    Some(x)
}

/// The parameters of the points of `bez` nearest to the samples' cracks: from the nearest
/// of 64 points along the curve, found walking along it as the samples go (`walk`: the
/// first point nearer than both its neighbours), else from their last values; then two
/// Newton steps.
pub(super) fn reparametrize(bez: &CubicBez, samples: &mut [Sample], walk: bool) {
    const STEPS: usize = 64;
    // (On the stack, and only made for a walk.)
    let along: Option<[Point; STEPS + 1]> =
        walk.then(|| std::array::from_fn(|k| bez.eval(k as f64 / STEPS as f64)));
    // The point and its two derivatives by Horner's rule.
    let w = PowerCubic::new(bez);
    let mut at: usize = 0;
    for s in samples {
        let mut u = s.u;
        if let Some(along) = &along {
            // The samples run along the curve: from the last one's nearest point, ahead
            // while the points come nearer (at most 16 steps), else back (at most 4).
            let dist = |i: usize| (along[i] - s.t).hypot2();
            let mut d = dist(at);
            let (from, lo, hi) = (at, at.saturating_sub(4), (at + 16).min(STEPS));
            while at < hi {
                let next = dist(at + 1);
                if next >= d {
                    break;
                }
                (at, d) = (at + 1, next);
            }
            if at == from {
                while at > lo {
                    let next = dist(at - 1);
                    if next >= d {
                        break;
                    }
                    (at, d) = (at - 1, next);
                }
            }
            u = at as f64 / STEPS as f64;
        }
        for _ in 0..2 {
            let off = w.p0 + w.offset(u) - s.t.to_vec2();
            let v = w.deriv(u);
            let den = v.hypot2() + off.dot(w.second_deriv(u));
            if den > 1e-12 {
                u = (u - off.dot(v) / den).clamp(0.0, 1.0);
            }
        }
        s.u = u;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::ParamCurveDeriv;

    #[test]
    fn a_fit_through_a_cubic_finds_it() {
        // Samples on a cubic, tolerances of 1/4 px: the fit passes them all.
        let (a, p1, p2, e) = (
            Point::new(0.0, 0.0),
            Point::new(10.0, 8.0),
            Point::new(25.0, 9.0),
            Point::new(40.0, 2.0),
        );
        let bez = CubicBez::new(a, p1, p2, e);
        let samples: Vec<Sample> = (1..40)
            .map(|k| {
                let u = f64::from(k) / 40.0;
                let d = bez.deriv().eval(u).to_vec2();
                let d = d / d.hypot();
                Sample {
                    u,
                    u0: u,
                    t: bez.eval(u),
                    normal: Vec2::new(-d.y, d.x),
                    tol: 0.25,
                }
            })
            .collect();
        let ([q1, q2], worst) = Fit::new(a, e, &samples).fit(&samples, 0, 3).expect("a fit");
        assert!(worst < 1e-6, "worst {worst}");
        assert!((q1 - p1).hypot() < 1e-6 && (q2 - p2).hypot() < 1e-6);
    }
}
