//! Colour vectorization: the image as regions of flat colour, each colour's layer traced,
//! decomposed and drawn with the binary pipeline, the layers stacked in a fixed order.
//!
//! # The stack
//! Layer `k` is the mask of the pixels whose colour is the `k`-th drawn *or any drawn
//! after it*: it covers its own colour, never a colour drawn before it (those are outside
//! its mask, and the render check keeps them out pixel for pixel), and is free to run under
//! the colours drawn after it. Each layer is exact in crispEdges on its own, so the stack is:
//! a pixel of the `k`-th colour is painted by layers `0..=k`, the last of them its own
//! colour, and by no later layer. Anti-aliased, the pixels along an edge between two regions
//! are covered by the lower layer whole, so no background shows through.
//!
//! # The image border
//! Each layer's mask is padded by one pixel on every side, each margin pixel a copy of the
//! nearest image pixel, before it is traced: a border that meets the image's edge runs on
//! into the margin instead of along the edge, and the first layer of an opaque image is a
//! rectangle one pixel larger than the image on every side. Traced unpadded, a curve piece
//! along the edge may cut a corner off an edge pixel (its centre still inside): exact in
//! crispEdges but a sliver of background anti-aliased. The path data is written moved
//! back by one pixel (exact: an integer shift), and renderers clip what lies outside the
//! image.
//!
//! # The order
//! Greedy, to keep the masks' borders short: the first layer is every pixel of a region;
//! then, of the colours not drawn yet, the one drawn next is the one whose removal leaves
//! the others' union with the shortest border, counted in pixel edges between that union
//! and the other pixels (the image border not counted), ties broken by more pixels first,
//! then by palette order (decreasing pixel count). For a background with disjoint shapes
//! the shape with the shortest border goes first, under the background (whose layer then
//! has a hole there instead of its border drawn twice), and the background before the
//! other shapes; the sum of the layers' borders is the same as drawing the background
//! first, one layer shorter.

use std::path::Path;

use super::options::Options;
use crate::bitmap::{colour_regions, decode_rgba, load_rgba, Band, Colour, Mask, Regions};
use crate::contour::{trace, Convention};
use crate::decompose::{decompose_reporting, Decomposition, OutlierRule};
use crate::error::Error;
use crate::export::json::{colour_json, JsonRegion};
use crate::export::layers::{layers_document, SvgLayer};
use crate::export::svg::SvgOutput;
use crate::fidelity::{colour_fidelity, ColourFidelity};
use crate::outline::Partition;

/// One layer of the stack.
#[derive(Clone, Debug)]
pub struct ColourLayer {
    /// Its colour.
    pub colour: Colour,
    /// Pixels of this colour.
    pub pixels: u64,
    /// The pixels it covers: its colour's and those of every colour drawn after it.
    pub mask: Mask,
    /// The borders of the mask padded by one pixel on every side (see the module
    /// documentation), decomposed: its pixel `(x + 1, y + 1)` is the image's `(x, y)`.
    pub decomposition: Decomposition,
}

/// What a colour vectorization made besides the SVG and the JSON.
#[derive(Clone, Debug)]
pub struct ColourVectorized {
    /// The regions (the quantized image when the input had more colours than asked).
    pub regions: Regions,
    /// The layers in drawing order. With [`Layout::Partition`](super::Layout::Partition):
    /// one per colour in palette order, each the colour's own pixels, and its
    /// decomposition that of their borders (padded the same way).
    pub layers: Vec<ColourLayer>,
    /// The comparison with the regions, if [`Options::fidelity`] and an SVG were asked.
    pub fidelity: Option<ColourFidelity>,
    /// With [`Layout::Partition`](super::Layout::Partition): the borders, each drawn once,
    /// and each region's loops of them.
    pub partition: Option<Partition>,
}

/// What [`run`] returns to [`vectorize`](super::vectorize).
pub(crate) struct ColourRun {
    pub(crate) colour: ColourVectorized,
    pub(crate) svg: Option<SvgOutput>,
    pub(crate) json: Option<String>,
    /// Every layer's contours and pieces, in drawing order.
    pub(crate) merged: Decomposition,
    /// The pixels of every region.
    pub(crate) mask: Mask,
}

