//! Paths of lines whose paint is known without a fill: a small loop with a pixel centre well
//! inside it, or every centre well clear of it; a contour's path clear of every centre and
//! winding round each as the contour's cracks do.
//!
//! The render checks ([`super::robust::loop_paints_nothing`]) fill a loop with tiny-skia,
//! moved by [`super::ROBUST_SHIFT`] each way, and in Chromium's tiles. Each of those fills
//! places an edge within a small distance of where it lies: tiny-skia's and Skia's fixed
//! point move an edge's crossing of a row of centres by at most 1/64 px (the offset to its
//! first row is truncated to 1/64 px) and by less than 1/256 px more over at most
//! [`SURE_SIZE`] rows, the moved fills move it by 1/64 px, and a tile's cut rounds the cut's
//! end to 1/128 px; less than 0.036 px in all. So a pixel centre inside the loop and farther
//! than that from every edge is painted by every fill, and a loop whose every centre lies
//! outside it and farther than that from every edge is painted by none. [`classify`] looks
//! for either, row of centres by row. Likewise a path every centre of which lies farther
//! than that from every edge paints, in every fill, the centres it winds round: where those
//! are the pixels of its contour, the path is exact, and else it is wrong exactly where it
//! winds otherwise than the contour's cracks ([`path_misplaced`]).

use super::render_check::Reference;
use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::{Point, Rect};

/// The pixel centres `i + 0.5` that lie in an interval of one axis: indices
/// `first..=last`, none when `last < first`.
#[derive(Clone, Copy)]
struct Centres {
    first: i64,
    last: i64,
}

impl Centres {
    /// The centres in `[lo, hi]`.
    fn within(lo: f64, hi: f64) -> Centres {
        Centres {
            first: ceil(lo - 0.5),
            last: floor(hi - 0.5),
        }
    }

    fn is_empty(self) -> bool {
        self.last < self.first
    }

    fn count(self) -> usize {
        (self.last - self.first + 1).max(0) as usize
    }

    fn indices(self) -> std::ops::RangeInclusive<i64> {
        self.first..=self.last
    }
}

/// What [`classify`] knows of a loop without filling it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Known {
    /// Every fill paints a pixel centre.
    Paints,
    /// No fill paints any pixel centre.
    PaintsNothing,
    /// Only the fills can tell.
    Unknown,
}

/// How far (px) from every edge a pixel centre must lie, inside a loop for
/// [`Known::Paints`], every centre outside it for [`Known::PaintsNothing`]: the fills' moves
/// (under 0.036 px, see the module documentation) with room to spare. (Nearer settles few
/// more loops: on 400² noise, 1/32 px settles 15 949 loops of lines that paint nothing,
/// 1/16 px 14 553, of 16 785; a centre inside was 1/8 px clear before loops that paint
/// nothing were settled too, and 1/16 px saves another 2% of the instructions there.)
const MARGIN: f64 = 1.0 / 16.0;

/// Largest width and height (px) of a loop [`classify`] looks into.
const SURE_SIZE: f64 = 64.0;

/// Most edges of a loop [`classify`] looks into.
const MOST_EDGES: usize = 16;

/// Most edges times rows of centres, and edges times centres looked at, in one [`classify`]:
/// beyond, the fills cost about as much.
const MOST_WORK: usize = 256;

/// One edge of a loop, ready for rows of centres.
#[derive(Clone, Copy, Default)]
struct Edge {
    /// The edge's lower and upper y.
    y_lo: f64,
    y_hi: f64,
    /// Its bounds widened by [`MARGIN`].
    near_x_lo: f64,
    near_x_hi: f64,
    near_y_lo: f64,
    near_y_hi: f64,
    /// Its start, and x's change per unit of y (0 for a horizontal edge).
    a: Point,
    run: f64,
    /// Half the width in x of the band within [`MARGIN`] of its line on a row: the margin
    /// times length / |dy| (unused for a horizontal edge).
    half: f64,
    /// +1 downwards, −1 upwards, 0 horizontal.
    dir: i32,
}

