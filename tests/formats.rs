//! Output formats by name through the command line: `-o` writes SVG, PDF or EPS by its
//! extension, pictures are PNG only, other names are usage errors before any work.
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const SAMPLE: &str = "samples/glyph_g_liberationserif_cap120.png";

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_layertrace"))
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

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

/// The names in `dir` (temporaries included), sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
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
