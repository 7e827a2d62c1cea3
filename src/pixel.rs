//! Integer pixel coordinates.

/// A pixel of a bitmap: `x` is the column, `y` the row, `(0, 0)` is the top-left pixel.
///
/// In SVG space the pixel is the unit square `[x, x+1] × [y, y+1]` and its centre is
/// `(x + 0.5, y + 0.5)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Pixel {
    /// Column, growing to the right.
    pub x: i32,
    /// Row, growing downwards.
    pub y: i32,
}

/// A hash set of pixels with rustc's `FxHasher` (`rustc-hash`): pixel sets and maps are
/// built per added contour point, where SipHash's resistance to chosen keys buys nothing.
/// Nothing depends on their iteration order (what is read out of them is sorted first).
pub(crate) type PixelSet = rustc_hash::FxHashSet<Pixel>;

/// A hash map from pixels with rustc's `FxHasher` (see [`PixelSet`]).
pub(crate) type PixelMap<V> = rustc_hash::FxHashMap<Pixel, V>;

impl Pixel {
    /// The pixel at column `x`, row `y`.
    #[inline]
    pub const fn new(x: i32, y: i32) -> Pixel {
        Pixel { x, y }
    }

    /// The four 4-neighbours, in the order right, down, left, up (clockwise on screen).
    #[inline]
    pub fn neighbours4(self) -> [Pixel; 4] {
        [
            Pixel::new(self.x + 1, self.y),
            Pixel::new(self.x, self.y + 1),
            Pixel::new(self.x - 1, self.y),
            Pixel::new(self.x, self.y - 1),
        ]
    }

    /// The 8-direction of `to − self`, clockwise on screen from "right": right 0,
    /// down-right 1, down 2, down-left 3, left 4, up-left 5, up 6, up-right 7. Returns `None`
    /// unless `to` is one of the eight neighbours.
    #[inline]
    pub fn direction_to(self, to: Pixel) -> Option<u8> {
        let dx = i64::from(to.x) - i64::from(self.x);
        let dy = i64::from(to.y) - i64::from(self.y);
        Some(match (dx, dy) {
            (1, 0) => 0,
            (1, 1) => 1,
            (0, 1) => 2,
            (-1, 1) => 3,
            (-1, 0) => 4,
            (-1, -1) => 5,
            (0, -1) => 6,
            (1, -1) => 7,
            _ => return None,
        })
    }

    /// True when `other` is one of the eight neighbours of `self` (not `self` itself).
    #[inline]
    pub fn is_8_adjacent(self, other: Pixel) -> bool {
        let dx = (self.x - other.x).abs();
        let dy = (self.y - other.y).abs();
        dx <= 1 && dy <= 1 && (dx, dy) != (0, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adjacency() {
        let p = Pixel::new(3, 4);
        assert!(p.neighbours4().iter().all(|&q| p.is_8_adjacent(q)));
        assert!(p.is_8_adjacent(Pixel::new(4, 5)));
        assert!(!p.is_8_adjacent(p));
        assert!(!p.is_8_adjacent(Pixel::new(5, 4)));
        assert_eq!(p.direction_to(Pixel::new(4, 4)), Some(0));
        assert_eq!(p.direction_to(Pixel::new(3, 3)), Some(6));
        assert_eq!(p.direction_to(Pixel::new(4, 3)), Some(7));
        assert_eq!(p.direction_to(p), None);
    }
}
