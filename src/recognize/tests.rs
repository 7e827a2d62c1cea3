//! Differential tests of the recognizer against an independent exact oracle.
//!
//! The oracle decides `0 ∈ conv(D)` by Carathéodory brute force: the origin is in the hull
//! iff some affinely independent subset of at most `n + 1` points of `D` holds it, which is a
//! linear system solved in exact `Ratio<i128>` arithmetic. It shares no code with the
//! recognizer. Every answer of the recognizer is also re-checked on its own terms: the
//! certificate's values recomputed point by point, the witness' weighted sum recomputed.

use super::*;
use crate::model::Model;
use num_rational::Ratio;
use num_traits::{One, Signed as _, Zero};
use proptest::prelude::*;
use std::collections::HashMap;

type Q = Ratio<i128>;
/// A set of points.
type Pts = Vec<Vec<i64>>;

/// Lifted differences `D` of a problem (relative to `origin`).
fn differences(
    basis: &dyn Basis,
    origin: &[i64],
    s: &[Vec<i64>],
    up: &[Vec<i64>],
    lo: &[Vec<i64>],
) -> Vec<Vec<i64>> {
    let lift = |p: &Vec<i64>| {
        let rel: Vec<i64> = p.iter().zip(origin).map(|(a, b)| a - b).collect();
        let mut f = vec![0; basis.dim()];
        basis.lift(&rel, &mut f).unwrap();
        f
    };
    let fs: Vec<Vec<i64>> = s.iter().map(lift).collect();
    let mut d = Vec::new();
    for fi in &fs {
        for o in up {
            let fo = lift(o);
            d.push(fo.iter().zip(fi).map(|(a, b)| a - b).collect());
        }
        for o in lo {
            let fo = lift(o);
            d.push(fi.iter().zip(&fo).map(|(a, b)| a - b).collect());
        }
    }
    d.sort();
    d.dedup();
    d
}

/// Is the origin in the convex hull of these affinely independent points? (`None` when they
/// are affinely dependent.)
fn simplex_holds_origin(pts: &[&Vec<i64>]) -> Option<bool> {
    let n = pts[0].len();
    let k = pts.len();
    // (n+1) × (k+1) augmented: coordinates, then the row of ones = 1.
    let mut m: Vec<Vec<Q>> = (0..=n)
        .map(|r| {
            let mut row: Vec<Q> = (0..k)
                .map(|c| {
                    if r < n {
                        Q::from_integer(pts[c][r] as i128)
                    } else {
                        Q::one()
                    }
                })
                .collect();
            row.push(if r < n { Q::zero() } else { Q::one() });
            row
        })
        .collect();
    let mut rank = 0;
    let mut pivots = Vec::new();
    for c in 0..k {
        let Some(p) = (rank..=n).find(|&r| !m[r][c].is_zero()) else {
            return None; // column dependent: affinely dependent points
        };
        m.swap(rank, p);
        let pv = m[rank][c];
        for cc in 0..=k {
            m[rank][cc] /= pv;
        }
        for r in 0..=n {
            if r != rank && !m[r][c].is_zero() {
                let f = m[r][c];
                for cc in 0..=k {
                    let v = m[rank][cc];
                    m[r][cc] -= f * v;
                }
            }
        }
        pivots.push(c);
        rank += 1;
    }
    // Consistency: remaining rows must have zero right-hand side.
    if (rank..=n).any(|r| !m[r][k].is_zero()) {
        return Some(false);
    }
    Some((0..k).all(|r| !m[r][k].is_negative()))
}

/// The oracle: `0 ∈ conv(D)`.
fn origin_in_conv_brute(d: &[Vec<i64>]) -> bool {
    if d.is_empty() {
        return false;
    }
    let n = d[0].len();
    let mut idx = Vec::new();
    fn rec(d: &[Vec<i64>], start: usize, left: usize, idx: &mut Vec<usize>) -> bool {
        if !idx.is_empty() {
            let pts: Vec<&Vec<i64>> = idx.iter().map(|&i| &d[i]).collect();
            match simplex_holds_origin(&pts) {
                Some(true) => return true,
                None => return false, // supersets are dependent too
                Some(false) => {}
            }
        }
        if left == 0 {
            return false;
        }
        for i in start..d.len() {
            idx.push(i);
            if rec(d, i + 1, left - 1, idx) {
                return true;
            }
            idx.pop();
        }
        false
    }
    rec(d, 0, n + 1, &mut idx)
}

