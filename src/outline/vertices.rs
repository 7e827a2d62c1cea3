//! Shared vertices of consecutive straight segments of the exact polygon.
//!
//! Two digital straight segments drawn along their largest-margin lines often do not meet
//! near their junction: consecutive lines of a gently curving border are nearly parallel
//! and cross pixels away. Bridging the two line ends with a short segment costs a command
//! and draws a notch. Instead both segments may end at one shared vertex `V` off their
//! lines, as long as each segment, now from its start vertex to `V` (or from `V` to its end
//! vertex), still has its pixel centres and the foreground beside them strictly on one side
//! and the background beside them strictly on the other ([`separates`], exact for points
//! on the grid). Candidates, in order: half-way between the two line ends, the crossing of
//! the lines (up to 4 px away), the pixel corner between the two end pixels, either line
//! end; then the crossings of lines turned about the segments' other ends, within their
//! *cones* of separating directions (each segment's line may turn about its fixed end as
//! long as it keeps its sides apart; up to 4 px from the junction). A centre within 3/64
//! px of a segment along its row must also lie on its side where tiny-skia's fixed point
//! puts the segment's crossing of that row ([`row_crossing`]), with the segment moved by
//! 1/64 px either way too, as the render check moves it. The render check has the last
//! word.

use super::cracks::{centre, first_crack_corner, last_crack_corner};
use super::ROBUST_SHIFT;
use crate::decompose::neighbour_sides;
use crate::pixel::Pixel;
use crate::pixel_flags::StretchSets;
use kurbo::{Point, Vec2};

/// Largest distance (pixels) from the junction of the crossing of two segments' lines tried
/// as their shared vertex.
const MAX_CROSSING_DISTANCE: f64 = 4.0;

/// The centres a segment must separate: its pixels and the foreground beside them (`low`),
/// the background beside them (`high`).
pub(crate) struct Sides {
    low: Vec<Point>,
    high: Vec<Point>,
}

impl Sides {
    /// The sides of the points `first..=last` of a closed contour.
    pub(crate) fn of(points: &[Pixel], first: usize, last: usize) -> Sides {
        let (low, high) = side_pixels(points, first, last);
        Sides {
            low: low.into_iter().map(centre).collect(),
            high: high.into_iter().map(centre).collect(),
        }
    }
}

/// The pixels a drawing of the points `first..=last` of a closed contour must keep apart:
/// those points and the foreground beside them (`low`, first the points in order), and the
/// background beside every one of them, the two ends included (`high`), each once.
pub(crate) fn side_pixels(points: &[Pixel], first: usize, last: usize) -> (Vec<Pixel>, Vec<Pixel>) {
    let n = points.len();
    let len = last + 1 - first;
    let mut seen = StretchSets::of(&points[first..=last]);
    let (mut low, mut high) = (Vec::with_capacity(2 * len), Vec::with_capacity(len + 4));
    for k in first..=last {
        low.push(points[k]);
        let (prev, next) = (points[(k + n - 1) % n], points[(k + 1) % n]);
        if let Some(sides) = neighbour_sides(prev, points[k], next) {
            for (q, right, left) in sides {
                if seen.is_point(q) {
                    continue;
                }
                if right && seen.first_right(q) {
                    high.push(q);
                }
                if left && !right && seen.first_left(q) {
                    low.push(q);
                }
            }
        }
    }
    (low, high)
}

