//! SVG export and fidelity round trip on the sample images.
//!
//! The round trip renders the SVG with the resvg crate as `resvg --shape-rendering
//! crispEdges` does ([`rasterize_svg`]). The bounds are measured figures, lowered whenever
//! the output gets better (a change that raises one says why in its commit); a failing
//! comparison writes `<sample>-<model>-{expected,actual,diff}.png` to
//! `target/fidelity-failures/` and names them.

use kurbo::{Arc, Point};
use layertrace::{
    compare, contour_path, decompose, diff_image, load_path, rasterize_svg, staircases,
    svg_document, trace, Contour, Convention, Decomposition, FidelityReport, LoadOptions, Mask,
    Model, OutlierRule, PathCommand, SvgOptions,
};
use std::path::{Path, PathBuf};

fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(name)
}

fn load(name: &str) -> Mask {
    load_path(&sample(name), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .mask
}

fn decomposition(mask: &Mask, model: Model) -> Decomposition {
    decompose(
        trace(mask, Convention::Default),
        model,
        OutlierRule::NotInPiece,
    )
}

fn json(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(sample(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The golden round trip: renders `svg` as resvg does and compares it with `expected`.
/// When more than `bound` pixels differ, writes `target/fidelity-failures/TAG-expected.png`,
/// `TAG-actual.png` and `TAG-diff.png` (see [`diff_image`]) and returns a message naming
/// them.
fn round_trip(tag: &str, expected: &Mask, svg: &str, bound: u64) -> Result<FidelityReport, String> {
    let actual = rasterize_svg(svg, expected.width(), expected.height())
        .map_err(|e| format!("{tag}: {e}"))?;
    let r = compare(expected, &actual);
    if r.differing <= bound {
        return Ok(r);
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fidelity-failures");
    let _ = std::fs::create_dir_all(&dir);
    let tag = tag.replace(':', "");
    let img = |m: &Mask| {
        image::GrayImage::from_fn(m.width(), m.height(), |x, y| {
            image::Luma([if m.get(i64::from(x), i64::from(y)) {
                0
            } else {
                255
            }])
        })
    };
    let _ = img(expected).save(dir.join(format!("{tag}-expected.png")));
    let _ = img(&actual).save(dir.join(format!("{tag}-actual.png")));
    let _ = diff_image(expected, &actual).save(dir.join(format!("{tag}-diff.png")));
    Err(format!(
        "{tag}: {} differing ({} missing, {} extra) > {bound}; see {}/{tag}-{{expected,actual,diff}}.png (diff: red missing, blue extra)",
        r.differing,
        r.missing,
        r.extra,
        dir.display()
    ))
}

/// The arcs of the contour whose pixels surround `centre`, as kurbo arcs, and its number of
/// pieces.
fn arcs_around(d: &Decomposition, centre: Point, radius: f64) -> (Vec<Arc>, usize) {
    let basis = d.model.basis();
    let (k, contour): (usize, &Contour) = d
        .contours
        .iter()
        .enumerate()
        .find(|(_, c)| {
            !c.hole
                && c.points.iter().all(|p| {
                    let q = Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5);
                    (q - centre).hypot() <= radius + 2.0
                })
        })
        .expect("a contour around the shape");
    let path = contour_path(contour, &d.pieces[k], &basis, 0.05, 0.0);
    let mut pen = path.start;
    let mut arcs = Vec::new();
    for c in &path.commands {
        if let PathCommand::Arc(a) = c {
            let a = kurbo::SvgArc { from: pen, ..*a };
            arcs.extend(Arc::from_svg_arc(&a));
        }
        pen = c.end();
    }
    (arcs, d.pieces[k].len())
}

/// Distance from `p` to the ellipse (centre, semi-axes `a ≥ b`, angle `theta`), by sampling.
fn ellipse_distance(p: Point, centre: Point, a: f64, b: f64, theta: f64) -> f64 {
    let (s, c) = theta.sin_cos();
    (0..3600)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 3600.0;
            let (u, v) = (a * t.cos(), b * t.sin());
            (Point::new(centre.x + u * c - v * s, centre.y + u * s + v * c) - p).hypot()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every arc of every disc lies within 0.75 px of the true circle; discs decomposed into a
/// single piece give arcs whose centre and radius are within 0.5 px of the truth, larger
/// ones (several pieces, each a local fit) within 8 % of the radius (at least 0.5 px) on
/// average (weighted by the arcs' angles).
#[test]
fn disc_arcs_match_the_true_circle() {
    let mask = load("syn_discs_r3_to_r200.png");
    let d = decomposition(&mask, Model::Circle);
    let spec = json("syn_discs_r3_to_r200.json");
    let mut single = 0;
    for op in spec["ops"].as_array().expect("ops") {
        let r = op["r"].as_f64().expect("r");
        let centre = Point::new(
            op["cx"].as_f64().expect("cx"),
            op["cy"].as_f64().expect("cy"),
        );
        let (arcs, pieces) = arcs_around(&d, centre, r);
        assert!(!arcs.is_empty(), "disc r={r}: no arc");
        let (mut w, mut dr, mut dc) = (0.0, 0.0, 0.0);
        for a in &arcs {
            for k in 0..=8 {
                let t = a.start_angle + a.sweep_angle * f64::from(k) / 8.0;
                let p = a.center + kurbo::Vec2::from_angle(t) * a.radii.x;
                let e = ((p - centre).hypot() - r).abs();
                assert!(
                    e <= 0.75,
                    "disc r={r}: arc point {p:?} is {e} px off the circle"
                );
            }
            let (ec, er) = ((a.center - centre).hypot(), (a.radii.x - r).abs());
            if pieces == 1 {
                assert!(
                    ec <= 0.5 && er <= 0.5,
                    "disc r={r}: one piece, arc centre {:?} radius {}",
                    a.center,
                    a.radii.x
                );
            }
            w += a.sweep_angle.abs();
            dr += a.sweep_angle.abs() * er;
            dc += a.sweep_angle.abs() * ec;
        }
        single += usize::from(pieces == 1);
        assert!(
            dr / w <= (0.08 * r).max(0.5) && dc / w <= (0.08 * r).max(0.5),
            "disc r={r}: mean radius error {}, centre error {}",
            dr / w,
            dc / w
        );
    }
    assert!(single >= 4, "only {single} discs in one piece");
}

/// A rotated ellipse small enough to be one conic piece gives elliptic arcs with the true
/// axes and angle; on the sample, every elliptic arc lies within 1.25 px of its ellipse (measured 1.07; the
/// border passes between inlier and background centres, as the true curve does).
#[test]
fn rotated_ellipse_arcs_match_the_true_ellipse() {
    let (cx, cy, a, b, theta) = (20.3, 18.6, 9.0, 5.0, 30f64.to_radians());
    let (s, c) = theta.sin_cos();
    let mask = Mask::from_fn(42, 38, |x, y| {
        let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - cy);
        let (u, v) = (dx * c + dy * s, -dx * s + dy * c);
        (u / a).powi(2) + (v / b).powi(2) <= 1.0
    });
    let d = decomposition(&mask, Model::Conic);
    let (arcs, _) = arcs_around(&d, Point::new(cx, cy), a);
    assert!(!arcs.is_empty());
    for arc in &arcs {
        let (major, minor, angle) = if arc.radii.x >= arc.radii.y {
            (arc.radii.x, arc.radii.y, arc.x_rotation)
        } else {
            (
                arc.radii.y,
                arc.radii.x,
                arc.x_rotation + std::f64::consts::FRAC_PI_2,
            )
        };
        let mut dtheta = (angle - theta).rem_euclid(std::f64::consts::PI);
        dtheta = dtheta.min(std::f64::consts::PI - dtheta);
        assert!(
            (major - a).abs() <= 0.5
                && (minor - b).abs() <= 0.5
                && dtheta <= 3f64.to_radians()
                && (arc.center - Point::new(cx, cy)).hypot() <= 0.5,
            "arc centre {:?} axes {major} {minor} angle {angle}",
            arc.center
        );
    }

    let mask = load("syn_ellipses_rotated.png");
    let d = decomposition(&mask, Model::Conic);
    let spec = json("syn_ellipses_rotated.json");
    let mut checked = 0;
    for op in spec["ops"].as_array().expect("ops") {
        let (a, b) = (op["a"].as_f64().expect("a"), op["b"].as_f64().expect("b"));
        let theta = op["theta_deg"].as_f64().expect("theta").to_radians();
        let centre = Point::new(
            op["cx"].as_f64().expect("cx"),
            op["cy"].as_f64().expect("cy"),
        );
        let (arcs, _) = arcs_around(&d, centre, a);
        for arc in &arcs {
            for k in 0..=4 {
                let t = arc.start_angle + arc.sweep_angle * f64::from(k) / 4.0;
                let (st, ct) = t.sin_cos();
                let (sr, cr) = arc.x_rotation.sin_cos();
                let (u, v) = (arc.radii.x * ct, arc.radii.y * st);
                let p = Point::new(
                    arc.center.x + u * cr - v * sr,
                    arc.center.y + u * sr + v * cr,
                );
                let e = ellipse_distance(p, centre, a, b, theta);
                assert!(
                    e <= 1.25,
                    "ellipse a={a} b={b}: arc point {p:?} is {e} px off"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} elliptic arcs checked");
}

#[test]
fn svg_parses_and_is_well_formed() {
    let mask = load("glyph_g_liberationserif_cap120.png");
    for model in [Model::Line, Model::Circle, Model::Conic] {
        let out = svg_document(
            &decomposition(&mask, model),
            mask.width(),
            mask.height(),
            &SvgOptions::default(),
        );
        let tree = usvg::Tree::from_str(&out.svg, &usvg::Options::default()).expect("usvg parses");
        assert_eq!((tree.size().width(), tree.size().height()), (110.0, 163.0));
        assert!(out.svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"110\" height=\"163\" viewBox=\"0 0 110 163\">"));
        assert_eq!(out.svg.matches("<path").count(), 1);
        assert_eq!(out.commands.move_to, 3);
        assert_eq!(out.commands.close, 3);
        // Compact numbers: no trailing zeros, at most 3 decimals.
        let d = out
            .svg
            .split(" d=\"")
            .nth(1)
            .expect("d")
            .split('"')
            .next()
            .expect("d");
        for num in d
            .split(|c: char| c.is_ascii_alphabetic() || c == ' ')
            .filter(|s| !s.is_empty())
        {
            assert!(num.parse::<f64>().is_ok(), "{num}");
            if let Some((_, frac)) = num.split_once('.') {
                assert!(frac.len() <= 3 && !frac.ends_with('0'), "{num}");
            }
        }
    }
}

/// The crack outline (every piece dropped) reproduces every sample exactly: the fallback
/// is exact and the rasterizer samples pixel centres.
#[test]
fn crack_outlines_are_exact() {
    for name in [
        "syn_tiny_blobs.png",
        "glyph_at_dejavusans_cap40.png",
        "lineart_cat_symbola_h300.png",
    ] {
        let mask = load(name);
        let mut d = decomposition(&mask, Model::Line);
        d.pieces.iter_mut().for_each(Vec::clear);
        let out = svg_document(&d, mask.width(), mask.height(), &SvgOptions::default());
        let name = name.trim_end_matches(".png");
        if let Err(e) = round_trip(&format!("{name}-cracks"), &mask, &out.svg, 0) {
            panic!("{e}");
        }
        assert_eq!(out.commands.arc + out.commands.quad + out.commands.cubic, 0);
    }
}

/// Largest number of differing pixels (in resvg) and of staircase runs measured for each
/// sample and model.
const BOUNDS: &[(&str, Model, u64, u64)] = &[
    ("digits_liberationsans_cap40", Model::Line, 3, 14),
    ("digits_liberationsans_cap40", Model::Circle, 124, 22),
    ("digits_liberationsans_cap40", Model::Conic, 94, 13),
    ("digits_liberationsans_cap40", Model::Poly(3), 221, 22),
    ("glyph_S_dejavusans_cap120", Model::Line, 0, 0),
    ("glyph_S_dejavusans_cap120", Model::Circle, 70, 1),
    ("glyph_S_dejavusans_cap120", Model::Conic, 58, 0),
    ("glyph_S_dejavusans_cap120", Model::Poly(3), 34, 2),
    ("glyph_at_dejavusans_cap40", Model::Line, 0, 6),
    ("glyph_at_dejavusans_cap40", Model::Circle, 41, 1),
    ("glyph_at_dejavusans_cap40", Model::Conic, 43, 2),
    ("glyph_at_dejavusans_cap40", Model::Poly(3), 29, 3),
    ("glyph_g_liberationserif_cap120", Model::Line, 1, 5),
    ("glyph_g_liberationserif_cap120", Model::Circle, 73, 6),
    ("glyph_g_liberationserif_cap120", Model::Conic, 44, 4),
    ("glyph_g_liberationserif_cap120", Model::Poly(3), 25, 8),
    ("lineart_cat_symbola_h300", Model::Line, 4, 38),
    ("lineart_cat_symbola_h300", Model::Circle, 328, 26),
    ("lineart_cat_symbola_h300", Model::Conic, 214, 25),
    ("lineart_cat_symbola_h300", Model::Poly(3), 118, 42),
    ("sil_horse_skimage", Model::Line, 2, 9),
    ("sil_horse_skimage", Model::Circle, 141, 14),
    ("sil_horse_skimage", Model::Conic, 84, 8),
    ("sil_horse_skimage", Model::Poly(3), 32, 19),
    ("suits_black_dejavusans_cap120", Model::Line, 0, 12),
    ("suits_black_dejavusans_cap120", Model::Circle, 120, 12),
    ("suits_black_dejavusans_cap120", Model::Conic, 89, 6),
    ("suits_black_dejavusans_cap120", Model::Poly(3), 41, 15),
    ("syn_big3000_many_shapes", Model::Line, 15, 482),
    ("syn_big3000_many_shapes", Model::Circle, 3954, 333),
    ("syn_big3000_many_shapes", Model::Conic, 3619, 325),
    ("syn_big3000_many_shapes", Model::Poly(3), 2324, 518),
    ("syn_border_touching", Model::Line, 0, 5),
    ("syn_border_touching", Model::Circle, 43, 1),
    ("syn_border_touching", Model::Conic, 59, 0),
    ("syn_border_touching", Model::Poly(3), 24, 2),
    ("syn_digital_circle_1px", Model::Line, 0, 8),
    ("syn_digital_circle_1px", Model::Circle, 190, 0),
    ("syn_digital_circle_1px", Model::Conic, 134, 0),
    ("syn_digital_circle_1px", Model::Poly(3), 20, 8),
    ("syn_discs_r3_to_r200", Model::Line, 3, 42),
    ("syn_discs_r3_to_r200", Model::Circle, 438, 35),
    ("syn_discs_r3_to_r200", Model::Conic, 352, 29),
    ("syn_discs_r3_to_r200", Model::Poly(3), 166, 44),
    ("syn_ellipses_rotated", Model::Line, 1, 14),
    ("syn_ellipses_rotated", Model::Circle, 238, 21),
    ("syn_ellipses_rotated", Model::Conic, 343, 5),
    ("syn_ellipses_rotated", Model::Poly(3), 68, 19),
    ("syn_fig15_ellipse_two_holes", Model::Line, 0, 4),
    ("syn_fig15_ellipse_two_holes", Model::Circle, 112, 13),
    ("syn_fig15_ellipse_two_holes", Model::Conic, 274, 5),
    ("syn_fig15_ellipse_two_holes", Model::Poly(3), 23, 16),
    ("syn_polygons_sharp", Model::Line, 4, 5),
    ("syn_polygons_sharp", Model::Circle, 4, 5),
    ("syn_polygons_sharp", Model::Conic, 0, 6),
    ("syn_polygons_sharp", Model::Poly(3), 0, 6),
    ("syn_tiny_blobs", Model::Line, 0, 9),
    ("syn_tiny_blobs", Model::Circle, 0, 8),
    ("syn_tiny_blobs", Model::Conic, 0, 9),
    ("syn_tiny_blobs", Model::Poly(3), 0, 8),
    ("word_Layers_dejavusans-bold_cap40", Model::Line, 1, 7),
    ("word_Layers_dejavusans-bold_cap40", Model::Circle, 43, 8),
    ("word_Layers_dejavusans-bold_cap40", Model::Conic, 24, 2),
    ("word_Layers_dejavusans-bold_cap40", Model::Poly(3), 26, 3),
];

#[test]
fn sample_fidelity_does_not_regress() {
    let mut failures = Vec::new();
    for name in BOUNDS
        .iter()
        .map(|b| b.0)
        .collect::<std::collections::BTreeSet<_>>()
    {
        let mask = load(&format!("{name}.png"));
        for &(_, model, bound, stairs) in BOUNDS.iter().filter(|b| b.0 == name) {
            let out = svg_document(
                &decomposition(&mask, model),
                mask.width(),
                mask.height(),
                &SvgOptions::default(),
            );
            match round_trip(&format!("{name}-{model}"), &mask, &out.svg, bound) {
                Ok(r) => assert_eq!(r.foreground, mask.count_foreground()),
                Err(e) => failures.push(e),
            }
            let s = staircases(&out.svg).expect("parses");
            if s.runs > stairs {
                failures.push(format!(
                    "{name} {model}: {} staircase runs ({} segments) > {stairs}",
                    s.runs, s.segments
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A comb (a bar and 20-pixel teeth every 40 pixels) is rectilinear, so every model's pieces
/// turn right-angled corners, where the separating curves pass within thousandths of a pixel
/// of pixel centres. With the default minimum clearance those pieces are drawn along their
/// pixel edges (merged into one `L` per straight run) and the round trip is exact; without
/// it, 50 (line), 191 (circle) pixels differed at 400×400 and the conic model gave 2264
/// before the largest-margin fix.
#[test]
fn comb_is_exact_with_the_default_clearance() {
    let mut mask = Mask::new(400, 400);
    for y in 0..400i64 {
        for x in 0..400i64 {
            let ink = (10..390).contains(&x)
                && ((10..60).contains(&y) || ((10..390).contains(&y) && x % 40 < 20));
            mask.set(x, y, ink);
        }
    }
    for model in [Model::Line, Model::Circle, Model::Conic] {
        let out = svg_document(
            &decomposition(&mask, model),
            400,
            400,
            &SvgOptions::default(),
        );
        if let Err(e) = round_trip(&format!("comb-{model}"), &mask, &out.svg, 0) {
            panic!("{e}");
        }
        // The outline has 2 · 10 + 2 straight sides per tooth row: far fewer commands than
        // its 4 000 boundary pixels.
        assert!(
            out.commands.total() < 600,
            "comb {model}: {} commands",
            out.commands.total()
        );
    }
}
