//! The partition layout: every border between two regions drawn once, used forward by the
//! region on its left and reversed by the region on its right (`--layout partition`).
//!
//! # Borders
//! The image's border cracks are cut at the junctions into [`Border`]s, each between two
//! labels (see [`BorderGraph`]). Each region's path is its borders chained into closed
//! loops: those with the region on their left as drawn, those with it on their right
//! reversed, point for point (the same numbers, written once per side). Every border ends at
//! its junctions' crack corners exactly (integers), so the loops close and two regions that
//! share a border share its drawing: no gap, no overlap, whatever the renderer. The loops
//! of a region are the boundary of its pixels (every corner has as many of its borders
//! arriving as leaving), so with the `nonzero` rule the path winds once round its pixels and
//! zero times elsewhere, holes and pinches included.
//!
//! # Drawing a border
//! Each region's own mask is traced and decomposed as in the binary pipeline (padded by one
//! pixel like the stack's layers) and every contour drawn exact in tiny-skia
//! ([`contour_path`]). A border between regions `a` and `b` is first cut out of `a`'s
//! outline, between the points nearest to its two end corners (see
//! [`cut`](crate::outline::cut)): that outline separates `a`'s pixel centres from every other
//! pixel's, `b`'s included. If that fails, from `b`'s outline (reversed); then along its
//! cracks, which is exact. A border against no region is cut from its region's outline or
//! drawn along its cracks; a border along the image's edge is drawn along its cracks (a
//! straight line on the edge).
//!
//! # Exact
//! Every region's path is rendered alone by resvg in crispEdges and compared with the
//! region's pixels. The region's borders nearest a wrong pixel (beside it, else within one
//! pixel, else two) move on to their next drawing, and the check runs again, until every region is exact: at worst every
//! border is along its cracks, which is the pixel boundary itself. Each region exact alone
//! means each pixel is painted by exactly one path.

use kurbo::{ParamCurve, PathSeg, Point, Rect};
use rayon::prelude::*;

use crate::bitmap::ColourImage;
use crate::contour::{crack_sides, Border, BorderGraph};
use crate::curve::PathCommand;
use crate::decompose::Decomposition;
use crate::error::Error;
use crate::outline::{
    contour_path, corner, cut, loop_path, reverse, BorderSource, ContourPath, Loop, OutlineOptions,
    Partition, PartitionBorder,
};

/// Most rounds of drawing and checking: each round moves the borders near a wrong pixel on
/// to their next drawing (at most three), and failing that moves every border of the
/// region to its cracks.
const MAX_ROUNDS: usize = 12;

