//! The GJK variant (the paper's Algorithm 1): is the origin outside `conv(D)`?
//!
//! The steps carry the paper's names:
//!
//! ```text
//! x ← pick_point(D)                      a point of D, or the closest point of the
//!                                        warm-start simplex            [`pick_point`]
//! loop
//!     if x = 0                          → the origin is in conv(simplex): not separable
//!     s ← support_point(D, −x)           argmin_{d∈D} x·d       [`SupportMap::support_point`]
//!     if x·s > 0                        → x separates: every d ∈ D has x·d ≥ x·s > 0
//!     if ‖x‖² − x·s ≤ ε‖x‖²             → x is already the closest point (numerically): stop
//!     simplex ← add_vertex(simplex, s)                             [`Simplex::add_vertex`]
//!     x ← closest_point_to_origin(simplex)             [`Simplex::closest_point_to_origin`]
//!     simplex ← remove_vertices(simplex)    the vertices of weight 0 [`Simplex::remove_vertices`]
//! ```
//!
//! In exact arithmetic every iteration strictly decreases `‖x‖` and no simplex repeats, so
//! the loop ends after finitely many steps (Wolfe 1976); in `f64` an iteration cap and the
//! "no progress" tests stop it, and the caller checks every answer exactly.

use super::scalar::Scalar;
use super::simplex::Simplex;
use super::support::SupportMap;

/// How a run of the GJK variant ended.
#[derive(Clone, Debug)]
pub(crate) enum GjkOutcome<T> {
    /// `x·d > 0` for every `d ∈ D` (as computed): `x` is a separating direction.
    Separated {
        /// The direction `x` (the current closest point).
        direction: Vec<T>,
        /// `min_{d∈D} x·d` as computed.
        margin: T,
        /// True when `x` is (numerically) the closest point of `conv(D)`: the largest margin.
        converged: bool,
    },
    /// The closest point is the origin: the simplex holds a witness.
    OriginInside,
    /// No progress or the iteration cap: undecided in this arithmetic.
    Stalled,
    /// `D` is empty: every direction separates.
    Empty,
}

/// Settings of a run.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GjkParams {
    /// Relative tolerance of the minor cycle's weights and solves (`f64` runs only).
    pub eps: f64,
    /// Relative gap `‖x‖² − x·s` below which the run has converged (`f64` runs only): a
    /// largest-margin run may stop well before the rounding tolerance `eps`.
    pub gap: f64,
    /// Tolerance of the test `x = 0`, relative to the largest squared vertex norm.
    pub eps_zero: f64,
    /// Iteration cap.
    pub max_iterations: usize,
    /// Stop at the first separating direction instead of the largest-margin one.
    pub first_separation: bool,
}

fn dot<T: Scalar>(a: &[T], b: &[T]) -> T {
    T::dot(a, b)
}

/// A run of [`gjk`]: how it ended, after how many iterations.
#[derive(Clone, Debug)]
pub(crate) struct GjkRun<T> {
    pub(crate) outcome: GjkOutcome<T>,
    pub(crate) iterations: usize,
}

fn ended<T>(outcome: GjkOutcome<T>, iterations: usize) -> GjkRun<T> {
    GjkRun {
        outcome,
        iterations,
    }
}

/// Runs the GJK variant from the given simplex (empty: start from any point of `D`).
pub(crate) fn gjk<T: Scalar, S: SupportMap<T>>(
    support: &mut S,
    simplex: &mut Simplex<T>,
    params: &GjkParams,
) -> GjkRun<T> {
    let dim = support.dim();
    if let Err(outcome) = pick_point(support, simplex, params.eps) {
        return ended(outcome, 0);
    }
    let mut previous = None::<T>;
    for iteration in 1..=params.max_iterations {
        let Some(x) = simplex.point(dim) else {
            return ended(GjkOutcome::Stalled, iteration);
        };
        debug_assert!(x.iter().all(Scalar::is_finite), "non-finite GJK point");
        if !x.iter().all(Scalar::is_finite) {
            return ended(GjkOutcome::Stalled, iteration);
        }
        let xx = dot(&x, &x);
        let max_w = simplex
            .vertices()
            .iter()
            .map(|v| dot(&v.point, &v.point))
            .fold(T::zero(), |m, n| if n > m { n } else { m });
        // (The buffers of points that end here go back to the simplex for the next run.)
        if xx <= T::tolerance(&max_w, params.eps_zero) {
            simplex.recycle(x);
            return ended(GjkOutcome::OriginInside, iteration);
        }
        // Every iteration must decrease ‖x‖² strictly; otherwise rounding is cycling.
        if previous.as_ref().is_some_and(|p| xx >= *p) {
            simplex.recycle(x);
            return ended(GjkOutcome::Stalled, iteration);
        }
        previous = Some(xx.clone());
        let buf = simplex.buffer();
        let Some(s) = support.support_point(&x, buf) else {
            simplex.recycle(x);
            return ended(GjkOutcome::Empty, iteration);
        };
        let xs = dot(&x, &s.point);
        let gap = xx.clone() - xs.clone();
        // A support point equal to a vertex (another inlier–outlier pair with the same
        // difference) brings nothing new: in exact arithmetic its gap is zero, and pushing it
        // would make the simplex affinely dependent.
        let converged = gap <= T::tolerance(&xx, params.gap) || simplex.contains_point(&s.point);
        if xs > T::zero() && (params.first_separation || converged) {
            simplex.recycle(s.point);
            return ended(
                GjkOutcome::Separated {
                    direction: x,
                    margin: xs,
                    converged,
                },
                iteration,
            );
        }
        if converged || simplex.contains(&s.tag) {
            // x is (numerically) the closest point but does not separate: x ≈ 0 in truth,
            // or rounding hides progress.
            simplex.recycle(x);
            simplex.recycle(s.point);
            return ended(GjkOutcome::Stalled, iteration);
        }
        simplex.add_vertex(s);
        simplex.recycle(x);
        // closest_point_to_origin runs remove_vertices on the vertices it no longer needs.
        if simplex.len() > dim + 1 || simplex.closest_point_to_origin(params.eps).is_err() {
            return ended(GjkOutcome::Stalled, iteration);
        }
        // n+1 affinely independent vertices, all with positive weight: the affine hull is the
        // whole space, so the closest point is the origin itself (in exact arithmetic; in f64
        // the witness check decides).
        if simplex.len() == dim + 1 {
            return ended(GjkOutcome::OriginInside, iteration);
        }
    }
    ended(GjkOutcome::Stalled, params.max_iterations)
}

