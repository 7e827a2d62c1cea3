//! Smooth mode (`--smooth ν`): every pixel the SVG renders differently (resvg, crispEdges)
//! lies within ν of the input's border, with no pixel staircase, on the bundled samples, on
//! random bitmaps and on the scan.

mod common;

use common::{cli_in, repo, samples};
use layertrace::{
    band_check, border_distance, rasterize_svg, staircases, vectorize, Band, Mask, Options,
    Threshold,
};
use proptest::prelude::*;
use std::path::Path;

/// Vectorizes `source` exactly and at `nu`; checks the guarantee on the rendering and
/// returns (exact commands, smooth commands, differing pixels).
fn check(source: &Path, nu: f64, options: Options) -> (usize, usize, u64) {
    let smooth = vectorize(source, &options.clone().smooth(nu).fidelity(true)).unwrap();
    let f = smooth.fidelity.as_ref().unwrap();
    let band = f.band.expect("a band check in smooth mode");
    assert_eq!(band.differing, f.report.differing);
    assert_eq!(
        band.beyond, 0,
        "{source:?} at ν = {nu}: pixels farther than ν from the border differ (largest {:.3})",
        band.max_distance
    );
    assert!(band.max_distance <= nu);
    // Recomputed here from the rendering, independently of the library's check.
    let mask = &smooth.mask;
    let rendered = rasterize_svg(smooth.svg_text(), mask.width(), mask.height()).unwrap();
    for y in 0..i64::from(mask.height()) {
        for x in 0..i64::from(mask.width()) {
            if mask.get(x, y) != rendered.get(x, y) {
                let d = border_distance(mask, x, y, nu + 1.0);
                assert!(
                    d.is_some_and(|d| d <= nu),
                    "{source:?}: ({x}, {y}) at {d:?}"
                );
            }
        }
    }
    let stairs = staircases(smooth.svg_text()).unwrap();
    assert_eq!(stairs.runs, 0, "{source:?} at ν = {nu}: pixel staircases");
    let exact = vectorize(source, &options).unwrap();
    (
        exact.svg.unwrap().commands.total(),
        smooth.svg.unwrap().commands.total(),
        f.report.differing,
    )
}

#[test]
fn samples_within_one_pixel_with_fewer_commands() {
    let (mut exact, mut smooth, mut px) = (0, 0, 0);
    for s in samples() {
        let (e, sm, d) = check(Path::new(&s), 1.0, Options::default());
        // Each contour is drawn with whichever of its two drawings has fewer commands.
        assert!(sm <= e, "{s}: {sm} smooth commands, {e} exact");
        exact += e;
        smooth += sm;
        px += d;
    }
    // Smoothing is what it is for: far fewer commands than the exact outline (measured:
    // 4 186 of 6 820, 61%, since the exact drawings draw runs as fitted cubics; about 40%
    // before they merged lines and runs).
    assert!(
        smooth * 100 < exact * 65,
        "{smooth} smooth commands, {exact} exact"
    );
    println!("ν = 1: {smooth} commands (exact {exact}), {px} px differ");
}

#[test]
fn half_and_two_pixels_keep_the_guarantee() {
    for s in [
        "samples/glyph_g_liberationserif_cap120.png",
        "samples/syn_discs_r3_to_r200.png",
        "samples/syn_polygons_sharp.png",
    ] {
        let (_, c05, d05) = check(&repo(s), 0.5, Options::default());
        let (_, c2, d2) = check(&repo(s), 2.0, Options::default());
        // A wider band: fewer commands, more pixels free to differ.
        assert!(
            c2 <= c05 && d2 >= d05,
            "{s}: {c05}/{d05} at ½, {c2}/{d2} at 2"
        );
    }
}

#[test]
fn the_scan_at_one_pixel() {
    let scan = repo("tests/data/scan_text_1200x800_q70.jpg");
    let options = Options::default()
        .threshold(Threshold::ADAPTIVE)
        .turdsize(4);
    let (exact, smooth, _) = check(&scan, 1.0, options);
    // Measured: 17 036 commands smooth, 22 375 exact (76%; 72% before the exact drawings
    // drew runs as fitted cubics, 23 731 exact; 60% before they merged their lines, 28 190
    // exact); the ragged edges of the scan's letters are what smoothing removes.
    assert!(
        smooth * 100 < exact * 80,
        "{smooth} smooth commands, {exact} exact"
    );
}

