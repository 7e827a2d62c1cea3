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

use std::fs::File;
use std::io::{BufRead, BufReader, Cursor, Seek};
use std::path::{Path, PathBuf};

use image::{DynamicImage, ImageDecoder, ImageReader, Limits};
use num_bigint::BigUint;

use crate::error::Error;

/// A binary image: each pixel is foreground (`true`) or background (`false`).
///
/// Pixels are stored as one bit each, row by row.
#[derive(Clone, PartialEq, Eq)]
pub struct Mask {
    width: u32,
    height: u32,
    bits: Vec<u64>,
}

impl std::fmt::Debug for Mask {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Mask {}x{}", self.width, self.height)?;
        if u64::from(self.width) * u64::from(self.height) <= 4096 {
            write!(f, "\n{}", self.to_ascii())?;
        }
        Ok(())
    }
}

impl Mask {
    /// An all-background mask of `width` × `height` pixels (allocates `width * height` bits).
    pub fn new(width: u32, height: u32) -> Mask {
        let n = u64::from(width) * u64::from(height);
        let words = usize::try_from(n.div_ceil(64)).unwrap_or(usize::MAX);
        Mask {
            width,
            height,
            bits: vec![0; words],
        }
    }

    /// A mask whose pixel `(x, y)` is foreground iff `f(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> bool) -> Mask {
        let mut m = Mask::new(width, height);
        for y in 0..height {
            for x in 0..width {
                if f(x, y) {
                    m.set(i64::from(x), i64::from(y), true);
                }
            }
        }
        m
    }

    /// Builds a mask from ASCII art, for tests and examples.
    ///
    /// Each non-blank line is one row (leading and trailing whitespace is ignored, so indented
    /// raw strings work); `#`, `X`, `x`, `1` and `@` are foreground, any other character is
    /// background. The width is the longest row; shorter rows are padded with background.
    ///
    /// ```
    /// let m = layertrace::Mask::from_ascii("#..\n.##");
    /// assert_eq!((m.width(), m.height(), m.count_foreground()), (3, 2, 3));
    /// assert!(m.get(0, 0) && !m.get(1, 0) && m.get(2, 1));
    /// ```
    pub fn from_ascii(art: &str) -> Mask {
        let rows: Vec<Vec<char>> = art
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .map(|l| l.chars().collect())
            .collect();
        let width = rows.iter().map(Vec::len).max().unwrap_or(0);
        let width = u32::try_from(width).unwrap_or(u32::MAX);
        let height = u32::try_from(rows.len()).unwrap_or(u32::MAX);
        let mut m = Mask::new(width, height);
        for (y, row) in rows.iter().enumerate() {
            for (x, &c) in row.iter().enumerate() {
                if matches!(c, '#' | 'X' | 'x' | '1' | '@') {
                    m.set(x as i64, y as i64, true);
                }
            }
        }
        m
    }

    /// The mask as ASCII art (`#` foreground, `.` background, one line per row), the inverse
    /// of [`Mask::from_ascii`].
    pub fn to_ascii(&self) -> String {
        let mut s = String::new();
        for y in 0..i64::from(self.height) {
            for x in 0..i64::from(self.width) {
                s.push(if self.get(x, y) { '#' } else { '.' });
            }
            s.push('\n');
        }
        s
    }

    /// Width in pixels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    #[inline]
    fn index(&self, x: i64, y: i64) -> Option<usize> {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return None;
        }
        usize::try_from(y as u64 * u64::from(self.width) + x as u64).ok()
    }

    /// True iff `(x, y)` is inside the image and foreground; everything outside is background.
    #[inline]
    pub fn get(&self, x: i64, y: i64) -> bool {
        match self.index(x, y) {
            Some(i) => self
                .bits
                .get(i / 64)
                .is_some_and(|w| (w >> (i % 64)) & 1 == 1),
            None => false,
        }
    }

    /// Sets pixel `(x, y)` to foreground (`true`) or background; ignored outside the image.
    #[inline]
    pub fn set(&mut self, x: i64, y: i64, value: bool) {
        if let Some(i) = self.index(x, y) {
            if let Some(w) = self.bits.get_mut(i / 64) {
                if value {
                    *w |= 1 << (i % 64);
                } else {
                    *w &= !(1 << (i % 64));
                }
            }
        }
    }

    /// Number of foreground pixels.
    pub fn count_foreground(&self) -> u64 {
        // Bits past the last pixel are never set, so whole words can be counted.
        self.bits.iter().map(|w| u64::from(w.count_ones())).sum()
    }

    /// The 64 pixels from row-major index `i` on (bit `k` = pixel `i + k`), background past
    /// the last pixel.
    #[inline]
    pub(crate) fn bits_at(&self, i: usize) -> u64 {
        let (q, r) = (i / 64, i % 64);
        let lo = self.bits.get(q).copied().unwrap_or(0) >> r;
        if r == 0 {
            lo
        } else {
            lo | (self.bits.get(q + 1).copied().unwrap_or(0) << (64 - r))
        }
    }

    /// Sets the pixels of row-major indices `from..=to` to foreground (indices past the
    /// last pixel are ignored).
    pub(crate) fn set_range(&mut self, from: usize, to: usize) {
        let n = self.bits.len() * 64;
        let pixels = self.width as usize * self.height as usize;
        let to = to.min(pixels.saturating_sub(1)).min(n.saturating_sub(1));
        let mut i = from;
        while i <= to {
            let (q, r) = (i / 64, i % 64);
            let k = (64 - r).min(to - i + 1);
            let ones = if k == 64 {
                u64::MAX
            } else {
                ((1u64 << k) - 1) << r
            };
            self.bits[q] |= ones;
            i += k;
        }
    }
}

