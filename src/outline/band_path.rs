//! Smooth outlines within ν pixels: curves through the border band, checked as tiny-skia
//! draws them.
//!
//! # Steps
//! 1. The fewest-vertex polygon whose edges pass within `ν +` [`POLYGON_SLACK`] of the crack
//!    corners they replace and leave every constraint pixel on its side
//!    ([`super::band_polygon`]); each vertex then moves within half a pixel to where the
//!    lines fitted to its two edges' corners meet (potrace's adjustment), unless that puts
//!    a constraint pixel between an edge and the crack path.
//! 2. Each vertex becomes a cubic from the midpoint of the edge before it to the midpoint of
//!    the edge after it, tangent to both edges (so consecutive cubics join smoothly), its
//!    handle lengths fitted by least squares to the crack corners between; or stays a
//!    corner: where it stands far from its neighbours' chord (`α = (1 − 1/d)/0.75 ≥ 1`,
//!    `d = dist(v_k, v_{k−1} v_{k+1}) / 2ν`: potrace's `alphamax` rule, at potrace's scale
//!    for ν = ½), or where no such cubic stays within `ν +` [`CURVE_SLACK`] of the corners
//!    with no constraint pixel between it and the crack path.
//! 3. Runs of curved vertices turning one way, less than [`MAX_RUN_TURN_DEGREES`] in all,
//!    become one cubic fitted the same way (same end tangents), as long as it passes the same
//!    tests.
//! 4. The path is filled with tiny-skia ([`super::render_check`]); where it paints a
//!    constraint pixel wrongly, merged runs near it are undone, then curves near it become
//!    corners, then vertices go back to their crack corners, then polygon edges there are
//!    split, until none is wrong (at worst the crack polygon itself).
//!
//! So every pixel the path draws differently from the contour is within ν of the border,
//! as tiny-skia (resvg) draws it.

use super::band_cells::Cells;
use super::band_polygon::Reach;
use super::builder::Builder;
use super::cracks::crack_polyline;
use super::path::ContourPath;
use super::render_check::{misplaced_pixels, Reference};
use super::OutlineOptions;
use crate::bitmap::Band;
use crate::contour::Contour;
use crate::curve::PathCommand;
use kurbo::{CubicBez, Line, ParamCurve, ParamCurveDeriv, ParamCurveNearest, Point, Vec2};

/// Largest total turn of a run of cubics merged into one.
pub(crate) const MAX_RUN_TURN_DEGREES: f64 = 175.0;

/// How much farther than ν (pixels) from a polygon edge the crack corners it replaces may
/// lie. The corners of a digital straight edge spread over about 1.4 px across it, so edges
/// through them need some slack; with the curves' slack, chosen on the 27 shared samples at
/// ν = 1 (slack 0 / 0: 7 462 commands, 18 419 px differ; 0.2 / 0.15: 5 498 and 22 300;
/// 0.5 / 0.5: 4 791 and 31 511; potrace: 5 867 and 23 792).
const POLYGON_SLACK: f64 = 0.2;

/// How much farther than ν (pixels) a fitted cubic may pass from the crack corners it
/// replaces, and they from it (see [`POLYGON_SLACK`]).
const CURVE_SLACK: f64 = 0.15;

/// The finest grid of smooth outlines (1/4 px): the curves only have to stay within the
/// band, and a coarser grid writes fewer digits. 27 shared samples at ν = 1, against the
/// exact drawings' 1/16 px: 127 351 → 91 818 bytes, commands 5 517 → 5 588, differing pixels
/// 22 150 → 22 921 (1/8 px: 109 772 bytes, 5 553 commands, 21 941 px).
const SMOOTH_GRID: u8 = 2;

/// potrace's `alphamax`: vertices with a larger α are corners.
const ALPHA_MAX: f64 = 1.0;

/// Most rounds of checking and repairing.
const MAX_ROUNDS: usize = 40;

