//! Chromium's raster tiles: where a browser showing the document at 1:1 cuts its path.
//!
//! Chromium rasterizes a page in tiles of 256 × 256 pixels that overlap their neighbours by
//! two pixels (one texel of border on each side), so a new tile starts every 254 pixels.
//! Tile `k` of a row (or column) is drawn with the clip `[254 k, 254 k + 256)`, within the
//! document, and shows only its inner pixels `[254 k + 1, 254 k + 255)` (the first from 0,
//! the last to the document's end).
//! Skia's edge clipper cuts every edge that crosses the clip where it crosses it, the new
//! end rounded to 1/64 px, which tilts what is left inside: the part of a segment between a
//! vertex and the cut is not the segment, and a curve cut there is subdivided anew.
//!
//! Measured with `scripts/browser_check.sh` (Chromium 156, headless, software raster, the
//! SVG opened as the page at 1:1): all 7 pixels Chromium drew differently from tiny-skia
//! over the 27 shared samples (conic and circle) were on commands crossing such a clip line,
//! a segment passing 0.018 px from a pixel centre came to pass on its other side when cut
//! at 256 (2393, 254) or at 1526 (1886, 1517), and tiny-skia reproduces such a tile when
//! the path is drawn into a mask that is exactly the tile's clip. Where a page puts a
//! document that is not the page itself is not known; [`super::ROBUST_SHIFT`] stands in
//! for those cuts. Chromium's cc sources (read, not measured here) choose other tile sizes for small or narrow pages (one
//! tile below 512 px both ways; 512-px-tall tiles on pages under 256 px wide): those were
//! not measured, and this model checks 256-px tiles on every page larger than one; the
//! move covers the rest.

use super::render_check::{painted_in, Reference, Window};
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// Pixels between the starts of consecutive tiles.
const TILE_STEP: i64 = 254;
/// Width and height of a tile's clip, its borders included.
const TILE_SIZE: i64 = 256;

/// The tiles of one axis that show pixels of `lo..hi` (document coordinates relative to its
/// origin, within `0..end`): `(k, clip, shown)` with the clip's and the shown pixels' ranges.
pub(crate) fn tiles(
    lo: i64,
    hi: i64,
    end: i64,
) -> impl Iterator<Item = (i64, (i64, i64), (i64, i64))> {
    // As Chromium's `TilingData`: the last tile also shows its far border pixel, so a page
    // of 254 k + 2 pixels has k tiles, not a last one of two pixels.
    let count = (1 + (end - 3).div_euclid(TILE_STEP)).max(1);
    let tile_of = |r: i64| (r - 1).div_euclid(TILE_STEP).clamp(0, count - 1);
    let (first, last) = (tile_of(lo.max(0)), tile_of((hi - 1).min(end - 1)));
    (first..=last).map(move |k| {
        let clip = (k * TILE_STEP, (k * TILE_STEP + TILE_SIZE).min(end));
        let shown = (
            if k == 0 { 0 } else { k * TILE_STEP + 1 },
            if k == count - 1 {
                clip.1
            } else {
                k * TILE_STEP + TILE_SIZE - 1
            },
        );
        (k, clip, shown)
    })
}

/// Pixels (of the contour's coordinates) that Chromium draws wrong in some tile, for a
/// document whose pixmap is `canvas` with its top-left corner at the page's origin: the
/// difference of the path and `reference` (see [`super::render_check::misplaced_pixels`])
/// drawn by tiny-skia into each tile's clip that cuts the path, counted on the pixels that
/// tile shows. Curves are drawn clipped (Skia clips every edge of a path that leaves the
/// tile). Tiles whose clip holds the whole path are left out: they draw it as the clipped
/// way of [`super::EdgeClipping::Unknown`] (or `Always`) does, which the caller checks.
/// Empty without a canvas.
pub(crate) fn misplaced_in_tiles(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    canvas: Option<Rect>,
) -> Vec<Pixel> {
    let Some(canvas) = canvas else {
        return Vec::new();
    };
    let page = Window::inside(canvas);
    if page.x1 - page.x0 <= TILE_SIZE && page.y1 - page.y0 <= TILE_SIZE {
        // One tile, whose clip is the page's.
        return Vec::new();
    }
    let round = Window::round(reference, start, commands);
    let Some(win) = round.within(page) else {
        return Vec::new();
    };
    // The path's own bounds (the window has two pixels to spare on every side): a clip
    // that holds them cuts nothing.
    let bounds = Window {
        x0: round.x0 + 2,
        y0: round.y0 + 2,
        x1: round.x1 - 2,
        y1: round.y1 - 2,
    };
    let (ox, oy) = (page.x0, page.y0);
    let (w, h) = (page.x1 - ox, page.y1 - oy);
    let mut out = Vec::new();
    for (_, (cy0, cy1), (sy0, sy1)) in tiles(win.y0 - oy, win.y1 - oy, h) {
        for (_, (cx0, cx1), (sx0, sx1)) in tiles(win.x0 - ox, win.x1 - ox, w) {
            let clip = Window {
                x0: ox + cx0,
                y0: oy + cy0,
                x1: ox + cx1,
                y1: oy + cy1,
            };
            if bounds.is_in(clip) {
                continue;
            }
            let Some(part) = win.within(clip) else {
                continue;
            };
            let shown = Window {
                x0: ox + sx0,
                y0: oy + sy0,
                x1: ox + sx1,
                y1: oy + sy1,
            };
            out.extend(
                painted_in(reference, start, commands, &part, &[true])
                    .into_iter()
                    .filter(|p| shown.contains(i64::from(p.x), i64::from(p.y))),
            );
        }
    }
    out
}

