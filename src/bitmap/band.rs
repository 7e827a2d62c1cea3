//! The border band of a mask: the pixels within ν of a pixel of the other colour, which a
//! smooth outline may draw either way.
//!
//! # Distance to the border
//! The distance of a pixel `p` to the border is the distance from its centre to the nearest
//! pixel *square* of the other colour inside the image:
//!
//! ```text
//! d(p) = min { √(max(|dx| − ½, 0)² + max(|dy| − ½, 0)²) : q = p + (dx, dy) in the image,
//!                                                          mask(q) ≠ mask(p) }
//! ```
//!
//! so a pixel with a 4-neighbour of the other colour is at ½, one with only a diagonal
//! neighbour at √½ ≈ 0.71, one two steps from the border at 1.5. Pixels outside the image
//! are no pixels: a shape touching the image border keeps its pixels there at their
//! distance to the nearest pixel of the other colour inside.

use super::mask::Mask;

/// Largest ν accepted by [`Band::new`] (pixels): the offsets searched grow as ν².
pub const MAX_BAND: f64 = 16.0;

/// The pixels of a mask within ν of the border (see the module documentation).
#[derive(Clone, Debug)]
pub struct Band {
    width: u32,
    height: u32,
    nu: f64,
    /// Row-major, one byte per pixel: 1 within ν of the border.
    near: Vec<u8>,
    /// Where an outline drawn in this band must stay: `[x0, x1] × [y0, y1]`.
    bounds: [f64; 4],
}

/// The offsets `(dx, dy) ≠ (0, 0)` whose pixel square is within `nu` of a pixel centre,
/// nearest first.
fn offsets(nu: f64) -> Vec<(i64, i64, f64)> {
    let r = (nu + 0.5).ceil() as i64;
    let mut out = Vec::new();
    for dy in -r..=r {
        for dx in -r..=r {
            if (dx, dy) == (0, 0) {
                continue;
            }
            let d = square_distance(dx, dy);
            if d <= nu {
                out.push((dx, dy, d));
            }
        }
    }
    out.sort_by(|a, b| a.2.total_cmp(&b.2));
    out
}

/// Distance from a pixel centre to the square of the pixel `(dx, dy)` away.
fn square_distance(dx: i64, dy: i64) -> f64 {
    let fx = (dx.abs() as f64 - 0.5).max(0.0);
    let fy = (dy.abs() as f64 - 0.5).max(0.0);
    fx.hypot(fy)
}

impl Band {
    /// The pixels of `mask` within `nu` of its border. Returns `None` unless
    /// `0 < nu <= MAX_BAND`.
    pub fn new(mask: &Mask, nu: f64) -> Option<Band> {
        if !(nu > 0.0 && nu <= MAX_BAND) {
            return None;
        }
        let (w, h) = (mask.width(), mask.height());
        let offs = offsets(nu);
        let mut near = vec![0u8; w as usize * h as usize];
        for y in 0..i64::from(h) {
            for x in 0..i64::from(w) {
                let v = mask.get(x, y);
                // Pixels with all four neighbours alike (or outside) and all eight alike are
                // common; the full search only runs where the colour changes nearby.
                let hit = offs.iter().any(|&(dx, dy, _)| {
                    let (qx, qy) = (x + dx, y + dy);
                    qx >= 0
                        && qy >= 0
                        && qx < i64::from(w)
                        && qy < i64::from(h)
                        && mask.get(qx, qy) != v
                });
                if hit {
                    near[y as usize * w as usize + x as usize] = 1;
                }
            }
        }
        Some(Band {
            width: w,
            height: h,
            nu,
            near,
            bounds: [0.0, 0.0, f64::from(w), f64::from(h)],
        })
    }

    /// The band with the outline kept in the rectangle `[x0, x1] × [y0, y1]` instead of the
    /// whole image (a padded image's own part, say: the renderer cuts paths at the border of
    /// what it draws).
    pub fn within(mut self, x0: f64, y0: f64, x1: f64, y1: f64) -> Band {
        self.bounds = [x0, y0, x1, y1];
        self
    }

    /// Where an outline drawn in this band must stay: `[x0, y0, x1, y1]`.
    pub fn bounds(&self) -> [f64; 4] {
        self.bounds
    }

