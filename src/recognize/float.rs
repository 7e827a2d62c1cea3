//! The float runs of the GJK variant and their exact checks: the recognizer's first try at
//! every query, in scaled or whitened coordinates, warm-started from the last simplex.

use super::budget::{direct_solve_cost, scan_cost, Meter};
use super::conditioning::LinearMap;
use super::exact::{
    barycentric_signed, closest_direction, origin_in_hull, reduce_by_gcd, round_to_certificate,
    verify_certificate,
};
use super::gjk::{gjk, GjkOutcome, GjkParams, GjkRun};
use super::proof::Extremes;
use super::simplex::Simplex;
use super::support::{FloatSupport, Sets, Tag};
use super::Stats;
use num_rational::BigRational;

/// Float runs per query at most (separations, convergence, corrections).
const MAX_FLOAT_RUNS: usize = 8;
/// Exact corrections of a float simplex per query at most.
const MAX_CORRECTIONS: usize = 5;

pub(super) const FLOAT_PARAMS: GjkParams = GjkParams {
    eps: 1e-12,
    gap: 1e-12,
    eps_zero: 1e-24,
    max_iterations: 1000,
    first_separation: true,
};

/// Buffers of [`float_decide`], kept by the recognizer from query to query.
#[derive(Debug, Default)]
pub(super) struct FloatScratch {
    /// The simplex vertices as exact points of `D` (only the first `simplex.len()` entries
    /// are meaningful; longer is kept for reuse).
    diffs: Vec<Vec<i64>>,
    /// The direction of the support scans in lifted coordinates.
    y: Vec<f64>,
    /// The buffers of [`round_to_certificate`].
    roundings: [Vec<i64>; 2],
}

/// A decision of the float runs, already checked exactly.
pub(super) enum FloatAnswer {
    /// A verified integer certificate.
    Described(Vec<i64>, Extremes),
    /// Tags of points of `D` and exact weights with `Σ λ d = 0`.
    NotDescribed(Vec<Tag>, Vec<BigRational>),
}

/// Float runs of the GJK variant on `map·D`, warm-started from `simplex`, each answer checked
/// exactly; `None` when none could be proven.
///
/// A float run that sees the origin inside a simplex the exact check puts it outside of drops
/// the vertex with the most negative exact barycentric weight and goes on (a few times).
/// `scratch` holds the runs' buffers.
// The recognizer's fields, borrowed one by one (the closure in `solve` holds the others).
#[allow(clippy::too_many_arguments)]
pub(super) fn float_decide(
    sets: Sets<'_>,
    map: &LinearMap,
    simplex: &mut Simplex<f64>,
    max_abs: &[i64],
    stats: &mut Stats,
    thorough: bool,
    scratch: &mut FloatScratch,
    meter: &mut Meter,
) -> Option<FloatAnswer> {
    let FloatScratch {
        diffs,
        y,
        roundings,
    } = scratch;
    // The exact points of D at the simplex's vertices, into `diffs` (allocations reused).
    let exact_points = |simplex: &Simplex<f64>, diffs: &mut Vec<Vec<i64>>| -> usize {
        let k = simplex.len();
        if diffs.len() < k {
            diffs.resize_with(k, Vec::new);
        }
        for (d, v) in diffs.iter_mut().zip(simplex.vertices()) {
            sets.difference_into(&v.tag, d);
        }
        k
    };
    let n = map.dim();
    let mut support = FloatSupport { sets, map, y };
    // Warm start: rebuild the kept vertices in the current coordinates.
    simplex.rebuild(|tag, point| support.point_into(tag, point));
    let mut params = FLOAT_PARAMS;
    let mut converging = false;
    let mut corrections = 0;
    // A float iteration: one support scan and a small float solve.
    let per_iteration = scan_cost(&sets) + (n as u64 + 1).pow(3);
    let solve_cost = direct_solve_cost(n);
    for _ in 0..MAX_FLOAT_RUNS {
        if meter.exhausted() {
            return None;
        }
        let (cap, limited) = meter.iterations(per_iteration, FLOAT_PARAMS.max_iterations);
        params.max_iterations = cap;
        let GjkRun {
            outcome,
            iterations,
        } = gjk(&mut support, simplex, &params);
        stats.float_iterations += iterations as u64;
        meter.charge(iterations as u64 * per_iteration);
        if limited && iterations >= cap {
            meter.exhaust();
            if matches!(outcome, GjkOutcome::Stalled) {
                return None;
            }
        }
        match outcome {
            GjkOutcome::Separated {
                direction,
                margin,
                converged,
            } => {
                // (Into the support's buffer: the run is over.)
                map.pull_back_into(&direction, support.y);
                simplex.recycle(direction);
                let k = exact_points(simplex, diffs);
                let tight = &diffs[..k];
                if let Some((a, e)) =
                    round_to_certificate(&sets, support.y, margin, max_abs, tight, meter, roundings)
                {
                    return Some(FloatAnswer::Described(a, e));
                }
                if converged || converging {
                    return None;
                }
                // Converge to the largest-margin direction, then round again.
                params.first_separation = false;
                converging = true;
            }
            GjkOutcome::Stalled if iterations == 0 => {
                // The warm-start simplex is degenerate in these coordinates: start afresh.
                simplex.clear();
            }
            GjkOutcome::Stalled if !thorough => return None,
            GjkOutcome::OriginInside | GjkOutcome::Stalled => {
                if simplex.len() > n + 1 {
                    return None;
                }
                let k = exact_points(simplex, diffs);
                let points = &diffs[..k];
                if !meter.try_charge(solve_cost) {
                    return None;
                }
                match barycentric_signed(points) {
                    Some(w) if w.iter().all(|v| !num_traits::Signed::is_negative(v)) => {
                        return Some(FloatAnswer::NotDescribed(simplex.tags(), w));
                    }
                    Some(w) if corrections < MAX_CORRECTIONS && simplex.len() > 1 => {
                        corrections += 1;
                        let worst = (0..w.len()).min_by(|&i, &j| w[i].cmp(&w[j])).unwrap_or(0);
                        simplex.drop_vertex(worst);
                    }
                    _ => {
                        // Decide on the simplex exactly: the origin in its hull is a witness;
                        // otherwise its exact closest point may separate all of D.
                        if let Some((used, weights)) = origin_in_hull(points, meter) {
                            let tags = used.iter().map(|&i| simplex.vertices()[i].tag).collect();
                            return Some(FloatAnswer::NotDescribed(tags, weights));
                        }
                        let a = closest_direction(points, meter)?;
                        meter.charge(scan_cost(&sets));
                        let e = verify_certificate(&sets, &a)?;
                        let (a, e) = reduce_by_gcd(a, e);
                        return Some(FloatAnswer::Described(a, e));
                    }
                }
            }
            GjkOutcome::Empty => return None,
        }
    }
    None
}

