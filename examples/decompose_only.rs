//! The floor of any drawing made from the paper's pieces: a whole process that loads an
//! image, thresholds it, traces its borders and decomposes them (exact certificates), as
//! the CLI does, and draws nothing. Timed beside potrace by `scripts/time_vs_potrace.sh`,
//! which runs it as it runs the CLI; it writes one line (contours and pieces) where the CLI
//! would write the SVG.
//!
//! `cargo build --release --example decompose_only`, then
//! `target/release/examples/decompose_only IMAGE -o OUT [--model M] [--threads N] [-q]`
//! (`--help` names `--threads` and `--quiet`, so that the script passes `--threads 1 -q`).

use layertrace::{vectorize, Model, Options};
use std::path::PathBuf;

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("decompose_only: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let (mut input, mut output) = (None::<PathBuf>, None::<PathBuf>);
    let (mut model, mut threads) = (Model::Conic, 1usize);
    let mut args = std::env::args_os().skip(1);
    while let Some(a) = args.next() {
        let mut value = || {
            args.next()
                .ok_or(format!("{} needs a value", a.to_string_lossy()))
        };
        match a.to_str() {
            Some("-h" | "--help") => {
                println!(
                    "Usage: decompose_only IMAGE -o OUT [--model M] [--threads N] [-q, --quiet]"
                );
                return Ok(());
            }
            Some("-o" | "--output") => output = Some(value()?.into()),
            Some("-m" | "--model") => model = value()?.to_string_lossy().parse()?,
            Some("--threads") => threads = value()?.to_string_lossy().parse()?,
            Some("-q" | "--quiet") => {}
            Some(o) if o.starts_with('-') && o != "-" => {
                return Err(format!("unknown option {o}").into())
            }
            _ => input = Some(a.into()),
        }
    }
    let input = input.ok_or("no input image")?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let options = Options::default()
        .model(model)
        .no_svg()
        .pool(std::sync::Arc::new(pool));
    let out = vectorize(input.as_path(), &options)?;
    let d = &out.decomposition;
    let line = format!(
        "{} contours, {} pieces\n",
        d.contours.len(),
        d.piece_count()
    );
    match output {
        Some(path) => std::fs::write(path, line)?,
        None => print!("{line}"),
    }
    Ok(())
}
