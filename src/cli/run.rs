//! One run of the tool: check the outputs, load, decompose, export, commit, report.

use super::args::Args;
use layertrace::{
    compare, decompose, decomposition_json, decomposition_picture, default_scale, diff_image,
    load_path, piece_kind, png_bytes, rasterize_svg, staircases, svg_document, trace,
    work_estimate, Basis, Compat, Contour, Convention, CurveKind, Error, JsonHeader, LoadOptions,
    Mask, OutlierRule, OutputSet, SvgOptions, Threshold,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Runs the tool once. Every output is checked before the input is read and put in place
/// only when everything succeeded.
pub fn run(args: &Args) -> Result<(), Error> {
    let start = Instant::now();
    let stdin = args.input == Path::new("-");
    let mut outs = OutputSet::new((!stdin).then_some(args.input.as_path()));
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
    let svg_out = add("-o", args.output.as_ref())?;
    let json_out = add("--json", args.json.as_ref())?;
    let picture_out = add("--decomposition", args.decomposition.as_ref())?;
    let diff_out = add("--diff", args.diff.as_ref())?;

    if let Some(n) = args.threads {
        // The main thread is one of the workers: with one thread, none is spawned and no
        // work is handed between threads. Fails only if a pool exists already (a second run
        // in one process keeps the first pool).
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .use_current_thread()
            .build_global();
    }
    let ipol = args.compat.is_some();
    let opts = LoadOptions {
        threshold: args.threshold.unwrap_or(if ipol {
            Threshold::Otsu
        } else {
            Threshold::Fixed(128)
        }),
        invert: args.invert,
        compat: if ipol { Compat::Ipol } else { Compat::Default },
        max_pixels: args.max_pixels,
        max_memory: args
            .max_memory
            .unwrap_or_else(layertrace::default_max_memory),
        turdsize: args.turdsize,
    };
    let loaded = load_path(&args.input, &opts)?;
    if args.report && args.turdsize > 0 {
        eprintln!("cleaning: {}", loaded.cleaned);
    }
    let mask = &loaded.mask;
    let (convention, rule) = if ipol {
        (Convention::Ipol, OutlierRule::Any)
    } else {
        (Convention::Default, OutlierRule::NotInPiece)
    };
    let contours = trace(mask, convention);
    check_memory(args, &contours, mask, opts.max_memory)?;
    let d = decompose(contours, args.model, rule);

    if let Some(id) = json_out {
        let header = JsonHeader {
            width: mask.width(),
            height: mask.height(),
            threshold: loaded.threshold,
            invert: args.invert,
        };
        outs.write(id, decomposition_json(&d, &header).into_bytes())?;
    }
    if let (Some(id), Some(path)) = (picture_out, &args.decomposition) {
        let scale = args
            .scale
            .unwrap_or_else(|| default_scale(mask.width(), mask.height()));
        let img = decomposition_picture(mask, &d, scale, args.max_pixels.max(1 << 24)).ok_or(
            Error::PictureTooLarge {
                path: path.clone(),
                scale,
            },
        )?;
        let bytes = png_bytes(&img).map_err(|source| Error::Encode {
            path: path.clone(),
            source,
        })?;
        outs.write(id, bytes)?;
    }

    if svg_out.is_some() || args.report || diff_out.is_some() {
        let opts = SvgOptions {
            fill: args.fill.clone(),
            grid: args.grid,
            tolerance: args.tolerance,
            min_clearance: args.min_clearance,
        };
        let out = svg_document(&d, mask.width(), mask.height(), &opts);
        if args.report || diff_out.is_some() {
            let actual = rasterize_svg(&out.svg, mask.width(), mask.height())?;
            let r = compare(mask, &actual);
            if let (Some(id), Some(path)) = (diff_out, &args.diff) {
                let bytes =
                    png_bytes(&diff_image(mask, &actual)).map_err(|source| Error::Encode {
                        path: path.clone(),
                        source,
                    })?;
                outs.write(id, bytes)?;
            }
            if args.report {
                let c = out.commands;
                let pct = if r.foreground > 0 {
                    100.0 * r.differing as f64 / r.foreground as f64
                } else {
                    0.0
                };
                eprintln!(
                    "fidelity: {} differing pixels ({} missing, {} extra; {:.3}% of {} foreground), IoU {:.5}",
                    r.differing, r.missing, r.extra, pct, r.foreground, r.iou
                );
                let f = out.fallback_reasons;
                eprintln!(
                    "svg: {} bytes, {} commands (M {}, L {}, A {}, Q {}, C {}, Z {}), {} curve pieces redrawn as exact polygons, {} stretches along pixel edges, max fit error {:.3} px",
                    out.svg.len(),
                    c.total(),
                    c.move_to,
                    c.line,
                    c.arc,
                    c.quad,
                    c.cubic,
                    c.close,
                    f.rendered + f.curve + f.thin + f.no_polynomial,
                    f.zero_certificate,
                    out.max_fit_error
                );
                let s = staircases(&out.svg)?;
                eprintln!(
                    "staircases: {} runs, {} segments in runs (of {} straight segments)",
                    s.runs, s.segments, s.lines
                );
            }
        }
        if let Some(id) = svg_out {
            outs.write(id, out.svg.into_bytes())?;
        }
    }
    outs.commit()?;

    if !args.quiet {
        let basis = d.model.basis();
        let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
        for p in d.pieces.iter().flatten() {
            let k: CurveKind = piece_kind(&basis as &dyn Basis, &p.certificate);
            *kinds.entry(k.name()).or_default() += 1;
        }
        let kinds: Vec<String> = kinds.iter().map(|(k, n)| format!("{k} {n}")).collect();
        let kinds = if kinds.is_empty() {
            String::new()
        } else {
            format!(" ({})", kinds.join(", "))
        };
        let holes = d.contours.iter().filter(|c| c.hole).count();
        let name = if stdin {
            "<stdin>".into()
        } else {
            args.input.display().to_string()
        };
        eprintln!(
            "{}: {}x{}, {} contours ({} holes), {} pieces{}, model {}, {:.1} ms",
            name,
            mask.width(),
            mask.height(),
            d.contours.len(),
            holes,
            d.piece_count(),
            kinds,
            d.model,
            start.elapsed().as_secs_f64() * 1e3
        );
    }
    Ok(())
}

/// Refuses a run whose work after tracing would need more than `limit` bytes, before it
/// allocates anything: the decomposition, and what the asked outputs need on top of it.
fn check_memory(args: &Args, contours: &[Contour], mask: &Mask, limit: u64) -> Result<(), Error> {
    let (w, h) = (mask.width(), mask.height());
    let e = work_estimate(contours, args.model, w, h, rayon::current_num_threads());
    let mut needed = e.contours + e.decomposition;
    let svg = args.output.is_some() || args.report || args.diff.is_some();
    if svg {
        let check = args.report || args.diff.is_some();
        needed += e.svg_document
            + if check {
                e.svg_drawing.max(e.fidelity)
            } else {
                e.svg_drawing
            };
    }
    if args.json.is_some() {
        // The JSON text: measured at most 160 bytes per contour point (a one-pixel
        // checkerboard, every contour a single piece), doubled for the string's growth.
        let points: u64 = contours.iter().map(|c| c.points.len() as u64).sum();
        needed += 2 * 160 * (points + contours.len() as u64);
    }
    if args.decomposition.is_some() {
        // A picture over decomposition_picture's own bound is refused there, not drawn.
        let k = u64::from(args.scale.unwrap_or_else(|| default_scale(w, h)));
        let pixels = u64::from(w) * k * u64::from(h) * k;
        needed += 3 * pixels.min(args.max_pixels.max(1 << 24));
    }
    if needed > limit {
        let path = if args.input == Path::new("-") {
            PathBuf::from("<stdin>")
        } else {
            args.input.clone()
        };
        return Err(Error::NeedsMemory {
            path,
            needed,
            limit,
        });
    }
    Ok(())
}
