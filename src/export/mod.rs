//! Outputs of a decomposition: JSON equations, the decomposition picture, SVG.

pub mod json;
pub mod picture;
pub mod svg;
