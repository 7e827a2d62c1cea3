//! The fidelity of a colour SVG: each region's pixels as resvg draws them, and the seams.
//!
//! # Differing pixels
//! The SVG is rendered as `resvg --shape-rendering crispEdges` does (see the parent module).
//! A pixel of a region differs when the rendered pixel is not opaque with exactly the
//! region's colour; a pixel of no region differs when anything is painted on it (alpha
//! above 0). Both are counted per colour (the expected one; painted pixels of no region
//! under the colour painted) and in total.
//!
//! # Seams
//! The same SVG is rendered anti-aliased (resvg's default `geometricPrecision`) on a
//! transparent canvas, which is what shows a contrasting background through wherever
//! coverage is missing. A seam pixel is a pixel whose 5 × 5 neighbourhood (within the
//! image; the image's own edge does not stop it) holds only pixels of some region, and
//! whose rendered alpha is below 255: a place inside the coloured area where the
//! background shows through, as it does along the shared edges of regions drawn side by
//! side. Pixels less than 3 pixels (in x or y) from a pixel of no region are not counted:
//! the outline against transparency is meant to be anti-aliased, and an exact curve there
//! may cross the square of the pixel next to an edge pixel (a 3 × 3 neighbourhood was
//! not enough: a random 7 × 9 shape had one such pixel).

use crate::bitmap::{distance_where, Colour, ColourImage};
use crate::error::Error;

/// The seam test looks this far round a pixel (the 5 × 5 neighbourhood above).
const SEAM_RADIUS: i64 = 2;

/// The pixels of one colour that differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ColourDiff {
    /// The colour.
    pub colour: Colour,
    /// Pixels of this colour in the expected image.
    pub pixels: u64,
    /// Of them, pixels rendered otherwise.
    pub differing: u64,
}

/// The comparison of a colour SVG with its regions.
#[derive(Clone, Debug, PartialEq)]
pub struct ColourFidelity {
    /// Per colour, in palette order.
    pub colours: Vec<ColourDiff>,
    /// Pixels of no region painted by the SVG.
    pub extra: u64,
    /// All differing pixels: those of every colour and `extra`.
    pub differing: u64,
    /// Pixels of the regions (all colours).
    pub pixels: u64,
    /// Seam pixels of the anti-aliased rendering (see the module documentation).
    pub seams: u64,
    /// The crispEdges rendering, straight (not premultiplied) RGBA.
    pub rendered: image::RgbaImage,
    /// With smooth outlines: how far the differing pixels are from a border between two
    /// colours (or a colour and no region).
    pub band: Option<super::BandCheck>,
}

/// Renders `svg` at the size of `expected`, crisp and anti-aliased, and compares (see the
/// module documentation).
///
/// With `band_nu` = Some(ν) (smooth outlines), also checks the guarantee of smooth outlines: every differing
/// pixel is within ν of a pixel of another colour or of no region (the distance from its
/// centre to that pixel's square).
///
/// ```
/// use layertrace::{colour_fidelity, vectorize, Options, Source};
/// let bytes = std::fs::read("samples/colour/colour_logo_crisp.png").unwrap();
/// let v = vectorize(Source::Bytes(&bytes), &Options::default().colors(4))?;
/// let c = v.colour.as_ref().unwrap();
/// let f = colour_fidelity(&v.svg.as_ref().unwrap().svg, &c.regions.image, None)?;
/// assert_eq!(f.differing, 0);
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn colour_fidelity(
    svg: &str,
    expected: &ColourImage,
    band_nu: Option<f64>,
) -> Result<ColourFidelity, Error> {
    let (w, h) = (expected.width(), expected.height());
    let crisp = super::render_with(svg, w, h, usvg::ShapeRendering::CrispEdges)?;
    let smooth = super::render_with(svg, w, h, usvg::ShapeRendering::GeometricPrecision)?;
    let palette = expected.palette();
    let mut colours: Vec<ColourDiff> = palette
        .iter()
        .map(|&colour| ColourDiff {
            colour,
            pixels: 0,
            differing: 0,
        })
        .collect();
    let mut extra = 0u64;
    let mut seams = 0u64;
    let mut band = band_nu.map(|nu| super::BandCheck {
        nu,
        differing: 0,
        beyond: 0,
        max_distance: 0.0,
    });
    let mut off = |xi: i64, yi: i64| {
        if let Some(b) = &mut band {
            let d = colour_border_distance(expected, xi, yi, b.nu + 4.0).unwrap_or(f64::INFINITY);
            b.differing += 1;
            b.max_distance = b.max_distance.max(d);
            b.beyond += u64::from(d > b.nu);
        }
    };
    let mut rendered = image::RgbaImage::new(w, h);
    let crisp_px = crisp.pixels();
    let smooth_px = smooth.pixels();
    for y in 0..h {
        for x in 0..w {
            let i = y as usize * w as usize + x as usize;
            let c = crisp_px[i].demultiply();
            rendered.put_pixel(x, y, image::Rgba([c.red(), c.green(), c.blue(), c.alpha()]));
            let (xi, yi) = (i64::from(x), i64::from(y));
            match expected.get(xi, yi) {
                Some(k) => {
                    let want = palette[k];
                    let d = &mut colours[k];
                    d.pixels += 1;
                    if c.alpha() != 255 || Colour::new(c.red(), c.green(), c.blue()) != want {
                        d.differing += 1;
                        off(xi, yi);
                    }
                    if smooth_px[i].alpha() < 255 && expected.regions_around(xi, yi, SEAM_RADIUS) {
                        seams += 1;
                    }
                }
                None => {
                    if c.alpha() > 0 {
                        extra += 1;
                        off(xi, yi);
                    }
                }
            }
        }
    }
    let differing = extra + colours.iter().map(|d| d.differing).sum::<u64>();
    let pixels = colours.iter().map(|d| d.pixels).sum();
    Ok(ColourFidelity {
        colours,
        extra,
        differing,
        pixels,
        seams,
        rendered,
        band,
    })
}

