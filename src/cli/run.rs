//! One run of the tool: one input with its named outputs, or many inputs into a folder.

use super::args::Args;
use super::batch;
use super::progress::Bar;
use layertrace::{
    colour_diff_image, diff_image, document_bytes, png_bytes, staircases, vectorize, Basis, Compat,
    CurveKind, Error, Format, Options, OutputSet, PictureFormat, Progress, Stage, SvgOptions,
    Vectorized,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// The drawing of one input: where, and in which format.
#[derive(Clone, Debug)]
pub struct Drawing {
    /// The file ('-' for standard output).
    pub path: PathBuf,
    /// SVG, PDF or EPS.
    pub format: Format,
}

/// The outputs of one input.
#[derive(Clone, Debug, Default)]
pub struct Outputs {
    /// The drawing (SVG, PDF or EPS).
    pub svg: Option<Drawing>,
    /// The JSON of the decomposition.
    pub json: Option<PathBuf>,
    /// The decomposition picture.
    pub picture: Option<PathBuf>,
    /// The round-trip differences.
    pub diff: Option<PathBuf>,
}

/// Runs the tool. Returns whether every input succeeded; an error that stops the whole run
/// (bad outputs, or the only input failing) is returned as such.
pub fn run(args: &Args) -> Result<bool, Error> {
    let pool = match args.threads {
        // The main thread is one of the workers: with one thread, none is spawned and no
        // work is handed between threads.
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .use_current_thread()
            .build()
            .ok()
            .map(Arc::new),
        None => None,
    };
    // The formats named by the outputs' extensions, before anything else (usage errors).
    let drawing = match &args.output {
        Some(path) => Some(Drawing {
            path: path.clone(),
            format: Format::from_path(path).map_err(|e| naming("-o", e))?,
        }),
        None => None,
    };
    for (flag, path) in [
        ("--decomposition", &args.decomposition),
        ("--diff", &args.diff),
    ] {
        if let Some(path) = path {
            PictureFormat::from_path(path).map_err(|e| naming(flag, e))?;
        }
    }
    match &args.out_dir {
        None => {
            let input = batch::single_input(args)?;
            let outputs = Outputs {
                svg: drawing,
                json: args.json.clone(),
                picture: args.decomposition.clone(),
                diff: args.diff.clone(),
            };
            let mut options = options(args, &outputs, pool);
            let bar = Arc::new(Bar::new(0, "contours", args.quiet));
            let b = bar.clone();
            options.progress = Some(Arc::new(move |p: Progress| {
                let stage = match p.stage {
                    Stage::Decompose => "decomposed",
                    _ => "drawn",
                };
                b.set(p.done, p.total, stage);
            }));
            let done = one(args, &input, &outputs, &options, true);
            bar.finish();
            let text = done?.text(args.quiet);
            if !text.is_empty() {
                eprintln!("{text}");
            }
            Ok(true)
        }
        Some(dir) => batch::run(args, dir, pool),
    }
}

/// The library options for `args`, asking for what `outputs` needs.
pub fn options(args: &Args, outputs: &Outputs, pool: Option<Arc<rayon::ThreadPool>>) -> Options {
    let mut o = Options::default()
        .model(args.model)
        .cover(args.cover)
        .invert(args.invert)
        .turdsize(args.turdsize)
        .max_pixels(args.max_pixels)
        .max_memory(
            args.max_memory
                .unwrap_or_else(layertrace::default_max_memory),
        )
        .compat(if args.compat.is_some() {
            Compat::Ipol
        } else {
            Compat::Default
        })
        .fidelity(args.report || outputs.diff.is_some())
        // The tile renders are only reported.
        .tile_fidelity(args.report)
        .json(outputs.json.is_some());
    o.threshold = args.threshold;
    o.smooth = args.smooth;
    o.colors = args.colors;
    o.layout = args.layout;
    o.alpha = args.alpha;
    o.svg = (outputs.svg.is_some() || args.report || outputs.diff.is_some()).then(|| SvgOptions {
        fill: args.fill.clone(),
        grid: args.grid,
        tolerance: args.tolerance,
        min_clearance: args.min_clearance,
        min_curve_points: args.min_curve_points,
        max_curve_points: args.max_curve_points,
        square_corners: args.square_corners,
    });
    if outputs.picture.is_some() {
        o.picture = Some(args.scale);
    }
    o.pool = pool;
    o
}

/// What one input printed: its `--report` lines ("" without `--report`), its summary line.
#[derive(Clone, Debug)]
pub struct Finished {
    /// The `--report` lines, each ending in a newline.
    pub report: String,
    /// The summary line (no newline).
    pub summary: String,
}

impl Finished {
    /// The report, and the summary unless `quiet`.
    pub fn text(&self, quiet: bool) -> String {
        let mut s = self.report.clone();
        if !quiet {
            s.push_str(&self.summary);
        }
        s.trim_end().to_string()
    }
}

/// Vectorizes `input` and writes its outputs, whole or not at all: every output is checked
/// before the input is read and put in place only when everything succeeded. `last`: the
/// process ends after this input (its commit is [`OutputSet::commit_final`]: a signal that
/// comes once the files are in place no longer ends it with 128 + the signal).
pub fn one(
    args: &Args,
    input: &Path,
    outputs: &Outputs,
    options: &Options,
    last: bool,
) -> Result<Finished, Error> {
    let start = Instant::now();
    let stdin = input == Path::new("-");
    let mut outs = OutputSet::new((!stdin).then_some(input));
    let mut named: Vec<(&str, PathBuf)> = Vec::new();
    let mut add = |flag: &'static str, path: Option<&PathBuf>| -> Result<_, Error> {
        let Some(path) = path else { return Ok(None) };
        let id = outs.add(path).map_err(|e| match e {
            // Name the options, not only the paths, in the message.
            Error::SameOutput { first, second } => {
                let flag_of = |p: &Path| named.iter().find(|(_, q)| *q == p).map(|(f, _)| *f);
                Error::SameOutput {
                    first: format!("{} {}", flag_of(&first).unwrap_or("?"), first.display()).into(),
                    second: format!("{flag} {}", second.display()).into(),
                }
            }
            e => e,
        })?;
        named.push((flag, path.clone()));
        Ok(Some(id))
    };
    let svg_out = add("-o", outputs.svg.as_ref().map(|d| &d.path))?;
    let json_out = add("--json", outputs.json.as_ref())?;
    let picture_out = add("--decomposition", outputs.picture.as_ref())?;
    let diff_out = add("--diff", outputs.diff.as_ref())?;

    // The outputs are moved out of `v`, not copied: an SVG or JSON can be hundreds of MB.
    // Every output is encoded before the first is written: no temporary file exists while
    // the run computes, so a signal ends it at once (see `signals`).
    let mut v = vectorize(input, options)?;
    let mut encoded: Vec<(layertrace::OutputId, Vec<u8>)> = Vec::new();
    if let (Some(id), Some(json)) = (json_out, v.json.take()) {
        encoded.push((id, json.into_bytes()));
    }
    if let (Some(id), Some(png)) = (picture_out, v.picture.take()) {
        encoded.push((id, png));
    }
    if let (Some(id), Some(path)) = (diff_out, &outputs.diff) {
        let picture = match (&v.fidelity, &v.colour) {
            (Some(f), _) => Some(diff_image(&v.mask, &f.rendered)),
            (None, Some(c)) => c
                .fidelity
                .as_ref()
                .map(|f| colour_diff_image(&c.regions.image, &f.rendered)),
            _ => None,
        };
        if let Some(picture) = picture {
            let bytes = png_bytes(&picture).map_err(|source| Error::Encode {
                path: path.clone(),
                source,
            })?;
            encoded.push((id, bytes));
        }
    }
    let mut report = if args.report && args.turdsize > 0 {
        format!("cleaning: {}\n", v.cleaned)
    } else {
        String::new()
    };
    if args.report {
        report += &self::report(&v)?;
    }
    if let (Some(id), Some(drawing), Some(svg)) = (svg_out, &outputs.svg, v.svg.as_mut()) {
        encoded.push((
            id,
            document_bytes(std::mem::take(&mut svg.svg), drawing.format)?,
        ));
    }
    for (id, bytes) in encoded {
        outs.write(id, bytes)?;
    }
    if last {
        outs.commit_final()?;
    } else {
        outs.commit()?;
    }
    // Not computed when it is not shown: classifying every piece took 1% of a run on noise.
    let summary = if args.quiet {
        String::new()
    } else {
        let name = if stdin {
            "<stdin>".into()
        } else {
            input.display().to_string()
        };
        summary(&name, &v, options, start)
    };
    // The process ends after its last input: the results are left to the system instead of
    // being freed piece by piece (0.6% of the instructions on 400² noise).
    if last {
        std::mem::forget(v);
    }
    Ok(Finished { report, summary })
}

