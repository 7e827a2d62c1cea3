//! Lists the differing pixels of one image and model with the nearest contour point and
//! whether it is at a piece end: `cargo run --release --example diff_detail -- FILE MODEL`.

use layertrace::{
    decompose, load_path, piece_kind, rasterize_svg, svg_document, trace, Convention, LoadOptions,
    Model, OutlierRule, SvgOptions,
};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let file = PathBuf::from(args.get(1).ok_or("file")?);
    let model: Model = args.get(2).ok_or("model")?.parse()?;
    let mask = load_path(&file, &LoadOptions::default())?.mask;
    let d = decompose(
        trace(&mask, Convention::Default),
        model,
        OutlierRule::NotInPiece,
    );
    let out = svg_document(&d, mask.width(), mask.height(), &SvgOptions::default());
    let actual = rasterize_svg(&out.svg, mask.width(), mask.height())?;
    let basis = model.basis();
    let (mut at_end, mut mid) = (0, 0);
    for y in 0..i64::from(mask.height()) {
        for x in 0..i64::from(mask.width()) {
            let (e, a) = (mask.get(x, y), actual.get(x, y));
            if e == a {
                continue;
            }
            // nearest contour point (Chebyshev)
            let mut best = (i64::MAX, 0, 0);
            for (ci, c) in d.contours.iter().enumerate() {
                for (pi, p) in c.points.iter().enumerate() {
                    let dd = (i64::from(p.x) - x).abs().max((i64::from(p.y) - y).abs());
                    if dd < best.0 {
                        best = (dd, ci, pi);
                    }
                }
            }
            let (dd, ci, pi) = best;
            let pieces = &d.pieces[ci];
            let n = d.contours[ci].points.len();
            let (k, piece) = pieces
                .iter()
                .enumerate()
                .find(|(_, p)| p.first <= pi && pi <= p.last)
                .ok_or("piece")?;
            let from_end = (pi - piece.first).min(piece.last - pi);
            if from_end <= 1 {
                at_end += 1;
            } else {
                mid += 1;
            }
            let cert = &piece.certificate;
            let dist = layertrace::level_polynomial(&basis, cert, layertrace::boundary_level(cert))
                .map(|poly| {
                    let c = kurbo::Point::new(x as f64 + 0.5, y as f64 + 0.5);
                    poly.eval(c) / poly.gradient(c).hypot()
                })
                .unwrap_or(f64::NAN);
            println!(
                "dist {dist:.5} {} ({x},{y}) contour {ci} (n={n}, hole {}) point {pi} d={dd} piece {k}/{} [{}..{}] {} from_end {from_end}",
                if e { "MISSING" } else { "EXTRA" },
                d.contours[ci].hole,
                pieces.len(),
                piece.first,
                piece.last,
                piece_kind(&basis, &piece.certificate).name(),
            );
        }
    }
    println!("near piece ends: {at_end}, mid-piece: {mid}");
    Ok(())
}
