//! layertrace: bitmap to SVG with exact curves, by Digital Level Layers.
//!
//! Implements *Digital Level Layers for Digital Curve Decomposition and Vectorization*
//! (L. Provot, Y. Gérard, F. Feschet, IPOL 2014).

mod bitmap;
mod contour;
mod error;
mod pixel;

pub use bitmap::{
    load_memory, load_path, threshold_image, Compat, LoadOptions, Loaded, Mask, Threshold,
};
pub use contour::{trace, Contour, Convention};
pub use error::Error;
pub use pixel::Pixel;
