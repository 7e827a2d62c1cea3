//! The largest-margin line between two planar integer point sets, from their convex hulls.
//!
//! For the line basis `(x, y)` the largest-margin direction of [`super::max_margin_direction`]
//! is the shortest vector `d = h* − l*` between the convex hulls of `low` and `high`: the
//! line through the middle of that vector, perpendicular to it, is the separating line
//! farthest from both sets. Two disjoint convex polygons are closest at a vertex of one and
//! an edge (or vertex) of the other, so the shortest vector is the least of the
//! vertex-to-edge vectors; hulls of the sides of digital straight segments have a handful of
//! vertices. The float GJK reaches the same vector iteratively; this is direct, and the
//! hulls are exact (integer arithmetic).

use super::MarginDirection;

/// An integer point.
type P = [i64; 2];

fn cross(o: P, a: P, b: P) -> i128 {
    let (ax, ay) = (i128::from(a[0] - o[0]), i128::from(a[1] - o[1]));
    let (bx, by) = (i128::from(b[0] - o[0]), i128::from(b[1] - o[1]));
    ax * by - ay * bx
}

/// The convex hull's vertices, counter-clockwise without collinear ones (Andrew's monotone
/// chain); one or two points for degenerate sets, none for an empty one.
fn hull(points: &[P]) -> Vec<P> {
    // Sides of a digital segment come nearly in order along it: often no sort is needed.
    let mut pts = points.to_vec();
    if !pts.is_sorted() {
        if pts.iter().rev().is_sorted() {
            pts.reverse();
        } else {
            pts.sort_unstable();
        }
    }
    pts.dedup();
    if pts.len() <= 2 {
        return pts;
    }
    let mut h: Vec<P> = Vec::with_capacity(pts.len() + 1);
    let chain = |h: &mut Vec<P>, p: P, start: usize| {
        while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
            h.pop();
        }
        h.push(p);
    };
    for &p in &pts {
        chain(&mut h, p, 0);
    }
    h.pop(); // the last point starts the upper chain
    let start = h.len();
    for &p in pts.iter().rev() {
        chain(&mut h, p, start);
    }
    h.pop(); // the first point started the lower chain
    h
}

