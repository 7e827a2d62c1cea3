//! Outputs of a decomposition: JSON equations, the decomposition picture, SVG, and the SVG
//! as PDF or EPS.

mod drawing;
mod eps;
pub mod format;
pub mod json;
mod pdf;
pub mod picture;
pub mod svg;
