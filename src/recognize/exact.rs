//! Exact checks: certificates in integers, witnesses in rationals, and the exact fallback.
//!
//! Every answer of the recognizer passes through here:
//! * "described" only with an integer vector `a` for which `max_{S⁻} a·F < min_S a·F` and
//!   `max_S a·F < min_{S⁺} a·F` hold in `i128` arithmetic (every product and sum is
//!   overflow-checked: an overflow rejects the candidate, it never wraps);
//! * "not described" only with points `d_1, …, d_k` of `D` and rational weights
//!   `λ_i ≥ 0`, `Σ λ_i = 1`, `Σ λ_i d_i = 0`, computed in exact rational arithmetic.

use super::bareiss;
use super::budget::{direct_solve_cost, rational_solve_cost, scan_cost, Meter, EXACT_SCAN_FACTOR};
use super::gjk::{gjk, GjkOutcome, GjkParams, GjkRun};
use super::proof::Extremes;
use super::scalar::Scalar;
use super::simplex::Simplex;
use super::support::{integer_direction, ExactSupport, ListSupport, Sets, SupportMap, Tag};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{PrimInt, Signed, ToPrimitive, Zero};

/// `a·f` in `i128`, or `None` on overflow.
#[inline]
pub(crate) fn dot_i128(a: &[i64], f: &[i64]) -> Option<i128> {
    let mut s: i128 = 0;
    for (&x, &y) in a.iter().zip(f) {
        s = s.checked_add((x as i128).checked_mul(y as i128)?)?;
    }
    Some(s)
}

/// Checks the integer direction `a` exactly on the three sets. Returns the extremes when it
/// separates, `None` when it does not (or on overflow); stops at the first violation.
pub(crate) fn verify_certificate(sets: &Sets<'_>, a: &[i64]) -> Option<Extremes> {
    let mut rows = sets.inliers.lifted_rows();
    let first = dot_i128(a, rows.next()?)?;
    let (mut lower, mut upper) = (first, first);
    for row in rows {
        let v = dot_i128(a, row)?;
        lower = lower.min(v);
        upper = upper.max(v);
    }
    let mut above = None::<i128>;
    for row in sets.upper.lifted_rows() {
        let v = dot_i128(a, row)?;
        if v <= upper {
            return None;
        }
        above = Some(above.map_or(v, |m| m.min(v)));
    }
    let mut below = None::<i128>;
    for row in sets.lower.lifted_rows() {
        let v = dot_i128(a, row)?;
        if v >= lower {
            return None;
        }
        below = Some(below.map_or(v, |m| m.max(v)));
    }
    Some(Extremes {
        lower,
        upper,
        above,
        below,
    })
}

/// Rounds the float direction `y` (unscaled coordinates) to integer directions at growing
/// scales and returns the first one that verifies exactly.
///
/// `margin` is the computed `min_{d∈D} y·d > 0` and `max_abs[i]` bounds `|F_i|` over the
/// sets: rounding `t·y` moves each `a·d` by at most `Σ_i max_abs[i]`, so a scale
/// `t > Σ max_abs / margin` is guaranteed to work when the float margin is right; the
/// ladder starts a few powers of two below that to find smaller integers. `bufs` are the
/// roundings' buffers (the caller's, kept from call to call; the certificate returned is
/// one of them, moved out).
pub(crate) fn round_to_certificate(
    sets: &Sets<'_>,
    y: &[f64],
    margin: f64,
    max_abs: &[i64],
    tight: &[Vec<i64>],
    meter: &mut Meter,
    bufs: &mut [Vec<i64>; 2],
) -> Option<(Vec<i64>, Extremes)> {
    let ymax = y.iter().fold(0.0f64, |m, v| m.max(f64::abs(*v)));
    if ymax.is_nan() || ymax <= 0.0 || !ymax.is_finite() || margin.is_nan() || margin <= 0.0 {
        return None;
    }
    let err: f64 = max_abs.iter().map(|&m| m as f64).sum::<f64>().max(1.0);
    // Scale at which the largest coefficient is 2^k.
    let needed = (err / margin * ymax).log2().ceil();
    let k_hi = (needed + 3.0).clamp(0.0, 61.0) as i32;
    let k_lo = (needed - 6.0).clamp(0.0, 61.0) as i32;
    // Two buffers, swapped: the rounding at this scale and the last one tried.
    let [a, last] = bufs;
    let mut tried = false;
    for k in k_lo..=k_hi {
        let t = (k as f64).exp2() / ymax;
        a.clear();
        a.extend(y.iter().map(|v| (v * t).round() as i64));
        if a.iter().all(|&v| v == 0) || (tried && last == a) {
            continue;
        }
        // Cheap filter first: the tightest points of D (the simplex) must be positive.
        let plausible = tight.iter().all(|d| dot_i128(a, d).is_some_and(|v| v > 0));
        if plausible {
            meter.charge(scan_cost(sets));
            if let Some(e) = verify_certificate(sets, a) {
                return Some(reduce_by_gcd(std::mem::take(a), e));
            }
        }
        std::mem::swap(a, last);
        tried = true;
    }
    None
}

