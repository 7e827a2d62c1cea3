//! Which `<path>` each contour is written in: every outer border with its holes, and the
//! groups that lie inside one of Chromium's raster tiles written together, apart from the
//! rest.
//!
//! # Why
//! tiny-skia and Skia clip a path's edges only where the *path's* bounds leave the clip
//! (the pixmap, or in Chromium each raster tile, see [`crate::outline::tiles`]); a clipped
//! path has its curves cut at their extrema before they are subdivided, which moves the
//! chords. A contour in a path that is never clipped needs its curves checked one way only
//! ([`EdgeClipping::Never`](crate::outline::EdgeClipping::Never)), about 13% less drawing
//! work on noise. One path for the whole document is clipped as soon as any contour comes
//! near the page's border or the page has several tiles; so groups that sit well inside one
//! tile go into that tile's own path.
//!
//! # Groups
//! A hole must stay in its outer border's path (with `nonzero`, a clockwise hole alone
//! paints its inside). The outer border of a hole is found from the contours alone, by their
//! cracks: from the hole's first crack in raster order — the left side of its topmost row's
//! leftmost pixel, whose left neighbour `q` is foreground — the nearest crack to the left of
//! `q` in that row with the foreground on its right belongs to the component of `q`
//! (the pixels between are foreground): its outer border, or another of its holes, whose
//! first crack comes earlier in raster order (that hole has a pixel in this row left of
//! `q`), so following such holes ends at the outer border.

use crate::contour::Contour;
use crate::outline::crack_polyline_into;
use crate::outline::tiles::{tiles, TileSize};

/// Fewest pixels between a group's pixels and the sides of the tile clip holding it for its
/// path to be drawn unclipped: the drawing of a contour stays within 2 px of its pixels'
/// squares (checked after drawing, see [`Tile::holds`]).
pub(crate) const TILE_MARGIN: i64 = 3;

/// The side (pixels) of the pieces tiny-skia draws a larger pixmap in (its `DrawTiler`).
const RESVG_PIECE: i64 = 8191;

/// For each of `contours` (traced in the default convention, see
/// [`crate::Convention::Default`]), the index of the outer border of its component: its
/// own for an outer border.
///
/// Returns `None` if the contours are not closed borders of that convention (an open
/// chain, a first point repeated at the end, as the IPOL convention has) or a hole's outer
/// border is not found.
pub(crate) fn outer_borders(contours: &[Contour]) -> Option<Vec<usize>> {
    let n = contours.len();
    let closed = |c: &Contour| {
        let m = c.points.len();
        c.closed && m > 0 && (m == 1 || c.points[0] != c.points[m - 1])
    };
    if !contours.iter().all(closed) {
        return None;
    }
    let mut outer: Vec<usize> = (0..n).collect();
    // Without holes each contour is its own outer border: no crack is looked at (the 3000²
    // sample's 350 contours: about 2 ms before the drawing could start).
    if !contours.iter().any(|c| c.hole) {
        return Some(outer);
    }
    // Vertical cracks with the foreground on their right, one per row: (y, x, contour).
    let mut entering: Vec<(i32, i32, u32)> = Vec::new();
    // Each hole's first vertical crack with the foreground on its left, in raster order.
    let mut first_crack: Vec<Option<(i32, i32)>> = vec![None; n];
    // Each contour's crack polygon, in one buffer.
    let mut poly = Vec::new();
    for (k, c) in contours.iter().enumerate() {
        let index = u32::try_from(k).ok()?;
        crack_polyline_into(&c.points, 0, c.points.len() - 1, &mut poly);
        for (i, a) in poly.iter().enumerate() {
            let b = poly[(i + 1) % poly.len()];
            if a.x != b.x {
                continue;
            }
            let x = a.x as i32;
            // Down the screen the foreground is on the right (see `crack_polyline`).
            if b.y > a.y {
                entering.extend((a.y as i32..b.y as i32).map(|y| (y, x, index)));
            } else if c.hole && b.y < a.y {
                let crack = (b.y as i32, x);
                first_crack[k] = Some(first_crack[k].map_or(crack, |f| f.min(crack)));
            }
        }
    }
    sort_by_rows(&mut entering);
    let mut holes: Vec<usize> = (0..n).filter(|&k| contours[k].hole).collect();
    holes.sort_unstable_by_key(|&k| first_crack[k]);
    for &h in &holes {
        let (y, x) = first_crack[h]?;
        // The nearest entering crack at or left of `q`'s left side (`q` = pixel x − 1).
        let i = entering.partition_point(|&(ey, ex, _)| (ey, ex) <= (y, x - 1));
        let &(ey, _, k) = entering.get(i.checked_sub(1)?)?;
        let k = k as usize;
        if ey != y || k == h {
            return None;
        }
        outer[h] = if contours[k].hole {
            // Resolved already: its first crack comes earlier.
            if first_crack[k]? >= first_crack[h]? {
                return None;
            }
            outer[k]
        } else {
            k
        };
    }
    Some(outer)
}

