//! Chromium's raster tiles: where a browser showing the document at 1:1 cuts its path.
//!
//! Chromium rasterizes a page in tiles that overlap their neighbours by two pixels (one
//! texel of border on each side). With tiles of `T` pixels (256 on most pages) a new tile
//! starts every `T − 2` pixels: tile `k` of a row (or column) is drawn with the clip
//! `[(T − 2) k, (T − 2) k + T)`, within the document, and shows only its inner pixels
//! `[(T − 2) k + 1, (T − 2) k + T − 1)` (the first from 0, the last to the document's end).
//! Skia's edge clipper cuts every edge that crosses the clip where it crosses it, the new
//! end rounded to 1/64 px, which tilts what is left inside: the part of a segment between a
//! vertex and the cut is not the segment, and a curve cut there is subdivided anew.
//!
//! Measured with `scripts/browser_check.sh` (Chromium 156, headless, software raster, the
//! SVG opened as the page at 1:1): all 7 pixels Chromium drew differently from tiny-skia
//! over the 27 shared samples (conic and circle) were on commands crossing such a clip line,
//! a segment passing 0.018 px from a pixel centre came to pass on its other side when cut
//! at 256 (2393, 254) or at 1526 (1886, 1517), and tiny-skia reproduces such a tile when
//! the path is drawn into a mask that is exactly the tile's clip.
//!
//! # Tile sizes
//! The size depends on the page ([`TileSize::of_page`], as cc's `TileSizeCalculator` for
//! software raster, with its default tile of 256 px and largest untiled layer of 512 px):
//! 256 × 256 px; 512 px tall on pages under 256 px wide (and 512 px wide on pages under 256
//! px tall); one tile, the whole page, on pages under 512 px both ways and along any side
//! shorter than its tile. Measured in Chromium 156 with wedges that lose a pixel when cut at
//! a given row (the segment above, moved): pages of 600², 256 × 1200 and 300 × 1200 are cut
//! at rows 256, 510 and 1020; pages of 200 × 1200 and 255 × 1200 at 510, 512 and 1020–1022
//! but not at 256 or 764; pages of 300², 511² and 200 × 500 nowhere. Where a page puts a
//! document that is not the page itself is not known; [`super::ROBUST_SHIFT`] stands in
//! for those cuts.

use super::render_check::{painted_in, Reference, Window};
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// cc's default tile size for software raster (`LayerTreeSettings::default_tile_size`).
const DEFAULT_TILE: i64 = 256;
/// cc's largest untiled layer (`LayerTreeSettings::max_untiled_layer_size`): the tile size
/// along the long side of a narrow page, and of a page smaller than this both ways.
const MAX_UNTILED: i64 = 512;
/// Tile sizes are rounded up to this when clamped to a small page (cc's `kTileRoundUp`).
const TILE_ROUND_UP: i64 = 64;

/// The size of Chromium's raster tiles on a page, clip borders included.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TileSize {
    /// Width of a tile (pixels).
    pub(crate) width: i64,
    /// Height of a tile (pixels).
    pub(crate) height: i64,
}

impl TileSize {
    /// The tiles of a `width` × `height` page: cc's `TileSizeCalculator::CalculateTileSize`
    /// without GPU raster, at device scale 1.
    pub(crate) fn of_page(width: i64, height: i64) -> TileSize {
        let (mut tw, mut th) = (DEFAULT_TILE, DEFAULT_TILE);
        // A narrow page gets taller tiles, a low one wider tiles, a small one a single tile.
        if width < DEFAULT_TILE {
            th = MAX_UNTILED;
        }
        if height < DEFAULT_TILE {
            tw = MAX_UNTILED;
        }
        if width < MAX_UNTILED && height < MAX_UNTILED {
            (tw, th) = (MAX_UNTILED, MAX_UNTILED);
        }
        // Clamped to the page, rounded up to 64 (then to 4, which 64 already is).
        let round_up = |v: i64| (v.max(1) + TILE_ROUND_UP - 1) / TILE_ROUND_UP * TILE_ROUND_UP;
        if width < tw {
            tw = round_up(width).min(tw);
        }
        if height < th {
            th = round_up(height).min(th);
        }
        TileSize {
            width: tw,
            height: th,
        }
    }
}

