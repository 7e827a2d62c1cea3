//! Time per stage (load, trace, decompose, SVG with its render checks) of each image, as a
//! markdown table: where the whole-process time goes.
//!
//! `cargo run --release --example stages -- [--model M] [--runs N] [--threads T] IMAGE…`
//!
//! Each stage's figure is the median of N runs (default 5) in one process, on T worker
//! threads (default 1); the last row sums the images. The stages are the CLI's
//! (`vectorize`) without its fidelity report.

use layertrace::{
    decompose, load_path, svg_document, trace, Convention, LoadOptions, Model, OutlierRule,
    SvgOptions,
};
use std::path::PathBuf;
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut model = Model::Conic;
    let mut runs = 5usize;
    let mut threads = 1usize;
    let mut images: Vec<PathBuf> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--model" => model = args.next().and_then(|m| m.parse().ok()).expect("--model M"),
            "--runs" => runs = args.next().and_then(|n| n.parse().ok()).expect("--runs N"),
            "--threads" => {
                threads = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .expect("--threads T")
            }
            _ => images.push(PathBuf::from(a)),
        }
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    println!("| image | contour px | load ms | trace ms | decompose ms | svg ms | total ms |");
    println!("|---|--:|--:|--:|--:|--:|--:|");
    let mut sums = [0.0f64; 5];
    let mut pixels_sum = 0usize;
    for path in &images {
        let mut t = [Vec::new(), Vec::new(), Vec::new(), Vec::new()];
        let mut pixels = 0;
        for _ in 0..runs {
            pool.install(|| {
                let s = Instant::now();
                let l = load_path(path, &LoadOptions::default()).expect("readable image");
                let a = s.elapsed().as_secs_f64();
                let contours = trace(&l.mask, Convention::Default);
                let b = s.elapsed().as_secs_f64();
                pixels = contours.iter().map(|c| c.points.len()).sum();
                let d = decompose(contours, model, OutlierRule::NotInPiece);
                let c = s.elapsed().as_secs_f64();
                let svg = svg_document(&d, l.mask.width(), l.mask.height(), &SvgOptions::default());
                std::hint::black_box(&svg);
                let e = s.elapsed().as_secs_f64();
                t[0].push(a * 1e3);
                t[1].push((b - a) * 1e3);
                t[2].push((c - b) * 1e3);
                t[3].push((e - c) * 1e3);
            });
        }
        let m: Vec<f64> = t.into_iter().map(median).collect();
        let total: f64 = m.iter().sum();
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
        println!(
            "| {} | {pixels} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            name.unwrap_or_default(),
            m[0],
            m[1],
            m[2],
            m[3],
            total
        );
        for (s, v) in sums.iter_mut().zip(m.iter().chain([&total])) {
            *s += v;
        }
        pixels_sum += pixels;
    }
    println!(
        "| **all** | {pixels_sum} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
        sums[0], sums[1], sums[2], sums[3], sums[4]
    );
}
