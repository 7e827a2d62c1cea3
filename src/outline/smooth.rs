//! Renderer-safe cubics through an exact polygon: two or three straight segments become one
//! smooth cubic that tiny-skia still draws as (nearly) those segments.
//!
//! tiny-skia and Skia draw a cubic as `2^k` chords between its points at `t = i / 2^k`, `k`
//! chosen from how far the curve bends; a flat cubic (`k = 1`) is drawn as the two chords
//! `B(0) → B(½) → B(1)`. So where the renderer check had to replace a curve by its exact
//! polygon `… A → M → B …` (digital straight segments), the cubic from `A` to `B` with
//! `B(½) = M`,
//!
//! ```text
//! B(½) = (A + 3 P1 + 3 P2 + B) / 8 = M,   P1 = A + α t_A,   P2 = B − β t_B,
//! ```
//!
//! with the tangents `t_A`, `t_B` of the polygon's vertices (the directions from the
//! previous vertex to the next, as a Catmull–Rom spline has them, so consecutive cubics
//! join smoothly), is drawn as that same polygon by the renderer and as a smooth curve by
//! everything that draws curves exactly (a vector editor, a zoomed-in view): half the
//! commands and no visible corners. Where the polygon bends too much for two chords, the
//! cubic is placed for four ([`cubic_in_four_chords`]: `B(¼)` and `B(¾)` on the two
//! segments), and three segments `A → M1 → M2 → B` may become one cubic with `B(¼) = M1`,
//! `B(¾) = M2` ([`cubic_over_three`]). Each such cubic is kept only if it changes no pixel
//! (its control points are snapped to the grid, and the renderer may cut it into more
//! chords): the loop from the cubic back along its segments, filled alone by tiny-skia in
//! a window of its own, and finely flattened, must paint nothing. The cubics of the last
//! two kinds cross their polygon, so they must also paint nothing with their control points
//! moved by 1/32 px (Skia's fixed point and Chromium's tiling cut them differently), and
//! must bend enough that the renderer does not draw them in two chords.

use super::builder::Builder;
use super::render_check::{misplaced_pixels, EdgeClipping, Reference};
use super::robust::{cubic_paints_nothing, loop_paints_nothing};
use crate::curve::PathCommand;
use kurbo::{ParamCurve, ParamCurveNearest, Point, Vec2};

/// Largest turn (degrees) between two segments merged into a cubic: sharper turns are
/// corners of the shape, not polygon vertices of a curve.
pub const MAX_TURN_DEGREES: f64 = 40.0;

/// Largest turn (degrees) at a vertex a cubic that crosses its polygon replaces: sharper
/// vertices are those of small shapes, whose polygon already strays from the true curve.
pub const MAX_CROSSING_TURN_DEGREES: f64 = 25.0;

/// Shortest segment (px) of a polygon a cubic that crosses it replaces, for the same reason.
pub const MIN_CROSSING_SEGMENT: f64 = 5.0;

/// Farthest (px) a cubic that crosses its polygon may stray from it.
const MAX_OFF_POLYGON: f64 = 0.25;

/// The chord estimate above which a cubic through the corner is not tried: the renderer
/// draws it in four chords or more, which leave the corner (48 is tiny-skia's bound; 6% of
/// those just above it passed anyway).
const TWO_CHORDS_AT_MOST: i64 = 64;

/// The chord estimate from which a cubic that crosses its polygon is tried: clearly above
/// tiny-skia's two-chord bound (48), which Skia may round otherwise.
const MORE_THAN_TWO_CHORDS: i64 = 56;

/// A merge of commands `i .. i + len` (two or three lines) into one cubic.
#[derive(Clone, Copy)]
struct Merge {
    /// Index of the first line.
    i: usize,
    /// How many lines.
    len: usize,
    cubic: PathCommand,
}

/// `v / |v|`; `None` for a zero vector.
fn unit(v: Vec2) -> Option<Vec2> {
    let h = v.hypot();
    (h > 0.0 && h.is_finite()).then(|| v / h)
}

