//! The thinnest layer of a model holding a set of points, exactly: the classical
//! recognition, asked for when a point file has no outliers.
//!
//! **Definition.** Let `φ(p) = (f_1(p), …, f_n(p))` be the model's non-constant basis
//! functions at `p`, in the points' own coordinates. A coefficient vector `c ≠ 0` defines the
//! layer `min_S c·φ ≤ c·φ(p) ≤ max_S c·φ` holding the inliers `S`; its *thickness* is
//! `(max_S c·φ − min_S c·φ) / max_j |c_j|`, the width measured with `c` normalised by the
//! largest absolute value of its non-constant coefficients (the L∞ norm). The thinnest layer
//! minimises the thickness over every `c`. For lines (`a x + b y`) this is the classical
//! arithmetical thickness `ω / max(|a|, |b|)` of digital straight segment recognition; for
//! the other models the normalisation depends on the coordinates, since translating the
//! points changes the lower-degree coefficients.
//!
//! **Computation.** With `max_j |c_j| = 1`, some `c_j` is `±1`, and `c` and `−c` give the
//! same layer, so the optimum is the least over `j` of the linear program
//! `LP_j: minimise u − ℓ over c, ℓ, u with c_j = 1, −1 ≤ c_i ≤ 1, ℓ ≤ c·φ(p) ≤ u (p ∈ S)`.
//! Each is solved through its dual, which has `n + 1` rows (`Σ y = 1`, `Σ z = 1`, and
//! `Σ (y_p − z_p) φ_i(p) + s_i − t_i = 0` for `i ≠ j`), maximising
//! `Σ (y_p − z_p) φ_j(p) − Σ (s_i + t_i)`, by the exact simplex of [`super::lp`]. Its
//! columns are generated: the program starts with the points extreme along each basis
//! function, and the duals of its optimum are a candidate `(c, ℓ, u)`; the inliers most
//! above `u` and most below `ℓ` are added, until none is outside (a pass in floating point
//! picks a few per side while it sees some clearly outside; the pass that decides that
//! none is outside is exact, in big integers). A program stops as soon
//! as its (dual, lower-bound) objective reaches the best thickness of the programs before
//! it. The optimal `c` is then scaled to the smallest integer vector (gcd 1), its bounds
//! computed on every inlier, and the layer and thickness checked again, exactly.
//!
//! Points on one curve of the model (or too few to span the lifted space) have thickness
//! zero: the layer is `lower = upper`.

use super::lp::{Column, Simplex, Status};
use super::{check_values, Layer, PointSets};
use crate::model::Basis;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use std::collections::HashSet;

/// The thinnest layer of the model holding the inliers (see [`crate::PointsAnswer`]): the
/// least `(upper − lower) / max_i |coefficients_i|` over every layer of the model holding
/// them, the constant's coefficient excluded from the maximum.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Thinnest {
    /// The layer in the points' own coordinates: integer coefficients whose gcd is 1, the
    /// bounds reached by inliers; `above` and `below` are `None`.
    pub layer: Layer,
    /// `(upper − lower) / max_i |coefficients_i|`, exactly: the least over every layer of
    /// the model holding the inliers.
    pub thickness: BigRational,
    /// The index of a coefficient of largest absolute value (the one the thickness is
    /// normalised by), in the basis' order; that coefficient is positive.
    pub normalising: usize,
    /// The work it took.
    pub work: ThinnestWork,
}

/// Counters of the linear programs solved for a [`Thinnest`] layer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ThinnestWork {
    /// Programs started (one per non-constant basis function).
    pub programs: u64,
    /// Programs stopped early, their lower bound already at the best thickness.
    pub pruned: u64,
    /// Simplex pivots, over all programs.
    pub pivots: u64,
    /// Rounds of column generation (a solve, then a pass over every inlier).
    pub rounds: u64,
    /// Distinct lifted inliers (the programs' candidate points).
    pub points: u64,
}

/// `φ(p)` exactly: the basis' own lifting when it fits `i64`, else its polynomials in big
/// integers; `None` when neither is possible.
fn lift_exact(basis: &dyn Basis, p: &[i64]) -> Option<Vec<BigInt>> {
    let mut f = vec![0i64; basis.dim()];
    if basis.lift(p, &mut f).is_some() {
        return Some(f.into_iter().map(BigInt::from).collect());
    }
    let functions = crate::model::terms_of(basis)?;
    let values = functions
        .iter()
        .map(|terms| {
            terms
                .iter()
                .map(|(c, e)| {
                    p.iter()
                        .zip(e)
                        .fold(BigInt::from(*c), |t, (&x, &k)| t * BigInt::from(x).pow(k))
                })
                .sum()
        })
        .collect();
    Some(values)
}

