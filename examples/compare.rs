//! Side-by-side comparison of layertrace with potrace and vtracer, measured the same way.
//!
//! `cargo build --release --examples && target/release/examples/compare [--runs N]
//! [--work DIR] [--diffs] IMAGES…` (or `scripts/compare.sh`, which installs the tools
//! first). The SVGs (and with `--diffs` a difference picture per SVG: input black on white,
//! missing pixels red, extra blue) stay in the work directory (default `target/compare`).
//!
//! For every image, the mask is layertrace's default thresholding (`load_path` with default
//! options: foreground = luma < 128). It is written once as a 0/255 grey PNG (read by
//! layertrace and vtracer) and as a PBM (read by potrace), so every tool sees the same pixels.
//! Each tool configuration is then run as a separate process:
//!
//! * layertrace line / circle / conic: `layertrace MASK.png -o OUT --model M --threads 1 -q`
//!   (the release binary next to this example's directory, or `$LAYERTRACE`);
//! * potrace default and `-a 0`: `potrace -s [-a 0] -o OUT MASK.pbm` (`$POTRACE` or `PATH`);
//! * vtracer binary mode, default curve mode (spline) and polygon:
//!   `vtracer --input MASK.png --output OUT --colormode bw [--mode polygon]`
//!   (`$VTRACER`, else `target/tools/bin/vtracer`, else `PATH`).
//!
//! One run under `/usr/bin/time -f %M` gives the peak resident memory and the SVG; then
//! `--runs` (default 5) plain runs give the median wall time of the whole command. Every SVG
//! gets its root `width`/`height` set to the image size in pixels (potrace writes them in
//! `pt`, which usvg would scale by 4/3; layertrace's and vtracer's are already the pixel size
//! and stay unchanged), is rendered with [`rasterize_svg`] (the resvg crate as
//! `resvg --shape-rendering crispEdges` draws it, one pixel per user unit) and compared with
//! the mask. Path commands are
//! counted with svgtypes' path parser, which expands implicit repeated commands; `M` and `Z`
//! are not counted. A tool that cannot be run is reported on standard error and its rows
//! are skipped.

use layertrace::{compare, diff_image, load_path, rasterize_svg, LoadOptions, Mask};
use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// Which file a tool reads.
#[derive(Clone, Copy)]
enum Input {
    /// The mask as a 0/255 grey PNG.
    Png,
    /// The mask as a binary PBM (P4).
    Pbm,
}

/// One tool configuration: a label, the program and how to call it.
struct Config {
    label: &'static str,
    program: PathBuf,
    input: Input,
    /// Arguments, with `{in}` and `{out}` replaced by the input and output paths.
    args: &'static [&'static str],
}

impl Config {
    fn command(&self, input: &Path, output: &Path) -> Vec<OsString> {
        self.args
            .iter()
            .map(|a| match *a {
                "{in}" => input.as_os_str().to_owned(),
                "{out}" => output.as_os_str().to_owned(),
                a => OsString::from(a),
            })
            .collect()
    }
}

/// Path commands by kind.
#[derive(Clone, Copy, Default)]
struct Counts {
    /// C, S, Q, T, A (absolute or relative).
    curves: u64,
    /// L, H, V (including the implicit line-tos after a move-to).
    lines: u64,
}

/// The measurements of one tool configuration on one image.
struct Row {
    image: String,
    tool: &'static str,
    counts: Counts,
    bytes: u64,
    missing: u64,
    extra: u64,
    median_ms: f64,
    /// Median CPU time (user + system), when `/proc/PID/schedstat` could be read.
    cpu_ms: Option<f64>,
    peak_mib: Option<f64>,
}

struct Options {
    runs: usize,
    /// Write a difference picture per SVG (input black, missing red, extra blue).
    diffs: bool,
    work: PathBuf,
    images: Vec<PathBuf>,
}

fn usage() -> ! {
    eprintln!("usage: compare [--runs N] [--work DIR] [--diffs] IMAGE…");
    std::process::exit(2);
}

fn parse_args() -> Options {
    let mut opts = Options {
        runs: 5,
        diffs: false,
        work: PathBuf::from("target/compare"),
        images: Vec::new(),
    };
    let mut args = std::env::args_os().skip(1);
    while let Some(a) = args.next() {
        match a.to_str() {
            Some("--runs") => {
                opts.runs = args
                    .next()
                    .and_then(|n| n.to_str().and_then(|n| n.parse().ok()))
                    .filter(|&n| n > 0)
                    .unwrap_or_else(|| usage());
            }
            Some("--work") => opts.work = args.next().map(PathBuf::from).unwrap_or_else(|| usage()),
            Some("--diffs") => opts.diffs = true,
            Some("-h" | "--help") => usage(),
            _ => opts.images.push(PathBuf::from(a)),
        }
    }
    if opts.images.is_empty() {
        usage();
    }
    opts
}

