//! A coarse stand-in for a contour's crack polygon that tiny-skia fills exactly like it.
//!
//! The render check fills every drawing together with the contour's crack polygon reversed
//! ([`super::render_check`]). The crack polygon has a vertical edge per run of pixel rows
//! at one `x`: on a gently sloping border, one per row, and most of a fill's cost is
//! setting up, sorting and retiring those edges. tiny-skia's scan converter (without
//! anti-aliasing) sees a polygon only through where its edges cross each row's centre line
//! `y = k + ½`: the crossing `x`, rounded to the nearest integer, is where a span of pixels
//! starts or ends, and the edge's direction is added to the winding there. So a polygon
//! whose edges cross every row centre with the same directions, within `±½` of the crack
//! edges' `x` (here within [`HALF_WIDTH`], far from the rounding points), is filled the same,
//! pixel for pixel and winding for winding.
//!
//! The crack polygon is cut into chains whose vertical edges run the same way in `y`
//! (down or up). Each chain is covered greedily by straight segments from one row boundary
//! to another: a segment must cross every row centre it spans inside the corridor
//! `s_k ± HALF_WIDTH` around that row's crack `x`, i.e. separate the corridors' left ends
//! from their right ends — an exact, incremental integer test in 1/64 px
//! ([`super::separation`]). A run of rows with the same crack `x` is constrained by its
//! first and last rows only (the others lie between them on both sides). Consecutive
//! segments, and consecutive chains, meet by horizontal edges on row boundaries, which
//! cross no row centre.

use super::builder::Builder;
use super::separation::Separation;
use super::MAX_GRID;
use crate::curve::PathCommand;
use kurbo::Point;

/// Half the corridor a coarse edge crosses each row centre in, around the crack's `x`, in
/// 1/64 px: 30/64 px, below ½ by more than the vertex snapping (1/128 px) and tiny-skia's
/// 16.16 fixed-point slope over at most [`MAX_ROWS`] rows (under 1/200 px).
const CORRIDOR_64: i64 = 30;

/// [`CORRIDOR_64`] in pixels, with the snapping allowed: no crossing is farther from the
/// crack's `x` (checked).
const HALF_WIDTH: f64 = (CORRIDOR_64 as f64 + 0.5) / 64.0;

/// Most rows one coarse edge spans (bounds tiny-skia's fixed-point drift along it).
const MAX_ROWS: usize = 256;

/// One row a chain crosses, in the chain's order: the row `k` (centre `k + ½`) and the
/// crack's `x` there.
#[derive(Clone, Copy)]
struct Row {
    k: i64,
    s: f64,
}

/// The coarse polygon of the closed axis-parallel polygon `M start commands Z` (lines with
/// integer vertices: a contour's cracks), as its start and lines. Returns `None` when the
/// polygon has an edge that is neither horizontal nor vertical, a non-integer vertex, or no
/// vertical edge.
pub(crate) fn coarse_cracks(
    start: Point,
    commands: &[PathCommand],
) -> Option<(Point, Vec<PathCommand>)> {
    let mut pts = Vec::with_capacity(commands.len() + 1);
    pts.push(start);
    for c in commands {
        match *c {
            PathCommand::Line(p) => pts.push(p),
            _ => return None,
        }
    }
    if pts.iter().any(|p| p.x.fract() != 0.0 || p.y.fract() != 0.0) {
        return None;
    }
    // Vertical edges in order: (x, from y, to y).
    let m = pts.len();
    let mut verticals: Vec<(f64, i64, i64)> = Vec::new();
    for i in 0..m {
        let (a, b) = (pts[i], pts[(i + 1) % m]);
        if a.x == b.x {
            if a.y != b.y {
                verticals.push((a.x, a.y as i64, b.y as i64));
            }
        } else if a.y != b.y {
            return None;
        }
    }
    let down = |v: &(f64, i64, i64)| v.2 > v.1;
    let nv = verticals.len();
    // Start at a change of direction (a closed polygon goes both ways).
    let first = (0..nv).find(|&j| down(&verticals[j]) != down(&verticals[(j + nv - 1) % nv]))?;
    let mut out: Vec<Point> = Vec::new();
    let mut rows: Vec<Row> = Vec::new();
    let mut j = 0;
    while j < nv {
        // One chain: the vertical edges from `first + j` running the same way.
        let dir = down(&verticals[(first + j) % nv]);
        rows.clear();
        while j < nv && down(&verticals[(first + j) % nv]) == dir {
            let (x, y0, y1) = verticals[(first + j) % nv];
            if dir {
                rows.extend((y0..y1).map(|k| Row { k, s: x }));
            } else {
                rows.extend((y1..y0).rev().map(|k| Row { k, s: x }));
            }
            j += 1;
        }
        cover_chain(&rows, dir, &mut out)?;
    }
    let start = out[0];
    let commands = out[1..].iter().map(|&p| PathCommand::Line(p)).collect();
    Some((start, commands))
}

