//! The parts a cubic is drawn in: tiny-skia and Skia cut it at its extrema, and where a clip
//! cuts it, and draw each part in chords of its own.
//!
//! A cubic edge is drawn as `2^k` chords, `k` from how far its control points stray from its
//! chord ([`super::smooth::chord_estimate`]). Both renderers first cut a cubic where it
//! turns back in `y`; when the path leaves the clip (the pixmap, or one of Chromium's raster
//! tiles, see [`super::tiles`]) they also cut it where it turns back in `x`, and then at the
//! clip's sides, keeping what lies inside (`SkEdgeClipper::clipCubic`). Each part has its
//! own estimate: a cubic whose whole estimate is clear of the bounds where the chord count
//! changes may have a part that is not, and renderers that compute the cut in different
//! floating point then draw that part in different chords (2 pixels of the 27 shared
//! samples in Chromium: the part of a cubic below a tile's top at y = 508 had the estimate
//! 240, one of those bounds).

use kurbo::common::{solve_cubic, solve_quadratic};
use kurbo::{CubicBez, ParamCurve, Point, Rect};

/// The parameters in `(0, 1)` where the coordinate `c` (the four control values) turns
/// back, in order.
fn extrema(c: [f64; 4]) -> Vec<f64> {
    // The derivative over 3: (c1 − c0)(1 − t)² + 2 (c2 − c1) t (1 − t) + (c3 − c2) t².
    let (d0, d1, d2) = (c[1] - c[0], c[2] - c[1], c[3] - c[2]);
    let mut ts: Vec<f64> = solve_quadratic(d0, 2.0 * (d1 - d0), d0 - 2.0 * d1 + d2)
        .into_iter()
        .filter(|t| *t > 0.0 && *t < 1.0)
        .collect();
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    ts
}

/// `bez` cut at the parameters `ts` (in order, within `(0, 1)`).
fn cut_at(bez: CubicBez, ts: &[f64]) -> Vec<CubicBez> {
    let mut out = Vec::with_capacity(ts.len() + 1);
    let mut from = 0.0;
    for &t in ts.iter().chain(std::iter::once(&1.0)) {
        if t > from {
            out.push(bez.subsegment(from..t));
        }
        from = t;
    }
    out
}

/// The parameter where the monotonic coordinate `c` (the four control values) reaches `v`;
/// `None` if it does not within `(0, 1)`.
fn crossing(c: [f64; 4], v: f64) -> Option<f64> {
    // c(t) − v in powers of t.
    let a0 = c[0] - v;
    let a1 = 3.0 * (c[1] - c[0]);
    let a2 = 3.0 * (c[2] - 2.0 * c[1] + c[0]);
    let a3 = c[3] - 3.0 * c[2] + 3.0 * c[1] - c[0];
    solve_cubic(a0, a1, a2, a3)
        .into_iter()
        .filter(|t| *t > 0.0 && *t < 1.0)
        .min_by(|s, t| (s - 0.5).abs().total_cmp(&(t - 0.5).abs()))
}

/// The part of the monotonic `bez` whose coordinate (`x` when `along_x`, else `y`) lies
/// within `lo..hi`; `None` if none does.
fn within(bez: CubicBez, along_x: bool, lo: f64, hi: f64) -> Option<CubicBez> {
    let pick = |p: Point| if along_x { p.x } else { p.y };
    let c = [pick(bez.p0), pick(bez.p1), pick(bez.p2), pick(bez.p3)];
    let (first, last) = (c[0].min(c[3]), c[0].max(c[3]));
    if last <= lo || first >= hi {
        return None;
    }
    let mut ts: Vec<f64> = [lo, hi]
        .into_iter()
        .filter(|&v| first < v && v < last)
        .filter_map(|v| crossing(c, v))
        .collect();
    ts.sort_by(f64::total_cmp);
    // The part between the cuts (or beside the one cut) that lies inside.
    let mid = |from: f64, to: f64| pick(bez.eval(0.5 * (from + to)));
    let bounds = std::iter::once(0.0)
        .chain(ts.iter().copied())
        .chain(std::iter::once(1.0))
        .collect::<Vec<f64>>();
    bounds
        .windows(2)
        .find(|w| w[1] > w[0] && (lo..hi).contains(&mid(w[0], w[1])))
        .map(|w| bez.subsegment(w[0]..w[1]))
}

