//! Colour vectorization on the colour samples (samples/colour/, samples/ipol/card_suits.png):
//! exact in resvg crispEdges against the regions, no seams when anti-aliased, the input's
//! own colours kept when there are few enough, and the command line around it.

mod common;

use common::{cli_in, repo};
use layertrace::{
    decode_rgba, vectorize, BorderSource, Colour, Error, Layout, Options, OPAQUE_ALPHA,
};
use proptest::prelude::*;
use std::path::Path;

/// (sample, --colors): every kind the issue names.
const CASES: [(&str, u16); 6] = [
    ("samples/colour/colour_logo_crisp.png", 8),
    ("samples/colour/colour_logo_aa.png", 4),
    ("samples/colour/colour_sprite_pico8_32.png", 16),
    ("samples/colour/colour_chart_aa.png", 6),
    ("samples/colour/colour_photo_like.png", 8),
    ("samples/ipol/card_suits.png", 3),
];

#[test]
fn samples_are_exact_in_crisp_edges_and_seamless() {
    for (path, n) in CASES {
        let v = vectorize(&repo(path), &Options::default().colors(n).fidelity(true))
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        let c = v.colour.as_ref().unwrap();
        let f = c.fidelity.as_ref().unwrap();
        let colours = c.regions.image.palette().len();
        assert!(
            colours >= 2 && colours <= usize::from(n),
            "{path}: {colours}"
        );
        assert_eq!(c.layers.len(), colours);
        assert_eq!(f.differing, 0, "{path}: {:?}", f.colours);
        assert_eq!(f.seams, 0, "{path}");
        assert_eq!(f.pixels, v.mask.count_foreground());
        // One path per colour, filled with it, in drawing order.
        let svg = v.svg_text();
        let fills: Vec<&str> = svg
            .match_indices("<path fill=\"")
            .map(|(i, m)| &svg[i + m.len()..i + m.len() + 7])
            .collect();
        let order: Vec<String> = c.layers.iter().map(|l| l.colour.to_string()).collect();
        assert_eq!(fills, order, "{path}");
    }
}

#[test]
fn few_colours_are_the_inputs_own() {
    for (path, n) in [
        ("samples/colour/colour_logo_crisp.png", 8),
        ("samples/colour/colour_sprite_pico8_32.png", 16),
    ] {
        let bytes = std::fs::read(repo(path)).unwrap();
        let rgba = decode_rgba(&bytes, Path::new(path), u64::MAX, u64::MAX).unwrap();
        let v = vectorize(&bytes, &Options::default().colors(n)).unwrap();
        let c = v.colour.unwrap();
        assert!(c.regions.exact, "{path}");
        for (x, y, p) in rgba.enumerate_pixels() {
            let want = (p[3] >= OPAQUE_ALPHA).then(|| Colour::new(p[0], p[1], p[2]));
            assert_eq!(c.regions.image.colour(x.into(), y.into()), want, "{path}");
        }
    }
    // The sprite has its 16 colours; the crisp logo its 4 (and transparency).
    let sprite = vectorize(
        &repo("samples/colour/colour_sprite_pico8_32.png"),
        &Options::default().colors(16),
    )
    .unwrap();
    assert_eq!(sprite.colour.unwrap().regions.image.palette().len(), 16);
}

#[test]
fn anti_aliased_fringes_do_not_become_regions() {
    // The anti-aliased logo in up to 6 colours: two more than the drawing's four, which
    // quantization spends on blends along the touching edges; those thin fringes join
    // their neighbours, and the colours left are near the crisp logo's four, nearly every
    // pixel with the crisp logo's colour.
    let crisp = vectorize(
        &repo("samples/colour/colour_logo_crisp.png"),
        &Options::default().colors(8),
    )
    .unwrap()
    .colour
    .unwrap();
    let aa = vectorize(
        &repo("samples/colour/colour_logo_aa.png"),
        &Options::default().colors(6),
    )
    .unwrap()
    .colour
    .unwrap();
    assert!(!aa.regions.exact);
    assert!(aa.regions.fringe > 0);
    let (ci, ai) = (&crisp.regions.image, &aa.regions.image);
    assert_eq!(ai.palette().len(), 4);
    for &c in ci.palette() {
        let near = ai
            .palette()
            .iter()
            .map(|&a| a.distance(c))
            .fold(f64::MAX, f64::min);
        assert!(near < 24.0, "{c}: {near} from {:?}", ai.palette());
    }
    let (mut both, mut same) = (0u64, 0u64);
    for y in 0..i64::from(ci.height()) {
        for x in 0..i64::from(ci.width()) {
            if let (Some(a), Some(c)) = (ai.colour(x, y), ci.colour(x, y)) {
                both += 1;
                let nearest = ci
                    .palette()
                    .iter()
                    .min_by(|p, q| p.distance(a).total_cmp(&q.distance(a)))
                    .unwrap();
                same += u64::from(*nearest == c);
            }
        }
    }
    assert!(same as f64 > 0.97 * both as f64, "{same} of {both}");
}