/// Divides a verified certificate by the gcd of its coefficients (every value `a·F` is a
/// multiple of it, so the extremes divide exactly).
pub(crate) fn reduce_by_gcd(a: Vec<i64>, e: Extremes) -> (Vec<i64>, Extremes) {
    let g = a.iter().fold(0i64, |g, &v| g.gcd(&v));
    if g <= 1 {
        return (a, e);
    }
    (
        a.into_iter().map(|v| v / g).collect(),
        e.divided_by(g as i128),
    )
}

/// The barycentric coordinates of the origin with respect to `points`, when the points are
/// affinely independent, the origin lies in their affine hull and every coordinate is
/// non-negative: `λ ≥ 0`, `Σλ = 1`, `Σ λ_i p_i = 0`, exactly.
///
/// One fraction-free (Bareiss) elimination of the `(n+1) × (k+1)` system
/// `[p_1 … p_k; 1 … 1] λ = [0; 1]` in big integers, then a rational back substitution.
pub(crate) fn barycentric_exact(points: &[Vec<i64>]) -> Option<Vec<BigRational>> {
    barycentric_signed(points).filter(|x| x.iter().all(|v| !v.is_negative()))
}

/// The barycentric coordinates of the origin with respect to affinely independent `points`
/// whose affine hull holds it, whatever their signs (a negative one names a vertex to drop).
/// Returns `None` if the points are affinely dependent or the origin is off their hull.
///
/// Fraction-free throughout: Bareiss elimination of `[p_1 … p_k; 1 … 1] λ = [0; 1]`, then
/// the back substitution of the integers `X_r = λ_r·D` (`D` the last pivot, the determinant
/// of the eliminated `k × k` system; `m_rr X_r = D m_rk − Σ_{c>r} m_rc X_c` divides exactly),
/// and one reduction per weight `X_r / D`. In overflow-checked `i64` first (its divisions
/// are the processor's, where `i128`'s are library calls), then `i128`, then big integers,
/// each when the one before overflows: the same exact integers either way.
pub(crate) fn barycentric_signed(points: &[Vec<i64>]) -> Option<Vec<BigRational>> {
    barycentric_fixed::<i64>(points)
        .or_else(|Overflow| barycentric_fixed::<i128>(points))
        .unwrap_or_else(|Overflow| barycentric_big(points))
}

/// A fixed-width integer operation overflowed.
struct Overflow;

