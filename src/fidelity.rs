//! The fidelity round trip: render an SVG back to pixels the way resvg does and compare with
//! the input mask.
//!
//! # What is measured
//! [`rasterize_svg`] renders the document with the resvg crate exactly as
//! `resvg --shape-rendering crispEdges` would: usvg parses it (layertrace builds usvg without
//! text support, so `<text>` is dropped) with `crispEdges` as the default shape rendering (a
//! `shape-rendering` attribute or style in the document wins, as in resvg), and
//! [`resvg::render`] paints the tree into a tiny-skia pixmap at one pixel per user unit after
//! the document's own transforms (viewBox included), fills and strokes alike. With
//! `crispEdges` resvg turns tiny-skia's anti-aliasing off, so an opaque paint leaves every
//! pixel at alpha 0 or 255; a pixel is foreground when its alpha is above 0 (painted at all,
//! also by a translucent paint or an anti-aliased path the document asks for).
//!
//! No curve is flattened here: the figures are those of the renderer, with its own
//! approximations.
//! * usvg turns elliptical arcs `A` into cubics within 0.1 pixel (kurbo's
//!   `Arc::to_cubic_beziers(0.1)` in svgtypes' path simplification) and keeps quadratic and
//!   cubic Béziers as they are.
//! * tiny-skia (after Skia, `edge.rs`, `edge_builder.rs`) cuts each quadratic or cubic into
//!   2^k line edges by forward differencing, `k` chosen by `diff_to_shift` from the curve's
//!   deviation for roughly 1/8 to 1/2 pixel accuracy (at most 2^6 edges), so a curve can be
//!   drawn that far from its true course.
//! * Vertices are rounded to 1/64 pixel (26.6 fixed point) and crossings interpolated in
//!   16.16 fixed point.
//! * Without anti-aliasing tiny-skia samples pixel centres (`scan/path.rs`): an edge covers
//!   row `y` when `y + 0.5` lies in `(y0, y1]` of the edge, and a span covers pixel `x` when
//!   `x + 0.5` lies in `(x_left, x_right]` of the crossings at height `y + 0.5`. So pixel
//!   `(x, y)` is painted iff its centre `(x + 0.5, y + 0.5)` is inside the drawn polygon —
//!   which is what the choice of border level assumes (see [`crate::level`]); the pixels
//!   that differ come from the approximations above.
//!
//! [`staircases`] counts pixel staircases in the path data (see its module).

use crate::bitmap::{border_distance, Mask};
use crate::error::Error;

mod colour;
pub(crate) mod staircase;

pub use colour::{colour_diff_image, colour_fidelity, ColourDiff, ColourFidelity};

pub use staircase::{staircases, StaircaseCount};

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

/// Where the differing pixels of a smooth outline lie (see [`band_check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandCheck {
    /// The ν checked against.
    pub nu: f64,
    /// Differing pixels.
    pub differing: u64,
    /// Differing pixels farther than ν from the border (0 when the guarantee holds).
    pub beyond: u64,
    /// Largest distance to the border of a differing pixel (0 when none differs).
    pub max_distance: f64,
}

/// Checks the guarantee of a smooth outline: every pixel where `rendered` differs from
/// `expected` lies within `nu` of `expected`'s border (the distance from its centre to the
/// nearest pixel square of the other colour, see [`crate::bitmap::Band`]).
///
/// ```
/// use layertrace::{band_check, Mask};
/// let expected = Mask::from_ascii(
///     "......
///      .####.
///      .####.
///      ......",
/// );
/// // One corner pixel lost: it lies on the border, within half a pixel of the background.
/// let mut rendered = expected.clone();
/// rendered.set(1, 1, false);
/// let b = band_check(&expected, &rendered, 1.0);
/// assert_eq!((b.differing, b.beyond), (1, 0));
/// assert!(b.max_distance <= 1.0);
/// ```
pub fn band_check(expected: &Mask, rendered: &Mask, nu: f64) -> BandCheck {
    let mut out = BandCheck {
        nu,
        differing: 0,
        beyond: 0,
        max_distance: 0.0,
    };
    let limit = nu.max(0.0) + 4.0;
    for y in 0..i64::from(expected.height()) {
        for x in 0..i64::from(expected.width()) {
            if expected.get(x, y) == rendered.get(x, y) {
                continue;
            }
            out.differing += 1;
            let d = border_distance(expected, x, y, limit).unwrap_or(f64::INFINITY);
            out.max_distance = out.max_distance.max(d);
            if d > nu {
                out.beyond += 1;
            }
        }
    }
    out
}

