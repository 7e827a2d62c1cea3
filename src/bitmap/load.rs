//! Reading and decoding image files, with the size limits checked before decoding.

use std::fs::File;
use std::io::{BufRead, BufReader, Cursor, Seek};
use std::path::{Path, PathBuf};

use image::{DynamicImage, ImageDecoder, ImageReader, Limits};

use super::grey::{default_grey, ipol_grey, Compat};
use super::mask::Mask;
use super::otsu::{histogram, otsu, Threshold};
use crate::error::Error;

/// Options of [`load_path`], [`load_memory`] and [`threshold_image`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadOptions {
    /// How the grey level threshold is chosen.
    pub threshold: Threshold,
    /// Swap foreground and background after thresholding (for light ink on dark paper).
    pub invert: bool,
    /// Which convention turns the pixels into grey levels.
    pub compat: Compat,
    /// Images with more pixels than this are refused before decoding their pixels.
    pub max_pixels: u64,
}

impl Default for LoadOptions {
    fn default() -> LoadOptions {
        LoadOptions {
            threshold: Threshold::Fixed(128),
            invert: false,
            compat: Compat::Default,
            max_pixels: 400_000_000,
        }
    }
}

/// The result of thresholding an image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loaded {
    /// The binary image.
    pub mask: Mask,
    /// The threshold actually used: before `invert`, foreground = grey < `threshold`.
    pub threshold: u8,
}

/// Reads, decodes and thresholds the image file at `path`.
///
/// The format is guessed from the content. Errors (unreadable file, unknown or corrupt
/// data, zero size, more than `opts.max_pixels` pixels) are returned, never panicked.
pub fn load_path(path: &Path, opts: &LoadOptions) -> Result<Loaded, Error> {
    let file = File::open(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let img = decode(BufReader::new(file), path, opts.max_pixels)?;
    Ok(threshold_image(&img, opts))
}

/// Decodes and thresholds an encoded image held in memory (errors name the file `<memory>`).
pub fn load_memory(bytes: &[u8], opts: &LoadOptions) -> Result<Loaded, Error> {
    let img = decode(Cursor::new(bytes), Path::new("<memory>"), opts.max_pixels)?;
    Ok(threshold_image(&img, opts))
}

fn decode<R: BufRead + Seek>(
    reader: R,
    path: &Path,
    max_pixels: u64,
) -> Result<DynamicImage, Error> {
    let decode_err = |source: image::ImageError| Error::Decode {
        path: PathBuf::from(path),
        source,
    };
    let reader = ImageReader::new(reader)
        .with_guessed_format()
        .map_err(|source| Error::Read {
            path: PathBuf::from(path),
            source,
        })?;
    let mut decoder = reader.into_decoder().map_err(decode_err)?;
    let (width, height) = decoder.dimensions();
    if width == 0 || height == 0 {
        return Err(Error::Empty {
            path: PathBuf::from(path),
            width,
            height,
        });
    }
    if u64::from(width) * u64::from(height) > max_pixels {
        return Err(Error::TooLarge {
            path: PathBuf::from(path),
            width,
            height,
            max_pixels,
        });
    }
    let mut limits = Limits::default();
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    // The output buffer plus room for the decoder's own buffers.
    limits.max_alloc = Some(
        decoder
            .total_bytes()
            .saturating_mul(2)
            .saturating_add(64 << 20),
    );
    decoder.set_limits(limits).map_err(decode_err)?;
    DynamicImage::from_decoder(decoder).map_err(decode_err)
}

/// Thresholds a decoded image into a [`Loaded`] mask according to `opts`
/// (`opts.max_pixels` is not checked here).
pub fn threshold_image(img: &DynamicImage, opts: &LoadOptions) -> Loaded {
    let (width, height) = (img.width(), img.height());
    let grey = match opts.compat {
        Compat::Default => default_grey(img),
        Compat::Ipol => ipol_grey(img),
    };
    let threshold = match opts.threshold {
        Threshold::Fixed(t) => t,
        // otsu() returns at most 254.
        Threshold::Otsu => otsu(&histogram(&grey)).saturating_add(1),
    };
    let mut mask = Mask::new(width, height);
    let w = width as usize;
    for (i, &g) in grey.iter().enumerate() {
        if (g < threshold) != opts.invert {
            mask.set((i % w.max(1)) as i64, (i / w.max(1)) as i64, true);
        }
    }
    Loaded { mask, threshold }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageBuffer, Luma};

    fn fixed(t: u8) -> LoadOptions {
        LoadOptions {
            threshold: Threshold::Fixed(t),
            ..LoadOptions::default()
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
        assert!(matches!(e, Error::Decode { .. }), "{e}");
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
        let crc = crc32(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        // An empty IDAT chunk, so that the header can be read completely.
        bytes.extend_from_slice(&0u32.to_be_bytes());
        bytes.extend_from_slice(b"IDAT");
        bytes.extend_from_slice(&crc32(b"IDAT").to_be_bytes());
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

    fn crc32(data: &[u8]) -> u32 {
        let mut crc = 0xffff_ffffu32;
        for &b in data {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 != 0 {
                    (crc >> 1) ^ 0xedb8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
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