/// Re-checks a certificate point by point, independently of the recognizer's code.
fn certificate_holds(
    basis: &dyn Basis,
    c: &Certificate,
    s: &[Vec<i64>],
    up: &[Vec<i64>],
    lo: &[Vec<i64>],
) -> bool {
    let val = |p: &Vec<i64>| -> i128 {
        let rel: Vec<i64> = p.iter().zip(&c.origin).map(|(a, b)| a - b).collect();
        let mut f = vec![0; basis.dim()];
        basis.lift(&rel, &mut f).unwrap();
        f.iter()
            .zip(&c.coefficients)
            .map(|(&a, &b)| a as i128 * b as i128)
            .sum()
    };
    let vs: Vec<i128> = s.iter().map(val).collect();
    let lower = *vs.iter().min().unwrap();
    let upper = *vs.iter().max().unwrap();
    lower == c.extremes.lower
        && upper == c.extremes.upper
        && up.iter().all(|p| val(p) > upper)
        && lo.iter().all(|p| val(p) < lower)
}

/// Re-checks a witness: its pairs come from the sets and the exact weighted sum is zero.
fn witness_holds(
    basis: &dyn Basis,
    w: &Witness,
    s: &[Vec<i64>],
    up: &[Vec<i64>],
    lo: &[Vec<i64>],
) -> bool {
    let from_sets = w.pairs.iter().all(|(i, o, side)| {
        s.contains(i)
            && match side {
                Side::Upper => up.contains(o),
                Side::Lower => lo.contains(o),
            }
    });
    from_sets && w.verify(basis)
}

#[derive(Default, Debug)]
struct Tally {
    instances: usize,
    described: usize,
    not_described: usize,
    checked_by_oracle: usize,
}

/// Runs one instance and checks everything. Returns (described, oracle ran).
fn check_instance(
    model: Model,
    s: &[Vec<i64>],
    up: &[Vec<i64>],
    lo: &[Vec<i64>],
    tally: &mut Tally,
) -> Result<(), TestCaseError> {
    let basis: Arc<dyn Basis> = Arc::new(model.basis());
    let Recognition {
        outcome,
        certificate: cert,
        witness: wit,
    } = recognize(basis.clone(), s, up, lo);
    tally.instances += 1;
    prop_assert_ne!(
        outcome,
        Outcome::Undecided,
        "undecided on {:?} {:?} {:?}",
        s,
        up,
        lo
    );
    let described = outcome == Outcome::Described;
    if described {
        tally.described += 1;
        let c = cert.expect("certificate");
        prop_assert!(
            certificate_holds(basis.as_ref(), &c, s, up, lo),
            "bad certificate {c:?}"
        );
    } else {
        tally.not_described += 1;
        let w = wit.expect("witness");
        prop_assert!(
            witness_holds(basis.as_ref(), &w, s, up, lo),
            "bad witness {w:?}"
        );
    }
    let d = differences(basis.as_ref(), &s[0], s, up, lo);
    if d.len() <= 14 {
        tally.checked_by_oracle += 1;
        let inside = origin_in_conv_brute(&d);
        prop_assert_eq!(
            described,
            !inside,
            "disagreement with the oracle ({:?}) on S={:?} S+={:?} S-={:?}",
            model,
            s,
            up,
            lo
        );
    }
    Ok(())
}

fn point2(range: i64) -> impl Strategy<Value = Vec<i64>> {
    (-range..=range, -range..=range).prop_map(|(x, y)| vec![x, y])
}

fn point3(range: i64) -> impl Strategy<Value = Vec<i64>> {
    (-range..=range, -range..=range, -range..=range).prop_map(|(x, y, z)| vec![x, y, z])
}

/// Random small instances: sets of random points, random offsets (large coordinates too).
fn small_instance(dim: usize, range: i64) -> impl Strategy<Value = (Pts, Pts, Pts, i64)> {
    let pt = move || -> BoxedStrategy<Vec<i64>> {
        if dim == 2 {
            point2(range).boxed()
        } else {
            point3(range).boxed()
        }
    };
    (
        proptest::collection::vec(pt(), 1..=4),
        proptest::collection::vec(pt(), 0..=3),
        proptest::collection::vec(pt(), 0..=3),
        prop_oneof![Just(0i64), Just(10_000i64), -50i64..50],
    )
}

