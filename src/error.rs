//! The one error type of layertrace's I/O boundaries.

use std::path::PathBuf;

/// Everything that can go wrong between the user's files and layertrace.
///
/// Every message is one line, naming the file involved.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The command line asks for something impossible (the message says what instead).
    #[error("{0}")]
    Arguments(String),
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
    /// A signal asked the run to stop ([`crate::interrupt_flags`]) while an
    /// [`crate::OutputSet`] held temporary files: they are removed and no destination
    /// changed.
    #[error("stopped by signal {signal}")]
    Interrupted {
        /// The signal's number.
        signal: i32,
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
    /// The image data ends early, or is too short for what its header announces.
    #[error("cannot decode {path}: the data is truncated or corrupt ({detail})")]
    Truncated {
        /// The file (`<memory>` for in-memory input, `<stdin>` for standard input).
        path: PathBuf,
        /// What showed it.
        detail: String,
    },
    /// Decoding and thresholding the image would need more memory than allowed; checked
    /// before the large allocations.
    #[error(
        "{path}: needs about {} of memory, more than the limit of {} (raise it with --max-memory)",
        size(*needed),
        size(*limit)
    )]
    NeedsMemory {
        /// The file.
        path: PathBuf,
        /// Estimated bytes needed.
        needed: u64,
        /// The limit ([`crate::LoadOptions::max_memory`]).
        limit: u64,
    },
    /// The system refused an allocation that the memory limit allowed.
    #[error("{path}: out of memory: cannot allocate {} (lower --max-memory to be refused before decoding)", size(*bytes))]
    OutOfMemory {
        /// The file.
        path: PathBuf,
        /// The size of the refused allocation.
        bytes: u64,
    },
    /// A pipe, FIFO or other input read into memory is longer than allowed.
    #[error("{path}: input is longer than {}, the bound set by --max-pixels and --max-memory", size(*limit))]
    InputTooLarge {
        /// The file (`<stdin>` for standard input).
        path: PathBuf,
        /// The bound in bytes.
        limit: u64,
    },
    /// The input holds no data at all.
    #[error("{path}: no data (empty file, or a pipe or FIFO with no writer)")]
    NoData {
        /// The file (`<stdin>` for standard input).
        path: PathBuf,
    },
    /// A binary run found no foreground in an image that has transparency: what is drawn is
    /// most likely in the alpha channel (a light logo on transparency).
    #[error("{path}: no foreground pixel at threshold {threshold}, but the image has transparency: try --alpha (its alpha channel as the shape) or --colors N")]
    NoForeground {
        /// The file (`<memory>` for in-memory input).
        path: PathBuf,
        /// The grey threshold used.
        threshold: u8,
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
    /// An output's name does not give a format that its option writes: an unknown
    /// extension, or none (see [`crate::Format::from_path`]); checked before any work.
    #[error("{path}: {} (use {expected})", unknown_format(extension.as_deref()))]
    UnknownFormat {
        /// The output path as given.
        path: PathBuf,
        /// Its extension, `None` when it has none.
        extension: Option<String>,
        /// The extensions accepted, e.g. `.svg, .pdf or .eps`.
        expected: &'static str,
    },
    /// The SVG document could not be written as PDF or EPS (see [`crate::document_bytes`]).
    #[error("cannot write {format}: {reason}")]
    Convert {
        /// The format asked for.
        format: crate::Format,
        /// Why (one line).
        reason: String,
    },
    /// A file of point sets (`layertrace recognize`) could not be read as one: not JSON, a
    /// field missing or of the wrong type, a coordinate that is not a 64-bit integer, points
    /// of different dimensions. The message names the field and, when the JSON parser knows
    /// it, the line and column.
    #[error("{path}: {message}")]
    PointFile {
        /// The file (`<stdin>` for standard input, `<memory>` for in-memory data).
        path: PathBuf,
        /// What is wrong, and where (one line).
        message: String,
    },
    /// Point sets that cannot be recognized as given: no inliers, a model of another
    /// dimension, a point whose lifting overflows 64-bit integers, or (never met in the
    /// tests) a recognition that could decide neither way. The message names the point.
    #[error("{0}")]
    Points(String),
    /// No raster of this size can be made (zero or too large).
    #[error("cannot rasterize at {width}x{height} pixels")]
    Raster {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
}

/// The start of an [`Error::UnknownFormat`] message.
fn unknown_format(extension: Option<&str>) -> String {
    match extension {
        Some(e) => format!("unknown output format '{e}'"),
        None => "no extension to name the output format".into(),
    }
}

/// A byte count for messages: GiB with one decimal from 1 GiB on, else MiB, else KiB.
fn size(bytes: u64) -> String {
    const KIB: f64 = 1024.0;
    let b = bytes as f64;
    if b >= KIB * KIB * KIB {
        format!("{:.1} GiB", b / (KIB * KIB * KIB))
    } else if b >= KIB * KIB {
        format!("{:.0} MiB", b / (KIB * KIB))
    } else {
        format!("{:.0} KiB", (b / KIB).ceil())
    }
}
