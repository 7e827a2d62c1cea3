//! Tests of the optimal cover: minimality against a brute force over every set of cuts,
//! each piece checked on its own with a fresh [`Recognizer`]; exact certificates; never
//! more pieces than the greedy.

use super::*;
use crate::bitmap::Mask;
use crate::contour::{trace, Convention};
use crate::recognize::Outcome;
use proptest::prelude::*;

/// The points `first..=last` of the cycle `points` (indices taken mod `n`) as a chain.
fn chain(points: &[Pixel], first: usize, last: usize) -> Vec<Pixel> {
    (first..=last).map(|k| points[k % points.len()]).collect()
}

/// Whether the chain `piece` is described, asked of a recognizer made for it alone.
fn described_alone(basis: &Arc<dyn Basis>, piece: &[Pixel], rule: OutlierRule) -> bool {
    if piece.len() <= 2 {
        return true;
    }
    let Outliers { right, left } = piece_outliers(piece, 0, piece.len() - 1, rule);
    let mut rec = Recognizer::new(basis.clone(), &xy(piece[0])).unwrap();
    for p in piece {
        rec.add_inlier(&xy(*p));
    }
    for q in &right {
        rec.add_outlier(&xy(*q), crate::recognize::Side::Upper);
    }
    for q in &left {
        rec.add_outlier(&xy(*q), crate::recognize::Side::Lower);
    }
    match rec.recognize() {
        Outcome::Described => true,
        Outcome::NotDescribed => false,
        o => panic!("undecided brute force: {o:?}"),
    }
}

/// `grown[i][l]`: the piece of `l` points from `i` (`1 ≤ l ≤ n`, wrapping if `closed`,
/// else `i + l ≤ n`) has every prefix described.
fn grown_table(
    basis: &Arc<dyn Basis>,
    points: &[Pixel],
    closed: bool,
    rule: OutlierRule,
) -> Vec<Vec<bool>> {
    let n = points.len();
    (0..n)
        .map(|i| {
            let mut row = vec![false; n + 1];
            let max = if closed { n } else { n - i };
            for l in 1..=max {
                row[l] = (l == 1 || row[l - 1])
                    && described_alone(basis, &chain(points, i, i + l - 1), rule);
            }
            row
        })
        .collect()
}

/// The fewest grown pieces covering the contour, over every set of cuts (a cut at `c`
/// starts a piece at point `c`; an open contour has a cut at 0).
fn brute_force_minimum(grown: &[Vec<bool>], closed: bool) -> usize {
    let n = grown.len();
    let mut best = usize::MAX;
    for set in 1u32..(1 << n) {
        if !closed && set & 1 == 0 {
            continue;
        }
        let cuts: Vec<usize> = (0..n).filter(|&c| set & (1 << c) != 0).collect();
        if cuts.len() >= best {
            continue;
        }
        let ok = cuts.iter().enumerate().all(|(k, &c)| {
            let next = match cuts.get(k + 1) {
                Some(&d) => d,
                None if closed => cuts[0] + n,
                None => n,
            };
            grown[c][next - c]
        });
        if ok {
            best = cuts.len();
        }
    }
    best
}

/// Checks the pieces of a rotated contour: they tile it from 0, each is grown (fresh
/// recognizers) and carries an exact certificate with its origin at its first point.
fn check_cover(basis: &Arc<dyn Basis>, pts: &[Pixel], pieces: &[Piece], rule: OutlierRule) {
    assert_eq!(pieces.first().map(|p| p.first), Some(0));
    assert_eq!(pieces.last().map(|p| p.last), Some(pts.len() - 1));
    for w in pieces.windows(2) {
        assert_eq!(w[0].last + 1, w[1].first);
    }
    for p in pieces {
        for last in p.first..=p.last {
            assert!(
                described_alone(basis, &pts[p.first..=last], rule),
                "prefix {}..={last} of piece {p:?}",
                p.first
            );
        }
        let c = &p.certificate;
        assert_eq!(c.origin, xy(pts[p.first]).to_vec());
        let v = |q: Pixel| c.value(basis.as_ref(), &xy(q)).unwrap();
        for q in &pts[p.first..=p.last] {
            assert!(
                c.extremes.lower <= v(*q) && v(*q) <= c.extremes.upper,
                "inlier {q:?} of {p:?}"
            );
        }
        let Outliers { right, left } = piece_outliers(pts, p.first, p.last, rule);
        assert!(
            right.iter().all(|&q| v(q) > c.extremes.upper),
            "right outliers of {p:?}"
        );
        assert!(
            left.iter().all(|&q| v(q) < c.extremes.lower),
            "left outliers of {p:?}"
        );
    }
}

