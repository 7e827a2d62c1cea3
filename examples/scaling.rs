//! How decomposition cost grows with contour length: borders of digital discs of growing
//! radius (10³ to 10⁶ contour pixels, generated directly, no bitmap), one contour each,
//! single thread. Prints a table of ns per contour pixel per model.
//!
//! `cargo run --release --example scaling [-- MAX_PIXELS]`

use layertrace::{decompose, Contour, Model, OutlierRule};
use std::time::Instant;

#[path = "common/disc.rs"]
mod disc;
use disc::disc_border;

fn main() {
    let max: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(2_000_000);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    println!(
        "| contour pixels | model | pieces | ms | ns / pixel | GJK runs | switched to whitened | exact fallbacks |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for r in [180.0, 1800.0, 18_000.0, 180_000.0] {
        let pts = disc_border(r);
        if pts.len() > max {
            break;
        }
        assert!(
            pts.windows(2).all(|w| w[0].is_8_adjacent(w[1])),
            "r={r}: not a path"
        );
        for model in [Model::Line, Model::Circle, Model::Conic] {
            let contours = vec![Contour {
                points: pts.clone(),
                hole: false,
                closed: true,
            }];
            let t = Instant::now();
            let d = pool.install(|| decompose(contours, model, OutlierRule::NotInPiece));
            let s = t.elapsed().as_secs_f64();
            println!(
                "| {} | {model} | {} | {:.1} | {:.0} | {} | {} | {} |",
                pts.len(),
                d.piece_count(),
                s * 1e3,
                s * 1e9 / pts.len() as f64,
                d.stats.float_runs,
                d.stats.whitened,
                d.stats.exact_fallbacks
            );
        }
    }
}