/// Whether the pixels `x0..x1` × `y0..y1` (contour coordinates) are `margin` pixels or
/// more from every line where a tile of `canvas` cuts paths (see [`misplaced_in_tiles`]):
/// a path drawn there is drawn the same wherever else it is put so. True without a canvas.
pub(crate) fn clear_of_tile_cuts(
    x0: i64,
    y0: i64,
    x1: i64,
    y1: i64,
    canvas: Option<Rect>,
    margin: i64,
) -> bool {
    let Some(canvas) = canvas else {
        return true;
    };
    let page = Window::inside(canvas);
    // Clip lines of one axis: 254 k and 254 k + 2 (k ≥ 1), below `end`.
    let clear = |lo: i64, hi: i64, origin: i64, end: i64| {
        let (lo, hi) = (lo - margin - origin, hi + margin - origin);
        let crosses = |offset: i64| {
            // Some k ≥ 1 with lo < 254 k + offset < hi and 254 k + offset < end (the first
            // line above lo: the others are farther).
            let k = ((lo - offset).div_euclid(TILE_STEP) + 1).max(1);
            let line = k * TILE_STEP + offset;
            // Tile k exists when its clip starts 3 or more pixels before the end.
            line < hi && k * TILE_STEP + 2 < end
        };
        !crosses(0) && !crosses(TILE_SIZE - TILE_STEP)
    };
    clear(x0, x1, page.x0, page.x1 - page.x0) && clear(y0, y1, page.y0, page.y1 - page.y0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// `clear_of_tile_cuts` against every clip line listed one by one.
        #[test]
        fn clear_means_no_clip_line_within_the_margin(
            x0 in -20i64..1200, w in 1i64..40, y0 in -20i64..1200, h in 1i64..40,
            ox in 0i64..4, oy in 0i64..4, cw in 200i64..1100, ch in 200i64..1100,
            margin in 0i64..7,
        ) {
            let canvas = Rect::new(ox as f64, oy as f64, (ox + cw) as f64, (oy + ch) as f64);
            // Lines of one axis: where a tile's clip starts or ends inside the page.
            let lines = |end: i64| -> Vec<i64> {
                let mut v = Vec::new();
                // The starts and ends of the clips of the tiles `tiles` lists, inside.
                for (_, (c0, c1), _) in tiles(0, end, end) {
                    for l in [c0, c1] {
                        if l > 0 && l < end {
                            v.push(l);
                        }
                    }
                }
                v
            };
            let near = |lo: i64, hi: i64, origin: i64, end: i64| {
                lines(end)
                    .iter()
                    .any(|&l| lo - margin - origin < l && l < hi + margin - origin)
            };
            let expected = !near(x0, x0 + w, ox, cw) && !near(y0, y0 + h, oy, ch);
            prop_assert_eq!(
                clear_of_tile_cuts(x0, y0, x0 + w, y0 + h, Some(canvas), margin),
                expected
            );
        }
    }

    /// The tiles of Chromium's `TilingData` (256-px tiles, one border texel): count
    /// `max(1, 1 + (end − 3) / 254)`, tile k's bounds `[254 k + 1, 254 k + 255)` with the
    /// first from 0 and the last to the end, its clip one pixel wider each side.
    #[test]
    fn tiles_are_chromiums() {
        for end in 1..3000i64 {
            let count = (1 + (end - 3).div_euclid(254)).max(1);
            let got: Vec<_> = tiles(0, end, end).collect();
            assert_eq!(got.len() as i64, count, "{end}");
            for (k, clip, shown) in got {
                let lo = if k == 0 { 0 } else { 254 * k + 1 };
                let hi = if k == count - 1 { end } else { 254 * k + 255 };
                assert_eq!(shown, (lo, hi), "{end} {k}");
                assert_eq!(clip, ((lo - 1).max(0), (hi + 1).min(end)), "{end} {k}");
            }
        }
    }

    #[test]
    fn every_pixel_is_shown_by_one_tile() {
        for end in [1, 200, 255, 256, 509, 510, 3000] {
            let mut shown_by = vec![0; end as usize];
            for (_, (c0, c1), (s0, s1)) in tiles(0, end, end) {
                assert!(c0 <= s0 && s1 <= c1 && c1 - c0 <= TILE_SIZE, "{end}");
                for r in s0..s1 {
                    shown_by[r as usize] += 1;
                }
            }
            assert!(shown_by.iter().all(|&n| n == 1), "{end}: {shown_by:?}");
        }
    }

    /// The case measured in Chromium: a segment passing 0.018 px right of the centre of
    /// pixel (2393, 254) (foreground on its left), cut at the clip's edge 256 of tile 0,
    /// leaves that pixel out in Chromium; drawn whole (tiny-skia, resvg) it keeps it in.
    #[test]
    fn a_segment_cut_at_a_tile_border_loses_a_pixel() {
        // A wedge whose right side is the measured segment, wound as layertrace's outer
        // borders are (counter-clockwise on screen).
        let (a, b) = (
            Point::new(2393.1875, 250.5625),
            Point::new(2394.5, 266.1875),
        );
        let start = Point::new(2385.0, 250.5625);
        let cmds = [
            PathCommand::Line(Point::new(2385.0, 266.1875)),
            PathCommand::Line(b),
            PathCommand::Line(a),
        ];
        // The reference: the staircase of the pixels whose centre is left of the segment,
        // rows 251 to 265.
        let right_end = |y: i64| {
            let cy = y as f64 + 0.5;
            let x = a.x + (b.x - a.x) * (cy - a.y) / (b.y - a.y);
            (x - 0.5).ceil()
        };
        let mut rc = vec![
            PathCommand::Line(Point::new(2385.0, 266.0)),
            PathCommand::Line(Point::new(right_end(265), 266.0)),
        ];
        for y in (251..=265).rev() {
            rc.push(PathCommand::Line(Point::new(right_end(y), y as f64)));
            if y > 251 {
                rc.push(PathCommand::Line(Point::new(right_end(y - 1), y as f64)));
            }
        }
        let rs = Point::new(2385.0, 251.0);
        let reference = Reference::new(rs, &rc);
        assert_eq!(right_end(254), 2394.0);
        let canvas = Some(Rect::new(0.0, 0.0, 3000.0, 3000.0));
        // Exact in tiny-skia as a whole…
        let whole = super::super::render_check::misplaced_pixels(
            &reference,
            start,
            &cmds,
            super::super::EdgeClipping::Unknown,
            canvas,
        );
        assert!(whole.is_empty(), "{whole:?}");
        // …but not in the tile that shows row 254.
        let wrong = misplaced_in_tiles(&reference, start, &cmds, canvas);
        assert_eq!(
            wrong.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>(),
            vec![(2393, 254)]
        );
        // Away from the clip lines nothing changes.
        let moved: Vec<PathCommand> = cmds
            .iter()
            .map(|c| c.translated(kurbo::Vec2::new(0.0, 100.0)))
            .collect();
        let start2 = start + kurbo::Vec2::new(0.0, 100.0);
        let rc2: Vec<PathCommand> = rc
            .iter()
            .map(|c| c.translated(kurbo::Vec2::new(0.0, 100.0)))
            .collect();
        let reference2 = Reference::new(rs + kurbo::Vec2::new(0.0, 100.0), &rc2);
        assert!(misplaced_in_tiles(&reference2, start2, &moved, canvas).is_empty());
        assert!(!clear_of_tile_cuts(2385, 250, 2395, 267, canvas, 2));
        assert!(clear_of_tile_cuts(2385, 350, 2395, 367, canvas, 2));
    }
}