/// Renders `svg` onto a `width` × `height` mask as Chromium draws the document opened at 1:1
/// with `shape-rendering="crispEdges"` (software raster, as headless Chromium does): tile by
/// tile, each overlapping its neighbours by two pixels, drawn by resvg into a pixmap that is
/// exactly the tile, so that tiny-skia's edge clipper cuts the path at the tile's border as
/// Skia's does, and keeping the pixels the tile shows (see `outline::tiles`). Tiles are
/// chosen as Chromium chooses them: 256 × 256 px; 512 px tall on pages under 256 px wide,
/// 512 px wide on pages under 256 px tall. Same errors as [`rasterize_svg`]; documents under
/// 512 pixels both ways are one tile and come out as [`rasterize_svg`] draws them.
///
/// ```
/// use layertrace::{compare, rasterize_svg, rasterize_svg_in_tiles};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="600" height="300" viewBox="0 0 600 300">
///   <path d="M10 10L590 20L300 290Z"/></svg>"#;
/// let tiled = rasterize_svg_in_tiles(svg, 600, 300)?;
/// let whole = rasterize_svg(svg, 600, 300)?;
/// // Where a tile's border cuts an edge, the part left inside is tilted a little: a few
/// // pixel centres close to the edges change side.
/// let d = compare(&whole, &tiled);
/// assert!(d.differing > 0 && d.differing < 10);
/// // Within one tile, nothing is cut.
/// let small = r#"<svg xmlns="http://www.w3.org/2000/svg" width="500" height="400" viewBox="0 0 500 400">
///   <path d="M3 3L497 10L100 397Z"/></svg>"#;
/// assert_eq!(
///     rasterize_svg_in_tiles(small, 500, 400)?,
///     rasterize_svg(small, 500, 400)?
/// );
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn rasterize_svg_in_tiles(svg: &str, width: u32, height: u32) -> Result<Mask, Error> {
    use crate::outline::tiles::{tiles, TileSize};
    let tree = parse(svg, usvg::ShapeRendering::CrispEdges)?;
    if width == 0 || height == 0 {
        return Err(Error::Raster { width, height });
    }
    let mut mask = Mask::new(width, height);
    let (w, h) = (i64::from(width), i64::from(height));
    let size = TileSize::of_page(w, h);
    for (_, (cy0, cy1), (sy0, sy1)) in tiles(0, h, h, size.height) {
        for (_, (cx0, cx1), (sx0, sx1)) in tiles(0, w, w, size.width) {
            let (tw, th) = ((cx1 - cx0) as u32, (cy1 - cy0) as u32);
            let mut pixmap = tiny_skia::Pixmap::new(tw, th).ok_or(Error::Raster {
                width: tw,
                height: th,
            })?;
            resvg::render(
                &tree,
                tiny_skia::Transform::from_translate(-cx0 as f32, -cy0 as f32),
                &mut pixmap.as_mut(),
            );
            for y in sy0..sy1 {
                for x in sx0..sx1 {
                    let i = ((y - cy0) * i64::from(tw) + (x - cx0)) as usize;
                    if pixmap.pixels()[i].alpha() > 0 {
                        mask.set(x, y, true);
                    }
                }
            }
        }
    }
    Ok(mask)
}

/// The pixmap `resvg --shape-rendering crispEdges` paints for `svg`, at `width` × `height`.
fn render(svg: &str, width: u32, height: u32) -> Result<tiny_skia::Pixmap, Error> {
    render_with(svg, width, height, usvg::ShapeRendering::CrispEdges)
}

/// The usvg tree of `svg` with `shape_rendering` as the default shape rendering.
fn parse(svg: &str, shape_rendering: usvg::ShapeRendering) -> Result<usvg::Tree, Error> {
    let options = usvg::Options {
        shape_rendering,
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &options).map_err(|source| Error::SvgParse { source })
}

