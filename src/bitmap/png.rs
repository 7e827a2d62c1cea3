//! PNG decoded row by row straight into the mask: memory is the mask plus a few rows, whatever
//! the bit depth and colour type (and a grey byte per pixel for Otsu's threshold).

use std::io::{BufRead, Seek, SeekFrom};
use std::path::Path;

use image::ColorType;
use png::{
    Adam7Info, BitDepth, DecodeOptions, Decoded, InterlaceInfo, StreamingDecoder, Transformations,
    UnfilterRegion,
};

use super::grey::{grey_row, Compat};
use super::load::{check_dimensions, check_memory, decode_error, Sink, SLACK};
use super::unfilter::unfilter;
use super::{LoadOptions, Loaded};
use crate::error::Error;

/// Decodes the PNG from `input` into a [`Loaded`] mask (`held` bytes of input are already in
/// memory, for the estimate). Same pixels as `image`'s PNG decoder: the `png` crate with its
/// `EXPAND` transformation (palette to RGB(A), low bit depths to 8 bits, `tRNS` to alpha).
pub(super) fn load_png<R: BufRead + Seek>(
    mut input: R,
    path: &Path,
    opts: &LoadOptions,
    held: u64,
) -> Result<Loaded, Error> {
    let read_err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let start = input.stream_position().map_err(read_err)?;
    let limits = png::Limits {
        bytes: usize::try_from(opts.max_memory).unwrap_or(usize::MAX),
    };
    let mut decoder = png::Decoder::new_with_limits(&mut input, limits);
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
    let info = reader.info();
    // Rows whose bytes are the pixels as they are (no palette, no bits to expand, no
    // transparent colour; 8 or 16 bits a sample): unfiltered here, flat stretches a chunk at a
    // time (the png crate's Paeth filter of grey rows was 8 of the 13 ms the 3000² sample
    // took to load, all before the drawing may start on several threads). The png crate still
    // reads the chunks, checks them and inflates the data; the file is read again from its
    // start, the chunks before the image data (already checked within the limits) once more.
    let plain = !info.interlaced
        && info.animation_control.is_none()
        && (info.color_type, info.bit_depth) == (ct, depth)
        && matches!(depth, BitDepth::Eight | BitDepth::Sixteen);
    if plain {
        let bpp = ct.samples() * if depth == BitDepth::Sixteen { 2 } else { 1 };
        drop(reader);
        input.seek(SeekFrom::Start(start)).map_err(read_err)?;
        let rows = PlainRows {
            width,
            height,
            bpp,
            color,
            compat: opts.compat,
        };
        rows.decode(input, &mut sink)
            .map_err(|e| e.into_error(path))?;
        return Ok(sink.finish());
    }
    let interlaced = info.interlaced;
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

/// The rows of a non-interlaced PNG whose bytes are its pixels, unfiltered by
/// [`super::unfilter`]: the png crate's [`StreamingDecoder`] reads the chunks and inflates the
/// image data into a buffer kept as the png crate's own reader keeps it.
struct PlainRows {
    width: u32,
    height: u32,
    /// Bytes per pixel.
    bpp: usize,
    color: ColorType,
    compat: Compat,
}

/// How [`PlainRows::decode`] failed.
enum PlainError {
    /// The png crate's error.
    Png(png::DecodingError),
    /// The image data ended before the last row.
    NoMoreData,
    /// A row's filter type is not one of the five.
    UnknownFilter(u8),
    /// A row the grey conversion refused.
    BadRow,
}

impl From<png::DecodingError> for PlainError {
    fn from(e: png::DecodingError) -> PlainError {
        PlainError::Png(e)
    }
}

impl PlainError {
    fn into_error(self, path: &Path) -> Error {
        match self {
            PlainError::Png(e) => png_error(e, path),
            // (The png crate's words for it.)
            PlainError::NoMoreData => Error::Truncated {
                path: path.to_path_buf(),
                detail: "PNG: IDAT or fdAT chunk does not have enough data for image.".into(),
            },
            PlainError::UnknownFilter(f) => decode_error(
                path,
                image::ImageFormat::Png,
                format!("unknown filter method {f}"),
            ),
            PlainError::BadRow => decode_error(path, image::ImageFormat::Png, "bad row"),
        }
    }
}

/// Bytes the inflater may add to the buffer at a time (the png crate's reader's growth).
const GROWTH: usize = 8 * 1024;

/// Bytes of rows already read before the buffer is moved back to its start.
const SHIFT_BACK: usize = 128 * 1024;

impl PlainRows {
    /// Reads the PNG from `reader` (at its signature) and puts its rows in `sink`.
    fn decode<R: BufRead>(&self, mut reader: R, sink: &mut Sink) -> Result<(), PlainError> {
        let mut options = DecodeOptions::default();
        options.set_ignore_text_chunk(true);
        let mut decoder = StreamingDecoder::new_with_options(options);
        let next = |reader: &mut R,
                    decoder: &mut StreamingDecoder,
                    data: Option<png::UnfilterBuf<'_>>|
         -> Result<Decoded, png::DecodingError> {
            let buf = reader.fill_buf()?;
            if buf.is_empty() {
                return Err(png::DecodingError::IoError(
                    std::io::ErrorKind::UnexpectedEof.into(),
                ));
            }
            let (consumed, decoded) = match data {
                Some(mut data) => decoder.update(buf, Some(&mut data))?,
                None => decoder.update(buf, None)?,
            };
            reader.consume(consumed);
            Ok(decoded)
        };
        // The chunks before the image data.
        loop {
            match next(&mut reader, &mut decoder, None)? {
                Decoded::ChunkBegin(_, png::chunk::IDAT) => break,
                Decoded::ChunkComplete(png::chunk::IEND) => return Err(PlainError::NoMoreData),
                _ => {}
            }
        }
        let row_len = self.width as usize * self.bpp;
        // A row as stored: its filter type, then its bytes.
        let stored = row_len + 1;
        // Inflated bytes: `data[start..region.filled]` not yet read as rows (filter byte
        // first); `data[region.available..region.filled]` the inflater's look-back, kept.
        let mut data: Vec<u8> = Vec::new();
        let mut region = UnfilterRegion::default();
        let mut start = 0usize;
        // Image bytes still to come from the inflater.
        let mut remaining = stored as u64 * u64::from(self.height);
        let mut flushed = false;
        let (mut prev, mut cur) = (vec![0u8; row_len], vec![0u8; row_len]);
        for y in 0..self.height {
            while region.filled - start < stored {
                if flushed {
                    return Err(PlainError::NoMoreData);
                }
                // Rows read are dropped from the front now and then (the look-back stays).
                let discard = region.available.min(start);
                if discard >= SHIFT_BACK && region.filled >= data.len() / 2 {
                    data.copy_within(discard..region.filled, 0);
                    region.available -= discard;
                    region.filled -= discard;
                    start -= discard;
                }
                // Room for the inflater, but not beyond the image's bytes.
                if region.filled + GROWTH > data.len() {
                    data.resize(region.filled + GROWTH, 0);
                }
                if let Ok(rest) = usize::try_from(remaining) {
                    if region.filled.saturating_add(rest) < data.len() {
                        data.truncate(region.filled + rest);
                    }
                }
                let before = region.filled;
                let decoded = next(&mut reader, &mut decoder, Some(region.as_buf(&mut data)));
                remaining -= (region.filled - before) as u64;
                if remaining == 0 {
                    region.available = region.filled;
                }
                match decoded {
                    Ok(Decoded::ImageDataFlushed) => flushed = true,
                    Ok(_) => {}
                    // A file cut after this row's bytes still gives this row.
                    Err(png::DecodingError::IoError(e))
                        if e.kind() == std::io::ErrorKind::UnexpectedEof
                            && region.filled - start >= stored =>
                    {
                        break
                    }
                    Err(e) => return Err(e.into()),
                }
            }
            let filter = data[start];
            cur.copy_from_slice(&data[start + 1..start + stored]);
            start += stored;
            unfilter(filter, self.bpp, &prev, &mut cur).ok_or(PlainError::UnknownFilter(filter))?;
            let grey = grey_row(self.color, true, self.width, &cur, self.compat)
                .ok_or(PlainError::BadRow)?;
            sink.put(y, 0, 1, &grey);
            std::mem::swap(&mut prev, &mut cur);
        }
        // The rest of the image data is read and dropped, as the png crate's reader does.
        while !flushed {
            flushed = matches!(
                next(&mut reader, &mut decoder, None)?,
                Decoded::ImageDataFlushed
            );
        }
        Ok(())
    }
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