/// How the grey level threshold is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Threshold {
    /// Foreground iff grey < the given value (so `Fixed(0)` gives no foreground).
    Fixed(u8),
    /// Otsu's method: `t` is the first grey level in `0..=254` maximising the
    /// between-class variance of the two classes `grey <= t` and `grey > t`, and the
    /// foreground is `grey <= t` (reported as threshold `t + 1`). A one-level image gives
    /// `t = 0`.
    Otsu,
}

/// Which program's reading of the input pixels to reproduce.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Compat {
    /// layertrace's own convention: composite on white, Rec. 709 luma.
    #[default]
    Default,
    /// The reference code of the IPOL article (`gjknd_1.1`): 8-bit grey as libpng gives it,
    /// alpha stripped without compositing (a transparent black pixel is black), RGB to grey
    /// with libpng's default weights, truncated: `(6968 R + 23434 G + 2366 B) >> 15` (libpng
    /// 1.6's 8-bit path without gamma; the rounded variant `+ 16384` flips pixels of the demo
    /// image `card_suits` against the reference's output), 16-bit
    /// samples reduced to their high byte. Use it with [`Threshold::Otsu`] to match the
    /// reference binarisation (ink = grey <= Otsu's t).
    Ipol,
}

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

/// Rounded `(c * a + full * (full - a)) / full`: channel `c` with alpha `a` over white.
#[inline]
fn over_white(c: u32, a: u32, full: u32) -> u32 {
    let (c, a, full) = (u64::from(c), u64::from(a), u64::from(full));
    ((c * a + full * (full - a) + full / 2) / full) as u32
}

/// Rec. 709 luma after compositing on white, one byte per pixel, row-major.
fn default_grey(img: &DynamicImage) -> Vec<u8> {
    if !img.color().has_alpha() {
        return img.to_luma8().into_raw();
    }
    let (w, h) = (img.width(), img.height());
    let eight_bit = matches!(
        img,
        DynamicImage::ImageLumaA8(_) | DynamicImage::ImageRgba8(_)
    );
    if eight_bit {
        let mut rgba = img.to_rgba8();
        for p in rgba.pixels_mut() {
            let a = u32::from(p[3]);
            for c in 0..3 {
                p[c] = over_white(u32::from(p[c]), a, 255) as u8;
            }
            p[3] = 255;
        }
        DynamicImage::ImageRgba8(rgba).to_luma8().into_raw()
    } else {
        let rgba = img.to_rgba16();
        let mut rgb = image::ImageBuffer::<image::Rgb<u16>, Vec<u16>>::new(w, h);
        for (q, p) in rgb.pixels_mut().zip(rgba.pixels()) {
            let a = u32::from(p[3]);
            for c in 0..3 {
                q[c] = over_white(u32::from(p[c]), a, 65535) as u16;
            }
        }
        DynamicImage::ImageRgb16(rgb).to_luma8().into_raw()
    }
}

/// libpng's default `rgb_to_gray` on 8-bit samples (truncating, as its no-gamma path does).
#[inline]
fn libpng_grey(r: u8, g: u8, b: u8) -> u8 {
    ((6968 * u32::from(r) + 23434 * u32::from(g) + 2366 * u32::from(b)) >> 15) as u8
}