/// A white disc on transparency.
fn white_logo() -> Vec<u8> {
    let img = image::RgbaImage::from_fn(24, 20, |x, y| {
        let (dx, dy) = (x as f64 - 11.5, y as f64 - 9.5);
        let a = if dx * dx + dy * dy < 49.0 { 255 } else { 0 };
        image::Rgba([255, 255, 255, a])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

#[test]
fn alpha_draws_a_white_logo_and_an_empty_binary_run_says_why() {
    let bytes = white_logo();
    let e = vectorize(&bytes, &Options::default()).unwrap_err();
    assert!(matches!(e, Error::NoForeground { .. }), "{e}");
    assert!(e.to_string().contains("--alpha") && !e.to_string().contains('\n'));
    let v = vectorize(&bytes, &Options::default().alpha(true).fidelity(true)).unwrap();
    assert!(v.mask.count_foreground() > 100);
    assert_eq!(v.fidelity.unwrap().report.differing, 0);
    // An opaque white image is simply empty, as before.
    let white = image::RgbaImage::from_pixel(8, 8, image::Rgba([255, 255, 255, 255]));
    let mut out = std::io::Cursor::new(Vec::new());
    white.write_to(&mut out, image::ImageFormat::Png).unwrap();
    let v = vectorize(&out.into_inner(), &Options::default()).unwrap();
    assert_eq!(v.mask.count_foreground(), 0);
}

#[test]
fn json_has_every_region_and_exact_equations() {
    let v = vectorize(
        &repo("samples/colour/colour_logo_crisp.png"),
        &Options::default().colors(8).json(true),
    )
    .unwrap();
    let j: serde_json::Value = serde_json::from_str(v.json.as_ref().unwrap()).unwrap();
    assert_eq!(j["format"], "layertrace-colour/1");
    assert_eq!(j["layout"], "stack");
    let c = v.colour.as_ref().unwrap();
    let regions = j["regions"].as_array().unwrap();
    assert_eq!(regions.len(), c.layers.len());
    let basis = layertrace::Model::Conic.basis();
    for (r, l) in regions.iter().zip(&c.layers) {
        assert_eq!(r["colour"], l.colour.to_string());
        assert_eq!(r["pixels"], l.pixels);
        let contours = r["contours"].as_array().unwrap();
        assert_eq!(contours.len(), l.decomposition.contours.len());
        // Every inlier of every piece in its layer, from the numbers written.
        for cj in contours {
            let points: Vec<layertrace::Pixel> = cj["points"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| layertrace::Pixel {
                    x: p[0].as_i64().unwrap() as i32,
                    y: p[1].as_i64().unwrap() as i32,
                })
                .collect();
            for piece in cj["pieces"].as_array().unwrap() {
                let num = |v: &serde_json::Value| -> Vec<i64> {
                    v.as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_i64().unwrap())
                        .collect()
                };
                let (o, a) = (num(&piece["origin"]), num(&piece["coefficients"]));
                let (lo, hi) = (
                    piece["lower"].as_i64().unwrap(),
                    piece["upper"].as_i64().unwrap(),
                );
                let (first, last) = (
                    piece["first"].as_u64().unwrap() as usize,
                    piece["last"].as_u64().unwrap() as usize,
                );
                for &p in &points[first..=last] {
                    let f = common::value(&basis, &o, &a, p);
                    assert!(i128::from(lo) <= f && f <= i128::from(hi));
                }
            }
        }
    }
}

#[test]
fn command_line() {
    let dir = tempfile::tempdir().unwrap();
    let logo = repo("samples/colour/colour_logo_aa.png");
    let logo = logo.to_str().unwrap();
    let (code, err) = cli_in(
        dir.path(),
        &[
            logo, "--colors", "4", "-o", "l.svg", "--report", "--diff", "d.png", "--json", "l.json",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("fidelity: 0 differing pixels"), "{err}");
    assert!(err.contains("0 seam pixels"), "{err}");
    assert!(err.contains("per colour"), "{err}");
    assert!(err.contains("4 colours (quantized"), "{err}");
    let svg = std::fs::read_to_string(dir.path().join("l.svg")).unwrap();
    assert_eq!(svg.matches("<path ").count(), 4);
    let diff = image::open(dir.path().join("d.png")).unwrap().to_rgb8();
    assert!(diff
        .pixels()
        .all(|p| p.0 != [255, 0, 0] && p.0 != [0, 0, 255]));
    assert!(dir.path().join("l.json").exists());
    // The partition layout: exact, one path per colour; its seams are counted too (the
    // shared borders' hairlines when anti-aliased).
    let (code, err) = cli_in(
        dir.path(),
        &[
            logo,
            "--colors",
            "4",
            "--layout",
            "partition",
            "-o",
            "p.svg",
            "--report",
            "--json",
            "p.json",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("fidelity: 0 differing pixels"), "{err}");
    assert!(err.contains("layout partition"), "{err}");
    let svg = std::fs::read_to_string(dir.path().join("p.svg")).unwrap();
    assert_eq!(svg.matches("<path ").count(), 4);
    let json = std::fs::read_to_string(dir.path().join("p.json")).unwrap();
    assert!(json.contains("\"layout\": \"partition\""));
    // The same drawing as PDF: one fill per colour.
    let (code, err) = cli_in(dir.path(), &[logo, "--colors", "4", "-o", "l.pdf"]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read(dir.path().join("l.pdf"))
        .unwrap()
        .starts_with(b"%PDF"));
    // Bad values and combinations are usage errors; no panic.
    for args in [
        &[logo, "--colors", "0"][..],
        &[logo, "--colors", "257"],
        &[logo, "--colors", "4", "--threshold", "100"],
        &[logo, "--colors", "4", "--alpha"],
        &[logo, "--layout", "stack"],
    ] {
        let (code, err) = cli_in(dir.path(), args);
        assert_eq!(code, 2, "{args:?}: {err}");
    }
    // A white logo on transparency: an error that names --alpha, then drawn with it.
    std::fs::write(dir.path().join("w.png"), white_logo()).unwrap();
    let (code, err) = cli_in(dir.path(), &["w.png", "-o", "w.svg"]);
    assert_eq!(code, 1);
    assert!(err.contains("--alpha") && err.lines().count() == 1, "{err}");
    assert!(!dir.path().join("w.svg").exists());
    let (code, err) = cli_in(dir.path(), &["w.png", "-o", "w.svg", "--alpha", "--report"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("fidelity: 0 differing"), "{err}");
}

/// The `<path>` elements of an SVG, each alone in a document of the same size.
fn each_path_alone(svg: &str) -> Vec<String> {
    let header = &svg[..svg.find('\n').unwrap() + 1];
    svg.lines()
        .filter(|l| l.starts_with("<path "))
        .map(|l| format!("{header}{l}\n</svg>\n"))
        .collect()
}

/// Every pixel of a region is painted by its own colour's path and by no other, every
/// pixel of no region by none (each path rendered alone in crispEdges).
fn assert_partition(svg: &str, c: &layertrace::ColourVectorized, what: &str) {
    let image = &c.regions.image;
    let (w, h) = (image.width(), image.height());
    let palette: Vec<String> = image.palette().iter().map(|c| c.to_string()).collect();
    let mut painted = vec![0u32; (w * h) as usize];
    for doc in each_path_alone(svg) {
        let fill = &doc[doc.find("<path fill=\"").unwrap() + 12..][..7];
        let k = palette.iter().position(|p| p == fill).unwrap();
        let mask = layertrace::rasterize_svg(&doc, w, h).unwrap();
        for y in 0..i64::from(h) {
            for x in 0..i64::from(w) {
                if mask.get(x, y) {
                    painted[(y * i64::from(w) + x) as usize] += 1;
                    assert_eq!(
                        image.get(x, y),
                        Some(k),
                        "{what}: ({x}, {y}) painted {fill}"
                    );
                }
            }
        }
    }
    for y in 0..i64::from(h) {
        for x in 0..i64::from(w) {
            let want = u32::from(image.get(x, y).is_some());
            assert_eq!(
                painted[(y * i64::from(w) + x) as usize],
                want,
                "{what}: ({x}, {y})"
            );
        }
    }
}

#[test]
fn partition_samples_are_exact_without_overlap() {
    for (path, n) in CASES {
        let options = Options::default()
            .colors(n)
            .layout(Layout::Partition)
            .fidelity(true)
            .json(true);
        let v = vectorize(&repo(path), &options).unwrap_or_else(|e| panic!("{path}: {e}"));
        let c = v.colour.as_ref().unwrap();
        let f = c.fidelity.as_ref().unwrap();
        assert_eq!(f.differing, 0, "{path}: {:?}", f.colours);
        let svg = v.svg_text();
        // One path per colour, in palette order.
        let fills: Vec<&str> = svg
            .match_indices("<path fill=\"")
            .map(|(i, m)| &svg[i + m.len()..i + m.len() + 7])
            .collect();
        let palette: Vec<String> = c
            .regions
            .image
            .palette()
            .iter()
            .map(|c| c.to_string())
            .collect();
        assert_eq!(fills, palette, "{path}");
        assert_partition(svg, c, path);
        let p = c.partition.as_ref().unwrap();
        // Every border is drawn once: used forward by its left region, reversed by its
        // right one when that is a region, and by no other loop.
        let mut uses = vec![(0, 0); p.borders.len()];
        for (k, loops) in p.loops.iter().enumerate() {
            for &(b, reversed) in loops.iter().flatten() {
                let border = &p.borders[b].border;
                assert_eq!(if reversed { border.right } else { border.left }, k);
                if reversed {
                    uses[b].1 += 1;
                } else {
                    uses[b].0 += 1;
                }
            }
        }
        for (b, u) in p.borders.iter().zip(&uses) {
            let shared = b.border.right < p.none;
            assert_eq!(*u, (1, usize::from(shared)), "{path}");
        }
        // The JSON lists the same borders, each with its two sides.
        let j: serde_json::Value = serde_json::from_str(v.json.as_ref().unwrap()).unwrap();
        assert_eq!(j["layout"], "partition");
        let borders = j["borders"].as_array().unwrap();
        assert_eq!(borders.len(), p.borders.len(), "{path}");
        let regions = j["regions"].as_array().unwrap();
        for (jb, pb) in borders.iter().zip(&p.borders) {
            assert_eq!(jb["left"], pb.border.left);
            assert_eq!(jb["drawn"], pb.source.name());
            // The pieces it was cut from: pieces of that region's contours, with equations.
            let pieces = jb["pieces"].as_array().unwrap();
            let owner = match pb.source {
                BorderSource::Left => Some(pb.border.left),
                BorderSource::Right => Some(pb.border.right),
                _ => None,
            };
            match owner {
                None => assert!(pieces.is_empty()),
                Some(k) => {
                    assert!(!pieces.is_empty(), "{path}");
                    for cp in pieces {
                        let contour = &regions[k]["contours"][cp[0].as_u64().unwrap() as usize];
                        let piece = &contour["pieces"][cp[1].as_u64().unwrap() as usize];
                        assert!(piece["coefficients"].is_array(), "{path}: {cp}");
                    }
                }
            }
        }
        let curves = p
            .borders
            .iter()
            .filter(|b| b.source != BorderSource::Cracks)
            .count();
        let inner_cracks: Vec<usize> = p
            .borders
            .iter()
            .filter(|b| b.source == BorderSource::Cracks && b.border.right != p.none + 1)
            .map(|b| b.border.corners.len() - 1)
            .collect();
        eprintln!(
            "{path}: {} borders, {curves} cut from outlines, {} along the image edge, \
             {} others along their cracks (longest {:?} cracks), {} rounds, {} seam px",
            p.borders.len(),
            p.borders
                .iter()
                .filter(|b| b.border.right == p.none + 1)
                .count(),
            inner_cracks.len(),
            inner_cracks.iter().max(),
            p.rounds,
            f.seams
        );
        assert!(curves > 0, "{path}");
    }
}

fn random_png(w: u32, h: u32, px: &[u8]) -> Vec<u8> {
    let palette = [
        [0, 0, 0, 0],
        [230, 40, 40, 255],
        [40, 90, 220, 255],
        [250, 250, 250, 255],
        [20, 160, 60, 255],
    ];
    let img = image::RgbaImage::from_fn(w, h, |x, y| {
        image::Rgba(palette[usize::from(px[(y * w + x) as usize] % 5)])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Random images of four colours and transparency, in blobs or noise: the partition
    /// paints every pixel of a region with exactly one path, its own, and no other pixel.
    #[test]
    fn partition_regions_do_not_overlap(
        (w, h, px) in (1u32..14, 1u32..14).prop_flat_map(|(w, h)| {
            (Just(w), Just(h), prop::collection::vec(0u8..5, (w * h) as usize))
        }),
        blobs in any::<bool>(),
    ) {
        // Blobs: each pixel takes its left neighbour's value in most rows, for longer borders.
        let px: Vec<u8> = if blobs {
            let mut v = px.clone();
            for i in 0..v.len() {
                if i % w as usize > 0 && v[i] % 3 != 0 {
                    v[i] = v[i - 1];
                }
            }
            v
        } else {
            px
        };
        let options = Options::default().colors(5).layout(Layout::Partition).fidelity(true);
        let v = vectorize(&random_png(w, h, &px), &options).unwrap();
        let c = v.colour.as_ref().unwrap();
        prop_assert_eq!(c.fidelity.as_ref().unwrap().differing, 0);
        assert_partition(v.svg_text(), c, "random");
    }
}
