//! The work budget of the greedy (issue 13): pieces cut by the budget keep exact
//! certificates, the cut is recorded (piece, statistics, JSON), and the decomposition stays
//! the same whatever the number of threads.

use layertrace::{
    decompose, decompose_within, decomposition_json, piece_outliers, trace, Convention, Cut,
    Decomposition, JsonHeader, Mask, Model, OutlierRule, Outliers, Pixel, WorkBudget,
};

mod common;
use common::value;

/// `n × n` pixels, each foreground with probability 1/2 (xorshift, fixed seed).
fn noise(n: u32, seed: u64) -> Mask {
    let mut s = seed;
    let bits: Vec<bool> = (0..n * n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s >> 63 == 1
        })
        .collect();
    Mask::from_fn(n, n, |x, y| bits[(y * n + x) as usize])
}

/// Every piece tiles its contour and its certificate holds exactly on its own sets.
fn check_certificates(d: &Decomposition) {
    let basis = d.model.basis();
    for (c, pieces) in d.contours.iter().zip(&d.pieces) {
        assert_eq!(pieces.first().map(|p| p.first), Some(0));
        assert_eq!(pieces.last().map(|p| p.last), Some(c.points.len() - 1));
        for w in pieces.windows(2) {
            assert_eq!(w[0].last + 1, w[1].first);
        }
        for p in pieces {
            let cert = &p.certificate;
            let v = |q: Pixel| value(&basis, &cert.origin, &cert.coefficients, q);
            let inl: Vec<i128> = c.points[p.first..=p.last].iter().map(|&q| v(q)).collect();
            assert_eq!(inl.iter().min(), Some(&cert.extremes.lower), "{p:?}");
            assert_eq!(inl.iter().max(), Some(&cert.extremes.upper), "{p:?}");
            let Outliers { right, left } = piece_outliers(&c.points, p.first, p.last, d.rule);
            assert!(
                right.iter().all(|&q| v(q) > cert.extremes.upper),
                "{p:?} right"
            );
            assert!(
                left.iter().all(|&q| v(q) < cert.extremes.lower),
                "{p:?} left"
            );
            // A cut piece is never the last one of its contour.
            if p.cut.is_some() {
                assert!(p.last + 1 < c.points.len());
            }
        }
    }
}

fn budget_cuts(d: &Decomposition) -> usize {
    d.pieces
        .iter()
        .flatten()
        .filter(|p| p.cut == Some(Cut::Budget))
        .count()
}

fn run(mask: &Mask, model: Model, budget: WorkBudget) -> Decomposition {
    decompose_within(
        trace(mask, Convention::Default),
        model,
        OutlierRule::NotInPiece,
        budget,
    )
}

/// On noise, poly:6 needs the exact fallback (dimension 27, about 20 ms an iteration) for
/// some pieces: the default budget cuts them, and every certificate still holds.
#[test]
fn default_budget_cuts_poly6_on_noise_and_certificates_hold() {
    let mask = noise(24, 2014);
    let d = decompose(
        trace(&mask, Convention::Default),
        Model::Poly(6),
        OutlierRule::NotInPiece,
    );
    check_certificates(&d);
    let cuts = budget_cuts(&d);
    assert!(cuts > 0, "no piece cut by the budget");
    assert_eq!(d.stats.over_budget as usize, cuts);
    assert_eq!(d.stats.undecided, 0);
    // The JSON names each cut piece.
    let header = JsonHeader {
        width: 24,
        height: 24,
        threshold: 128,
        invert: false,
    };
    let json = decomposition_json(&d, &header);
    let v: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    let cut_in_json = v["contours"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c["pieces"].as_array().unwrap())
        .filter(|s| s["cut"] == "budget")
        .count();
    assert_eq!(cut_in_json, cuts);
}

/// A budget of nothing: every solve is refused, so every piece is as long as the previous
/// certificate allowed, and still exact; with more budget the pieces are never more.
#[test]
fn tiny_budgets_cut_more_and_stay_exact() {
    let mask = noise(20, 7);
    for model in [Model::Line, Model::Conic, Model::Poly(4)] {
        let none = run(
            &mask,
            model,
            WorkBudget {
                base: 0,
                per_point: 0,
            },
        );
        check_certificates(&none);
        assert!(budget_cuts(&none) > 0, "{model}");
        let some = run(
            &mask,
            model,
            WorkBudget {
                base: 200_000,
                per_point: 0,
            },
        );
        check_certificates(&some);
        let all = run(&mask, model, WorkBudget::UNLIMITED);
        check_certificates(&all);
        assert_eq!(budget_cuts(&all), 0, "{model}");
        assert!(
            budget_cuts(&some) <= budget_cuts(&none),
            "{model}: {} cuts with some budget, {} with none",
            budget_cuts(&some),
            budget_cuts(&none)
        );
    }
}

/// The budget counts work, not time: one, two and four threads give the same pieces.
#[test]
fn budget_cuts_do_not_depend_on_threads() {
    let mask = noise(32, 99);
    let budget = WorkBudget {
        base: 20_000,
        per_point: 1_000,
    };
    let runs: Vec<Decomposition> = [1, 2, 4]
        .iter()
        .map(|&t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
                .install(|| run(&mask, Model::Poly(4), budget))
        })
        .collect();
    assert!(budget_cuts(&runs[0]) > 0);
    for r in &runs[1..] {
        assert_eq!(r.pieces, runs[0].pieces);
        assert_eq!(r.stats, runs[0].stats);
    }
}