/// Covers the rows of one chain (in order, running down when `down`) with straight
/// segments, each crossing every row centre it spans within [`HALF_WIDTH`] of the crack's
/// `x` there, the longest such from each start; appends each segment's two ends to `out`
/// (consecutive segments are joined by horizontal edges on row boundaries, which cross no
/// row centre). Returns `None` if a snapped segment leaves a corridor (not expected).
fn cover_chain(rows: &[Row], down: bool, out: &mut Vec<Point>) -> Option<()> {
    // Each row as two integer points in 1/64 px, the corridor's ends; a line separating the
    // left ends from the right ones crosses every row centre inside its corridor.
    let ends = |r: &Row| {
        let (x, y) = ((r.s * 64.0) as i64, r.k * 64 + 32);
        ([x - CORRIDOR_64, y], [x + CORRIDOR_64, y])
    };
    // Within a run of rows with the same crack `x`, the crossing is linear in `y` and the
    // corridor the same: the run's first and last rows imply the others.
    let constrain = |sep: &mut Separation, rows: &[Row]| -> bool {
        let mut ok = true;
        for (t, r) in rows.iter().enumerate() {
            let end_of_run =
                t == 0 || t + 1 == rows.len() || rows[t - 1].s != r.s || rows[t + 1].s != r.s;
            if end_of_run {
                let (l, h) = ends(r);
                ok &= sep.add_low(l) && sep.add_high(h);
            }
        }
        ok
    };
    // A segment's separation and the trial copy of each step, their buffers reused.
    let (mut sep, mut trial) = (Separation::new(), Separation::new());
    let mut i = 0;
    while i < rows.len() {
        let limit = rows.len().min(i + MAX_ROWS);
        sep.clear();
        let mut j = i;
        while j < limit {
            // The rest of this run (within the limit), by its two ends.
            let mut e = j + 1;
            while e < limit && rows[e].s == rows[j].s {
                e += 1;
            }
            trial.clone_from(&sep);
            let (a, b) = (ends(&rows[j]), ends(&rows[e - 1]));
            if trial.add_low(a.0)
                && trial.add_high(a.1)
                && trial.add_low(b.0)
                && trial.add_high(b.1)
            {
                std::mem::swap(&mut sep, &mut trial);
                j = e;
                continue;
            }
            // Part of the run fits: row by row.
            while j < e {
                let (l, h) = ends(&rows[j]);
                trial.clone_from(&sep);
                if !(trial.add_low(l) && trial.add_high(h)) {
                    break;
                }
                std::mem::swap(&mut sep, &mut trial);
                j += 1;
            }
            break;
        }
        debug_assert!(j > i);
        debug_assert!({
            let mut again = Separation::new();
            constrain(&mut again, &rows[i..j])
        });
        // One row alone always fits.
        let n = sep.normal()?;
        let (nx, ny) = (n[0] as f64, n[1] as f64);
        if nx <= 0.0 {
            return None;
        }
        let dot =
            |p: [i64; 2]| i128::from(n[0]) * i128::from(p[0]) + i128::from(n[1]) * i128::from(p[1]);
        let mut max_low = i128::MIN;
        let mut min_high = i128::MAX;
        for r in &rows[i..j] {
            let (l, h) = ends(r);
            max_low = max_low.max(dot(l));
            min_high = min_high.min(dot(h));
        }
        let c = (max_low as f64 + min_high as f64) / 2.0;
        // x (px) where the line crosses height y (px).
        let x_at = |y: f64| (c - ny * y * 64.0) / nx / 64.0;
        let (first, last) = (rows[i].k, rows[j - 1].k);
        let (y0, y1) = if down {
            (first, last + 1)
        } else {
            (first + 1, last)
        };
        // Vertices on the 1/64 px grid, exact in tiny-skia's fixed point (rows are integers).
        let grid = Builder::new(MAX_GRID);
        let p = grid.snap(Point::new(x_at(y0 as f64), y0 as f64));
        let q = grid.snap(Point::new(x_at(y1 as f64), y1 as f64));
        let ok = rows[i..j].iter().all(|r| {
            let x = p.x + (q.x - p.x) * (r.k as f64 + 0.5 - p.y) / (q.y - p.y);
            (x - r.s).abs() <= HALF_WIDTH
        });
        if !ok {
            return None;
        }
        out.push(p);
        out.push(q);
        i = j;
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::{trace, Convention};
    use crate::outline::cracks_path;
    use crate::outline::render_check::{misplaced_pixels, EdgeClipping, Reference};
    use crate::Mask;
    use proptest::prelude::*;

    /// The coarse polygons of every contour of `mask`, checked against the crack polygons
    /// with tiny-skia; returns (crack edges, coarse edges).
    fn check(mask: &Mask) -> (usize, usize) {
        let (mut crack_edges, mut coarse_edges) = (0, 0);
        for c in trace(mask, Convention::Default) {
            let cracks = cracks_path(&c.points);
            let Some((start, coarse)) = coarse_cracks(cracks.start, &cracks.commands) else {
                panic!("no coarse polygon for {:?}", c.points);
            };
            let reference = Reference::new(cracks.start, &cracks.commands);
            let wrong = misplaced_pixels(&reference, start, &coarse, EdgeClipping::Never, None);
            assert!(wrong.is_empty(), "{wrong:?} for {:?}", c.points);
            crack_edges += cracks.commands.len();
            coarse_edges += coarse.len();
        }
        (crack_edges, coarse_edges)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Random bitmaps: every contour's coarse polygon paints its crack polygon's pixels,
        /// winding for winding.
        #[test]
        fn fills_like_the_cracks(bits in prop::collection::vec(any::<bool>(), 12 * 10)) {
            let rows: Vec<String> = bits
                .chunks(12)
                .map(|r| r.iter().map(|&b| if b { '#' } else { '.' }).collect())
                .collect();
            check(&Mask::from_ascii(&rows.join("\n")));
        }
    }

    /// A large disc: a few coarse edges per octant, far fewer than the cracks.
    #[test]
    fn a_disc_needs_few_edges() {
        let r = 60.0f64;
        let rows: Vec<String> = (0..130)
            .map(|y| {
                (0..130)
                    .map(|x| {
                        let (dx, dy) = (f64::from(x) - 64.5, f64::from(y) - 64.5);
                        if dx * dx + dy * dy <= r * r {
                            '#'
                        } else {
                            '.'
                        }
                    })
                    .collect()
            })
            .collect();
        let (cracks, coarse) = check(&Mask::from_ascii(&rows.join("\n")));
        assert!(
            coarse * 3 < cracks,
            "{coarse} coarse edges for {cracks} crack edges"
        );
    }
}
