//! Random bitmaps up to 64×64 (noise, blobs, thin lines, checkerboards) through the whole
//! pipeline with every model: no panic, every certificate holds, every boundary pixel is in
//! a piece, the SVG parses and rasterizes, and its fidelity is measured.

use layertrace::{
    decompose, fidelity, piece_outliers, svg_document, trace, Convention, Mask, Model, OutlierRule,
    Outliers, Pixel, SvgOptions,
};
use proptest::prelude::*;
use std::collections::HashSet;

#[derive(Clone, Debug)]
enum Pattern {
    Noise {
        density: u8,
        seed: u64,
    },
    Blobs(Vec<(i32, i32, i32, bool)>),
    Lines(Vec<(i32, i32, i32, i32)>),
    Checker {
        cell: u32,
        x0: u32,
        y0: u32,
        x1: u32,
        y1: u32,
    },
}

fn pattern() -> impl Strategy<Value = Pattern> {
    prop_oneof![
        (0u8..=255, any::<u64>()).prop_map(|(density, seed)| Pattern::Noise { density, seed }),
        proptest::collection::vec((0i32..64, 0i32..64, 1i32..14, any::<bool>()), 1..6)
            .prop_map(Pattern::Blobs),
        proptest::collection::vec((0i32..64, 0i32..64, 0i32..64, 0i32..64), 1..5)
            .prop_map(Pattern::Lines),
        (1u32..4, 0u32..30, 0u32..30, 30u32..64, 30u32..64).prop_map(|(cell, x0, y0, x1, y1)| {
            Pattern::Checker {
                cell,
                x0,
                y0,
                x1,
                y1,
            }
        }),
    ]
}

fn render(p: &Pattern, w: u32, h: u32) -> Mask {
    let mut m = Mask::new(w, h);
    match p {
        Pattern::Noise { density, seed } => {
            let mut s = *seed | 1;
            for y in 0..h {
                for x in 0..w {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    m.set(x.into(), y.into(), (s & 0xff) < u64::from(*density));
                }
            }
        }
        Pattern::Blobs(v) => {
            for &(cx, cy, r, square) in v {
                for y in cy - r..=cy + r {
                    for x in cx - r..=cx + r {
                        let inside = square || (x - cx).pow(2) + (y - cy).pow(2) <= r * r;
                        if inside {
                            m.set(x.into(), y.into(), true);
                        }
                    }
                }
            }
        }
        Pattern::Lines(v) => {
            for &(x0, y0, x1, y1) in v {
                let n = (x1 - x0).abs().max((y1 - y0).abs()).max(1);
                for k in 0..=n {
                    let x = x0 + (x1 - x0) * k / n;
                    let y = y0 + (y1 - y0) * k / n;
                    m.set(x.into(), y.into(), true);
                }
            }
        }
        Pattern::Checker {
            cell,
            x0,
            y0,
            x1,
            y1,
        } => {
            for y in *y0..(*y1).min(h) {
                for x in *x0..(*x1).min(w) {
                    m.set(x.into(), y.into(), (x / cell + y / cell) % 2 == 0);
                }
            }
        }
    }
    m
}

fn boundary_pixels(m: &Mask) -> HashSet<Pixel> {
    let mut s = HashSet::new();
    for y in 0..i64::from(m.height()) {
        for x in 0..i64::from(m.width()) {
            if m.get(x, y)
                && (!m.get(x + 1, y) || !m.get(x - 1, y) || !m.get(x, y + 1) || !m.get(x, y - 1))
            {
                s.insert(Pixel::new(x as i32, y as i32));
            }
        }
    }
    s
}

/// The properties of the module doc on one bitmap.
fn check(p: &Pattern, w: u32, h: u32) -> Result<(), TestCaseError> {
    let mask = render(p, w, h);
    let contours = trace(&mask, Convention::Default);
    let mut covered = HashSet::new();
    for model in [Model::Line, Model::Circle, Model::Conic, Model::Poly(3)] {
        let d = decompose(contours.clone(), model, OutlierRule::NotInPiece);
        prop_assert_eq!(d.stats.undecided, 0);
        let basis = model.basis();
        for (c, pieces) in d.contours.iter().zip(&d.pieces) {
            for piece in pieces {
                let cert = &piece.certificate;
                let v = |q: &Pixel| cert.value(&basis, &[q.x as i64, q.y as i64]).unwrap();
                for q in &c.points[piece.first..=piece.last] {
                    prop_assert!(cert.extremes.lower <= v(q) && v(q) <= cert.extremes.upper);
                    covered.insert(*q);
                }
                let Outliers { right: r, left: l } =
                    piece_outliers(&c.points, piece.first, piece.last, OutlierRule::NotInPiece);
                prop_assert!(r.iter().all(|q| v(q) > cert.extremes.upper));
                prop_assert!(l.iter().all(|q| v(q) < cert.extremes.lower));
            }
        }
        let out = svg_document(&d, w, h, &SvgOptions::default());
        let report = fidelity(&out.svg, &mask).expect("the SVG parses and rasterizes");
        prop_assert_eq!(report.foreground, mask.count_foreground());
        prop_assert!(report.differing <= report.foreground + u64::from(w) * u64::from(h));
        prop_assert!(out.max_fit_error <= 0.05 + 1e-9);
    }
    prop_assert_eq!(covered, boundary_pixels(&mask));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn whole_pipeline(p in pattern(), w in 1u32..=64, h in 1u32..=64) {
        check(&p, w, h)?;
    }
}

/// Inputs on which `whole_pipeline` once failed, checked on every run.
#[test]
fn past_failures() {
    // poly:3: a trace step jumped the 0.1 px gap between two branches by a saddle, and its
    // cubic was accepted with a fit error of 0.32 px (tolerance 0.05).
    let cases = [(
        Pattern::Noise {
            density: 126,
            seed: 14661649786248384942,
        },
        54,
        15,
    )];
    for (p, w, h) in cases {
        check(&p, w, h).unwrap_or_else(|e| panic!("{p:?} {w}x{h}: {e}"));
    }
}
