//! The one error type of layertrace's I/O boundaries.

use std::path::PathBuf;

/// Everything that can go wrong between the user's files and layertrace.
///
/// Every message is one line, naming the file involved.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The input file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// An output path resolves to the input file (directly, through `./`, a link or a hard
    /// link): writing it would destroy the input.
    #[error("{path}: is the input file; refusing to overwrite it (choose another output name)")]
    OutputIsInput {
        /// The output path as given.
        path: PathBuf,
    },
    /// Two outputs of one run go to the same place (the same file, or both to standard output).
    #[error("{second}: names the same destination as {first}; each output needs its own")]
    SameOutput {
        /// The output named first.
        first: PathBuf,
        /// The output named second.
        second: PathBuf,
    },
    /// The input could not be decoded as an image (unknown format, corrupt or truncated data).
    #[error("cannot decode {path}: {source}")]
    Decode {
        /// The file (`<memory>` for in-memory input).
        path: PathBuf,
        /// The decoder's reason.
        source: image::ImageError,
    },
    /// The image has more pixels than allowed; checked before decoding the pixels.
    #[error("{path}: image is {width}x{height} pixels, more than the limit of {max_pixels} (raise it with --max-pixels)")]
    TooLarge {
        /// The file (`<memory>` for in-memory input).
        path: PathBuf,
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
        /// The limit that was exceeded.
        max_pixels: u64,
    },
    /// The image has zero width or zero height.
    #[error("{path}: image is empty ({width}x{height} pixels)")]
    Empty {
        /// The file (`<memory>` for in-memory input).
        path: PathBuf,
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// The decomposition picture would be too large at the requested scale.
    #[error(
        "{path}: the decomposition picture at scale {scale} would be too large (lower --scale)"
    )]
    PictureTooLarge {
        /// The picture file.
        path: PathBuf,
        /// The requested scale.
        scale: u32,
    },
    /// An output image could not be encoded.
    #[error("cannot encode {path}: {source}")]
    Encode {
        /// The file.
        path: PathBuf,
        /// The encoder's reason.
        source: image::ImageError,
    },
    /// An SVG document could not be parsed (fidelity check).
    #[error("cannot parse SVG: {source}")]
    SvgParse {
        /// usvg's reason.
        source: usvg::Error,
    },
    /// No raster of this size can be made (zero or too large).
    #[error("cannot rasterize at {width}x{height} pixels")]
    Raster {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
}