/// Optimal, greedy and brute-force counts of one contour; checks the optimal pieces.
fn compare(
    points: &[Pixel],
    closed: bool,
    model: Model,
    rule: OutlierRule,
) -> (usize, usize, usize) {
    let basis: Arc<dyn Basis> = Arc::new(model.basis());
    let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
    let greedy = decompose_points(points, &mut rec, rule);
    let (s, pieces) = optimal_points(points, closed, &mut rec, rule, WorkBudget::default());
    assert!(closed || s == 0);
    let mut rotated = points.to_vec();
    rotated.rotate_left(s);
    check_cover(&basis, &rotated, &pieces, rule);
    let brute = brute_force_minimum(&grown_table(&basis, points, closed, rule), closed);
    (pieces.len(), greedy.len(), brute)
}

/// Masks of at most 6 × 5 pixels, about two thirds foreground: contours of up to about 18
/// points.
fn tiny_mask() -> impl Strategy<Value = Mask> {
    (2u32..7, 2u32..6, prop::collection::vec(0u8..3, 30)).prop_map(|(w, h, bits)| {
        let mut m = Mask::new(w, h);
        for y in 0..h {
            for x in 0..w {
                m.set(i64::from(x), i64::from(y), bits[(y * 6 + x) as usize] > 0);
            }
        }
        m
    })
}

/// Contours of at most this many points are brute-forced (2^n sets of cuts).
const BRUTE_MAX: usize = 18;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    /// On every contour of a small random mask, in every model: the optimal cover has the
    /// fewest grown pieces of all covers (brute force over all sets of cuts, the first cut
    /// anywhere), and no more than the greedy's.
    #[test]
    fn optimal_is_minimal_by_brute_force(mask in tiny_mask(), ipol in any::<bool>()) {
        let (convention, rule) = if ipol {
            (Convention::Ipol, OutlierRule::Any)
        } else {
            (Convention::Default, OutlierRule::NotInPiece)
        };
        for c in trace(&mask, convention) {
            if c.points.len() > BRUTE_MAX {
                continue;
            }
            for model in [Model::Line, Model::Circle, Model::Conic] {
                let (optimal, greedy, brute) = compare(&c.points, wraps(&c), model, rule);
                prop_assert_eq!(optimal, brute, "{} {:?}", model, c.points);
                prop_assert!(optimal <= greedy, "{} {:?}", model, c.points);
            }
        }
    }
}

