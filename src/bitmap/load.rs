//! Reading and decoding image files, with the size and memory limits checked before the
//! pixels are decoded.
//!
//! PNG is decoded row by row into the mask ([`super::png`]), JPEG by zune-jpeg in strict mode
//! ([`super::jpeg`]); other formats by `image` into one buffer, turned into grey row by row.

use std::io::{BufRead, BufReader, Cursor, Read, Seek};
use std::path::Path;

use image::error::ImageFormatHint;
use image::{DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits};

use super::adaptive;
use super::clean::Cleaned;
use super::grey::{default_grey, grey_row, ipol_grey, Compat};
use super::input::{default_max_memory, display_name, open, Input};
use super::jpeg::load_jpeg;
use super::mask::Mask;
use super::otsu::{histogram, otsu, Threshold};
use super::png::load_png;
use crate::error::Error;

/// Allowance in the memory estimates for what is not counted (decoder state, small buffers).
pub(super) const SLACK: u64 = 16 << 20;

/// Options of [`load_path`], [`load_memory`] and [`threshold_image`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadOptions {
    /// How the grey level threshold is chosen.
    pub threshold: Threshold,
    /// Swap foreground and background after thresholding (for light ink on dark paper); the
    /// adaptive threshold is applied to the inverted grey levels instead.
    pub invert: bool,
    /// Which convention turns the pixels into grey levels.
    pub compat: Compat,
    /// Images with more pixels than this are refused before decoding their pixels.
    pub max_pixels: u64,
    /// Bytes that reading, decoding and thresholding may use. An image whose estimated need
    /// is larger is refused ([`Error::NeedsMemory`]) before its pixels are decoded; it also
    /// bounds how much of a pipe is read. Default [`default_max_memory`].
    pub max_memory: u64,
    /// Drop foreground components and holes whose border encloses at most this many pixels
    /// right after thresholding ([`Mask::clean`], potrace's `turdsize`). Default 0: the mask
    /// is the thresholded image, exactly.
    pub turdsize: u64,
}

impl Default for LoadOptions {
    fn default() -> LoadOptions {
        LoadOptions {
            threshold: Threshold::Fixed(128),
            invert: false,
            compat: Compat::Default,
            max_pixels: 400_000_000,
            max_memory: default_max_memory(),
            turdsize: 0,
        }
    }
}

/// The result of thresholding an image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loaded {
    /// The binary image.
    pub mask: Mask,
    /// The threshold actually used: before `invert`, foreground = grey < `threshold`. For
    /// [`Threshold::Adaptive`], which has a threshold per pixel, their mean (rounded), for
    /// information only.
    pub threshold: u8,
    /// What cleaning ([`LoadOptions::turdsize`]) dropped; all zero without it.
    pub cleaned: Cleaned,
}

/// Reads, decodes and thresholds the image file at `path`; `-` reads standard input.
///
/// The format is guessed from the content. Standard input, pipes, FIFOs and other
/// non-seekable files are first read into memory (at most
/// `min(max_memory / 2, 8 max_pixels + 64 MiB)` bytes); a FIFO with no writer is
/// [`Error::NoData`] at once. Errors (unreadable file, unknown, corrupt or truncated data,
/// zero size, more than `opts.max_pixels` pixels, more memory than `opts.max_memory`) are
/// returned, never panicked, and name standard input `<stdin>`.
///
/// ```
/// use layertrace::{load_path, LoadOptions};
/// use std::path::Path;
/// let loaded = load_path(Path::new("samples/glyph_g_liberationserif_cap120.png"), &LoadOptions::default())?;
/// assert!(loaded.mask.count_foreground() > 0);
/// // A missing file is a clear error naming it.
/// let e = load_path(Path::new("no/such.png"), &LoadOptions::default()).unwrap_err();
/// assert!(e.to_string().contains("no/such.png"));
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn load_path(path: &Path, opts: &LoadOptions) -> Result<Loaded, Error> {
    let name = display_name(path);
    match open(path, &name, opts.max_pixels, opts.max_memory)? {
        Input::File(file) => load_reader(BufReader::with_capacity(1 << 16, file), &name, opts, 0),
        Input::Bytes(bytes) => load_bytes(&bytes, &name, opts),
    }
}

