//! Many inputs in one run: folders expanded to their images, one SVG per input in the output
//! folder, inputs processed in parallel, every failure named and the others still written.

use super::args::Args;
use super::progress::Bar;
use super::run::{one, options, Drawing, Outputs};
use layertrace::{Error, Format};
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// File extensions taken from a folder (compared without case).
const IMAGE_EXTENSIONS: [&str; 12] = [
    "png", "bmp", "pbm", "pgm", "ppm", "pnm", "tif", "tiff", "gif", "jpg", "jpeg", "webp",
];

/// The input of a run without `--out-dir`: exactly one file, or `-`.
pub fn single_input(args: &Args) -> Result<PathBuf, Error> {
    let many = || {
        Error::Arguments(format!(
            "{} inputs but one output: use --out-dir DIR to write one SVG per input",
            args.inputs.len()
        ))
    };
    match args.inputs.as_slice() {
        [one] if one.is_dir() => Err(Error::Arguments(format!(
            "{} is a folder: use --out-dir DIR to vectorize the images in it",
            one.display()
        ))),
        [one] => Ok(one.clone()),
        _ => Err(many()),
    }
}

/// The image files of the inputs: files as given, folders replaced by their image files
/// (by extension, hidden files skipped, in name order, not recursive).
fn expand(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    for input in inputs {
        if input == Path::new("-") {
            return Err(Error::Arguments(
                "standard input ('-') cannot be used with --out-dir".into(),
            ));
        }
        if !input.is_dir() {
            files.push(input.clone());
            continue;
        }
        let read_err = |source| Error::Read {
            path: input.clone(),
            source,
        };
        let mut found = Vec::new();
        for entry in std::fs::read_dir(input).map_err(read_err)? {
            let path = entry.map_err(read_err)?.path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            let image = path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| IMAGE_EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(e)));
            if image && !name.starts_with('.') && path.is_file() {
                found.push(path);
            }
        }
        if found.is_empty() {
            return Err(Error::Arguments(format!(
                "{}: no image files in this folder (looked for .{})",
                input.display(),
                IMAGE_EXTENSIONS.join(", .")
            )));
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

/// The output of each input in `dir`: its file name without the extension, then `.svg`
/// (or the format's extension). Two inputs with the same name are refused before any work.
fn destinations(files: &[PathBuf], dir: &Path, format: Format) -> Result<Vec<PathBuf>, Error> {
    let mut seen: HashMap<PathBuf, &Path> = HashMap::new();
    let mut out = Vec::with_capacity(files.len());
    for f in files {
        let stem = f.file_stem().unwrap_or(f.as_os_str());
        let dest = dir.join(Path::new(stem).with_extension(format.extension()));
        if let Some(first) = seen.insert(dest.clone(), f) {
            return Err(Error::Arguments(format!(
                "{} and {} would both be written to {}; rename one or run them apart",
                first.display(),
                f.display(),
                dest.display()
            )));
        }
        out.push(dest);
    }
    Ok(out)
}

/// Vectorizes every input into `dir`, in parallel. Returns whether all succeeded; the
/// failures are named on standard error as they happen.
pub fn run(args: &Args, dir: &Path, pool: Option<Arc<rayon::ThreadPool>>) -> Result<bool, Error> {
    let files = expand(&args.inputs)?;
    let dests = destinations(&files, dir, args.out_format)?;
    std::fs::create_dir_all(dir).map_err(|source| Error::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let threads = pool
        .as_ref()
        .map_or_else(rayon::current_num_threads, |p| p.current_num_threads());
    let concurrent = threads.clamp(1, files.len().max(1)) as u64;
    let bar = Bar::new(files.len() as u64, "files", args.quiet);
    let failed = AtomicUsize::new(0);
    let work = || {
        files.par_iter().zip(&dests).for_each(|(file, dest)| {
            let outputs = Outputs {
                svg: Some(Drawing {
                    path: dest.clone(),
                    format: args.out_format,
                }),
                ..Outputs::default()
            };
            let mut opts = options(args, &outputs, pool.clone());
            // The memory limit is shared by the inputs processed at the same time.
            opts.max_memory /= concurrent;
            match one(args, file, &outputs, &opts, false) {
                Ok(done) => {
                    let text = done.text(args.quiet);
                    if !text.is_empty() {
                        bar.println(&text);
                    }
                }
                Err(e) => {
                    failed.fetch_add(1, Ordering::Relaxed);
                    bar.println(&format!("layertrace: {e}"));
                }
            }
            bar.inc();
        })
    };
    match &pool {
        Some(p) => p.install(work),
        None => work(),
    }
    bar.finish();
    let failed = failed.into_inner();
    if failed == files.len() {
        eprintln!(
            "layertrace: all {failed} inputs failed; nothing was written to {}",
            dir.display()
        );
    } else if failed > 0 {
        eprintln!(
            "layertrace: {failed} of {} inputs failed; the others were written to {}",
            files.len(),
            dir.display()
        );
    }
    Ok(failed == 0)
}