/// How one polygon vertex is drawn.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    /// Index of its crack corner.
    crack: usize,
    p: Point,
    /// Moved off its crack corner by [`adjusted`].
    adjusted: bool,
    /// Drawn as a corner (two lines through it).
    corner: bool,
    /// The cubic's control points, when not a corner.
    controls: [Point; 2],
}

/// A drawn item, for the repairs.
#[derive(Clone, Copy, Debug)]
enum Item {
    /// Cubic merged from the run of vertices `first..=last`.
    Run { first: usize, last: usize },
    /// The cubic of one vertex.
    Curve(usize),
    /// The two lines of a corner vertex.
    Corner(usize),
}

/// `v / |v|`, or `None` for a zero vector.
fn unit(v: Vec2) -> Option<Vec2> {
    let h = v.hypot();
    (h > 0.0 && h.is_finite()).then(|| v / h)
}

/// The cubic as a polyline of `n + 1` points.
fn flatten(c: &CubicBez, out: &mut Vec<Point>) {
    let len = (c.p1 - c.p0).hypot() + (c.p2 - c.p1).hypot() + (c.p3 - c.p2).hypot();
    let n = ((len * 2.0).sqrt().ceil() as usize).clamp(4, 64);
    for i in 0..=n {
        out.push(c.eval(i as f64 / n as f64));
    }
}

/// Distance from `p` to the segment `a b` (a point when `a == b`), by kurbo's nearest point
/// of a [`Line`].
fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    Line::new(a, b).nearest(p, 0.0).distance_sq.sqrt()
}

/// The smooth outline of one contour (see the module documentation).
/// The path stays in the image: a path that leaves it is cut at the image border by the
/// renderer's edge clipper, which moves the chords of its curves in ways the render check
/// does not see.
pub(crate) fn band_contour_path(
    contour: &Contour,
    band: &Band,
    opts: &OutlineOptions,
) -> ContourPath {
    let points = &contour.points;
    let n = points.len();
    let mut corners = if n == 0 {
        Vec::new()
    } else {
        crack_polyline(points, 0, n - 1)
    };
    if corners.len() > 1 && corners.first() == corners.last() {
        corners.pop();
    }
    let nu = band.nu();
    let grid = opts.grid.min(SMOOTH_GRID);
    let crack_path = || {
        let mut b = Builder::new(0);
        b.polyline(&corners);
        let (start, commands) = b.into_commands();
        ContourPath {
            start: start.unwrap_or_default(),
            commands,
            ..ContourPath::default()
        }
    };
    let m = corners.len();
    if m < 4 {
        return crack_path();
    }
    let reference = {
        let c = crack_path();
        Reference::new(c.start, &c.commands)
    };
    let cells = Cells::new(&corners, band, nu.ceil() as i64 + 3);
    let reach = Reach::new(&corners, &cells, nu + POLYGON_SLACK);
    let mut verts: Vec<usize> = reach.fewest_vertices();
    let mut forced_corner = vec![false; m];
    let mut no_merge = vec![false; m];
    let mut no_adjust = vec![false; m];
    for _ in 0..MAX_ROUNDS {
        let vs = vertices(
            &verts,
            &corners,
            &cells,
            &forced_corner,
            &no_adjust,
            nu,
            grid,
        );
        let (start, commands, items) = draw(&vs, &corners, &cells, &no_merge, nu, grid);
        let wrong: Vec<_> =
            misplaced_pixels(&reference, start, &commands, opts.clipping, opts.canvas)
                .into_iter()
                .filter(|q| !band.free(i64::from(q.x), i64::from(q.y)))
                .collect();
        if wrong.is_empty() {
            let out = ContourPath {
                start,
                commands,
                ..ContourPath::default()
            };
            return out;
        }
        if !repair(
            &wrong,
            &vs,
            &items,
            &mut verts,
            &mut forced_corner,
            &mut no_merge,
            &mut no_adjust,
        ) {
            break;
        }
    }
    let mut out = crack_path();
    out.fallbacks.invalid_pieces += 1;
    out
}