/// True when the segment `u → v` has every `low` centre strictly on one side of its line
/// and every `high` centre strictly on the other, counting only the centres whose
/// projection falls on the segment (the others are the neighbouring segments' to
/// separate). With grid points the signs are exact.
pub(crate) fn separates(u: Point, v: Point, sides: &Sides) -> bool {
    let d = v - u;
    let len2 = d.hypot2();
    if len2 == 0.0 {
        return false;
    }
    let on_span = |p: &Point| {
        let t = (*p - u).dot(d);
        (0.0..=len2).contains(&t)
    };
    let side = |p: &Point| d.cross(*p - u);
    // Along its row, a centre within 1/64 px of the line counts as on it.
    let clear = d.y.abs() / 64.0;
    // Closer than 3/64 px along its row, the centre must also be on its side where
    // tiny-skia puts the segment's crossing of the row (rounded to 1/64 px), with the
    // segment where it is and moved by 1/64 px either way (the render check's moves).
    let near = 3.0 * clear;
    let rendered_right = |p: &Point, s: f64| {
        if s.abs() >= near {
            return true;
        }
        // Right of the line along the row (larger x) when `s · d.y < 0`.
        let right = s * d.y < 0.0;
        let (row, column) = (p.y.floor() as i64, p.x.floor() as i64);
        [0.0, ROBUST_SHIFT, -ROBUST_SHIFT].iter().all(|&m| {
            let shift = Vec2::new(m, 0.0);
            match row_crossing(u + shift, v + shift, row) {
                Some(x) => ((x + 0x8000) >> 16 <= column) == right,
                None => true,
            }
        })
    };
    let (mut low_sign, mut high_sign) = (0.0f64, 0.0f64);
    for p in sides.low.iter().filter(|p| on_span(p)) {
        let s = side(p);
        if s.abs() <= clear || s * low_sign < 0.0 || !rendered_right(p, s) {
            return false;
        }
        low_sign = s.signum();
    }
    for p in sides.high.iter().filter(|p| on_span(p)) {
        let s = side(p);
        if s.abs() <= clear || s * high_sign < 0.0 || s * low_sign > 0.0 || !rendered_right(p, s) {
            return false;
        }
        high_sign = s.signum();
    }
    true
}

/// Where tiny-skia's scan converter puts the line `a → b` on the row of pixel centres
/// `y = row + 0.5` (16.16 fixed point, as its `LineEdge` steps it: the points in 1/64 px,
/// the slope and the first row's crossing truncated), or `None` when it does not draw the
/// line on that row. A pixel whose column `c` has `round(x) <= c` lies right of it.
fn row_crossing(a: Point, b: Point, row: i64) -> Option<i64> {
    // tiny-skia converts `f32` coordinates to 1/64 px, truncating (exact on the grid).
    let fdot6 = |v: f64| i64::from((v as f32 * 64.0) as i32);
    let (mut x0, mut y0, mut x1, mut y1) = (fdot6(a.x), fdot6(a.y), fdot6(b.x), fdot6(b.y));
    if y0 > y1 {
        std::mem::swap(&mut x0, &mut x1);
        std::mem::swap(&mut y0, &mut y1);
    }
    let (top, bottom) = ((y0 + 32) >> 6, (y1 + 32) >> 6);
    if top == bottom || row < top || row >= bottom {
        return None;
    }
    let slope = (((x1 - x0) << 16) / (y1 - y0)).clamp(i64::from(i32::MIN), i64::from(i32::MAX));
    let dy = (top << 6) + 32 - y0;
    let x = (x0 + ((slope * dy) >> 16)) << 10;
    Some(x + slope * (row - top))
}

