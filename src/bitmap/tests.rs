//! The streaming loaders against the whole-image path (`image` decodes everything, then
//! [`threshold_image`]): the same mask and threshold for every bundled sample and for PNGs of
//! every colour type, bit depth and interlace method, in both conventions.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use super::*;
use crate::error::Error;

/// Every combination of convention, threshold and inversion worth comparing.
fn all_options() -> Vec<LoadOptions> {
    let mut out = Vec::new();
    for compat in [Compat::Default, Compat::Ipol] {
        for threshold in [Threshold::Fixed(128), Threshold::Fixed(77), Threshold::Otsu] {
            for invert in [false, true] {
                out.push(LoadOptions {
                    threshold,
                    invert,
                    compat,
                    ..LoadOptions::default()
                });
            }
        }
    }
    // The scan options: a grey buffer, then cleaning.
    for (threshold, invert, turdsize) in [
        (Threshold::ADAPTIVE, false, 0),
        (
            Threshold::Adaptive {
                radius: 3,
                k_percent: 35,
            },
            true,
            3,
        ),
        (Threshold::Fixed(128), false, 5),
    ] {
        out.push(LoadOptions {
            threshold,
            invert,
            turdsize,
            ..LoadOptions::default()
        });
    }
    out
}

fn assert_same_as_whole_image(bytes: &[u8], what: &str) {
    let img = image::load_from_memory(bytes).unwrap_or_else(|e| panic!("{what}: {e}"));
    for opts in all_options() {
        let old = threshold_image(&img, &opts);
        let new = load_memory(bytes, &opts).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(new.threshold, old.threshold, "{what} {opts:?}");
        assert_eq!(new.cleaned, old.cleaned, "{what} {opts:?}");
        assert!(new.mask == old.mask, "{what} {opts:?}: masks differ");
    }
}

#[test]
fn bundled_samples_as_before() {
    let mut paths: Vec<PathBuf> = Vec::new();
    for dir in ["samples", "samples/ipol"] {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "png") {
                paths.push(p);
            }
        }
    }
    assert!(paths.len() >= 25, "{} samples", paths.len());
    for p in paths {
        let img = image::open(&p).unwrap();
        for opts in all_options() {
            let old = threshold_image(&img, &opts);
            let new = load_path(&p, &opts).unwrap();
            assert_eq!(new.threshold, old.threshold, "{} {opts:?}", p.display());
            assert_eq!(new.cleaned, old.cleaned, "{} {opts:?}", p.display());
            assert!(new.mask == old.mask, "{} {opts:?}", p.display());
        }
    }
}

/// A minimal PNG writer (stored deflate blocks), for every layout including Adam7, which the
/// png crate's encoder does not write.
struct Png {
    width: u32,
    height: u32,
    /// PNG colour type: 0 grey, 2 RGB, 3 palette, 4 grey + alpha, 6 RGBA.
    color: u8,
    depth: u8,
    interlaced: bool,
    /// Line `k` of each pass filtered with filter type `k % 5` (else none).
    filtered: bool,
    palette: Vec<u8>,
    trns: Vec<u8>,
}

impl Png {
    fn channels(&self) -> usize {
        match self.color {
            0 | 3 => 1,
            2 => 3,
            4 => 2,
            _ => 4,
        }
    }