/// `name` in a directory of `PATH`.
fn in_path(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(name))
        .find(|p| p.is_file())
}

/// The program from `$var`, else the first of `candidates` that exists, else `PATH`.
fn locate(var: &str, candidates: &[PathBuf], name: &str) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os(var) {
        return Some(PathBuf::from(p));
    }
    candidates
        .iter()
        .find(|p| p.is_file())
        .cloned()
        .or_else(|| in_path(name))
}

/// Whether `program --version` runs and succeeds.
fn runs(program: &Path) -> bool {
    Command::new(program)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The tool configurations whose programs can be run; the others are reported and skipped.
fn configs() -> Vec<Config> {
    // This example lives in target/<profile>/examples/.
    let exe = std::env::current_exe().unwrap_or_default();
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let target_dir = profile_dir
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let layertrace = locate(
        "LAYERTRACE",
        &[profile_dir.join("layertrace")],
        "layertrace",
    );
    let potrace = locate("POTRACE", &[], "potrace");
    let vtracer = locate(
        "VTRACER",
        &[target_dir.join("tools/bin/vtracer")],
        "vtracer",
    );
    let mut out = Vec::new();
    for (name, program, list) in [
        (
            "layertrace",
            layertrace,
            &[
                (
                    "layertrace line",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--model",
                        "line",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
                (
                    "layertrace circle",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--model",
                        "circle",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
                (
                    "layertrace conic",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--model",
                        "conic",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
                (
                    "layertrace --smooth 0.5",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--smooth",
                        "0.5",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
                (
                    "layertrace --smooth 1",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--smooth",
                        "1",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
                (
                    "layertrace --smooth 2",
                    Input::Png,
                    &[
                        "{in}",
                        "-o",
                        "{out}",
                        "--smooth",
                        "2",
                        "--threads",
                        "1",
                        "-q",
                    ][..],
                ),
            ][..],
        ),
        (
            "potrace",
            potrace,
            &[
                ("potrace", Input::Pbm, &["-s", "-o", "{out}", "{in}"][..]),
                (
                    "potrace -a 0",
                    Input::Pbm,
                    &["-s", "-a", "0", "-o", "{out}", "{in}"][..],
                ),
            ][..],
        ),
        (
            "vtracer",
            vtracer,
            &[
                (
                    "vtracer spline (default)",
                    Input::Png,
                    &["--input", "{in}", "--output", "{out}", "--colormode", "bw"][..],
                ),
                (
                    "vtracer polygon",
                    Input::Png,
                    &[
                        "--input",
                        "{in}",
                        "--output",
                        "{out}",
                        "--colormode",
                        "bw",
                        "--mode",
                        "polygon",
                    ][..],
                ),
            ][..],
        ),
    ] {
        match program {
            Some(p) if runs(&p) => {
                for &(label, input, args) in list {
                    out.push(Config {
                        label,
                        program: p.clone(),
                        input,
                        args,
                    });
                }
            }
            Some(p) => eprintln!(
                "compare: {name} ({}) does not run; skipping its rows",
                p.display()
            ),
            None => eprintln!("compare: {name} not found; skipping its rows"),
        }
    }
    out
}

/// The mask as a binary PBM: 1 = black = foreground, rows padded to whole bytes.
fn pbm(mask: &Mask) -> Vec<u8> {
    let (w, h) = (mask.width(), mask.height());
    let mut out = format!("P4\n{w} {h}\n").into_bytes();
    for y in 0..h {
        let mut byte = 0u8;
        for x in 0..w {
            if mask.get(i64::from(x), i64::from(y)) {
                byte |= 0x80 >> (x % 8);
            }
            if x % 8 == 7 || x + 1 == w {
                out.push(byte);
                byte = 0;
            }
        }
    }
    out
}

/// The mask as a grey image: 0 = foreground, 255 = background.
fn grey(mask: &Mask) -> image::GrayImage {
    image::GrayImage::from_fn(mask.width(), mask.height(), |x, y| {
        image::Luma([if mask.get(i64::from(x), i64::from(y)) {
            0
        } else {
            255
        }])
    })
}

/// The XML tree of `svg`, DOCTYPE allowed (potrace writes one).
fn parse_xml(svg: &str) -> Option<roxmltree::Document<'_>> {
    let opt = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    roxmltree::Document::parse_with_options(svg, opt).ok()
}

/// `svg` with the `width` and `height` attributes of its root element set to `w` and `h`
/// (inserted if absent), and whether that changed anything.
fn pixel_size(svg: &str, w: u32, h: u32) -> Option<(String, bool)> {
    let doc = parse_xml(svg)?;
    let root = doc.root_element();
    let tag = root.range();
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    let mut changed = false;
    for (name, value) in [("width", w), ("height", h)] {
        let value = value.to_string();
        match root
            .attributes()
            .find(|a| a.name() == name && a.namespace().is_none())
        {
            Some(a) => {
                if a.value() != value {
                    changed = true;
                    edits.push((a.range(), format!("{name}=\"{value}\"")));
                }
            }
            None => {
                changed = true;
                let at = tag.start + "<svg".len();
                edits.push((at..at, format!(" {name}=\"{value}\"")));
            }
        }
    }
    let mut out = svg.to_string();
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    for (range, text) in edits {
        out.replace_range(range, &text);
    }
    Some((out, changed))
}

/// Path commands of every `d` attribute of `svg`, implicit repetitions expanded.
fn count_commands(svg: &str) -> Option<Counts> {
    use svgtypes::PathSegment as S;
    let doc = parse_xml(svg)?;
    let mut c = Counts::default();
    for node in doc.descendants().filter(|n| n.has_tag_name("path")) {
        let Some(d) = node.attribute("d") else {
            continue;
        };
        for seg in svgtypes::PathParser::from(d) {
            match seg.ok()? {
                S::LineTo { .. } | S::HorizontalLineTo { .. } | S::VerticalLineTo { .. } => {
                    c.lines += 1
                }
                S::CurveTo { .. }
                | S::SmoothCurveTo { .. }
                | S::Quadratic { .. }
                | S::SmoothQuadratic { .. }
                | S::EllipticalArc { .. } => c.curves += 1,
                S::MoveTo { .. } | S::ClosePath { .. } => {}
            }
        }
    }
    Some(c)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// Runs `program args` once with its output discarded; the error says what went wrong.
fn run(program: &Path, args: &[OsString]) -> Result<(), String> {
    let out = Command::new(program)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .output()
        .map_err(|e| format!("{}: {e}", program.display()))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{} exited with {}: {}",
            program.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ))
    }
}

/// CPU time (ms, user + system) of the children waited for so far.
fn children_cpu_ms() -> Option<f64> {
    use nix::sys::resource::{getrusage, UsageWho};
    let u = getrusage(UsageWho::RUSAGE_CHILDREN).ok()?;
    let ms = |t: nix::sys::time::TimeVal| t.tv_sec() as f64 * 1e3 + t.tv_usec() as f64 / 1e3;
    Some(ms(u.user_time()) + ms(u.system_time()))
}

/// Wall time (ms) of one run of `program args`, from spawning to its exit, and its CPU time
/// (ms, user + system, all its threads) by `getrusage(RUSAGE_CHILDREN)` before and after.
fn timed_run(program: &Path, args: &[OsString]) -> Result<(f64, Option<f64>), String> {
    let before = children_cpu_ms();
    let t = Instant::now();
    let status = Command::new(program)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .map_err(|e| format!("{}: {e}", program.display()))?;
    let wall = t.elapsed().as_secs_f64() * 1e3;
    let cpu = before.zip(children_cpu_ms()).map(|(b, a)| a - b);
    if !status.success() {
        return Err(format!("{} exited with {status}", program.display()));
    }
    Ok((wall, cpu))
}

/// Peak resident memory (MiB) of one run of `program args` under `/usr/bin/time`, or
/// `None` without it.
fn peak_memory(program: &Path, args: &[OsString], work: &Path) -> Result<Option<f64>, String> {
    let time = Path::new("/usr/bin/time");
    if !time.is_file() {
        run(program, args)?;
        return Ok(None);
    }
    let report = work.join("time.txt");
    let mut full: Vec<OsString> = vec!["-f".into(), "%M".into(), "-o".into()];
    full.push(report.clone().into_os_string());
    full.push(program.as_os_str().to_owned());
    full.extend(args.iter().cloned());
    run(time, &full)?;
    let text = std::fs::read_to_string(&report).map_err(|e| e.to_string())?;
    let kib: f64 = text
        .lines()
        .last()
        .and_then(|l| l.trim().parse().ok())
        .ok_or_else(|| format!("unexpected /usr/bin/time output {text:?}"))?;
    Ok(Some(kib / 1024.0))
}

fn measure(
    config: &Config,
    image: &str,
    mask: &Mask,
    inputs: (&Path, &Path),
    opts: &Options,
    resized: &mut Vec<&'static str>,
) -> Result<Row, String> {
    let input = match config.input {
        Input::Png => inputs.0,
        Input::Pbm => inputs.1,
    };
    let slug: String = config
        .label
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let output = opts.work.join(format!("{image}.{slug}.svg"));
    let _ = std::fs::remove_file(&output);
    let args = config.command(input, &output);
    let peak_mib = peak_memory(&config.program, &args, &opts.work)?;
    let svg = std::fs::read_to_string(&output)
        .map_err(|e| format!("reading {}: {e}", output.display()))?;
    let (sized, changed) = pixel_size(&svg, mask.width(), mask.height())
        .ok_or_else(|| format!("{} is not well-formed XML", output.display()))?;
    if changed && !resized.contains(&config.label) {
        resized.push(config.label);
    }
    let counts =
        count_commands(&svg).ok_or_else(|| format!("bad path data in {}", output.display()))?;
    let actual = rasterize_svg(&sized, mask.width(), mask.height()).map_err(|e| e.to_string())?;
    let r = compare(mask, &actual);
    if opts.diffs {
        let path = opts.work.join(format!("{image}.{slug}.diff.png"));
        diff_image(mask, &actual)
            .save(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let mut times = Vec::with_capacity(opts.runs);
    let mut cpu = Vec::with_capacity(opts.runs);
    for _ in 0..opts.runs {
        let (wall, c) = timed_run(&config.program, &args)?;
        times.push(wall);
        if let Some(c) = c {
            cpu.push(c);
        }
    }
    Ok(Row {
        image: image.to_string(),
        tool: config.label,
        counts,
        bytes: svg.len() as u64,
        missing: r.missing,
        extra: r.extra,
        median_ms: median(&mut times),
        cpu_ms: (cpu.len() == times.len()).then(|| median(&mut cpu)),
        peak_mib,
    })
}

fn ms(t: Option<f64>) -> String {
    t.map_or_else(|| "n/a".to_string(), |t| format!("{t:.1}"))
}

fn mib(m: Option<f64>) -> String {
    m.map_or_else(|| "n/a".to_string(), |m| format!("{m:.1}"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let opts = parse_args();
    let configs = configs();
    std::fs::create_dir_all(&opts.work)?;
    let mut rows: Vec<Row> = Vec::new();
    let mut sizes: Vec<(String, u32, u32, u64)> = Vec::new();
    let mut resized: Vec<&'static str> = Vec::new();
    for path in &opts.images {
        let image = path
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let mask = match load_path(path, &LoadOptions::default()) {
            Ok(l) => l.mask,
            Err(e) => {
                eprintln!("compare: {}: {e}; skipping", path.display());
                continue;
            }
        };
        let png = opts.work.join(format!("{image}.mask.png"));
        let pbm_path = opts.work.join(format!("{image}.mask.pbm"));
        grey(&mask).save(&png)?;
        std::fs::write(&pbm_path, pbm(&mask))?;
        sizes.push((
            image.clone(),
            mask.width(),
            mask.height(),
            mask.count_foreground(),
        ));
        for config in &configs {
            eprintln!("compare: {image}: {}", config.label);
            match measure(
                config,
                &image,
                &mask,
                (&png, &pbm_path),
                &opts,
                &mut resized,
            ) {
                Ok(row) => rows.push(row),
                Err(e) => eprintln!("compare: {image}: {}: {e}; row skipped", config.label),
            }
        }
    }
    print!("{}", report(&rows, &sizes, &configs, &resized, opts.runs));
    Ok(())
}

/// The markdown tables.
fn report(
    rows: &[Row],
    sizes: &[(String, u32, u32, u64)],
    configs: &[Config],
    resized: &[&str],
    runs: usize,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| image | tool | curves | lines | SVG bytes | differing px (missing + extra) | median ms | CPU ms | peak MiB |"
    );
    let _ = writeln!(s, "|---|---|--:|--:|--:|--:|--:|--:|--:|");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} ({} + {}) | {:.1} | {} | {} |",
            r.image,
            r.tool,
            r.counts.curves,
            r.counts.lines,
            r.bytes,
            r.missing + r.extra,
            r.missing,
            r.extra,
            r.median_ms,
            ms(r.cpu_ms),
            mib(r.peak_mib)
        );
    }

    let _ = writeln!(
        s,
        "\nSummary over the images (sums, except the median of the per-image median times and the largest peak memory):\n"
    );
    let _ = writeln!(
        s,
        "| tool | images | curves | lines | SVG bytes | differing px (missing + extra) | total ms | median ms | total CPU ms | median CPU ms | max peak MiB |"
    );
    let _ = writeln!(s, "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    for c in configs {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.tool == c.label).collect();
        if mine.is_empty() {
            continue;
        }
        let sum = |f: &dyn Fn(&Row) -> u64| mine.iter().map(|r| f(r)).sum::<u64>();
        let mut times: Vec<f64> = mine.iter().map(|r| r.median_ms).collect();
        let total: f64 = times.iter().sum();
        let peak = mine
            .iter()
            .filter_map(|r| r.peak_mib)
            .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
        let (missing, extra) = (sum(&|r| r.missing), sum(&|r| r.extra));
        let mut cpu: Vec<f64> = mine.iter().filter_map(|r| r.cpu_ms).collect();
        let (cpu_total, cpu_median) = if cpu.len() == mine.len() {
            (Some(cpu.iter().sum()), Some(median(&mut cpu)))
        } else {
            (None, None)
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} ({} + {}) | {:.1} | {:.1} | {} | {} | {} |",
            c.label,
            mine.len(),
            sum(&|r| r.counts.curves),
            sum(&|r| r.counts.lines),
            sum(&|r| r.bytes),
            missing + extra,
            missing,
            extra,
            total,
            median(&mut times),
            ms(cpu_total),
            ms(cpu_median),
            mib(peak)
        );
    }

    let find = |image: &str, tool: &str| rows.iter().find(|r| r.image == image && r.tool == tool);
    let _ = writeln!(
        s,
        "\nTime of layertrace conic relative to potrace (default), per image:\n"
    );
    let _ = writeln!(
        s,
        "| image | size | foreground px | potrace ms | layertrace conic ms | ratio | potrace CPU ms | layertrace conic CPU ms | CPU ratio |"
    );
    let _ = writeln!(s, "|---|--:|--:|--:|--:|--:|--:|--:|--:|");
    let (mut ratios, mut cpu_ratios) = (Vec::new(), Vec::new());
    let ratio = |p: Option<f64>, l: Option<f64>, acc: &mut Vec<f64>| match (p, l) {
        (Some(p), Some(l)) if p > 0.0 => {
            acc.push(l / p);
            format!("{:.1}×", l / p)
        }
        _ => "n/a".to_string(),
    };
    for (image, w, h, fg) in sizes {
        let (p, l) = (find(image, "potrace"), find(image, "layertrace conic"));
        let (pw, lw) = (p.map(|r| r.median_ms), l.map(|r| r.median_ms));
        let (pc, lc) = (p.and_then(|r| r.cpu_ms), l.and_then(|r| r.cpu_ms));
        let _ = writeln!(
            s,
            "| {image} | {w}×{h} | {fg} | {} | {} | {} | {} | {} | {} |",
            ms(pw),
            ms(lw),
            ratio(pw, lw, &mut ratios),
            ms(pc),
            ms(lc),
            ratio(pc, lc, &mut cpu_ratios)
        );
    }
    for (name, v) in [("wall", &mut ratios), ("CPU", &mut cpu_ratios)] {
        if !v.is_empty() {
            let geo = (v.iter().map(|r| r.ln()).sum::<f64>() / v.len() as f64).exp();
            let _ = writeln!(
                s,
                "\nRatio of {name} times: median {:.1}×, geometric mean {geo:.1}× over {} images.",
                median(v),
                v.len()
            );
        }
    }
    let _ = writeln!(
        s,
        "\nTimes: median of {runs} runs of the whole command (process start, reading the mask \
         file, writing the SVG), layertrace with `--threads 1`; ms is wall time, CPU ms the \
         child's user + system time (`getrusage(RUSAGE_CHILDREN)` differences). Peak MiB: maximum resident set \
         size of one run (`/usr/bin/time -f %M`). Curves: C/S/Q/T/A commands; lines: L/H/V \
         (implicit repetitions expanded; M and Z not counted). Differing pixels: the SVG \
         rasterized by usvg + tiny-skia without anti-aliasing, pixel centres, compared with the \
         mask."
    );
    if !resized.is_empty() {
        let _ = writeln!(
            s,
            "SVG width/height set to the image size in pixels before rasterizing (changed for: {}).",
            resized.join(", ")
        );
    }
    s
}