/// Masks of up to 12 × 12 pixels, about two thirds foreground.
fn small_mask() -> impl Strategy<Value = Mask> {
    (3u32..13, 3u32..13, prop::collection::vec(0u8..3, 144)).prop_map(|(w, h, bits)| {
        let mut m = Mask::new(w, h);
        for y in 0..h {
            for x in 0..w {
                m.set(i64::from(x), i64::from(y), bits[(y * 12 + x) as usize] > 0);
            }
        }
        m
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]
    /// The sweep's bounds hold the reach of a growth started afresh at every start, exactly
    /// where it says so and everywhere once every start is settled; its greedy pieces are
    /// the greedy's.
    #[test]
    fn reach_is_fresh_growth(mask in small_mask(), ipol in any::<bool>()) {
        let (convention, rule) = if ipol {
            (Convention::Ipol, OutlierRule::Any)
        } else {
            (Convention::Default, OutlierRule::NotInPiece)
        };
        for c in trace(&mask, convention) {
            let (pts, n, closed) = (&c.points, c.points.len(), wraps(&c));
            for model in [Model::Line, Model::Circle, Model::Conic] {
                let basis: Arc<dyn Basis> = Arc::new(model.basis());
                let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
                let budget = WorkBudget::default();
                let mut r = super::reach::Reach::new(pts, closed, &mut rec, rule, budget);
                prop_assert_eq!(&r.greedy, &decompose_points(pts, &mut rec, rule));
                let mut w = window::Window::new(pts, rule);
                let fresh: Vec<usize> = (0..n)
                    .map(|i| {
                        let mut cert = w.begin(&mut rec, i);
                        let cap = if closed { i + n - 1 } else { n - 1 };
                        w.grow(&mut rec, cap, budget, &mut cert);
                        w.last
                    })
                    .collect();
                let (low, up) = (r.lower(), r.upper());
                for i in 0..n {
                    prop_assert!(low[i] <= fresh[i] && fresh[i] <= up[i],
                        "start {} of {}: {} <= {} <= {} {:?}", i, model, low[i], fresh[i], up[i], pts);
                    if r.is_exact(i) {
                        prop_assert_eq!(low[i], up[i]);
                    }
                }
                for i in 0..n {
                    let low = r.lower();
                    r.settle(i, low[i], &mut rec);
                }
                prop_assert_eq!(r.lower(), fresh.clone(), "{} {:?}", model, pts);
                prop_assert_eq!(r.upper(), fresh, "{} {:?}", model, pts);
            }
        }
    }
}

/// The border of a filled square from the middle of a side: the greedy needs a fifth piece
/// for the side it started in; the optimal cover cuts at a corner.
#[test]
fn square_from_mid_side() {
    let mut m = Mask::new(12, 12);
    for y in 2..10 {
        for x in 2..10 {
            m.set(x, y, true);
        }
    }
    let c = trace(&m, Convention::Default).remove(0);
    let mut pts = c.points.clone();
    pts.rotate_left(3);
    let (optimal, greedy, _) = {
        let basis: Arc<dyn Basis> = Arc::new(Model::Line.basis());
        let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
        let greedy = decompose_points(&pts, &mut rec, OutlierRule::NotInPiece);
        let (s, pieces) = optimal_points(
            &pts,
            true,
            &mut rec,
            OutlierRule::NotInPiece,
            WorkBudget::default(),
        );
        let mut rotated = pts.clone();
        rotated.rotate_left(s);
        check_cover(&basis, &rotated, &pieces, OutlierRule::NotInPiece);
        (pieces.len(), greedy.len(), s)
    };
    assert_eq!((optimal, greedy), (4, 5));
}

/// The decomposition rotates the contours whose cover starts elsewhere, and says which
/// cover it used.
#[test]
fn decomposition_rotates_and_names_the_cover() {
    let mut m = Mask::new(30, 30);
    for y in 0..30i64 {
        for x in 0..30i64 {
            m.set(x, y, (x - 14) * (x - 14) + (y - 15) * (y - 15) * 2 <= 120);
        }
    }
    for model in [Model::Line, Model::Circle, Model::Conic] {
        let contours = trace(&m, Convention::Default);
        let greedy = decompose(contours.clone(), model, OutlierRule::NotInPiece);
        let d = decompose_cover(
            contours.clone(),
            model,
            OutlierRule::NotInPiece,
            WorkBudget::default(),
            Cover::Optimal,
        );
        assert_eq!(d.cover, Cover::Optimal);
        assert!(d.piece_count() <= greedy.piece_count());
        let basis: Arc<dyn Basis> = Arc::new(model.basis());
        for ((c, pieces), original) in d.contours.iter().zip(&d.pieces).zip(&contours) {
            // The same cycle.
            let n = c.points.len();
            let s = (0..n)
                .find(|&s| (0..n).all(|k| c.points[k] == original.points[(k + s) % n]))
                .expect("a rotation of the traced contour");
            let _ = s;
            check_cover(&basis, &c.points, pieces, OutlierRule::NotInPiece);
        }
    }
}
