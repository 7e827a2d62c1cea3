//! The pixels around one contour for its smooth outline: which are free (within ν of the
//! border) and, for the others, on which side of the contour they lie; and the pixel
//! centres a closed polyline winds round.

use crate::bitmap::Band;
use kurbo::Point;

/// A pixel's label.
const FREE: u8 = 0;
/// A constraint pixel the contour's crack polygon winds round.
const INSIDE: u8 = 1;
/// A constraint pixel outside the contour's crack polygon.
const OUTSIDE: u8 = 2;

/// Labels of the pixels in a window round a contour.
pub(crate) struct Cells {
    x0: i64,
    y0: i64,
    w: i64,
    h: i64,
    label: Vec<u8>,
    /// The sign of `cross(crack edge, centre − edge start)` for pixels inside the crack
    /// polygon near an edge (−1 when the inside is on the left on screen).
    inside_sign: i8,
}

impl Cells {
    /// The labels round the closed crack polygon `corners` (pixel corners, unit steps), in
    /// its bounding box grown by `margin` pixels.
    pub(crate) fn new(corners: &[Point], band: &Band, margin: i64) -> Cells {
        let (mut lo, mut hi) = ([i64::MAX; 2], [i64::MIN; 2]);
        for p in corners {
            let (x, y) = (p.x.round() as i64, p.y.round() as i64);
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
        if corners.is_empty() {
            lo = [0, 0];
            hi = [0, 0];
        }
        let (x0, y0) = (lo[0] - margin, lo[1] - margin);
        let (w, h) = (hi[0] - lo[0] + 2 * margin, hi[1] - lo[1] + 2 * margin);
        let mut label = vec![OUTSIDE; (w * h) as usize];
        for_each_inside(corners, x0, y0, w, h, |x, y| {
            label[((y - y0) * w + (x - x0)) as usize] = INSIDE;
            true
        });
        for y in 0..h {
            for x in 0..w {
                if band.free(x0 + x, y0 + y) {
                    label[(y * w + x) as usize] = FREE;
                }
            }
        }
        // The side of the first edge the polygon winds round.
        let mut inside_sign = -1;
        if corners.len() >= 2 {
            let (a, b) = (corners[0], corners[1]);
            let d = b - a;
            // The centre beside the edge with cross(d, c − a) < 0.
            let c = a.midpoint(b) + kurbo::Vec2::new(d.y, -d.x) * 0.5;
            let (cx, cy) = (c.x.floor() as i64, c.y.floor() as i64);
            let inside = corners.len() > 2 && {
                let mut hit = false;
                for_each_inside(corners, cx, cy, 1, 1, |_, _| {
                    hit = true;
                    false
                });
                hit
            };
            inside_sign = if inside { -1 } else { 1 };
        }
        Cells {
            x0,
            y0,
            w,
            h,
            label,
            inside_sign,
        }
    }

    fn get(&self, x: i64, y: i64) -> u8 {
        let (cx, cy) = (x - self.x0, y - self.y0);
        if cx < 0 || cy < 0 || cx >= self.w || cy >= self.h {
            return FREE;
        }
        self.label[(cy * self.w + cx) as usize]
    }

    /// For a constraint pixel, the sign `cross(edge, centre − edge start)` must have for an
    /// edge of the outline passing by it; `None` for a free pixel (or outside the window).
    pub(crate) fn required_sign(&self, x: i64, y: i64) -> Option<i8> {
        match self.get(x, y) {
            INSIDE => Some(self.inside_sign),
            OUTSIDE => Some(-self.inside_sign),
            _ => None,
        }
    }

    /// True when the closed polyline `poly` winds round the centre of no constraint pixel.
    pub(crate) fn region_free(&self, poly: &[Point]) -> bool {
        let mut free = true;
        for_each_inside(poly, self.x0, self.y0, self.w, self.h, |x, y| {
            if self.get(x, y) != FREE {
                free = false;
            }
            free
        });
        free
    }
}

/// Calls `visit(x, y)` for the pixels of the window `x0 ≤ x < x0 + w`, `y0 ≤ y < y0 + h`
/// whose centre the closed polyline `poly` winds round (nonzero; a centre on the polyline
/// counts as wound round), row by row, until `visit` returns false.
pub(crate) fn for_each_inside(
    poly: &[Point],
    x0: i64,
    y0: i64,
    w: i64,
    h: i64,
    mut visit: impl FnMut(i64, i64) -> bool,
) {
    let n = poly.len();
    if n < 2 || w <= 0 || h <= 0 {
        return;
    }
    // Only the rows the polyline spans.
    let (ymin, ymax) = poly
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.y), b.max(p.y))
        });
    if !(ymin.is_finite() && ymax.is_finite()) {
        return;
    }
    let top = ((ymin - 0.5).floor() as i64).max(y0);
    let bottom = ((ymax - 0.5).ceil() as i64 + 1).min(y0 + h);
    if top >= bottom {
        return;
    }
    let (y0, h) = (top, bottom - top);
    // Crossings of each row's centre line, bucketed by row.
    let mut rows: Vec<Vec<(f64, i32)>> = vec![Vec::new(); h as usize];
    for k in 0..n {
        let (p, q) = (poly[k], poly[(k + 1) % n]);
        if p.y == q.y {
            continue;
        }
        let (ylo, yhi) = (p.y.min(q.y), p.y.max(q.y));
        // Rows whose centre y + 0.5 lies in [ylo, yhi).
        let r0 = ((ylo - 0.5).ceil() as i64).max(y0);
        let r1 = (((yhi - 0.5).ceil() as i64) - 1).min(y0 + h - 1);
        let dir = if q.y > p.y { 1 } else { -1 };
        for r in r0..=r1 {
            let yc = r as f64 + 0.5;
            let x = p.x + (yc - p.y) * (q.x - p.x) / (q.y - p.y);
            rows[(r - y0) as usize].push((x, dir));
        }
    }
    for (ri, row) in rows.iter_mut().enumerate() {
        if row.is_empty() {
            continue;
        }
        row.sort_by(|a, b| a.0.total_cmp(&b.0));
        let y = y0 + ri as i64;
        let mut wind = 0i32;
        for k in 0..row.len() {
            let (xa, d) = row[k];
            let before = wind;
            wind += d;
            // Centres on a crossing count as inside.
            let on = |x: i64| (x as f64 + 0.5 - xa).abs() < 1e-12;
            let xa_cell = (xa - 0.5).ceil() as i64;
            if before == 0 && on(xa_cell) && xa_cell >= x0 && xa_cell < x0 + w && !visit(xa_cell, y)
            {
                return;
            }
            if wind != 0 {
                let xb = row.get(k + 1).map_or(xa, |r| r.0);
                // Centres x + 0.5 in (xa, xb].
                let c0 = ((xa - 0.5).floor() as i64 + 1).max(x0);
                let c1 = ((xb - 0.5).floor() as i64).min(x0 + w - 1);
                for x in c0..=c1 {
                    if !visit(x, y) {
                        return;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_inside_a_triangle_and_a_square() {
        let sq = [
            Point::new(1.0, 1.0),
            Point::new(1.0, 4.0),
            Point::new(4.0, 4.0),
            Point::new(4.0, 1.0),
        ];
        let mut got = Vec::new();
        for_each_inside(&sq, 0, 0, 6, 6, |x, y| {
            got.push((x, y));
            true
        });
        got.sort();
        let want: Vec<(i64, i64)> = (1..4).flat_map(|x| (1..4).map(move |y| (x, y))).collect();
        assert_eq!(got, want);
        // A triangle: brute force by winding.
        let tri = [
            Point::new(0.3, 0.2),
            Point::new(7.7, 2.9),
            Point::new(2.1, 6.6),
        ];
        let mut got = Vec::new();
        for_each_inside(&tri, -2, -2, 12, 12, |x, y| {
            got.push((x, y));
            true
        });
        let mut want = Vec::new();
        for y in -2..10 {
            for x in -2..10 {
                let c = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let s = |a: Point, b: Point| (b - a).cross(c - a);
                let (s0, s1, s2) = (s(tri[0], tri[1]), s(tri[1], tri[2]), s(tri[2], tri[0]));
                if (s0 > 0.0 && s1 > 0.0 && s2 > 0.0) || (s0 < 0.0 && s1 < 0.0 && s2 < 0.0) {
                    want.push((x, y));
                }
            }
        }
        got.sort();
        want.sort();
        assert_eq!(got, want);
    }
}