/// [`barycentric_signed`] in the fixed-width integers `T` (`i64`, `i128`), every operation
/// checked.
fn barycentric_fixed<T>(points: &[Vec<i64>]) -> Result<Option<Vec<BigRational>>, Overflow>
where
    T: PrimInt + Signed + Integer + From<i64> + Into<BigInt>,
{
    let k = points.len();
    let Some(n) = points.first().map(Vec::len) else {
        return Ok(None);
    };
    let rows = n + 1;
    let mut m: Vec<T> = Vec::with_capacity(rows * (k + 1));
    for r in 0..rows {
        for c in 0..k {
            m.push(if r < n {
                <T as From<i64>>::from(points[c][r])
            } else {
                T::one()
            });
        }
        m.push(if r == n { T::one() } else { T::zero() });
    }
    let w = k + 1;
    let mut prev = T::one();
    for c in 0..k {
        let Some(p) = (c..rows).find(|&r| !m[r * w + c].is_zero()) else {
            return Ok(None); // dependent columns
        };
        if p != c {
            for cc in 0..w {
                m.swap(c * w + cc, p * w + cc);
            }
        }
        let pivot = m[c * w + c];
        for r in c + 1..rows {
            let lead = m[r * w + c];
            for cc in c + 1..w {
                let v = pivot
                    .checked_mul(&m[r * w + cc])
                    .and_then(|x| x.checked_sub(&lead.checked_mul(&m[c * w + cc])?))
                    .and_then(|x| x.checked_div(&prev))
                    .ok_or(Overflow)?;
                m[r * w + cc] = v;
            }
            m[r * w + c] = T::zero();
        }
        prev = pivot;
    }
    if (k..rows).any(|r| !m[r * w + k].is_zero()) {
        return Ok(None);
    }
    let d = m[(k - 1) * w + (k - 1)];
    let mut x = vec![T::zero(); k];
    for r in (0..k).rev() {
        let mut s = d.checked_mul(&m[r * w + k]).ok_or(Overflow)?;
        for c in r + 1..k {
            s = m[r * w + c]
                .checked_mul(&x[c])
                .and_then(|t| s.checked_sub(&t))
                .ok_or(Overflow)?;
        }
        x[r] = s.checked_div(&m[r * w + r]).ok_or(Overflow)?;
    }
    // (Negations below need values above the type's least.)
    if d == T::min_value() || x.contains(&T::min_value()) {
        return Err(Overflow);
    }
    Ok(Some(
        x.into_iter()
            .map(|v| {
                let g = v.gcd(&d);
                let (num, den) = if d.is_negative() {
                    (-v / g, -d / g)
                } else {
                    (v / g, d / g)
                };
                BigRational::new_raw(num.into(), den.into())
            })
            .collect(),
    ))
}

/// [`barycentric_signed`] in big integers.
fn barycentric_big(points: &[Vec<i64>]) -> Option<Vec<BigRational>> {
    let k = points.len();
    let n = points.first()?.len();
    let mut m: Vec<Vec<BigInt>> = (0..=n)
        .map(|r| {
            let mut row: Vec<BigInt> = (0..k)
                .map(|c| BigInt::from(if r < n { points[c][r] } else { 1 }))
                .collect();
            row.push(BigInt::from(u8::from(r == n)));
            row
        })
        .collect();
    let (x, d) = bareiss::solve(&mut m, k)?;
    Some(
        x.into_iter()
            .map(|v| BigRational::new(v, d.clone()))
            .collect(),
    )
}

/// Decides exactly whether the origin lies in the convex hull of `points`; returns the
/// points used and their weights (`λ ≥ 0`, `Σλ = 1`, `Σ λ d = 0`) when it does.
pub(crate) fn origin_in_hull(
    points: &[Vec<i64>],
    meter: &mut Meter,
) -> Option<(Vec<usize>, Vec<BigRational>)> {
    if points.is_empty() {
        return None;
    }
    // The float simplex is usually exactly right: one direct solve.
    if !meter.try_charge(direct_solve_cost(points[0].len())) {
        return None;
    }
    if let Some(w) = barycentric_exact(points) {
        return Some(((0..points.len()).collect(), w));
    }
    let mut list = rational_list(points);
    let mut simplex = Simplex::default();
    let params = metered_params(exact_params(list.dim()), list.dim(), 0, meter);
    let GjkRun {
        outcome,
        iterations,
    } = gjk(&mut list, &mut simplex, &params);
    charge_exact(meter, &params, iterations, list.dim(), 0);
    match outcome {
        GjkOutcome::OriginInside => {
            let (tags, weights) = simplex.into_tags_and_weights();
            Some((tags.iter().map(|t| t.inlier as usize).collect(), weights))
        }
        _ => None,
    }
}

/// An explicit list of integer points as exact rationals, for the exact GJK.
fn rational_list(points: &[Vec<i64>]) -> ListSupport<BigRational> {
    ListSupport {
        points: points
            .iter()
            .map(|p| p.iter().map(|&v| BigRational::from_i64(v)).collect())
            .collect(),
    }
}

