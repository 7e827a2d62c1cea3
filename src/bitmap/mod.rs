//! Loading images and thresholding them into a binary foreground mask.
//!
//! Two conventions are offered (see [`Compat`]):
//!
//! * [`Compat::Default`] composites transparent pixels on white, takes the Rec. 709 luma
//!   (as `image`'s `to_luma8` does) and thresholds it.
//! * [`Compat::Ipol`] reproduces how the reference code of the IPOL 2014 article reads its
//!   input (8-bit grey through libpng: alpha stripped, libpng's default RGB to grey weights).
//!
//! Image dimensions are checked against [`LoadOptions::max_pixels`] before any pixel is
//! decoded.

mod grey;
mod load;
mod mask;
mod otsu;

pub use grey::Compat;
pub use load::{load_memory, load_path, threshold_image, LoadOptions, Loaded};
pub use mask::Mask;
pub use otsu::Threshold;
