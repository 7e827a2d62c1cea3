//! Where the drawing's time goes by contour size: each contour of an image drawn alone
//! ([`contour_path`], one thread, no memo of tiny shapes), timed, and summed by size class
//! (points in `[2^k, 2^(k+1))`), with the number of distinct shapes in each class (points
//! relative to the first one, and the hole flag: what a memo keyed by shape could share).
//!
//! The options are the SVG document's for curves checked both ways (the whole image as the
//! canvas, `EdgeClipping::Unknown`); the document draws the groups well inside one of
//! Chromium's tiles more cheaply, unclipped only, and the tiny contours once per shape, so
//! the sum is an upper estimate of the document's drawing time.
//!
//! `cargo run --release --example draw_sizes -- IMAGE [MODEL]`

use layertrace::{
    contour_path, decompose, load_path, trace, Convention, Decomposition, EdgeClipping,
    LoadOptions, Model, OutlierRule, OutlineOptions, PathCommand, PolynomialBasis,
};
use std::collections::{HashMap, HashSet};
use std::time::Instant;

/// One size class's totals.
#[derive(Default)]
struct Class {
    contours: usize,
    points: usize,
    ms: f64,
    commands: usize,
    curves: usize,
    shapes: HashSet<(bool, Vec<(i32, i32)>)>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("usage: draw_sizes IMAGE [MODEL]")?;
    let model: Model = args.next().unwrap_or_else(|| "conic".into()).parse()?;
    let mask = load_path(std::path::Path::new(&path), &LoadOptions::default())?.mask;
    let (w, h) = (f64::from(mask.width()), f64::from(mask.height()));
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let d = pool.install(|| {
        decompose(
            trace(&mask, Convention::Default),
            model,
            OutlierRule::NotInPiece,
        )
    });
    let basis = model.basis();
    let opts = OutlineOptions {
        clipping: EdgeClipping::Unknown,
        canvas: Some(kurbo::Rect::new(0.0, 0.0, w, h)),
        ..OutlineOptions::default()
    };
    let mut classes: HashMap<u32, Class> = HashMap::new();
    // (The drawing runs on the pool's one thread, as the document's would.)
    pool.install(|| draw_all(&d, &basis, &opts, &mut classes));
    report(&path, model, &d, &classes);
    Ok(())
}

/// Draws every contour of `d` alone, timed, into its size class.
fn draw_all(
    d: &Decomposition,
    basis: &PolynomialBasis,
    opts: &OutlineOptions,
    classes: &mut HashMap<u32, Class>,
) {
    for (c, pieces) in d.contours.iter().zip(&d.pieces) {
        let n = c.points.len();
        let k = usize::BITS - n.max(1).leading_zeros() - 1;
        let t = Instant::now();
        let drawn = contour_path(c, pieces, basis, opts);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let class = classes.entry(k).or_default();
        class.contours += 1;
        class.points += n;
        class.ms += ms;
        class.commands += drawn.commands.len();
        class.curves += drawn
            .commands
            .iter()
            .filter(|c| !matches!(c, PathCommand::Line(_)))
            .count();
        let first = c.points.first().copied().unwrap_or_default();
        class.shapes.insert((
            c.hole,
            c.points
                .iter()
                .map(|p| (p.x - first.x, p.y - first.y))
                .collect(),
        ));
    }
}

fn report(path: &str, model: Model, d: &Decomposition, classes: &HashMap<u32, Class>) {
    let total: f64 = classes.values().map(|c| c.ms).sum();
    println!(
        "{path}, {model}: {} contours, drawing {total:.1} ms",
        d.contours.len()
    );
    println!();
    println!("| points | contours | distinct shapes | drawing ms | share | µs per point | commands | curves |");
    println!("|---|--:|--:|--:|--:|--:|--:|--:|");
    let mut keys: Vec<u32> = classes.keys().copied().collect();
    keys.sort_unstable();
    for k in keys {
        let c = &classes[&k];
        println!(
            "| {}–{} | {} | {} | {:.1} | {:.0}% | {:.2} | {} | {} |",
            1u64 << k,
            (1u64 << (k + 1)) - 1,
            c.contours,
            c.shapes.len(),
            c.ms,
            100.0 * c.ms / total.max(f64::MIN_POSITIVE),
            1e3 * c.ms / c.points.max(1) as f64,
            c.commands,
            c.curves
        );
    }
}
