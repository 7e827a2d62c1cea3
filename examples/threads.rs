//! Speed-up of the decomposition (contours in parallel, rayon) from 1 to N threads on one
//! image: median of 5 runs per thread count, decomposition stage only.
//!
//! `cargo run --release --example threads -- IMAGE [MODEL]`

use layertrace::{decompose, load_path, trace, Convention, LoadOptions, Model, OutlierRule};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .unwrap_or_else(|| "samples/syn_big3000_many_shapes.png".into());
    let model: Model = args.next().unwrap_or_else(|| "conic".into()).parse()?;
    let mask = load_path(std::path::Path::new(&path), &LoadOptions::default())?.mask;
    let contours = trace(&mask, Convention::Default);
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let mut base = None;
    for threads in 1..=cores.max(2) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let mut times: Vec<f64> = (0..5)
            .map(|_| {
                let c = contours.clone();
                let t = Instant::now();
                let d = pool.install(|| decompose(c, model, OutlierRule::NotInPiece));
                std::hint::black_box(d.piece_count());
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let median = times[2];
        let b = *base.get_or_insert(median);
        println!(
            "{path} {model}: {threads} thread(s) {median:.1} ms, speed-up {:.2}x ({} contours)",
            b / median,
            contours.len()
        );
    }
    Ok(())
}