fn shift(v: &[Vec<i64>], by: i64) -> Vec<Vec<i64>> {
    v.iter()
        .map(|p| p.iter().map(|c| c + by).collect())
        .collect()
}

/// Instances built from a random polynomial so that they are often described (then
/// perturbed): the points of a box with `f` in a band are inliers, those just above and below
/// are outliers.
fn banded_instance(
    model: Model,
    coefs: &[i64],
    band: i64,
    flip: Option<usize>,
    range: i64,
) -> (Pts, Pts, Pts) {
    let basis = model.basis();
    let mut s = Vec::new();
    let mut up = Vec::new();
    let mut lo = Vec::new();
    let mut f = vec![0; basis.dim()];
    for x in -range..=range {
        for y in -range..=range {
            basis.lift(&[x, y], &mut f).unwrap();
            let v: i64 = f.iter().zip(coefs).map(|(a, b)| a * b).sum();
            if (0..band).contains(&v) {
                s.push(vec![x, y]);
            } else if (band..3 * band).contains(&v) {
                up.push(vec![x, y]);
            } else if (-2 * band..0).contains(&v) {
                lo.push(vec![x, y]);
            }
        }
    }
    if let Some(k) = flip {
        if !up.is_empty() {
            let p = up.remove(k % up.len());
            lo.push(p);
        }
    }
    (s, up, lo)
}

macro_rules! differential {
    ($name:ident, $model:expr, $dim:expr, $range:expr, $cases:expr) => {
        proptest! {
            #![proptest_config(ProptestConfig::with_cases($cases))]
            #[test]
            fn $name(inst in small_instance($dim, $range)) {
                let (s, up, lo, off) = inst;
                let mut tally = Tally::default();
                check_instance($model, &shift(&s, off), &shift(&up, off), &shift(&lo, off), &mut tally)?;
            }
        }
    };
}

differential!(random_line, Model::Line, 2, 6, 3000);
differential!(random_circle, Model::Circle, 2, 6, 3000);
differential!(random_conic, Model::Conic, 2, 6, 3000);
differential!(random_poly3, Model::Poly(3), 2, 4, 1500);
differential!(random_poly4, Model::Poly(4), 2, 3, 1000);
differential!(random_quadric3, Model::Quadric3, 3, 3, 1000);

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn banded_instances(
        model in prop_oneof![Just(Model::Line), Just(Model::Circle), Just(Model::Conic), Just(Model::Poly(3))],
        raw in proptest::collection::vec(-6i64..=6, 10),
        band in 1i64..40,
        flip in proptest::option::of(0usize..100),
    ) {
        let basis = model.basis();
        let coefs = &raw[..basis.dim()];
        prop_assume!(coefs.iter().any(|&c| c != 0));
        let (s, up, lo) = banded_instance(model, coefs, band, flip, 6);
        prop_assume!(!s.is_empty());
        let mut tally = Tally::default();
        check_instance(model, &s, &up, &lo, &mut tally)?;
        if flip.is_none() {
            prop_assert_eq!(tally.described, 1, "a banded instance is described by construction");
        }
    }
}

