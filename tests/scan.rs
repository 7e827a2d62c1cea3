//! The scan case: `tests/data/scan_text_1200x800_q70.jpg` (made by `scripts/make_scan.py`:
//! text, dust, a lighting gradient, a binding shadow at the left edge, a broad cast shadow
//! over the lower right, JPEG quality 70) through `--threshold adaptive --turdsize 4`.

use layertrace::{load_path, trace, Convention, LoadOptions, Mask, Threshold};
use std::collections::VecDeque;
use std::path::Path;

mod common;
use common::bin;

const SCAN: &str = "tests/data/scan_text_1200x800_q70.jpg";

fn load(threshold: Threshold, turdsize: u64) -> layertrace::Loaded {
    let opts = LoadOptions {
        threshold,
        turdsize,
        ..LoadOptions::default()
    };
    load_path(Path::new(SCAN), &opts).unwrap()
}

/// Foreground fraction of the rectangle `x0..x1` × `y0..y1`.
fn fraction(m: &Mask, (x0, x1): (i64, i64), (y0, y1): (i64, i64)) -> f64 {
    let fg = (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .filter(|&(x, y)| m.get(x, y))
        .count();
    fg as f64 / ((x1 - x0) * (y1 - y0)) as f64
}

/// Regions of the page, from the layout `make_scan.py` draws.
const BLANK_LIT: ((i64, i64), (i64, i64)) = ((560, 1200), (0, 120));
const BLANK_BINDING_SHADOW: ((i64, i64), (i64, i64)) = ((0, 30), (0, 800));
const BLANK_CAST_SHADOW: ((i64, i64), (i64, i64)) = ((700, 1200), (690, 800));
/// The second paragraph's lines, lit and in the cast shadow.
const TEXT_LIT: ((i64, i64), (i64, i64)) = ((300, 590), (420, 640));
const TEXT_CAST_SHADOW: ((i64, i64), (i64, i64)) = ((850, 1140), (420, 640));

#[test]
fn shadows_stay_background_and_text_stays_ink() {
    let f = |m: &Mask, (xs, ys): ((i64, i64), (i64, i64))| fraction(m, xs, ys);
    let adaptive = load(Threshold::ADAPTIVE, 0).mask;
    let otsu = load(Threshold::Otsu, 0).mask;
    // The case is hard: Otsu's global threshold makes both shadows largely ink.
    for region in [BLANK_BINDING_SHADOW, BLANK_CAST_SHADOW] {
        assert!(f(&otsu, region) > 0.3, "otsu {}", f(&otsu, region));
    }
    // The adaptive threshold keeps blank paper blank, lit or in shadow: noise in the deep
    // binding shadow leaves single pixels, which --turdsize 4 drops; dust remains (about
    // 0.3% of the page).
    let scan = load(Threshold::ADAPTIVE, 4).mask;
    let lit = f(&scan, BLANK_LIT);
    for region in [BLANK_LIT, BLANK_BINDING_SHADOW, BLANK_CAST_SHADOW] {
        let (raw, v) = (f(&adaptive, region), f(&scan, region));
        assert!(raw < 0.02 && v < 0.006, "blank paper {region:?}: {raw} {v}");
        assert!(
            v < 2.0 * lit + 0.001,
            "blank paper {region:?}: {v}, lit {lit}"
        );
    }
    // Text in the shadow is about as much ink as text in the light.
    let (a, b) = (f(&scan, TEXT_LIT), f(&scan, TEXT_CAST_SHADOW));
    assert!(a > 0.1 && (0.8..1.25).contains(&(b / a)), "text {a} vs {b}");
    let (a, b) = (f(&otsu, TEXT_LIT), f(&otsu, TEXT_CAST_SHADOW));
    assert!(b / a > 2.0, "otsu text {a} vs {b}");
    // A white page stays empty.
    let white =
        image::GrayImage::from_fn(300, 200, |x, y| image::Luma([240 - ((x + y) % 5) as u8]));
    let l = layertrace::threshold_image(
        &image::DynamicImage::ImageLuma8(white),
        &LoadOptions {
            threshold: Threshold::ADAPTIVE,
            ..LoadOptions::default()
        },
    );
    assert_eq!(l.mask.count_foreground(), 0);
}

/// The pixels of one component or hole.
type Region = Vec<(i64, i64)>;

/// The components (8-connected foreground) and holes (4-connected background not touching
/// the border) of `m`.
fn regions(m: &Mask) -> (Vec<Region>, Vec<Region>) {
    let (w, h) = (i64::from(m.width()), i64::from(m.height()));
    let mut seen = vec![false; (w * h) as usize];
    let (mut components, mut holes) = (Vec::new(), Vec::new());
    for y0 in 0..h {
        for x0 in 0..w {
            if seen[(y0 * w + x0) as usize] {
                continue;
            }
            let fg = m.get(x0, y0);
            seen[(y0 * w + x0) as usize] = true;
            let mut pixels = vec![(x0, y0)];
            let mut queue = VecDeque::from([(x0, y0)]);
            let mut touches = false;
            while let Some((x, y)) = queue.pop_front() {
                touches |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
                for dy in -1..=1 {
                    for dx in -1..=1i64 {
                        let (nx, ny) = (x + dx, y + dy);
                        if (dx != 0 && dy != 0 && !fg)
                            || !(0..w).contains(&nx)
                            || !(0..h).contains(&ny)
                            || seen[(ny * w + nx) as usize]
                            || m.get(nx, ny) != fg
                        {
                            continue;
                        }
                        seen[(ny * w + nx) as usize] = true;
                        pixels.push((nx, ny));
                        queue.push_back((nx, ny));
                    }
                }
            }
            if fg {
                components.push(pixels);
            } else if !touches {
                holes.push(pixels);
            }
        }
    }
    (components, holes)
}

#[test]
fn turdsize_drops_exactly_the_small_components_and_holes() {
    let raw = load(Threshold::ADAPTIVE, 0);
    let cleaned = load(Threshold::ADAPTIVE, 4);
    assert_eq!(raw.cleaned.components + raw.cleaned.holes, 0);
    // At 4 pixels the enclosed area of a border is its own pixel count: a component with a
    // hole has at least 4 + 1 pixels inside its border, a hole around an island 8 + 1. So
    // the small ones are those of at most 4 pixels.
    let (components, holes) = regions(&raw.mask);
    let small_components: Vec<_> = components.iter().filter(|c| c.len() <= 4).collect();
    let small_holes: Vec<_> = holes.iter().filter(|c| c.len() <= 4).collect();
    assert!(
        small_components.len() > 50,
        "the scan has specks: {}",
        small_components.len()
    );
    let mut expected = raw.mask.clone();
    for &(x, y) in small_components.iter().copied().flatten() {
        expected.set(x, y, false);
    }
    for &(x, y) in small_holes.iter().copied().flatten() {
        expected.set(x, y, true);
    }
    assert!(cleaned.mask == expected, "the cleaned mask differs");
    let c = cleaned.cleaned;
    assert_eq!(c.turdsize, 4);
    assert_eq!(c.components, small_components.len() as u64);
    assert_eq!(c.holes, small_holes.len() as u64);
    let pixels: usize = small_components
        .iter()
        .chain(&small_holes)
        .map(|r| r.len())
        .sum();
    assert_eq!(c.pixels, pixels as u64);
    // Each is one contour fewer.
    let before = trace(&raw.mask, Convention::Default).len() as u64;
    let after = trace(&cleaned.mask, Convention::Default).len() as u64;
    assert_eq!(before - after, c.components + c.holes);
    assert_eq!(before, (components.len() + holes.len()) as u64);
}

/// Runs the CLI; returns the contour count of its summary line and standard error.
fn cli(args: &[&str]) -> (u64, String) {
    let out = bin().arg(SCAN).args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?}: {err}");
    let summary = err.lines().last().unwrap_or_default();
    let contours = summary
        .split(", ")
        .find_map(|part| {
            part.strip_suffix(" contours")
                .or_else(|| part.split_once(" contours").map(|(n, _)| n))
        })
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no contour count in {summary:?}"));
    (contours, err)
}

