//! Output formats by name through the command line: `-o` writes SVG, PDF or EPS by its
//! extension, pictures are PNG only, other names are usage errors before any work; and the
//! PDF and EPS files draw the input in real readers (poppler's `pdftoppm`, Ghostscript).
//!
//! The readers are external programs. Without them the rendering tests print a note and
//! pass, except when the environment variable `CI` is set: then they fail, so CI (which
//! installs them, see `.ci/run`) cannot skip them silently.

mod common;

use common::{bin, names, repo};

use kurbo::Shape;
use layertrace::{document_bytes, load_path, Format, LoadOptions, Mask};
use std::path::Path;
use std::process::{Command, Stdio};

const SAMPLE: &str = "samples/glyph_g_liberationserif_cap120.png";

fn scratch() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("layertrace-formats-")
        .tempdir()
        .unwrap()
}

/// Runs the CLI in `dir`: (exit code, stdout, stderr).
fn cli_in(dir: &Path, args: &[&str]) -> (i32, Vec<u8>, String) {
    let out = bin()
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        out.stdout,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn unknown_extensions_are_usage_errors_before_any_work() {
    let dir = scratch();
    let d = dir.path();
    let sample = repo(SAMPLE);
    let s = sample.to_str().unwrap();
    for (args, message) in [
        (
            vec![s, "-o", "x.txt"],
            "-o x.txt: unknown output format 'txt' (use .svg, .pdf or .eps)",
        ),
        (
            vec![s, "-o", "x.png", "--json", "x.json"],
            "-o x.png: unknown output format 'png' (use .svg, .pdf or .eps)",
        ),
        (
            vec![s, "--json", "x.json", "-o", "x"],
            "-o x: no extension to name the output format (use .svg, .pdf or .eps)",
        ),
        (
            vec![s, "-o", "/dev/null"],
            "-o /dev/null: no extension to name the output format (use .svg, .pdf or .eps)",
        ),
        (
            vec![s, "-o", "x.svg", "--decomposition", "x.svg"],
            "--decomposition x.svg: unknown output format 'svg' (use .png)",
        ),
        (
            vec![s, "--diff", "x.PDF"],
            "--diff x.PDF: unknown output format 'PDF' (use .png)",
        ),
        (
            vec![s, "--decomposition", "d"],
            "--decomposition d: no extension to name the output format (use .png)",
        ),
        // Before the input is even read: a missing input would be exit 1.
        (
            vec!["missing.png", "-o", "x.ps"],
            "-o x.ps: unknown output format 'ps' (use .svg, .pdf or .eps)",
        ),
    ] {
        let (code, stdout, err) = cli_in(d, &args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(err, format!("layertrace: {message}\n"), "{args:?}");
        assert!(stdout.is_empty(), "{args:?}");
        assert!(names(d).is_empty(), "{args:?}: left {:?}", names(d));
    }
}

#[test]
fn formats_by_extension_in_any_case() {
    let dir = scratch();
    let d = dir.path();
    let sample = repo(SAMPLE);
    let s = sample.to_str().unwrap();
    let (code, _, err) = cli_in(
        d,
        &[
            s,
            "-o",
            "g.PDF",
            "--decomposition",
            "d.Png",
            "--diff",
            "x.png",
            "-q",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(names(d), ["d.Png", "g.PDF", "x.png"]);
    assert!(std::fs::read(d.join("g.PDF"))
        .unwrap()
        .starts_with(b"%PDF-1.4\n"));
    for png in ["d.Png", "x.png"] {
        assert!(std::fs::read(d.join(png))
            .unwrap()
            .starts_with(b"\x89PNG\r\n"));
    }
    let (code, _, err) = cli_in(d, &[s, "-o", "g.eps", "-q"]);
    assert_eq!(code, 0, "{err}");
    let eps = std::fs::read_to_string(d.join("g.eps")).unwrap();
    assert!(eps.starts_with("%!PS-Adobe-3.0 EPSF-3.0\n"), "{eps}");
    assert!(eps.contains("\n%%BoundingBox: 0 0 110 163\n"), "{eps}");
    assert!(eps.ends_with("%%EOF\n"));
    // Standard output stays SVG; pictures to standard output are PNG.
    let (code, stdout, err) = cli_in(d, &[s, "-o", "-", "-q"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.starts_with(b"<svg "));
    let (code, stdout, err) = cli_in(d, &[s, "--decomposition", "-", "-q"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.starts_with(b"\x89PNG\r\n"));
}

/// EPS cannot hold a translucent fill: refused with one line, nothing written.
#[test]
fn translucent_eps_is_refused() {
    let dir = scratch();
    let d = dir.path();
    let sample = repo(SAMPLE);
    let args = [
        sample.to_str().unwrap(),
        "-o",
        "g.eps",
        "--fill",
        "rgba(0,0,0,0.5)",
    ];
    let (code, _, err) = cli_in(d, &args);
    assert_eq!(code, 1, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("cannot write EPS: a fill has opacity 0.502"),
        "{err}"
    );
    assert!(names(d).is_empty());
    // PDF has transparency.
    let args = [args[0], "-o", "g.pdf", "--fill", "rgba(0,0,0,0.5)", "-q"];
    let (code, _, err) = cli_in(d, &args);
    assert_eq!(code, 0, "{err}");
}

/// Whether `program` runs; when it does not, fails under CI and tells otherwise.
fn have(program: &str, version_arg: &str) -> bool {
    let ok = Command::new(program)
        .arg(version_arg)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "{program} is missing, and CI is set: install it (see .ci/run)"
        );
        eprintln!(
            "skipped: {program} is not installed (apt-get install poppler-utils ghostscript)"
        );
    }
    ok
}

/// Renderings are this many times finer than the image: see [`compare_centres`].
const FINE: u32 = 15;

/// Compares `mask` with a rendering `FINE` times finer, reading for each pixel the fine
/// pixel centred on its centre (FINE is odd). PostScript and PDF scan conversion paints
/// every device pixel the shape touches at all ("any part of pixel"), so at one device
/// pixel per image pixel every pixel the border crosses would be painted (448 extra pixels
/// of 4 347 for the glyph); finer, a pixel reads as painted when the shape comes within
/// 1/(2 FINE) px of its centre, close to the centre sampling of the SVG renderers.
/// Returns (missing, extra).
fn compare_centres(mask: &Mask, png: &Path) -> (u64, u64) {
    let img = image::open(png).unwrap().into_luma8();
    assert_eq!(
        img.dimensions(),
        (FINE * mask.width(), FINE * mask.height()),
        "{}",
        png.display()
    );
    let (mut missing, mut extra) = (0, 0);
    for y in 0..mask.height() {
        for x in 0..mask.width() {
            let want = mask.get(x.into(), y.into());
            let got = img.get_pixel(FINE * x + FINE / 2, FINE * y + FINE / 2).0[0] < 128;
            missing += u64::from(want && !got);
            extra += u64::from(got && !want);
        }
    }
    (missing, extra)
}

/// Writes `sample` as `ext` and renders it with `render(file, out_png)`; returns the input
/// mask's foreground and (missing, extra).
fn round_trip(sample: &str, ext: &str, render: impl Fn(&Path, &Path)) -> (u64, (u64, u64)) {
    let dir = scratch();
    let file = dir.path().join(format!("out.{ext}"));
    let (code, _, err) = cli_in(
        dir.path(),
        &[repo(sample).to_str().unwrap(), "-o", file.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{err}");
    let png = dir.path().join("render.png");
    render(&file, &png);
    let mask = load_path(&repo(sample), &LoadOptions::default())
        .unwrap()
        .mask;
    let foreground = (0..mask.height())
        .flat_map(|y| (0..mask.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| mask.get(x.into(), y.into()))
        .count() as u64;
    (foreground, compare_centres(&mask, &png))
}

fn run(cmd: &mut Command) {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The samples, each with the most differing pixels allowed: measured 13 (glyph g, both
/// readers) and 9 (the word), none missing — borders passing within 1/30 px of a pixel
/// centre — with poppler 22.12 and Ghostscript 10.00 at 15 × 72 dpi; twice that allowed.
const SAMPLES: [(&str, u64); 2] = [
    (SAMPLE, 26),
    ("samples/word_Layers_dejavusans-bold_cap40.png", 18),
];

#[test]
fn pdf_draws_the_input_in_poppler() {
    if !have("pdftoppm", "-v") {
        return;
    }
    for (sample, bound) in SAMPLES {
        let (foreground, (missing, extra)) = round_trip(sample, "pdf", |pdf, png| {
            let dpi = (72 * FINE).to_string();
            let stem = png.with_extension("");
            run(Command::new("pdftoppm")
                .args(["-r", &dpi, "-aa", "no", "-aaVector", "no", "-gray", "-png"])
                .arg("-singlefile")
                .arg(pdf)
                .arg(&stem));
        });
        eprintln!("{sample}: PDF in poppler: {missing} missing, {extra} extra of {foreground}");
        assert!(foreground > 500, "{sample}: {foreground}");
        assert!(
            missing + extra <= bound,
            "{sample}: {missing} + {extra} > {bound}"
        );
    }
}

/// Quadratic Béziers (which layertrace writes for parabolas, rarely in the samples) become
/// the same cubics: the PDF draws the pixels whose centres the true curves enclose (kurbo's
/// exact winding numbers). A rounded shape with an inner loop of the same orientation: a
/// hole with evenodd, filled with nonzero.
#[test]
fn quadratics_draw_their_true_curves() {
    if !have("pdftoppm", "-v") {
        return;
    }
    let dir = scratch();
    let d = "M10 50Q10 10 50 10Q93 10 90 50Q90 85 50 85.5Q10 89 10 50Z\
             M30 45Q50 25.0625 70 45Q50 65 30 45Z";
    let path = kurbo::BezPath::from_svg(d).unwrap();
    for rule in ["nonzero", "evenodd"] {
        let expected = Mask::from_fn(100, 90, |x, y| {
            let w = path.winding(kurbo::Point::new(x as f64 + 0.5, y as f64 + 0.5));
            if rule == "nonzero" {
                w != 0
            } else {
                w % 2 != 0
            }
        });
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"100\" \
             height=\"90\" viewBox=\"0 0 100 90\">\n\
             <path fill=\"black\" fill-rule=\"{rule}\" d=\"{d}\"/>\n</svg>\n"
        );
        let pdf = dir.path().join(format!("{rule}.pdf"));
        std::fs::write(&pdf, document_bytes(svg, Format::Pdf).unwrap()).unwrap();
        let png = dir.path().join(format!("{rule}.png"));
        run(Command::new("pdftoppm")
            .args([
                "-r",
                &(72 * FINE).to_string(),
                "-aa",
                "no",
                "-aaVector",
                "no",
            ])
            .args(["-gray", "-png", "-singlefile"])
            .arg(&pdf)
            .arg(png.with_extension("")));
        let (missing, extra) = compare_centres(&expected, &png);
        eprintln!("quadratics, {rule}: {missing} missing, {extra} extra");
        assert!(missing + extra <= 10, "{rule}: {missing} + {extra}");
    }
}

#[test]
fn eps_draws_the_input_in_ghostscript() {
    if !have("gs", "--version") {
        return;
    }
    for (sample, bound) in SAMPLES {
        let (foreground, (missing, extra)) = round_trip(sample, "eps", |eps, png| {
            run(Command::new("gs")
                .args(["-q", "-dSAFER", "-dBATCH", "-dNOPAUSE", "-sDEVICE=pnggray"])
                .arg(format!("-r{}", 72 * FINE))
                .args(["-dGraphicsAlphaBits=1", "-dEPSCrop"])
                .arg(format!("-sOutputFile={}", png.display()))
                .arg(eps));
        });
        eprintln!("{sample}: EPS in Ghostscript: {missing} missing, {extra} extra of {foreground}");
        assert!(foreground > 500, "{sample}: {foreground}");
        assert!(
            missing + extra <= bound,
            "{sample}: {missing} + {extra} > {bound}"
        );
    }
}