/// Names the option in an [`Error::UnknownFormat`]: `-o x.txt: unknown output format …`.
fn naming(flag: &str, e: Error) -> Error {
    match e {
        Error::UnknownFormat {
            path,
            extension,
            expected,
        } => Error::UnknownFormat {
            path: format!("{flag} {}", path.display()).into(),
            extension,
            expected,
        },
        e => e,
    }
}

/// The `--report` lines: fidelity, the SVG's commands, staircases.
fn report(v: &Vectorized) -> Result<String, Error> {
    let mut text = String::new();
    if let Some(f) = v.colour.as_ref().and_then(|c| c.fidelity.as_ref()) {
        let pct = if f.pixels > 0 {
            100.0 * f.differing as f64 / f.pixels as f64
        } else {
            0.0
        };
        text += &format!(
            "fidelity: {} differing pixels ({:.3}% of {} in regions; {} painted outside them), {} seam pixels (anti-aliased)\n",
            f.differing, pct, f.pixels, f.extra, f.seams
        );
        let per: Vec<String> = f
            .colours
            .iter()
            .map(|d| format!("{} {}/{}", d.colour, d.differing, d.pixels))
            .collect();
        text += &format!("per colour (differing/pixels): {}\n", per.join(", "));
        if let Some(b) = f.band {
            text += &band_line(&b);
        }
    }
    let (Some(out), Some(f)) = (&v.svg, &v.fidelity) else {
        if v.colour.is_some() {
            if let Some(out) = &v.svg {
                text += &svg_lines(out)?;
            }
        }
        return Ok(text);
    };
    let r = f.report;
    let pct = if r.foreground > 0 {
        100.0 * r.differing as f64 / r.foreground as f64
    } else {
        0.0
    };
    text += &format!(
        "fidelity: {} differing pixels ({} missing, {} extra; {:.3}% of {} foreground), IoU {:.5}\n",
        r.differing, r.missing, r.extra, pct, r.foreground, r.iou
    );
    if let Some(t) = f.tiled {
        text += &format!(
            "fidelity in Chromium's raster tiles (the document opened at 1:1): {} differing pixels ({} missing, {} extra)\n",
            t.differing, t.missing, t.extra
        );
    }
    if let Some(b) = f.band {
        text += &band_line(&b);
    }
    text += &svg_lines(out)?;
    Ok(text)
}

