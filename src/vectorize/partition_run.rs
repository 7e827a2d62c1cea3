//! `--colors N --layout partition` from the regions to the outputs: every region's own
//! pixels traced and decomposed, the shared borders drawn once (see [`super::partition`]),
//! then the SVG, the JSON and the fidelity asked for.

use crate::decompose::Decomposition;
use crate::error::Error;

/// The partition layout of [`super::colour::run`]: every region's own pixels traced and
/// decomposed, the borders drawn once, the SVG, JSON and fidelity asked.
pub(super) fn run(
    name: &std::path::Path,
    regions: crate::bitmap::Regions,
    options: &super::Options,
) -> Result<super::colour::ColourRun, Error> {
    use super::colour::{pad, ColourLayer, ColourRun, MARGIN};
    use crate::export::partition::{
        partition_document, partition_json, path_data, PartitionRegion,
    };

    if options.smooth.is_some() {
        return Err(Error::Arguments(
            "smooth: not with --layout partition (its borders are exact)".into(),
        ));
    }
    let image = &regions.image;
    let counts = image.counts();
    let mut layers = Vec::with_capacity(image.palette().len());
    for (k, &colour) in image.palette().iter().enumerate() {
        let mask = image.mask_where(|c| c == k);
        let padded = pad(&mask);
        layers.push(ColourLayer::traced(
            colour, counts[k], mask, &padded, name, options,
        )?);
    }
    let outline = options
        .svg
        .as_ref()
        .map(|svg| {
            crate::export::svg::outline_options(svg, image.width(), image.height(), MARGIN as u32)
        })
        .unwrap_or_default();
    // Borders are cut out of the regions' paths at the corners where regions meet: those
    // vertices must stay, so no lines are merged.
    let outline = crate::outline::OutlineOptions {
        merge_lines: false,
        ..outline
    };
    let decompositions: Vec<&Decomposition> = layers.iter().map(|l| &l.decomposition).collect();
    let part = super::partition::partition(image, &decompositions, MARGIN, &outline)?;
    let (w, h) = (image.width(), image.height());
    let fills: Vec<String> = layers.iter().map(|l| l.colour.to_string()).collect();
    let svg = options.svg.as_ref().map(|_| {
        let mut commands = crate::outline::CommandCounts::default();
        let data: Vec<(String, String)> = (0..layers.len())
            .map(|k| {
                // The grid the render check drew with (`o.grid` clamped by outline_options).
                let (d, c) = path_data(&part.region_paths(k), outline.grid);
                commands += &c;
                (fills[k].clone(), d)
            })
            .collect();
        let mut out = crate::export::svg::empty_output(partition_document(&data, w, h));
        out.commands = commands;
        out
    });
    let json = options.json.then(|| {
        let regions: Vec<PartitionRegion<'_>> = layers
            .iter()
            .zip(&fills)
            .map(|(l, colour)| PartitionRegion {
                colour,
                pixels: l.pixels,
                decomposition: &l.decomposition,
            })
            .collect();
        partition_json(
            &regions,
            &part,
            MARGIN,
            (options.model, options.cover),
            w,
            h,
        )
    });
    // (Smooth partitions are refused above, so the fidelity check has no band.)
    ColourRun::finish(regions, layers, svg, json, Some(part), options)
}