/// The pixmap resvg paints for `svg` at `width` × `height` with `shape_rendering` as the
/// default shape rendering.
fn render_with(
    svg: &str,
    width: u32,
    height: u32,
    shape_rendering: usvg::ShapeRendering,
) -> Result<tiny_skia::Pixmap, Error> {
    let tree = parse(svg, shape_rendering)?;
    let mut pixmap =
        tiny_skia::Pixmap::new(width, height).ok_or(Error::Raster { width, height })?;
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

/// Renders `svg` onto a `width` × `height` mask as `resvg --shape-rendering crispEdges` does
/// (see the module documentation): a pixel is foreground when painted.
///
/// Fails with [`Error::SvgParse`] when usvg rejects the document and with
/// [`Error::Raster`] when no pixmap of that size can be made (zero or huge size).
///
/// ```
/// use layertrace::rasterize_svg;
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="3" viewBox="0 0 4 3">
///   <path d="M1 0H3V2H1Z"/></svg>"#;
/// let mask = rasterize_svg(svg, 4, 3)?;
/// assert!(mask.get(1, 0) && mask.get(2, 1) && !mask.get(0, 0) && !mask.get(1, 2));
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn rasterize_svg(svg: &str, width: u32, height: u32) -> Result<Mask, Error> {
    let pixmap = render(svg, width, height)?;
    let mut mask = Mask::new(width, height);
    let w = u64::from(width);
    for (i, px) in pixmap.pixels().iter().enumerate() {
        if px.alpha() > 0 {
            let i = i as u64;
            mask.set((i % w) as i64, (i / w) as i64, true);
        }
    }
    Ok(mask)
}

/// Compares two masks pixel by pixel over the larger of their sizes (outside a mask is
/// background).
///
/// ```
/// use layertrace::{compare, Mask};
/// let expected = Mask::from_ascii("##.\n##.");
/// let actual = Mask::from_ascii("#..\n###");
/// let r = compare(&expected, &actual);
/// assert_eq!((r.missing, r.extra, r.differing, r.foreground), (1, 1, 2, 4));
/// ```
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
///
/// ```
/// use layertrace::{decompose, fidelity, svg_document, trace, Convention, Mask, Model};
/// use layertrace::{OutlierRule, SvgOptions};
/// let mask = Mask::from_fn(30, 20, |x, y| (x + y) % 17 < 9 && y > 2);
/// let d = decompose(trace(&mask, Convention::Default), Model::Conic, OutlierRule::NotInPiece);
/// let out = svg_document(&d, 30, 20, &SvgOptions::default());
/// // Exact as resvg draws it.
/// assert_eq!(fidelity(&out.svg, &mask)?.differing, 0);
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn fidelity(svg: &str, mask: &Mask) -> Result<FidelityReport, Error> {
    let actual = rasterize_svg(svg, mask.width(), mask.height())?;
    Ok(compare(mask, &actual))
}

/// A picture of the comparison, over the larger of the two sizes: agreeing pixels black
/// (foreground) or white, missing pixels (expected only) red, extra pixels (actual only) blue.
///
/// ```
/// use layertrace::{diff_image, Mask};
/// let expected = Mask::from_ascii("#.");
/// let actual = Mask::from_ascii(".#");
/// let img = diff_image(&expected, &actual);
/// assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]); // missing: red
/// assert_eq!(img.get_pixel(1, 0).0, [0, 0, 255]); // extra: blue
/// ```
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
    fn crisp_edges_by_default_unless_the_document_says_otherwise() {
        let disc = |attr: &str| {
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="20"><circle cx="10" cy="10" r="7.3"{attr}/></svg>"#
            )
        };
        let alphas = |svg: &str| {
            let p = render(svg, 20, 20).unwrap();
            let mut a: Vec<u8> = p.pixels().iter().map(|px| px.alpha()).collect();
            a.sort_unstable();
            a.dedup();
            a
        };
        assert_eq!(alphas(&disc("")), [0, 255]);
        let smooth = disc(r#" shape-rendering="geometricPrecision""#);
        assert!(alphas(&smooth).len() > 2);
        // Every painted pixel is foreground: the anti-aliased disc covers the crisp one.
        let (crisp, aa) = (
            rasterize_svg(&disc(""), 20, 20).unwrap(),
            rasterize_svg(&smooth, 20, 20).unwrap(),
        );
        let r = compare(&aa, &crisp);
        assert!(r.missing > 0 && r.extra == 0);
    }

    #[test]
    fn strokes_are_drawn_too() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="6" height="6">
            <path d="M0 3H6" fill="none" stroke="black" stroke-width="2"/></svg>"#;
        let m = rasterize_svg(svg, 6, 6).unwrap();
        assert_eq!(
            m.to_ascii(),
            "......\n......\n######\n######\n......\n......\n"
        );
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