/// The cubic from `a` through `m` (at `t = ½`) to `b` with tangent directions `ta` at `a`
/// and `tb` at `b`, control points snapped by `builder`. Returns `None` when the tangents
/// do not give control points ahead of `a` and behind `b` within the chord's length.
fn cubic_through(
    a: Point,
    m: Point,
    b: Point,
    ta: Vec2,
    tb: Vec2,
    snap: &Builder,
) -> Option<[Point; 2]> {
    // α t_A − β t_B = (8/3) (M − (A + B)/2).
    let rhs = (m - a.midpoint(b)) * (8.0 / 3.0);
    let det = ta.cross(-tb);
    if det.abs() < 1e-9 {
        return None;
    }
    let alpha = rhs.cross(-tb) / det;
    let beta = ta.cross(rhs) / det;
    let reach = (b - a).hypot();
    if !(alpha > 0.0 && beta > 0.0 && alpha < 0.75 * reach && beta < 0.75 * reach) {
        return None;
    }
    Some([snap.snap(a + ta * alpha), snap.snap(b - tb * beta)])
}

/// The cubic from `a` to `b` that tiny-skia, cutting it into four chords at `t = ¼, ½, ¾`,
/// draws as the polygon `a → m → b`: `B(½) = m`, `B(¼)` on the line `a m` and `B(¾)` on the
/// line `m b`, four linear equations in the two control points,
///
/// ```text
/// 3 P1 + 3 P2 = 8 m − a − b,
/// n1 · (27 P1 + 9 P2) = n1 · (37 a − b),          n1 ⟂ m − a,
/// n2 · (9 P1 + 27 P2) = n2 · (64 m − a − 27 b),   n2 ⟂ b − m,
/// ```
///
/// for bends too strong for [`cubic_through`]'s two chords. Control points snapped by
/// `snap`. Returns `None` when the segments are parallel or a control point falls behind
/// its end (the cubic would loop).
fn cubic_in_four_chords(a: Point, m: Point, b: Point, snap: &Builder) -> Option<[Point; 2]> {
    let (u, v) = (m - a, b - m);
    let (n1, n2) = (Vec2::new(-u.y, u.x), Vec2::new(-v.y, v.x));
    // P2 = s − P1.
    let s = (m.to_vec2() * 8.0 - a.to_vec2() - b.to_vec2()) / 3.0;
    // 18 n1·P1 = n1·(37 a − b − 9 s);  −18 n2·P1 = n2·(64 m − a − 27 b − 27 s).
    let c1 = n1.dot(a.to_vec2() * 37.0 - b.to_vec2() - s * 9.0) / 18.0;
    let c2 = -n2.dot(m.to_vec2() * 64.0 - a.to_vec2() - b.to_vec2() * 27.0 - s * 27.0) / 18.0;
    let det = n1.cross(n2);
    if det.abs() < 1e-9 * u.hypot2().max(v.hypot2()) {
        return None;
    }
    // Solve n1·P = c1, n2·P = c2 (Cramer).
    let p1 = Point::new((c1 * n2.y - c2 * n1.y) / det, (n1.x * c2 - n2.x * c1) / det);
    let p2 = (s - p1.to_vec2()).to_point();
    unlooped(a, p1, p2, b, u, v, snap)
}

/// The control points `p1`, `p2` of the cubic from `a` to `b`, snapped by `snap`, when
/// `p1` lies ahead of `a` along `ta` and `p2` behind `b` along `tb`, both within the
/// chord's length; `None` otherwise (the cubic would loop or swing wide).
fn unlooped(
    a: Point,
    p1: Point,
    p2: Point,
    b: Point,
    ta: Vec2,
    tb: Vec2,
    snap: &Builder,
) -> Option<[Point; 2]> {
    let ahead = (p1 - a).dot(ta) > 0.0 && (b - p2).dot(tb) > 0.0;
    let reach = (b - a).hypot();
    let near = (p1 - a).hypot() < reach && (b - p2).hypot() < reach;
    (ahead && near).then(|| [snap.snap(p1), snap.snap(p2)])
}

