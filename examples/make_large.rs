//! Writes the large test images of the robustness checks:
//! `large_shapes.png` (10 000 × 10 000, thousands of discs, ellipses and polygons) and
//! `large_comb.png` (10 000 × 10 000, one comb-shaped component whose outer border is a single
//! contour of about five million pixels).
//!
//! `cargo run --release --example make_large -- OUT_DIR`

use image::{GrayImage, Luma};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args().nth(1).unwrap_or_else(|| ".".into());
    let n = 10_000u32;
    // Deterministic pseudo-random shapes on a grid of cells.
    let mut shapes = GrayImage::from_pixel(n, n, Luma([255]));
    let mut seed = 2014u64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let cell = 160u32;
    for cy in 0..n / cell {
        for cx in 0..n / cell {
            let (x0, y0) = ((cx * cell) as f64 + 80.0, (cy * cell) as f64 + 80.0);
            let (a, b, th) = (
                20.0 + 55.0 * rnd(),
                10.0 + 55.0 * rnd(),
                std::f64::consts::PI * rnd(),
            );
            let sides = (rnd() * 6.0) as u32; // 0..2: ellipse, else a polygon with 3..5 sides
            for y in (cy * cell)..((cy + 1) * cell) {
                for x in (cx * cell)..((cx + 1) * cell) {
                    let (dx, dy) = (x as f64 + 0.5 - x0, y as f64 + 0.5 - y0);
                    let (u, v) = (
                        dx * th.cos() + dy * th.sin(),
                        -dx * th.sin() + dy * th.cos(),
                    );
                    let inside = if sides < 3 {
                        (u / a).powi(2) + (v / b).powi(2) <= 1.0
                    } else {
                        let k = sides as f64;
                        let ang = v.atan2(u);
                        let sector = (ang / (std::f64::consts::TAU / k)).floor() + 0.5;
                        let mid = sector * std::f64::consts::TAU / k;
                        u * mid.cos() + v * mid.sin() <= a * (std::f64::consts::PI / k).cos()
                    };
                    if inside {
                        shapes.put_pixel(x, y, Luma([0]));
                    }
                }
            }
        }
    }
    shapes.save(format!("{dir}/large_shapes.png"))?;
    // A comb: a bar along the top and 249 teeth of width 20 every 40 pixels.
    let comb = GrayImage::from_fn(n, n, |x, y| {
        let ink = (10..n - 10).contains(&x)
            && ((10..60).contains(&y) || ((10..n - 10).contains(&y) && x % 40 < 20));
        Luma([if ink { 0 } else { 255 }])
    });
    comb.save(format!("{dir}/large_comb.png"))?;
    Ok(())
}
