//! The `layertrace` command-line tool: parse arguments, call the library, report.

use clap::Parser;
use layertrace::{
    compare, decompose, decomposition_json, decomposition_picture, default_scale, diff_image,
    load_path, piece_kind, png_bytes, rasterize_svg, staircases, svg_document, trace, write_atomic,
    Basis, Compat, Convention, CurveKind, Error, JsonHeader, LoadOptions, Model, OutlierRule,
    SvgOptions, Threshold,
};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

const AFTER_HELP: &str = "\
Examples:
  layertrace samples/glyph_g_liberationserif_cap120.png -o g.svg --report
  layertrace logo.png -o logo.svg --model circle --fill '#1a237e' --precision 2
  layertrace samples/glyph_g_liberationserif_cap120.png --json g.json --decomposition g.png
  layertrace scan.png --model circle --threshold otsu --json -
  layertrace samples/ipol/card_suits.png --compat ipol --model conic --decomposition cs.png

Exit codes:
  0  success
  1  bad input or output (missing, unreadable, not an image, truncated, empty, too large,
     unwritable output); the message says which, and no partial output file is left
  2  bad command-line arguments";

/// Vectorize a bitmap by Digital Level Layers: every border of the shapes is cut into
/// pieces, each described exactly by a digital line, circle, conic or polynomial layer.
#[derive(Parser, Debug)]
#[command(name = "layertrace", version, about, after_help = AFTER_HELP)]
struct Args {
    /// Input image (PNG, BMP, PNM/PBM, TIFF, GIF, JPEG, WebP).
    input: PathBuf,

    /// Write the SVG ('-' for standard output): one path, lines, exact circular and
    /// elliptic arcs, parabolas as quadratic Béziers, other curves as fitted cubics.
    #[arg(short, long, value_name = "OUT.svg")]
    output: Option<PathBuf>,

    /// Render the SVG back as `resvg --shape-rendering crispEdges` does and report on
    /// standard error: differing pixels, IoU, path commands by type, SVG size, pixel
    /// staircases (runs of 4 or more alternating axis-aligned steps of at most 2 px).
    #[arg(long)]
    report: bool,

    /// Write the round-trip differences as PNG: input black on white, missing pixels red,
    /// extra pixels blue.
    #[arg(long, value_name = "FILE.png")]
    diff: Option<PathBuf>,

    /// Fill colour of the SVG path.
    #[arg(long, value_name = "COLOUR", default_value = "black")]
    fill: String,

    /// Decimals of the SVG coordinates.
    #[arg(long, value_name = "N", default_value_t = 3, value_parser = clap::value_parser!(u8).range(0..=12))]
    precision: u8,

    /// Largest distance (pixels) of fitted cubic Béziers to the true curve (hyperbolas,
    /// degenerate conics, poly:D).
    #[arg(long, value_name = "PX", default_value_t = 0.05)]
    tolerance: f64,

    /// Draw a piece along its pixel edges when its curve passes closer than this (pixels,
    /// plus the coordinate rounding) to a pixel centre, which renderers working on a
    /// 1/64 px grid could paint on either side; 0 keeps every curve (smaller SVG).
    #[arg(long, value_name = "PX", default_value_t = 1.0 / 64.0, value_parser = parse_clearance)]
    min_clearance: f64,

    /// Write the pieces and their exact equations as JSON ('-' for standard output).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,

    /// Write a picture of the decomposition (PNG), in the style of the paper's figures.
    #[arg(long, value_name = "FILE.png")]
    decomposition: Option<PathBuf>,

    /// Family of curves: line, circle, conic, or poly:D (polynomials of degree D = 1..6).
    #[arg(long, short, default_value = "conic", value_parser = parse_model)]
    model: Model,

    /// Foreground is luma < N (0..=255), or 'otsu' for Otsu's threshold
    /// [default: 128, or otsu with --compat ipol].
    #[arg(long, value_name = "N|otsu", value_parser = parse_threshold)]
    threshold: Option<Threshold>,

    /// Light foreground on a dark background.
    #[arg(long)]
    invert: bool,