/// The lesser of two numbers, neither NaN (without `f64::min`'s care for NaN).
fn less(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// The greater of two numbers, neither NaN.
fn greater(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

impl Edge {
    fn new(a: Point, b: Point) -> Edge {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let horizontal = dy == 0.0;
        let (y_lo, y_hi) = (less(a.y, b.y), greater(a.y, b.y));
        Edge {
            y_lo,
            y_hi,
            near_x_lo: less(a.x, b.x) - MARGIN,
            near_x_hi: greater(a.x, b.x) + MARGIN,
            near_y_lo: y_lo - MARGIN,
            near_y_hi: y_hi + MARGIN,
            a,
            run: if horizontal { 0.0 } else { dx / dy },
            half: if horizontal {
                0.0
            } else {
                MARGIN * (dx * dx + dy * dy).sqrt() / dy.abs()
            },
            dir: if horizontal {
                0
            } else if dy > 0.0 {
                1
            } else {
                -1
            },
        }
    }

    /// The interval of x on the row `y` within [`MARGIN`] of the edge's band: the band of its
    /// line (|cross| < margin · length) within its bounds widened by the margin, which holds
    /// every point that near the edge. `None` if the row passes farther.
    fn near(&self, y: f64) -> Option<(f64, f64)> {
        if y <= self.near_y_lo || y >= self.near_y_hi {
            return None;
        }
        let (mut lo, mut hi) = (self.near_x_lo, self.near_x_hi);
        if self.dir != 0 {
            let x = self.x_at(y);
            lo = greater(lo, x - self.half);
            hi = less(hi, x + self.half);
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Where the edge's line meets the row `y` (not for a horizontal edge).
    fn x_at(&self, y: f64) -> f64 {
        self.a.x + self.run * (y - self.a.y)
    }

    /// Whether the edge crosses the row `y`, counted half-open in y as the fills count it.
    fn crosses(&self, y: f64) -> bool {
        self.dir != 0 && self.y_lo <= y && y < self.y_hi
    }
}

/// `v.floor()` for the moderate values of pixel coordinates, without a library call.
fn floor(v: f64) -> i64 {
    let t = v as i64;
    t - i64::from(v < t as f64)
}

/// `v.ceil()` for the moderate values of pixel coordinates, without a library call.
fn ceil(v: f64) -> i64 {
    let t = v as i64;
    t + i64::from(v > t as f64)
}

/// What the fills of the closed loop of lines `M anchor lp Z` paint, where it is known
/// without them (see the module documentation): [`Known::Paints`] when a centre inside the
/// `canvas` lies inside the loop and farther than [`MARGIN`] from every edge,
/// [`Known::PaintsNothing`] when every centre lies outside it and farther than [`MARGIN`]
/// from every edge. [`Known::Unknown`] for a curve, a loop larger than [`SURE_SIZE`] or of
/// more than [`MOST_EDGES`] edges, or more work than [`MOST_WORK`].
///
/// A centre on an edge is left to the fills even where a fill moved by 1/64 px has it
/// inside: tiny-skia's fixed point may truncate a crossing by as much (its first row's
/// offset, slope times distance, is truncated to 1/64 px; a proptest found such a triangle).
///
/// Row of centres by row: each edge's nearness meets the row in an interval, and the loop's
/// inside on the row lies between its crossings, which lie in those intervals; so only the
/// centres within their hull need a look.
pub(crate) fn classify(anchor: Point, lp: &[PathCommand], canvas: Option<Rect>) -> Known {
    if lp.len() + 1 > MOST_EDGES {
        return Known::Unknown;
    }
    let mut edges = [Edge::default(); MOST_EDGES];
    let (mut lo, mut hi) = (anchor, anchor);
    let mut from = anchor;
    for (k, c) in lp
        .iter()
        .chain(std::iter::once(&PathCommand::Line(anchor)))
        .enumerate()
    {
        let PathCommand::Line(p) = *c else {
            return Known::Unknown;
        };
        edges[k] = Edge::new(from, p);
        lo = Point::new(less(lo.x, p.x), less(lo.y, p.y));
        hi = Point::new(greater(hi.x, p.x), greater(hi.y, p.y));
        from = p;
    }
    let edges = &edges[..=lp.len()];
    if !(hi.x - lo.x <= SURE_SIZE && hi.y - lo.y <= SURE_SIZE) {
        return Known::Unknown;
    }
    // Rows of centres y + 0.5 within the margin of the bounds; none, or no such column of
    // centres x + 0.5, and the loop is clear of every centre.
    let rows = Centres::within(lo.y - MARGIN, hi.y + MARGIN);
    if rows.is_empty() || Centres::within(lo.x - MARGIN, hi.x + MARGIN).is_empty() {
        return Known::PaintsNothing;
    }
    let mut work = rows.count() * edges.len();
    if work > MOST_WORK {
        return Known::Unknown;
    }
    let mut nothing = true;
    // Per row: each near edge's interval; each crossing and its direction.
    let mut near = [(0.0f64, 0.0f64); MOST_EDGES];
    let mut crossings = [(0.0f64, 0i32); MOST_EDGES];
    for row in rows.indices() {
        let y = row as f64 + 0.5;
        let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut n_near, mut n_cross) = (0, 0);
        for e in edges {
            if let Some((l, r)) = e.near(y) {
                near[n_near] = (l, r);
                n_near += 1;
                left = less(left, l);
                right = greater(right, r);
            }
            if e.crosses(y) {
                crossings[n_cross] = (e.x_at(y), e.dir);
                n_cross += 1;
            }
        }
        if left > right {
            continue;
        }
        let cols = Centres::within(left, right);
        work += cols.count() * edges.len();
        if work > MOST_WORK {
            return Known::Unknown;
        }
        for col in cols.indices() {
            let x = col as f64 + 0.5;
            // Near an edge, only the fills can tell; clear of them, wound round or not.
            if near[..n_near].iter().any(|&(l, r)| l <= x && x <= r) {
                nothing = false;
                continue;
            }
            let winding: i32 = crossings[..n_cross]
                .iter()
                .filter(|&&(cx, _)| cx < x)
                .map(|&(_, d)| d)
                .sum();
            if winding != 0 {
                if canvas.is_none_or(|r| r.contains(Point::new(x, y))) {
                    return Known::Paints;
                }
                nothing = false;
            }
        }
    }
    if nothing {
        Known::PaintsNothing
    } else {
        Known::Unknown
    }
}

/// Most pixels in the bounds of a path and its reference that [`path_misplaced`] looks
/// at: beyond, it leaves the path to the fills.
const MOST_CELLS: usize = 4096;

/// The pixels every fill of the closed path of lines `M start commands Z` paints wrong
/// against `reference` (empty when it paints exactly the pixels of `reference`), known
/// without a fill: every pixel centre lies farther than [`MARGIN`] from every edge of the
/// path, so every fill (moved by [`super::ROBUST_SHIFT`] too, and cut at Chromium's tiles;
/// see the module documentation) paints the centres where the path winds otherwise than
/// the reference does. `None` where only the fills can tell: a centre near an edge, a
/// curve, an edge across more than [`SURE_SIZE`] rows, bounds of more than [`MOST_CELLS`]
/// pixels, a path within a pixel of the `canvas`'s border or a reference that is not a
/// crack polygon (whole-pixel corners, axis-aligned edges).
///
/// The fills compare windings (the path and the reference reversed, filled together, paint
/// where they differ: [`super::render_check::misplaced_pixels`]). The reference's edges cross
/// every row of centres at a whole pixel, half a pixel from every centre, so its winding is
/// known exactly; each crossing of a row changes the windings of the centres to its right,
/// so a prefix sum along the row gives every centre's difference of the two. The pixels
/// come row by row, left to right, as the fills give them.
pub(crate) fn path_misplaced(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    canvas: Option<Rect>,
) -> Option<Vec<Pixel>> {
    let finite = |p: Point| p.x.is_finite() && p.y.is_finite();
    if commands.is_empty() || !finite(start) {
        return None;
    }
    let (mut lo, mut hi) = (start, start);
    for c in commands {
        let PathCommand::Line(p) = *c else {
            return None;
        };
        // (Each point: `less` and `greater` would let a later number stand for a NaN.)
        if !finite(p) {
            return None;
        }
        lo = Point::new(less(lo.x, p.x), less(lo.y, p.y));
        hi = Point::new(greater(hi.x, p.x), greater(hi.y, p.y));
    }
    if let Some(c) = canvas {
        if !(c.x0 <= lo.x - 1.0 && hi.x + 1.0 <= c.x1 && c.y0 <= lo.y - 1.0 && hi.y + 1.0 <= c.y1) {
            return None;
        }
    }
    // Centres (x + 0.5, y + 0.5) of the columns x0.. and rows y0.. of the bounds, one more
    // column for the crossings right of every centre.
    let (x0, y0) = (
        floor(less(lo.x, reference.lo.x)),
        floor(less(lo.y, reference.lo.y)),
    );
    let (x1, y1) = (
        ceil(greater(hi.x, reference.hi.x)),
        ceil(greater(hi.y, reference.hi.y)),
    );
    let (width, height) = ((x1 - x0 + 2) as usize, (y1 - y0 + 1) as usize);
    if width.saturating_mul(height) > MOST_CELLS {
        return None;
    }
    // At each centre, the change of the windings (path minus reference) from its left.
    let mut change = vec![0i32; width * height];
    let mut cross = |row: i64, col: i64, d: i32| {
        change[(row - y0) as usize * width + (col - x0) as usize] += d;
    };
    let mut from = start;
    for c in commands
        .iter()
        .chain(std::iter::once(&PathCommand::Line(start)))
    {
        let p = c.end();
        let e = Edge::new(from, p);
        from = p;
        if e.y_hi - e.y_lo > SURE_SIZE {
            return None;
        }
        // The rows of centres within the margin of the edge: none may pass near a centre.
        for row in Centres::within(e.near_y_lo, e.near_y_hi).indices() {
            let y = row as f64 + 0.5;
            if let Some((l, r)) = e.near(y) {
                if !Centres::within(l, r).is_empty() {
                    return None;
                }
            }
            if e.crosses(y) {
                // The first centre right of the crossing (none is on it: none is near).
                cross(row, ceil(e.x_at(y) - 0.5), e.dir);
            }
        }
    }
    let mut from = reference.start;
    let closing = (!reference.vertices.is_empty()).then_some(&reference.start);
    for &b in reference.vertices.iter().chain(closing) {
        let a = from;
        from = b;
        if a.x.fract() != 0.0 || a.y.fract() != 0.0 || (a.x != b.x && a.y != b.y) {
            return None;
        }
        if a.y != b.y {
            // Reversed: an edge downwards winds −1.
            let dir = if b.y > a.y { -1 } else { 1 };
            for row in less(a.y, b.y) as i64..greater(a.y, b.y) as i64 {
                cross(row, a.x as i64, dir);
            }
        }
    }
    let mut wrong = Vec::new();
    for (row, changes) in (y0..).zip(change.chunks_exact(width)) {
        let mut winding = 0;
        for (col, &d) in (x0..).zip(changes) {
            winding += d;
            if winding != 0 {
                // Within the bounds of coordinates of at most 2^24: whole `i32`s.
                wrong.push(Pixel {
                    x: col as i32,
                    y: row as i32,
                });
            }
        }
    }
    Some(wrong)
}

/// Whether [`path_misplaced`] knows the path exact without a fill.
#[cfg(test)]
fn path_draws_right(
    reference: &Reference,
    start: Point,
    commands: &[PathCommand],
    canvas: Option<Rect>,
) -> bool {
    path_misplaced(reference, start, commands, canvas).is_some_and(|w| w.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outline::render_check::EdgeClipping;
    use crate::outline::robust::filled_paints_nothing;
    use proptest::prelude::*;

    /// A page large enough for Chromium's tiles of 256 px (cut at 254 and 256).
    const PAGE: Rect = Rect::new(0.0, 0.0, 600.0, 600.0);

    proptest! {
        /// What is known without a fill is what the fills give: random small polygons on
        /// the 1/16-px grid, some across a tile's cut, some along pixel edges and centres.
        #[test]
        fn known_loops_fill_as_known(
            path in prop::collection::vec((0i32..48, 0i32..48), 3..9),
            at in prop::sample::select(vec![2.0, 252.0, 254.5]),
            step in prop::sample::select(vec![16.0, 8.0, 2.0]),
            robust in any::<bool>(),
        ) {
            let p = |&(x, y): &(i32, i32)| Point::new(f64::from(x) / step + at, f64::from(y) / step + at);
            let anchor = p(&path[0]);
            let lp: Vec<PathCommand> = path[1..].iter().map(|q| PathCommand::Line(p(q))).collect();
            let filled = filled_paints_nothing(anchor, &lp, EdgeClipping::Never, Some(PAGE), robust);
            match classify(anchor, &lp, Some(PAGE)) {
                Known::Paints => prop_assert!(!filled),
                Known::PaintsNothing => prop_assert!(filled),
                Known::Unknown => {}
            }
        }
    }

    /// The crack polygon (corners in order, from the first row's left end, rightwards)
    /// of rows `at + i` of pixels covering `at + l_i .. at + r_i`, consecutive rows made to
    /// overlap (a 4-connected shape without holes).
    fn cracks_of(rows: &[(i32, i32)], at: f64) -> Vec<Point> {
        let mut spans: Vec<(i32, i32)> = Vec::new();
        for &(l, len) in rows {
            let (mut l, mut r) = (l, l + len);
            if let Some(&(pl, pr)) = spans.last() {
                l = l.min(pr - 1);
                r = r.max(pl + 1);
            }
            spans.push((l, r));
        }
        let p = |x: i32, y: usize| Point::new(f64::from(x) + at, y as f64 + at);
        let mut corners = vec![p(spans[0].0, 0)];
        for (i, &(_, r)) in spans.iter().enumerate() {
            corners.push(p(r, i));
            corners.push(p(r, i + 1));
        }
        for (i, &(l, _)) in spans.iter().enumerate().rev() {
            corners.push(p(l, i + 1));
            corners.push(p(l, i));
        }
        corners.pop();
        corners.dedup();
        corners
    }

    proptest! {
        /// What is known of a path of lines without a fill is what every fill of the
        /// render check gives, the same pixels in the same order: paths near random shapes'
        /// crack polygons (corners dropped, moved by multiples of 1/64 px; all kept where
        /// fewer than three would be), some across a tile's cut, some on a page, some not.
        #[test]
        fn paths_known_right_fill_right(
            rows in prop::collection::vec((0i32..6, 1i32..6), 1..6),
            moves in prop::collection::vec((any::<bool>(), -24i32..=24, -24i32..=24), 24),
            at in prop::sample::select(vec![2.0, 250.0, 253.0]),
            page in any::<bool>(),
        ) {
            let corners = cracks_of(&rows, at);
            let reference = Reference::new(
                corners[0],
                &corners[1..].iter().map(|&q| PathCommand::Line(q)).collect::<Vec<_>>(),
            );
            let moved = |(&q, &(_, dx, dy)): (&Point, &(bool, i32, i32))| {
                q + kurbo::Vec2::new(f64::from(dx), f64::from(dy)) / 64.0
            };
            let mut path: Vec<Point> = corners
                .iter()
                .zip(moves.iter().cycle())
                .filter(|(_, m)| m.0)
                .map(moved)
                .collect();
            if path.len() < 3 {
                path = corners.iter().zip(moves.iter().cycle()).map(moved).collect();
            }
            let lp: Vec<PathCommand> = path[1..].iter().map(|&q| PathCommand::Line(q)).collect();
            let opts = crate::outline::OutlineOptions {
                canvas: page.then_some(PAGE),
                ..Default::default()
            };
            if let Some(known) = path_misplaced(&reference, path[0], &lp, opts.canvas) {
                let wrong = super::super::misplaced_when_filled(&reference, &reference, path[0], &lp, &opts);
                prop_assert_eq!(known, wrong);
            }
        }
    }

    #[test]
    fn a_path_near_the_cracks_is_known_right() {
        // Two rows: 1..4 and 2..5, at 10.
        let corners = cracks_of(&[(1, 3), (2, 3)], 10.0);
        let lines =
            |c: &[Point]| -> Vec<PathCommand> { c.iter().map(|&q| PathCommand::Line(q)).collect() };
        let reference = Reference::new(corners[0], &lines(&corners[1..]));
        // The cracks themselves.
        assert!(path_draws_right(
            &reference,
            corners[0],
            &lines(&corners[1..]),
            None
        ));
        // The step's corner (14, 11) moved in, 0.3 px from the centres beside it.
        let cut: Vec<Point> = corners
            .iter()
            .map(|&q| {
                if q == Point::new(14.0, 11.0) {
                    Point::new(14.25, 10.75)
                } else {
                    q
                }
            })
            .collect();
        assert!(path_draws_right(
            &reference,
            cut[0],
            &lines(&cut[1..]),
            None
        ));
        // Within a pixel of the page's border (at 15.5): left to the fills.
        let page = Rect::new(0.0, 0.0, 15.5, 30.0);
        assert!(!path_draws_right(
            &reference,
            cut[0],
            &lines(&cut[1..]),
            Some(page)
        ));
        // The first corner dropped: the line from (11, 11) to (14, 10) passes through the
        // centre (12.5, 10.5) and leaves the pixel (11, 10) out.
        let through: Vec<Point> = corners
            .iter()
            .copied()
            .filter(|&q| q != Point::new(11.0, 10.0))
            .collect();
        assert!(!path_draws_right(
            &reference,
            through[0],
            &lines(&through[1..]),
            None
        ));
        // A point that is not a number: left to the fills (which give up on it).
        let mut lost = lines(&corners[1..]);
        lost[2] = PathCommand::Line(Point::new(f64::NAN, 11.0));
        assert!(!path_draws_right(&reference, corners[0], &lost, None));
        let nan = Point::new(f64::NAN, f64::NAN);
        assert!(!path_draws_right(
            &reference,
            nan,
            &lines(&corners[1..]),
            None
        ));
        // A curve: only the fills can tell.
        let mut curved = lines(&corners[1..]);
        curved[0] = PathCommand::Quad(Point::new(12.0, 9.0), corners[1]);
        assert!(!path_draws_right(&reference, corners[0], &curved, None));
    }

    fn l(x: f64, y: f64) -> PathCommand {
        PathCommand::Line(Point::new(x, y))
    }

    #[test]
    fn a_centre_clear_of_the_edges_is_painted() {
        // A triangle round the centre (3.5, 3.5), 0.35 px from its nearest edge.
        let corner = [l(5.0, 3.0), l(3.0, 5.0)];
        assert_eq!(classify(Point::new(3.0, 3.0), &corner, None), Known::Paints);
        // Not when the canvas leaves the centre out.
        let canvas = Rect::new(0.0, 0.0, 3.0, 10.0);
        assert_eq!(
            classify(Point::new(3.0, 3.0), &corner, Some(canvas)),
            Known::Unknown
        );
        // A sliver passing 0.05 px from the centre: only the fills can tell.
        let sliver = [l(4.0, 3.55), l(3.0, 3.45)];
        assert_eq!(
            classify(Point::new(3.0, 3.55), &sliver, None),
            Known::Unknown
        );
        // A pixel's corner cut through its centre (66.5, 9.5): only the fills can tell.
        let corner = [l(67.0, 9.0), l(67.0, 10.0)];
        assert_eq!(
            classify(Point::new(66.0, 10.0), &corner, None),
            Known::Unknown
        );
        // A curve: unknown.
        let curve = [PathCommand::Quad(
            Point::new(5.0, 3.0),
            Point::new(3.0, 5.0),
        )];
        assert_eq!(classify(Point::new(3.0, 3.0), &curve, None), Known::Unknown);
    }

    #[test]
    fn a_loop_clear_of_every_centre_paints_nothing() {
        // A thin triangle between the rows of centres 3.5 and 4.5, 0.2 px from them.
        let thin = [l(9.0, 3.7), l(5.0, 4.3)];
        assert_eq!(
            classify(Point::new(2.0, 3.7), &thin, None),
            Known::PaintsNothing
        );
        // Its corner 0.03 px above the centre (5.5, 4.5): only the fills can tell.
        let near = [l(9.0, 4.2), l(5.5, 4.47)];
        assert_eq!(classify(Point::new(2.0, 4.2), &near, None), Known::Unknown);
        // Two edges meeting on a pixel centre: unknown.
        let through = [l(4.5, 4.5), l(6.0, 4.4)];
        assert_eq!(
            classify(Point::new(3.0, 4.4), &through, None),
            Known::Unknown
        );
        // A loop larger than the work allowed: unknown.
        let large = [l(40.0, 0.25), l(40.0, 40.25), l(0.0, 40.25)];
        assert_eq!(
            classify(Point::new(0.0, 0.25), &large, None),
            Known::Unknown
        );
    }
}