/// Decodes and thresholds an encoded image held in memory (errors name the file `<memory>`).
///
/// ```
/// use layertrace::{load_memory, LoadOptions, Threshold};
/// let bytes = std::fs::read("samples/glyph_g_liberationserif_cap120.png").unwrap();
/// let opts = LoadOptions { threshold: Threshold::Otsu, ..LoadOptions::default() };
/// let loaded = load_memory(&bytes, &opts)?;
/// assert!(loaded.mask.width() > 0 && loaded.threshold > 0);
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn load_memory(bytes: &[u8], opts: &LoadOptions) -> Result<Loaded, Error> {
    load_bytes(bytes, Path::new("<memory>"), opts)
}

fn load_bytes(bytes: &[u8], path: &Path, opts: &LoadOptions) -> Result<Loaded, Error> {
    if bytes.is_empty() {
        return Err(Error::NoData {
            path: path.to_path_buf(),
        });
    }
    if image::guess_format(bytes).ok() == Some(ImageFormat::Jpeg) {
        return load_jpeg(bytes, path, opts);
    }
    load_reader(Cursor::new(bytes), path, opts, bytes.len() as u64)
}

/// Dispatches on the format guessed from the first bytes; `held` bytes of input are in memory.
fn load_reader<R: BufRead + Seek>(
    mut reader: R,
    path: &Path,
    opts: &LoadOptions,
    held: u64,
) -> Result<Loaded, Error> {
    let read_err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let format = {
        let head = reader.fill_buf().map_err(read_err)?;
        image::guess_format(head).ok()
    };
    match format {
        Some(ImageFormat::Png) => load_png(reader, path, opts, held),
        Some(ImageFormat::Jpeg) => {
            // zune-jpeg decodes from memory: read the whole file, within the budget.
            let cap = opts.max_memory.saturating_sub(held);
            let mut bytes = Vec::new();
            reader
                .take(cap.saturating_add(1))
                .read_to_end(&mut bytes)
                .map_err(read_err)?;
            check_memory(path, held + bytes.len() as u64, opts)?;
            load_jpeg(&bytes, path, opts)
        }
        _ => load_other(reader, path, opts, held),
    }
}

/// Every other format, through `image`: its output buffer is allocated here, fallibly, and
/// turned into grey row by row.
fn load_other<R: BufRead + Seek>(
    reader: R,
    path: &Path,
    opts: &LoadOptions,
    held: u64,
) -> Result<Loaded, Error> {
    let decode_err = |source: image::ImageError| Error::Decode {
        path: path.to_path_buf(),
        source,
    };
    let mut reader = ImageReader::new(reader)
        .with_guessed_format()
        .map_err(|source| Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
    let format = reader
        .format()
        .map_or(ImageFormatHint::Unknown, ImageFormatHint::from);
    let mut limits = Limits::default();
    limits.max_alloc = Some(opts.max_memory);
    reader.limits(limits.clone());
    let mut decoder = reader.into_decoder().map_err(decode_err)?;
    let (width, height) = decoder.dimensions();
    check_dimensions(path, width, height, opts.max_pixels)?;
    let total = decoder.total_bytes();
    // The output buffer, as much again for the decoder's own (strips, frames, planes), the
    // mask and a few rows.
    let sink = Sink::bytes(width, height, opts);
    let rows = 32 * u64::from(width) * 4;
    check_memory(path, held + 2 * total + sink + rows + SLACK, opts)?;
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    limits.max_alloc = Some(opts.max_memory.saturating_sub(held + total + sink));
    decoder.set_limits(limits).map_err(decode_err)?;
    let color = decoder.color_type();
    let mut buf = try_buffer(total, path)?;
    decoder.read_image(&mut buf).map_err(decode_err)?;
    let mut sink = Sink::new(width, height, opts, path)?;
    let line = usize::try_from(total / u64::from(height)).unwrap_or(usize::MAX);
    for (y, row) in buf.chunks_exact(line.max(1)).enumerate() {
        let grey = grey_row(color, false, width, row, opts.compat).ok_or_else(|| {
            decode_error(
                path,
                format.clone(),
                format!("unsupported pixel type {color:?}"),
            )
        })?;
        sink.put(y as u32, 0, 1, &grey);
    }
    Ok(sink.finish())
}

/// Refuses empty images and images of more than `max_pixels` pixels.
pub(super) fn check_dimensions(
    path: &Path,
    width: u32,
    height: u32,
    max_pixels: u64,
) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::Empty {
            path: path.to_path_buf(),
            width,
            height,
        });
    }
    if u64::from(width) * u64::from(height) > max_pixels {
        return Err(Error::TooLarge {
            path: path.to_path_buf(),
            width,
            height,
            max_pixels,
        });
    }
    Ok(())
}