#[test]
fn degenerate_cases() {
    let p = |x: i64, y: i64| vec![x, y];
    let mut tally = Tally::default();
    for model in [Model::Line, Model::Circle, Model::Conic, Model::Poly(4)] {
        // Empty outlier sets: described (by the zero function).
        check_instance(model, &[p(0, 0), p(3, 1)], &[], &[], &mut tally).unwrap();
        // Duplicate points.
        check_instance(
            model,
            &[p(0, 0), p(0, 0), p(1, 0)],
            &[p(0, 1), p(0, 1)],
            &[p(0, -1)],
            &mut tally,
        )
        .unwrap();
        // One point in both outlier sets: never described.
        let Recognition {
            outcome: o,
            witness: w,
            ..
        } = recognize(
            Arc::new(model.basis()),
            &[p(0, 0), p(1, 0)],
            &[p(5, 5)],
            &[p(5, 5)],
        );
        assert_eq!(o, Outcome::NotDescribed, "{model:?}");
        assert!(w.unwrap().verify(&model.basis()));
        // An outlier equal to an inlier: never described.
        let Recognition { outcome: o, .. } = recognize(
            Arc::new(model.basis()),
            &[p(0, 0), p(2, 1)],
            &[p(2, 1)],
            &[],
        );
        assert_eq!(o, Outcome::NotDescribed, "{model:?}");
        // Collinear inliers with outliers on both sides: described.
        let s: Vec<_> = (0..20).map(|i| p(i, 2 * i)).collect();
        let up: Vec<_> = (0..20).map(|i| p(i, 2 * i + 1)).collect();
        let lo: Vec<_> = (0..20).map(|i| p(i, 2 * i - 1)).collect();
        check_instance(model, &s, &up, &lo, &mut tally).unwrap();
        assert_eq!(
            recognize(Arc::new(model.basis()), &s, &up, &lo).outcome,
            Outcome::Described
        );
        // Large coordinates.
        let big = |v: &Vec<Vec<i64>>| shift(v, 10_000);
        check_instance(model, &big(&s), &big(&up), &big(&lo), &mut tally).unwrap();
    }
    // Cocircular inliers: the circle x²+y² = 25 with outliers inside and outside.
    let s = vec![
        p(5, 0),
        p(3, 4),
        p(0, 5),
        p(-3, 4),
        p(-5, 0),
        p(-4, -3),
        p(0, -5),
        p(4, -3),
    ];
    let out = vec![
        p(6, 0),
        p(4, 4),
        p(0, 6),
        p(-4, 4),
        p(-6, 0),
        p(-5, -3),
        p(0, -6),
        p(5, -3),
    ];
    let inn = vec![
        p(4, 0),
        p(2, 3),
        p(0, 4),
        p(-2, 3),
        p(-4, 0),
        p(-3, -2),
        p(0, -4),
        p(3, -2),
    ];
    for model in [Model::Circle, Model::Conic, Model::Poly(3)] {
        let Recognition {
            outcome: o,
            certificate: c,
            ..
        } = recognize(Arc::new(model.basis()), &s, &out, &inn);
        assert_eq!(o, Outcome::Described, "{model:?}");
        assert!(certificate_holds(
            &model.basis(),
            &c.unwrap(),
            &s,
            &out,
            &inn
        ));
    }
    // The line model cannot describe a circle.
    assert_eq!(
        recognize(Arc::new(Model::Line.basis()), &s, &out, &inn).outcome,
        Outcome::NotDescribed
    );
}

/// A digitized circle arc grown point by point with its 4-neighbours as outliers: every
/// incremental answer equals the from-scratch answer, and the certificates check.
#[test]
fn incremental_equals_from_scratch() {
    for model in [Model::Line, Model::Circle, Model::Conic] {
        let basis: Arc<dyn Basis> = Arc::new(model.basis());
        let r2 = 40 * 40;
        // Pixels of the first octant of the disc border, in order.
        let mut arc: Vec<Vec<i64>> = Vec::new();
        let mut y = 40i64;
        for x in 0..=40i64 {
            while y > 0 && x * x + y * y > r2 {
                y -= 1;
            }
            if x > y {
                break;
            }
            arc.push(vec![x, y]);
        }
        let mut rec = Recognizer::new(basis.clone(), &arc[0]).unwrap();
        let (mut s, mut up, mut lo): (Pts, Pts, Pts) = Default::default();
        let mut count: HashMap<Vec<i64>, ()> = HashMap::new();
        for p in &arc {
            rec.add_inlier(p);
            s.push(p.clone());
            count.insert(p.clone(), ());
            // Outside (upper) and inside (lower) neighbours.
            for q in [vec![p[0], p[1] + 1], vec![p[0] + 1, p[1] + 1]] {
                if q[0] * q[0] + q[1] * q[1] > r2 && !up.contains(&q) {
                    rec.add_outlier(&q, Side::Upper);
                    up.push(q);
                }
            }
            let q = vec![p[0], p[1] - 1];
            if q[0] * q[0] + q[1] * q[1] <= r2 && !lo.contains(&q) && !s.contains(&q) {
                rec.add_outlier(&q, Side::Lower);
                lo.push(q);
            }
            let inc = rec.recognize();
            let Recognition {
                outcome: scratch, ..
            } = recognize(basis.clone(), &s, &up, &lo);
            assert_eq!(inc, scratch, "{model:?} after {} points", s.len());
            if inc == Outcome::Described {
                assert!(certificate_holds(
                    basis.as_ref(),
                    &rec.certificate().unwrap(),
                    &s,
                    &up,
                    &lo
                ));
            } else {
                assert!(witness_holds(
                    basis.as_ref(),
                    rec.witness().unwrap(),
                    &s,
                    &up,
                    &lo
                ));
            }
        }
        if model != Model::Line {
            assert_eq!(
                rec.recognize(),
                Outcome::Described,
                "{model:?}: a circle arc is a digital circle"
            );
        }
        let st = rec.stats();
        assert!(st.certificate_reused > 0, "{model:?}: {st:?}");
    }
}