/// Draws the partition of `image`, whose region `k`'s own pixels, padded by `margin` pixels,
/// were decomposed into `decompositions[k]`.
pub(crate) fn partition(
    image: &ColourImage,
    decompositions: &[&Decomposition],
    margin: i64,
    outline: &OutlineOptions,
) -> Result<Partition, Error> {
    let (w, h) = (image.width(), image.height());
    let n = image.palette().len();
    let graph = BorderGraph::new(w, h, n, |x, y| image.get(x, y));
    let m = margin as f64;
    // Every region's closed outlines, moved into image coordinates.
    let loops: Vec<Vec<Loop>> = decompositions
        .par_iter()
        .map(|d| {
            let basis = d.model.basis();
            d.contours
                .iter()
                .zip(&d.pieces)
                .map(|(c, pieces)| {
                    let cp = contour_path(c, pieces, &basis, outline);
                    let shift = |p: Point| Point::new(p.x - m, p.y - m);
                    let commands: Vec<PathCommand> = cp
                        .commands
                        .iter()
                        .map(|c| match *c {
                            PathCommand::Line(p) => PathCommand::Line(shift(p)),
                            PathCommand::Quad(a, p) => PathCommand::Quad(shift(a), shift(p)),
                            PathCommand::Cubic(a, b, p) => {
                                PathCommand::Cubic(shift(a), shift(b), shift(p))
                            }
                            PathCommand::Arc(mut a) => {
                                a.from = shift(a.from);
                                a.to = shift(a.to);
                                PathCommand::Arc(a)
                            }
                        })
                        .collect();
                    Loop::new(shift(cp.start), &commands)
                })
                .collect()
        })
        .collect();
    let none = graph.none;
    let grid = outline.grid;
    // The drawings each border may have, in order of preference.
    let sources: Vec<Vec<BorderSource>> = graph
        .borders
        .iter()
        .map(|b| {
            let mut s = Vec::with_capacity(3);
            if b.right != graph.outside {
                s.push(BorderSource::Left);
                if b.right < none {
                    s.push(BorderSource::Right);
                }
            }
            s.push(BorderSource::Cracks);
            s
        })
        .collect();
    let draw = |b: &Border, source: BorderSource| -> Option<Vec<PathCommand>> {
        match source {
            BorderSource::Cracks => Some(cracks(b)),
            BorderSource::Left => cut_border(b, &loops[b.left], false, grid),
            BorderSource::Right => cut_border(b, &loops[b.right], true, grid),
        }
    };
    let mut drawn: Vec<PartitionBorder> = graph
        .borders
        .par_iter()
        .zip(&sources)
        .map(|(b, s)| first_drawing(b, s, &draw))
        .collect();
    // Region loops.
    let region_loops: Vec<Vec<Vec<(usize, bool)>>> =
        (0..n).map(|k| chain(&graph.borders, k)).collect();
    // Borders by the pixels beside them.
    let mut near: Vec<Vec<u32>> = vec![Vec::new(); w as usize * h as usize];
    for (i, b) in graph.borders.iter().enumerate() {
        for p in b.corners.windows(2) {
            for (x, y) in crack_sides(p[0], p[1]) {
                if x >= 0 && y >= 0 && x < i64::from(w) && y < i64::from(h) {
                    let v = &mut near[y as usize * w as usize + x as usize];
                    if v.last() != Some(&(i as u32)) {
                        v.push(i as u32);
                    }
                }
            }
        }
    }
    // The pixels region `k` gets wrong when its path alone is rendered, for every region
    // marked in `dirty` (none for the others).
    let wrong_pixels =
        |drawn: &[PartitionBorder], dirty: &[bool]| -> Result<Vec<Vec<(i64, i64)>>, Error> {
            (0..n)
                .into_par_iter()
                .map(|k| {
                    if !dirty[k] {
                        return Ok(Vec::new());
                    }
                    let paths: Vec<ContourPath> = region_loops[k]
                        .iter()
                        .map(|l| loop_path(drawn, l))
                        .collect();
                    let d = crate::export::partition::path_data(&paths, grid);
                    let svg = crate::export::partition::single_path_document(&d, w, h);
                    let rendered = crate::fidelity::rasterize_svg(&svg, w, h)?;
                    let mut wrong = Vec::new();
                    for y in 0..i64::from(h) {
                        for x in 0..i64::from(w) {
                            if rendered.get(x, y) != (image.get(x, y) == Some(k)) {
                                wrong.push((x, y));
                            }
                        }
                    }
                    Ok(wrong)
                })
                .collect()
        };
    let mut dirty = vec![true; n];
    let mut rounds = 0;
    loop {
        rounds += 1;
        let wrong = wrong_pixels(&drawn, &dirty)?;
        dirty = vec![false; n];
        if wrong.iter().all(Vec::is_empty) {
            break;
        }
        // Per border: None, or whether it goes straight to its cracks.
        let mut moved: Vec<Option<bool>> = vec![None; drawn.len()];
        for (k, pixels) in wrong.iter().enumerate() {
            if pixels.is_empty() {
                continue;
            }
            let mut any = false;
            for &(x, y) in pixels {
                // The borders of region k beside the pixel, else within one pixel of it,
                // else within two.
                for r in 0..=2 {
                    let mut found = false;
                    for v in (y - r).max(0)..(y + r + 1).min(i64::from(h)) {
                        for u in (x - r).max(0)..(x + r + 1).min(i64::from(w)) {
                            for &b in &near[v as usize * w as usize + u as usize] {
                                let b = b as usize;
                                let border = &graph.borders[b];
                                if (border.left == k || border.right == k)
                                    && drawn[b].source != BorderSource::Cracks
                                {
                                    // Moved by this region or by the other side of the
                                    // border: either way something near changes.
                                    found = true;
                                    any = true;
                                    if moved[b].is_none() {
                                        moved[b] = Some(false);
                                    }
                                }
                            }
                        }
                    }
                    if found {
                        break;
                    }
                }
            }
            if !any || rounds + 1 >= MAX_ROUNDS {
                // Nothing near to move (not seen), or out of rounds: every border of the
                // region along its cracks.
                for (b, border) in graph.borders.iter().enumerate() {
                    if (border.left == k || border.right == k)
                        && drawn[b].source != BorderSource::Cracks
                    {
                        moved[b] = Some(true);
                    }
                }
            }
        }
        for (b, &mv) in moved.iter().enumerate() {
            let Some(to_cracks) = mv else { continue };
            let s = &sources[b];
            let next = if to_cracks {
                &s[s.len() - 1..]
            } else {
                let at = s.iter().position(|&x| x == drawn[b].source).unwrap_or(0);
                &s[at + 1..]
            };
            drawn[b] = first_drawing(&graph.borders[b], next, &draw);
            let border = &graph.borders[b];
            dirty[border.left] = true;
            if border.right < none {
                dirty[border.right] = true;
            }
        }
        if rounds > MAX_ROUNDS + 2 {
            // Out of rounds: the regions changed last are checked once more, and if one is
            // still wrong every border goes along its cracks, which is exact by
            // construction (each region is then its pixels' own polygon).
            if wrong_pixels(&drawn, &dirty)?.iter().any(|p| !p.is_empty()) {
                for (b, border) in graph.borders.iter().enumerate() {
                    if drawn[b].source != BorderSource::Cracks {
                        let s = &sources[b];
                        drawn[b] = first_drawing(border, &s[s.len() - 1..], &draw);
                    }
                }
            }
            break;
        }
    }
    Ok(Partition {
        borders: drawn,
        loops: region_loops,
        none,
        rounds,
    })
}