/// Refuses to go on if `needed` bytes are more than `opts.max_memory`.
pub(super) fn check_memory(path: &Path, needed: u64, opts: &LoadOptions) -> Result<(), Error> {
    if needed > opts.max_memory {
        return Err(Error::NeedsMemory {
            path: path.to_path_buf(),
            needed,
            limit: opts.max_memory,
        });
    }
    Ok(())
}

/// A zeroed buffer of `len` bytes, or [`Error::OutOfMemory`] instead of an abort.
pub(super) fn try_buffer(len: u64, path: &Path) -> Result<Vec<u8>, Error> {
    let oom = || Error::OutOfMemory {
        path: path.to_path_buf(),
        bytes: len,
    };
    let n = usize::try_from(len).map_err(|_| oom())?;
    let mut buf = Vec::new();
    buf.try_reserve_exact(n).map_err(|_| oom())?;
    buf.resize(n, 0);
    Ok(buf)
}

/// A decoding error of `format` with the decoder's (or our) reason.
pub(super) fn decode_error(
    path: &Path,
    format: impl Into<ImageFormatHint>,
    err: impl Into<Box<dyn std::error::Error + Send + Sync>>,
) -> Error {
    Error::Decode {
        path: path.to_path_buf(),
        source: image::ImageError::Decoding(image::error::DecodingError::new(format.into(), err)),
    }
}

/// Receives grey levels row by row (or Adam7 pass line by line) and makes the mask: directly
/// for a fixed threshold, through a grey byte per pixel for Otsu's and the adaptive one.
pub(super) struct Sink {
    width: u32,
    mask: Mask,
    /// Every pixel's grey level, kept for Otsu's and the adaptive threshold only.
    grey: Option<Vec<u8>>,
    threshold: u8,
    opts: LoadOptions,
}

impl Sink {
    /// Bytes a sink of `width` × `height` pixels allocates at its peak: the mask, and either
    /// the grey levels with what thresholding them needs, or what cleaning needs (the grey
    /// levels are freed first).
    pub(super) fn bytes(width: u32, height: u32, opts: &LoadOptions) -> u64 {
        let pixels = u64::from(width) * u64::from(height);
        let grey = match opts.threshold {
            Threshold::Fixed(_) => 0,
            Threshold::Otsu => pixels,
            Threshold::Adaptive { .. } => pixels + adaptive::bytes(width),
        };
        let clean = if opts.turdsize > 0 {
            Mask::clean_bytes(width, height)
        } else {
            0
        };
        Mask::bytes_for(width, height) + grey.max(clean)
    }

