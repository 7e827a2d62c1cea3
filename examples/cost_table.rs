//! Time per stage on the adversarial inputs of issue 13 (checkerboard of single pixels,
//! 50 % noise, one-pixel-wide spirals of growing size) or on image files, one thread by
//! default. Prints a markdown table: contour points, pieces, milliseconds per stage (load:
//! decoding a file or making the input), and nanoseconds per contour point of the
//! decomposition and of the SVG export (flat when the cost per contour pixel is bounded).
//!
//! `cargo run --release --example cost_table [-- [--runs N] [--threads T] INPUT…]` with INPUT
//! one of `checker:N`, `noise:N`, `spiral:N` (N the image side), optionally `@MODEL`
//! (`noise:400@poly:6`). Default: `spiral:501 spiral:1001 spiral:2001 noise:400
//! noise:400@poly:6 checker:2000`. `--runs N`: each stage's median of N runs (default 1);
//! `--threads T`: T worker threads (default 1), to see which stage scales.
//!
//! With `--memory` first, each input runs in a child process of its own and the table is
//! of memory instead: the peak resident memory after the mask was built (Linux `VmHWM`,
//! reset through `/proc/self/clear_refs`) next to [`work_estimate`]'s upper estimate.
//! Besides the generated inputs, INPUT may be an image file (`samples/x.png`).

use layertrace::{
    decompose, fidelity, load_path, svg_document, trace, work_estimate, Convention, LoadOptions,
    Mask, Model, OutlierRule, SvgOptions,
};
use std::time::Instant;

#[path = "common/cost_inputs.rs"]
mod cost_inputs;

fn mask_of(image: &str) -> Option<Mask> {
    let Some((kind, n)) = image.split_once(':') else {
        let loaded = load_path(std::path::Path::new(image), &LoadOptions::default()).ok()?;
        return Some(loaded.mask);
    };
    let n: u32 = n.parse().ok()?;
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

/// A line of `/proc/self/status` in bytes (`VmHWM`, `VmRSS`).
fn status_bytes(key: &str) -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// One input in this process: peak memory above the mask, and the estimate.
fn memory_row(input: &str) {
    let (image, model) = input.split_once('@').unwrap_or((input, "conic"));
    let model: Model = model.parse().expect("model");
    let mask = mask_of(image).expect("checker:N, noise:N, spiral:N or an image");
    let (w, h) = (mask.width(), mask.height());
    // Reset the peak to the current resident set.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    let base = status_bytes("VmRSS:");
    let contours = trace(&mask, Convention::Default);
    let points: usize = contours.iter().map(|c| c.points.len()).sum();
    let count = contours.len();
    let est = work_estimate(&contours, model, w, h, 1);
    let d = decompose(contours, model, OutlierRule::NotInPiece);
    let svg = svg_document(&d, w, h, &SvgOptions::default());
    let _ = fidelity(&svg.svg, &mask).expect("rasterize");
    let peak = status_bytes("VmHWM:").saturating_sub(base);
    let mb = |b: u64| b as f64 / (1 << 20) as f64;
    println!(
        "| {image} | {model} | {count} | {points} | {:.1} | {:.1} | {:.1} | {:.2} |",
        mb(svg.svg.len() as u64),
        mb(peak),
        mb(est.bytes),
        est.bytes as f64 / peak.max(1) as f64
    );
}

fn main() {
    let mut inputs: Vec<String> = std::env::args().skip(1).collect();
    if inputs.first().map(String::as_str) == Some("--one") {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("thread pool");
        pool.install(|| memory_row(&inputs[1]));
        return;
    }
    let memory = inputs.first().map(String::as_str) == Some("--memory");
    if memory {
        inputs.remove(0);
    }
    let (mut runs, mut threads) = (1usize, 1usize);
    while let Some(flag @ ("--runs" | "--threads")) = inputs.first().map(String::as_str) {
        let value = inputs
            .get(1)
            .and_then(|v| v.parse().ok())
            .filter(|&v| v > 0);
        let value = value.unwrap_or_else(|| panic!("{flag} needs a positive number"));
        if flag == "--runs" {
            runs = value;
        } else {
            threads = value;
        }
        inputs.drain(..2);
    }
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
    if memory {
        println!("| input | model | contours | contour points | SVG MB | measured peak MB | estimate MB | estimate / measured |");
        println!("|---|---|---|---|---|---|---|---|");
        let exe = std::env::current_exe().expect("own path");
        for input in &inputs {
            let out = std::process::Command::new(&exe)
                .args(["--one", input])
                .output()
                .expect("child");
            print!("{}", String::from_utf8_lossy(&out.stdout));
        }
        return;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    println!(
        "| input | model | contours | contour points | pieces | budget cuts | work units (M) | load ms | trace ms | decompose ms | decompose ns/unit | svg ms | fidelity ms | decompose ns/point | svg ns/point |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for input in &inputs {
        let (image, model) = input.split_once('@').unwrap_or((input, "conic"));
        let model: Model = model.parse().expect("model");
        // Seconds per stage, one vector per stage, one entry per run.
        let mut times: [Vec<f64>; 5] = Default::default();
        let mut last = None;
        for _ in 0..runs {
            let t = Instant::now();
            let mask = mask_of(image).expect("checker:N, noise:N, spiral:N or an image");
            times[0].push(t.elapsed().as_secs_f64());
            let (w, h) = (mask.width(), mask.height());
            pool.install(|| {
                let t = Instant::now();
                let contours = trace(&mask, Convention::Default);
                times[1].push(t.elapsed().as_secs_f64());
                let points: usize = contours.iter().map(|c| c.points.len()).sum();
                let count = contours.len();
                let t = Instant::now();
                let d = decompose(contours, model, OutlierRule::NotInPiece);
                times[2].push(t.elapsed().as_secs_f64());
                let t = Instant::now();
                let svg = svg_document(&d, w, h, &SvgOptions::default());
                times[3].push(t.elapsed().as_secs_f64());
                let t = Instant::now();
                let f = fidelity(&svg.svg, &mask).expect("rasterize");
                times[4].push(t.elapsed().as_secs_f64());
                let _ = f;
                last = Some((count, points, d));
            });
        }
        let Some((count, points, d)) = last else {
            continue;
        };
        let [t_load, t_trace, t_dec, t_svg, t_fid] = times.map(median);
        println!(
            "| {image} | {model} | {count} | {points} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.1} | {:.1} | {:.0} | {:.0} |",
            d.piece_count(),
            budget_cuts(&d),
            d.stats.work as f64 / 1e6,
            t_load * 1e3,
            t_trace * 1e3,
            t_dec * 1e3,
            t_dec * 1e9 / d.stats.work.max(1) as f64,
            t_svg * 1e3,
            t_fid * 1e3,
            t_dec * 1e9 / points.max(1) as f64,
            t_svg * 1e9 / points.max(1) as f64,
        );
    }
}

/// The median of `v` (the upper one of an even count); 0 for none.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

fn budget_cuts(d: &layertrace::Decomposition) -> usize {
    d.pieces
        .iter()
        .flatten()
        .filter(|p| p.cut == Some(layertrace::Cut::Budget))
        .count()
}