/// `a · b`.
fn dot(a: &[BigInt], b: &[BigInt]) -> BigInt {
    a.iter()
        .zip(b)
        .filter(|(x, y)| !x.is_zero() && !y.is_zero())
        .map(|(x, y)| x * y)
        .sum()
}

/// The thinnest layer of `basis` holding `inliers` (at least one), checked exactly; the
/// error message names the point whose lifting cannot be computed, or the failed check.
pub(super) fn thinnest(basis: &dyn Basis, inliers: &[Vec<i64>]) -> Result<Thinnest, String> {
    let n = basis.dim();
    let mut seen = HashSet::new();
    let mut lifted = Vec::new();
    for (i, p) in inliers.iter().enumerate() {
        let f = lift_exact(basis, p).ok_or_else(|| {
            format!("inliers[{i}] = {p:?}: its lifting overflows 64-bit integers and the basis has no polynomials to compute it exactly")
        })?;
        if seen.insert(f.clone()) {
            lifted.push(f);
        }
    }
    // Differences from the first point: the same programs (Σ y = Σ z), smaller numbers.
    let reference = lifted
        .first()
        .cloned()
        .unwrap_or_else(|| vec![BigInt::zero(); n]);
    let g: Vec<Vec<BigInt>> = lifted
        .iter()
        .map(|f| f.iter().zip(&reference).map(|(a, b)| a - b).collect())
        .collect();
    let gf: Vec<Vec<f64>> = g
        .iter()
        .map(|p| p.iter().map(|v| v.to_f64().unwrap_or(f64::NAN)).collect())
        .collect();
    let mut work = ThinnestWork {
        points: g.len() as u64,
        ..ThinnestWork::default()
    };
    let mut best: Option<(BigRational, usize, Vec<BigInt>)> = None;
    for j in 0..n {
        work.programs += 1;
        let bound = best.as_ref().map(|b| &b.0);
        match program(&g, &gf, j, bound, &mut work)? {
            Some((t, c)) => best = Some((t, j, c)),
            None => work.pruned += 1,
        }
    }
    let (thickness, normalising, c) = best.ok_or("a basis without functions has no layer")?;
    // The smallest integer vector along the optimum, and its bounds on every inlier.
    let divisor = c.iter().fold(BigInt::zero(), |g, x| g.gcd(x));
    let coefficients: Vec<BigInt> = c.iter().map(|x| x / &divisor).collect();
    let values: Vec<BigInt> = lifted.iter().map(|f| dot(&coefficients, f)).collect();
    let lower = values.iter().min().cloned().unwrap_or_default();
    let upper = values.iter().max().cloned().unwrap_or_default();
    let layer = Layer {
        coefficients,
        lower,
        upper,
        above: None,
        below: None,
    };
    check(basis, inliers, &layer, &thickness, normalising)
        .map_err(|m| format!("the thinnest layer failed its exact check ({m}; please report)"))?;
    Ok(Thinnest {
        layer,
        thickness,
        normalising,
        work,
    })
}

/// The layer holds every inlier with its bounds reached (evaluated again, by
/// [`Layer::value`]), coefficient `normalising` is one of largest absolute value, and the
/// thickness is the layer's.
fn check(
    basis: &dyn Basis,
    inliers: &[Vec<i64>],
    layer: &Layer,
    thickness: &BigRational,
    normalising: usize,
) -> Result<(), String> {
    let sets = PointSets::new(inliers.to_vec());
    check_values(
        &sets,
        |p| layer.value(basis, p),
        (layer.lower.clone(), layer.upper.clone()),
        (None, None),
    )?;
    let largest = layer.coefficients.iter().map(BigInt::abs).max();
    let norm = layer.coefficients.get(normalising).cloned();
    if !norm.as_ref().is_some_and(Signed::is_positive) || largest != norm {
        return Err("normalising coefficient".into());
    }
    let width = BigRational::new(&layer.upper - &layer.lower, norm.unwrap_or_default());
    if width != *thickness {
        return Err(format!("thickness {width}, not {thickness}"));
    }
    Ok(())
}

