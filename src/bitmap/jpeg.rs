//! JPEG, decoded by zune-jpeg in strict mode after a walk over the file's segments: a file
//! that ends before its end-of-image marker, or whose image data is too short for the size its
//! header announces, is refused as truncated before anything large is allocated.

use std::path::Path;

use image::{ColorType, ImageFormat};
use zune_core::bytestream::ZCursor;
use zune_core::colorspace::ColorSpace;
use zune_core::options::DecoderOptions;
use zune_jpeg::errors::DecodeErrors;

use super::grey::grey_row;
use super::load::{check_dimensions, check_memory, decode_error, try_buffer, Sink, SLACK};
use super::{LoadOptions, Loaded};
use crate::error::Error;

/// What the walk over the segments found.
#[derive(Debug, Default, PartialEq, Eq)]
pub(super) struct Layout {
    /// Width and height from the frame header (SOF).
    pub width: u32,
    /// Height, see `width`.
    pub height: u32,
    /// The SOF marker's low nibble: 0, 1 baseline/extended, 2 progressive, 3 lossless, ...
    pub process: u8,
    /// (horizontal, vertical) sampling factors of each component.
    pub sampling: Vec<(u8, u8)>,
    /// Number of scans (SOS segments).
    pub scans: usize,
    /// Bytes of entropy-coded data, all scans together.
    pub entropy_bytes: u64,
}

impl Layout {
    /// 8×8 blocks that the components hold at least (without the padding of interleaved
    /// scans).
    fn blocks(&self) -> u64 {
        let hmax = self.sampling.iter().map(|s| s.0).max().unwrap_or(1).max(1);
        let vmax = self.sampling.iter().map(|s| s.1).max().unwrap_or(1).max(1);
        let (w, h) = (u64::from(self.width), u64::from(self.height));
        self.sampling
            .iter()
            .map(|&(hs, vs)| {
                let cw = (w * u64::from(hs)).div_ceil(u64::from(hmax));
                let ch = (h * u64::from(vs)).div_ceil(u64::from(vmax));
                cw.div_ceil(8) * ch.div_ceil(8)
            })
            .sum()
    }

    /// `Err` (a message for [`Error::Truncated`]) if the entropy-coded data is shorter than the
    /// fewest bits the announced blocks need: 2 per block in sequential Huffman coding (a DC
    /// difference code and an end-of-block code, each at least one bit), 1 in progressive
    /// coding (the first DC scan). Cheap, and catches a forged size before it is allocated.
    pub(super) fn plausible(&self) -> Result<(), String> {
        // Huffman-coded processes only: 0, 1 sequential, 2 progressive (arithmetic coding and
        // lossless are refused by the decoder anyway).
        let min_bits = match self.process {
            0 | 1 => 2,
            2 => 1,
            _ => 0,
        };
        let blocks = self.blocks();
        if self.entropy_bytes.saturating_mul(8) < blocks.saturating_mul(min_bits) {
            return Err(format!(
                "JPEG: the header announces {}x{} pixels ({blocks} blocks of 8x8) but the \
                 file holds only {} bytes of image data",
                self.width, self.height, self.entropy_bytes
            ));
        }
        Ok(())
    }

    /// Bytes of coefficients kept for the whole image when it is decoded scan by scan
    /// (progressive, or baseline with one component per scan): 64 `i16` per padded block.
    fn coefficient_bytes(&self) -> u64 {
        if self.process == 2 || self.scans > 1 {
            // Padding of interleaved MCUs: at most one more row and column of MCUs (32 px).
            let padded = Layout {
                width: self.width.saturating_add(32),
                height: self.height.saturating_add(32),
                sampling: self.sampling.clone(),
                ..Layout::default()
            };
            padded.blocks() * 128
        } else {
            0
        }
    }
}