/// Sorts `(y, x, k)` entries as `sort_unstable` does: by a counting sort of their rows,
/// then each row by itself (noise has millions of entries over a few thousand rows: the
/// sort of them all took 0.7% of 2000² noise's instructions).
fn sort_by_rows(entries: &mut Vec<(i32, i32, u32)>) {
    let (Some(lo), Some(hi)) = (
        entries.iter().map(|e| e.0).min(),
        entries.iter().map(|e| e.0).max(),
    ) else {
        return;
    };
    let rows = usize::try_from(i64::from(hi) - i64::from(lo) + 1).unwrap_or(usize::MAX);
    if entries.len() < 1024 || rows > entries.len() {
        entries.sort_unstable();
        return;
    }
    let row = |e: &(i32, i32, u32)| (e.0 - lo) as usize;
    let mut starts = vec![0usize; rows + 1];
    for e in entries.iter() {
        starts[row(e) + 1] += 1;
    }
    for r in 0..rows {
        starts[r + 1] += starts[r];
    }
    let mut next = starts.clone();
    let mut sorted = vec![(0, 0, 0); entries.len()];
    for e in entries.iter() {
        let at = &mut next[row(e)];
        sorted[*at] = *e;
        *at += 1;
    }
    for span in starts.windows(2) {
        sorted[span[0]..span[1]].sort_unstable();
    }
    *entries = sorted;
}

/// A tile of Chromium's raster (see [`crate::outline::tiles`]) holding groups of contours:
/// its clip, in pixels of the page (within one of the pieces tiny-skia draws a pixmap over
/// 8191 px in).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct Tile {
    /// First row of the clip.
    y0: i64,
    /// First column of the clip.
    x0: i64,
    /// Row after the clip.
    y1: i64,
    /// Column after the clip.
    x1: i64,
}

impl Tile {
    /// The tile of a `width` × `height` page whose clip holds the pixels `x0..x1` ×
    /// `y0..y1` with [`TILE_MARGIN`] pixels to spare, the only tile that shows any of them
    /// (on a page drawn as one tile, the page itself). `None` if there is none such.
    pub(crate) fn holding(
        x0: i64,
        y0: i64,
        x1: i64,
        y1: i64,
        width: u32,
        height: u32,
    ) -> Option<Tile> {
        let (w, h) = (i64::from(width), i64::from(height));
        let size = TileSize::of_page(w, h);
        // tiny-skia draws a pixmap over 8191 px either way in pieces of 8191 px, each with
        // its own clip (`DrawTiler`): the group must keep inside one of those too, and the
        // tile's clip is its part inside that piece.
        let pieces = w > RESVG_PIECE || h > RESVG_PIECE;
        let one = |lo: i64, hi: i64, end: i64, size: i64| {
            if lo < 0 || hi > end || lo >= hi {
                return None;
            }
            let mut it = tiles(lo, hi, end, size);
            let (_, mut clip, _) = it.next()?;
            if pieces {
                let first = lo / RESVG_PIECE * RESVG_PIECE;
                clip = (clip.0.max(first), clip.1.min(first + RESVG_PIECE));
            }
            (it.next().is_none() && clip.0 + TILE_MARGIN <= lo && hi + TILE_MARGIN <= clip.1)
                .then_some(clip)
        };
        let (cx, cy) = (one(x0, x1, w, size.width)?, one(y0, y1, h, size.height)?);
        Some(Tile {
            y0: cy.0,
            x0: cx.0,
            y1: cy.1,
            x1: cx.1,
        })
    }