/// The cubics tiny-skia and Skia draw `bez` as (each in its own chords): cut where it turns
/// back in `y`; with a `clip` (the path is clipped), also where it turns back in `x`, and
/// then kept only within the clip (parts beside it become vertical lines, not listed).
pub(crate) fn drawn_parts(bez: CubicBez, clip: Option<Rect>) -> Vec<CubicBez> {
    let ys = extrema([bez.p0.y, bez.p1.y, bez.p2.y, bez.p3.y]);
    let mono_y = cut_at(bez, &ys);
    let Some(clip) = clip else {
        return mono_y;
    };
    let mut out = Vec::new();
    for part in mono_y {
        let xs = extrema([part.p0.x, part.p1.x, part.p2.x, part.p3.x]);
        for mono in cut_at(part, &xs) {
            if let Some(inside) = within(mono, false, clip.y0, clip.y1)
                .and_then(|q| within(q, true, clip.x0, clip.x1))
            {
                out.push(inside);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::smooth::chord_estimate;
    use super::*;

    fn estimate(q: &CubicBez, origin: Point) -> i64 {
        let o = origin.to_vec2();
        chord_estimate(q.p0 - o, q.p1 - o, q.p2 - o, q.p3 - o)
    }

    #[test]
    fn a_monotonic_cubic_is_one_part() {
        let bez = CubicBez::new((0.0, 0.0), (10.0, 2.0), (20.0, 8.0), (30.0, 12.0));
        assert_eq!(drawn_parts(bez, None), vec![bez]);
        let big = Rect::new(-10.0, -10.0, 100.0, 100.0);
        let parts = drawn_parts(bez, Some(big));
        assert_eq!(parts.len(), 1);
        assert!((parts[0].p3 - bez.p3).hypot() < 1e-9);
    }

    #[test]
    fn turning_back_in_y_cuts_always_in_x_only_when_clipped() {
        // Up then down (one y extremum), and right then left (one x extremum).
        let bez = CubicBez::new((0.0, 0.0), (40.0, 30.0), (40.0, 30.0), (0.0, 1.0));
        assert_eq!(drawn_parts(bez, None).len(), 2);
        let clip = Rect::new(-100.0, -100.0, 100.0, 100.0);
        let parts = drawn_parts(bez, Some(clip));
        assert!(parts.len() >= 3, "{}", parts.len());
        // The parts join up into the whole.
        for w in parts.windows(2) {
            assert!((w[0].p3 - w[1].p0).hypot() < 1e-9);
        }
    }

    #[test]
    fn a_clip_keeps_what_lies_inside() {
        // From Chromium on sil_kangaroo: the part of this cubic below y = 508 (a tile's top)
        // bends by 240/64 px by the renderers' estimate, a bound between 4 and 8 chords,
        // though the whole cubic's 366 is far from any.
        let bez = CubicBez::new(
            (647.0, 520.0),
            (646.0625, 515.75),
            (645.5, 511.125),
            (625.9375, 506.0),
        );
        let tile = Rect::new(508.0, 508.0, 764.0, 540.0);
        let parts = drawn_parts(bez, Some(tile));
        assert_eq!(parts.len(), 1);
        let q = parts[0];
        let (top, bottom) = (q.p0.y.min(q.p3.y), q.p0.y.max(q.p3.y));
        assert!((top - 508.0).abs() < 1e-9 && (bottom - 520.0).abs() < 1e-9);
        assert!((300..900).contains(&estimate(&bez, Point::ZERO)));
        assert!(
            (238..=242).contains(&estimate(&q, tile.origin())),
            "{}",
            estimate(&q, tile.origin())
        );
        // The tile above, clipped at its bottom (510), keeps the rest.
        let above = drawn_parts(bez, Some(Rect::new(508.0, 254.0, 764.0, 510.0)));
        assert_eq!(above.len(), 1);
        assert!((above[0].p0.y.max(above[0].p3.y) - 510.0).abs() < 1e-9);
        // Beside the clip: nothing drawn as a cubic.
        assert!(drawn_parts(bez, Some(Rect::new(0.0, 0.0, 500.0, 500.0))).is_empty());
    }
}