/// The cubic from `a` to `b` with `B(¼) = m1` and `B(¾) = m2`, drawn by tiny-skia in four
/// chords (or eight, through the same points) as the polygon `a → m1 → m2 → b` with its
/// middle segment replaced by the two chords through `B(½)`:
///
/// ```text
/// 27 P1 + 9 P2 = 64 m1 − 27 a − b,   9 P1 + 27 P2 = 64 m2 − a − 27 b.
/// ```
///
/// Control points snapped by `snap`. Returns `None` when a control point falls behind its
/// end (the cubic would loop).
fn cubic_over_three(
    a: Point,
    m1: Point,
    m2: Point,
    b: Point,
    snap: &Builder,
) -> Option<[Point; 2]> {
    let r1 = m1.to_vec2() * 64.0 - a.to_vec2() * 27.0 - b.to_vec2();
    let r2 = m2.to_vec2() * 64.0 - a.to_vec2() - b.to_vec2() * 27.0;
    let p1 = ((r1 * 27.0 - r2 * 9.0) / 648.0).to_point();
    let p2 = ((r2 * 27.0 - r1 * 9.0) / 648.0).to_point();
    unlooped(a, p1, p2, b, m1 - a, b - m2, snap)
}

/// How far tiny-skia and Skia estimate the cubic `a p1 p2 b` to bend, in 1/64 px
/// (`cubic_delta_from_line` and `cheap_distance` of their `edge.rs`): below 48 they draw
/// it in two chords, from 48 to 239 in four, from 240 in eight or more (see
/// [`super::absorb`]'s `chord_shift`).
pub(super) fn chord_estimate(a: Point, p1: Point, p2: Point, b: Point) -> i64 {
    let f = |v: f64| (v * 64.0) as i64;
    let delta = |a: f64, b: f64, c: f64, d: f64| {
        let (a, b, c, d) = (f(a), f(b), f(c), f(d));
        let one_third = ((a * 8 - b * 15 + 6 * c + d) * 19) >> 9;
        let two_third = ((a + 6 * b - c * 15 + d * 8) * 19) >> 9;
        one_third.abs().max(two_third.abs())
    };
    let dx = delta(a.x, p1.x, p2.x, b.x);
    let dy = delta(a.y, p1.y, p2.y, b.y);
    dx.max(dy) + (dx.min(dy) >> 1)
}