    /// Whether a path whose points lie within `bounds` is drawn unclipped in this tile and
    /// in no other: `bounds` is one pixel or more inside the clip (Skia rounds a path's
    /// bounds out to whole pixels; the neighbouring tiles' clips overlap this one by two
    /// pixels, and show none of them).
    pub(crate) fn holds(&self, bounds: kurbo::Rect) -> bool {
        bounds.x0 >= (self.x0 + 1) as f64
            && bounds.y0 >= (self.y0 + 1) as f64
            && bounds.x1 <= (self.x1 - 1) as f64
            && bounds.y1 <= (self.y1 - 1) as f64
    }
}

/// Contours grouped into paths (see [`tiles_of_groups`]).
pub(crate) struct Grouping {
    /// For each contour, the index of its group's outer border (see [`outer_borders`]).
    pub(crate) outer: Vec<usize>,
    /// For each contour, the tile whose own path its group is written in, unclipped;
    /// `None` for the contours left in the path of the rest.
    pub(crate) tile: Vec<Option<Tile>>,
}

/// The groups of `contours` (each outer border with its holes, see [`outer_borders`]) on a
/// `width` × `height` page, and the tile holding each ([`Tile::holding`]).
///
/// Returns `None` if the contours cannot be grouped or no group is held by a tile.
pub(crate) fn tiles_of_groups(contours: &[Contour], width: u32, height: u32) -> Option<Grouping> {
    let mut tile_of_outer: Vec<Option<Tile>> = vec![None; contours.len()];
    let mut any = false;
    for (k, c) in contours.iter().enumerate() {
        if c.hole {
            continue;
        }
        // The outer border's pixels span the component's, holes included.
        let Some([x0, y0, x1, y1]) = c.pixel_box() else {
            continue;
        };
        tile_of_outer[k] = Tile::holding(x0, y0, x1, y1, width, height);
        any |= tile_of_outer[k].is_some();
    }
    // The cracks are looked at only when some group can be held.
    if !any {
        return None;
    }
    let outer = outer_borders(contours)?;
    let tile = outer.iter().map(|&o| tile_of_outer[o]).collect();
    Some(Grouping { outer, tile })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use proptest::prelude::*;

    /// The component label of every foreground pixel (8-connected), by flood fill.
    fn labels(mask: &Mask) -> Vec<Option<usize>> {
        let (w, h) = (mask.width() as i64, mask.height() as i64);
        let mut label = vec![None; (w * h) as usize];
        let mut next = 0;
        for start in 0..w * h {
            if label[start as usize].is_some() || !mask.get(start % w, start / w) {
                continue;
            }
            let mut stack = vec![start];
            label[start as usize] = Some(next);
            while let Some(i) = stack.pop() {
                let (x, y) = (i % w, i / w);
                for (dx, dy) in [
                    (-1, -1),
                    (0, -1),
                    (1, -1),
                    (-1, 0),
                    (1, 0),
                    (-1, 1),
                    (0, 1),
                    (1, 1),
                ] {
                    let (u, v) = (x + dx, y + dy);
                    if u >= 0 && v >= 0 && u < w && v < h && mask.get(u, v) {
                        let j = (v * w + u) as usize;
                        if label[j].is_none() {
                            label[j] = Some(next);
                            stack.push(j as i64);
                        }
                    }
                }
            }
            next += 1;
        }
        label
    }

    proptest! {
        /// Every hole is given the outer border of the component its pixels belong to
        /// (labelled by flood fill), on random bitmaps full of nested holes and islands.
        #[test]
        fn holes_get_their_components_outer_border(
            w in 1u32..24, h in 1u32..24, seed in any::<u64>(), density in 30u32..80,
        ) {
            let mut state = seed | 1;
            let mask = Mask::from_fn(w, h, |_, _| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state % 100) < u64::from(density)
            });
            let contours = trace(&mask, Convention::Default);
            let outer = outer_borders(&contours).expect("default contours");
            let label = labels(&mask);
            let of = |c: &Contour| label[(c.points[0].y as u32 * w + c.points[0].x as u32) as usize];
            for (k, c) in contours.iter().enumerate() {
                let o = &contours[outer[k]];
                prop_assert!(!o.hole);
                prop_assert_eq!(of(c), of(o), "contour {} given {}", k, outer[k]);
                if !c.hole {
                    prop_assert_eq!(outer[k], k);
                }
            }
        }
    }

    proptest::proptest! {
        /// The counting sort by rows gives `sort_unstable`'s order.
        #[test]
        fn rows_then_columns_as_a_sort(
            entries in proptest::collection::vec((-3i32..40, -5i32..5, 0u32..4), 0..3000),
        ) {
            let mut ours = entries.clone();
            sort_by_rows(&mut ours);
            let mut expected = entries;
            expected.sort_unstable();
            proptest::prop_assert_eq!(ours, expected);
        }
    }

    #[test]
    fn ipol_chains_are_not_grouped() {
        let mask = Mask::from_ascii(
            "#####
             #...#
             #####",
        );
        assert!(outer_borders(&trace(&mask, Convention::Ipol)).is_none());
        assert_eq!(
            outer_borders(&trace(&mask, Convention::Default)),
            Some(vec![0, 0])
        );
    }

    #[test]
    fn tiles_hold_groups_clear_of_their_sides() {
        // One tile: the page, 3 px to spare.
        assert!(Tile::holding(3, 3, 97, 47, 100, 50).is_some());
        assert!(Tile::holding(2, 3, 97, 47, 100, 50).is_none());
        assert!(Tile::holding(3, 3, 98, 47, 100, 50).is_none());
        // 600²: tiles of 256 px every 254; clips [0, 256), [254, 510), [508, 600).
        let t = Tile::holding(300, 10, 400, 100, 600, 600).expect("inside the second column");
        assert_eq!((t.x0, t.x1, t.y0, t.y1), (254, 510, 0, 256));
        // Shown by two tiles (the first shows up to 255, the second from 255).
        assert!(Tile::holding(240, 10, 256, 100, 600, 600).is_none());
        // Within the clip but too near its side.
        assert!(Tile::holding(255, 10, 300, 100, 600, 600).is_none());
        assert!(Tile::holding(257, 10, 300, 100, 600, 600).is_some());
        assert!(t.holds(kurbo::Rect::new(255.0, 1.0, 509.0, 255.0)));
        assert!(!t.holds(kurbo::Rect::new(254.5, 1.0, 300.0, 200.0)));
        // 9000 × 20: one Chromium tile [8160, 8672) holds both, but tiny-skia draws the
        // pixmap in pieces [0, 8191) and [8191, 9000), each clipped.
        assert!(Tile::holding(8180, 3, 8189, 17, 9000, 20).is_none());
        let t = Tile::holding(8194, 3, 8200, 17, 9000, 20).expect("inside the second piece");
        assert_eq!((t.x0, t.x1), (8191, 8672));
        assert!(Tile::holding(8170, 3, 8180, 17, 9000, 20).is_some());
    }
}
