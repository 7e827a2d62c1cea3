//! The fidelity round trip: rasterize an SVG back to pixels and compare with the input mask.
//!
//! # How pixels are decided
//! [`rasterize_svg`] parses the document with usvg (default options; layertrace builds usvg
//! without text support, so `<text>` is dropped) and fills every filled path with tiny-skia,
//! anti-aliasing off, at one pixel per user unit after the document's own transforms
//! (viewBox included), honouring the path's fill rule. A pixel is foreground when painted.
//!
//! tiny-skia's non-anti-aliased scan converter (`scan/path.rs`, `edge.rs`, after Skia)
//! samples pixel centres: an edge covers row `y` when `y + 0.5` lies in `(y0, y1]` of the
//! edge (`fdot6::round` of its ends), and a span covers pixel `x` when `x + 0.5` lies in
//! `(x_left, x_right]` of the crossings at height `y + 0.5` (`fdot16::round_to_i32`). So pixel
//! `(x, y)` is painted iff its centre `(x + 0.5, y + 0.5)` is inside the path — which is
//! what the choice of border level assumes (see [`crate::level`]) — up to two
//! approximations of the rasterizer:
//! * vertices are truncated to 1/64 pixel (26.6 fixed point) and crossings interpolated in
//!   16.16 fixed point;
//! * curves are cut into line edges by forward differencing with only ~1/8 to 1/2 pixel
//!   accuracy (`diff_to_shift`), far coarser than the margins the exact curves keep to pixel
//!   centres. To measure the geometry rather than that shortcut, [`rasterize_svg`] flattens
//!   every path itself with kurbo within [`FLATTEN_TOLERANCE`] before filling, so tiny-skia
//!   only sees line edges.
//!
//! usvg itself turns elliptical arcs into cubics within 0.1 pixel (kurbo's
//! `Arc::to_cubic_beziers(0.1)` in svgtypes' path simplification); the arcs layertrace
//! writes are short pieces, for which that conversion is much closer than its bound.
//!
//! [`staircases`] counts pixel staircases in the path data (see its module).

use crate::bitmap::Mask;
use crate::error::Error;
use kurbo::{BezPath, PathEl, Point};

mod staircase;

pub use staircase::{path_staircases, staircases, StaircaseCount};

/// Tolerance (pixels) of the flattening of curves done by [`rasterize_svg`] before filling
/// (raised to `1e-8` times the path's extent for paths over 100 000 pixels wide).
pub const FLATTEN_TOLERANCE: f64 = 1e-3;

/// The comparison of an expected mask with the mask of its rasterized SVG.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FidelityReport {
    /// Pixels foreground in the expected mask only.
    pub missing: u64,
    /// Pixels foreground in the actual mask only.
    pub extra: u64,
    /// Foreground pixels of the expected mask.
    pub foreground: u64,
    /// `missing + extra`.
    pub differing: u64,
    /// Intersection over union of the two foregrounds (1 when both are empty).
    pub iou: f64,
}

fn point(p: tiny_skia::Point) -> Point {
    Point::new(f64::from(p.x), f64::from(p.y))
}

/// The path after `transform`, flattened into line segments.
fn flatten(path: &tiny_skia::Path, transform: tiny_skia::Transform) -> Option<tiny_skia::Path> {
    let path = path.clone().transform(transform)?;
    let mut bez = BezPath::new();
    for seg in path.segments() {
        use tiny_skia::PathSegment as S;
        bez.push(match seg {
            S::MoveTo(p) => PathEl::MoveTo(point(p)),
            S::LineTo(p) => PathEl::LineTo(point(p)),
            S::QuadTo(c, p) => PathEl::QuadTo(point(c), point(p)),
            S::CubicTo(c1, c2, p) => PathEl::CurveTo(point(c1), point(c2), point(p)),
            S::Close => PathEl::ClosePath,
        });
    }
    // Bounded work on absurd coordinates: the tolerance grows with the path's extent.
    let b = path.bounds();
    let extent = f64::from(b.width().max(b.height()));
    let tolerance = FLATTEN_TOLERANCE.max(extent * 1e-8);
    let mut pb = tiny_skia::PathBuilder::new();
    kurbo::flatten(bez, tolerance, |el| match el {
        PathEl::MoveTo(p) => pb.move_to(p.x as f32, p.y as f32),
        PathEl::LineTo(p) => pb.line_to(p.x as f32, p.y as f32),
        PathEl::ClosePath => pb.close(),
        // `flatten` emits only the three above.
        PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => pb.line_to(p.x as f32, p.y as f32),
    });
    pb.finish()
}

fn fill_group(group: &usvg::Group, pixmap: &mut tiny_skia::Pixmap) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => fill_group(g, pixmap),
            usvg::Node::Path(p) => {
                let Some(fill) = p.fill() else { continue };
                if !p.is_visible() {
                    continue;
                }
                let Some(path) = flatten(p.data(), p.abs_transform()) else {
                    continue;
                };
                let rule = match fill.rule() {
                    usvg::FillRule::NonZero => tiny_skia::FillRule::Winding,
                    usvg::FillRule::EvenOdd => tiny_skia::FillRule::EvenOdd,
                };
                let mut paint = tiny_skia::Paint::default();
                paint.set_color_rgba8(0, 0, 0, 255);
                paint.anti_alias = false;
                pixmap.fill_path(&path, &paint, rule, tiny_skia::Transform::identity(), None);
            }
            _ => {}
        }
    }
}