/// The points screened per side and round.
const SCREENED: usize = 4;

/// The indices of up to [`SCREENED`] points of `gf` (the lifted points as floats) most
/// above `u` and most below `ℓ` for `c / det`, by a clear margin in floating point; `None`
/// when a number does not fit a float.
fn screen(
    gf: &[Vec<f64>],
    c: &[BigInt],
    (u, l): (&BigInt, &BigInt),
    det: &BigInt,
) -> Option<Vec<usize>> {
    let d = det.to_f64().filter(|v| v.is_finite() && *v > 0.0)?;
    let ratio = |v: &BigInt| v.to_f64().map(|x| x / d).filter(|x| x.is_finite());
    let cf: Vec<f64> = c.iter().map(ratio).collect::<Option<_>>()?;
    let (uf, lf) = (ratio(u)?, ratio(l)?);
    let scale: f64 = gf
        .iter()
        .flat_map(|p| p.iter().zip(&cf).map(|(a, b)| (a * b).abs()))
        .fold(uf.abs().max(lf.abs()), f64::max);
    let margin = 1e-9 * scale.max(1.0);
    let mut above = Vec::new();
    let mut below = Vec::new();
    for (k, p) in gf.iter().enumerate() {
        let v: f64 = p.iter().zip(&cf).map(|(a, b)| a * b).sum();
        if v > uf + margin {
            above.push((v - uf, k));
        } else if v < lf - margin {
            below.push((lf - v, k));
        }
    }
    let mut out = Vec::new();
    for side in [&mut above, &mut below] {
        side.sort_by(|a, b| b.0.total_cmp(&a.0));
        out.extend(side.iter().take(SCREENED).map(|&(_, k)| k));
    }
    Some(out)
}