/// The closest point of `conv(points)` to the origin, exactly, as an integer direction
/// (`None` if it is the origin, or too large for `i64`). A float run that stalls near a
/// face of `D` often has the right face: this direction then separates all of `D`.
pub(crate) fn closest_direction(points: &[Vec<i64>], meter: &mut Meter) -> Option<Vec<i64>> {
    let mut list = rational_list(points);
    let mut simplex = Simplex::default();
    let params = GjkParams {
        first_separation: false,
        ..exact_params(list.dim())
    };
    let params = metered_params(params, list.dim(), 0, meter);
    let GjkRun {
        outcome,
        iterations,
    } = gjk(&mut list, &mut simplex, &params);
    charge_exact(meter, &params, iterations, list.dim(), 0);
    let GjkOutcome::Separated { direction, .. } = outcome else {
        return None;
    };
    let x = integer_direction(&direction);
    let g = x.iter().fold(BigInt::zero(), |g, v| g.gcd(v));
    if g.is_zero() {
        return None;
    }
    x.iter().map(|v| (v / &g).to_i64()).collect()
}

/// Units of one exact GJK iteration in dimension `n` whose support scans cost `scan` units
/// in floating point.
fn exact_iteration_cost(n: usize, scan: u64) -> u64 {
    rational_solve_cost(n).saturating_add(scan.saturating_mul(EXACT_SCAN_FACTOR))
}

/// `params` with the iteration cap lowered to what the meter still affords.
fn metered_params(params: GjkParams, n: usize, scan: u64, meter: &Meter) -> GjkParams {
    let (cap, _) = meter.iterations(exact_iteration_cost(n, scan), params.max_iterations);
    GjkParams {
        max_iterations: cap,
        ..params
    }
}

/// Charges an exact run; marks the meter exhausted when the run used up a cap the meter
/// lowered (the guard cap of `exact_params` is not a budget matter).
fn charge_exact(meter: &mut Meter, params: &GjkParams, iterations: usize, n: usize, scan: u64) {
    meter.charge((iterations as u64).saturating_mul(exact_iteration_cost(n, scan)));
    if iterations >= params.max_iterations && params.max_iterations < exact_params(n).max_iterations
    {
        meter.exhaust();
    }
}

fn exact_params(dim: usize) -> GjkParams {
    GjkParams {
        eps: 0.0,
        gap: 0.0,
        eps_zero: 0.0,
        // Finite in exact arithmetic (Wolfe); the cap is a guard, far above what is met.
        max_iterations: 10_000 + 1_000 * dim,
        first_separation: true,
    }
}

/// The exact decision of the fallback.
pub(crate) enum ExactDecision {
    /// A verified integer certificate.
    Described(Vec<i64>, Extremes),
    /// Tags of points of `D` and weights with `Σ λ d = 0`.
    NotDescribed(Vec<Tag>, Vec<BigRational>),
    /// The exact run hit its cap, or its direction does not fit in `i64`.
    Undecided,
    /// The exact run stopped at the work limit.
    OverBudget,
}

/// The exact fallback: the same GJK variant in rational arithmetic, warm-started from the
/// tags of the float run's simplex.
pub(crate) fn decide_exactly(
    sets: &Sets<'_>,
    warm: &[Tag],
    max_abs: &[i64],
    meter: &mut Meter,
) -> ExactDecision {
    let mut support = ExactSupport { sets: *sets };
    let n = max_abs.len();
    let scan = scan_cost(sets);
    let mut simplex: Simplex<BigRational> = Simplex::default();
    // Warm start from the float run's whole simplex (uniform weights, reduced exactly); if
    // its vertices are affinely dependent in exact arithmetic, from its first vertex.
    if !warm.is_empty() {
        simplex = Simplex::uniform(warm.iter().map(|t| support.vertex(t)).collect());
        if !meter.try_charge(rational_solve_cost(n)) {
            return ExactDecision::OverBudget;
        }
        if simplex.closest_point_to_origin(0.0).is_err() {
            simplex.reset_to(support.vertex(&warm[0]));
        }
    }
    let params = metered_params(exact_params(n), n, scan, meter);
    let GjkRun {
        outcome,
        iterations,
    } = gjk(&mut support, &mut simplex, &params);
    charge_exact(meter, &params, iterations, n, scan);
    if matches!(outcome, GjkOutcome::Stalled) && meter.exhausted() {
        return ExactDecision::OverBudget;
    }
    match outcome {
        GjkOutcome::Separated { direction, .. } => {
            let x = integer_direction(&direction);
            certificate_from_big(sets, &x, meter)
        }
        GjkOutcome::OriginInside => {
            let (tags, weights) = simplex.into_tags_and_weights();
            ExactDecision::NotDescribed(tags, weights)
        }
        GjkOutcome::Empty => ExactDecision::Described(vec![0; max_abs.len()], Extremes::default()),
        GjkOutcome::Stalled => ExactDecision::Undecided,
    }
}

