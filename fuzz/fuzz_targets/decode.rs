//! Arbitrary bytes through the whole pipeline: decode, threshold, trace, decompose, JSON and
//! SVG export, and the SVG's round trip.
#![no_main]

use layertrace::{
    decompose, decomposition_json, fidelity, load_memory, svg_document, trace, Convention,
    JsonHeader, LoadOptions, Model, OutlierRule, SvgOptions,
};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let opts = LoadOptions {
        max_pixels: 1 << 16,
        ..LoadOptions::default()
    };
    let Ok(loaded) = load_memory(data, &opts) else {
        return;
    };
    let contours = trace(&loaded.mask, Convention::Default);
    let d = decompose(contours, Model::Conic, OutlierRule::NotInPiece);
    assert_eq!(d.stats.undecided, 0);
    let h = JsonHeader {
        width: loaded.mask.width(),
        height: loaded.mask.height(),
        threshold: loaded.threshold,
        invert: false,
    };
    let _ = decomposition_json(&d, &h);
    let out = svg_document(&d, h.width, h.height, &SvgOptions::default());
    // The SVG must parse and rasterize.
    fidelity(&out.svg, &loaded.mask).expect("the SVG parses");
});