/// Decodes the image and vectorizes it in `colors` colours.
pub(super) fn run(
    name: &Path,
    source: super::Source<'_>,
    colors: u16,
    options: &Options,
) -> Result<ColourRun, Error> {
    let rgba = match source {
        super::Source::Path(path) => load_rgba(path, options.max_pixels, options.max_memory)?,
        super::Source::Bytes(bytes) => {
            decode_rgba(bytes, name, options.max_pixels, options.max_memory)?
        }
        super::Source::Mask(_) => {
            return Err(Error::Arguments(
                "colour vectorization needs an image, not a mask".into(),
            ))
        }
    };
    let regions = colour_regions(&rgba, colors);
    drop(rgba);
    if options.layout == super::Layout::Partition {
        return super::partition_run::run(name, regions, options);
    }
    let image = &regions.image;
    let order = stack_order(image);
    let counts = image.counts();
    let mut rank = vec![0usize; order.len()];
    for (r, &k) in order.iter().enumerate() {
        rank[k] = r;
    }
    let mut layers = Vec::with_capacity(order.len());
    // Smooth outlines: each layer's band, its outline kept in the image's part of the
    // padded mask (a path leaving the image is cut by the renderer).
    let mut bands: Vec<Option<Band>> = Vec::with_capacity(order.len());
    let (m, iw, ih) = (
        MARGIN as f64,
        f64::from(image.width()),
        f64::from(image.height()),
    );
    for (r, &k) in order.iter().enumerate() {
        let mask = image.mask_where(|c| rank[c] >= r);
        let padded = pad(&mask);
        bands.push(
            options
                .smooth
                .and_then(|nu| Band::new(&padded, nu))
                .map(|b| b.within(m, m, m + iw, m + ih)),
        );
        layers.push(ColourLayer::traced(
            image.palette()[k],
            counts[k],
            mask,
            &padded,
            name,
            options,
        )?);
    }
    let (w, h) = (image.width(), image.height());
    let fills: Vec<String> = layers.iter().map(|l| l.colour.to_string()).collect();
    let svg = options.svg.as_ref().map(|o| {
        let svg_layers: Vec<SvgLayer<'_>> = layers
            .iter()
            .zip(&fills)
            .zip(&bands)
            .map(|((l, fill), band)| SvgLayer {
                fill,
                decomposition: &l.decomposition,
                band: band.as_ref(),
            })
            .collect();
        layers_document(&svg_layers, w, h, MARGIN as u32, o)
    });
    let json = options.json.then(|| {
        let regions: Vec<JsonRegion<'_>> = layers
            .iter()
            .zip(&fills)
            .map(|(l, colour)| JsonRegion {
                colour,
                pixels: l.pixels,
                decomposition: &l.decomposition,
                margin: MARGIN,
            })
            .collect();
        colour_json(
            &regions,
            options.model,
            options.cover,
            w,
            h,
            options.layout.name(),
        )
    });
    ColourRun::finish(regions, layers, svg, json, None, options)
}

impl ColourRun {
    /// The run once its layers are drawn: the fidelity check (when asked), the merged
    /// decomposition and the mask of every region's pixels.
    pub(super) fn finish(
        regions: Regions,
        layers: Vec<ColourLayer>,
        svg: Option<SvgOutput>,
        json: Option<String>,
        partition: Option<Partition>,
        options: &Options,
    ) -> Result<ColourRun, Error> {
        let image = &regions.image;
        let fidelity = match (&svg, options.fidelity) {
            (Some(svg), true) => Some(colour_fidelity(&svg.svg, image, options.smooth)?),
            _ => None,
        };
        let merged = merged_decomposition(&layers, options);
        let mask = image.mask_where(|_| true);
        Ok(ColourRun {
            colour: ColourVectorized {
                regions,
                layers,
                fidelity,
                partition,
            },
            svg,
            json,
            merged,
            mask,
        })
    }
}

impl ColourLayer {
    /// The layer of `mask`, whose padded copy `padded` (see the module documentation) is
    /// traced and decomposed, after the memory check.
    pub(super) fn traced(
        colour: Colour,
        pixels: u64,
        mask: Mask,
        padded: &Mask,
        name: &Path,
        options: &Options,
    ) -> Result<ColourLayer, Error> {
        let contours = trace(padded, Convention::Default);
        super::check_memory(name, options, &contours, &mask)?;
        let decomposition = decompose_reporting(
            contours,
            options.model,
            OutlierRule::NotInPiece,
            options.budget,
            options.cover,
            &|_| {},
        );
        Ok(ColourLayer {
            colour,
            pixels,
            mask,
            decomposition,
        })
    }
}

/// Every layer's contours and pieces in drawing order, as one decomposition.
pub(super) fn merged_decomposition(layers: &[ColourLayer], options: &Options) -> Decomposition {
    let mut merged = Decomposition {
        model: options.model,
        contours: Vec::new(),
        pieces: Vec::new(),
        rule: OutlierRule::NotInPiece,
        cover: options.cover,
        stats: Default::default(),
    };
    for l in layers {
        merged
            .contours
            .extend(l.decomposition.contours.iter().cloned());
        merged.pieces.extend(l.decomposition.pieces.iter().cloned());
        merged.stats += &l.decomposition.stats;
    }
    merged
}

/// The margin of the padded masks.
pub(super) const MARGIN: i64 = 1;