/// Whether Chromium draws a `width` × `height` page as one tile, whose clip is the page's:
/// then it cuts no path anywhere else than the page's border.
pub(crate) fn one_tile(width: i64, height: i64) -> bool {
    let size = TileSize::of_page(width, height);
    tile_count(width, size.width) == 1 && tile_count(height, size.height) == 1
}

/// The whole pixels of the page `canvas` and the size of its tiles, when Chromium draws it
/// in several; `None` without a canvas, or when its one tile's clip is the page's.
fn tiled_page(canvas: Option<Rect>) -> Option<(Window, TileSize)> {
    let page = Window::inside(canvas?);
    let (w, h) = (page.x1 - page.x0, page.y1 - page.y0);
    (!one_tile(w, h)).then(|| (page, TileSize::of_page(w, h)))
}

/// How many tiles of `size` pixels (two of them borders shared with the neighbours) cover
/// `end` pixels, as Chromium's `TilingData`: the last tile also shows its far border pixel,
/// so a page of `(size − 2) k + 2` pixels has `k` tiles, not a last one of two pixels.
fn tile_count(end: i64, size: i64) -> i64 {
    (1 + (end - 3).div_euclid(size - 2)).max(1)
}

/// The tiles of `size` pixels of one axis that show pixels of `lo..hi` (document
/// coordinates relative to its origin, within `0..end`): `(k, clip, shown)` with the clip's
/// and the shown pixels' ranges.
pub(crate) fn tiles(
    lo: i64,
    hi: i64,
    end: i64,
    size: i64,
) -> impl Iterator<Item = (i64, (i64, i64), (i64, i64))> {
    let step = size - 2;
    let count = tile_count(end, size);
    let tile_of = move |r: i64| (r - 1).div_euclid(step).clamp(0, count - 1);
    let (first, last) = (tile_of(lo.max(0)), tile_of((hi - 1).min(end - 1)));
    (first..=last).map(move |k| {
        let clip = (k * step, (k * step + size).min(end));
        let shown = (
            if k == 0 { 0 } else { k * step + 1 },
            if k == count - 1 {
                clip.1
            } else {
                k * step + size - 1
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
    let Some((page, size)) = tiled_page(canvas) else {
        return Vec::new();
    };
    let (w, h) = (page.x1 - page.x0, page.y1 - page.y0);
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
    let mut out = Vec::new();
    for (_, (cy0, cy1), (sy0, sy1)) in tiles(win.y0 - oy, win.y1 - oy, h, size.height) {
        for (_, (cx0, cx1), (sx0, sx1)) in tiles(win.x0 - ox, win.x1 - ox, w, size.width) {
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
            // Drawn in the tile's own coordinates, from its clip's corner, as Chromium (and
            // `rasterize_svg_in_tiles`) draws it: the edge clipper cuts a curve in `f32`,
            // whose rounding depends on where the origin is (a cubic cut at x = 512 in a
            // mask starting at 496 lost a pixel that the tile at 0 draws).
            let frame = Window {
                x0: clip.x0,
                y0: clip.y0,
                x1: part.x1,
                y1: part.y1,
            };
            out.extend(
                painted_in(reference, start, commands, &frame, &[true])
                    .into_iter()
                    .filter(|p| shown.contains(i64::from(p.x), i64::from(p.y))),
            );
        }
    }
    out
}

/// The clips (contour coordinates) of the tiles of `canvas` that show pixels of `bounds`
/// (a curve's control polygon's bounds) and cut it: a curve crossing the side of one of
/// them is drawn there in the parts [`super::chops::drawn_parts`] lists. Empty without a
/// canvas or on a page drawn as one tile.
pub(crate) fn cutting_clips(bounds: Rect, canvas: Option<Rect>) -> Vec<Rect> {
    let Some((page, size)) = tiled_page(canvas) else {
        return Vec::new();
    };
    let (w, h) = (page.x1 - page.x0, page.y1 - page.y0);
    let (ox, oy) = (page.x0, page.y0);
    let (x0, y0) = (bounds.x0.floor() as i64 - ox, bounds.y0.floor() as i64 - oy);
    let (x1, y1) = (bounds.x1.ceil() as i64 - ox, bounds.y1.ceil() as i64 - oy);
    let mut out = Vec::new();
    for (_, (cy0, cy1), _) in tiles(y0, y1.max(y0 + 1), h, size.height) {
        for (_, (cx0, cx1), _) in tiles(x0, x1.max(x0 + 1), w, size.width) {
            let clip = Rect::new(
                (ox + cx0) as f64,
                (oy + cy0) as f64,
                (ox + cx1) as f64,
                (oy + cy1) as f64,
            );
            let holds = clip.x0 <= bounds.x0
                && clip.y0 <= bounds.y0
                && bounds.x1 <= clip.x1
                && bounds.y1 <= clip.y1;
            if !holds {
                out.push(clip);
            }
        }
    }
    out
}

/// How far (px) [`loop_paints_nothing_in_tiles_moved`] moves a loop: twice the
/// [`super::ROBUST_SHIFT`] of whole paths (27 shared samples, conic: 8 630 commands with
/// 1/64 px and 1 pixel wrong in Chromium, 8 671 with 1/32 px and none, 8 697 with 1/16).
const TILE_SHIFT: f64 = 1.0 / 32.0;

/// Whether the closed loop `M anchor lp Z` paints no pixel centre in Chromium's tiles (see
/// [`misplaced_in_tiles`]) when moved by [`TILE_SHIFT`] each way along both axes. Where a
/// tile's side cuts a curve, the ends of the part left are off the 1/64-px grid and
/// renderers compute them each in their own floating point: a chord 0.005 px below a pixel
/// centre (by exact arithmetic) left that pixel out in tiny-skia's tile but painted it in
/// Chromium's (suits_white, conic), which moving sideways by 1/64 px did not find.
pub(crate) fn loop_paints_nothing_in_tiles_moved(
    anchor: Point,
    lp: &[PathCommand],
    canvas: Option<Rect>,
) -> bool {
    let d = TILE_SHIFT;
    [(d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d)]
        .into_iter()
        .all(|(dx, dy)| {
            let v = kurbo::Vec2::new(dx, dy);
            let moved: Vec<PathCommand> = lp.iter().map(|c| c.translated(v)).collect();
            let nothing = Reference::new(anchor + v, &[]);
            misplaced_in_tiles(&nothing, anchor + v, &moved, canvas).is_empty()
        })
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
    let (w, h) = (page.x1 - page.x0, page.y1 - page.y0);
    let size = TileSize::of_page(w, h);
    // Clip lines of one axis: (size − 2) k and (size − 2) k + 2 (k ≥ 1), below `end`.
    let clear = |lo: i64, hi: i64, origin: i64, end: i64, size: i64| {
        let step = size - 2;
        let (lo, hi) = (lo - margin - origin, hi + margin - origin);
        let crosses = |offset: i64| {
            // Some k ≥ 1 with lo < step k + offset < hi and step k + offset < end (the first
            // line above lo: the others are farther).
            let k = ((lo - offset).div_euclid(step) + 1).max(1);
            let line = k * step + offset;
            // Tile k exists when its clip starts 3 or more pixels before the end.
            line < hi && k * step + 2 < end
        };
        !crosses(0) && !crosses(2)
    };
    clear(x0, x1, page.x0, w, size.width) && clear(y0, y1, page.y0, h, size.height)
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
            let size = TileSize::of_page(cw, ch);
            // Lines of one axis: where a tile's clip starts or ends inside the page.
            let lines = |end: i64, size: i64| -> Vec<i64> {
                let mut v = Vec::new();
                // The starts and ends of the clips of the tiles `tiles` lists, inside.
                for (_, (c0, c1), _) in tiles(0, end, end, size) {
                    for l in [c0, c1] {
                        if l > 0 && l < end {
                            v.push(l);
                        }
                    }
                }
                v
            };
            let near = |lo: i64, hi: i64, origin: i64, end: i64, size: i64| {
                lines(end, size)
                    .iter()
                    .any(|&l| lo - margin - origin < l && l < hi + margin - origin)
            };
            let expected =
                !near(x0, x0 + w, ox, cw, size.width) && !near(y0, y0 + h, oy, ch, size.height);
            prop_assert_eq!(
                clear_of_tile_cuts(x0, y0, x0 + w, y0 + h, Some(canvas), margin),
                expected
            );
        }
    }

    /// The tiles of Chromium's `TilingData` (one border texel): count
    /// `max(1, 1 + (end − 3) / (T − 2))`, tile k's bounds `[(T − 2) k + 1, (T − 2) k + T − 1)`
    /// with the first from 0 and the last to the end, its clip one pixel wider each side.
    #[test]
    fn tiles_are_chromiums() {
        for size in [256i64, 512] {
            let step = size - 2;
            for end in 1..3000i64 {
                let count = (1 + (end - 3).div_euclid(step)).max(1);
                let got: Vec<_> = tiles(0, end, end, size).collect();
                assert_eq!(got.len() as i64, count, "{size} {end}");
                for (k, clip, shown) in got {
                    let lo = if k == 0 { 0 } else { step * k + 1 };
                    let hi = if k == count - 1 {
                        end
                    } else {
                        step * k + size - 1
                    };
                    assert_eq!(shown, (lo, hi), "{size} {end} {k}");
                    assert_eq!(
                        clip,
                        ((lo - 1).max(0), (hi + 1).min(end)),
                        "{size} {end} {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_pixel_is_shown_by_one_tile() {
        for size in [256i64, 320, 512] {
            for end in [1, 200, 255, 256, 509, 510, 511, 512, 1021, 1022, 3000] {
                let mut shown_by = vec![0; end as usize];
                for (_, (c0, c1), (s0, s1)) in tiles(0, end, end, size) {
                    assert!(c0 <= s0 && s1 <= c1 && c1 - c0 <= size, "{end}");
                    for r in s0..s1 {
                        shown_by[r as usize] += 1;
                    }
                }
                assert!(
                    shown_by.iter().all(|&n| n == 1),
                    "{size} {end}: {shown_by:?}"
                );
            }
        }
    }

    /// The pages measured in Chromium 156 (see the module's documentation): the rows where
    /// tiles cut paths, and single tiles.
    #[test]
    fn tile_sizes_are_the_measured_ones() {
        let cut_rows = |w: i64, h: i64| -> Vec<i64> {
            let size = TileSize::of_page(w, h);
            let mut v: Vec<i64> = tiles(0, h, h, size.height)
                .flat_map(|(_, (c0, c1), _)| [c0, c1])
                .filter(|&l| l > 0 && l < h)
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        for (w, h) in [(600, 600), (256, 1200), (300, 1200)] {
            let rows = cut_rows(w, h);
            assert!(rows.starts_with(&[254, 256, 508, 510]), "{w}×{h}: {rows:?}");
            assert!(!one_tile(w, h));
        }
        for (w, h) in [(200, 1200), (255, 1200)] {
            assert_eq!(cut_rows(w, h), vec![510, 512, 1020, 1022], "{w}×{h}");
            assert_eq!(TileSize::of_page(w, h).width, 256);
            assert!(!one_tile(w, h));
        }
        for (w, h) in [(300, 300), (511, 511), (200, 500), (256, 256), (1, 1)] {
            assert!(one_tile(w, h), "{w}×{h}");
            assert!(cut_rows(w, h).is_empty(), "{w}×{h}");
        }
        // Low pages: tiles 512 wide, one tile tall.
        assert_eq!(
            TileSize::of_page(1200, 200),
            TileSize {
                width: 512,
                height: 256
            }
        );
        assert!(!one_tile(1200, 200) && !one_tile(513, 200) && one_tile(512, 200));
        assert!(!one_tile(512, 512) && !one_tile(257, 512) && !one_tile(512, 300));
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

    /// The same wedge on a page 200 px wide, as measured in Chromium: its 512-px-tall
    /// tiles cut it at row 512, not at 256.
    #[test]
    fn narrow_pages_are_cut_at_512() {
        let v = |dy: f64| kurbo::Vec2::new(100.0 - 2393.0, dy);
        let wedge = |dy: f64| {
            let (a, b) = (
                Point::new(2393.1875, 250.5625) + v(dy),
                Point::new(2394.5, 266.1875) + v(dy),
            );
            let start = Point::new(2385.0, 250.5625) + v(dy);
            let cmds = vec![
                PathCommand::Line(Point::new(2385.0, 266.1875) + v(dy)),
                PathCommand::Line(b),
                PathCommand::Line(a),
            ];
            // The pixels whose centre is left of the segment, rows 251 to 265 (moved).
            let right_end = |y: f64| {
                let cy = y + 0.5;
                let x = a.x + (b.x - a.x) * (cy - a.y) / (b.y - a.y);
                (x - 0.5).ceil()
            };
            let (x0, y0) = (2385.0 + v(dy).x, 251.0 + dy);
            let mut rc = vec![
                PathCommand::Line(Point::new(x0, y0 + 15.0)),
                PathCommand::Line(Point::new(right_end(y0 + 14.0), y0 + 15.0)),
            ];
            for r in (0..15).rev() {
                let y = y0 + f64::from(r);
                rc.push(PathCommand::Line(Point::new(right_end(y), y)));
                if r > 0 {
                    rc.push(PathCommand::Line(Point::new(right_end(y - 1.0), y)));
                }
            }
            (start, cmds, Reference::new(Point::new(x0, y0), &rc))
        };
        let narrow = Some(Rect::new(0.0, 0.0, 200.0, 1200.0));
        let wide = Some(Rect::new(0.0, 0.0, 600.0, 1200.0));
        let pixels = |(start, cmds, reference): (Point, Vec<PathCommand>, Reference), canvas| {
            misplaced_in_tiles(&reference, start, &cmds, canvas)
                .iter()
                .map(|p| (p.x, p.y))
                .collect::<Vec<_>>()
        };
        // Across row 256: cut on a wide page, not on the narrow one.
        assert_eq!(pixels(wedge(0.0), wide), vec![(100, 254)]);
        assert!(pixels(wedge(0.0), narrow).is_empty());
        // Across row 512: cut on the narrow page (tile 0's clip ends there).
        assert_eq!(pixels(wedge(256.0), narrow), vec![(100, 510)]);
    }

    #[test]
    fn clips_that_cut_a_curve() {
        // A page 150 px tall has tiles 512 px wide: clips [0, 512) and [510, 574).
        let page = Some(Rect::new(0.0, 0.0, 574.0, 150.0));
        let across = Rect::new(490.5, 15.3, 517.7, 24.5);
        assert_eq!(
            cutting_clips(across, page),
            vec![
                Rect::new(0.0, 0.0, 512.0, 150.0),
                Rect::new(510.0, 0.0, 574.0, 150.0)
            ]
        );
        // Inside the first tile and away from the second's border: nothing cuts it.
        assert!(cutting_clips(Rect::new(400.0, 15.0, 505.0, 30.0), page).is_empty());
        // A page drawn as one tile, or no page: nothing either.
        let small = Some(Rect::new(0.0, 0.0, 300.0, 300.0));
        assert!(cutting_clips(Rect::new(100.0, 100.0, 290.0, 290.0), small).is_empty());
        assert!(cutting_clips(across, None).is_empty());
    }
}