    /// `samples(x, y, c)`: sample `c` of pixel `(x, y)`, below `2^depth`.
    fn encode(&self, samples: impl Fn(u32, u32, usize) -> u16) -> Vec<u8> {
        let passes: Vec<(u32, u32, u32, u32)> = if self.interlaced {
            vec![
                (0, 8, 0, 8),
                (4, 8, 0, 8),
                (0, 4, 4, 8),
                (2, 4, 0, 4),
                (0, 2, 2, 4),
                (1, 2, 0, 2),
                (0, 1, 1, 2),
            ]
        } else {
            vec![(0, 1, 0, 1)]
        };
        let mut raw = Vec::new();
        for (x0, xs, y0, ys) in passes {
            let xs_: Vec<u32> = (x0..self.width).step_by(xs as usize).collect();
            if xs_.is_empty() {
                continue;
            }
            // Bytes per pixel for the filters (at least 1).
            let bpp = (self.channels() * usize::from(self.depth)).div_ceil(8);
            let mut above: Vec<u8> = Vec::new();
            for (k, y) in (y0..self.height).step_by(ys as usize).enumerate() {
                let row_start = raw.len();
                let (mut acc, mut bits) = (0u32, 0u32);
                for &x in &xs_ {
                    for c in 0..self.channels() {
                        let v = u32::from(samples(x, y, c));
                        match self.depth {
                            16 => raw.extend_from_slice(&(v as u16).to_be_bytes()),
                            8 => raw.push(v as u8),
                            d => {
                                acc = (acc << d) | v;
                                bits += u32::from(d);
                                if bits == 8 {
                                    raw.push(acc as u8);
                                    (acc, bits) = (0, 0);
                                }
                            }
                        }
                    }
                }
                if bits > 0 {
                    raw.push((acc << (8 - bits)) as u8);
                }
                let line = raw.split_off(row_start);
                let filter = if self.filtered { (k % 5) as u8 } else { 0 };
                above.resize(line.len(), 0);
                raw.push(filter);
                raw.extend(super::unfilter::spec::filtered(filter, bpp, &above, &line));
                above = line;
            }
        }
        let mut z = vec![0x78, 0x01];
        let blocks: Vec<&[u8]> = raw.chunks(65535).collect();
        for (i, b) in blocks.iter().enumerate() {
            z.push(u8::from(i + 1 == blocks.len()));
            z.extend_from_slice(&(b.len() as u16).to_le_bytes());
            z.extend_from_slice(&(!(b.len() as u16)).to_le_bytes());
            z.extend_from_slice(b);
        }
        let (mut a, mut b) = (1u32, 0u32);
        for &x in &raw {
            a = (a + u32::from(x)) % 65521;
            b = (b + a) % 65521;
        }
        z.extend_from_slice(&((b << 16) | a).to_be_bytes());
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        let mut ihdr = Vec::new();
        ihdr.extend_from_slice(&self.width.to_be_bytes());
        ihdr.extend_from_slice(&self.height.to_be_bytes());
        ihdr.extend_from_slice(&[self.depth, self.color, 0, 0, u8::from(self.interlaced)]);
        chunk(&mut out, b"IHDR", &ihdr);
        if !self.palette.is_empty() {
            chunk(&mut out, b"PLTE", &self.palette);
        }
        if !self.trns.is_empty() {
            chunk(&mut out, b"tRNS", &self.trns);
        }
        chunk(&mut out, b"IDAT", &z);
        chunk(&mut out, b"IEND", &[]);
        out
    }
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend_from_slice(&(data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    let crc = crc32fast::hash(&out[start..]);
    out.extend_from_slice(&crc.to_be_bytes());
}

/// Pseudo-random samples, with large flat regions so that thresholds split them.
fn sample(depth: u8, seed: u64) -> impl Fn(u32, u32, usize) -> u16 {
    move |x, y, c| {
        let mut s = seed ^ (u64::from(x) << 32) ^ (u64::from(y) << 8) ^ c as u64;
        for _ in 0..3 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
        }
        let max = (1u32 << depth) - 1;
        let v = if (x / 5 + y / 3) % 3 == 0 {
            (s % u64::from(max + 1)) as u32
        } else if (x + y) % 2 == 0 {
            max
        } else {
            max / 3
        };
        v as u16
    }
}

/// Flat blocks 20 pixels wide (every filter stores long runs of zeros there, see
/// `unfilter`), every third one pseudo-random.
fn blocks(depth: u8, seed: u64) -> impl Fn(u32, u32, usize) -> u16 {
    let noise = sample(depth, seed);
    move |x, y, c| {
        let max = (1u32 << depth) - 1;
        match (x / 20 + y / 4) % 3 {
            0 => noise(x, y, c),
            1 => max as u16,
            _ => (max / 3) as u16,
        }
    }
}

#[test]
fn generated_pngs_as_before() {
    let mut cases = 0;
    for (w, h) in [(37, 29), (1, 1), (3, 2), (9, 1), (1, 9), (16, 16), (90, 13)] {
        for (interlaced, filtered) in [(false, false), (true, false), (false, true), (true, true)] {
            for (color, depths) in [
                (0u8, &[1u8, 2, 4, 8, 16][..]),
                (2, &[8, 16][..]),
                (3, &[1, 2, 4, 8][..]),
                (4, &[8, 16][..]),
                (6, &[8, 16][..]),
            ] {
                for &depth in depths {
                    for with_trns in [false, true] {
                        if with_trns && matches!(color, 4 | 6) {
                            continue;
                        }
                        let colours = 1usize << depth.min(8);
                        let mut png = Png {
                            width: w,
                            height: h,
                            color,
                            depth,
                            interlaced,
                            filtered,
                            palette: Vec::new(),
                            trns: Vec::new(),
                        };
                        if color == 3 {
                            png.palette = (0..colours * 3).map(|i| (i * 97 % 256) as u8).collect();
                        }
                        if with_trns {
                            let s = sample(depth, 7);
                            png.trns = match color {
                                0 => s(1, 1, 0).to_be_bytes().to_vec(),
                                2 => [s(1, 1, 0), s(1, 1, 1), s(1, 1, 2)]
                                    .iter()
                                    .flat_map(|v| v.to_be_bytes())
                                    .collect(),
                                _ => (0..colours).map(|i| (i * 53 % 256) as u8).collect(),
                            };
                        }
                        for flat in [false, true] {
                            let bytes = if flat {
                                png.encode(blocks(depth, 7))
                            } else {
                                png.encode(sample(depth, 7))
                            };
                            let what = format!(
                                "{w}x{h} colour {color} depth {depth} trns {with_trns} \
                             interlaced {interlaced} filtered {filtered}"
                            );
                            assert_same_as_whole_image(&bytes, &format!("{what} flat {flat}"));
                            cases += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(cases > 900, "{cases}");
}

#[test]
fn other_formats_as_before() {
    let rgba = image::RgbaImage::from_fn(41, 23, |x, y| {
        let s = sample(8, 3);
        image::Rgba([
            s(x, y, 0) as u8,
            s(x, y, 1) as u8,
            s(x, y, 2) as u8,
            s(x, y, 3) as u8,
        ])
    });
    let img = image::DynamicImage::ImageRgba8(rgba);
    let rgb16 = image::DynamicImage::ImageRgb16(img.to_rgb16());
    let rgba16 = image::DynamicImage::ImageRgba16(img.to_rgba16());
    for (img, format) in [
        (&img, image::ImageFormat::Bmp),
        (&img, image::ImageFormat::Tiff),
        (&rgba16, image::ImageFormat::Tiff),
        (&rgb16, image::ImageFormat::Pnm),
        (&img, image::ImageFormat::Gif),
        (&img, image::ImageFormat::WebP),
    ] {
        let mut out = Cursor::new(Vec::new());
        img.write_to(&mut out, format).unwrap();
        assert_same_as_whole_image(out.get_ref(), &format!("{format:?} {:?}", img.color()));
    }
    let mut jpeg = Vec::new();
    let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 80);
    img.to_rgb8().write_with_encoder(enc).unwrap();
    assert_same_as_whole_image(&jpeg, "JPEG rgb");
    let mut jpeg = Vec::new();
    let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 80);
    img.to_luma8().write_with_encoder(enc).unwrap();
    assert_same_as_whole_image(&jpeg, "JPEG grey");
}

#[test]
fn truncated_pngs_and_jpegs_say_so() {
    let png = Png {
        width: 64,
        height: 40,
        color: 6,
        depth: 8,
        interlaced: false,
        filtered: true,
        palette: Vec::new(),
        trns: Vec::new(),
    }
    .encode(sample(8, 1));
    let mut jpeg = Vec::new();
    let img = image::RgbImage::from_fn(120, 80, |x, y| {
        image::Rgb([(x * 2) as u8, (y * 3) as u8, ((x + y) % 256) as u8])
    });
    let enc = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 90);
    img.write_with_encoder(enc).unwrap();
    for bytes in [&png, &jpeg] {
        assert!(load_memory(bytes, &LoadOptions::default()).is_ok());
        for percent in [30, 60, 90, 99] {
            let cut = &bytes[..bytes.len() * percent / 100];
            let e = load_memory(cut, &LoadOptions::default()).unwrap_err();
            assert!(matches!(e, Error::Truncated { .. }), "{percent}%: {e}");
            assert!(e.to_string().contains("truncated"), "{e}");
        }
    }
}

#[test]
fn unknown_filter_types_are_decode_errors() {
    // Grey rows are unfiltered by `unfilter`, palette rows by the png crate.
    for color in [0u8, 3] {
        let mut png = Png {
            width: 8,
            height: 4,
            color,
            depth: 8,
            interlaced: false,
            filtered: false,
            palette: if color == 3 {
                (0..768).map(|i| (i % 256) as u8).collect()
            } else {
                Vec::new()
            },
            trns: Vec::new(),
        }
        .encode(sample(8, 1));
        assert!(load_memory(&png, &LoadOptions::default()).is_ok());
        // The IDAT's data is stored: the second row's filter byte follows the zlib header
        // (2 bytes), the block's header (5) and the first row (9).
        let at = png.windows(4).position(|w| w == b"IDAT").unwrap();
        let len = u32::from_be_bytes(png[at - 4..at].try_into().unwrap()) as usize;
        png[at + 4 + 2 + 5 + 9] = 9;
        let crc = crc32fast::hash(&png[at..at + 4 + len]);
        png[at + 4 + len..at + 8 + len].copy_from_slice(&crc.to_be_bytes());
        let e = load_memory(&png, &LoadOptions::default()).unwrap_err();
        assert!(matches!(e, Error::Decode { .. }), "colour {color}: {e}");
        assert!(e.to_string().contains("filter"), "colour {color}: {e}");
    }
}

#[test]
fn memory_limit_is_checked_before_decoding() {
    let p = Path::new("samples/syn_big3000_many_shapes.png"); // 3000 x 3000
    let opts = |max_memory, threshold| LoadOptions {
        max_memory,
        threshold,
        ..LoadOptions::default()
    };
    // Mask: 1.1 MB; with Otsu also 9 MB of grey levels.
    let e = load_path(p, &opts(1 << 20, Threshold::Fixed(128))).unwrap_err();
    assert!(
        matches!(e, Error::NeedsMemory { limit, .. } if limit == 1 << 20),
        "{e}"
    );
    assert!(e.to_string().contains("--max-memory"), "{e}");
    let e = load_path(p, &opts(24 << 20, Threshold::Otsu)).unwrap_err();
    assert!(matches!(e, Error::NeedsMemory { .. }), "{e}");
    assert!(load_path(p, &opts(24 << 20, Threshold::Fixed(128))).is_ok());
    assert!(load_path(p, &opts(64 << 20, Threshold::Otsu)).is_ok());
}

/// Options thresholding at a fixed grey level `t`, the rest default.
pub(super) fn fixed(t: u8) -> LoadOptions {
    LoadOptions {
        threshold: Threshold::Fixed(t),
        ..LoadOptions::default()
    }
}