/// Powers of two bringing every lifted coordinate near magnitude one (`max_abs[i]` bounds
/// `|F_i|`): separation is invariant under this diagonal map, and the float solves are far
/// better conditioned.
pub(super) fn power_of_two_scale(max_abs: &[i64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(max_abs.len());
    power_of_two_scale_into(max_abs, &mut out);
    out
}

/// [`power_of_two_scale`] into `out`'s buffer.
pub(super) fn power_of_two_scale_into(max_abs: &[i64], out: &mut Vec<f64>) {
    out.clear();
    out.extend(max_abs.iter().map(|&m| scale_for(m)));
}

/// `2^−⌈log₂ m⌉` (one over the least power of two at least `m`) for `m > 0`, else 1: the
/// scale of a coordinate of magnitude at most `m`.
///
/// Below `2^48` by the integer's bits: `k = ⌈log₂ m⌉` is the bit length of `m − 1`, and
/// `log₂` in `f64` gives the same ceiling there. For a power of two it is exact; otherwise
/// `m = 2^(k−1)(1 + x)` with `2^(1−k) ≤ x < 1`, and `log₂ m − (k − 1) = log₂(1 + x)`, about
/// `1.44 x` where `x` is small: more than a unit in the last place of `k − 1` (`2^−47` for
/// `32 ≤ k − 1 < 48`, less below), so a logarithm within an ulp stays above `k − 1` and its
/// ceiling is `k` (the test checks every `m` up to `2^20` and those around each power of two
/// up to `2^50`, bit for bit). Above, as `f64` computes it.
fn scale_for(m: i64) -> f64 {
    if m <= 0 {
        1.0
    } else if m < 1 << 48 {
        let k = 64 - (m - 1).leading_zeros();
        f64::from_bits(u64::from(1023 - k) << 52)
    } else {
        (-(m as f64).log2().ceil()).exp2()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_two_by_bits_are_those_of_log2() {
        // Every magnitude up to 2^20, and around every power of two up to 2^48 and past.
        let by_log2 = |m: i64| (-(m as f64).log2().ceil()).exp2();
        let mut ms: Vec<i64> = (1..=1 << 20).collect();
        for k in 20..=50 {
            for d in -3i64..=3 {
                ms.push((1i64 << k) + d);
            }
        }
        for m in ms {
            assert_eq!(scale_for(m).to_bits(), by_log2(m).to_bits(), "m = {m}");
        }
        assert_eq!(scale_for(0), 1.0);
        assert_eq!(scale_for(-5), 1.0);
    }
}