    /// An empty sink; allocation failures are [`Error::OutOfMemory`].
    pub(super) fn new(
        width: u32,
        height: u32,
        opts: &LoadOptions,
        path: &Path,
    ) -> Result<Sink, Error> {
        let mask = Mask::try_new(width, height).ok_or(Error::OutOfMemory {
            path: path.to_path_buf(),
            bytes: Mask::bytes_for(width, height),
        })?;
        let (grey, threshold) = match opts.threshold {
            Threshold::Fixed(t) => (None, t),
            Threshold::Otsu | Threshold::Adaptive { .. } => {
                let n = u64::from(width) * u64::from(height);
                (Some(try_buffer(n, path)?), 0)
            }
        };
        Ok(Sink {
            width,
            mask,
            grey,
            threshold,
            opts: *opts,
        })
    }

    /// The grey levels of pixels `(x0 + k step, y)`, `k = 0, 1, ...`.
    pub(super) fn put(&mut self, y: u32, x0: u32, step: u32, grey: &[u8]) {
        let base = y as usize * self.width as usize + x0 as usize;
        let step = step as usize;
        match &mut self.grey {
            Some(all) => {
                for (k, &g) in grey.iter().enumerate() {
                    if let Some(p) = all.get_mut(base + k * step) {
                        *p = g;
                    }
                }
            }
            None => {
                let (t, invert) = (self.threshold, self.opts.invert);
                // A row of consecutive pixels: its whole words of 64 first, compared at
                // once ([`below`]); the rest pixel by pixel.
                let mut done = 0;
                if step == 1 {
                    let (words, rest) = grey.as_chunks::<64>();
                    done = grey.len() - rest.len();
                    let flip = if invert { u64::MAX } else { 0 };
                    for (c, chunk) in words.iter().enumerate() {
                        self.mask.set_word_at(base + 64 * c, below(chunk, t) ^ flip);
                    }
                }
                for (k, &g) in grey[done..].iter().enumerate() {
                    if (g < t) != invert {
                        self.mask.set_index(base + (done + k) * step);
                    }
                }
            }
        }
    }

    /// The mask, cleaned, and the threshold used (Otsu's and the adaptive one are decided
    /// here, on every pixel).
    pub(super) fn finish(mut self) -> Loaded {
        if let Some(grey) = self.grey.take() {
            self.threshold = threshold_grey(&grey, &self.opts, &mut self.mask);
        }
        let cleaned = self.mask.clean(self.opts.turdsize);
        Loaded {
            mask: self.mask,
            threshold: self.threshold,
            cleaned,
        }
    }
}

/// Bit `i` set when `grey[i]` is below `t`: 64 pixels compared at once. The compares are
/// written as a loop of bytes the compiler vectorizes (16 at a time with SSE2, the x86-64
/// baseline: a max, an equality and a mask per 16 pixels), each giving `0x80` or 0; the
/// high bits of each eight bytes are then gathered into one byte by one multiplication
/// (the products of distinct bits land on distinct bits: no carries). The former eight at
/// once in a `u64` (a borrow-free subtraction per byte) took 2.1 instructions a pixel of
/// the 3000² sample; this about 1.1.
fn below(grey: &[u8; 64], t: u8) -> u64 {
    let mut high = [0u8; 64];
    for (h, &g) in high.iter_mut().zip(grey) {
        *h = if g < t { 0x80 } else { 0 };
    }
    let mut word = 0u64;
    for (k, eight) in high.as_chunks::<8>().0.iter().enumerate() {
        let b = u64::from_le_bytes(*eight).wrapping_mul(0x0002_0408_1020_4081) >> 56;
        word |= b << (8 * k);
    }
    word
}

/// Sets the foreground pixels of `grey` (every pixel of `mask`, row-major) in `mask`, all
/// background before; returns the threshold used ([`Loaded::threshold`]).
fn threshold_grey(grey: &[u8], opts: &LoadOptions, mask: &mut Mask) -> u8 {
    let threshold = match opts.threshold {
        Threshold::Fixed(t) => t,
        // otsu() returns at most 254.
        Threshold::Otsu => otsu(&histogram(grey)).saturating_add(1),
        Threshold::Adaptive { radius, k_percent } => {
            let (w, h) = (mask.width(), mask.height());
            return adaptive::sauvola(grey, w, h, radius, k_percent, opts.invert, mask);
        }
    };
    for (i, &g) in grey.iter().enumerate() {
        if (g < threshold) != opts.invert {
            mask.set_index(i);
        }
    }
    threshold
}

