//! Tests of [`contour_path`]: exact in tiny-skia, on the grid, no staircases.

use super::*;
use crate::bitmap::Mask;
use crate::contour::{trace, Convention};
use crate::curve::PathCommand;
use crate::decompose::{decompose, OutlierRule};
use crate::model::Model;
use proptest::prelude::*;

/// True when `path` is made of horizontal and vertical lines between whole-pixel corners:
/// no pixel centre can lie on it, and renderers draw it exactly.
fn exact_by_construction(path: &ContourPath) -> bool {
    let mut pen = path.start;
    let whole = |p: kurbo::Point| p.x.fract() == 0.0 && p.y.fract() == 0.0;
    whole(pen)
        && path.commands.iter().all(|c| match *c {
            PathCommand::Line(p) => {
                let ok = whole(p) && (p.x == pen.x || p.y == pen.y);
                pen = p;
                ok
            }
            _ => false,
        })
}

/// Misplaced points of every contour of `mask` drawn with `model` on `grid`, and the
/// number of points off the grid.
fn check(mask: &Mask, model: Model, grid: u8) -> (usize, usize) {
    let d = decompose(
        trace(mask, Convention::Default),
        model,
        OutlierRule::NotInPiece,
    );
    let basis = d.model.basis();
    let opts = OutlineOptions {
        grid,
        ..OutlineOptions::default()
    };
    let scale = f64::from(1u32 << grid);
    let off =
        |p: kurbo::Point| usize::from((p.x * scale).fract() != 0.0 || (p.y * scale).fract() != 0.0);
    let (mut bad, mut off_grid) = (0, 0);
    for (c, pieces) in d.contours.iter().zip(&d.pieces) {
        let cp = contour_path(c, pieces, &basis, &opts);
        if cp.commands.is_empty() {
            continue;
        }
        off_grid += off(cp.start);
        for cmd in &cp.commands {
            off_grid += match *cmd {
                PathCommand::Line(p) => off(p),
                PathCommand::Quad(a, p) => off(a) + off(p),
                PathCommand::Cubic(a, b, p) => off(a) + off(b) + off(p),
                PathCommand::Arc(_) => 1,
            };
        }
        let reference = cracks_path(&c.points);
        let reference = Reference::new(reference.start, &reference.commands);
        bad += misplaced_pixels(
            &reference,
            cp.start,
            &cp.commands,
            EdgeClipping::Unknown,
            None,
        )
        .len();
    }
    (bad, off_grid)
}

/// The path of the first contour of `mask` decomposed with `model`, default options.
fn first_path(mask: &Mask, model: Model) -> ContourPath {
    first_path_with(mask, model, &OutlineOptions::default())
}

/// The path of the first contour of `mask` decomposed with `model`, drawn with `opts`.
fn first_path_with(mask: &Mask, model: Model, opts: &OutlineOptions) -> ContourPath {
    let d = decompose(
        trace(mask, Convention::Default),
        model,
        OutlierRule::NotInPiece,
    );
    contour_path(&d.contours[0], &d.pieces[0], &d.model.basis(), opts)
}

#[test]
fn single_pixel_is_a_diamond() {
    let mask = Mask::from_ascii("...\n.#.\n...");
    let cp = first_path(&mask, Model::Line);
    // Its square (along its cracks), with the corners cut: the diamond through the middles
    // of its sides, which keeps the same pixel centres inside.
    let mut corners: Vec<(f64, f64)> = cp.commands.iter().map(|c| (c.end().x, c.end().y)).collect();
    corners.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(corners, [(1.0, 1.5), (1.5, 1.0), (1.5, 2.0), (2.0, 1.5)]);
    assert_eq!(check(&mask, Model::Line, 4), (0, 0));
    assert!(!has_staircase(cp.start, &cp.commands));
}

#[test]
fn square_corners_keep_the_pixel_square() {
    let opts = OutlineOptions {
        square_corners: true,
        ..OutlineOptions::default()
    };
    let cp = first_path_with(&Mask::from_ascii("...\n.#.\n..."), Model::Line, &opts);
    assert_eq!(cp.start, kurbo::Point::new(2.0, 1.0));
    assert_eq!(cp.commands.len(), 4);
    assert!(exact_by_construction(&cp));
}