    /// Width of the image in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height of the image in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The ν of the band.
    pub fn nu(&self) -> f64 {
        self.nu
    }

    /// True when pixel `(x, y)` may be drawn either way: within ν of the border, or outside
    /// the image (never drawn).
    #[inline]
    pub fn free(&self, x: i64, y: i64) -> bool {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return true;
        }
        self.near[y as usize * self.width as usize + x as usize] != 0
    }
}

/// The distance of pixel `(x, y)` of `mask` to its border (see the module documentation),
/// searched up to `limit` pixels. Returns `None` when no pixel of the other colour is within
/// `limit` (or the pixel is outside the image).
///
/// ```
/// use layertrace::{border_distance, Mask};
/// let mask = Mask::from_ascii(".......\n.#####.\n.#####.\n.#####.\n.......");
/// // Beside the background: half a pixel; two steps in: one and a half.
/// assert_eq!(border_distance(&mask, 1, 2, 4.0), Some(0.5));
/// assert_eq!(border_distance(&mask, 3, 2, 4.0), Some(1.5));
/// // Nothing of the other colour within the limit.
/// assert_eq!(border_distance(&mask, 3, 2, 1.0), None);
/// ```
pub fn border_distance(mask: &Mask, x: i64, y: i64, limit: f64) -> Option<f64> {
    let v = mask.get(x, y);
    distance_where(mask.width(), mask.height(), x, y, limit, |u, w| {
        mask.get(u, w) != v
    })
}

/// The distance from the centre of pixel `(x, y)` to the square of the nearest pixel `q` of
/// a `width` × `height` image with `other(q)`, searched up to `limit` pixels (the distance
/// of [`border_distance`], for any notion of "the other colour"). Returns `None` when there
/// is none within `limit`, or `(x, y)` is outside the image.
pub fn distance_where(
    width: u32,
    height: u32,
    x: i64,
    y: i64,
    limit: f64,
    other: impl Fn(i64, i64) -> bool,
) -> Option<f64> {
    let (w, h) = (i64::from(width), i64::from(height));
    if x < 0 || y < 0 || x >= w || y >= h {
        return None;
    }
    offsets(limit.clamp(0.0, MAX_BAND * 4.0))
        .into_iter()
        .find(|&(dx, dy, _)| {
            let (qx, qy) = (x + dx, y + dy);
            qx >= 0 && qy >= 0 && qx < w && qy < h && other(qx, qy)
        })
        .map(|(_, _, d)| d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn distances_of_a_square() {
        // A 7 × 7 square in a 9 × 9 image.
        let mask = Mask::from_fn(9, 9, |x, y| (1..8).contains(&x) && (1..8).contains(&y));
        assert_eq!(border_distance(&mask, 1, 1, 5.0), Some(0.5));
        assert_eq!(border_distance(&mask, 2, 2, 5.0), Some(1.5));
        assert_eq!(border_distance(&mask, 4, 4, 5.0), Some(3.5));
        assert_eq!(border_distance(&mask, 4, 4, 3.0), None);
        // Outside: the corner pixel of the image touches the square only diagonally.
        assert_eq!(border_distance(&mask, 0, 0, 5.0), Some(0.5f64.hypot(0.5)));
        let band = Band::new(&mask, 1.0).unwrap();
        assert!(band.free(1, 1) && band.free(0, 0) && !band.free(2, 2) && band.free(-1, 3));
        assert!(Band::new(&mask, 0.0).is_none() && Band::new(&mask, f64::NAN).is_none());
    }

    proptest! {
        /// A pixel is in the band exactly when its border distance is at most ν.
        #[test]
        fn band_is_distance_at_most_nu(
            bits in proptest::collection::vec(any::<bool>(), 64),
            nu in 0.3f64..3.0,
        ) {
            let mask = Mask::from_fn(8, 8, |x, y| bits[(y * 8 + x) as usize]);
            let band = Band::new(&mask, nu).unwrap();
            for y in 0..8 {
                for x in 0..8 {
                    let d = border_distance(&mask, x, y, nu);
                    prop_assert_eq!(band.free(x, y), d.is_some_and(|d| d <= nu));
                }
            }
        }
    }
}
