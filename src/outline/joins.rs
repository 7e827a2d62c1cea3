//! One drawing of a contour: each stretch along its curve between junctions shared with its
//! neighbours, or along its cracks.
//!
//! Consecutive stretches `k` and `k+1` (and the last with the first: contours are closed)
//! meet near their adjacent end pixels `a = p_last(k)`, `b = p_first(k+1)`; let `m` be the
//! middle of their centres.
//! * Both have curves: the junction is their intersection closest to `m` within
//!   [`JUNCTION_MAX_DISTANCE`] ([`intersect_near`]).
//! * Otherwise (no intersection that close, e.g. nearly parallel lines, or a neighbour
//!   along cracks): stretch `k` ends at the projection of `m` on its curve (or at its last
//!   crack corner), stretch `k+1` starts at the projection of `m` on its own, and a straight
//!   segment bridges the two.
//! * A *cracked* junction draws pixels `a` and `b` along their cracks and each curve ends
//!   at the projection of the nearer crack corner.
//! * Two straight segments of the exact polygon bridged that way share one vertex instead
//!   where both still separate their pixels from the background ([`super::vertices`]),
//!   unless the render check asked for the bridge back (`keep_bridge`); a straight segment
//!   bridged to a curve ends (or starts) where the curve does, on the same terms.
//! * A contour of one stretch with a curve runs once round it, from and back to the
//!   projection of `m`.
//!
//! A stretch whose curve does not come within [`JUNCTION_MAX_DISTANCE`] of a junction, that
//! [`level_curve_path`] cannot draw, or that strays farther than [`STRAY_MARGIN`] from its
//! pixels is drawn along its cracks in this drawing and reported, to be refined.

use super::builder::Builder;
use super::cracks::{centre, crack_polyline_into, first_crack_corner, last_crack_corner};
use super::path::ContourPath;
use super::stretch::{Drawing, Stretch};
use super::vertices::{separates, shared_vertex, Sides};
use crate::curve::{intersect_near, level_curve_path, project, LevelPath, PathCommand};
use crate::pixel::Pixel;
use kurbo::{BezPath, Point};
use rustc_hash::FxHashMap as HashMap;

/// Largest distance (pixels) from the middle of two adjacent end pixels' centres to the
/// junction of their pieces' curves, or to the projection used instead.
pub const JUNCTION_MAX_DISTANCE: f64 = 1.5;

/// A piece's curve between its junctions must stay within this distance (pixels) of the
/// bounding box of the piece's pixels, or the piece falls back to its cracks: a level curve
/// may run far from the pixels where no outlier holds it (e.g. round a huge circle when the
/// whole contour is one piece).
pub const STRAY_MARGIN: f64 = 2.0;

/// A stretch's drawing between two end points: its commands and fitting error, or `None`
/// when it cannot be drawn.
type Drawn = Option<LevelPath>;

/// What one drawing computes that the next can reuse: the intersection at each junction
/// (it depends only on the two curves and `m`) and each stretch's path between given end
/// points, keyed by stretch ids.
#[derive(Default)]
pub(crate) struct Memo {
    intersections: HashMap<(usize, usize), Option<Point>>,
    paths: HashMap<(usize, [u64; 4]), Drawn>,
    /// The projection of a target point on a stretch's curve, by stretch id and target
    /// (the same junctions are projected again in every drawing).
    projections: HashMap<(usize, [u64; 2]), Option<Point>>,
    /// The centres each straight segment separates, by stretch id.
    sides: HashMap<usize, Sides>,
    /// The shared vertex (or `None`) of two straight segments at their junction, by their
    /// stretch ids and their other ends (which may be vertices shared with their other
    /// neighbours): every round asked again for the same junctions.
    shared: HashMap<(usize, usize, [u64; 4]), Option<Point>>,
}

/// A drawing and the stretches that could not be drawn along their curve in it.
pub(crate) struct Built {
    /// The path.
    pub path: ContourPath,
    /// Per command of the path: a segment of a polygon that may be smoothed.
    pub smooth: Vec<bool>,
    /// Per junction: the two straight segments share a vertex off their lines.
    pub shared: Vec<bool>,
    /// Indices of stretches with a curve drawn along their cracks instead.
    pub failed: Vec<usize>,
}