/// The first drawing of `b` that works among `sources` (cracks always do).
fn first_drawing(
    b: &Border,
    sources: &[BorderSource],
    draw: &(dyn Fn(&Border, BorderSource) -> Option<Vec<PathCommand>> + Sync),
) -> PartitionBorder {
    for &s in sources {
        if let Some(commands) = draw(b, s) {
            return PartitionBorder {
                border: b.clone(),
                source: s,
                commands,
            };
        }
    }
    PartitionBorder {
        border: b.clone(),
        source: BorderSource::Cracks,
        commands: cracks(b),
    }
}

/// The border along its cracks: a line to every corner where it turns, and to the last.
fn cracks(b: &Border) -> Vec<PathCommand> {
    let c = &b.corners;
    let mut out = Vec::new();
    for i in 1..c.len() {
        let last = i + 1 == c.len();
        let turns = !last && {
            let (d0, d1) = (
                (c[i].0 - c[i - 1].0, c[i].1 - c[i - 1].1),
                (c[i + 1].0 - c[i].0, c[i + 1].1 - c[i].1),
            );
            d0 != d1
        };
        if last || turns {
            out.push(PathCommand::Line(corner(c[i])));
        }
    }
    out
}

/// The border cut out of `loops` (the outlines of the region on its left, or with
/// `reversed` on its right: then cut from its last corner to its first and turned round),
/// on the `2^-grid` grid.
fn cut_border(b: &Border, loops: &[Loop], reversed: bool, grid: u8) -> Option<Vec<PathCommand>> {
    let c = &b.corners;
    let (from, to) = (corner(c[0]), corner(*c.last()?));
    // The length of the line through the cracks' midpoints: near the true curve's for
    // staircases and straight runs alike.
    let mut length = 0.0;
    let mut pen = from;
    for p in c.windows(2) {
        let mid = corner(p[0]).midpoint(corner(p[1]));
        length += (mid - pen).hypot();
        pen = mid;
    }
    length += (to - pen).hypot();
    let mut bounds = Rect::from_points(from, from);
    for &p in c {
        bounds = bounds.union_pt(corner(p));
    }
    let segs = if reversed {
        cut(loops, to, from, length, bounds)?
    } else {
        cut(loops, from, to, length, bounds)?
    };
    let scale = f64::from(1u32 << grid.min(20));
    let snap = |p: Point| Point::new((p.x * scale).round() / scale, (p.y * scale).round() / scale);
    let start = if reversed { to } else { from };
    let mut pen = start;
    let mut commands = Vec::with_capacity(segs.len());
    for s in &segs {
        let c = match s {
            PathSeg::Line(l) => PathCommand::Line(snap(l.p1)),
            PathSeg::Quad(q) => PathCommand::Quad(snap(q.p1), snap(q.p2)),
            PathSeg::Cubic(q) => PathCommand::Cubic(snap(q.p1), snap(q.p2), snap(q.p3)),
        };
        let degenerate = match c {
            PathCommand::Line(p) => p == pen,
            PathCommand::Quad(a, p) => a == pen && p == pen,
            PathCommand::Cubic(a, b2, p) => a == pen && b2 == pen && p == pen,
            PathCommand::Arc(_) => false,
        };
        if !degenerate {
            pen = c.end();
            commands.push(c);
        }
    }
    let end = if reversed { from } else { to };
    if pen != end || commands.is_empty() {
        return None;
    }
    debug_assert_eq!(segs.last().map(|s| s.end()), Some(end));
    Some(if reversed {
        reverse(start, &commands)
    } else {
        commands
    })
}

