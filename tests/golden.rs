//! Golden files, in resvg's style: the SVG and the JSON of a handful of samples, byte for
//! byte, so that a refactoring that claims to change nothing is checked to change nothing.
//!
//! The expected files are `tests/golden/NAME.svg` and `NAME.json`. On a difference the test
//! writes the new files to `target/golden-failures/` with `NAME-expected.png`,
//! `NAME-actual.png` and `NAME-diff.png` (the two SVGs as resvg draws them in crispEdges; diff:
//! red where only the expected SVG paints, blue where only the new one does) and names them.
//! An intended change is accepted by running the tests with `LAYERTRACE_BLESS=1`, which
//! rewrites the expected files; the commit then says why the output changed.

use layertrace::{diff_image, rasterize_svg, vectorize, Cover, Model, Options};
use std::path::{Path, PathBuf};

/// (name, sample, options): one of each model and of the cover, a colour run and a
/// smooth one, on samples small enough to keep the files short.
fn cases() -> Vec<(&'static str, &'static str, Options)> {
    let base = || Options::default().json(true);
    vec![
        (
            "glyph_g_conic",
            "samples/glyph_g_liberationserif_cap120.png",
            base(),
        ),
        (
            "glyph_g_line_optimal",
            "samples/glyph_g_liberationserif_cap120.png",
            base().model(Model::Line).cover(Cover::Optimal),
        ),
        (
            "fig15_circle",
            "samples/syn_fig15_ellipse_two_holes.png",
            base().model(Model::Circle),
        ),
        (
            "at_poly3",
            "samples/glyph_at_dejavusans_cap40.png",
            base().model(Model::Poly(3)),
        ),
        (
            "suits_smooth1",
            "samples/suits_black_dejavusans_cap120.png",
            base().smooth(1.0),
        ),
        (
            "logo_colours4",
            "samples/colour/colour_logo_aa.png",
            base().colors(4),
        ),
    ]
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Writes the pictures of both SVGs and their difference; returns where.
fn pictures(name: &str, expected: &str, actual: &str, width: u32, height: u32) -> String {
    let dir = repo("target/golden-failures");
    let _ = std::fs::create_dir_all(&dir);
    let (Ok(e), Ok(a)) = (
        rasterize_svg(expected, width, height),
        rasterize_svg(actual, width, height),
    ) else {
        return "(the SVGs could not be rendered)".into();
    };
    let grey = |m: &layertrace::Mask| {
        image::GrayImage::from_fn(m.width(), m.height(), |x, y| {
            image::Luma([if m.get(i64::from(x), i64::from(y)) {
                0
            } else {
                255
            }])
        })
    };
    let _ = grey(&e).save(dir.join(format!("{name}-expected.png")));
    let _ = grey(&a).save(dir.join(format!("{name}-actual.png")));
    let _ = diff_image(&e, &a).save(dir.join(format!("{name}-diff.png")));
    format!("{}/{name}-{{expected,actual,diff}}.png", dir.display())
}

#[test]
fn svg_and_json_are_byte_identical() {
    let bless = std::env::var_os("LAYERTRACE_BLESS").is_some_and(|v| v == "1");
    let golden = repo("tests/golden");
    let mut failures = Vec::new();
    for (name, sample, options) in cases() {
        let v = vectorize(&repo(sample), &options).unwrap();
        let svg = v.svg_text();
        let json = v.json.as_deref().unwrap();
        let (w, h) = (v.mask.width(), v.mask.height());
        for (ext, actual) in [("svg", svg), ("json", json)] {
            let path = golden.join(format!("{name}.{ext}"));
            if bless {
                std::fs::create_dir_all(&golden).unwrap();
                std::fs::write(&path, actual).unwrap();
                continue;
            }
            let expected = std::fs::read_to_string(&path).unwrap_or_else(|e| {
                panic!(
                    "{}: {e}; run with LAYERTRACE_BLESS=1 to write it",
                    path.display()
                )
            });
            if expected == actual {
                continue;
            }
            let out = repo("target/golden-failures");
            let _ = std::fs::create_dir_all(&out);
            let _ = std::fs::write(out.join(format!("{name}.{ext}")), actual);
            let line = expected
                .lines()
                .zip(actual.lines())
                .position(|(a, b)| a != b)
                .map_or(expected.lines().count().min(actual.lines().count()), |i| i);
            let pictures = if ext == "svg" {
                pictures(name, &expected, actual, w, h)
            } else {
                String::new()
            };
            failures.push(format!(
                "{name}.{ext}: differs from line {} on; the new file is in {} {pictures}",
                line + 1,
                out.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "golden files differ (LAYERTRACE_BLESS=1 accepts an intended change):\n{}",
        failures.join("\n")
    );
}
