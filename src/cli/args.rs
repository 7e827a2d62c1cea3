//! The command line: every option, checked when it is parsed.

use clap::Parser;
use layertrace::{Cover, Format, Layout, Model, ParseLayoutError, Threshold};
use std::path::PathBuf;

const AFTER_HELP: &str = "\
Examples:
  layertrace samples/glyph_g_liberationserif_cap120.png -o g.svg --report
  layertrace logo.png -o logo.svg --model circle --fill '#1a237e' --grid 3
  layertrace logo.png -o logo.pdf --model circle
  layertrace samples/glyph_g_liberationserif_cap120.png --json g.json --decomposition g.png
  cat scan.png | layertrace - --model circle --threshold otsu --json -
  layertrace page.jpg -o page.svg --threshold adaptive --turdsize 4 --report
  layertrace samples/ipol/card_suits.png --compat ipol --model conic --decomposition cs.png
  layertrace scans/ logo.png --out-dir svg/ --model circle
  layertrace icon.png -o icon.svg --colors 16 --report
  layertrace photo.png -o photo.svg --colors 8 --json photo.json --diff photo-diff.png
  layertrace white-logo-on-transparency.png -o logo.svg --alpha

The web page (drop an image, see the result): layertrace serve --help
  layertrace serve --port 8080   (then open http://127.0.0.1:8080/)

Point sets (2-D or 3-D, from a JSON file): layertrace recognize --help
  layertrace recognize points.json --model quadric3
  (an image file named 'recognize' is given as ./recognize)

Output files:
  The extension names the format (any case): -o writes .svg, .pdf (PDF 1.4) or .eps
  (EPSF-3.0), the page the image's size with one pixel = one point; --decomposition and
  --diff write .png; '-' is SVG or PNG. Other names are refused (exit 2) before any work.
  Every output is checked before any work starts (its directory writable, not the input
  file, no two outputs to the same place) and written whole or not at all: each goes to a
  temporary file beside it, and all of them are renamed into place only when the whole run
  has succeeded, so a failure or an interrupt (Ctrl-C, SIGTERM) leaves every destination as
  it was and no temporary file behind. An existing file is replaced atomically and keeps its
  permissions; a symbolic link is followed (the file it names is written, the link stays);
  devices, FIFOs and /dev/stdout are written in place; '-' is standard output.

Exit codes:
  0  success
  1  bad input or output (missing, unreadable, not an image, truncated, empty, too large,
     unwritable output, output naming the input); the message says which, and no output
     file is changed
  2  bad command-line arguments (also: two outputs to the same place, an output name
     without a known extension, several inputs or a folder without --out-dir)
  128+N  stopped by signal N (130 Ctrl-C, 143 SIGTERM), no output file changed (but with
     --out-dir the finished inputs' files stay, and a signal while standard output is
     written leaves the files in place; one after the files are in place ends with 0)";

/// Vectorize a bitmap by Digital Level Layers: every border of the shapes is cut into
/// pieces, each described exactly by a digital line, circle, conic or polynomial layer.
#[derive(Parser, Debug)]
#[command(name = "layertrace", version, about, after_help = AFTER_HELP)]
pub struct Args {
    /// Input images (PNG, BMP, PNM/PBM, TIFF, GIF, JPEG, WebP), or folders of them (their
    /// image files, by extension, in name order); '-' reads standard input.
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<PathBuf>,

    /// Write the drawing as SVG, PDF or EPS, chosen by the extension: .svg, .pdf, .eps
    /// ('-' for standard output, SVG). Paths of lines, parabolas as quadratic Béziers,
    /// circular and elliptic arcs as cubics within 0.01 px of the exact arc, other curves as
    /// fitted cubics (an outer border and its holes in the same path); PDF and EPS hold the
    /// same coordinates, one pixel = one point.
    #[arg(short, long, value_name = "OUT.svg|pdf|eps")]
    pub output: Option<PathBuf>,

    /// Write each input's drawing into DIR as NAME.svg (or .pdf, .eps: --out-format; NAME: the input's file name without its
    /// extension; DIR is created if missing). Inputs are processed in parallel; a failed
    /// input is named on standard error, the others are still written, and the exit code is 1.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["output", "json", "decomposition", "diff"])]
    pub out_dir: Option<PathBuf>,

    /// The format of the files --out-dir writes: svg, pdf or eps.
    #[arg(long, value_name = "svg|pdf|eps", default_value = "svg", requires = "out_dir",
          value_parser = parse_format)]
    pub out_format: Format,

    /// Render the SVG back as `resvg --shape-rendering crispEdges` does and report on
    /// standard error: differing pixels, IoU, path commands by type, SVG size, pixel
    /// staircases (runs of 4 or more alternating axis-aligned steps of at most 2 px). With
    /// --colors: differing pixels per colour and in total, and seam pixels (pixels inside
    /// the coloured area, their 5x5 neighbourhood all in regions, where the anti-aliased
    /// rendering lets the background show: alpha below 255).
    #[arg(long)]
    pub report: bool,

    /// Write the round-trip differences as PNG (FILE.png, or '-' for standard output): the
    /// foreground mask (the input after thresholding) black on white, missing pixels red,
    /// extra pixels blue. With --colors: the regions faded, pixels of a wrong colour red,
    /// painted pixels of no region blue.
    #[arg(long, value_name = "FILE.png")]
    pub diff: Option<PathBuf>,

    /// Fill colour of the SVG path (a CSS colour: a name, #rgb, #rrggbb, rgb(…), hsl(…)).
    #[arg(long, value_name = "COLOUR", default_value = "black", value_parser = parse_colour)]
    pub fill: String,

    /// SVG coordinates are multiples of 1/2^N pixel (0 to 6; 6 is the 1/64 px vertex grid of
    /// tiny-skia and Skia), written exactly: N = 4 writes at most four decimals. Every
    /// contour is checked in tiny-skia on that grid, so a coarser grid only costs commands.
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = clap::value_parser!(u8).range(0..=6))]
    pub grid: u8,

    /// Largest distance (pixels, 0.001 to 10) of fitted cubic Béziers to the true curve
    /// (hyperbolas, degenerate conics, poly:D).
    #[arg(long, value_name = "PX", default_value_t = 0.05, value_parser = parse_tolerance)]
    pub tolerance: f64,

    /// Draw a curve piece as its exact polygon (straight segments) without trying its curve when
    /// the curve passes closer than this (pixels, 0 to 10) to a pixel centre; larger values
    /// give more margin for other renderers. Every curve is checked in tiny-skia anyway; 0
    /// tries them all (the default 1/32 skips those that practically never pass).
    #[arg(long, value_name = "PX", default_value_t = 1.0 / 32.0, value_parser = parse_clearance)]
    pub min_clearance: f64,

    /// Draw a curve piece of fewer than N contour points as its exact polygon, joined to its
    /// neighbours' and smoothed with them, without trying its curve: on a short piece the
    /// curve's own command saves nothing (fewer commands and bytes, less time). 0 tries the
    /// curves of short pieces too (with --max-curve-points 0, every curve); the JSON keeps
    /// every piece's equation either way.
    #[arg(long, value_name = "N", default_value_t = layertrace::DEFAULT_MIN_CURVE_POINTS)]
    pub min_curve_points: usize,

    /// Draw a curve piece of more than N contour points as its exact polygon, smoothed with
    /// its neighbours' and drawn in cubics along its gentle turns, without trying its curve:
    /// long curves seldom pass the render check, and the cubics draw them in fewer commands
    /// (less time, fewer bytes). 0 sets no limit (with --min-curve-points 0, every curve is
    /// tried); the JSON keeps every piece's equation either way.
    #[arg(long, value_name = "N", default_value_t = layertrace::DEFAULT_MAX_CURVE_POINTS)]
    pub max_curve_points: usize,

    /// Keep the square corners of one-pixel features (lone pixels, one-pixel spurs and
    /// notches), for pixel art. By default the corners inside a pixel staircase are cut by
    /// half a pixel (a lone pixel becomes a diamond, a spur a spike), which changes no pixel
    #[arg(long)]
    pub square_corners: bool,

    /// Write the pieces and their exact equations as JSON ('-' for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write a picture of the decomposition (PNG: FILE.png, or '-' for standard output), in
    /// the style of the paper's figures.
    #[arg(long, value_name = "FILE.png")]
    pub decomposition: Option<PathBuf>,

    /// Family of curves: line, circle, conic, or poly:D (polynomials of degree D = 1..6).
    #[arg(long, short, default_value = "conic", value_parser = parse_model)]
    pub model: Model,

    /// How each border is cut into pieces: 'greedy' (the paper's: each piece grown as far
    /// as it goes, from the border's first pixel) or 'optimal' (the fewest such pieces, cut
    /// anywhere round the border; never more pieces than greedy, and slower).
    #[arg(long, value_name = "greedy|optimal", default_value = "greedy")]
    pub cover: Cover,

    /// Smooth curves instead of the exact outline, for scans and design work: the outline
    /// may pass anywhere within NU pixels of the border (0 < NU <= 16; 1 is a good start).
    /// Guarantee: every pixel the SVG renders differently (resvg, crispEdges) lies within NU
    /// of the input's border, measured from its centre to the nearest pixel square of the
    /// other colour (a pixel beside the border is at 0.5); --report prints the largest such
    /// distance. Not with --compat ipol.
    #[arg(long, value_name = "NU")]
    pub smooth: Option<f64>,

    /// Foreground is luma < N (0..=255), 'otsu' for Otsu's threshold, or 'adaptive' for a
    /// local threshold that ignores lighting gradients and shadows (scans, photographs of
    /// pages; Sauvola's rule over a window of radius R pixels, 1 to 1000, default 16, with
    /// k = K/100, K 0 to 100, default 20: 'adaptive:R' or 'adaptive:R:K')
    /// [default: 128, or otsu with --compat ipol].
    #[arg(long, value_name = "N|otsu|adaptive[:R[:K]]", value_parser = parse_threshold)]
    pub threshold: Option<Threshold>,

    /// Drop specks and fill holes whose border encloses at most N pixels, after
    /// thresholding (potrace's -t); 0 keeps the thresholded image exactly. --report says
    /// what was dropped.
    #[arg(long, value_name = "N", default_value_t = 0, conflicts_with = "compat")]
    pub turdsize: u64,

    /// Light foreground on a dark background.
    #[arg(long)]
    pub invert: bool,

    /// Colour: the image becomes regions of at most N flat colours (1 to 256), one path per
    /// colour. An image with at most N colours keeps them exactly (pixel art, icons, flags,
    /// charts); any other is quantized (NeuQuant, Ward's merging, k-means) and its anti-aliasing
    /// fringes (1-2 px of in-between colour along an edge between two regions) join the
    /// nearer region. Pixels with alpha below 128 belong to no region. --report and --diff
    /// compare with these regions.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256),
          conflicts_with_all = ["threshold", "invert", "compat", "turdsize", "alpha", "decomposition"])]
    pub colors: Option<u16>,

    /// How --colors draws the regions: 'stack' (each colour's path also covers the colours
    /// drawn after it, which paint over it: exact in crispEdges, and no background shows
    /// between regions when anti-aliased) or 'partition' (regions side by side, every
    /// shared border drawn once and used by both: no overlap, for editors and GIS; exact in
    /// crispEdges, but anti-aliased renderers show faint hairlines along shared borders).
    #[arg(long, value_name = "stack|partition", default_value = "stack",
          value_parser = parse_layout, requires = "colors")]
    pub layout: Layout,

    /// The alpha channel is the shape (alpha at least 128), whatever its colour: for
    /// one-colour icons on transparency, such as a white logo.
    #[arg(long, conflicts_with_all = ["threshold", "invert", "compat"])]
    pub alpha: bool,

    /// Follow the conventions of the paper authors' program instead of layertrace's:
    /// alpha-stripped grey, 4-connected objects, crack-following borders, outliers
    /// whatever their colour. Reproduces the article's segment counts.
    #[arg(long, value_name = "ipol", value_parser = ["ipol"],
          conflicts_with_all = ["output", "report", "diff"])]
    pub compat: Option<String>,

    /// Enlargement of the decomposition picture, 1 to 64 [default: about 800 pixels wide].
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub scale: Option<u32>,

    /// Refuse images with more pixels than this (checked before decoding).
    #[arg(long, value_name = "N", default_value_t = 400_000_000,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub max_pixels: u64,

    /// Refuse images whose decoding would need more memory than this, e.g. 2G, 512M, 1.5GiB
    /// (checked before decoding) [default: half the RAM, within the process's ulimit].
    #[arg(long, value_name = "SIZE", value_parser = layertrace::parse_memory_size)]
    pub max_memory: Option<u64>,

    /// Worker threads for the decomposition, 1 to 4 × the cores [default: all cores].
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,

    /// No summary line on standard error.
    #[arg(long, short)]
    pub quiet: bool,
}