/// Thresholds a decoded image into a [`Loaded`] mask according to `opts`, and cleans it
/// (`opts.max_pixels` and `opts.max_memory` are not checked here).
///
/// ```
/// use layertrace::{threshold_image, LoadOptions, Threshold};
/// let grey = image::GrayImage::from_fn(4, 1, |x, _| image::Luma([(x * 80) as u8]));
/// let opts = LoadOptions { threshold: Threshold::Fixed(100), ..LoadOptions::default() };
/// let loaded = threshold_image(&image::DynamicImage::ImageLuma8(grey), &opts);
/// // Foreground is darker than the threshold: luma 0 and 80.
/// assert!(loaded.mask.get(0, 0) && loaded.mask.get(1, 0) && !loaded.mask.get(2, 0));
/// ```
pub fn threshold_image(img: &DynamicImage, opts: &LoadOptions) -> Loaded {
    let (width, height) = (img.width(), img.height());
    let grey = match opts.compat {
        Compat::Default => default_grey(img),
        Compat::Ipol => ipol_grey(img),
    };
    let mut mask = Mask::new(width, height);
    let threshold = threshold_grey(&grey, opts, &mut mask);
    let cleaned = mask.clean(opts.turdsize);
    Loaded {
        mask,
        threshold,
        cleaned,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::tests::fixed;
    use image::{ImageBuffer, Luma};
    use proptest::prelude::*;

    /// Every grey level against every threshold, in every byte of the word.
    #[test]
    fn sixty_four_compares_at_once_are_the_compares() {
        for t in 0..=255u8 {
            for g in 0..=255u8 {
                for at in [0, 1, 7, 8, 15, 16, 31, 56, 63] {
                    // The other bytes just below and just above `g`.
                    for other in [g.wrapping_sub(1), g.wrapping_add(1), 0, 255] {
                        let mut bytes = [other; 64];
                        bytes[at] = g;
                        bytes[(at + 9) % 64] = t;
                        let want = bytes
                            .iter()
                            .enumerate()
                            .fold(0u64, |b, (i, &v)| b | (u64::from(v < t) << i));
                        assert_eq!(below(&bytes, t), want, "{g} < {t} at {at}");
                    }
                }
            }
        }
    }

    proptest! {
        /// Rows put whole (64 pixels to a word) make the mask that pixels put one at a time
        /// make, at any width, threshold and inversion.
        #[test]
        fn rows_put_whole_mask_as_pixels_do(
            w in 1u32..200,
            h in 1u32..4,
            t in any::<u8>(),
            invert in any::<bool>(),
            seed in any::<u64>(),
        ) {
            let opts = LoadOptions { invert, ..fixed(t) };
            let path = Path::new("rows.png");
            let (mut rows, mut pixels) = (
                Sink::new(w, h, &opts, path).expect("a sink"),
                Sink::new(w, h, &opts, path).expect("a sink"),
            );
            let mut s = seed | 1;
            for y in 0..h {
                let grey: Vec<u8> = (0..w)
                    .map(|_| {
                        s ^= s << 13;
                        s ^= s >> 7;
                        s ^= s << 17;
                        (s >> 24) as u8
                    })
                    .collect();
                rows.put(y, 0, 1, &grey);
                for (x, g) in (0u32..).zip(&grey) {
                    pixels.put(y, x, 1, std::slice::from_ref(g));
                }
            }
            prop_assert_eq!(&rows.mask, &pixels.mask);
        }
    }

    fn png_bytes(img: &DynamicImage) -> Vec<u8> {
        let mut out = Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    }

    fn assert_one_line(e: &Error) {
        let msg = e.to_string();
        assert!(
            !msg.is_empty() && !msg.contains('\n'),
            "not one line: {msg:?}"
        );
    }

    #[test]
    fn load_memory_roundtrip_and_errors() {
        let img = DynamicImage::ImageLuma8(ImageBuffer::from_fn(10, 10, |x, _| {
            Luma([if x < 4 { 0 } else { 255 }])
        }));
        let bytes = png_bytes(&img);
        let l = load_memory(&bytes, &LoadOptions::default()).unwrap();
        assert_eq!(l.mask.count_foreground(), 40);
        assert_eq!(l.threshold, 128);

        // Truncated data.
        let e = load_memory(&bytes[..bytes.len() / 2], &LoadOptions::default()).unwrap_err();
        assert!(matches!(e, Error::Truncated { .. }), "{e}");
        assert!(e.to_string().contains("truncated"), "{e}");
        assert_one_line(&e);
        // Not an image.
        let e = load_memory(
            b"hello, world, this is not an image",
            &LoadOptions::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Decode { .. }), "{e}");
        assert_one_line(&e);
        let e = load_memory(&[], &LoadOptions::default()).unwrap_err();
        assert_one_line(&e);
        // Over the limit.
        let opts = LoadOptions {
            max_pixels: 99,
            ..LoadOptions::default()
        };
        let e = load_memory(&bytes, &opts).unwrap_err();
        assert!(matches!(
            e,
            Error::TooLarge {
                width: 10,
                height: 10,
                max_pixels: 99,
                ..
            }
        ));
        assert!(e.to_string().contains("--max-pixels"), "{e}");
        assert_one_line(&e);
        // Zero size (a PNM header can say so).
        for zero in [&b"P5\n0 5\n255\n"[..], &b"P5\n3 0\n255\n"[..]] {
            let e = load_memory(zero, &LoadOptions::default()).unwrap_err();
            assert!(matches!(e, Error::Empty { .. }), "{e}");
            assert_one_line(&e);
        }
        // Missing file.
        let e = load_path(
            Path::new("samples/does-not-exist.png"),
            &LoadOptions::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Read { .. }), "{e}");
        assert_one_line(&e);
    }

    #[test]
    fn dimensions_checked_before_pixels() {
        // A PNG whose header claims 100000 x 100000 pixels but holds no pixel data: the
        // limit must trigger (a decode attempt would fail differently, or allocate 10 GB).
        let mut bytes = png_bytes(&DynamicImage::ImageLuma8(ImageBuffer::from_pixel(
            1,
            1,
            Luma([0u8]),
        )));
        bytes.truncate(33); // signature + IHDR chunk
        bytes[16..20].copy_from_slice(&100_000u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&100_000u32.to_be_bytes());
        let crc = crc32fast::hash(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        // An empty IDAT chunk, so that the header can be read completely.
        bytes.extend_from_slice(&0u32.to_be_bytes());
        bytes.extend_from_slice(b"IDAT");
        bytes.extend_from_slice(&crc32fast::hash(b"IDAT").to_be_bytes());
        let e = load_memory(&bytes, &LoadOptions::default()).unwrap_err();
        assert!(
            matches!(
                e,
                Error::TooLarge {
                    width: 100_000,
                    height: 100_000,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn samples_are_binary_and_load() {
        // The corpus images are 0/255 grey: any threshold in 1..=255 gives the same mask.
        let p = Path::new("samples/glyph_g_liberationserif_cap120.png");
        let a = load_path(p, &fixed(1)).unwrap();
        let b = load_path(p, &fixed(255)).unwrap();
        let o = load_path(
            p,
            &LoadOptions {
                threshold: Threshold::Otsu,
                ..LoadOptions::default()
            },
        )
        .unwrap();
        assert_eq!((a.mask.width(), a.mask.height()), (110, 163));
        assert!(a.mask.count_foreground() > 0);
        assert_eq!(a.mask, b.mask);
        assert_eq!(a.mask, o.mask);
        assert_eq!(o.threshold, 1);
    }
}