/// The vector from `p` to the closest point of the segment `a..b` (a point when `a == b`).
fn to_segment(p: P, a: P, b: P) -> [f64; 2] {
    let (px, py) = (p[0] as f64, p[1] as f64);
    let (ax, ay) = (a[0] as f64, a[1] as f64);
    let (ex, ey) = ((b[0] - a[0]) as f64, (b[1] - a[1]) as f64);
    let len2 = ex * ex + ey * ey;
    let t = if len2 > 0.0 {
        (((px - ax) * ex + (py - ay) * ey) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [ax + t * ex - px, ay + t * ey - py]
}

/// Keeps in `best` (squared length, vector) the shortest vector from a vertex of the hull
/// `from` to an edge of the hull `to` when shorter, times `sign` (−1 to point the other way).
fn shortest(from: &[P], to: &[P], sign: f64, best: &mut Option<(f64, [f64; 2])>) {
    let m = to.len();
    for &p in from {
        for k in 0..m {
            let v = to_segment(p, to[k], to[(k + 1) % m]);
            let d2 = v[0] * v[0] + v[1] * v[1];
            if best.is_none_or(|(b, _)| d2 < b) {
                *best = Some((d2, [sign * v[0], sign * v[1]]));
            }
        }
    }
}

/// The direction of largest margin from `low` to `high` (points relative to any common
/// origin), the shortest vector `d` between their convex hulls, with the level half-way
/// between the sets: `d·l < level < d·h` for every pair. Returns `None` if either set is
/// empty or the hulls meet.
pub(crate) fn line_margin_direction(low: &[P], high: &[P]) -> Option<MarginDirection> {
    let (lh, hh) = (hull(low), hull(high));
    if lh.is_empty() || hh.is_empty() {
        return None;
    }
    let mut best = None;
    shortest(&lh, &hh, 1.0, &mut best);
    shortest(&hh, &lh, -1.0, &mut best);
    let (d2, d) = best?;
    // Crossing hulls have vertex-to-edge vectors too: the shortest one separates only when
    // the hulls are disjoint. (A linear function's extremes over a set are at its hull's
    // vertices.)
    let value = |p: &P| d[0] * p[0] as f64 + d[1] * p[1] as f64;
    let top = lh.iter().map(value).fold(f64::NEG_INFINITY, f64::max);
    let bottom = hh.iter().map(value).fold(f64::INFINITY, f64::min);
    (d2 > 0.0 && top < bottom).then(|| MarginDirection {
        direction: d.to_vec(),
        level: (top + bottom) / 2.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn hull_of_a_square_with_inner_and_collinear_points() {
        let pts = [[0, 0], [2, 0], [1, 0], [2, 2], [0, 2], [1, 1], [0, 1]];
        assert_eq!(hull(&pts), vec![[0, 0], [2, 0], [2, 2], [0, 2]]);
    }

    #[test]
    fn two_squares_side_by_side() {
        let low = [[0, 0], [1, 0], [0, 1], [1, 1]];
        let high = [[4, 0], [5, 0], [4, 1], [5, 1]];
        let m = line_margin_direction(&low, &high).unwrap();
        assert_eq!((m.direction, m.level), (vec![3.0, 0.0], 7.5));
        let m = line_margin_direction(&high, &low).unwrap();
        assert_eq!((m.direction, m.level), (vec![-3.0, 0.0], -7.5));
        // Overlapping hulls: no separation.
        assert_eq!(line_margin_direction(&low, &[[1, 1], [3, 3]]), None);
    }

    proptest! {
        /// The vector separates strictly when a line separates the sets (checked by brute
        /// force over the lines through pairs of points, nudged), and no point pair of the
        /// sets is closer than it, and its length is no more than every pair's distance (it
        /// is the distance between the hulls, at most that between any two points).
        #[test]
        fn separates_and_is_shortest(
            low in prop::collection::vec((0i64..8, 0i64..8), 1..8),
            high in prop::collection::vec((0i64..8, 0i64..8), 1..8),
        ) {
            let low: Vec<P> = low.into_iter().map(|(x, y)| [x, y]).collect();
            let high: Vec<P> = high.into_iter().map(|(x, y)| [x, y]).collect();
            let dot = |d: [f64; 2], p: P| d[0] * p[0] as f64 + d[1] * p[1] as f64;
            // Strictly separable iff some direction among the normals of point differences,
            // turned a little either way, separates (the extreme separating directions are
            // normals of such differences).
            let mut dirs = Vec::new();
            for a in low.iter().chain(&high) {
                for b in low.iter().chain(&high) {
                    let (ex, ey) = ((b[0] - a[0]) as f64, (b[1] - a[1]) as f64);
                    for s in [-1e-6, 1e-6] {
                        dirs.push([-ey + s * ex, ex + s * ey]);
                        dirs.push([ey + s * ex, -ex + s * ey]);
                    }
                }
            }
            dirs.push([1.0, 0.0]);
            dirs.push([0.0, 1.0]);
            dirs.push([-1.0, 0.0]);
            dirs.push([0.0, -1.0]);
            let separates = |d: [f64; 2]| {
                let top = low.iter().map(|&p| dot(d, p)).fold(f64::NEG_INFINITY, f64::max);
                let bottom = high.iter().map(|&p| dot(d, p)).fold(f64::INFINITY, f64::min);
                top < bottom
            };
            let separable = dirs.iter().any(|&d| separates(d));
            match line_margin_direction(&low, &high) {
                None => prop_assert!(!separable),
                Some(m) => {
                    let d = [m.direction[0], m.direction[1]];
                    let top = low.iter().map(|&p| dot(d, p)).fold(f64::NEG_INFINITY, f64::max);
                    let bottom = high.iter().map(|&p| dot(d, p)).fold(f64::INFINITY, f64::min);
                    prop_assert!(top < m.level && m.level < bottom);
                    prop_assert!(separable);
                    prop_assert!(separates(d));
                    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
                    // Its margin: the gap between the sets along the unit direction.
                    let u = [d[0] / len, d[1] / len];
                    let top = low.iter().map(|&p| dot(u, p)).fold(f64::NEG_INFINITY, f64::max);
                    let bottom = high.iter().map(|&p| dot(u, p)).fold(f64::INFINITY, f64::min);
                    prop_assert!((bottom - top - len).abs() < 1e-9, "gap {} len {}", bottom - top, len);
                    // No separating direction tried has a larger gap.
                    for &e in &dirs {
                        let l = (e[0] * e[0] + e[1] * e[1]).sqrt();
                        if l == 0.0 { continue; }
                        let v = [e[0] / l, e[1] / l];
                        let t = low.iter().map(|&p| dot(v, p)).fold(f64::NEG_INFINITY, f64::max);
                        let b = high.iter().map(|&p| dot(v, p)).fold(f64::INFINITY, f64::min);
                        prop_assert!(b - t <= len + 1e-9);
                    }
                }
            }
        }
    }
}