#[test]
fn the_cli_reports_the_band_and_refuses_bad_distances() {
    let dir = tempfile::tempdir().unwrap();
    let g = repo("samples/glyph_g_liberationserif_cap120.png");
    let g = g.to_str().unwrap();
    let out = layertrace_out(dir.path(), &[g, "-o", "g.svg", "--smooth", "1", "--report"]);
    assert!(
        out.contains("within 1 px of the border (largest distance") && out.contains(", 0 beyond"),
        "{out}"
    );
    for bad in ["0", "-1", "nan", "17", "x"] {
        let arg = format!("--smooth={bad}");
        let (code, err) = cli_in(dir.path(), &[g, "-o", "bad.svg", &arg]);
        assert_ne!(code, 0, "--smooth {bad}");
        // One line says what is wrong (clap adds a hint line for values it cannot parse).
        assert!(err.lines().next().unwrap_or("").contains("smooth"), "{err}");
        assert!(!dir.path().join("bad.svg").exists());
    }
    let (code, _) = cli_in(
        dir.path(),
        &[g, "-o", "i.svg", "--smooth", "1", "--compat", "ipol"],
    );
    assert_ne!(code, 0);
}

/// The tool's standard error for a successful run.
fn layertrace_out(dir: &Path, args: &[&str]) -> String {
    let (code, err) = cli_in(dir, args);
    assert_eq!(code, 0, "{err}");
    err
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// On random bitmaps, the pixels that differ are all within ν of the border.
    #[test]
    fn random_bitmaps_keep_the_guarantee(
        bits in proptest::collection::vec(any::<bool>(), 18 * 18),
        blobs in proptest::collection::vec((2u32..16, 2u32..16, 1u32..7), 0..4),
        nu in prop_oneof![Just(0.5), Just(1.0), Just(1.5), Just(2.0), Just(3.0)],
    ) {
        // Noise thinned out, plus a few discs: borders of every shape and size.
        let mask = Mask::from_fn(18, 18, |x, y| {
            let disc = blobs.iter().any(|&(cx, cy, r)| {
                let (dx, dy) = (x as i64 - cx as i64, y as i64 - cy as i64);
                dx * dx + dy * dy <= i64::from(r * r)
            });
            disc ^ (bits[(y * 18 + x) as usize] && (x * 7 + y * 3) % 5 == 0)
        });
        let out = vectorize(&mask, &Options::default().smooth(nu).fidelity(true)).unwrap();
        let b = band_check(&mask, &out.fidelity.as_ref().unwrap().rendered, nu);
        prop_assert_eq!(b.beyond, 0, "largest distance {}\n{}", b.max_distance, out.svg_text());
        prop_assert!(Band::new(&mask, nu).is_some());
        // No staircase check here: contours touching the image border are drawn exactly,
        // and random bitmaps are full of one-pixel features there.
    }
}

#[test]
fn colour_layers_keep_the_guarantee_without_seams() {
    // (image, colours, whether smooth mode must take fewer commands than the exact drawing:
    // not on the chart, whose bars and small text the exact drawing joins into straight
    // runs — 360 commands against smooth mode's 380 when measured — where smooth mode must
    // stay within a tenth of it).
    for (path, n, fewer) in [
        ("samples/colour/colour_logo_aa.png", 4, true),
        ("samples/colour/colour_chart_aa.png", 6, false),
        ("samples/colour/colour_photo_like.png", 8, true),
    ] {
        let options = Options::default().colors(n).fidelity(true);
        let exact = vectorize(&repo(path), &options).unwrap();
        let v = vectorize(&repo(path), &options.smooth(1.0)).unwrap();
        let f = v.colour.as_ref().unwrap().fidelity.as_ref().unwrap();
        let b = f.band.expect("a band check in smooth mode");
        assert_eq!(b.differing, f.differing, "{path}");
        assert_eq!(b.beyond, 0, "{path}: largest distance {}", b.max_distance);
        assert_eq!(f.seams, 0, "{path}");
        let (e, s) = (
            exact.svg.unwrap().commands.total(),
            v.svg.as_ref().unwrap().commands.total(),
        );
        if fewer {
            assert!(s < e, "{path}: {s} smooth commands, {e} exact");
        } else {
            assert!(10 * s <= 11 * e, "{path}: {s} smooth commands, {e} exact");
        }
        assert_eq!(staircases(v.svg_text()).unwrap().runs, 0, "{path}");
    }
}
