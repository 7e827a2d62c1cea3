//! Time per stage on the adversarial inputs of issue 13 (checkerboard of single pixels,
//! 50 % noise, one-pixel-wide spirals of growing size), one thread. Prints a markdown table:
//! contour points, pieces, milliseconds per stage, and nanoseconds per contour point of the
//! decomposition and of the SVG export (flat when the cost per contour pixel is bounded).
//!
//! `cargo run --release --example cost_table [-- INPUT…]` with INPUT one of `checker:N`,
//! `noise:N`, `spiral:N` (N the image side), optionally `@MODEL` (`noise:400@poly:6`).
//! Default: `spiral:501 spiral:1001 spiral:2001 noise:400 noise:400@poly:6 checker:2000`.
//! Peak memory is measured on the command-line tool (`/usr/bin/time -v`) on the images
//! `make_cost` writes.

use layertrace::{
    decompose, fidelity, svg_document, trace, Convention, Mask, Model, OutlierRule, SvgOptions,
};
use std::time::Instant;

#[path = "common/cost_inputs.rs"]
mod cost_inputs;

fn mask_of(kind: &str, n: u32) -> Option<Mask> {
    Some(match kind {
        "checker" => Mask::from_fn(n, n, cost_inputs::checker),
        "noise" => {
            let v = cost_inputs::noise(n);
            Mask::from_fn(n, n, |x, y| v[(y * n + x) as usize])
        }
        "spiral" => {
            let v = cost_inputs::spiral(n);
            Mask::from_fn(n, n, |x, y| v[(y * n + x) as usize])
        }
        _ => return None,
    })
}

fn main() {
    let mut inputs: Vec<String> = std::env::args().skip(1).collect();
    if inputs.is_empty() {
        inputs = [
            "spiral:501",
            "spiral:1001",
            "spiral:2001",
            "noise:400",
            "noise:400@poly:6",
            "checker:2000",
        ]
        .map(String::from)
        .to_vec();
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!(
        "| input | model | contours | contour points | pieces | budget cuts | work units (M) | trace ms | decompose ms | decompose ns/unit | svg ms | fidelity ms | decompose ns/point | svg ns/point |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for input in &inputs {
        let (image, model) = input.split_once('@').unwrap_or((input, "conic"));
        let model: Model = model.parse().expect("model");
        let (kind, n) = image.split_once(':').expect("INPUT is KIND:N");
        let n: u32 = n.parse().expect("N");
        let mask = mask_of(kind, n).expect("checker, noise or spiral");
        pool.install(|| {
            let t = Instant::now();
            let contours = trace(&mask, Convention::Default);
            let t_trace = t.elapsed().as_secs_f64();
            let points: usize = contours.iter().map(|c| c.points.len()).sum();
            let count = contours.len();
            let t = Instant::now();
            let d = decompose(contours, model, OutlierRule::NotInPiece);
            let t_dec = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let svg = svg_document(&d, n, n, &SvgOptions::default());
            let t_svg = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let f = fidelity(&svg.svg, &mask).expect("rasterize");
            let t_fid = t.elapsed().as_secs_f64();
            let _ = f;
            println!(
                "| {image} | {model} | {count} | {points} | {} | {} | {:.1} | {:.0} | {:.0} | {:.2} | {:.0} | {:.0} | {:.0} | {:.0} |",
                d.piece_count(),
                budget_cuts(&d),
                d.stats.work as f64 / 1e6,
                t_trace * 1e3,
                t_dec * 1e3,
                t_dec * 1e9 / d.stats.work.max(1) as f64,
                t_svg * 1e3,
                t_fid * 1e3,
                t_dec * 1e9 / points.max(1) as f64,
                t_svg * 1e9 / points.max(1) as f64,
            );
        });
    }
}

fn budget_cuts(d: &layertrace::Decomposition) -> usize {
    d.pieces
        .iter()
        .flatten()
        .filter(|p| p.cut == Some(layertrace::Cut::Budget))
        .count()
}
