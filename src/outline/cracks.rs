//! Pixel cracks: the sides a contour pixel shares with the background beside it, the exact
//! drawing of pieces without a usable curve.

use crate::decompose::Piece;
use crate::pixel::Pixel;
use kurbo::Point;

/// The centre of a pixel in SVG space.
pub(crate) fn centre(p: Pixel) -> Point {
    Point::new(f64::from(p.x) + 0.5, f64::from(p.y) + 0.5)
}

/// The side of pixel `p` facing the 4-direction `d` (0 right, 2 down, 4 left, 6 up),
/// traversed with the pixel on its left (counter-clockwise on screen).
fn side(p: Pixel, d: u8) -> [Point; 2] {
    let (x, y) = (f64::from(p.x), f64::from(p.y));
    match d {
        0 => [Point::new(x + 1.0, y + 1.0), Point::new(x + 1.0, y)],
        6 => [Point::new(x + 1.0, y), Point::new(x, y)],
        4 => [Point::new(x, y), Point::new(x, y + 1.0)],
        _ => [Point::new(x, y + 1.0), Point::new(x + 1.0, y + 1.0)],
    }
}

/// The crack corners of `cur` between `prev` and `next`: its sides facing the 4-neighbours on
/// the right of the walk, counter-clockwise on screen from the side after `prev` to the side
/// before `next`. A U-turn (`prev == next`) gives every side but the one facing them; `None`
/// for `prev`/`next` (no neighbours: one-pixel contour) or non-adjacent input gives the whole
/// square.
fn crack_corners(prev: Option<Pixel>, cur: Pixel, next: Option<Pixel>, out: &mut Vec<Point>) {
    // At most 7 directions (no allocation: this runs for every pixel of every junction).
    let mut dirs = [0u8; 8];
    let count = match (
        prev.and_then(|p| cur.direction_to(p)),
        next.and_then(|q| cur.direction_to(q)),
    ) {
        (Some(a), Some(b)) => {
            let span = match (a + 8 - b) % 8 {
                0 => 8,
                s => s,
            };
            for k in 1..span {
                dirs[usize::from(k - 1)] = (a + 8 - k) % 8;
            }
            usize::from(span - 1)
        }
        _ => {
            dirs[..4].copy_from_slice(&[6, 4, 2, 0]);
            4
        }
    };
    for &d in dirs[..count].iter().filter(|&&d| d % 2 == 0) {
        for q in side(cur, d) {
            if out.last() != Some(&q) {
                out.push(q);
            }
        }
    }
}

/// Crack corners of the pixels `first..=last` of a closed contour.
pub(crate) fn crack_polyline(points: &[Pixel], first: usize, last: usize) -> Vec<Point> {
    let n = points.len();
    if n == 0 {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(4 * (last.min(n - 1) + 1).saturating_sub(first) + 4);
    for i in first..=last.min(n - 1) {
        let (prev, next) = if n == 1 {
            (None, None)
        } else {
            (Some(points[(i + n - 1) % n]), Some(points[(i + 1) % n]))
        };
        crack_corners(prev, points[i], next, &mut out);
    }
    out
}

/// True when the pieces cover `0..n` consecutively.
pub(crate) fn pieces_valid(n: usize, pieces: &[Piece]) -> bool {
    let mut next = 0;
    for p in pieces {
        if p.first != next || p.last < p.first || p.last >= n {
            return false;
        }
        next = p.last + 1;
    }
    next == n && !pieces.is_empty()
}
