//! Measures colour SVGs of one image against layertrace's regions of it (README, "Colour
//! images"): `cargo run --release --example colour_compare -- IMAGE N A.svg [B.svg …]`.
//!
//! For every SVG, one line: differing pixels, seam pixels, path commands, bytes.
//! * The reference is the image's regions in `N` colours as `--colors N` makes them (the
//!   input's own colours when it has at most `N`).
//! * Differing: rendered as `resvg --shape-rendering crispEdges` does, a pixel of a region
//!   differs when it is not opaque or the palette colour nearest to its rendered colour is
//!   not its region's; a pixel of no region differs when painted. For layertrace's own SVG
//!   this is exactly `--report`'s count (its colours are the palette's); another tracer's
//!   colours, averaged its own way, are not penalized for being a few units off.
//! * Seams: `--report`'s definition (pixels whose 5 × 5 neighbourhood is all in regions,
//!   rendered anti-aliased with alpha below 255).
//! * Commands: path segments as usvg's parser (svgtypes) reads the `d` attributes, M and Z
//!   included, implicit repeats counted.
//! * Overlaps: pixels painted by more than one `<path>`, each path rendered alone in
//!   crispEdges (0 for a partition; a stack's lower layers run under the upper ones on
//!   purpose).
//!
//! With `--render DIR` first, each SVG's anti-aliased rendering is also written as
//! `DIR/<svg name>.aa.png`: over magenta, so that any seam shows, enlarged 6 times
//! (nearest neighbour).

use layertrace::{colour_regions, decode_rgba, Colour, ColourImage};
use std::path::Path;

fn render(svg: &str, w: u32, h: u32, crisp: bool) -> tiny_skia::Pixmap {
    let options = usvg::Options {
        shape_rendering: if crisp {
            usvg::ShapeRendering::CrispEdges
        } else {
            usvg::ShapeRendering::GeometricPrecision
        },
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).expect("SVG parses");
    let mut pixmap = tiny_skia::Pixmap::new(w, h).unwrap();
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    pixmap
}

fn commands(svg: &str) -> usize {
    let doc = roxmltree::Document::parse(svg).expect("XML parses");
    doc.descendants()
        .filter_map(|n| n.attribute("d"))
        .map(|d| svgtypes::PathParser::from(d).filter(|s| s.is_ok()).count())
        .sum()
}

/// Pixels painted by more than one `<path>` of `svg`, each rendered alone in crispEdges.
fn overlaps(svg: &str, w: u32, h: u32) -> u64 {
    let doc = roxmltree::Document::parse(svg).expect("XML parses");
    let root = doc.root_element();
    let mut painted = vec![0u32; (w * h) as usize];
    for node in root.descendants().filter(|n| n.has_tag_name("path")) {
        let d = node.attribute("d").unwrap_or("");
        let rule = node.attribute("fill-rule").unwrap_or("nonzero");
        let alone = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"{}\"><path fill-rule=\"{rule}\" d=\"{d}\"/></svg>",
            root.attribute("viewBox")
                .map_or(format!("0 0 {w} {h}"), str::to_string)
        );
        let p = render(&alone, w, h, true);
        for (i, c) in p.pixels().iter().enumerate() {
            painted[i] += u32::from(c.alpha() > 0);
        }
    }
    painted.iter().filter(|&&k| k > 1).count() as u64
}

fn measure(image: &ColourImage, svg: &str) -> (u64, u64) {
    let (w, h) = (image.width(), image.height());
    let crisp = render(svg, w, h, true);
    let smooth = render(svg, w, h, false);
    let palette = image.palette();
    let (mut differing, mut seams) = (0u64, 0u64);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let c = crisp.pixels()[i].demultiply();
            let (xi, yi) = (i64::from(x), i64::from(y));
            match image.get(xi, yi) {
                Some(k) => {
                    let got = Colour::new(c.red(), c.green(), c.blue());
                    let nearest = (0..palette.len())
                        .min_by_key(|&j| {
                            let p = palette[j];
                            let d = |a: u8, b: u8| (i32::from(a) - i32::from(b)).pow(2);
                            d(p.r, got.r) + d(p.g, got.g) + d(p.b, got.b)
                        })
                        .unwrap_or(0);
                    if c.alpha() != 255 || nearest != k {
                        differing += 1;
                    }
                    // The seam test of `colour_fidelity`: see-through with regions all round.
                    if smooth.pixels()[i].alpha() < 255 && image.regions_around(xi, yi, 2) {
                        seams += 1;
                    }
                }
                None => differing += u64::from(c.alpha() > 0),
            }
        }
    }
    (differing, seams)
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let render_dir = if args.first().map(String::as_str) == Some("--render") && args.len() > 1 {
        let dir = args[1].clone();
        args.drain(..2);
        Some(dir)
    } else {
        None
    };
    if args.len() < 3 {
        eprintln!("usage: colour_compare IMAGE N A.svg [B.svg ...]");
        std::process::exit(2);
    }
    let bytes = std::fs::read(&args[0]).expect("image readable");
    let rgba = decode_rgba(&bytes, Path::new(&args[0]), u64::MAX, u64::MAX).expect("image");
    let n: u16 = args[1].parse().expect("N");
    let regions = colour_regions(&rgba, n);
    println!(
        "{}: {} colours ({})",
        args[0],
        regions.image.palette().len(),
        if regions.exact { "exact" } else { "quantized" }
    );
    for path in &args[2..] {
        let svg = std::fs::read_to_string(path).expect("SVG readable");
        let (differing, seams) = measure(&regions.image, &svg);
        if let Some(dir) = &render_dir {
            let (w, h) = (regions.image.width(), regions.image.height());
            let smooth = render(&svg, w, h, false);
            let k = 6;
            let img = image::RgbImage::from_fn(w * k, h * k, |x, y| {
                let c = smooth.pixel(x / k, y / k).unwrap();
                // Premultiplied over opaque magenta.
                let a = 255 - u16::from(c.alpha());
                let over = |v: u8, bg: u16| (u16::from(v) + (bg * a + 127) / 255).min(255) as u8;
                image::Rgb([over(c.red(), 255), over(c.green(), 0), over(c.blue(), 255)])
            });
            let stem = Path::new(path)
                .file_stem()
                .unwrap()
                .to_string_lossy()
                .into_owned();
            img.save(Path::new(dir).join(format!("{stem}.aa.png")))
                .expect("PNG written");
        }
        let (w, h) = (regions.image.width(), regions.image.height());
        println!(
            "{path}: differing {differing}, seams {seams}, commands {}, bytes {}, overlaps {}",
            commands(&svg),
            svg.len(),
            overlaps(&svg, w, h)
        );
    }
}
