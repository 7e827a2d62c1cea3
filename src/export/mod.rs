//! Outputs of a decomposition: JSON equations, the decomposition picture, SVG (one path, or
//! one per colour), and the SVG as PDF or EPS.

mod drawing;
mod eps;
pub mod format;
mod groups;
pub mod json;
pub(crate) mod json_layout;
pub mod layers;
pub mod partition;
mod path_text;
mod pdf;
pub mod picture;
pub mod svg;