/// Distance from the centre of pixel `(x, y)` to the square of the nearest pixel of another
/// colour or of no region, searched up to `limit`.
fn colour_border_distance(expected: &ColourImage, x: i64, y: i64, limit: f64) -> Option<f64> {
    let own = expected.get(x, y);
    distance_where(expected.width(), expected.height(), x, y, limit, |u, v| {
        expected.get(u, v) != own
    })
}

/// A picture of the comparison: the regions in their colours, faded halfway to white,
/// pixels of no region white, differing region pixels red, painted pixels of no region blue.
///
/// ```
/// use layertrace::{colour_diff_image, colour_regions};
/// let img = image::RgbaImage::from_fn(4, 2, |x, _| {
///     if x < 2 { image::Rgba([250, 0, 0, 255]) } else { image::Rgba([0, 0, 250, 255]) }
/// });
/// let regions = colour_regions(&img, 2);
/// // A rendering that paints everything red: the blue region's pixels show as differing.
/// let rendered = image::RgbaImage::from_pixel(4, 2, image::Rgba([250, 0, 0, 255]));
/// let pic = colour_diff_image(&regions.image, &rendered);
/// assert_eq!(pic.get_pixel(3, 0).0, [255, 0, 0]);
/// assert_ne!(pic.get_pixel(0, 0).0, [255, 0, 0]);
/// ```
pub fn colour_diff_image(expected: &ColourImage, rendered: &image::RgbaImage) -> image::RgbImage {
    image::RgbImage::from_fn(expected.width(), expected.height(), |x, y| {
        let r = rendered.get_pixel(x, y);
        let fade = |v: u8| 128 + v / 2;
        image::Rgb(match expected.colour(i64::from(x), i64::from(y)) {
            Some(c) if r[3] == 255 && [r[0], r[1], r[2]] == c.rgb() => {
                [fade(c.r), fade(c.g), fade(c.b)]
            }
            Some(_) => [255, 0, 0],
            None if r[3] > 0 => [0, 0, 255],
            None => [255, 255, 255],
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_squares() -> ColourImage {
        // Left half red, right half blue, a transparent column at the right.
        let px: Vec<Option<u16>> = (0..4 * 5)
            .map(|i| match i % 5 {
                0 | 1 => Some(0),
                2 | 3 => Some(1),
                _ => None,
            })
            .collect();
        ColourImage::new(
            5,
            4,
            &px,
            vec![Colour::new(255, 0, 0), Colour::new(0, 0, 255)],
        )
        .unwrap()
    }

    const HEAD: &str =
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="5" height="4" viewBox="0 0 5 4">"#;

    #[test]
    fn side_by_side_is_exact_but_seamed_stacked_is_not() {
        let img = two_squares();
        // Side by side, along x = 2.5... no: along the pixel edge x = 2, but cut by a
        // slanted edge so that anti-aliasing leaves partial coverage on both sides.
        let side = format!(
            "{HEAD}<path fill=\"#ff0000\" d=\"M0 0H2.4L1.6 4H0Z\"/><path fill=\"#0000ff\" d=\"M2.4 0H4V4H1.6Z\"/></svg>"
        );
        let f = colour_fidelity(&side, &img, None).unwrap();
        assert_eq!(f.differing, 0, "{f:?}");
        assert_eq!(f.pixels, 16);
        assert!(f.seams > 0, "{f:?}");
        // Stacked: red under the whole area, blue on top.
        let stacked = format!(
            "{HEAD}<path fill=\"#ff0000\" d=\"M0 0H4V4H0Z\"/><path fill=\"#0000ff\" d=\"M2.4 0H4V4H1.6Z\"/></svg>"
        );
        let f = colour_fidelity(&stacked, &img, None).unwrap();
        assert_eq!((f.differing, f.seams), (0, 0), "{f:?}");
        // A wrong colour, and paint where no region is.
        let wrong = format!(
            "{HEAD}<path fill=\"#ff0000\" d=\"M0 0H5V4H0Z\"/><path fill=\"#0000fe\" d=\"M2 0H4V4H2Z\"/></svg>"
        );
        let f = colour_fidelity(&wrong, &img, None).unwrap();
        assert_eq!((f.colours[0].differing, f.colours[1].differing), (0, 8));
        assert_eq!((f.extra, f.differing), (4, 12));
        let d = colour_diff_image(&img, &f.rendered);
        assert_eq!(d.get_pixel(2, 0).0, [255, 0, 0]);
        assert_eq!(d.get_pixel(4, 0).0, [0, 0, 255]);
        assert_eq!(d.get_pixel(0, 0).0, [255, 128, 128]);
    }
}
