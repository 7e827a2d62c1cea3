//! The decomposition picture, in the style of the paper's figures.
//!
//! Background white, foreground light grey; each piece's pixels coloured red, green, blue in
//! turn, the first piece of each contour yellow; the first pixel of each piece marked by a
//! dark square in its middle (or drawn dark at scale 1 and 2). Pixels are enlarged `scale`
//! times so that they can be seen.

use crate::bitmap::Mask;
use crate::decompose::Decomposition;
use image::{Rgb, RgbImage};

const WHITE: Rgb<u8> = Rgb([255, 255, 255]);
const GREY: Rgb<u8> = Rgb([205, 205, 205]);
const YELLOW: Rgb<u8> = Rgb([245, 200, 0]);
const CYCLE: [Rgb<u8>; 3] = [Rgb([220, 30, 30]), Rgb([30, 160, 30]), Rgb([30, 70, 230])];
const MARK: Rgb<u8> = Rgb([20, 20, 20]);

/// The default enlargement: about 800 pixels on the longer side, between 1 and 16.
pub(crate) fn default_scale(width: u32, height: u32) -> u32 {
    (800 / width.max(height).max(1)).clamp(1, 16)
}

/// Draws the picture. Returns `None` if the enlarged image would exceed `max_pixels`.
///
/// ```
/// use layertrace::{decompose, decomposition_picture, trace, Convention, Mask, Model, OutlierRule};
/// let mask = Mask::from_ascii("......\n.####.\n.####.\n......");
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// let pic = decomposition_picture(&mask, &d, 8, 1 << 20).unwrap();
/// assert_eq!(pic.dimensions(), (6 * 8, 4 * 8));
/// // Too large for the pixel limit: no picture.
/// assert!(decomposition_picture(&mask, &d, 8, 100).is_none());
/// ```
pub fn decomposition_picture(
    mask: &Mask,
    d: &Decomposition,
    scale: u32,
    max_pixels: u64,
) -> Option<RgbImage> {
    let scale = scale.max(1);
    let (w, h) = (
        mask.width().checked_mul(scale)?,
        mask.height().checked_mul(scale)?,
    );
    if u64::from(w) * u64::from(h) > max_pixels {
        return None;
    }
    let mut img = RgbImage::from_pixel(w, h, WHITE);
    let fill = |x: i64, y: i64, c: Rgb<u8>, img: &mut RgbImage| {
        if x < 0 || y < 0 || x >= i64::from(mask.width()) || y >= i64::from(mask.height()) {
            return;
        }
        for dy in 0..scale {
            for dx in 0..scale {
                img.put_pixel(x as u32 * scale + dx, y as u32 * scale + dy, c);
            }
        }
    };
    for y in 0..i64::from(mask.height()) {
        for x in 0..i64::from(mask.width()) {
            if mask.get(x, y) {
                fill(x, y, GREY, &mut img);
            }
        }
    }
    for (c, pieces) in d.contours.iter().zip(&d.pieces) {
        for (k, p) in pieces.iter().enumerate() {
            let colour = if k == 0 { YELLOW } else { CYCLE[(k - 1) % 3] };
            for q in &c.points[p.first..=p.last] {
                fill(i64::from(q.x), i64::from(q.y), colour, &mut img);
            }
        }
    }
    // Marks last, so that no later piece paints over them.
    for (c, pieces) in d.contours.iter().zip(&d.pieces) {
        for p in pieces {
            let q = c.points[p.first];
            if q.x < 0 || q.y < 0 || q.x as u32 >= mask.width() || q.y as u32 >= mask.height() {
                continue;
            }
            let (x0, y0) = (q.x as u32 * scale, q.y as u32 * scale);
            let (m0, m1) = if scale < 3 {
                (0, scale)
            } else {
                (scale / 4, scale - scale / 4)
            };
            for dy in m0..m1 {
                for dx in m0..m1 {
                    img.put_pixel(x0 + dx, y0 + dy, MARK);
                }
            }
        }
    }
    Some(img)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose, OutlierRule};
    use crate::model::Model;

    #[test]
    fn colours_and_marks() {
        let mask = Mask::from_ascii(
            "
            ......
            .####.
            .####.
            .####.
            ......",
        );
        let d = decompose(
            trace(&mask, Convention::Default),
            Model::Line,
            OutlierRule::NotInPiece,
        );
        let img = decomposition_picture(&mask, &d, 4, u64::MAX).unwrap();
        assert_eq!(img.dimensions(), (24, 20));
        // Background white, interior pixel (2..3, 2) is grey, a border pixel is coloured.
        assert_eq!(*img.get_pixel(0, 0), WHITE);
        assert_eq!(*img.get_pixel(2 * 4 + 1, 2 * 4 + 1), GREY);
        let first = d.contours[0].points[0];
        // The first pixel of the first piece is marked in the middle, yellow at the edge.
        assert_eq!(
            *img.get_pixel(first.x as u32 * 4 + 2, first.y as u32 * 4 + 2),
            MARK
        );
        assert_eq!(
            *img.get_pixel(first.x as u32 * 4, first.y as u32 * 4),
            YELLOW
        );
        // Pieces beyond the first use the cycle colours.
        let coloured = img.pixels().filter(|p| CYCLE.contains(p)).count();
        assert!(coloured > 0);
        assert!(decomposition_picture(&mask, &d, 4, 100).is_none());
    }
}