/// `LP_j` on the points `g` (lifted, `g[0] = 0`), through its dual with column generation:
/// `(thickness, c)` with `c` integer and `c_j > 0` the largest in absolute value, or `None`
/// when its objective reached `bound` first (its optimum is no less).
#[allow(clippy::type_complexity)]
fn program(
    g: &[Vec<BigInt>],
    gf: &[Vec<f64>],
    j: usize,
    bound: Option<&BigRational>,
    work: &mut ThinnestWork,
) -> Result<Option<(BigRational, Vec<BigInt>)>, String> {
    let n = g[0].len();
    let m = n + 1;
    // Rows: 0 is Σ y = 1 (dual u), 1 is Σ z = 1 (dual −ℓ), then one per i ≠ j (dual −c_i).
    let row = |i: usize| 2 + i - usize::from(i > j);
    let mut b = vec![BigInt::zero(); m];
    b[0] = BigInt::from(1);
    b[1] = BigInt::from(1);
    // The unit columns: y and z of point 0 (φ = 0, objective 0), then s_i (objective −1).
    let mut unit = vec![BigInt::from(-1); m];
    unit[0] = BigInt::zero();
    unit[1] = BigInt::zero();
    let mut lp = Simplex::new(b, unit);
    for i in (0..n).filter(|&i| i != j) {
        let mut entries = vec![BigInt::zero(); m];
        entries[row(i)] = BigInt::from(-1);
        lp.add(Column {
            entries,
            objective: BigInt::from(-1),
        });
    }
    let mut taken = vec![false; g.len()];
    taken[0] = true;
    let mut take = |lp: &mut Simplex, k: usize| -> bool {
        if std::mem::replace(&mut taken[k], true) {
            return false;
        }
        let (mut y, mut z) = (vec![BigInt::zero(); m], vec![BigInt::zero(); m]);
        y[0] = BigInt::from(1);
        z[1] = BigInt::from(1);
        for i in (0..n).filter(|&i| i != j) {
            y[row(i)] = g[k][i].clone();
            z[row(i)] = -&g[k][i];
        }
        lp.add(Column {
            entries: y,
            objective: g[k][j].clone(),
        });
        lp.add(Column {
            entries: z,
            objective: -&g[k][j],
        });
        true
    };
    // The points extreme along each basis function.
    for i in 0..n {
        let by = |k: &usize| g[*k][i].clone();
        if let Some(k) = (0..g.len()).max_by_key(by) {
            take(&mut lp, k);
        }
        if let Some(k) = (0..g.len()).min_by_key(by) {
            take(&mut lp, k);
        }
    }
    let result = loop {
        work.rounds += 1;
        match lp.solve(bound) {
            Status::Optimal => {}
            Status::Bounded => break None,
            // The primal is feasible (c = e_j), so its dual is bounded.
            Status::Unbounded => return Err("unbounded dual program (please report)".into()),
        }
        let pi = lp.duals();
        let det = lp.det().clone();
        let c: Vec<BigInt> = (0..n)
            .map(|i| if i == j { det.clone() } else { -&pi[row(i)] })
            .collect();
        // Screening in floating point first: the most violated points not yet taken, a few
        // per side; the exact pass below runs only when it finds none (and decides).
        if let Some(found) = screen(gf, &c, (&pi[0], &-&pi[1]), &det) {
            let mut added = false;
            for k in found {
                added |= take(&mut lp, k);
            }
            if added {
                continue;
            }
        }
        let values: Vec<BigInt> = g.iter().map(|p| dot(&c, p)).collect();
        let (mut hi, mut lo) = (0, 0);
        for (k, v) in values.iter().enumerate() {
            if *v > values[hi] {
                hi = k;
            }
            if *v < values[lo] {
                lo = k;
            }
        }
        // u = π_0 / det, ℓ = −π_1 / det.
        let (above, below) = (values[hi] > pi[0], values[lo] < -&pi[1]);
        if above {
            take(&mut lp, hi);
        }
        if below {
            take(&mut lp, lo);
        }
        if !above && !below {
            let thickness = BigRational::new(&values[hi] - &values[lo], det);
            if thickness != lp.objective() {
                return Err("duality gap (please report)".into());
            }
            break Some((thickness, c));
        }
    };
    work.pivots += lp.pivots;
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use proptest::prelude::*;

    fn rational(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    /// The L∞-thinnest strip of a finite planar set, by brute force: its direction is
    /// orthogonal to an edge of the convex hull, so every pair of points gives a candidate
    /// normal `(a, b) = (dy, −dx)`; the thickness of `a x + b y` is its range over the set
    /// divided by `max(|a|, |b|)`.
    fn brute_force_line(points: &[Vec<i64>]) -> BigRational {
        let mut best: Option<BigRational> = None;
        for p in points {
            for q in points {
                let (a, b) = (q[1] - p[1], p[0] - q[0]);
                if a == 0 && b == 0 {
                    continue;
                }
                let v = |r: &Vec<i64>| a * r[0] + b * r[1];
                let hi = points.iter().map(v).max().unwrap();
                let lo = points.iter().map(v).min().unwrap();
                let t = rational(hi - lo, a.abs().max(b.abs()));
                best = Some(best.map_or(t.clone(), |b| b.min(t)));
            }
        }
        // A single point (or copies of one): thickness zero.
        best.unwrap_or_else(BigRational::zero)
    }

    /// A centre in [−1000, 1000]², a radius in 1..=21 and 1 to 13 offsets within it.
    fn planar_set() -> impl Strategy<Value = Vec<Vec<i64>>> {
        (-1000i64..=1000, -1000i64..=1000, 1i64..=21).prop_flat_map(|(cx, cy, r)| {
            proptest::collection::vec((-r..=r, -r..=r), 1..=13).prop_map(move |offsets| {
                offsets
                    .into_iter()
                    .map(|(dx, dy)| vec![cx + dx, cy + dy])
                    .collect()
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(150))]

        #[test]
        fn random_planar_sets_match_brute_force_for_lines(points in planar_set()) {
            let basis = Model::Line.basis();
            let t = thinnest(&basis, &points).unwrap();
            prop_assert_eq!(
                &t.thickness,
                &brute_force_line(&points),
                "{:?} {:?}",
                points,
                t.layer
            );
        }
    }

    /// Digital straight segments: the thickness of the naive line `0 ≤ a x − b y < max`
    /// digitized over a long run is `(max(|a|, |b|) − 1) / max(|a|, |b|)`.
    #[test]
    fn a_naive_digital_segment_has_its_arithmetical_thickness() {
        let basis = Model::Line.basis();
        let points: Vec<Vec<i64>> = (0i64..40).map(|x| vec![x, (3 * x).div_euclid(7)]).collect();
        let t = thinnest(&basis, &points).unwrap();
        assert_eq!(t.thickness, rational(6, 7));
        let c = &t.layer.coefficients;
        assert_eq!(c.len(), 2);
        assert_eq!(t.layer.upper.clone() - &t.layer.lower, BigInt::from(6));
        assert_eq!(c[t.normalising].abs(), BigInt::from(7));
    }

    /// Points on one curve of the model: thickness zero, `lower == upper`.
    #[test]
    fn points_on_a_curve_of_the_model_have_thickness_zero() {
        let cases: Vec<(Model, Vec<Vec<i64>>)> = vec![
            (
                Model::Line,
                (0..9).map(|k| vec![3 * k - 5, 2 * k + 1]).collect(),
            ),
            (
                Model::Circle,
                vec![
                    vec![5, 0],
                    vec![3, 4],
                    vec![0, 5],
                    vec![-4, 3],
                    vec![-5, 0],
                    vec![0, -5],
                    vec![4, -3],
                ],
            ),
            (
                Model::Quadric3,
                (-3i64..=3)
                    .flat_map(|x| (-3i64..=3).map(move |y| vec![x, y, x * x - 2 * x * y + 3]))
                    .collect(),
            ),
            // A single point.
            (Model::Poly3(3), vec![vec![7, -1, 2]]),
        ];
        for (model, points) in cases {
            let basis = model.basis();
            let t = thinnest(&basis, &points).unwrap();
            assert!(t.thickness.is_zero(), "{model}: {}", t.thickness);
            assert_eq!(t.layer.lower, t.layer.upper, "{model}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(9))]

        /// Digitized circles and conics: the layer holds every point (checked in `thinnest`
        /// itself too), and no coefficient vector of a random family is thinner: near the
        /// optimum (each coefficient times 50, plus −3..=3) or anywhere (plus −500..=500).
        #[test]
        fn no_random_direction_is_thinner_than_the_thinnest(
            model in prop_oneof![Just(Model::Circle), Just(Model::Conic), Just(Model::Poly(3))],
            (a, b) in (1i64..=4, 1i64..=4),
            (cx, cy) in (-50i64..=50, -50i64..=50),
            directions in proptest::collection::vec(
                (proptest::bool::ANY, proptest::collection::vec(-500i64..=500, 10)),
                300,
            ),
        ) {
            let basis = model.basis();
            let mut points = Vec::new();
            for x in -12..=12 {
                for y in -12..=12 {
                    let v = a * x * x + b * y * y + x * y;
                    if (60..60 + 3 * (a + b)).contains(&v) {
                        points.push(vec![x + cx, y + cy]);
                    }
                }
            }
            let t = thinnest(&basis, &points).unwrap();
            for p in &points {
                let v = t.layer.value(&basis, p).unwrap();
                prop_assert!(t.layer.lower <= v && v <= t.layer.upper);
            }
            let lifted: Vec<Vec<BigInt>> = points
                .iter()
                .map(|p| lift_exact(&basis, p).unwrap())
                .collect();
            for (near, offsets) in directions {
                let c: Vec<BigInt> = t
                    .layer
                    .coefficients
                    .iter()
                    .zip(offsets)
                    .map(|(x, o)| x * 50 + if near { o % 4 } else { o })
                    .collect();
                let values: Vec<BigInt> = lifted.iter().map(|f| dot(&c, f)).collect();
                let norm = c.iter().map(BigInt::abs).max().unwrap();
                if norm.is_zero() {
                    continue;
                }
                let width = values.iter().max().unwrap() - values.iter().min().unwrap();
                prop_assert!(BigRational::new(width, norm) >= t.thickness, "{}", model);
            }
        }
    }

    /// Far from the origin the liftings overflow `i64`: big integers answer.
    #[test]
    fn far_points_are_lifted_in_big_integers() {
        let basis = Model::Poly(6).basis();
        let b = crate::model::PolynomialBasis::new(
            2,
            vec![vec![(1, vec![6, 0])], vec![(1, vec![0, 1])]],
            vec!["x^6".into(), "y".into()],
        )
        .unwrap();
        let far = vec![vec![1 << 20, 0], vec![0, 1], vec![3, 3]];
        assert!(thinnest(&basis, &far).is_ok());
        assert!(thinnest(&b, &far).is_ok());
    }
}
