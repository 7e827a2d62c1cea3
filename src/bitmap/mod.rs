//! Loading images and thresholding them into a binary foreground mask.
//!
//! Two conventions are offered (see [`Compat`]):
//!
//! * [`Compat::Default`] composites transparent pixels on white, takes the Rec. 709 luma
//!   (as `image`'s `to_luma8` does) and thresholds it.
//! * [`Compat::Ipol`] reproduces how the reference code of the IPOL 2014 article reads its
//!   input (8-bit grey through libpng: alpha stripped, libpng's default RGB to grey weights).
//!
//! Image dimensions are checked against [`LoadOptions::max_pixels`], and the memory that
//! decoding and thresholding will need against [`LoadOptions::max_memory`], before any pixel
//! is decoded. PNG is decoded row by row straight into the mask (through a grey byte per
//! pixel for Otsu's and the adaptive threshold, which need the whole image). For scans, a
//! local threshold ([`Threshold::Adaptive`]) and speck and hole removal ([`Mask::clean`],
//! [`LoadOptions::turdsize`]) follow potrace's companion mkbitmap and its `-t` option.

mod adaptive;
mod band;
mod clean;
pub(crate) mod colour;
mod grey;
mod index;
mod input;
mod jpeg;
mod load;
mod mask;
mod otsu;
mod png;
#[cfg(test)]
mod tests;
mod unfilter;

pub use band::{border_distance, distance_where, Band, MAX_BAND};
pub use clean::Cleaned;
pub use colour::{
    alpha_mask, colour_regions, decode_rgba, has_transparency, load_rgba, Colour, ColourImage,
    Regions, MAX_COLOURS, OPAQUE_ALPHA,
};
pub use grey::Compat;
pub(crate) use index::Index;
pub use input::{default_max_memory, parse_memory_size};
pub use load::{load_memory, load_path, threshold_image, LoadOptions, Loaded};
pub use mask::Mask;
#[cfg(test)]
pub(crate) use mask::{random_mask, repeated_blob};
pub use otsu::{ParseThresholdError, Threshold};
