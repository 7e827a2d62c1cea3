//! Writes the adversarial inputs of the cost checks (issue 13, items 3 and 6):
//! `checker_2000.png` (2000 × 2000 checkerboard of single pixels: two million tiny contours),
//! `noise_400.png` (400 × 400, each pixel black with probability 1/2, fixed seed) and
//! `spiral_N.png` for N in 501, 1001, 2001, 4001 (a one-pixel-wide square spiral whose arms
//! are two pixels apart: one contour of about N² pixels). Black is foreground.
//!
//! `cargo run --release --example make_cost -- OUT_DIR`

use image::{GrayImage, Luma};

#[path = "common/cost_inputs.rs"]
mod cost_inputs;

fn grey(n: u32, ink: &[bool]) -> GrayImage {
    GrayImage::from_fn(n, n, |x, y| {
        Luma([if ink[(y * n + x) as usize] { 0 } else { 255 }])
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args().nth(1).unwrap_or_else(|| ".".into());
    let checker = GrayImage::from_fn(2000, 2000, |x, y| {
        Luma([if cost_inputs::checker(x, y) { 0 } else { 255 }])
    });
    checker.save(format!("{dir}/checker_2000.png"))?;
    grey(400, &cost_inputs::noise(400)).save(format!("{dir}/noise_400.png"))?;
    for n in [501, 1001, 2001, 4001] {
        grey(n, &cost_inputs::spiral(n)).save(format!("{dir}/spiral_{n}.png"))?;
    }
    Ok(())
}
