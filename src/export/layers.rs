//! The SVG of a colour image: one `<path>` per colour, drawn in order (`--layout stack`).
//!
//! The document is that of [`svg_document`](super::svg::svg_document) (same header, same
//! path data, `fill-rule="nonzero"`; PDF and EPS read it as well), with one
//! `<path fill="#rrggbb" …>` per layer in drawing order instead of one path; a layer
//! without contours writes no path. In the
//! stack layout layer `k` covers the pixels of colour `k` and of every colour drawn after
//! it: each later layer paints its own pixels over it, so every pixel ends with its own
//! colour, and no background shows between two regions, anti-aliased or not.

use std::fmt::Write as _;

use crate::bitmap::Band;
use crate::decompose::Decomposition;
use crate::export::path_text::xml_escape;
use crate::export::svg::{empty_output, outline_options, path_data, SvgOptions, SvgOutput};
use crate::outline::OutlineOptions;

/// One layer of [`layers_document`]: its fill and its borders.
#[derive(Clone, Copy, Debug)]
pub struct SvgLayer<'a> {
    /// The `fill` attribute (XML-escaped on output).
    pub fill: &'a str,
    /// The borders of the layer's mask, decomposed.
    pub decomposition: &'a Decomposition,
    /// With smooth outlines: the band of the layer's (padded) mask.
    pub band: Option<&'a Band>,
}

/// The SVG document of `layers` drawn in order over a `width` × `height` image, with the
/// outline options of `opts` (its `fill` is not used: each layer has its own). The
/// layers' contours are in the coordinates of the image padded by `margin` pixels on every
/// side (image pixel `(x, y)` is `(x + margin, y + margin)`), and are written moved back
/// into the image's. The output's counts are those of all layers.
///
/// ```
/// use layertrace::{decompose, layers_document, trace, Convention, Mask, Model, OutlierRule};
/// use layertrace::{SvgLayer, SvgOptions};
/// // Two layers of a 6 × 4 image, traced on masks padded by one pixel.
/// let wide = Mask::from_ascii("........\n.######.\n.######.\n.######.\n.######.\n........");
/// let small = Mask::from_ascii("........\n........\n...##...\n...##...\n........\n........");
/// let dw = decompose(trace(&wide, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let ds = decompose(trace(&small, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let layers = [
///     SvgLayer { fill: "#1f4e9c", decomposition: &dw, band: None },
///     SvgLayer { fill: "#f2c318", decomposition: &ds, band: None },
/// ];
/// let out = layers_document(&layers, 6, 4, 1, &SvgOptions::default());
/// assert_eq!(out.svg.matches("<path").count(), 2);
/// assert!(out.svg.find("#1f4e9c") < out.svg.find("#f2c318"));
/// ```
pub fn layers_document(
    layers: &[SvgLayer<'_>],
    width: u32,
    height: u32,
    margin: u32,
    opts: &SvgOptions,
) -> SvgOutput {
    // The stack's anti-aliased seams rely on each colour's edges as drawn: no merged lines.
    let outline = OutlineOptions {
        merge_lines: false,
        ..outline_options(opts, width, height, margin)
    };
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{width}\" \
         height=\"{height}\" viewBox=\"0 0 {width} {height}\">"
    );
    let mut drawn = Vec::with_capacity(layers.len());
    for layer in layers {
        let paths = path_data(layer.decomposition, &outline, layer.band, margin, &|_| {});
        if !paths.data.is_empty() {
            let _ = writeln!(
                svg,
                "<path fill=\"{}\" fill-rule=\"nonzero\" d=\"{}\"/>",
                xml_escape(layer.fill),
                paths.data
            );
        }
        drawn.push(paths);
    }
    svg.push_str("</svg>\n");
    let mut out = empty_output(svg);
    for paths in &drawn {
        out.add(paths);
    }
    out
}