/// The line fitted to points by least squares: a point on it and its unit direction.
#[derive(Clone, Copy, Debug)]
struct FitLine {
    at: Point,
    dir: Vec2,
}

impl FitLine {
    /// The least-squares line of `pts` (their centroid and principal direction). Returns
    /// `None` for fewer than two distinct points.
    fn of(pts: impl Iterator<Item = Point> + Clone) -> Option<FitLine> {
        let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for p in pts.clone() {
            n += 1.0;
            sx += p.x;
            sy += p.y;
        }
        if n < 2.0 {
            return None;
        }
        let c = Point::new(sx / n, sy / n);
        let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
        for p in pts {
            let d = p - c;
            xx += d.x * d.x;
            xy += d.x * d.y;
            yy += d.y * d.y;
        }
        let angle = 0.5 * (2.0 * xy).atan2(xx - yy);
        let dir = Vec2::new(angle.cos(), angle.sin());
        (xx + yy > 0.0).then_some(FitLine { at: c, dir })
    }

    /// Squared distance of `p` to the line.
    fn dist2(&self, p: Point) -> f64 {
        let c = self.dir.cross(p - self.at);
        c * c
    }
}

/// The polygon's vertices moved (within half a pixel, potrace's rule) to where the lines
/// fitted to the crack corners of their two edges meet best, so that the edges run through
/// the middle of the border's steps rather than along their outer corners; each edge whose
/// region against the crack path would then hold a constraint pixel keeps its vertices
/// where they were.
///
/// Vertices stay on the grid of `2^(1 − grid)` px, so that the midpoints of the edges, where
/// the curves start and end, are on the path's grid of `2^−grid` px.
fn adjusted(
    verts: &[usize],
    corners: &[Point],
    cells: &Cells,
    no_adjust: &[bool],
    grid: u8,
) -> Vec<Point> {
    let steps = 1i32 << grid.saturating_sub(1).min(4);
    let m = corners.len();
    let p = verts.len();
    let span = |k: usize| {
        let (a, b) = (verts[k], verts[(k + 1) % p]);
        let len = (b + m - a) % m;
        (a, if len == 0 { m } else { len })
    };
    let lines: Vec<Option<FitLine>> = (0..p)
        .map(|k| {
            let (a, len) = span(k);
            FitLine::of((0..=len).map(|i| corners[(a + i) % m]))
        })
        .collect();
    let mut pos: Vec<Point> = verts.iter().map(|&v| corners[v % m]).collect();
    for k in 0..p {
        if no_adjust[verts[k] % m] {
            continue;
        }
        let (Some(l0), Some(l1)) = (lines[(k + p - 1) % p], lines[k]) else {
            continue;
        };
        let o = pos[k];
        let q = |x: Point| l0.dist2(x) + l1.dist2(x);
        let mut best = (q(o), o);
        for i in 0..=steps {
            for j in 0..=steps {
                let step = |k: i32| f64::from(k) / f64::from(steps) - 0.5;
                let c = o + Vec2::new(step(i), step(j));
                if !cells.in_image(c) {
                    continue;
                }
                let v = q(c);
                if v < best.0 - 1e-12 {
                    best = (v, c);
                }
            }
        }
        pos[k] = best.1;
    }
    // Edges whose region holds a constraint pixel go back to the crack corners.
    for _ in 0..3 {
        let mut reverted = false;
        for k in 0..p {
            let (a, len) = span(k);
            let (s, e) = (pos[k], pos[(k + 1) % p]);
            if s == corners[a % m] && e == corners[(a + len) % m] {
                continue;
            }
            let mut poly = Vec::with_capacity(len + 3);
            poly.push(s);
            poly.push(e);
            for i in (0..=len).rev() {
                poly.push(corners[(a + i) % m]);
            }
            if !cells.region_free(&poly) {
                pos[k] = corners[a % m];
                pos[(k + 1) % p] = corners[(a + len) % m];
                reverted = true;
            }
        }
        if !reverted {
            break;
        }
    }
    pos
}

