//! PNG decoded row by row straight into the mask: memory is the mask plus a few rows, whatever
//! the bit depth and colour type (and a grey byte per pixel for Otsu's threshold).

use std::io::{BufRead, Seek};
use std::path::Path;

use image::ColorType;
use png::{Adam7Info, BitDepth, InterlaceInfo, Transformations};

use super::grey::grey_row;
use super::load::{check_dimensions, check_memory, decode_error, Sink, SLACK};
use super::{LoadOptions, Loaded};
use crate::error::Error;

/// Decodes the PNG from `reader` into a [`Loaded`] mask (`held` bytes of input are already in
/// memory, for the estimate). Same pixels as `image`'s PNG decoder: the `png` crate with its
/// `EXPAND` transformation (palette to RGB(A), low bit depths to 8 bits, `tRNS` to alpha).
pub(super) fn load_png<R: BufRead + Seek>(
    reader: R,
    path: &Path,
    opts: &LoadOptions,
    held: u64,
) -> Result<Loaded, Error> {
    let limits = png::Limits {
        bytes: usize::try_from(opts.max_memory).unwrap_or(usize::MAX),
    };
    let mut decoder = png::Decoder::new_with_limits(reader, limits);
    decoder.set_ignore_text_chunk(true);
    let info = decoder.read_header_info().map_err(|e| png_error(e, path))?;
    let (width, height) = (info.width, info.height);
    check_dimensions(path, width, height, opts.max_pixels)?;
    decoder.set_transformations(Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| png_error(e, path))?;
    let (ct, depth) = reader.output_color_type();
    let color = color_type(ct, depth).ok_or_else(|| {
        decode_error(
            path,
            image::ImageFormat::Png,
            format!("unsupported PNG colour type {ct:?} at {depth:?}"),
        )
    })?;
    let line = reader.output_line_size(width).unwrap_or(usize::MAX) as u64;
    // The png crate's raw and unfiltered rows, ours, and the row conversions (at most
    // 4 bytes per sample, 4 samples per pixel).
    let rows = 4 * line + 16 * u64::from(width);
    check_memory(
        path,
        held + Sink::bytes(width, height, opts) + rows + SLACK,
        opts,
    )?;
    let mut sink = Sink::new(width, height, opts, path)?;
    let interlaced = reader.info().interlaced;
    let mut passes = Adam7::new(width, height);
    let mut y = 0u32;
    loop {
        let row = match reader.next_interlaced_row() {
            Ok(Some(row)) => row,
            Ok(None) => break,
            Err(e) => return Err(png_error(e, path)),
        };
        // Where the row's pixels go: every pixel of row y, or one pass line of Adam7.
        let (row_y, x0, step, n) = if interlaced {
            let Some(p) = passes.next() else {
                return Err(decode_error(path, image::ImageFormat::Png, "too many rows"));
            };
            let InterlaceInfo::Adam7(got) = row.interlace() else {
                return Err(decode_error(path, image::ImageFormat::Png, "bad interlace"));
            };
            if *got != Adam7Info::new(p.pass, p.line, width) {
                return Err(decode_error(
                    path,
                    image::ImageFormat::Png,
                    "bad Adam7 order",
                ));
            }
            (p.y, p.x0, p.step, p.samples)
        } else {
            y += 1;
            (y - 1, 0, 1, width)
        };
        let grey = grey_row(color, true, n, row.data(), opts.compat)
            .ok_or_else(|| decode_error(path, image::ImageFormat::Png, "bad row"))?;
        sink.put(row_y, x0, step, &grey);
    }
    if (interlaced && passes.next().is_some()) || (!interlaced && y != height) {
        return Err(Error::Truncated {
            path: path.to_path_buf(),
            detail: "fewer rows than the header announces".into(),
        });
    }
    Ok(sink.finish())
}

/// `image`'s colour type for the png crate's output (after `EXPAND`, depth 8 or 16).
fn color_type(ct: png::ColorType, depth: BitDepth) -> Option<ColorType> {
    use png::ColorType as P;
    Some(match (ct, depth) {
        (P::Grayscale, BitDepth::Eight) => ColorType::L8,
        (P::Grayscale, BitDepth::Sixteen) => ColorType::L16,
        (P::GrayscaleAlpha, BitDepth::Eight) => ColorType::La8,
        (P::GrayscaleAlpha, BitDepth::Sixteen) => ColorType::La16,
        (P::Rgb, BitDepth::Eight) => ColorType::Rgb8,
        (P::Rgb, BitDepth::Sixteen) => ColorType::Rgb16,
        (P::Rgba, BitDepth::Eight) => ColorType::Rgba8,
        (P::Rgba, BitDepth::Sixteen) => ColorType::Rgba16,
        _ => return None,
    })
}

/// The png crate's error as ours: running out of data is [`Error::Truncated`].
fn png_error(e: png::DecodingError, path: &Path) -> Error {
    let truncated = match &e {
        png::DecodingError::IoError(io) => io.kind() == std::io::ErrorKind::UnexpectedEof,
        // "IDAT or fDAT chunk does not have enough data for image."
        png::DecodingError::Format(f) => f.to_string().contains("enough data"),
        _ => false,
    };
    match e {
        _ if truncated => Error::Truncated {
            path: path.to_path_buf(),
            detail: format!("PNG: {e}"),
        },
        png::DecodingError::IoError(source) => Error::Read {
            path: path.to_path_buf(),
            source,
        },
        png::DecodingError::LimitsExceeded => Error::Decode {
            path: path.to_path_buf(),
            source: image::ImageError::Limits(image::error::LimitError::from_kind(
                image::error::LimitErrorKind::InsufficientMemory,
            )),
        },
        e => decode_error(path, image::ImageFormat::Png, e),
    }
}

/// One line of an Adam7 pass: image row `y`, pixels `x0, x0 + step, ...` (`samples` of them).
struct PassLine {
    pass: u8,
    line: u32,
    y: u32,
    x0: u32,
    step: u32,
    samples: u32,
}

/// The lines of the seven Adam7 passes in file order, empty passes skipped (as the png crate
/// orders them; each is checked against the decoder's own [`Adam7Info`]).
struct Adam7 {
    width: u32,
    height: u32,
    pass: u8,
    line: u32,
}

impl Adam7 {
    /// (x offset, x step, y offset, y step) of passes 1 to 7.
    const PASSES: [(u32, u32, u32, u32); 7] = [
        (0, 8, 0, 8),
        (4, 8, 0, 8),
        (0, 4, 4, 8),
        (2, 4, 0, 4),
        (0, 2, 2, 4),
        (1, 2, 0, 2),
        (0, 1, 1, 2),
    ];

    fn new(width: u32, height: u32) -> Adam7 {
        Adam7 {
            width,
            height,
            pass: 1,
            line: 0,
        }
    }
}

impl Iterator for Adam7 {
    type Item = PassLine;

    fn next(&mut self) -> Option<PassLine> {
        while self.pass <= 7 {
            let (x0, xs, y0, ys) = Adam7::PASSES[usize::from(self.pass - 1)];
            let samples = self.width.saturating_sub(x0).div_ceil(xs);
            let lines = self.height.saturating_sub(y0).div_ceil(ys);
            if self.line < lines && samples > 0 {
                let line = self.line;
                self.line += 1;
                return Some(PassLine {
                    pass: self.pass,
                    line,
                    y: y0 + line * ys,
                    x0,
                    step: xs,
                    samples,
                });
            }
            self.pass += 1;
            self.line = 0;
        }
        None
    }
}