/// The shared vertex of segment `j` (from `u`, its start vertex) and segment `k` (to `w`,
/// its end vertex) at their junction between contour points `a` (last of `j`) and `b`
/// (first of `k`), where `j` ends at `end_j` and `k` starts at `start_k` on their own lines;
/// `snap` puts candidates on the grid. `None` when no candidate keeps both separating.
#[allow(clippy::too_many_arguments)]
pub(crate) fn shared_vertex(
    points: &[Pixel],
    a: usize,
    b: usize,
    u: Point,
    end_j: Point,
    start_k: Point,
    w: Point,
    sides_j: &Sides,
    sides_k: &Sides,
    snap: impl Fn(Point) -> Point,
) -> Option<Point> {
    let corner = match (
        last_crack_corner(points, a, a),
        first_crack_corner(points, b, b),
    ) {
        (Some(p), Some(q)) => Some(p.midpoint(q)),
        _ => None,
    };
    // Where the two segments' lines cross, if not far beyond the junction.
    let crossing = line_crossing(u, end_j - u, start_k, w - start_k)
        .map(|(t, _)| u + (end_j - u) * t)
        .filter(|x| (*x - end_j.midpoint(start_k)).hypot() <= MAX_CROSSING_DISTANCE);
    let candidates = [
        Some(end_j.midpoint(start_k)),
        crossing,
        corner,
        Some(end_j),
        Some(start_k),
    ];
    let ok = |v: Point| separates(u, v, sides_j) && separates(v, w, sides_k);
    if let Some(v) = candidates.into_iter().flatten().map(&snap).find(|&v| ok(v)) {
        return Some(v);
    }
    // Where the lines through `u` and through `w` that separate their segments' sides
    // cross: each line may turn within its cone of separating directions.
    let junction = end_j.midpoint(start_k);
    let cj = cone(u, end_j - u, sides_j)?;
    let ck = cone(w, start_k - w, sides_k)?;
    let mut found: Vec<(f64, Point)> = Vec::new();
    for fj in [0.5, 0.25, 0.75] {
        for fk in [0.5, 0.25, 0.75] {
            let dj = cj.direction(fj);
            let dk = ck.direction(fk);
            // `u + s dj = w + t dk`, ahead of both apexes (`dk` points from `w` back to the
            // junction).
            let Some((s, t)) = line_crossing(u, dj, w, dk) else {
                continue;
            };
            if s <= 0.0 || t <= 0.0 {
                continue;
            }
            let x = snap(u + dj * s);
            let d = (x - junction).hypot();
            if d <= MAX_CROSSING_DISTANCE {
                found.push((d, x));
            }
        }
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    found.into_iter().map(|(_, v)| v).find(|&v| ok(v))
}

/// The parameters `(s, t)` where the lines `p + s dp` and `q + t dq` cross; `None` when
/// they are parallel.
fn line_crossing(p: Point, dp: Vec2, q: Point, dq: Vec2) -> Option<(f64, f64)> {
    let den = dp.cross(dq);
    (den != 0.0).then(|| ((q - p).cross(dq) / den, (q - p).cross(dp) / den))
}

/// The directions from an apex along which a line keeps a segment's two sides apart: the
/// open wedge from `lower` counter-clockwise to `upper` (in the `x`, `y` frame).
struct Cone {
    lower: Vec2,
    upper: Vec2,
}

impl Cone {
    /// The direction at about fraction `f` of the wedge, from `lower`.
    fn direction(&self, f: f64) -> Vec2 {
        self.lower.normalize() * (1.0 - f) + self.upper.normalize() * f
    }
}

/// The cone of separating directions from `apex` for `sides`, `reference` a direction that
/// separates them (its side tells which set lies left); only the centres ahead of the apex
/// count, so every direction compared lies within a quarter turn of `reference` and the
/// cross product orders them. `None` when the cone is empty.
fn cone(apex: Point, reference: Vec2, sides: &Sides) -> Option<Cone> {
    let sigma = sides
        .low
        .iter()
        .map(|p| reference.cross(*p - apex))
        .find(|c| *c != 0.0)?
        .signum();
    // A quarter turn either way from the reference.
    let (mut lower, mut upper) = (
        Vec2::new(reference.y, -reference.x),
        Vec2::new(-reference.y, reference.x),
    );
    for (set, left) in [(&sides.low, sigma > 0.0), (&sides.high, sigma < 0.0)] {
        for p in set.iter() {
            let v = *p - apex;
            if v.dot(reference) <= 0.0 {
                continue;
            }
            // A centre left of the line (counter-clockwise) bounds the direction above,
            // one right of it below.
            if left {
                if upper.cross(v) < 0.0 {
                    upper = v;
                }
            } else if lower.cross(v) > 0.0 {
                lower = v;
            }
        }
    }
    (lower.cross(upper) > 0.0).then_some(Cone { lower, upper })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        /// `row_crossing` says which pixels tiny-skia fills beside a segment: the segment
        /// closed into a polygon reaching far right (its other edges vertical and
        /// horizontal, off the row centres) fills exactly the pixels of the row right of
        /// the crossing.
        #[test]
        fn row_crossing_is_where_tiny_skia_cuts_the_row(
            x0 in 32i32..480, y0 in 0i32..512, x1 in 32i32..480, y1 in 0i32..512,
        ) {
            prop_assume!(y0 != y1);
            // Points on the 1/16 px grid, inside a 40 × 40 px mask.
            let (a, b) = (
                Point::new(f64::from(x0) / 16.0, f64::from(y0) / 16.0 + 4.0),
                Point::new(f64::from(x1) / 16.0, f64::from(y1) / 16.0 + 4.0),
            );
            let mut pb = tiny_skia::PathBuilder::new();
            pb.move_to(a.x as f32, a.y as f32);
            pb.line_to(b.x as f32, b.y as f32);
            pb.line_to(38.0, b.y as f32);
            pb.line_to(38.0, a.y as f32);
            pb.close();
            let path = pb.finish().unwrap();
            let mut mask = tiny_skia::Mask::new(40, 40).unwrap();
            mask.fill_path(
                &path,
                tiny_skia::FillRule::Winding,
                false,
                tiny_skia::Transform::identity(),
            );
            let mut crossed = 0;
            for row in 0..40i64 {
                let Some(x) = row_crossing(a, b, row) else { continue };
                crossed += 1;
                for column in 0..38i64 {
                    let filled = mask.data()[(row * 40 + column) as usize] != 0;
                    prop_assert_eq!(
                        filled,
                        (x + 0x8000) >> 16 <= column,
                        "row {} column {} crossing {}", row, column, x as f64 / 65536.0
                    );
                }
            }
            // Every row whose centre lies strictly between the ends is crossed.
            let (lo, hi) = (a.y.min(b.y), a.y.max(b.y));
            let inner = (0..40).filter(|&r| f64::from(r) + 0.5 > lo + 1.0 / 64.0 && f64::from(r) + 0.5 < hi).count();
            prop_assert!(crossed >= inner);
        }
    }

    /// The cone from an apex holds the directions that keep the two sides apart, and is
    /// empty when no line from there does.
    #[test]
    fn cones_hold_the_separating_directions() {
        let sides = Sides {
            low: vec![Point::new(0.5, 0.5), Point::new(1.5, 0.5)],
            high: vec![Point::new(0.5, 1.5), Point::new(1.5, 1.5)],
        };
        // Right of the apex (0, 1), the low centres above and the high ones below: the
        // cone holds the directions between the lines to (1.5, 0.5) and to (1.5, 1.5).
        let c = cone(Point::new(0.0, 1.0), Vec2::new(1.0, 0.0), &sides).unwrap();
        for f in [0.25, 0.5, 0.75] {
            let d = c.direction(f);
            assert!(d.x > 0.0 && (d.y / d.x).abs() < 1.0 / 3.0, "{d:?}");
        }
        // Low and high swapped: no direction from that apex keeps them apart.
        let swapped = Sides {
            low: sides.high.clone(),
            high: vec![
                Point::new(0.5, 0.5),
                Point::new(1.5, 0.5),
                Point::new(1.5, 1.5),
            ],
        };
        assert!(cone(Point::new(0.0, 1.0), Vec2::new(1.0, 0.0), &swapped).is_none());
    }

    #[test]
    fn separation_counts_only_the_span() {
        let sides = Sides {
            low: vec![
                Point::new(0.5, 0.5),
                Point::new(1.5, 0.5),
                Point::new(9.5, 1.5),
            ],
            high: vec![Point::new(0.5, 1.5), Point::new(1.5, 1.5)],
        };
        // y = 1 from x = 0 to 2: low above, high below; (9.5, 1.5) is off the span.
        assert!(separates(
            Point::new(0.0, 1.0),
            Point::new(2.0, 1.0),
            &sides
        ));
        // Through a centre: not strict.
        assert!(!separates(
            Point::new(-0.5, 0.5),
            Point::new(2.5, 0.5),
            &sides
        ));
        // A vertical line 1/128 px right of a centre is too close (Chromium's tile cuts
        // move edges by about 1/64 px along the rows); 1/32 px is enough.
        let column = Sides {
            low: vec![Point::new(0.5, 1.5)],
            high: vec![Point::new(1.5, 2.5)],
        };
        let at = |x: f64| separates(Point::new(x, 0.0), Point::new(x, 4.0), &column);
        assert!(!at(0.5 + 1.0 / 128.0));
        assert!(at(0.5 + 1.0 / 32.0));
        // Tilted so that (1.5, 1.5) is above it.
        assert!(!separates(
            Point::new(0.0, 1.0),
            Point::new(2.0, 1.8),
            &sides
        ));
    }
}