    /// Follow the conventions of the paper authors' program instead of layertrace's:
    /// alpha-stripped grey, 4-connected objects, crack-following borders, outliers
    /// whatever their colour. Reproduces the article's segment counts.
    #[arg(long, value_name = "ipol", value_parser = ["ipol"],
          conflicts_with_all = ["output", "report", "diff"])]
    compat: Option<String>,

    /// Enlargement of the decomposition picture [default: about 800 pixels wide].
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=64))]
    scale: Option<u32>,

    /// Refuse images with more pixels than this (checked before decoding).
    #[arg(long, value_name = "N", default_value_t = 400_000_000)]
    max_pixels: u64,

    /// Worker threads for the decomposition (default: all cores).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,

    /// No summary line on standard error.
    #[arg(long, short)]
    quiet: bool,
}

fn parse_model(s: &str) -> Result<Model, String> {
    let m: Model = s.parse().map_err(|e| format!("{e}"))?;
    if matches!(m, Model::Quadric3 | Model::Poly3(_)) {
        return Err("3D models apply to point sets, not to images".into());
    }
    Ok(m)
}

fn parse_clearance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v >= 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a distance in pixels (a number >= 0)")),
    }
}

fn parse_threshold(s: &str) -> Result<Threshold, String> {
    if s.eq_ignore_ascii_case("otsu") {
        return Ok(Threshold::Otsu);
    }
    s.parse::<u8>()
        .map(Threshold::Fixed)
        .map_err(|_| format!("'{s}' is neither a number 0..=255 nor 'otsu'"))
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("layertrace: {e}");
            ExitCode::from(1)
        }
    }
}

fn run(args: &Args) -> Result<(), Error> {
    let start = Instant::now();
    if let Some(n) = args.threads {
        // Only fails if a pool exists already, which cannot happen here.
        // The main thread is one of the workers: with one thread, none is spawned and no
        // work is handed between threads.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
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
    };
    let loaded = load_path(&args.input, &opts)?;
    let mask = &loaded.mask;
    let (convention, rule) = if ipol {
        (Convention::Ipol, OutlierRule::Any)
    } else {
        (Convention::Default, OutlierRule::NotInPiece)
    };
    let contours = trace(mask, convention);
    let d = decompose(contours, args.model, rule);

    if let Some(path) = &args.json {
        let header = JsonHeader {
            width: mask.width(),
            height: mask.height(),
            threshold: loaded.threshold,
            invert: args.invert,
        };
        write_atomic(path, decomposition_json(&d, &header).as_bytes())?;
    }
    if let Some(path) = &args.decomposition {
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
        write_atomic(path, &bytes)?;
    }

    if args.output.is_some() || args.report || args.diff.is_some() {
        let opts = SvgOptions {
            fill: args.fill.clone(),
            precision: args.precision,
            tolerance: args.tolerance,
            min_clearance: args.min_clearance,
        };
        let out = svg_document(&d, mask.width(), mask.height(), &opts);
        if let Some(path) = &args.output {
            write_atomic(path, out.svg.as_bytes())?;
        }
        if args.report || args.diff.is_some() {
            let actual = rasterize_svg(&out.svg, mask.width(), mask.height())?;
            let r = compare(mask, &actual);
            if let Some(path) = &args.diff {
                let bytes =
                    png_bytes(&diff_image(mask, &actual)).map_err(|source| Error::Encode {
                        path: path.clone(),
                        source,
                    })?;
                write_atomic(path, &bytes)?;
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
                eprintln!(
                    "svg: {} bytes, {} commands (M {}, L {}, A {}, Q {}, C {}, Z {}), {} pieces drawn along pixel edges, max fit error {:.3} px",
                    out.svg.len(),
                    c.total(),
                    c.move_to,
                    c.line,
                    c.arc,
                    c.quad,
                    c.cubic,
                    c.close,
                    out.fallbacks,
                    out.max_fit_error
                );
                let s = staircases(&out.svg)?;
                eprintln!(
                    "staircases: {} runs, {} segments in runs (of {} straight segments)",
                    s.runs, s.segments, s.lines
                );
            }
        }
    }

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
        eprintln!(
            "{}: {}x{}, {} contours ({} holes), {} pieces{}, model {}, {:.1} ms",
            args.input.display(),
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