/// The `--report` lines on the SVG: its commands, staircases.
fn svg_lines(out: &layertrace::SvgOutput) -> Result<String, Error> {
    let mut text = String::new();
    let c = out.commands;
    let fb = out.fallback_reasons;
    text += &format!(
        "svg: {} bytes, {} commands (M {}, L {}, A {}, Q {}, C {}, Z {}), {} redrawn as exact polygons, {} along pixel edges, max fit error {:.3} px\n",
        out.svg.len(),
        c.total(),
        c.move_to,
        c.line,
        c.arc,
        c.quad,
        c.cubic,
        c.close,
        count(
            fb.rendered + fb.curve + fb.thin + fb.short + fb.long + fb.no_polynomial,
            "curve piece",
            "curve pieces"
        ),
        count(fb.zero_certificate, "stretch", "stretches"),
        out.max_fit_error
    );
    let s = staircases(&out.svg)?;
    text += &format!(
        "staircases: {} runs, {} segments in runs (of {} straight segments)\n",
        s.runs, s.segments, s.lines
    );
    Ok(text)
}

/// The `--report` line of smooth mode: where the differing pixels are.
fn band_line(b: &layertrace::BandCheck) -> String {
    format!(
        "smooth: {} differing pixels within {} px of the border (largest distance {:.3} px), {} beyond\n",
        b.differing - b.beyond,
        b.nu,
        b.max_distance,
        b.beyond
    )
}