/// Grey levels as the IPOL reference reads them (see [`Compat::Ipol`]).
fn ipol_grey(img: &DynamicImage) -> Vec<u8> {
    match img {
        DynamicImage::ImageLuma8(b) => b.as_raw().clone(),
        DynamicImage::ImageLumaA8(b) => b.pixels().map(|p| p[0]).collect(),
        DynamicImage::ImageLuma16(b) => b.pixels().map(|p| (p[0] >> 8) as u8).collect(),
        DynamicImage::ImageLumaA16(b) => b.pixels().map(|p| (p[0] >> 8) as u8).collect(),
        DynamicImage::ImageRgb8(b) => b.pixels().map(|p| libpng_grey(p[0], p[1], p[2])).collect(),
        DynamicImage::ImageRgba8(b) => b.pixels().map(|p| libpng_grey(p[0], p[1], p[2])).collect(),
        other => other
            .to_rgba16()
            .pixels()
            .map(|p| libpng_grey((p[0] >> 8) as u8, (p[1] >> 8) as u8, (p[2] >> 8) as u8))
            .collect(),
    }
}

fn histogram(grey: &[u8]) -> [u64; 256] {
    let mut h = [0u64; 256];
    for &g in grey {
        h[g as usize] += 1;
    }
    h
}

/// Otsu's threshold: the first `t` in `0..=254` maximising the between-class variance of
/// `{grey <= t}` and `{grey > t}`; 0 when every candidate has zero variance.
///
/// The variance is compared exactly: up to a constant factor it is
/// `(N S0 - W0 S)^2 / (W0 W1)` with `N`, `S` the pixel count and grey sum, `W0`, `S0` those of
/// the dark class and `W1 = N - W0`; fractions are compared by cross-multiplication in big
/// integers (255 candidates, so the cost is negligible).
pub(crate) fn otsu(hist: &[u64; 256]) -> u8 {
    let n: BigUint = hist.iter().map(|&c| BigUint::from(c)).sum();
    let s: BigUint = hist
        .iter()
        .enumerate()
        .map(|(g, &c)| BigUint::from(g as u64) * c)
        .sum();
    let zero = BigUint::ZERO;
    let (mut w0, mut s0) = (BigUint::ZERO, BigUint::ZERO);
    let mut best_t = 0u8;
    // Best so far as (numerator, denominator); starts at variance zero.
    let mut best = (BigUint::ZERO, BigUint::from(1u8));
    for t in 0..=254u8 {
        let c = hist[usize::from(t)];
        if c == 0 && t != 0 {
            // Same classes as t - 1: same variance, never a new first maximum.
            continue;
        }
        w0 += c;
        s0 += BigUint::from(t) * c;
        if w0 == zero || w0 == n {
            continue;
        }
        let w1 = &n - &w0;
        let (a, b) = (&n * &s0, &w0 * &s);
        let d = if a > b { a - b } else { b - a };
        let num = &d * &d;
        let den = &w0 * &w1;
        if &num * &best.1 > &best.0 * &den {
            best = (num, den);
            best_t = t;
        }
    }
    best_t
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageBuffer, Luma, Rgb, Rgba};
    use proptest::prelude::*;

    proptest! {
        /// `bits_at` and `set_range` agree with pixel-by-pixel `get` and `set`.
        #[test]
        fn word_access_matches_pixels(
            w in 1u32..150,
            h in 1u32..5,
            seed in any::<u64>(),
            a in 0usize..800,
            len in 0usize..200,
        ) {
            let mut m = Mask::new(w, h);
            let mut s = seed | 1;
            for y in 0..i64::from(h) {
                for x in 0..i64::from(w) {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    m.set(x, y, s & 1 == 1);
                }
            }
            let n = (w * h) as usize;
            let pixel = |m: &Mask, i: usize| {
                i < n && m.get((i % w as usize) as i64, (i / w as usize) as i64)
            };
            let a = a % n;
            let word = m.bits_at(a);
            for k in 0..64 {
                prop_assert_eq!((word >> k) & 1 == 1, pixel(&m, a + k), "bit {} from {}", k, a);
            }
            let mut r = m.clone();
            let b = a + len;
            r.set_range(a, b);
            for i in 0..n {
                prop_assert_eq!(pixel(&r, i), pixel(&m, i) || (a..=b).contains(&i), "pixel {}", i);
            }
            prop_assert_eq!(r.count_foreground(), (0..n).filter(|&i| pixel(&r, i)).count() as u64);
        }
    }

    fn fixed(t: u8) -> LoadOptions {
        LoadOptions {
            threshold: Threshold::Fixed(t),
            ..LoadOptions::default()
        }
    }

    fn one_pixel_rgba8(p: [u8; 4]) -> DynamicImage {
        DynamicImage::ImageRgba8(ImageBuffer::from_pixel(1, 1, Rgba(p)))
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
    fn mask_basics() {
        let m = Mask::from_ascii(
            "
            #..
            .##
            ",
        );
        assert_eq!((m.width(), m.height()), (3, 2));
        assert_eq!(m.count_foreground(), 3);
        assert!(m.get(0, 0) && m.get(1, 1) && m.get(2, 1));
        assert!(!m.get(1, 0) && !m.get(-1, 0) && !m.get(0, -1) && !m.get(3, 1) && !m.get(0, 2));
        assert_eq!(Mask::from_ascii(&m.to_ascii()), m);
        let mut n = Mask::new(70, 3);
        n.set(69, 2, true);
        n.set(70, 2, true); // outside: ignored
        n.set(-1, 0, true);
        assert_eq!(n.count_foreground(), 1);
        n.set(69, 2, false);
        assert_eq!(n.count_foreground(), 0);
        let f = Mask::from_fn(5, 4, |x, y| (x + y) % 2 == 0);
        assert_eq!(f.count_foreground(), 10);
        assert!(f.get(4, 0) && !f.get(4, 1));
    }

    #[test]
    fn compositing_on_white() {
        // Transparent black is white paper; opaque black is ink.
        let t = |p| {
            threshold_image(&one_pixel_rgba8(p), &fixed(128))
                .mask
                .get(0, 0)
        };
        assert!(!t([0, 0, 0, 0]));
        assert!(t([0, 0, 0, 255]));
        // alpha 100: 255 * 155 / 255 = 155 (paper); alpha 200: 55 (ink).
        assert!(!t([0, 0, 0, 100]));
        assert!(t([0, 0, 0, 200]));
        // A transparent pixel counts as white whatever its colour.
        let l = threshold_image(&one_pixel_rgba8([0, 0, 0, 0]), &fixed(255));
        assert!(!l.mask.get(0, 0), "white must not be below 255");
        // Grey with alpha.
        let la = DynamicImage::ImageLumaA8(ImageBuffer::from_pixel(1, 1, image::LumaA([0u8, 0])));
        assert!(!threshold_image(&la, &fixed(128)).mask.get(0, 0));
        // 16-bit: same rule, per channel over 65535.
        let t16 = |p: [u16; 4]| {
            let img = DynamicImage::ImageRgba16(ImageBuffer::from_pixel(1, 1, Rgba(p)));
            threshold_image(&img, &fixed(128)).mask.get(0, 0)
        };
        assert!(!t16([0, 0, 0, 0]));
        assert!(t16([0, 0, 0, 65535]));
        assert!(!t16([0, 0, 0, 20000])); // about 177 in 8 bits
        assert!(t16([0, 0, 0, 50000])); // about 60
    }

    /// Foreground status of a one-pixel RGB image at two thresholds around `luma`.
    fn check_grey(rgb: [u8; 3], expected: u8, compat: Compat) {
        let img = DynamicImage::ImageRgb8(ImageBuffer::from_pixel(1, 1, Rgb(rgb)));
        let at = |t| {
            let opts = LoadOptions { compat, ..fixed(t) };
            threshold_image(&img, &opts).mask.get(0, 0)
        };
        assert!(!at(expected), "{rgb:?}: grey should be >= {expected}");
        if expected < 255 {
            assert!(at(expected + 1), "{rgb:?}: grey should be <= {expected}");
        }
    }

    #[test]
    fn luma_is_rec709() {
        // Rec. 709 luma, truncated like image's to_luma8: 0.2126 R + 0.7152 G + 0.0722 B.
        // (Rec. 601 would give red 76, green 150, blue 29.)
        for (rgb, w) in [
            ([255, 0, 0], 0.2126),
            ([0, 255, 0], 0.7152),
            ([0, 0, 255], 0.0722),
        ] {
            let expected = (255.0f64 * w).floor() as u8;
            check_grey(rgb, expected, Compat::Default);
        }
        check_grey([100, 100, 100], 100, Compat::Default);
    }

    #[test]
    fn ipol_grey_is_libpng_and_strips_alpha() {
        for rgb in [
            [255u8, 0, 0],
            [0, 255, 0],
            [0, 0, 255],
            [12, 200, 77],
            [255, 255, 255],
        ] {
            let v = (6968.0 * f64::from(rgb[0])
                + 23434.0 * f64::from(rgb[1])
                + 2366.0 * f64::from(rgb[2]))
                / 32768.0;
            check_grey(rgb, v.floor() as u8, Compat::Ipol);
        }
        let ipol = LoadOptions {
            compat: Compat::Ipol,
            ..fixed(128)
        };
        // Transparent black is black in the reference (alpha stripped, not composited).
        assert!(threshold_image(&one_pixel_rgba8([0, 0, 0, 0]), &ipol)
            .mask
            .get(0, 0));
        assert!(
            !threshold_image(&one_pixel_rgba8([255, 255, 255, 0]), &ipol)
                .mask
                .get(0, 0)
        );
        // Grey images keep their value.
        let g = DynamicImage::ImageLuma8(ImageBuffer::from_pixel(1, 1, Luma([77u8])));
        let at = |t| {
            threshold_image(
                &g,
                &LoadOptions {
                    compat: Compat::Ipol,
                    ..fixed(t)
                },
            )
        };
        assert!(!at(77).mask.get(0, 0) && at(78).mask.get(0, 0));
    }

    /// Between-class variance for `{g <= t}` vs `{g > t}`, in floating point.
    fn variance(hist: &[u64; 256], t: usize) -> f64 {
        let n: f64 = hist.iter().map(|&c| c as f64).sum();
        let w0: f64 = hist[..=t].iter().map(|&c| c as f64).sum();
        let w1 = n - w0;
        if w0 == 0.0 || w1 == 0.0 {
            return 0.0;
        }
        let m0 = hist[..=t]
            .iter()
            .enumerate()
            .map(|(g, &c)| g as f64 * c as f64)
            .sum::<f64>()
            / w0;
        let m1 = hist[t + 1..]
            .iter()
            .enumerate()
            .map(|(g, &c)| (g + t + 1) as f64 * c as f64)
            .sum::<f64>()
            / w1;
        w0 * w1 * (m0 - m1) * (m0 - m1) / (n * n)
    }

    fn assert_otsu_is_first_max(hist: &[u64; 256]) {
        let t = usize::from(otsu(hist));
        assert!(t <= 254);
        let v = variance(hist, t);
        let best = (0..=254).map(|u| variance(hist, u)).fold(0.0, f64::max);
        assert!(v >= best * (1.0 - 1e-12), "t={t} v={v} best={best}");
        for u in 0..t {
            assert!(
                variance(hist, u) < v * (1.0 - 1e-12) || v == 0.0,
                "earlier max at {u}"
            );
        }
    }

    #[test]
    fn otsu_bimodal() {
        // Dark cluster 30..=50, light cluster 190..=210, on a 64x64 image.
        let img = ImageBuffer::from_fn(64, 64, |x, y| {
            let k = ((x * 7 + y * 13) % 21) as u8;
            Luma([if (x / 8 + y / 8) % 3 == 0 {
                30 + k
            } else {
                190 + k
            }])
        });
        let dark = img.pixels().filter(|p| p[0] <= 50).count() as u64;
        let img = DynamicImage::ImageLuma8(img);
        let opts = LoadOptions {
            threshold: Threshold::Otsu,
            ..LoadOptions::default()
        };
        let l = threshold_image(&img, &opts);
        assert!(
            (51..=190).contains(&l.threshold),
            "threshold {}",
            l.threshold
        );
        assert_eq!(l.mask.count_foreground(), dark);
        assert_otsu_is_first_max(&histogram(img.as_luma8().unwrap().as_raw()));
        // invert swaps the classes.
        let inv = threshold_image(
            &img,
            &LoadOptions {
                invert: true,
                ..opts
            },
        );
        assert_eq!(inv.mask.count_foreground(), 64 * 64 - dark);
        // Two levels: the plateau's first maximum is the dark level itself.
        let mut h = [0u64; 256];
        h[0] = 10;
        h[255] = 30;
        assert_eq!(otsu(&h), 0);
        h[0] = 0;
        assert_eq!(otsu(&h), 0, "one level: no maximum, t = 0");
    }

    proptest! {
        #[test]
        fn otsu_matches_float_first_max(
            levels in proptest::collection::vec((0usize..256, 1u64..1000), 1..12)
        ) {
            let mut h = [0u64; 256];
            for (g, c) in levels {
                h[g] += c;
            }
            assert_otsu_is_first_max(&h);
        }
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