/// True when the path from `from` along `cmds` stays within [`STRAY_MARGIN`] of the
/// bounding box of the pixels (squares) of its piece.
fn stays_near(from: Point, cmds: &[PathCommand], pixels: &[Pixel]) -> bool {
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in pixels {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        x0 = x0.min(x);
        y0 = y0.min(y);
        x1 = x1.max(x + 1.0);
        y1 = y1.max(y + 1.0);
    }
    let allowed = kurbo::Rect::new(x0, y0, x1, y1).inflate(STRAY_MARGIN, STRAY_MARGIN);
    let mut path = BezPath::new();
    path.move_to(from);
    let mut pen = from;
    for c in cmds {
        c.push_path_els(pen, &mut path);
        pen = c.end();
    }
    let b = kurbo::Shape::bounding_box(&path);
    b.x0 >= allowed.x0 && b.y0 >= allowed.y0 && b.x1 <= allowed.x1 && b.y1 <= allowed.y1
}

/// The centres straight segment `s` separates, computed once per stretch.
fn sides_of<'m>(memo: &'m mut Memo, points: &[Pixel], s: &Stretch) -> &'m Sides {
    memo.sides
        .entry(s.id)
        .or_insert_with(|| Sides::of(points, s.first, s.last))
}

/// One drawing of a contour's `stretches` on the grid of `2^-grid` px; `cracked[j]` draws
/// the end pixel of stretch `j` and the start pixel of the next one along their cracks.
pub(crate) fn build(
    points: &[Pixel],
    stretches: &[Stretch],
    cracked: &[bool],
    keep_bridge: &[bool],
    memo: &mut Memo,
    grid: u8,
    smooth: bool,
) -> Built {
    let mut out = ContourPath::default();
    let m = stretches.len();
    // (A command or two per stretch, mostly: no reallocation.)
    let mut b = Builder::with_capacity(grid, 2 * m + 4);
    let mut use_curve: Vec<bool> = stretches.iter().map(|s| s.poly.is_some()).collect();
    let mut failed = Vec::new();
    // A stretch whose both end pixels are cracked and that has no more than one pixel
    // between them is drawn along its cracks.
    for k in 0..m {
        if use_curve[k] && cracked[(k + m - 1) % m] && cracked[k] && stretches[k].len() <= 3 {
            use_curve[k] = false;
        }
    }
    // The first and last crack corners of stretch `k` (without its crack polyline).
    let first_corner = |k: usize| first_crack_corner(points, stretches[k].first, stretches[k].last);
    let last_corner = |k: usize| last_crack_corner(points, stretches[k].first, stretches[k].last);
    // Junction j joins stretch j (its end) and stretch (j + 1) % m (its start).
    let mut ends = vec![Point::ZERO; m];
    let mut starts = vec![Point::ZERO; m];
    let mut bridged = vec![false; m];
    loop {
        out.joins = Default::default();
        bridged.iter_mut().for_each(|v| *v = false);
        let mut lost = Vec::new();
        for j in 0..m {
            let k = (j + 1) % m;
            let (sj, sk) = (&stretches[j], &stretches[k]);
            let (a, bi) = (sj.last, sk.first);
            let mid = centre(points[a]).midpoint(centre(points[bi]));
            let (end_target, start_target) = if cracked[j] {
                out.joins.cracked += 1;
                (
                    first_crack_corner(points, a, a).unwrap_or(mid),
                    last_crack_corner(points, bi, bi).unwrap_or(mid),
                )
            } else {
                if let (true, true, Some(pa), Some(pb)) =
                    (use_curve[j], use_curve[k], &sj.poly, &sk.poly)
                {
                    if j != k {
                        let x = *memo
                            .intersections
                            .entry((sj.id, sk.id))
                            .or_insert_with(|| intersect_near(pa, pb, mid, JUNCTION_MAX_DISTANCE));
                        if let Some(x) = x {
                            ends[j] = x;
                            starts[k] = x;
                            out.joins.intersection += 1;
                            continue;
                        }
                    }
                }
                out.joins.bridged += 1;
                bridged[j] = true;
                (mid, mid)
            };
            let mut project = |id: usize, poly, target: Point| {
                *memo
                    .projections
                    .entry((id, [target.x.to_bits(), target.y.to_bits()]))
                    .or_insert_with(|| project(poly, target, JUNCTION_MAX_DISTANCE))
            };
            match (&sj.poly, use_curve[j]) {
                (Some(pa), true) => match project(sj.id, pa, end_target) {
                    Some(x) => ends[j] = x,
                    None => lost.push(j),
                },
                _ => ends[j] = last_corner(j).unwrap_or(mid),
            }
            match (&sk.poly, use_curve[k]) {
                (Some(pb), true) => match project(sk.id, pb, start_target) {
                    Some(x) => starts[k] = x,
                    None => lost.push(k),
                },
                _ => starts[k] = first_corner(k).unwrap_or(mid),
            }
        }
        if lost.is_empty() {
            break;
        }
        for j in lost {
            if use_curve[j] {
                use_curve[j] = false;
                failed.push(j);
            }
        }
    }
    // Straight segments bridged at a junction share a vertex where they can; a straight
    // segment beside a curve ends (or starts) where the curve does, when it still keeps
    // its sides apart from there.
    let straight = |k: usize| use_curve[k] && stretches[k].drawing == Drawing::Straight;
    let curve = |k: usize| use_curve[k] && stretches[k].drawing == Drawing::Curve;
    let mut shared = vec![false; m];
    for j in 0..m {
        let k = (j + 1) % m;
        if j == k || keep_bridge[j] || !bridged[j] {
            continue;
        }
        let v = if straight(j) && straight(k) {
            sides_of(memo, points, &stretches[j]);
            sides_of(memo, points, &stretches[k]);
            // (`ends[j]` and `starts[k]`, the projections of the junction on the two
            // lines, are fixed by the stretches.) The outer ends are passed where they
            // are written, so that the row check sees the segments tiny-skia will draw.
            let key = (
                stretches[j].id,
                stretches[k].id,
                [starts[j].x, starts[j].y, ends[k].x, ends[k].y].map(f64::to_bits),
            );
            *memo.shared.entry(key).or_insert_with(|| {
                shared_vertex(
                    points,
                    stretches[j].last,
                    stretches[k].first,
                    b.snap(starts[j]),
                    ends[j],
                    starts[k],
                    b.snap(ends[k]),
                    &memo.sides[&stretches[j].id],
                    &memo.sides[&stretches[k].id],
                    |p| b.snap(p),
                )
            })
        } else if straight(j) && curve(k) {
            // Where the curve's start is written.
            let v = b.snap(starts[k]);
            let sides = sides_of(memo, points, &stretches[j]);
            separates(b.snap(starts[j]), v, sides).then_some(v)
        } else if curve(j) && straight(k) {
            let v = b.snap(ends[j]);
            let sides = sides_of(memo, points, &stretches[k]);
            separates(v, b.snap(ends[k]), sides).then_some(v)
        } else {
            None
        };
        if let Some(v) = v {
            shared[j] = true;
            ends[j] = v;
            starts[k] = v;
            out.joins.shared += 1;
            out.joins.bridged -= 1;
        }
    }
    // The cracks of pixels `first..=last`, drawn through one buffer.
    let mut crack_buf: Vec<Point> = Vec::new();
    let mut draw_cracks = |first: usize, last: usize, b: &mut Builder| {
        crack_polyline_into(points, first, last, &mut crack_buf);
        b.polyline(&crack_buf);
    };
    for (k, s) in stretches.iter().enumerate() {
        // The segments of polygons (and the bridges into them) may become cubics.
        b.smooth = smooth && s.drawing == Drawing::Straight;
        let poly = match (&s.poly, use_curve[k]) {
            (Some(p), true) => p,
            _ => {
                draw_cracks(s.first, s.last, &mut b);
                continue;
            }
        };
        let head = cracked[(k + m - 1) % m];
        let tail = cracked[k];
        if head {
            draw_cracks(s.first, s.first, &mut b);
        }
        let (from, to) = (starts[k], ends[k]);
        b.goto(from);
        if s.drawing == Drawing::Straight && m > 1 {
            // A straight segment; its ends may be vertices shared with its neighbours,
            // off its own line.
            b.goto(to);
        } else if !(m > 1 || head || tail) || (to - from).hypot() > 1e-9 {
            let key = (s.id, [from.x, from.y, to.x, to.y].map(f64::to_bits));
            let drawn = memo
                .paths
                .entry(key)
                .or_insert_with(|| {
                    let pixels = &points[s.first..=s.last];
                    let guide: Vec<Point> = pixels.iter().map(|&p| centre(p)).collect();
                    level_curve_path(poly, from, to, &guide, s.tolerance)
                        .filter(|p| stays_near(from, &p.commands, pixels))
                })
                .clone();
            match drawn {
                Some(p) => {
                    out.max_fit_error = out.max_fit_error.max(p.max_error);
                    b.extend(&p.commands);
                }
                None => {
                    failed.push(k);
                    draw_cracks(s.first, s.last, &mut b);
                }
            }
        }
        if tail {
            draw_cracks(s.last, s.last, &mut b);
        }
    }
    let (start, commands, tags) = b.into_tagged();
    out.start = start.unwrap_or_default();
    out.commands = commands;
    failed.sort_unstable();
    failed.dedup();
    Built {
        path: out,
        smooth: tags,
        shared,
        failed,
    }
}