/// Walks the segments of a JPEG file up to its end-of-image marker; `Err` (a message for
/// [`Error::Truncated`]) if the data ends first. Anything else unusual is left to the decoder
/// to judge.
pub(super) fn walk(bytes: &[u8]) -> Result<Layout, String> {
    let ends = |what: &str| Err(format!("JPEG: the file ends {what}"));
    let mut layout = Layout::default();
    let n = bytes.len();
    if bytes.get(..2) != Some(&[0xFF, 0xD8][..]) {
        return Ok(layout);
    }
    let mut i = 2;
    loop {
        if i >= n {
            return ends("before its end-of-image marker");
        }
        if bytes[i] != 0xFF {
            // Not a marker where one should be: the decoder reports it.
            return Ok(layout);
        }
        while i < n && bytes[i] == 0xFF {
            i += 1;
        }
        if i >= n {
            return ends("before its end-of-image marker");
        }
        let m = bytes[i];
        i += 1;
        match m {
            0xD9 => return Ok(layout),
            0xD0..=0xD7 | 0x01 => continue,
            _ => {}
        }
        if i + 2 > n {
            return ends("inside a segment header");
        }
        let len = usize::from(u16::from_be_bytes([bytes[i], bytes[i + 1]]));
        if len < 2 {
            return Ok(layout);
        }
        if i + len > n {
            return ends("inside a segment");
        }
        let seg = &bytes[i + 2..i + len];
        let sof = matches!(m, 0xC0..=0xCF) && !matches!(m, 0xC4 | 0xC8 | 0xCC);
        if sof && layout.sampling.is_empty() && seg.len() >= 6 {
            layout.process = m & 0x0F;
            layout.height = u32::from(u16::from_be_bytes([seg[1], seg[2]]));
            layout.width = u32::from(u16::from_be_bytes([seg[3], seg[4]]));
            let count = usize::from(seg[5]);
            for c in seg[6..].chunks_exact(3).take(count) {
                layout.sampling.push((c[1] >> 4, c[1] & 0x0F));
            }
        }
        i += len;
        if m == 0xDA {
            layout.scans += 1;
            // Entropy-coded data up to the next marker other than RSTn (FF 00 is a stuffed FF).
            loop {
                if i + 1 >= n {
                    return ends("inside the image data, before its end-of-image marker");
                }
                if bytes[i] != 0xFF {
                    i += 1;
                    layout.entropy_bytes += 1;
                } else if bytes[i + 1] == 0x00 || (0xD0..=0xD7).contains(&bytes[i + 1]) {
                    i += 2;
                    layout.entropy_bytes += 2;
                } else {
                    break;
                }
            }
        }
    }
}