/// The vertices of the polygon `verts` (crack indices) with their drawing decided.
fn vertices(
    verts: &[usize],
    corners: &[Point],
    cells: &Cells,
    forced_corner: &[bool],
    no_adjust: &[bool],
    nu: f64,
    grid: u8,
) -> Vec<Vertex> {
    let m = corners.len();
    let p = verts.len();
    let pos = adjusted(verts, corners, cells, no_adjust, grid);
    let at = |k: usize| pos[k % p];
    let mut out = Vec::with_capacity(p);
    for k in 0..p {
        let (prev, v, next) = (at(k + p - 1), at(k), at(k + 1));
        let crack = verts[k] % m;
        let mut vertex = Vertex {
            crack,
            p: v,
            adjusted: v != corners[crack],
            corner: true,
            controls: [v, v],
        };
        if !forced_corner[crack] && p >= 3 {
            let chord = next - prev;
            let len = chord.hypot();
            let dist = if len > 0.0 {
                chord.cross(v - prev).abs() / len
            } else {
                f64::INFINITY
            };
            let d = dist / (2.0 * nu);
            let alpha = if d > 1.0 { (1.0 - 1.0 / d) / 0.75 } else { 0.0 };
            vertex.corner = alpha >= ALPHA_MAX;
        }
        out.push(vertex);
    }
    // The curves, fitted to the crack corners; those that fail stay corners.
    let fits: Vec<Option<CubicBez>> = (0..p)
        .map(|k| {
            if out[k].corner {
                None
            } else {
                merged(&out, |q| q % p, k, k, corners, cells, nu)
            }
        })
        .collect();
    for (v, fit) in out.iter_mut().zip(fits) {
        match fit {
            Some(c) => v.controls = [c.p1, c.p2],
            None => v.corner = true,
        }
    }
    out
}

/// The rotation of the vertices to start drawing from: a corner if any, else where the
/// turn changes direction, else 0.
fn start_index(vs: &[Vertex]) -> usize {
    let p = vs.len();
    if let Some(k) = vs.iter().position(|v| v.corner) {
        return k;
    }
    let turn = |k: usize| {
        let (a, b, c) = (vs[(k + p - 1) % p].p, vs[k].p, vs[(k + 1) % p].p);
        (b - a).cross(c - b) > 0.0
    };
    (0..p)
        .find(|&k| turn(k) != turn((k + p - 1) % p))
        .unwrap_or(0)
}

/// The path of the vertices: its start, commands and what drew each part.
fn draw(
    vs: &[Vertex],
    corners: &[Point],
    cells: &Cells,
    no_merge: &[bool],
    nu: f64,
    grid: u8,
) -> (Point, Vec<PathCommand>, Vec<(Item, kurbo::Rect)>) {
    let p = vs.len();
    let s = start_index(vs);
    let idx = |k: usize| (s + k) % p;
    let mid = |k: usize| vs[idx(k + p - 1)].p.midpoint(vs[idx(k)].p);
    let mut b = Builder::new(grid);
    let mut items = Vec::with_capacity(p);
    // The path starts at the midpoint of the edge before the first vertex.
    b.goto(mid(0));
    let mut k = 0;
    while k < p {
        let v = vs[idx(k)];
        let from = mid(k);
        let to = mid(k + 1);
        if v.corner {
            b.goto(v.p);
            b.goto(to);
            let r = kurbo::Rect::from_points(from, v.p).union_pt(to);
            items.push((Item::Corner(v.crack), r));
            k += 1;
            continue;
        }
        // The longest run of curves from k that merges into one cubic.
        let mut best: Option<(usize, CubicBez)> = None;
        let mut j = k + 1;
        let mut misses = 0;
        while j < p && !no_merge[v.crack] && misses < 2 {
            let w = vs[idx(j)];
            if w.corner || no_merge[w.crack] {
                break;
            }
            match merged(vs, idx, k, j, corners, cells, nu) {
                Some(c) => {
                    best = Some((j, c));
                    misses = 0;
                }
                None => {
                    if !same_turn(vs, idx, k, j) {
                        break;
                    }
                    misses += 1;
                }
            }
            j += 1;
        }
        match best {
            Some((last, c)) => {
                let c = snap_cubic(&b, c);
                b.extend(&[PathCommand::Cubic(c.p1, c.p2, c.p3)]);
                let r = cubic_bounds(&c);
                items.push((
                    Item::Run {
                        first: vs[idx(k)].crack,
                        last: vs[idx(last)].crack,
                    },
                    r,
                ));
                k = last + 1;
            }
            None => {
                let c = CubicBez::new(from, v.controls[0], v.controls[1], to);
                let c = snap_cubic(&b, c);
                b.extend(&[PathCommand::Cubic(c.p1, c.p2, c.p3)]);
                items.push((Item::Curve(v.crack), cubic_bounds(&c)));
                k += 1;
            }
        }
    }
    let (start, commands) = b.into_commands();
    (start.unwrap_or_default(), commands, items)
}

