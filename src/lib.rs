//! layertrace: bitmap to SVG with exact curves, by Digital Level Layers.
//!
//! One call does it all: [`vectorize`] reads an image (a file, encoded bytes or a [`Mask`]),
//! and returns the SVG, the decomposition with the exact equation of every piece, and on
//! request the fidelity check, the JSON and a picture of the pieces ([`Options`] says which).
//!
//! ```
//! use layertrace::{vectorize, Model, Options};
//!
//! let options = Options::default().model(Model::Conic).fidelity(true);
//! let out = vectorize(std::path::Path::new("samples/glyph_g_liberationserif_cap120.png"), &options)?;
//! std::fs::write(std::env::temp_dir().join("g.svg"), out.svg_text()).unwrap();
//!
//! // What resvg draws of the SVG is the input's mask, pixel for pixel.
//! assert_eq!(out.fidelity.unwrap().report.differing, 0);
//! println!("{} pieces", out.decomposition.piece_count());
//! # Ok::<(), layertrace::Error>(())
//! ```
//!
//! Implements *Digital Level Layers for Digital Curve Decomposition and Vectorization*
//! (L. Provot, Y. Gérard, F. Feschet, IPOL 2014). Data flows through the stages in order,
//! each callable on its own:
//! [`load_path`] (image → foreground [`Mask`]), [`trace`] (borders as 8-connected pixel
//! paths), [`decompose`] (greedy pieces, each with an exact [`Certificate`] from the
//! [`Recognizer`]), then [`decomposition_json`], [`decomposition_picture`] and
//! [`svg_document`], and [`fidelity`] to render the SVG back as resvg draws it and count
//! differing pixels ([`staircases`] counts pixel staircases in its path data).
//! Point sets given as such, in 2-D or 3-D, go to [`recognize_points`] (`layertrace
//! recognize` on the command line).
//!
//! Colour images ([`Options::colors`], `--colors N`): [`colour_regions`] makes regions of
//! at most `N` flat colours (the input's own when it has no more), the stack order orders
//! them, each colour's layer goes through the stages above, [`layers_document`] draws one
//! path per colour, [`colour_fidelity`] compares the rendering colour by colour and counts
//! seams, [`colour_json`] writes every region's borders and equations. With
//! [`Layout::Partition`] the cracks between regions are cut at their junctions into
//! borders ([`BorderGraph`]), each drawn once and used by both of its regions
//! ([`Partition`]), so no two paths overlap.
//!
//! ```
//! use layertrace::{decompose, fidelity, svg_document, trace, Convention, Mask, Model,
//!                  OutlierRule, SvgOptions};
//!
//! // A filled disc of radius 6 on a 16 × 16 bitmap (pixel centres within the circle).
//! let mask = Mask::from_fn(16, 16, |x, y| {
//!     let (dx, dy) = (x as f64 + 0.5 - 8.0, y as f64 + 0.5 - 8.0);
//!     dx * dx + dy * dy <= 36.0
//! });
//! let contours = trace(&mask, Convention::Default);
//! assert_eq!(contours.len(), 1);
//!
//! let d = decompose(contours, Model::Circle, OutlierRule::NotInPiece);
//! let basis = Model::Circle.basis();
//! for (contour, pieces) in d.contours.iter().zip(&d.pieces) {
//!     for piece in pieces {
//!         // Every pixel of the piece lies in its layer, exactly.
//!         let c = &piece.certificate;
//!         for p in &contour.points[piece.first..=piece.last] {
//!             let f = c.value(&basis, &[p.x.into(), p.y.into()]).unwrap();
//!             assert!(c.extremes.lower <= f && f <= c.extremes.upper);
//!         }
//!     }
//! }
//!
//! let svg = svg_document(&d, 16, 16, &SvgOptions::default());
//! let report = fidelity(&svg.svg, &mask).unwrap();
//! println!("{} pieces, {} differing pixels", d.piece_count(), report.differing);
//! ```

mod bitmap;
mod contour;
mod curve;
mod decompose;
mod error;
mod estimate;
mod export;
mod fidelity;
mod level;
mod model;
mod outline;
mod output;
mod pixel;
mod pixel_flags;
mod points;
mod recognize;
mod steps;
mod vectorize;

pub use vectorize::{
    vectorize, ColourLayer, ColourVectorized, Fidelity, Layout, Options, ParseLayoutError,
    Progress, ProgressFn, Source, Stage, Vectorized,
};

pub use bitmap::{
    alpha_mask, colour_regions, decode_rgba, has_transparency, load_rgba, Colour, ColourImage,
    Regions, MAX_COLOURS, OPAQUE_ALPHA,
};
pub use bitmap::{
    border_distance, default_max_memory, load_memory, load_path, parse_memory_size,
    threshold_image, Band, Cleaned, Compat, LoadOptions, Loaded, Mask, ParseThresholdError,
    Threshold, MAX_BAND,
};
pub use contour::{trace, Border, BorderGraph, Contour, Convention};
pub use curve::{
    level_curve_path, Conic, CurveKind, EllipseParams, HyperbolaParams, LevelPath, ParabolaParams,
    PathCommand, Polynomial, MAX_DEGREE,
};
pub use decompose::{
    decompose, decompose_cover, decompose_points, decompose_within, piece_outliers, Cover, Cut,
    Decomposition, OutlierRule, Outliers, Piece, WorkBudget,
};
pub use error::Error;
pub use estimate::{work_estimate, WorkEstimate};
pub use export::format::{document_bytes, Format, PictureFormat};
pub use export::json::{colour_json, decomposition_json, JsonHeader, JsonRegion};
pub use export::layers::{layers_document, SvgLayer};
pub use export::picture::decomposition_picture;
pub use export::svg::{smooth_svg_document, svg_document, SvgOptions, SvgOutput};
pub use fidelity::{
    band_check, compare, diff_image, fidelity, rasterize_svg, rasterize_svg_in_tiles, staircases,
    BandCheck, FidelityReport, StaircaseCount,
};
pub use fidelity::{colour_diff_image, colour_fidelity, ColourDiff, ColourFidelity};
pub use level::{boundary_level, curve_kind, level_polynomial, piece_kind};
pub use model::{Basis, Model, ParseModelError, PolynomialBasis, Terms, MAX_POLY_DEGREE};
/// The exact integers and fractions of [`Layer`] and [`Witness::exact_weights`].
pub use num_bigint::BigInt;
/// See [`BigInt`].
pub use num_rational::BigRational;
pub use outline::{
    contour_path, BorderSource, CommandCounts, ContourPath, EdgeClipping, FallbackCounts,
    JoinCounts, OutlineOptions, Partition, PartitionBorder, DEFAULT_MAX_CURVE_POINTS,
    DEFAULT_MIN_CURVE_POINTS, MAX_GRID,
};
pub use output::{
    exit_removing_temporaries, interrupt_flags, png_bytes, write_atomic, InterruptFlags, OutputId,
    OutputSet,
};
pub use pixel::Pixel;
pub use points::{
    point_sets_from_json, read_point_sets, recognition_json, recognize_points,
    recognize_points_with, Layer, PointSets, PointsAnswer, PointsRecognition, Thinnest,
    ThinnestWork,
};
pub use recognize::{
    max_margin_direction, recognize, Certificate, Extremes, MarginDirection, Outcome, Recognition,
    Recognizer, Side, Stats, Witness,
};
