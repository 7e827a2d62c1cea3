//! Turning decoded pixels into grey levels, by layertrace's convention or the IPOL reference's.

use std::borrow::Cow;

use image::{ColorType, DynamicImage, ImageBuffer};

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
    /// samples reduced to their high byte. Use it with [`Threshold::Otsu`](crate::Threshold::Otsu) to match the
    /// reference binarisation (ink = grey <= Otsu's t).
    Ipol,
}

/// Rounded `(c * a + full * (full - a)) / full`: channel `c` with alpha `a` over white.
#[inline]
fn over_white(c: u32, a: u32, full: u32) -> u32 {
    let (c, a, full) = (u64::from(c), u64::from(a), u64::from(full));
    ((c * a + full * (full - a) + full / 2) / full) as u32
}

/// Rec. 709 luma after compositing on white, one byte per pixel, row-major.
pub(super) fn default_grey(img: &DynamicImage) -> Vec<u8> {
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

/// The grey levels of one row of `width` decoded pixels of type `color`, by the same functions
/// (so to the same values) as a whole image; `None` for a pixel type `image` has no
/// [`DynamicImage`] variant for.
///
/// 16-bit and float samples are big-endian if `big_endian` (as PNG rows are), else native.
/// Every conversion is pixel by pixel, so a row gives the row of the whole image's grey.
/// 8-bit grey rows are their grey levels: given back as they are, not copied.
pub(super) fn grey_row(
    color: ColorType,
    big_endian: bool,
    width: u32,
    bytes: &[u8],
    compat: Compat,
) -> Option<Cow<'_, [u8]>> {
    fn u16s(bytes: &[u8], be: bool) -> Vec<u16> {
        bytes
            .chunks_exact(2)
            .map(|c| {
                let c = [c[0], c[1]];
                if be {
                    u16::from_be_bytes(c)
                } else {
                    u16::from_ne_bytes(c)
                }
            })
            .collect()
    }
    fn f32s(bytes: &[u8], be: bool) -> Vec<f32> {
        bytes
            .chunks_exact(4)
            .map(|c| {
                let c = [c[0], c[1], c[2], c[3]];
                if be {
                    f32::from_be_bytes(c)
                } else {
                    f32::from_ne_bytes(c)
                }
            })
            .collect()
    }
    let (w, be) = (width, big_endian);
    let img = match color {
        // Grey stays grey whatever the convention: no conversion at all.
        ColorType::L8 => return Some(Cow::Borrowed(bytes)),
        ColorType::La8 => DynamicImage::ImageLumaA8(ImageBuffer::from_raw(w, 1, bytes.to_vec())?),
        ColorType::Rgb8 => DynamicImage::ImageRgb8(ImageBuffer::from_raw(w, 1, bytes.to_vec())?),
        ColorType::Rgba8 => DynamicImage::ImageRgba8(ImageBuffer::from_raw(w, 1, bytes.to_vec())?),
        ColorType::L16 => DynamicImage::ImageLuma16(ImageBuffer::from_raw(w, 1, u16s(bytes, be))?),
        ColorType::La16 => {
            DynamicImage::ImageLumaA16(ImageBuffer::from_raw(w, 1, u16s(bytes, be))?)
        }
        ColorType::Rgb16 => DynamicImage::ImageRgb16(ImageBuffer::from_raw(w, 1, u16s(bytes, be))?),
        ColorType::Rgba16 => {
            DynamicImage::ImageRgba16(ImageBuffer::from_raw(w, 1, u16s(bytes, be))?)
        }
        ColorType::Rgb32F => {
            DynamicImage::ImageRgb32F(ImageBuffer::from_raw(w, 1, f32s(bytes, be))?)
        }
        ColorType::Rgba32F => {
            DynamicImage::ImageRgba32F(ImageBuffer::from_raw(w, 1, f32s(bytes, be))?)
        }
        _ => return None,
    };
    Some(Cow::Owned(match compat {
        Compat::Default => default_grey(&img),
        Compat::Ipol => ipol_grey(&img),
    }))
}

/// libpng's default `rgb_to_gray` on 8-bit samples (truncating, as its no-gamma path does).
#[inline]
fn libpng_grey(r: u8, g: u8, b: u8) -> u8 {
    ((6968 * u32::from(r) + 23434 * u32::from(g) + 2366 * u32::from(b)) >> 15) as u8
}

/// Grey levels as the IPOL reference reads them (see [`Compat::Ipol`]).
pub(super) fn ipol_grey(img: &DynamicImage) -> Vec<u8> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::tests::fixed;
    use crate::bitmap::{threshold_image, LoadOptions};
    use image::{ImageBuffer, Luma, Rgb, Rgba};

    fn one_pixel_rgba8(p: [u8; 4]) -> DynamicImage {
        DynamicImage::ImageRgba8(ImageBuffer::from_pixel(1, 1, Rgba(p)))
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
}