fn snap_cubic(b: &Builder, c: CubicBez) -> CubicBez {
    CubicBez::new(b.snap(c.p0), b.snap(c.p1), b.snap(c.p2), b.snap(c.p3))
}

fn cubic_bounds(c: &CubicBez) -> kurbo::Rect {
    kurbo::Rect::from_points(c.p0, c.p3)
        .union_pt(c.p1)
        .union_pt(c.p2)
}

/// True when the vertices `k..=j` all turn the same way and less than
/// [`MAX_RUN_TURN_DEGREES`] in all.
fn same_turn(vs: &[Vertex], idx: impl Fn(usize) -> usize, k: usize, j: usize) -> bool {
    let p = vs.len();
    let mut total = 0.0;
    let mut sign = 0.0;
    for q in k..=j {
        let (a, b, c) = (vs[idx(q + p - 1)].p, vs[idx(q)].p, vs[idx(q + 1)].p);
        let (u, w) = (b - a, c - b);
        let cr = u.cross(w);
        if cr == 0.0 {
            continue;
        }
        if sign != 0.0 && cr.signum() != sign {
            return false;
        }
        sign = cr.signum();
        total += cr.atan2(u.dot(w)).abs();
    }
    total.to_degrees() < MAX_RUN_TURN_DEGREES
}

/// The crack corner index halfway along the edge from crack corner `a` to `b`.
fn mid_index(a: usize, b: usize, m: usize) -> usize {
    let span = match (b + m - a) % m {
        0 => m,
        s => s,
    };
    a + span / 2
}

/// The point of `c` nearest to `q`, as its parameter (sampled, then refined by Newton).
fn nearest_t(c: &CubicBez, q: Point, t0: f64) -> f64 {
    let mut t = t0;
    let mut best = (c.eval(t) - q).hypot2();
    for i in 0..=16 {
        let s = i as f64 / 16.0;
        let d = (c.eval(s) - q).hypot2();
        if d < best {
            best = d;
            t = s;
        }
    }
    let d1 = c.deriv();
    let d2 = d1.deriv();
    for _ in 0..3 {
        let e = c.eval(t) - q;
        let v = d1.eval(t).to_vec2();
        let f = e.dot(v);
        let g = v.dot(v) + e.dot(d2.eval(t).to_vec2());
        if g.abs() < 1e-12 {
            break;
        }
        t = (t - f / g).clamp(0.0, 1.0);
    }
    t
}

