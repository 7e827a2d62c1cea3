//! tiny-skia's line clipper for fills (its `line_clipper.rs`, from Skia's `SkLineClipper`),
//! for [`super::scan`]'s fills of paths that leave their window: what tiny-skia's edge
//! clipper makes of each line when a path's bounds are not inside the mask.
//!
//! A line is cut where it crosses the mask's top and bottom (the parts beyond are dropped)
//! and its sides (the parts beyond become vertical lines on the side they lie beyond, which
//! keep each row's winding); the new ends are computed in `f64` from the line's `f32` ends,
//! pinned between them and rounded to `f32`, exactly as tiny-skia computes them, so the
//! edges built from the parts are tiny-skia's.

use tiny_skia_path::{Point as SkPoint, Scalar};

/// The parts of the line `src` clipped to the mask `[0, w] × [0, h]` as tiny-skia's edge
/// clipper clips it for a fill (nothing culled to the right), each given to `part` from
/// its start to its end, in the line's direction.
pub(super) fn clip_line(
    src: [SkPoint; 2],
    (w, h): (f32, f32),
    mut part: impl FnMut(SkPoint, SkPoint),
) {
    let (left, top, right, bottom) = (0.0f32, 0.0f32, w, h);
    let (i0, i1) = if src[0].y < src[1].y { (0, 1) } else { (1, 0) };
    // Wholly above or below.
    if src[i1].y <= top || src[i0].y >= bottom {
        return;
    }
    // Chopped in y to one segment.
    let mut tmp = src;
    if src[i0].y < top {
        tmp[i0] = SkPoint::from_xy(sect_with_horizontal(&src, top), top);
    }
    if tmp[i1].y > bottom {
        tmp[i1] = SkPoint::from_xy(sect_with_horizontal(&src, bottom), bottom);
    }
    // Then into one to three segments within the sides, from left to right.
    let (i0, i1, mut reverse) = if src[0].x < src[1].x {
        (0, 1, false)
    } else {
        (1, 0, true)
    };
    let mut result = [SkPoint::zero(); 4];
    let count = if tmp[i1].x <= left || tmp[i0].x >= right {
        // Wholly beyond a side: the vertical line there, in the line's own order.
        let x = if tmp[i1].x <= left { left } else { right };
        tmp[0].x = x;
        tmp[1].x = x;
        reverse = false;
        result[..2].copy_from_slice(&tmp);
        2
    } else {
        let mut at = 0;
        if tmp[i0].x < left {
            result[at] = SkPoint::from_xy(left, tmp[i0].y);
            at += 1;
            result[at] = SkPoint::from_xy(left, sect_clamp_with_vertical(&tmp, left));
        } else {
            result[at] = tmp[i0];
        }
        at += 1;
        if tmp[i1].x > right {
            result[at] = SkPoint::from_xy(right, sect_clamp_with_vertical(&tmp, right));
            at += 1;
            result[at] = SkPoint::from_xy(right, tmp[i1].y);
        } else {
            result[at] = tmp[i1];
        }
        at + 1
    };
    if reverse {
        result[..count].reverse();
    }
    for k in 1..count {
        part(result[k - 1], result[k]);
    }
}

/// The x where the line `src` crosses the row `y` (tiny-skia's `sect_with_horizontal`).
fn sect_with_horizontal(src: &[SkPoint; 2], y: f32) -> f32 {
    let dy = src[1].y - src[0].y;
    if dy.is_nearly_zero() {
        src[0].x.ave(src[1].x)
    } else {
        let (x0, y0) = (f64::from(src[0].x), f64::from(src[0].y));
        let (x1, y1) = (f64::from(src[1].x), f64::from(src[1].y));
        let x = x0 + (f64::from(y) - y0) * (x1 - x0) / (y1 - y0);
        pin(x, x0, x1) as f32
    }
}