/// Not a check but a report: `cargo test --release --lib differential_report -- --ignored
/// --nocapture` prints, per basis, how many random instances were decided, how, and how
/// often the exact fallback was needed.
#[test]
#[ignore]
fn differential_report() {
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = move |m: i64| -> i64 {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % (2 * m as u64 + 1)) as i64 - m
    };
    for (model, dim, range, count) in [
        (Model::Line, 2, 6, 20000),
        (Model::Circle, 2, 6, 20000),
        (Model::Conic, 2, 6, 20000),
        (Model::Poly(3), 2, 4, 5000),
        (Model::Poly(4), 2, 3, 3000),
        (Model::Quadric3, 3, 3, 3000),
    ] {
        let start = std::time::Instant::now();
        let mut tally = Tally::default();
        let mut stats = Stats::default();
        for _ in 0..count {
            let ns = 1 + (rnd(1) + 1) as usize * 2;
            let (nu, nl) = ((rnd(1) + 2) as usize, (rnd(1) + 2) as usize);
            let all: Vec<Vec<i64>> = (0..ns + nu + nl)
                .map(|_| (0..dim).map(|_| rnd(range)).collect())
                .collect();
            let (s, rest) = all.split_at(ns);
            let (up, lo) = rest.split_at(nu);
            let basis: Arc<dyn Basis> = Arc::new(model.basis());
            let mut r = Recognizer::new(basis, &s[0]).unwrap();
            s.iter().for_each(|p| r.add_inlier(p));
            up.iter().for_each(|p| r.add_outlier(p, Side::Upper));
            lo.iter().for_each(|p| r.add_outlier(p, Side::Lower));
            r.recognize();
            stats += &r.stats();
            check_instance(model, s, up, lo, &mut tally).unwrap();
        }
        println!(
            "{:<9} instances {:>6}  described {:>6}  not described {:>6}  oracle-checked {:>6}  float runs {:>6}  exact fallbacks {:>4}  undecided {}  ({:.1}s)",
            model.name(), tally.instances, tally.described, tally.not_described,
            tally.checked_by_oracle, stats.float_runs, stats.exact_fallbacks, stats.undecided,
            start.elapsed().as_secs_f64()
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]
    /// The exact fallback alone (never reached by the random instances above, where the
    /// float run always proves its answer) agrees with the oracle, and its answers check.
    #[test]
    fn exact_fallback_agrees_with_the_oracle(
        model in prop_oneof![Just(Model::Line), Just(Model::Circle), Just(Model::Conic)],
        inst in small_instance(2, 5),
    ) {
        let (s, up, lo, off) = inst;
        let (s, up, lo) = (shift(&s, off), shift(&up, off), shift(&lo, off));
        let basis: Arc<dyn Basis> = Arc::new(model.basis());
        let mut r = Recognizer::new(basis.clone(), &s[0]).unwrap();
        s.iter().for_each(|p| r.add_inlier(p));
        up.iter().for_each(|p| r.add_outlier(p, Side::Upper));
        lo.iter().for_each(|p| r.add_outlier(p, Side::Lower));
        let sets = Sets { inliers: &r.inliers, upper: &r.upper, lower: &r.lower };
        let d = differences(basis.as_ref(), &s[0], &s, &up, &lo);
        let inside = origin_in_conv_brute(&d);
        match exact::decide_exactly(&sets, &[], &r.max_abs, &mut Meter::unlimited()) {
            exact::ExactDecision::Described(a, e) => {
                prop_assert!(!inside, "exact says described, oracle says not");
                let c = Certificate { origin: s[0].clone(), coefficients: a, extremes: e };
                prop_assert!(certificate_holds(basis.as_ref(), &c, &s, &up, &lo));
            }
            exact::ExactDecision::NotDescribed(tags, weights) => {
                prop_assert!(inside, "exact says not described, oracle says described");
                // The weighted sum of the named differences is zero.
                let n = basis.dim();
                let mut sum = vec![BigRational::from_integer(0.into()); n];
                for (t, w) in tags.iter().zip(&weights) {
                    for (k, v) in sets.difference(t).into_iter().enumerate() {
                        sum[k] += w * BigRational::from_integer(v.into());
                    }
                }
                prop_assert!(sum.iter().all(|v| *v == BigRational::from_integer(0.into())));
            }
            exact::ExactDecision::Undecided | exact::ExactDecision::OverBudget => {
                prop_assert!(false, "undecided")
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// `small_certificate` returns a certificate that holds, never with larger coefficients.
    #[test]
    fn small_certificates_hold_and_are_not_larger(
        model in prop_oneof![Just(Model::Line), Just(Model::Circle), Just(Model::Conic)],
        raw in proptest::collection::vec(-6i64..=6, 10),
        band in 1i64..40,
    ) {
        let basis = model.basis();
        let coefs = &raw[..basis.dim()];
        prop_assume!(coefs.iter().any(|&c| c != 0));
        let (s, up, lo) = banded_instance(model, coefs, band, None, 6);
        prop_assume!(!s.is_empty());
        let Recognition { outcome: o, certificate: c, .. } = recognize(Arc::new(model.basis()), &s, &up, &lo);
        prop_assert_eq!(o, Outcome::Described);
        let c = c.unwrap();
        let small = small_certificate(&basis, &c, &s, &up, &lo);
        prop_assert!(certificate_holds(&basis, &small, &s, &up, &lo), "{small:?}");
        let size = |c: &Certificate| c.coefficients.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
        prop_assert!(size(&small) <= size(&c), "{small:?} larger than {c:?}");
    }
}

/// The exact decision of the current sets of `r`, by the exact fallback alone.
fn exact_outcome(r: &Recognizer) -> Outcome {
    let sets = Sets {
        inliers: &r.inliers,
        upper: &r.upper,
        lower: &r.lower,
    };
    match exact::decide_exactly(&sets, &[], &r.max_abs, &mut Meter::unlimited()) {
        exact::ExactDecision::Described(..) => Outcome::Described,
        exact::ExactDecision::NotDescribed(..) => Outcome::NotDescribed,
        exact::ExactDecision::Undecided => Outcome::Undecided,
        exact::ExactDecision::OverBudget => Outcome::OverBudget,
    }
}

/// A long, nearly flat arc of a digital circle of radius 180 000 under the conic basis: the
/// lifted points lie close to a 3-dimensional subspace and the float runs in scaled
/// coordinates stall (the case that once sent most queries of a 10⁶-pixel contour to the
/// exact fallback). Grown pixel by pixel as a decomposition does, a new piece started at each
/// "not described": the float runs in whitened coordinates prove every answer, each one the
/// same as the exact fallback's, and each certificate or witness checks.
#[test]
fn long_flat_arc_is_decided_like_the_exact_fallback() {
    let r: i64 = 180_000;
    let basis: Arc<dyn Basis> = Arc::new(Model::Conic.basis());
    let top = |x: i64| -> i64 {
        let mut y = ((r * r - x * x) as f64).sqrt() as i64;
        while x * x + y * y > r * r {
            y -= 1;
        }
        while x * x + (y + 1) * (y + 1) <= r * r {
            y += 1;
        }
        y
    };
    let mut total = Stats::default();
    let mut checked = 0;
    // Columns x0.. of the disc border, slopes from 0.1 to 0.7: one pixel per column.
    for x0 in [20_000i64, 57_000, 100_000] {
        let mut rec = Recognizer::new(basis.clone(), &[x0, top(x0)]).unwrap();
        let (mut s, mut up, mut lo): (Pts, Pts, Pts) = Default::default();
        let mut pieces = 0;
        let mut x = x0;
        while pieces < 2 {
            let y = top(x);
            let p = vec![x, y];
            rec.add_inlier(&p);
            s.push(p);
            for q in [vec![x, y + 1], vec![x + 1, y + 1]] {
                if q[0] * q[0] + q[1] * q[1] > r * r && !up.contains(&q) {
                    rec.add_outlier(&q, Side::Upper);
                    up.push(q);
                }
            }
            let q = vec![x, y - 1];
            rec.add_outlier(&q, Side::Lower);
            lo.push(q);
            let before = rec.stats();
            let got = rec.recognize();
            if rec.stats().float_runs > before.float_runs {
                // A GJK run decided: compare with the exact fallback, check the proof.
                assert_eq!(got, exact_outcome(&rec), "x0 {x0}, {} pixels", s.len());
                checked += 1;
                if got == Outcome::Described {
                    let c = rec.certificate().unwrap();
                    assert!(certificate_holds(basis.as_ref(), &c, &s, &up, &lo));
                } else {
                    let w = rec.witness().unwrap();
                    assert!(witness_holds(basis.as_ref(), w, &s, &up, &lo));
                }
            }
            if got != Outcome::Described {
                pieces += 1;
                rec.reset(&[x, y]);
                (s, up, lo) = Default::default();
                continue; // the same pixel starts the next piece
            }
            x += 1;
        }
        total += &rec.stats();
    }
    assert!(checked > 50, "{total:?}");
    assert!(
        total.whitened > 0,
        "the whitened coordinates were not needed: {total:?}"
    );
    assert_eq!(total.exact_fallbacks, 0, "{total:?}");
    assert_eq!(total.undecided, 0, "{total:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    /// Float runs in whitened coordinates alone, on banded instances (large enough to be
    /// whitened): every answer they prove is the exact fallback's, and checks.
    #[test]
    fn whitened_float_runs_agree_with_the_exact_fallback(
        model in prop_oneof![Just(Model::Line), Just(Model::Circle), Just(Model::Conic), Just(Model::Poly(3))],
        raw in proptest::collection::vec(-6i64..=6, 10),
        band in 1i64..40,
        flip in proptest::option::of(0usize..100),
    ) {
        let basis: Arc<dyn Basis> = Arc::new(model.basis());
        let coefs = &raw[..basis.dim()];
        prop_assume!(coefs.iter().any(|&c| c != 0));
        let (s, up, lo) = banded_instance(model, coefs, band, flip, 6);
        prop_assume!(!s.is_empty() && (!up.is_empty() || !lo.is_empty()));
        let mut r = Recognizer::new(basis.clone(), &s[0]).unwrap();
        s.iter().for_each(|p| r.add_inlier(p));
        up.iter().for_each(|p| r.add_outlier(p, Side::Upper));
        lo.iter().for_each(|p| r.add_outlier(p, Side::Lower));
        r.moments.catch_up(&r.inliers);
        let Some(map) = LinearMap::whitening(&r.moments) else {
            return Ok(());
        };
        let want = exact_outcome(&r);
        let sets = Sets { inliers: &r.inliers, upper: &r.upper, lower: &r.lower };
        let mut simplex = Simplex::default();
        let mut stats = Stats::default();
        let got = float_decide(
            sets,
            &map,
            &mut simplex,
            &r.max_abs,
            &mut stats,
            true,
            &mut FloatScratch::default(),
            &mut Meter::unlimited(),
        );
        match got {
            Some(FloatAnswer::Described(a, e)) => {
                prop_assert_eq!(want, Outcome::Described);
                let c = Certificate { origin: s[0].clone(), coefficients: a, extremes: e };
                prop_assert!(certificate_holds(basis.as_ref(), &c, &s, &up, &lo));
            }
            Some(FloatAnswer::NotDescribed(tags, weights)) => {
                prop_assert_eq!(want, Outcome::NotDescribed);
                r.reject(tags, weights);
                prop_assert!(witness_holds(basis.as_ref(), r.witness().unwrap(), &s, &up, &lo));
            }
            None => {}
        }
    }
}

/// The witness of an answer is the proof for the sets it was found in, even when it is
/// first asked for after a removal has renumbered the outliers it names.
#[test]
fn a_witness_outlives_the_removal_of_an_outlier() {
    let basis: Arc<dyn Basis> = Arc::new(Model::Line.basis());
    let s = vec![vec![0, 0], vec![4, 0]];
    // (2, 0) cannot be strictly above a line through the inliers; (10, 10) can, and goes
    // first, so removing it moves (2, 0) to its index.
    let up = vec![vec![10, 10], vec![2, 0]];
    let mut rec = Recognizer::new(basis.clone(), &s[0]).unwrap();
    for p in &s {
        rec.add_inlier(p);
    }
    for p in &up {
        rec.add_outlier(p, Side::Upper);
    }
    assert_eq!(rec.recognize(), Outcome::NotDescribed);
    assert!(rec.remove_outlier(&up[0], Side::Upper));
    let w = rec.witness().expect("the last answer's witness");
    assert!(witness_holds(basis.as_ref(), w, &s, &up, &[]));
    assert!(w.pairs.iter().all(|(_, o, _)| *o == up[1]));
}