fn parse_layout(s: &str) -> Result<Layout, String> {
    s.parse().map_err(|e: ParseLayoutError| e.to_string())
}

pub(super) fn parse_model(s: &str) -> Result<Model, String> {
    Model::parse_image_model(s).map_err(|e| e.to_string())
}

/// A finite number in `lo..=hi`.
fn number_in(s: &str, lo: f64, hi: f64, what: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (lo..=hi).contains(&v) => Ok(v),
        _ => Err(format!("'{s}' is not {what} (a number from {lo} to {hi})")),
    }
}

fn parse_format(s: &str) -> Result<Format, String> {
    Format::from_path(std::path::Path::new(&format!("x.{s}")))
        .map_err(|_| format!("'{s}' is not an output format (svg, pdf or eps)"))
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    number_in(s, 0.001, 10.0, "a distance in pixels")
}

fn parse_clearance(s: &str) -> Result<f64, String> {
    number_in(s, 0.0, 10.0, "a distance in pixels")
}

pub(super) fn parse_threshold(s: &str) -> Result<Threshold, String> {
    s.parse()
        .map_err(|e: layertrace::ParseThresholdError| e.to_string())
}

/// The most worker threads accepted: four per core (more only costs memory and start-up).
pub fn max_threads() -> usize {
    4 * std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn parse_threads(s: &str) -> Result<usize, String> {
    // Up to 4 is allowed on every machine; only more needs the core count, which costs
    // reading the cgroup's CPU quota (0.4 ms).
    let n = s.trim().parse::<usize>();
    if let Ok(n @ 1..=4) = n {
        return Ok(n);
    }
    let max = max_threads();
    match n {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "'{s}' is not a thread count from 1 to {max} (4 × this machine's cores)"
        )),
    }
}

/// A CSS colour as SVG accepts it; refused otherwise (it is written into an attribute).
fn parse_colour(s: &str) -> Result<String, String> {
    match s.parse::<svgtypes::Color>() {
        Ok(_) if !s.contains(['"', '<', '>', '&', '\'']) => Ok(s.trim().to_string()),
        _ => Err(format!(
            "'{s}' is not a colour (a name such as black, #rgb, #rrggbb, rgb(…) or hsl(…))"
        )),
    }
}
