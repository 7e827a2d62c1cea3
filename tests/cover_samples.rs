//! The optimal cover on every bundled sample and model: never more pieces than the greedy
//! (contour by contour), the same cycles of points, pieces tiling each contour with exact
//! certificates checked here independently; and the CLI's `--cover` reaching the JSON.

use layertrace::{
    decompose, decompose_cover, load_path, piece_outliers, trace, Convention, Cover, LoadOptions,
    Model, OutlierRule, Outliers, Pixel, WorkBudget,
};
use std::path::Path;
use std::process::Command;

mod common;
use common::{samples, value};

/// True when `b` is `a` started at another point.
fn is_rotation(a: &[Pixel], b: &[Pixel]) -> bool {
    let n = a.len();
    n == b.len()
        && (n == 0
            || (0..n)
                .filter(|&s| a[s] == b[0])
                .any(|s| (0..n).all(|k| b[k] == a[(s + k) % n])))
}

#[test]
fn optimal_never_more_pieces_than_greedy_on_every_sample() {
    let mut totals = Vec::new();
    for path in samples() {
        let loaded = load_path(Path::new(&path), &LoadOptions::default()).unwrap();
        let contours = trace(&loaded.mask, Convention::Default);
        for model in [Model::Line, Model::Circle, Model::Conic] {
            let greedy = decompose(contours.clone(), model, OutlierRule::NotInPiece);
            let d = decompose_cover(
                contours.clone(),
                model,
                OutlierRule::NotInPiece,
                WorkBudget::default(),
                Cover::Optimal,
            );
            assert_eq!(d.cover, Cover::Optimal);
            assert_eq!(d.stats.undecided, 0, "{path} {model}");
            let basis = model.basis();
            for (k, (c, pieces)) in d.contours.iter().zip(&d.pieces).enumerate() {
                let n = c.points.len();
                assert!(
                    pieces.len() <= greedy.pieces[k].len(),
                    "{path} {model} contour {k}"
                );
                assert!(
                    is_rotation(&contours[k].points, &c.points),
                    "{path} {model}"
                );
                assert_eq!(pieces.first().map(|p| p.first), Some(0));
                assert_eq!(pieces.last().map(|p| p.last), Some(n - 1));
                for w in pieces.windows(2) {
                    assert_eq!(w[0].last + 1, w[1].first, "{path} {model}");
                }
                for p in pieces {
                    let cert = &p.certificate;
                    let first = &c.points[p.first];
                    assert_eq!(cert.origin, vec![first.x as i64, first.y as i64]);
                    let v = |q: Pixel| value(&basis, &cert.origin, &cert.coefficients, q);
                    let inl: Vec<i128> = c.points[p.first..=p.last].iter().map(|&q| v(q)).collect();
                    assert_eq!(
                        inl.iter().min(),
                        Some(&cert.extremes.lower),
                        "{path} {model}"
                    );
                    assert_eq!(
                        inl.iter().max(),
                        Some(&cert.extremes.upper),
                        "{path} {model}"
                    );
                    let Outliers { right, left } =
                        piece_outliers(&c.points, p.first, p.last, OutlierRule::NotInPiece);
                    assert!(
                        right.iter().all(|&q| v(q) > cert.extremes.upper),
                        "{path} {model}"
                    );
                    assert!(
                        left.iter().all(|&q| v(q) < cert.extremes.lower),
                        "{path} {model}"
                    );
                }
            }
            totals.push((path.clone(), model, greedy.piece_count(), d.piece_count()));
        }
    }
    for (path, model, g, o) in &totals {
        eprintln!("{path} {model}: greedy {g}, optimal {o}");
    }
    // The optimal cover is not always the greedy's: somewhere it saves pieces.
    assert!(totals.iter().any(|(_, _, g, o)| o < g));
}

#[test]
fn cli_cover_reaches_the_json() {
    let bin = env!("CARGO_BIN_EXE_layertrace");
    for cover in ["greedy", "optimal"] {
        let out = Command::new(bin)
            .args([
                "samples/glyph_g_liberationserif_cap120.png",
                "--json",
                "-",
                "--cover",
                cover,
                "-q",
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["cover"], cover);
    }
    let out = Command::new(bin)
        .args([
            "samples/glyph_g_liberationserif_cap120.png",
            "--cover",
            "best",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