/// `mask` with a margin of [`MARGIN`] pixel on every side, each margin pixel a copy of the
/// nearest pixel of the image.
pub(super) fn pad(mask: &Mask) -> Mask {
    let (w, h) = (i64::from(mask.width()), i64::from(mask.height()));
    let m = MARGIN as u32;
    Mask::from_fn(mask.width() + 2 * m, mask.height() + 2 * m, |x, y| {
        let x = (i64::from(x) - MARGIN).clamp(0, w - 1);
        let y = (i64::from(y) - MARGIN).clamp(0, h - 1);
        mask.get(x, y)
    })
}

/// The drawing order of the palette indices of `image` (see the module documentation).
pub fn stack_order(image: &crate::bitmap::ColourImage) -> Vec<usize> {
    let n = image.palette().len();
    // adj[a][b]: 4-adjacent pixel pairs of colours a and b (index n: no region).
    let mut adj = vec![vec![0u64; n + 1]; n + 1];
    let at = |x: i64, y: i64| image.get(x, y).unwrap_or(n);
    for y in 0..i64::from(image.height()) {
        for x in 0..i64::from(image.width()) {
            let a = at(x, y);
            for (dx, dy) in [(1, 0), (0, 1)] {
                let (u, v) = (x + dx, y + dy);
                if u < i64::from(image.width()) && v < i64::from(image.height()) {
                    let b = at(u, v);
                    if a != b {
                        adj[a][b] += 1;
                        adj[b][a] += 1;
                    }
                }
            }
        }
    }
    let counts = image.counts();
    let mut left: Vec<bool> = vec![true; n];
    let mut order = Vec::with_capacity(n);
    while order.len() < n {
        let mut best: Option<(u64, usize)> = None;
        for c in (0..n).filter(|&c| left[c]) {
            // The border of (left \ {c}): its pairs with every colour not left (and no
            // region), minus c's own pairs with them, plus c's pairs with the rest of left.
            let border: u64 = (0..n)
                .filter(|&a| left[a] && a != c)
                .map(|a| {
                    (0..=n)
                        .filter(|&b| b == n || !left[b] || b == c)
                        .map(|b| adj[a][b])
                        .sum::<u64>()
                })
                .sum();
            let better = match best {
                None => true,
                Some((b, k)) => border < b || (border == b && counts[c] > counts[k]),
            };
            if better {
                best = Some((border, c));
            }
        }
        let Some((_, c)) = best else { break };
        left[c] = false;
        order.push(c);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::ColourImage;
    use proptest::prelude::*;

    fn image(art: &str) -> ColourImage {
        let rows: Vec<&str> = art
            .lines()
            .map(str::trim)
            .filter(|r| !r.is_empty())
            .collect();
        let (w, h) = (rows[0].len() as u32, rows.len() as u32);
        let px: Vec<Option<u16>> = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| (b != b'.').then(|| u16::from(b - b'0'))))
            .collect();
        let palette = (0..=px.iter().flatten().copied().max().unwrap_or(0))
            .map(|k| Colour::new(k as u8 * 40, 0, 0))
            .collect();
        ColourImage::new(w, h, &px, palette).unwrap()
    }

    #[test]
    fn background_with_two_shapes() {
        // 0 the background, 1 a large square, 2 a small one: 2 first (the background then
        // has a hole there), then 0, then 1 on top.
        let img = image(
            "00000000
             01110000
             01110020
             01110000
             00000000",
        );
        assert_eq!(stack_order(&img), vec![2, 0, 1]);
    }

    fn png(w: u32, h: u32, px: &[u8]) -> Vec<u8> {
        let palette = [
            [0, 0, 0, 0],
            [230, 40, 40, 255],
            [40, 90, 220, 255],
            [250, 250, 250, 255],
        ];
        let img = image::RgbaImage::from_fn(w, h, |x, y| {
            image::Rgba(palette[usize::from(px[(y * w + x) as usize] % 4)])
        });
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// Random images of three colours and transparency: the stack is exact in
        /// crispEdges, seamless anti-aliased, one path per colour in drawing order.
        #[test]
        fn stack_is_exact_and_seamless(
            (w, h, px) in (1u32..10, 1u32..10).prop_flat_map(|(w, h)| {
                (Just(w), Just(h), prop::collection::vec(0u8..4, (w * h) as usize))
            })
        ) {
            let options = Options::default().colors(4).fidelity(true);
            let v = crate::vectorize(&png(w, h, &px), &options).unwrap();
            let c = v.colour.unwrap();
            let f = c.fidelity.unwrap();
            prop_assert_eq!(f.differing, 0, "{:?}", f.colours);
            prop_assert_eq!(f.seams, 0);
            prop_assert!(c.regions.exact);
            let paths = v.svg.unwrap().svg.matches("<path ").count();
            prop_assert_eq!(paths, c.layers.len());
        }
    }

    #[test]
    fn every_colour_once() {
        let img = image(
            "0123.
             3210.
             .....",
        );
        let mut o = stack_order(&img);
        o.sort();
        assert_eq!(o, vec![0, 1, 2, 3]);
    }
}