#[test]
fn disc_is_exact() {
    let mut rows = String::new();
    for y in 0..40 {
        for x in 0..40 {
            let (dx, dy) = (f64::from(x) - 19.3, f64::from(y) - 20.1);
            rows.push(if dx * dx + dy * dy < 15.2 * 15.2 {
                '#'
            } else {
                '.'
            });
        }
        rows.push('\n');
    }
    let mask = Mask::from_ascii(&rows);
    for model in [Model::Circle, Model::Conic, Model::Line] {
        for grid in [2, 4, 6] {
            assert_eq!(check(&mask, model, grid), (0, 0), "{model} grid {grid}");
        }
    }
    // Arcs are written as cubics.
    assert_eq!(first_path(&mask, Model::Circle).counts().arc, 0);
}

#[test]
fn bad_pieces_fall_back_to_cracks() {
    let mask = Mask::from_ascii("##\n##");
    let mut d = decompose(
        trace(&mask, Convention::Default),
        Model::Line,
        OutlierRule::NotInPiece,
    );
    let basis = d.model.basis();
    for p in d.pieces[0].iter_mut() {
        p.last += 7;
    }
    let cp = exact_path(
        &d.contours[0],
        &d.pieces[0],
        &basis,
        &OutlineOptions::default(),
        &mut None,
        &mut None,
    );
    assert_eq!(cp.fallbacks.invalid_pieces, 1);
    assert!(exact_by_construction(&cp));
    // Drawn: the square with its corners cut, no staircase.
    let drawn = contour_path(
        &d.contours[0],
        &d.pieces[0],
        &basis,
        &OutlineOptions::default(),
    );
    let mut pen = drawn.start;
    let mut diagonals = 0;
    for c in &drawn.commands {
        let d = c.end() - pen;
        diagonals += usize::from(d.x != 0.0 && d.y != 0.0);
        pen = c.end();
    }
    assert_eq!(diagonals, 4, "{:?}", drawn.commands);
    assert!(!has_staircase(drawn.start, &drawn.commands));
    let empty = Contour {
        points: Vec::new(),
        hole: false,
        closed: true,
    };
    assert!(
        contour_path(&empty, &[], &basis, &OutlineOptions::default())
            .commands
            .is_empty()
    );
}

fn small_mask() -> impl Strategy<Value = Mask> {
    (
        3u32..14,
        3u32..14,
        prop::collection::vec(any::<bool>(), 14 * 14),
    )
        .prop_map(|(w, h, bits)| {
            let mut m = Mask::new(w, h);
            for y in 0..h {
                for x in 0..w {
                    m.set(i64::from(x), i64::from(y), bits[(y * 14 + x) as usize]);
                }
            }
            m
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// Every contour's path, filled by tiny-skia, paints its pixels and not the background
    /// beside them, with every point on the grid, for every model.
    #[test]
    fn exact_in_tiny_skia(mask in small_mask(), grid in 0u8..=6) {
        for model in [Model::Line, Model::Circle, Model::Conic] {
            prop_assert_eq!(check(&mask, model, grid), (0, 0), "{}", model);
        }
    }

    /// No contour's path has a pixel staircase, on grids fine enough for the half-pixel
    /// cuts of its corners, whatever the one-pixel features of the input.
    #[test]
    fn no_staircases(mask in small_mask(), grid in 1u8..=6) {
        let d = decompose(trace(&mask, Convention::Default), Model::Conic, OutlierRule::NotInPiece);
        let basis = d.model.basis();
        let opts = OutlineOptions { grid, ..OutlineOptions::default() };
        for (c, pieces) in d.contours.iter().zip(&d.pieces) {
            let cp = contour_path(c, pieces, &basis, &opts);
            prop_assert!(!has_staircase(cp.start, &cp.commands), "{:?}", cp.commands);
        }
    }
}
