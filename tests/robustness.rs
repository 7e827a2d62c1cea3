//! Bad inputs get a one-line error and exit code 1, never a panic or a partial file; the same
//! input gives byte-identical output across runs and thread counts.

mod common;

use layertrace::{
    decompose, decomposition_json, load_path, svg_document, trace, Convention, JsonHeader,
    LoadOptions, Model, OutlierRule, SvgOptions,
};
use std::path::Path;

/// A fresh folder of its own (random name, removed when dropped, even when the test fails).
fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("layertrace-rob-{name}-"))
        .tempdir()
        .unwrap()
}

/// Runs the CLI, returns (exit code, stderr).
fn cli(args: &[&str]) -> (i32, String) {
    let out = common::bin().args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn bad_inputs_fail_cleanly() {
    let tmp = scratch("bad");
    let dir = tmp.path();
    let d = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let good = std::fs::read("samples/sil_horse_skimage.png").unwrap();
    std::fs::write(d("truncated.png"), &good[..good.len() / 3]).unwrap();
    std::fs::write(d("text.png"), b"this is not an image\n").unwrap();
    std::fs::write(d("empty.png"), b"").unwrap();
    // A PNM header claiming zero width.
    std::fs::write(d("zero.pgm"), b"P5\n0 10\n255\n").unwrap();
    // A PNG header claiming 100000 x 100000 pixels (checked before decoding).
    let mut huge = good.clone();
    huge[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    let crc = crc32fast::hash(&huge[12..29]);
    huge[29..33].copy_from_slice(&crc.to_be_bytes());
    std::fs::write(d("huge.png"), &huge).unwrap();
    let json = d("out.json");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec![d("missing.png")], "cannot read"),
        // A folder is read only with --out-dir (tests/batch.rs); alone it is refused.
        (vec![dir.to_string_lossy().into_owned()], "is a folder"),
        (vec![d("truncated.png")], "cannot decode"),
        (vec![d("text.png")], "cannot decode"),
        (vec![d("empty.png")], ""),
        (vec![d("zero.pgm")], ""),
        (vec![d("huge.png")], "--max-pixels"),
        (
            vec![
                "samples/syn_tiny_blobs.png".into(),
                "--max-pixels".into(),
                "100".into(),
            ],
            "--max-pixels",
        ),
        (
            vec![
                "samples/syn_tiny_blobs.png".into(),
                "--json".into(),
                d("no/such/dir/out.json"),
            ],
            "cannot write",
        ),
    ];
    for (args, needle) in cases {
        let mut a: Vec<&str> = args.iter().map(String::as_str).collect();
        a.extend(["--json", json.as_str()]);
        if args.iter().any(|s| s == "--json") {
            a.truncate(a.len() - 2);
        }
        let (code, err) = cli(&a);
        let want = if needle == "is a folder" { 2 } else { 1 };
        assert_eq!(code, want, "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(err.starts_with("layertrace: "), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(
            !Path::new(&json).exists(),
            "{args:?}: output written on failure"
        );
    }
    // Usage errors: exit code 2.
    assert_eq!(
        cli(&["samples/syn_tiny_blobs.png", "--model", "spline"]).0,
        2
    );
    assert_eq!(
        cli(&["samples/syn_tiny_blobs.png", "--threshold", "300"]).0,
        2
    );
    tmp.close().unwrap();
}

#[test]
fn blank_and_full_images() {
    let tmp = scratch("blank");
    let dir = tmp.path();
    let white = image::GrayImage::from_pixel(7, 5, image::Luma([255]));
    let black = image::GrayImage::from_pixel(7, 5, image::Luma([0]));
    white.save(dir.join("white.png")).unwrap();
    black.save(dir.join("black.png")).unwrap();
    let load = |n: &str| load_path(&dir.join(n), &LoadOptions::default()).unwrap();
    assert!(trace(&load("white.png").mask, Convention::Default).is_empty());
    // All foreground: one contour, the image border (7·2 + 3·2 pixels).
    let cs = trace(&load("black.png").mask, Convention::Default);
    assert_eq!(cs.len(), 1);
    assert_eq!(cs[0].points.len(), 20);
    for f in ["white.png", "black.png"] {
        let path = dir.join(f).to_string_lossy().into_owned();
        let out = dir.join("o.json").to_string_lossy().into_owned();
        let (code, err) = cli(&[&path, "--json", &out]);
        assert_eq!(code, 0, "{err}");
    }
    tmp.close().unwrap();
}

fn outputs_with_threads(path: &str, model: Model, threads: usize) -> String {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let loaded = load_path(Path::new(path), &LoadOptions::default()).unwrap();
        let d = decompose(
            trace(&loaded.mask, Convention::Default),
            model,
            OutlierRule::NotInPiece,
        );
        let h = JsonHeader {
            width: loaded.mask.width(),
            height: loaded.mask.height(),
            threshold: loaded.threshold,
            invert: false,
        };
        let svg = svg_document(&d, h.width, h.height, &SvgOptions::default()).svg;
        decomposition_json(&d, &h) + &svg
    })
}

#[test]
fn deterministic_across_runs_and_threads() {
    for path in [
        "samples/lineart_cat_symbola_h300.png",
        "samples/digits_liberationsans_cap40.png",
    ] {
        for model in [Model::Line, Model::Conic] {
            let one = outputs_with_threads(path, model, 1);
            assert_eq!(one, outputs_with_threads(path, model, 2), "{path} {model}");
            assert_eq!(one, outputs_with_threads(path, model, 4), "{path} {model}");
            assert_eq!(one, outputs_with_threads(path, model, 1), "{path} {model}");
        }
    }
}

/// `-o /dev/stdout` into a file a shell opened for appending (`>> out.svg`): what was there
/// stays, the SVG follows it (renaming over `/dev/stdout`'s target used to replace the file).
#[cfg(target_os = "linux")]
#[test]
fn output_to_redirected_stdout_appends() {
    let tmp = scratch("stdout");
    let dir = tmp.path();
    let out = dir.join("out.svg");
    std::fs::write(&out, "HEAD\n").unwrap();
    let file = std::fs::OpenOptions::new().append(true).open(&out).unwrap();
    let status = common::bin()
        .args([
            "samples/glyph_at_dejavusans_cap40.png",
            "-o",
            "/dev/stdout",
            "-q",
        ])
        .stdout(file)
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with("HEAD\n<svg "),
        "{}",
        &text[..text.len().min(80)]
    );
    assert!(text.trim_end().ends_with("</svg>"));
    tmp.close().unwrap();
}