/// Handle lengths `a`, `b` of the cubic `p0, p0 + a u0, p3 − b u1, p3` closest (least
/// squares) to `data` at parameters `t`.
fn handles(
    p0: Point,
    p3: Point,
    u0: Vec2,
    u1: Vec2,
    data: &[Point],
    t: &[f64],
) -> Option<(f64, f64)> {
    let (mut c11, mut c12, mut c22, mut x1, mut x2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (q, &s) in data.iter().zip(t) {
        let r = 1.0 - s;
        let (b0, b1, b2, b3) = (r * r * r, 3.0 * s * r * r, 3.0 * s * s * r, s * s * s);
        let a1 = u0 * b1;
        let a2 = -u1 * b2;
        let base = p0.to_vec2() * (b0 + b1) + p3.to_vec2() * (b2 + b3);
        let rest = q.to_vec2() - base;
        c11 += a1.dot(a1);
        c12 += a1.dot(a2);
        c22 += a2.dot(a2);
        x1 += a1.dot(rest);
        x2 += a2.dot(rest);
    }
    let det = c11 * c22 - c12 * c12;
    if det.abs() < 1e-12 {
        return None;
    }
    let a = (x1 * c22 - x2 * c12) / det;
    let b = (c11 * x2 - c12 * x1) / det;
    (a.is_finite() && b.is_finite()).then_some((a, b))
}

/// One cubic for the vertices `k..=j` (one vertex when `j == k`): from the midpoint of the
/// edge before `k` to the midpoint of the edge after `j`, tangent to both edges, its handle
/// lengths fitted by least squares to the crack corners in between. `None` unless the turn
/// is one-way and small enough, the handles stop short of where the tangents meet, the
/// cubic stays within `ν +` [`CURVE_SLACK`] of those corners both ways, and the region between
/// it and the crack path holds no constraint pixel.
#[allow(clippy::too_many_arguments)]
fn merged(
    vs: &[Vertex],
    idx: impl Fn(usize) -> usize + Copy,
    k: usize,
    j: usize,
    corners: &[Point],
    cells: &Cells,
    nu: f64,
) -> Option<CubicBez> {
    if j > k && !same_turn(vs, idx, k, j) {
        return None;
    }
    let p = vs.len();
    let m = corners.len();
    let (vk, vj) = (vs[idx(k)], vs[idx(j)]);
    let (before, after) = (vs[idx(k + p - 1)], vs[idx(j + 1)]);
    let p0 = before.p.midpoint(vk.p);
    let p3 = vj.p.midpoint(after.p);
    let u0 = unit(vk.p - before.p)?;
    let u1 = unit(after.p - vj.p)?;
    let c0 = mid_index(before.crack, vk.crack, m);
    let mut c1 = mid_index(vj.crack, after.crack, m);
    while c1 < c0 {
        c1 += m;
    }
    if c1 - c0 >= m {
        return None;
    }
    // The data: the crack corners between the ends.
    let mut data = Vec::with_capacity(c1 - c0 + 3);
    data.push(p0);
    data.extend((c0..=c1).map(|i| corners[i % m]));
    data.push(p3);
    let mut t = Vec::with_capacity(data.len());
    let mut acc = 0.0;
    for (i, q) in data.iter().enumerate() {
        if i > 0 {
            acc += (*q - data[i - 1]).hypot();
        }
        t.push(acc);
    }
    if acc <= 0.0 {
        return None;
    }
    for x in &mut t {
        *x /= acc;
    }
    let (mut a, mut b) = handles(p0, p3, u0, u1, &data, &t)?;
    for _ in 0..2 {
        if !(a > 0.0 && b > 0.0) {
            break;
        }
        let c = CubicBez::new(p0, p0 + u0 * a, p3 - u1 * b, p3);
        for (x, q) in t.iter_mut().zip(&data) {
            *x = nearest_t(&c, *q, *x);
        }
        (a, b) = handles(p0, p3, u0, u1, &data, &t)?;
    }
    // Handles stop short of where the end tangents meet (no inflection, no loop).
    let chord = p3 - p0;
    let denom = u0.cross(u1);
    let (ta, tb) = if denom.abs() > 1e-9 {
        (chord.cross(u1) / denom, -chord.cross(u0) / denom)
    } else {
        (chord.hypot(), chord.hypot())
    };
    if !(ta > 0.0 && tb > 0.0) {
        return None;
    }
    let (a, b) = (a.clamp(0.3 * ta, ta), b.clamp(0.3 * tb, tb));
    let c = CubicBez::new(p0, p0 + u0 * a, p3 - u1 * b, p3);
    // Inside the image, so not cut at its border by the renderer.
    if !(cells.in_image(c.p1) && cells.in_image(c.p2)) {
        return None;
    }
    let mut new = Vec::with_capacity(64);
    flatten(&c, &mut new);
    let crack: Vec<Point> = (c0..=c1).map(|i| corners[i % m]).collect();
    // Within the tolerance of the crack corners both ways.
    let tol = nu + CURVE_SLACK;
    let near = |q: Point, line: &[Point]| {
        if line.len() == 1 {
            return (q - line[0]).hypot();
        }
        line.windows(2)
            .map(|w| segment_distance(q, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    };
    if crack.iter().any(|&q| near(q, &new) > tol) || new.iter().any(|&q| near(q, &crack) > tol) {
        return None;
    }
    // No constraint pixel between the cubic and the crack path.
    let mut region = new;
    region.extend(crack.iter().rev());
    cells.region_free(&region).then_some(c)
}

/// Undoes what drew near the wrong pixels: merged runs first, then curves, then splits the
/// polygon edges there. Returns false when nothing could be changed.
fn repair(
    wrong: &[crate::pixel::Pixel],
    vs: &[Vertex],
    items: &[(Item, kurbo::Rect)],
    verts: &mut Vec<usize>,
    forced_corner: &mut [bool],
    no_merge: &mut [bool],
    no_adjust: &mut [bool],
) -> bool {
    let m = forced_corner.len();
    let near = |r: &kurbo::Rect, q: &crate::pixel::Pixel| {
        let c = Point::new(f64::from(q.x) + 0.5, f64::from(q.y) + 0.5);
        r.inflate(1.5, 1.5).contains(c)
    };
    let mut changed = false;
    for level in 0..3 {
        for (item, r) in items {
            if !wrong.iter().any(|q| near(r, q)) {
                continue;
            }
            match (*item, level) {
                (Item::Run { first, last }, 0) => {
                    // Crack indices of the run's vertices.
                    for v in vs {
                        let inside = if first <= last {
                            (first..=last).contains(&v.crack)
                        } else {
                            v.crack >= first || v.crack <= last
                        };
                        if inside && !no_merge[v.crack] {
                            no_merge[v.crack] = true;
                            changed = true;
                        }
                    }
                }
                (Item::Curve(c), 1) if !forced_corner[c] => {
                    forced_corner[c] = true;
                    changed = true;
                }
                (Item::Corner(c), 2) if vs.iter().any(|v| v.crack == c && v.adjusted) => {
                    no_adjust[c] = true;
                    changed = true;
                }
                (Item::Corner(c), 2) => {
                    // Split the two edges at this corner at the crack corners halfway.
                    if let Some(pos) = verts.iter().position(|&v| v % m == c) {
                        let p = verts.len();
                        let here = verts[pos];
                        let before = verts[(pos + p - 1) % p];
                        let after = verts[(pos + 1) % p];
                        let span = |a: usize, b: usize| (b + m - a % m) % m;
                        let mut add = Vec::new();
                        if span(before, here) > 1 {
                            add.push((before % m + span(before, here) / 2) % m);
                        }
                        if span(here, after) > 1 {
                            add.push((here % m + span(here, after) / 2) % m);
                        }
                        for a in add {
                            forced_corner[a] = true;
                            verts.push(a);
                            changed = true;
                        }
                        forced_corner[c] = true;
                    }
                }
                _ => {}
            }
        }
        if changed {
            break;
        }
    }
    if changed {
        for v in verts.iter_mut() {
            *v %= m;
        }
        verts.sort_unstable();
        verts.dedup();
    }
    changed
}