/// The y where the line `src` crosses the column `x`, pinned between its ends (tiny-skia's
/// `sect_clamp_with_vertical`).
fn sect_clamp_with_vertical(src: &[SkPoint; 2], x: f32) -> f32 {
    let dx = src[1].x - src[0].x;
    let y = if dx.is_nearly_zero() {
        src[0].y.ave(src[1].y)
    } else {
        let (x0, y0) = (f64::from(src[0].x), f64::from(src[0].y));
        let (x1, y1) = (f64::from(src[1].x), f64::from(src[1].y));
        (y0 + (f64::from(x) - x0) * (y1 - y0) / (x1 - x0)) as f32
    };
    pin(y, src[0].y, src[1].y)
}

/// `value` within the limits, given in either order.
fn pin<T: PartialOrd>(value: T, a: T, b: T) -> T {
    let (lo, hi) = if b < a { (b, a) } else { (a, b) };
    if value < lo {
        lo
    } else if value > hi {
        hi
    } else {
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(a: (f32, f32), b: (f32, f32), w: f32, h: f32) -> Vec<[(f32, f32); 2]> {
        let mut out = Vec::new();
        clip_line(
            [SkPoint::from_xy(a.0, a.1), SkPoint::from_xy(b.0, b.1)],
            (w, h),
            |p, q| out.push([(p.x, p.y), (q.x, q.y)]),
        );
        out
    }

    #[test]
    fn lines_inside_stay() {
        assert_eq!(
            parts((1.0, 2.0), (5.5, 7.25), 10.0, 10.0),
            [[(1.0, 2.0), (5.5, 7.25)]]
        );
        assert_eq!(
            parts((5.5, 7.25), (1.0, 2.0), 10.0, 10.0),
            [[(5.5, 7.25), (1.0, 2.0)]]
        );
        // On the sides too.
        assert_eq!(
            parts((0.0, 0.0), (10.0, 10.0), 10.0, 10.0),
            [[(0.0, 0.0), (10.0, 10.0)]]
        );
    }

    #[test]
    fn above_and_below_go_beyond_the_sides_stand() {
        assert!(parts((1.0, -3.0), (8.0, -0.5), 10.0, 10.0).is_empty());
        assert!(parts((1.0, 10.0), (8.0, 12.0), 10.0, 10.0).is_empty());
        // Beyond the left side, downwards: the vertical line on it, same direction.
        assert_eq!(
            parts((-4.0, 1.0), (-2.0, 6.0), 10.0, 10.0),
            [[(0.0, 1.0), (0.0, 6.0)]]
        );
        // Beyond the right side, upwards, cut at the top.
        assert_eq!(
            parts((12.0, 6.0), (14.0, -2.0), 10.0, 10.0),
            [[(10.0, 6.0), (10.0, 0.0)]]
        );
    }

    #[test]
    fn a_line_across_is_cut_where_it_crosses() {
        // From (−2, 1) to (8, 6): crosses x = 0 at y = 2.
        assert_eq!(
            parts((-2.0, 1.0), (8.0, 6.0), 10.0, 10.0),
            [[(0.0, 1.0), (0.0, 2.0)], [(0.0, 2.0), (8.0, 6.0)]]
        );
        // Backwards: the same parts reversed, in reverse order.
        assert_eq!(
            parts((8.0, 6.0), (-2.0, 1.0), 10.0, 10.0),
            [[(8.0, 6.0), (0.0, 2.0)], [(0.0, 2.0), (0.0, 1.0)]]
        );
        // Through the left side and the bottom: (−5, 0) to (15, 20) in a 10 × 8 mask, cut
        // at y = 8 (x = 3) first.
        assert_eq!(
            parts((-5.0, 0.0), (15.0, 20.0), 10.0, 8.0),
            [[(0.0, 0.0), (0.0, 5.0)], [(0.0, 5.0), (3.0, 8.0)]]
        );
        // Through both sides: three parts.
        assert_eq!(
            parts((-5.0, 0.0), (15.0, 4.0), 10.0, 8.0),
            [
                [(0.0, 0.0), (0.0, 1.0)],
                [(0.0, 1.0), (10.0, 3.0)],
                [(10.0, 3.0), (10.0, 4.0)]
            ]
        );
    }
}
