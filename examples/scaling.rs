//! How decomposition cost grows with contour length: borders of digital discs of growing
//! radius (10³ to 10⁶ contour pixels, generated directly, no bitmap), one contour each,
//! single thread. Prints a table of ns per contour pixel per model.
//!
//! `cargo run --release --example scaling [-- MAX_PIXELS]`

use layertrace::{decompose, Contour, Model, OutlierRule, Pixel};
use std::collections::HashSet;
use std::time::Instant;

/// The border (pixels inside with a 4-neighbour outside) of the disc of pixel centres within
/// `r` of the corner (0, 0), counter-clockwise on screen from the angle −π.
fn disc_border(r: f64) -> Vec<Pixel> {
    // Highest inside row of column x (centres symmetric about y = −1/2), if any.
    let top = |x: i64| -> Option<i64> {
        let fx = x as f64 + 0.5;
        (fx.abs() <= r).then(|| ((r * r - fx * fx).sqrt() - 0.5).floor() as i64)
    };
    let ri = r.ceil() as i64 + 1;
    let mut set = HashSet::new();
    for x in -ri..=ri {
        let Some(t) = top(x) else { continue };
        if t < -1 - t {
            continue; // empty column
        }
        let lowest = match (top(x - 1), top(x + 1)) {
            (Some(a), Some(b)) => a.min(b).max(-1 - t - 1) + 1,
            _ => -1 - t, // an outermost column: all border
        };
        for y in lowest.min(t)..=t {
            set.insert(Pixel::new(x as i32, y as i32));
            set.insert(Pixel::new(x as i32, (-1 - y) as i32));
        }
    }
    let mut v: Vec<Pixel> = set.into_iter().collect();
    let angle = |p: &Pixel| -((p.y as f64 + 0.5).atan2(p.x as f64 + 0.5));
    v.sort_by_cached_key(|p| OrderedAngle(angle(p)));
    v
}

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

/// An angle ordered by `f64::total_cmp`.
#[derive(PartialEq)]
struct OrderedAngle(f64);

impl Eq for OrderedAngle {}

impl PartialOrd for OrderedAngle {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for OrderedAngle {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}