/// Decodes the JPEG in `bytes` (held in memory, counted in the estimate) into a mask. Same
/// pixels as `image`'s JPEG decoder (zune-jpeg, RGB output for colour images) except that
/// decoding is strict: a premature end of data is an error, not grey padding.
pub(super) fn load_jpeg(bytes: &[u8], path: &Path, opts: &LoadOptions) -> Result<Loaded, Error> {
    let truncated = |detail: String| Error::Truncated {
        path: path.to_path_buf(),
        detail,
    };
    let layout = walk(bytes).map_err(truncated)?;
    if !layout.sampling.is_empty() {
        // Checked before the decoder reads the headers and sets anything up.
        check_dimensions(path, layout.width, layout.height, opts.max_pixels)?;
        layout.plausible().map_err(truncated)?;
    }
    let options = DecoderOptions::default()
        .set_strict_mode(true)
        .set_max_width(usize::MAX)
        .set_max_height(usize::MAX);
    let mut decoder = zune_jpeg::JpegDecoder::new_with_options(ZCursor::new(bytes), options);
    decoder.decode_headers().map_err(|e| jpeg_error(e, path))?;
    let (w, h) = decoder.dimensions().unwrap_or((0, 0));
    let (width, height) = (
        u32::try_from(w).unwrap_or(u32::MAX),
        u32::try_from(h).unwrap_or(u32::MAX),
    );
    check_dimensions(path, width, height, opts.max_pixels)?;
    let (out_space, color) = match decoder.input_colorspace() {
        Some(ColorSpace::Luma) => (ColorSpace::Luma, ColorType::L8),
        Some(ColorSpace::LumaA) => (ColorSpace::LumaA, ColorType::La8),
        Some(ColorSpace::RGBA) => (ColorSpace::RGBA, ColorType::Rgba8),
        _ => (ColorSpace::RGB, ColorType::Rgb8),
    };
    decoder.set_options(decoder.options().jpeg_set_out_colorspace(out_space));
    let size = decoder.output_buffer_size().unwrap_or(usize::MAX) as u64;
    let line = u64::from(width) * u64::from(color.bytes_per_pixel());
    // Our buffer, the coefficients of a multi-scan image, zune's per-MCU-row buffers (16
    // rows of every component, with upsampling scratch), our row conversions.
    let decoder_bytes = size + layout.coefficient_bytes() + 64 * line;
    let needed = bytes.len() as u64 + decoder_bytes + Sink::bytes(width, height, opts) + SLACK;
    check_memory(path, needed, opts)?;
    let mut buf = try_buffer(size, path)?;
    decoder
        .decode_into(&mut buf)
        .map_err(|e| jpeg_error(e, path))?;
    let mut sink = Sink::new(width, height, opts, path)?;
    let line = line as usize;
    for (y, row) in buf.chunks_exact(line.max(1)).take(h).enumerate() {
        let grey = grey_row(color, false, width, row, opts.compat)
            .ok_or_else(|| decode_error(path, ImageFormat::Jpeg, "bad row"))?;
        sink.put(y as u32, 0, 1, &grey);
    }
    Ok(sink.finish())
}

/// zune-jpeg's error as ours: running out of data is [`Error::Truncated`].
fn jpeg_error(e: DecodeErrors, path: &Path) -> Error {
    let text = e.to_string();
    let truncated = matches!(e, DecodeErrors::ExhaustedData)
        || text.contains("Premature end")
        || text.contains("No more bytes");
    if truncated {
        Error::Truncated {
            path: path.to_path_buf(),
            detail: format!("JPEG: {}", text.trim_matches('"')),
        }
    } else {
        decode_error(path, ImageFormat::Jpeg, text.trim_matches('"').to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn jpeg(w: u32, h: u32) -> Vec<u8> {
        let img = image::RgbImage::from_fn(w, h, |x, y| {
            let v = if (x / 7 + y / 5) % 3 == 0 { 20 } else { 230 };
            image::Rgb([v, v / 2, 255 - v])
        });
        let mut out = Vec::new();
        let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 85);
        img.write_with_encoder(enc).unwrap();
        out
    }

    #[test]
    fn walk_reads_the_layout() {
        let bytes = jpeg(100, 60);
        let l = walk(&bytes).unwrap();
        assert_eq!((l.width, l.height, l.process, l.scans), (100, 60, 0, 1));
        assert_eq!(l.sampling.len(), 3);
        assert!(l.entropy_bytes > 0 && (l.entropy_bytes as usize) < bytes.len());
        assert!(l.plausible().is_ok());
        // 100 x 60 in 4:2:0 or 4:4:4: at least 13 x 8 luma blocks.
        assert!(l.blocks() >= 13 * 8, "{}", l.blocks());
        let forged = Layout {
            width: 65500,
            height: 6000,
            ..l
        };
        assert!(forged.plausible().unwrap_err().contains("65500x6000"));
        // Every cut before the end-of-image marker is truncated.
        for cut in [3, 20, bytes.len() / 3, bytes.len() - 2, bytes.len() - 1] {
            assert!(walk(&bytes[..cut]).is_err(), "cut at {cut} accepted");
        }
    }
}
