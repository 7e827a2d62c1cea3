//! Prints, for every sample image (or the files given) and the line, circle and conic
//! models: pieces, path commands by type, fallbacks, differing pixels and time.
//!
//! `cargo run --release --example fidelity_table [-- files…]`; with `DIFF_DIR` set, writes
//! a diff PNG per image and model with differences there.

use layertrace::{
    decompose, diff_image, fidelity, load_path, rasterize_svg, svg_document, trace, Convention,
    LoadOptions, Model, OutlierRule, SvgOptions,
};
use std::path::PathBuf;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut files: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if files.is_empty() {
        for e in std::fs::read_dir("samples")? {
            let p = e?.path();
            if p.extension().is_some_and(|x| x == "png") {
                files.push(p);
            }
        }
        files.sort();
    }
    println!("| sample | model | pieces | M | L | A | Q | C | Z | fallbacks (zero/poly/rendered/curve) | joins x/bridged/cracked | missing | extra | max fit err | time ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for f in &files {
        let loaded = load_path(f, &LoadOptions::default())?;
        let mask = loaded.mask;
        for model in [Model::Line, Model::Circle, Model::Conic] {
            let t = Instant::now();
            let d = decompose(
                trace(&mask, Convention::Default),
                model,
                OutlierRule::NotInPiece,
            );
            if std::env::var("STAGES").is_ok() {
                eprintln!(
                    "decomposed {model}: {} pieces in {:?}",
                    d.piece_count(),
                    t.elapsed()
                );
            }
            let out = svg_document(&d, mask.width(), mask.height(), &SvgOptions::default());
            let ms = t.elapsed().as_secs_f64() * 1e3;
            if std::env::var("STAGES").is_ok() {
                eprintln!("svg {} bytes", out.svg.len());
                std::fs::write("/tmp/last.svg", &out.svg)?;
            }
            let r = fidelity(&out.svg, &mask)?;
            let c = out.commands;
            let fb = out.fallback_reasons;
            println!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}/{}/{}/{}) | {}/{}/{} | {} | {} | {:.3} | {:.0} |",
                f.file_stem().unwrap_or_default().to_string_lossy(),
                model,
                d.piece_count(),
                c.move_to, c.line, c.arc, c.quad, c.cubic, c.close,
                out.fallbacks, fb.zero_certificate, fb.no_polynomial, fb.rendered, fb.curve,
                out.joins.intersection, out.joins.bridged, out.joins.cracked,
                r.missing, r.extra, out.max_fit_error, ms
            );
            if let Ok(dir) = std::env::var("DIFF_DIR") {
                if r.differing > 0 {
                    let actual = rasterize_svg(&out.svg, mask.width(), mask.height())?;
                    let name = format!(
                        "{}_{}.png",
                        f.file_stem().unwrap_or_default().to_string_lossy(),
                        model
                    );
                    diff_image(&mask, &actual).save(PathBuf::from(&dir).join(name))?;
                    std::fs::write(
                        PathBuf::from(&dir).join(format!(
                            "{}_{}.svg",
                            f.file_stem().unwrap_or_default().to_string_lossy(),
                            model
                        )),
                        &out.svg,
                    )?;
                }
            }
        }
    }
    Ok(())
}