#[test]
fn cli_adaptive_and_turdsize_give_far_fewer_contours_than_otsu() {
    let tmp = tempfile::Builder::new()
        .prefix("layertrace-scan-")
        .tempdir()
        .unwrap();
    let dir = tmp.path();
    let (svg_otsu, svg_scan) = (dir.join("otsu.svg"), dir.join("scan.svg"));
    let (otsu, _) = cli(&["--threshold", "otsu", "-o", svg_otsu.to_str().unwrap()]);
    let (scan, err) = cli(&[
        "--threshold",
        "adaptive",
        "--turdsize",
        "4",
        "--report",
        "-o",
        svg_scan.to_str().unwrap(),
    ]);
    assert!(2 * scan < otsu, "adaptive + turdsize {scan} vs otsu {otsu}");
    let size = |p: &Path| std::fs::metadata(p).unwrap().len();
    // 291 760 B against 390 476 B when measured (the shadows Otsu turns into ink are long
    // ragged borders; since their pieces of fewer than 12 points are drawn as polygons, the
    // gap is smaller than the 339 445 against 672 879 B before).
    assert!(5 * size(&svg_scan) < 4 * size(&svg_otsu));
    // --report says what cleaning dropped, as the library counted it.
    let cleaned = load(Threshold::ADAPTIVE, 4).cleaned;
    let line = format!("cleaning: {cleaned}");
    assert!(err.lines().any(|l| l == line), "{line:?} not in {err}");
    assert!(line.contains("components and") && line.ends_with("of at most 4 px"));
    tmp.close().unwrap();
}

#[test]
fn bad_values_are_refused_by_the_parser() {
    for args in [
        &["--threshold", "adaptive:0"][..],
        &["--threshold", "adaptive:5:101"],
        &["--threshold", "adaptive:5:20:1"],
        &["--threshold", "adaptive:x"],
        &["--turdsize", "-1"],
        &["--turdsize", "4", "--compat", "ipol"],
    ] {
        let out = bin().arg(SCAN).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error:"), "{args:?}: {err}");
    }
}
