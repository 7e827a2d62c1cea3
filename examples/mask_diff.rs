//! Compares the foreground masks of two images (each read by the library, luma < 128, alpha
//! composited on white) and prints `differing missing extra`:
//! `cargo run --release --example mask_diff -- INPUT RENDERED [DIFF.png]`.
//!
//! `scripts/browser_check.sh` uses it on a Chromium screenshot of layertrace's SVG
//! (`RENDERED`) against the image it came from (`INPUT`). The two must have the same size;
//! `DIFF.png` (optional) shows the differences as `--diff` does (missing red, extra blue).
//! With `LIST=1` in the environment, each differing pixel is printed too (`x y missing|extra`).

use layertrace::{compare, diff_image, load_path, png_bytes, write_atomic, LoadOptions};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [input, rendered, rest @ ..] = args.as_slice() else {
        return Err("usage: mask_diff INPUT RENDERED [DIFF.png]".into());
    };
    let opts = LoadOptions::default();
    let expected = load_path(input, &opts)?.mask;
    let actual = load_path(rendered, &opts)?.mask;
    if (expected.width(), expected.height()) != (actual.width(), actual.height()) {
        return Err(format!(
            "{} is {}x{} but {} is {}x{}",
            input.display(),
            expected.width(),
            expected.height(),
            rendered.display(),
            actual.width(),
            actual.height()
        )
        .into());
    }
    let r = compare(&expected, &actual);
    if let Some(path) = rest.first() {
        write_atomic(path, &png_bytes(&diff_image(&expected, &actual))?)?;
    }
    if std::env::var_os("LIST").is_some() {
        for y in 0..i64::from(expected.height()) {
            for x in 0..i64::from(expected.width()) {
                match (expected.get(x, y), actual.get(x, y)) {
                    (true, false) => eprintln!("{x} {y} missing"),
                    (false, true) => eprintln!("{x} {y} extra"),
                    _ => {}
                }
            }
        }
    }
    println!("{} {} {}", r.differing, r.missing, r.extra);
    Ok(())
}
