//! Unit tests of [`recognize_points`]: answers re-checked exactly here, errors named.

use super::*;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// The exact check of a witness, written again from its definition.
fn witness_holds(basis: &dyn Basis, w: &Witness) -> bool {
    let n = basis.dim();
    let lift = |p: &[i64]| {
        let rel: Vec<i64> = p.iter().zip(&w.origin).map(|(a, b)| a - b).collect();
        let mut f = vec![0; n];
        basis.lift(&rel, &mut f).unwrap();
        f
    };
    let mut sum = vec![BigRational::zero(); n];
    let mut total = BigRational::zero();
    for ((inl, out, side), weight) in w.pairs.iter().zip(w.exact_weights()) {
        if weight.is_negative() {
            return false;
        }
        total += weight;
        let (fi, fo) = (lift(inl), lift(out));
        for k in 0..n {
            let d = match side {
                Side::Upper => fo[k] - fi[k],
                Side::Lower => fi[k] - fo[k],
            };
            sum[k] += weight * BigRational::from_integer(d.into());
        }
    }
    !w.pairs.is_empty() && total.is_one() && sum.iter().all(Zero::is_zero)
}

/// The layer holds exactly: inliers within (bounds reached), outliers strictly outside.
fn layer_holds(basis: &dyn Basis, sets: &PointSets, l: &Layer) -> bool {
    let v = |p: &Vec<i64>| l.value(basis, p).unwrap();
    let values: Vec<BigInt> = sets.inliers.iter().map(v).collect();
    values.iter().all(|x| l.lower <= *x && *x <= l.upper)
        && values.contains(&l.lower)
        && values.contains(&l.upper)
        && sets.above.iter().all(|p| v(p) > l.upper)
        && sets.below.iter().all(|p| v(p) < l.lower)
}

/// A digital conic band: `lo ≤ f ≤ hi` inliers, the rest of a box split above and below.
fn band(f: impl Fn(i64, i64) -> i64, lo: i64, hi: i64, offset: i64) -> PointSets {
    let mut s = PointSets::default();
    for x in offset - 8..=offset + 8 {
        for y in offset - 8..=offset + 8 {
            let v = f(x, y);
            let p = vec![x, y];
            if v < lo {
                s.below.push(p);
            } else if v > hi {
                s.above.push(p);
            } else {
                s.inliers.push(p);
            }
        }
    }
    s
}

#[test]
fn a_digital_conic_is_described_far_from_the_origin_too() {
    for offset in [0, 1000, -70_000] {
        let o = offset;
        let sets = band(
            |x, y| (x - o).pow(2) + 2 * (y - o).pow(2) - 3 * (x - o),
            20,
            27,
            o,
        );
        let r = recognize_points(&sets, Model::Conic).unwrap();
        assert_eq!(
            r.counts,
            [sets.inliers.len(), sets.above.len(), sets.below.len()]
        );
        let PointsAnswer::Described { layer, local } = &r.answer else {
            panic!("{offset}: not described");
        };
        let basis = Model::Conic.basis();
        assert!(
            layer_holds(&basis, &sets, layer.as_ref().unwrap()),
            "{offset}"
        );
        assert!(sets.inliers.iter().all(|p| {
            let v = local.value(&basis, p).unwrap();
            local.extremes.lower <= v && v <= local.extremes.upper
        }));
        assert_eq!(r.basis.len(), 6);
    }
}

#[test]
fn a_set_that_no_line_describes_has_a_witness() {
    // A circle band is not a line band.
    let sets = band(|x, y| x * x + y * y, 20, 30, 0);
    let r = recognize_points(&sets, Model::Line).unwrap();
    let PointsAnswer::NotDescribed(w) = &r.answer else {
        panic!("described");
    };
    assert!(witness_holds(&Model::Line.basis(), w));
    // The circle model describes it.
    assert!(recognize_points(&sets, Model::Circle)
        .unwrap()
        .is_described());
}

#[test]
fn a_3d_ellipsoidal_layer_is_described_and_a_flipped_point_is_not() {
    let f = |x: i64, y: i64, z: i64| 4 * x * x + 9 * y * y + 16 * z * z;
    let mut sets = PointSets::default();
    for x in -8..=8 {
        for y in -6..=6 {
            for z in -5..=5 {
                let (v, p) = (f(x, y, z), vec![x, y, z]);
                match v {
                    ..=143 => sets.below.push(p),
                    144..=180 => sets.inliers.push(p),
                    _ => sets.above.push(p),
                }
            }
        }
    }
    let basis = Model::Quadric3.basis();
    let r = recognize_points(&sets, Model::Quadric3).unwrap();
    let PointsAnswer::Described { layer, .. } = &r.answer else {
        panic!("not described");
    };
    assert!(layer_holds(&basis, &sets, layer.as_ref().unwrap()));
    // A point of the layer's middle declared above: no quadric separates any more.
    let moved = sets.inliers.remove(sets.inliers.len() / 2);
    sets.above.push(moved);
    let r = recognize_points(&sets, Model::Quadric3).unwrap();
    let PointsAnswer::NotDescribed(w) = &r.answer else {
        panic!("described");
    };
    assert!(witness_holds(&basis, w));
}

/// Without outliers: the thinnest layer. For the triangle (0, 0), (5, 1), (2, 9) the
/// L∞-thinnest strip runs along the edge from (0, 0) to (2, 9): `9x − 2y`, range 43.
#[test]
fn without_outliers_the_thinnest_layer_answers() {
    let sets = PointSets::new(vec![vec![0, 0], vec![5, 1], vec![2, 9]]);
    let r = recognize_points(&sets, Model::Line).unwrap();
    assert!(r.is_described());
    let PointsAnswer::Thinnest(t) = &r.answer else {
        panic!("not the thinnest layer: {:?}", r.answer);
    };
    assert_eq!(t.thickness, BigRational::new(43.into(), 9.into()));
    let l = r.layer().unwrap();
    let basis = Model::Line.basis();
    assert!(layer_holds(&basis, &sets, l));
    assert_eq!(l.upper.clone() - &l.lower, BigInt::from(43));
    assert_eq!(t.work.programs, 2);
    assert_eq!(r.stats.queries, 0);
}

#[test]
fn bad_sets_are_errors_naming_the_point() {
    let msg = |sets: &PointSets, m: Model| match recognize_points(sets, m) {
        Err(Error::Points(s)) => s,
        other => panic!("{other:?}"),
    };
    assert!(msg(&PointSets::default(), Model::Line).contains("no inliers"));
    let flat = PointSets::new(vec![vec![1, 2]]).with_below(vec![vec![0, 0]]);
    let m = msg(&flat, Model::Quadric3);
    assert!(
        m.contains("inliers[0] has 2 coordinates") && m.contains("3-D"),
        "{m}"
    );
    let far = PointSets::new(vec![vec![0, 0]]).with_above(vec![vec![1 << 40, 0]]);
    let m = msg(&far, Model::Poly(2));
    assert!(m.contains("above[0]") && m.contains("overflows"), "{m}");
    // At the ends of the i64 range, the subtraction from the origin overflows first.
    let ends = PointSets::new(vec![vec![i64::MIN, 0], vec![i64::MAX, 0]]);
    assert!(msg(&ends.clone().with_above(vec![vec![0, 1]]), Model::Line).contains("overflows"));
    // Without outliers the thinnest layer is computed in big integers: no overflow.
    let r = recognize_points(&ends, Model::Poly(3)).unwrap();
    assert!(layer_holds(
        &Model::Poly(3).basis(),
        &ends,
        r.layer().unwrap()
    ));
}