/// Replaces runs of two or three consecutive lines flagged in `smooth` by cubics where
/// the path still paints exactly what `reference` paints; see the module documentation.
/// `start`, `commands` describe the closed path; `grid` is the builder's.
pub(crate) fn smooth_polygon(
    start: Point,
    commands: &[PathCommand],
    smooth: &[bool],
    reference: &Reference,
    grid: u8,
    clipping: EdgeClipping,
    canvas: Option<kurbo::Rect>,
) -> Vec<PathCommand> {
    let n = commands.len();
    let snap = Builder::new(grid);
    let vertex = |j: usize| if j == 0 { start } else { commands[j - 1].end() };
    let is_line = |j: usize| matches!(commands[j], PathCommand::Line(_));
    // Tangent at vertex j (the end of command j − 1): from vertex j − 1 to vertex j + 1.
    let tangent = |j: usize| -> Option<Vec2> {
        let prev = if j == 0 { vertex(n) } else { vertex(j - 1) };
        let next = if j >= n { vertex(1) } else { vertex(j + 1) };
        unit(next - prev)
    };
    let cos_max = MAX_TURN_DEGREES.to_radians().cos();
    // Each merge on its own: the closed loop `A —cubic→ B → M → A` winds, round each pixel
    // centre, the change the merge makes to the path's winding there (tiny-skia's scan
    // converter sums each edge's crossings by itself, and a line drawn both ways cancels).
    // The polygon is exact, so a merge whose loop paints no pixel in either of tiny-skia's
    // edge modes, nor finely flattened, leaves every pixel as it was; and merges that each
    // change nothing change nothing together. Small windows instead of whole-contour fills.
    // The true curve (finely flattened) is checked too when `fine`.
    let paints_nothing = |j: usize, len: usize, cubic: PathCommand, fine: bool| {
        let a = vertex(j);
        // At most three lines back.
        let mut lp = [cubic; 4];
        for (slot, k) in lp[1..].iter_mut().zip((j..j + len).rev()) {
            *slot = PathCommand::Line(vertex(k));
        }
        loop_paints_nothing(a, &lp[..=len], clipping, canvas, fine)
    };
    // The cosine of the turn at vertex v; `None` beside a zero-length segment.
    let turn_cos =
        |v: usize| Some(unit(vertex(v) - vertex(v - 1))?.dot(unit(vertex(v + 1) - vertex(v))?));
    // A cubic that crosses its polygon (lines j .. j + len) is kept when it replaces gentle
    // vertices between long segments, bends clearly beyond two chords (Skia may round the
    // estimate otherwise), stays near its polygon all along (no wiggle a zoomed-in view
    // would show), changes nothing, and still changes nothing in tiny-skia with its control
    // points moved (`cubic_paints_nothing`).
    let robust = |j: usize, len: usize, cubic: PathCommand| {
        let PathCommand::Cubic(p1, p2, e) = cubic else {
            return false;
        };
        let a = vertex(j);
        let cos_crossing = MAX_CROSSING_TURN_DEGREES.to_radians().cos();
        let long =
            (j..j + len).all(|v| (vertex(v + 1) - vertex(v)).hypot() >= MIN_CROSSING_SEGMENT);
        let gentle =
            long && (j + 1..j + len).all(|v| turn_cos(v).is_some_and(|c| c >= cos_crossing));
        let bez = kurbo::CubicBez::new(a, p1, p2, e);
        let near_polygon = || {
            (1..16).all(|k| {
                let q = bez.eval(f64::from(k) / 16.0);
                (j..j + len)
                    .map(|s| {
                        kurbo::Line::new(vertex(s), vertex(s + 1))
                            .nearest(q, 1e-9)
                            .distance_sq
                    })
                    .fold(f64::INFINITY, f64::min)
                    <= MAX_OFF_POLYGON * MAX_OFF_POLYGON
            })
        };
        gentle
            && chord_estimate(a, p1, p2, e) >= MORE_THAN_TWO_CHORDS
            && near_polygon()
            && cubic_paints_nothing(cubic, |c, fine| paints_nothing(j, len, c, fine))
    };
    // Pairs from the first line on; a pair that cannot merge leaves its second line to the
    // next pair.
    let mut merges: Vec<Merge> = Vec::new();
    let mut i = 0;
    // Lines j and j + 1 may be drawn as one curve.
    let smooth_turn = |j: usize| {
        smooth[j]
            && smooth[j + 1]
            && is_line(j)
            && is_line(j + 1)
            && turn_cos(j + 1).is_some_and(|c| c >= cos_max)
    };
    while i + 1 < n {
        if !smooth_turn(i) {
            i += 1;
            continue;
        }
        let (a, m, b) = (vertex(i), vertex(i + 1), vertex(i + 2));
        if i + 2 < n && smooth_turn(i + 1) {
            let c = vertex(i + 3);
            let three = cubic_over_three(a, m, b, c, &snap)
                .map(|[p1, p2]| PathCommand::Cubic(p1, p2, c))
                .filter(|&cubic| robust(i, 3, cubic));
            if let Some(cubic) = three {
                merges.push(Merge { i, len: 3, cubic });
                i += 3;
                continue;
            }
        }
        // Drawn in two chords (smooth joins), else in four.
        let two = || {
            let (ta, tb) = (tangent(i)?, tangent(i + 2)?);
            let [p1, p2] = cubic_through(a, m, b, ta, tb, &snap)?;
            // Only if the renderer may draw it in two chords.
            (chord_estimate(a, p1, p2, b) < TWO_CHORDS_AT_MOST).then_some([p1, p2])
        };
        let four = || cubic_in_four_chords(a, m, b, &snap);
        let kept = two()
            .map(|[p1, p2]| PathCommand::Cubic(p1, p2, b))
            .filter(|&c| paints_nothing(i, 2, c, true))
            .or_else(|| {
                four()
                    .map(|[p1, p2]| PathCommand::Cubic(p1, p2, b))
                    .filter(|&c| robust(i, 2, c))
            });
        match kept {
            Some(cubic) => {
                merges.push(Merge { i, len: 2, cubic });
                i += 2;
            }
            None => i += 1,
        }
    }
    let assemble = |merges: &[Merge]| -> Vec<PathCommand> {
        let mut out = Vec::with_capacity(n);
        let mut k = 0;
        let mut j = 0;
        while j < n {
            if k < merges.len() && merges[k].i == j {
                out.push(merges[k].cubic);
                j += merges[k].len;
                k += 1;
            } else {
                out.push(commands[j]);
                j += 1;
            }
        }
        out
    };
    let out = assemble(&merges);
    debug_assert!(
        misplaced_pixels(reference, start, &out, clipping, canvas).is_empty(),
        "a smoothed path misplaces pixels"
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The point at `t` of the cubic `a p1 p2 b`.
    fn at(a: Point, [p1, p2]: [Point; 2], b: Point, t: f64) -> Point {
        kurbo::CubicBez::new(a, p1, p2, b).eval(t)
    }

    /// Distance from `p` to the line through `a` and `b`.
    fn off_line(p: Point, a: Point, b: Point) -> f64 {
        (b - a).cross(p - a).abs() / (b - a).hypot()
    }

    /// A polygon corner `a → m → b` with integer vertices, turning by 3° to 40°.
    fn corner() -> impl Strategy<Value = [Point; 3]> {
        let pt = || (-60i32..60, -60i32..60).prop_map(|(x, y)| Point::new(x.into(), y.into()));
        (pt(), pt(), pt())
            .prop_map(|(a, m, b)| [a, m, b])
            .prop_filter("a gentle turn", |&[a, m, b]| {
                let (u, v) = (m - a, b - m);
                let turn = u.cross(v).atan2(u.dot(v)).abs().to_degrees();
                u.hypot() >= 4.0 && v.hypot() >= 4.0 && (3.0..=MAX_TURN_DEGREES).contains(&turn)
            })
    }

    /// Snapping to 1/64 px moves a point of the cubic by at most this.
    const SNAPPED: f64 = 1.0 / 64.0;

    proptest! {
        /// The four chords at `t = ¼, ½, ¾` run along the polygon: `B(½) = m`, `B(¼)` on
        /// the line `a m`, `B(¾)` on the line `m b`.
        #[test]
        fn four_chords_run_along_the_polygon([a, m, b] in corner()) {
            if let Some(c) = cubic_in_four_chords(a, m, b, &Builder::new(6)) {
                prop_assert!((at(a, c, b, 0.5) - m).hypot() <= SNAPPED);
                prop_assert!(off_line(at(a, c, b, 0.25), a, m) <= SNAPPED);
                prop_assert!(off_line(at(a, c, b, 0.75), m, b) <= SNAPPED);
            }
        }

        /// Over three segments, `B(¼)` and `B(¾)` are the polygon's inner vertices.
        #[test]
        fn three_segments_keep_their_vertices(
            [a, m1, m2] in corner(),
            (dx, dy) in (-30i32..30, -30i32..30),
        ) {
            let b = m2 + Vec2::new(dx.into(), dy.into());
            if let Some(c) = cubic_over_three(a, m1, m2, b, &Builder::new(6)) {
                prop_assert!((at(a, c, b, 0.25) - m1).hypot() <= SNAPPED);
                prop_assert!((at(a, c, b, 0.75) - m2).hypot() <= SNAPPED);
            }
        }
    }

    /// Two chords for a flat cubic, more for a bent one, as tiny-skia decides.
    #[test]
    fn chord_estimate_grows_with_the_bend() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(30.0, 0.0));
        let flat = chord_estimate(a, Point::new(10.0, 0.1), Point::new(20.0, 0.1), b);
        let bent = chord_estimate(a, Point::new(10.0, 6.0), Point::new(20.0, 6.0), b);
        assert!(flat < 48, "{flat}");
        assert!(bent >= 112, "{bent}");
    }
}