/// An `i64` certificate from an exact separating direction: the direction itself divided by
/// its gcd when it fits, otherwise roundings of it at growing precision.
fn certificate_from_big(sets: &Sets<'_>, x: &[BigInt], meter: &mut Meter) -> ExactDecision {
    let g = x.iter().fold(BigInt::zero(), |g, v| g.gcd(v));
    let reduced: Vec<BigInt> = if g.is_zero() {
        x.to_vec()
    } else {
        x.iter().map(|v| v / &g).collect()
    };
    if let Some(a) = reduced
        .iter()
        .map(|v| v.to_i64())
        .collect::<Option<Vec<i64>>>()
    {
        meter.charge(scan_cost(sets));
        if let Some(e) = verify_certificate(sets, &a) {
            let (a, e) = reduce_by_gcd(a, e);
            return ExactDecision::Described(a, e);
        }
    }
    // Too large for i64 (or overflowing i128 products): round a scaled-down copy.
    let bits = reduced.iter().map(|v| v.abs().bits()).max().unwrap_or(0);
    for keep in (8..=60u64).rev().step_by(4) {
        let shift = bits.saturating_sub(keep);
        let a: Vec<i64> = reduced
            .iter()
            .map(|v| {
                let q: BigRational =
                    BigRational::new(v.clone(), BigInt::from(1u8) << shift as usize);
                q.round().to_integer().to_i64().unwrap_or(0)
            })
            .collect();
        meter.charge(scan_cost(sets));
        if let Some(e) = verify_certificate(sets, &a) {
            let (a, e) = reduce_by_gcd(a, e);
            return ExactDecision::Described(a, e);
        }
    }
    ExactDecision::Undecided
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// `Σλ = 1` and `Σ λ_i p_i = 0`, exactly.
    fn solves(points: &[Vec<i64>], w: &[BigRational]) -> bool {
        let one = BigRational::from_integer(BigInt::from(1));
        let sum = w.iter().fold(<BigRational as Zero>::zero(), |s, x| s + x);
        let n = points[0].len();
        sum == one
            && (0..n).all(|r| {
                w.iter()
                    .zip(points)
                    .fold(<BigRational as Zero>::zero(), |s, (x, p)| {
                        s + x * BigInt::from(p[r])
                    })
                    .is_zero()
            })
    }

    proptest! {
        /// The `i64` and `i128` paths and the big-integer path give the same answer, and it
        /// solves the system; some instances overflow the fixed widths (large coordinates)
        /// and take the big path.
        #[test]
        fn barycentric_paths_agree(
            n in 1usize..7,
            k in 1usize..8,
            big in any::<bool>(),
            seed in any::<u64>(),
        ) {
            let mut s = seed | 1;
            let mut next = move || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                s
            };
            let range: i64 = if big { 1 << 40 } else { 9 };
            let k = k.min(n + 1);
            // Points whose affine hull holds the origin: the last is minus a positive
            // combination of the others.
            let mut points: Vec<Vec<i64>> = (0..k - 1)
                .map(|_| (0..n).map(|_| (next() % (2 * range as u64 + 1)) as i64 - range).collect())
                .collect();
            let weights: Vec<i64> = (0..k - 1).map(|_| (next() % 4) as i64 + 1).collect();
            let last: Vec<i64> = (0..n)
                .map(|r| -points.iter().zip(&weights).map(|(p, w)| p[r] * w).sum::<i64>())
                .collect();
            points.push(last);
            let fast = barycentric_fixed::<i128>(&points).unwrap_or_default();
            let slow = barycentric_big(&points);
            if let Ok(found) = barycentric_fixed::<i128>(&points) {
                prop_assert_eq!(&found, &slow);
            }
            if let Ok(found) = barycentric_fixed::<i64>(&points) {
                prop_assert_eq!(&found, &slow);
            }
            if let Some(w) = fast.as_ref().or(slow.as_ref()) {
                prop_assert!(solves(&points, w));
            }
        }
    }
}