/// `n` and the noun, singular or plural.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The summary line: size, contours, pieces by kind, model, threshold, time.
pub fn summary(name: &str, v: &Vectorized, options: &Options, start: Instant) -> String {
    let d = &v.decomposition;
    let basis = d.model.basis();
    let mut kinds: BTreeMap<CurveKind, usize> = BTreeMap::new();
    for p in d.pieces.iter().flatten() {
        let k = layertrace::piece_kind(&basis as &dyn Basis, &p.certificate);
        *kinds.entry(k).or_default() += 1;
    }
    let kinds: Vec<String> = kinds
        .iter()
        .map(|(k, &n)| {
            let (one, many) = match (k, d.model) {
                // The line model's only degenerate pieces are those without an equation.
                (CurveKind::Degenerate, layertrace::Model::Line) => {
                    ("piece without equation", "pieces without equation")
                }
                _ => kind_nouns(*k),
            };
            count(n, one, many)
        })
        .collect();
    let kinds = if kinds.is_empty() {
        String::new()
    } else {
        format!(" ({})", kinds.join(", "))
    };
    let holes = d.contours.iter().filter(|c| c.hole).count();
    let threshold = match (&v.colour, options.alpha) {
        (Some(c), _) => format!(
            "{} ({}, layout {})",
            count(c.regions.image.palette().len(), "colour", "colours"),
            if c.regions.exact {
                "the image's own".to_string()
            } else {
                format!("quantized, {} fringe pixel changes", c.regions.fringe)
            },
            options.layout.name()
        ),
        (None, true) => "alpha channel".to_string(),
        (None, false) => threshold_text(v, options),
    };
    format!(
        "{name}: {}x{}, {} ({}), {}{kinds}, model {}, {threshold}{}, {:.1} ms",
        v.mask.width(),
        v.mask.height(),
        count(d.contours.len(), "contour", "contours"),
        if holes == 0 {
            "no holes".to_string()
        } else {
            count(holes, "hole", "holes")
        },
        count(d.piece_count(), "piece", "pieces"),
        d.model,
        if options.invert { ", inverted" } else { "" },
        start.elapsed().as_secs_f64() * 1e3
    )
}

/// How the summary names the threshold.
fn threshold_text(v: &Vectorized, options: &Options) -> String {
    match options.effective_threshold() {
        layertrace::Threshold::Otsu => format!("threshold {} (Otsu)", v.threshold),
        layertrace::Threshold::Adaptive { radius, k_percent } => format!(
            "threshold adaptive (radius {radius}, k {:.2}, mean {})",
            f64::from(k_percent) / 100.0,
            v.threshold
        ),
        _ => format!("threshold {}", v.threshold),
    }
}

/// What the summary calls pieces of each kind (singular, plural).
fn kind_nouns(k: CurveKind) -> (&'static str, &'static str) {
    match k {
        CurveKind::Line => ("line", "lines"),
        CurveKind::Circle => ("circular arc", "circular arcs"),
        CurveKind::Ellipse => ("elliptic arc", "elliptic arcs"),
        CurveKind::Parabola => ("parabolic arc", "parabolic arcs"),
        CurveKind::Hyperbola => ("hyperbolic arc", "hyperbolic arcs"),
        CurveKind::Degenerate => ("degenerate conic", "degenerate conics"),
        _ => ("polynomial curve", "polynomial curves"),
    }
}