/// The loops of region `k`: its borders (forward when it is on their left, reversed when
/// on their right) chained at their corners, each loop from the smallest unused border,
/// continuing at every corner with the smallest unused border leaving it.
fn chain(borders: &[Border], k: usize) -> Vec<Vec<(usize, bool)>> {
    use std::collections::BTreeMap;
    let ends = |b: &Border, reversed: bool| {
        let (s, e) = (b.corners[0], *b.corners.last().expect("corners"));
        if reversed {
            (e, s)
        } else {
            (s, e)
        }
    };
    let mine: Vec<(usize, bool)> = borders
        .iter()
        .enumerate()
        .filter_map(|(i, b)| {
            if b.left == k {
                Some((i, false))
            } else if b.right == k {
                Some((i, true))
            } else {
                None
            }
        })
        .collect();
    let mut leaving: BTreeMap<(i64, i64), Vec<(usize, bool)>> = BTreeMap::new();
    for &(i, r) in &mine {
        leaving
            .entry(ends(&borders[i], r).0)
            .or_default()
            .push((i, r));
    }
    let mut used = std::collections::HashSet::new();
    let mut out = Vec::new();
    for &(i, r) in &mine {
        if used.contains(&i) {
            continue;
        }
        used.insert(i);
        let (start, mut at) = ends(&borders[i], r);
        let mut l = vec![(i, r)];
        while at != start {
            let next = leaving
                .get(&at)
                .and_then(|v| v.iter().find(|(j, _)| !used.contains(j)).copied());
            let Some((j, rj)) = next else { break };
            used.insert(j);
            l.push((j, rj));
            at = ends(&borders[j], rj).1;
        }
        out.push(l);
    }
    out
}
