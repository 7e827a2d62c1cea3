//! layertrace: bitmap to SVG with exact curves, by Digital Level Layers.
//!
//! Implements *Digital Level Layers for Digital Curve Decomposition and Vectorization*
//! (L. Provot, Y. Gérard, F. Feschet, IPOL 2014).

mod bitmap;
mod contour;
mod curve;
mod decompose;
mod error;
mod export;
mod fidelity;
mod level;
mod model;
mod output;
mod pixel;
mod recognize;

pub use bitmap::{
    load_memory, load_path, threshold_image, Compat, LoadOptions, Loaded, Mask, Threshold,
};
pub use contour::{trace, Contour, Convention};
pub use curve::{
    intersect_near, level_curve_path, project, Conic, ConicKind, PathCommand, Polynomial,
    ARC_FLATTEN_TOLERANCE, GUIDE_MAX_DISTANCE, MAX_DEGREE,
};
pub use decompose::{
    decompose, decompose_points, neighbour_sides, piece_outliers, Decomposition, OutlierRule, Piece,
};
pub use error::Error;
pub use export::json::{decomposition_json, JsonHeader};
pub use export::picture::{decomposition_picture, default_scale};
pub use export::svg::{
    contour_path, svg_document, CommandCounts, ContourPath, FallbackCounts, JoinCounts, SvgOptions,
    SvgOutput, JUNCTION_MAX_DISTANCE,
};
pub use fidelity::{
    compare, diff_image, fidelity, rasterize_svg, FidelityReport, FLATTEN_TOLERANCE,
};
pub use level::{
    border_polynomial, boundary_level, curve_kind, level_polynomial, piece_kind, polynomial_of,
    CurveKind,
};
pub use model::{Basis, Model, ParseModelError, PolynomialBasis, Terms, MAX_POLY_DEGREE};
pub use output::{png_bytes, write_atomic};
pub use pixel::Pixel;
pub use recognize::{
    max_margin_direction, recognize, Certificate, Outcome, Recognizer, Side, Stats, Witness,
};