/// Rasterizes `svg` onto a `width` × `height` mask: usvg parse, every path flattened and
/// filled by tiny-skia without anti-aliasing (a pixel is painted when its centre is inside).
///
/// Fails with [`Error::SvgParse`] when usvg rejects the document and with
/// [`Error::Raster`] when no pixmap of that size can be made (zero or huge size).
pub fn rasterize_svg(svg: &str, width: u32, height: u32) -> Result<Mask, Error> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|source| Error::SvgParse { source })?;
    let mut pixmap =
        tiny_skia::Pixmap::new(width, height).ok_or(Error::Raster { width, height })?;
    fill_group(tree.root(), &mut pixmap);
    let mut mask = Mask::new(width, height);
    for (i, px) in pixmap.pixels().iter().enumerate() {
        if px.alpha() > 0 {
            let i = i as u64;
            let w = u64::from(width);
            mask.set((i % w) as i64, (i / w) as i64, true);
        }
    }
    Ok(mask)
}

/// Compares two masks pixel by pixel over the larger of their sizes (outside a mask is
/// background).
pub fn compare(expected: &Mask, actual: &Mask) -> FidelityReport {
    let w = expected.width().max(actual.width());
    let h = expected.height().max(actual.height());
    let (mut missing, mut extra, mut both) = (0u64, 0u64, 0u64);
    for y in 0..i64::from(h) {
        for x in 0..i64::from(w) {
            match (expected.get(x, y), actual.get(x, y)) {
                (true, true) => both += 1,
                (true, false) => missing += 1,
                (false, true) => extra += 1,
                (false, false) => {}
            }
        }
    }
    let union = both + missing + extra;
    FidelityReport {
        missing,
        extra,
        foreground: both + missing,
        differing: missing + extra,
        iou: if union == 0 {
            1.0
        } else {
            both as f64 / union as f64
        },
    }
}

/// Rasterizes `svg` at the size of `mask` and compares.
pub fn fidelity(svg: &str, mask: &Mask) -> Result<FidelityReport, Error> {
    let actual = rasterize_svg(svg, mask.width(), mask.height())?;
    Ok(compare(mask, &actual))
}

/// A picture of the comparison, over the larger of the two sizes: agreeing pixels black
/// (foreground) or white, missing pixels (expected only) red, extra pixels (actual only) blue.
pub fn diff_image(expected: &Mask, actual: &Mask) -> image::RgbImage {
    let w = expected.width().max(actual.width());
    let h = expected.height().max(actual.height());
    image::RgbImage::from_fn(w, h, |x, y| {
        let (x, y) = (i64::from(x), i64::from(y));
        image::Rgb(match (expected.get(x, y), actual.get(x, y)) {
            (true, true) => [0, 0, 0],
            (false, false) => [255, 255, 255],
            (true, false) => [255, 0, 0],
            (false, true) => [0, 0, 255],
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_sampling() {
        // Rectangles stopping just short of, or starting just past, pixel centres.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="3" viewBox="0 0 4 3">
            <path d="M0 0L2.49 0L2.49 1.49L0 1.49Z"/></svg>"#;
        let m = rasterize_svg(svg, 4, 3).unwrap();
        assert_eq!(m.to_ascii(), "##..\n....\n....\n");
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="3">
            <path d="M0.51 0.51L4 0.51L4 3L0.51 3Z"/></svg>"#;
        let m = rasterize_svg(svg, 4, 3).unwrap();
        assert_eq!(m.to_ascii(), "....\n.###\n.###\n");
    }

    #[test]
    fn fill_rules_and_transforms() {
        let ring = "M0 0H6V6H0Z M2 2H4V4H2Z";
        let svg = |rule: &str, tf: &str| {
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8"><g transform="{tf}"><path fill-rule="{rule}" d="{ring}"/></g></svg>"#
            )
        };
        let nonzero = rasterize_svg(&svg("nonzero", "translate(0 0)"), 8, 8).unwrap();
        let evenodd = rasterize_svg(&svg("evenodd", "translate(1 1)"), 8, 8).unwrap();
        assert_eq!(nonzero.count_foreground(), 36);
        assert_eq!(evenodd.count_foreground(), 32);
        assert!(!evenodd.get(3, 3) && evenodd.get(1, 1) && !evenodd.get(0, 0));
    }

    #[test]
    fn compare_and_diff() {
        let a = Mask::from_ascii("##.\n#..");
        let b = Mask::from_ascii("#..\n#.#");
        let r = compare(&a, &b);
        assert_eq!(
            (r.missing, r.extra, r.foreground, r.differing),
            (1, 1, 3, 2)
        );
        assert!((r.iou - 0.5).abs() < 1e-12);
        let img = diff_image(&a, &b);
        assert_eq!(img.get_pixel(1, 0).0, [255, 0, 0]);
        assert_eq!(img.get_pixel(2, 1).0, [0, 0, 255]);
        assert_eq!(img.get_pixel(0, 0).0, [0, 0, 0]);
        assert_eq!(compare(&Mask::new(2, 2), &Mask::new(2, 2)).iou, 1.0);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(
            rasterize_svg("<svg", 4, 4),
            Err(Error::SvgParse { .. })
        ));
        let ok = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4"/>"#;
        assert!(matches!(rasterize_svg(ok, 0, 4), Err(Error::Raster { .. })));
    }
}
