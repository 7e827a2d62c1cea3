//! The optimal cover on every bundled sample and model: never more pieces than the greedy
//! (contour by contour), the same cycles of points, pieces tiling each contour with exact
//! certificates checked here independently; and the CLI's `--cover` reaching the JSON.

use layertrace::{
    decompose, decompose_cover, load_path, trace, Convention, Cover, LoadOptions, Model,
    OutlierRule, Pixel, WorkBudget,
};
use std::path::Path;

mod common;
use common::{check_pieces, samples};

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
                assert!(
                    pieces.len() <= greedy.pieces[k].len(),
                    "{path} {model} contour {k}"
                );
                assert!(
                    is_rotation(&contours[k].points, &c.points),
                    "{path} {model}"
                );
                check_pieces(&basis, c, pieces, &format!("{path} {model}"));
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
    for cover in ["greedy", "optimal"] {
        let out = common::bin()
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
    let out = common::bin()
        .args([
            "samples/glyph_g_liberationserif_cap120.png",
            "--cover",
            "best",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
