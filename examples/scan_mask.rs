//! The foreground mask that layertrace traces, as a PBM for other tracers, and an SVG drawn
//! back to a PNG to look at; `scripts/scan_vs_potrace.sh` uses both.
//!
//! ```text
//! cargo run --release --example scan_mask -- mask INPUT THRESHOLD TURDSIZE OUT.pbm
//! cargo run --release --example scan_mask -- render IN.svg WIDTH HEIGHT OUT.png
//! ```
//!
//! `mask` loads `INPUT` as the CLI does with `--threshold THRESHOLD --turdsize TURDSIZE`
//! (THRESHOLD: a number, `otsu`, `adaptive` or `adaptive:R:K`), writes the mask as a binary
//! PBM (1 = foreground, as potrace reads it) and prints `foreground PIXELS` and what cleaning
//! dropped. `render` draws an SVG as the fidelity check does (resvg, crisp edges) at
//! `WIDTH` × `HEIGHT` pixels, black on white.

use layertrace::{load_path, png_bytes, rasterize_svg, write_atomic, LoadOptions, Mask, Threshold};
use std::path::PathBuf;

fn threshold(s: &str) -> Result<Threshold, String> {
    if s == "otsu" {
        return Ok(Threshold::Otsu);
    }
    if let Some(rest) = s.strip_prefix("adaptive") {
        let n: Vec<u32> = rest
            .split(':')
            .skip(1)
            .map(|p| p.parse().map_err(|_| format!("bad threshold {s}")))
            .collect::<Result<_, _>>()?;
        return Ok(Threshold::Adaptive {
            radius: n.first().copied().unwrap_or(Threshold::ADAPTIVE_RADIUS),
            k_percent: n.get(1).map_or(Threshold::ADAPTIVE_K_PERCENT, |&k| k as u8),
        });
    }
    s.parse()
        .map(Threshold::Fixed)
        .map_err(|_| format!("bad threshold {s}"))
}

/// The mask as a binary PBM (P4): rows padded to whole bytes, 1 = foreground.
fn pbm(mask: &Mask) -> Vec<u8> {
    let (w, h) = (mask.width(), mask.height());
    let mut out = format!("P4\n{w} {h}\n").into_bytes();
    for y in 0..i64::from(h) {
        for x0 in (0..i64::from(w)).step_by(8) {
            let mut byte = 0u8;
            for k in 0..8 {
                if mask.get(x0 + k, y) {
                    byte |= 0x80 >> k;
                }
            }
            out.push(byte);
        }
    }
    out
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    match args.as_slice() {
        ["mask", input, t, turdsize, out] => {
            let opts = LoadOptions {
                threshold: threshold(t)?,
                turdsize: turdsize.parse()?,
                ..LoadOptions::default()
            };
            let loaded = load_path(&PathBuf::from(input), &opts)?;
            write_atomic(&PathBuf::from(out), &pbm(&loaded.mask))?;
            println!(
                "foreground {}, threshold {}, cleaning {}",
                loaded.mask.count_foreground(),
                loaded.threshold,
                loaded.cleaned
            );
        }
        ["render", svg, w, h, out] => {
            let svg = std::fs::read_to_string(svg)?;
            let m = rasterize_svg(&svg, w.parse()?, h.parse()?)?;
            let img = image::RgbImage::from_fn(m.width(), m.height(), |x, y| {
                let v = if m.get(x.into(), y.into()) { 0 } else { 255 };
                image::Rgb([v, v, v])
            });
            write_atomic(&PathBuf::from(out), &png_bytes(&img)?)?;
        }
        _ => {
            return Err("usage: scan_mask mask INPUT THRESHOLD TURDSIZE OUT.pbm | \
                        scan_mask render IN.svg WIDTH HEIGHT OUT.png"
                .into())
        }
    }
    Ok(())
}