/// pickPoint: the first `x`. An empty simplex starts from a point of `D` (the support
/// point in any direction); a warm-start simplex from its own closest point to the origin.
/// `Err` is the run's outcome when there is no start: `Empty` for an empty `D`, `Stalled`
/// for a warm-start simplex that is (numerically) affinely dependent.
fn pick_point<T: Scalar, S: SupportMap<T>>(
    support: &mut S,
    simplex: &mut Simplex<T>,
    eps: f64,
) -> Result<(), GjkOutcome<T>> {
    if simplex.is_empty() {
        let mut any = simplex.buffer();
        any.clear();
        any.resize(support.dim(), T::zero());
        let buf = simplex.buffer();
        let v = support.support_point(&any, buf);
        simplex.recycle(any);
        match v {
            Some(v) => simplex.reset_to(v),
            None => return Err(GjkOutcome::Empty),
        }
    } else if simplex.closest_point_to_origin(eps).is_err() {
        return Err(GjkOutcome::Stalled);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recognize::support::ListSupport;
    use proptest::prelude::*;

    fn norm2(x: &[f64]) -> f64 {
        x.iter().map(|v| v * v).sum()
    }

    /// Brute force over all faces: for every subset of the points, the nearest point of its
    /// affine hull (normal equations, own elimination); those with non-negative weights are
    /// points of the hull, and the closest of them is the answer.
    fn brute_closest(points: &[Vec<f64>]) -> f64 {
        let k = points.len();
        let mut best = f64::INFINITY;
        for mask in 1u32..(1 << k) {
            let sub: Vec<&Vec<f64>> = (0..k)
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| &points[i])
                .collect();
            let m = sub.len();
            // Bordered system [G 1; 1ᵀ 0] [μ; ρ] = [0; 1].
            let mut a = vec![vec![0.0; m + 2]; m + 1];
            for i in 0..m {
                for j in 0..m {
                    a[i][j] = sub[i].iter().zip(sub[j]).map(|(x, y)| x * y).sum();
                }
                a[i][m] = 1.0;
                a[m][i] = 1.0;
            }
            a[m][m + 1] = 1.0;
            let n = m + 1;
            let mut ok = true;
            for c in 0..n {
                let p = (c..n)
                    .max_by(|&x, &y| a[x][c].abs().partial_cmp(&a[y][c].abs()).unwrap())
                    .unwrap();
                if a[p][c].abs() < 1e-9 {
                    ok = false;
                    break;
                }
                a.swap(c, p);
                for r in 0..n {
                    if r != c {
                        let f = a[r][c] / a[c][c];
                        for cc in c..=n {
                            a[r][cc] -= f * a[c][cc];
                        }
                    }
                }
            }
            if !ok {
                continue;
            }
            let mu: Vec<f64> = (0..m).map(|i| a[i][n] / a[i][i]).collect();
            if mu.iter().any(|&w| w < -1e-12) {
                continue;
            }
            let dim = points[0].len();
            let x: Vec<f64> = (0..dim)
                .map(|d| sub.iter().zip(&mu).map(|(p, w)| p[d] * w).sum())
                .collect();
            best = best.min(norm2(&x).sqrt());
        }
        best
    }

    /// The closest point of a simplex (its vertex list) to the origin: the GJK variant run to
    /// convergence on the explicit vertex list.
    fn closest(points: &[Vec<f64>]) -> f64 {
        let mut list = ListSupport {
            points: points.to_vec(),
        };
        let mut simplex = Simplex::default();
        let params = GjkParams {
            eps: 1e-12,
            gap: 1e-12,
            eps_zero: 1e-24,
            max_iterations: 100,
            first_separation: false,
        };
        match gjk(&mut list, &mut simplex, &params).outcome {
            GjkOutcome::Separated { direction, .. } => norm2(&direction).sqrt(),
            GjkOutcome::OriginInside => 0.0,
            GjkOutcome::Stalled => norm2(&simplex.point(points[0].len()).unwrap()).sqrt(),
            GjkOutcome::Empty => f64::NAN,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]
        #[test]
        fn closest_point_of_simplex_matches_brute_force(
            dim in 1usize..=6,
            raw in proptest::collection::vec(proptest::collection::vec(-10i32..=10, 6), 1..=7),
        ) {
            // Up to dim+1 random points in dimension dim, degenerate sets included.
            let points: Vec<Vec<f64>> = raw
                .iter()
                .take(dim + 1)
                .map(|p| p[..dim].iter().map(|&v| v as f64).collect())
                .collect();
            let got = closest(&points);
            let want = brute_closest(&points);
            prop_assert!((got - want).abs() <= 1e-4 * (1.0 + want),
                "dim {dim}: GJK {got}, brute force {want}, points {points:?}");
        }
    }
}
