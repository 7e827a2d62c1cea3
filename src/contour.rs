//! Border tracing: turning a [`Mask`] into chains of boundary pixels.
//!
//! Two conventions are offered (see [`Convention`]); both are iterative and run in time
//! linear in the number of pixels plus the total contour length.

use crate::bitmap::Mask;
use crate::pixel::Pixel;

/// One traced border: a chain of foreground pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Contour {
    /// The pixels in tracing order; consecutive points are 8-adjacent and distinct.
    /// [`Convention::Default`] does not repeat the first point at the end;
    /// [`Convention::Ipol`] does for closed contours.
    pub points: Vec<Pixel>,
    /// True for the border of a hole (a bounded background region), false for an outer
    /// border (and for every open chain).
    pub hole: bool,
    /// False only for [`Convention::Ipol`] chains that end on the image border.
    pub closed: bool,
}

/// Which connectivity, start points, orientation and point lists [`trace`] produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Convention {
    /// layertrace's convention: 8-connected foreground, 4-connected background, outside the
    /// image is background.
    ///
    /// One closed contour per 8-connected foreground component (its outer border) and one
    /// per hole (bounded 4-connected background component). A contour's points are the
    /// foreground pixels having a 4-neighbour in the background region it separates from the
    /// foreground: the surrounding region for an outer border, the hole for a hole border.
    /// Foreground is on the left of the walk on screen (y down): outer borders run
    /// counter-clockwise, hole borders clockwise. An outer border starts at its component's
    /// first pixel in raster order (smallest y, then smallest x); a hole border at the pixel
    /// directly above the hole's first pixel in raster order. The first point is not
    /// repeated at the end. A pixel may appear several times (one-pixel-thin parts); an
    /// isolated pixel gives a one-point contour. Contours are listed in raster order of the
    /// first pixel of their component or hole.
    #[default]
    Default,
    /// The reference code of the IPOL 2014 article (`gjknd_1.1`): 4-connected foreground
    /// (ink), 8-connected background (paper).
    ///
    /// Contours follow the cracks (pixel edges) between ink and paper inside the image, ink on
    /// the walker's right (outer contours clockwise on screen, holes anticlockwise); each
    /// crack contributes its ink pixel, consecutive duplicates dropped. Chains reaching the
    /// image border are open (`closed = false`, the image border is not a crack); they are
    /// found first, by scanning the border cracks (vertical cracks of the top then bottom row,
    /// column by column, then horizontal cracks of the left then right column, row by row),
    /// and listed from the end found first, in whichever direction leads into the image.
    /// Closed contours are then found by scanning the interior cracks column by column
    /// (x, then y; at each pixel the crack on its right before the crack below it): an outer
    /// contour normally starts at the topmost pixel of its leftmost column, a hole at the ink
    /// pixel just left of the topmost pixel of the hole's leftmost column. A closed contour
    /// repeats its start pixel at the end.
    Ipol,
}

/// Traces every border of `mask` in the given convention (see [`Convention`]).
///
/// Pixel coordinates are `i32`: a mask wider or taller than `i32::MAX - 2` pixels gives no
/// contours (the loader's pixel limit keeps images far below that).
pub fn trace(mask: &Mask, convention: Convention) -> Vec<Contour> {
    let limit = (i32::MAX - 2) as u32;
    if mask.width() > limit || mask.height() > limit {
        return Vec::new();
    }
    match convention {
        Convention::Default => trace_default(mask),
        Convention::Ipol => trace_ipol(mask),
    }
}

// ---------------------------------------------------------------------------------------
// Default convention: Moore-neighbour tracing, components found by flood fill.
// ---------------------------------------------------------------------------------------

/// The eight neighbour offsets; increasing index turns clockwise on screen.
const DIRS: [(i32, i32); 8] = [
    (1, 0),   // 0 E
    (1, 1),   // 1 SE
    (0, 1),   // 2 S
    (-1, 1),  // 3 SW
    (-1, 0),  // 4 W
    (-1, -1), // 5 NW
    (0, -1),  // 6 N
    (1, -1),  // 7 NE
];
const DIR_S: usize = 2;
const DIR_N: usize = 6;

#[inline]
fn offset(p: Pixel, d: usize) -> Pixel {
    let (dx, dy) = DIRS[d % 8];
    Pixel::new(p.x + dx, p.y + dy)
}

#[inline]
fn dir_of(dx: i32, dy: i32) -> usize {
    DIRS.iter().position(|&o| o == (dx, dy)).unwrap_or(0)
}

#[inline]
fn fg(mask: &Mask, p: Pixel) -> bool {
    mask.get(i64::from(p.x), i64::from(p.y))
}

/// One Moore step: at `p`, whose neighbour in direction `back` is background in the region
/// being followed, sweep the neighbours counter-clockwise on screen starting after `back`;
/// the first foreground one is the next pixel. Returns it with the direction, seen from it,
/// of the background cell examined just before it (which becomes the next `back`).
#[inline]
fn moore_step(mask: &Mask, p: Pixel, back: usize) -> Option<(Pixel, usize)> {
    for k in 1..8 {
        let d = (back + 8 - k) % 8;
        let q = offset(p, d);
        if fg(mask, q) {
            let c = offset(p, d + 1);
            return Some((q, dir_of(c.x - q.x, c.y - q.y)));
        }
    }
    None
}

/// Traces the closed border through `p0`, starting with background direction `back0`
/// (a background neighbour of `p0` in the region followed).
///
/// Stops when the first move `p0 -> p1` is about to be repeated: the state after a move is a
/// function of the move, so this is exactly one period (Jacob's criterion in move form; a
/// plain "back at p0" test would stop early on thin shapes).
fn moore_trace(mask: &Mask, p0: Pixel, back0: usize) -> Vec<Pixel> {
    let mut points = vec![p0];
    let Some((p1, mut back)) = moore_step(mask, p0, back0) else {
        return points;
    };
    let mut cur = p1;
    // A pixel is visited at most once per run of background in its 8-neighbourhood (at most
    // four runs), so this bound is never reached; it only guarantees termination.
    let limit = 4 * u64::from(mask.width()) * u64::from(mask.height()) + 1;
    // `moore_step` cannot fail here: `cur` was entered from a foreground neighbour.
    while let Some((next, nb)) = moore_step(mask, cur, back) {
        if (cur == p0 && next == p1) || points.len() as u64 > limit {
            break;
        }
        points.push(cur);
        cur = next;
        back = nb;
    }
    points
}

/// A "visited" bit per pixel.
struct Visited(Mask);

/// The low `k` bits set (`1 ≤ k ≤ 64`).
#[inline]
fn low_bits(k: usize) -> u64 {
    if k >= 64 {
        u64::MAX
    } else {
        (1u64 << k) - 1
    }
}

/// The pixels a flood of value `value` may still enter, 64 at a time: bit `k` of
/// `same(i)` is set iff pixel `i + k` (row-major) has the value and is not visited.
struct Unvisited<'a> {
    mask: &'a Mask,
    visited: &'a Mask,
    value: bool,
}

impl Unvisited<'_> {
    #[inline]
    fn same(&self, i: usize) -> u64 {
        let m = self.mask.bits_at(i);
        let m = if self.value { m } else { !m };
        m & !self.visited.bits_at(i)
    }

    /// The first `x` of the run of `same` pixels of row `row` (starting at row-major index
    /// `base`) that ends at `x0` (itself `same`).
    fn run_start(&self, base: usize, x0: usize) -> usize {
        let mut left = x0;
        while left > 0 {
            let k = left.min(64);
            // Bit 63 of `w` is pixel left − 1, bit 64 − k pixel left − k.
            let w = self.same(base + left - k) << (64 - k);
            let ones = (w.leading_ones() as usize).min(k);
            left -= ones;
            if ones < k {
                break;
            }
        }
        left
    }

    /// The last `x` of the run of `same` pixels starting at `x0` in a row of width `w`.
    fn run_end(&self, base: usize, x0: usize, w: usize) -> usize {
        let mut right = x0;
        while right + 1 < w {
            let k = (w - 1 - right).min(64);
            let bits = self.same(base + right + 1) & low_bits(k);
            let ones = (bits.trailing_ones() as usize).min(k);
            right += ones;
            if ones < k {
                break;
            }
        }
        right
    }
}

/// Marks the component of `start` (8-connected if foreground, 4-connected otherwise) as
/// visited; returns true when it touches the image border.
///
/// Span filling: each stack entry is a seed pixel; its whole horizontal run of unvisited
/// pixels of the same value is marked at once, and the rows above and below are scanned over
/// the run (widened by one pixel on each side for 8-connectivity) for new seeds, one per
/// run. Runs are found and marked 64 pixels at a time on the bit rows of the mask.
fn flood(mask: &Mask, visited: &mut Visited, start: Pixel, stack: &mut Vec<Pixel>) -> bool {
    let value = fg(mask, start);
    let (w, h) = (mask.width() as usize, mask.height() as usize);
    let reach = usize::from(value); // 8-connected foreground reaches diagonally
    let mut touches = false;
    stack.clear();
    stack.push(start);
    while let Some(p) = stack.pop() {
        let (x, y) = (p.x as usize, p.y as usize);
        let base = y * w;
        let u = Unvisited {
            mask,
            visited: &visited.0,
            value,
        };
        if u.same(base + x) & 1 == 0 {
            continue;
        }
        let left = u.run_start(base, x);
        let right = u.run_end(base, x, w);
        visited.0.set_range(base + left, base + right);
        if y == 0 || y == h - 1 || left == 0 || right == w - 1 {
            touches = true;
        }
        let u = Unvisited {
            mask,
            visited: &visited.0,
            value,
        };
        for ny in [y.wrapping_sub(1), y + 1] {
            if ny >= h {
                continue; // also y − 1 below row 0 (wrapped)
            }
            let nbase = ny * w;
            let (from, to) = (left.saturating_sub(reach), (right + reach).min(w - 1));
            // One seed per run: the set bits of `same` whose left neighbour (within the
            // scanned span) is not set.
            let mut prev = 0u64;
            let mut xx = from;
            while xx <= to {
                let k = (to - xx + 1).min(64);
                let bits = u.same(nbase + xx) & low_bits(k);
                let mut starts = bits & !((bits << 1) | prev);
                while starts != 0 {
                    let j = starts.trailing_zeros() as usize;
                    stack.push(Pixel::new((xx + j) as i32, ny as i32));
                    starts &= starts - 1;
                }
                prev = (bits >> (k - 1)) & 1;
                xx += k;
            }
        }
    }
    touches
}

fn trace_default(mask: &Mask) -> Vec<Contour> {
    let mut visited = Visited(Mask::new(mask.width(), mask.height()));
    let mut stack = Vec::new();
    let mut out = Vec::new();
    let w = mask.width() as usize;
    for y in 0..mask.height() as usize {
        let base = y * w;
        let mut x = 0;
        while x < w {
            // Skip visited pixels 64 at a time.
            let k = (w - x).min(64);
            let free = !visited.0.bits_at(base + x) & low_bits(k);
            if free == 0 {
                x += k;
                continue;
            }
            x += free.trailing_zeros() as usize;
            let p = Pixel::new(x as i32, y as i32);
            let touches = flood(mask, &mut visited, p, &mut stack);
            if fg(mask, p) {
                // All of N, NW, NE and W precede p in raster order: background.
                out.push(Contour {
                    points: moore_trace(mask, p, DIR_N),
                    hole: false,
                    closed: true,
                });
            } else if !touches {
                // A hole: the pixel above its first pixel is foreground (y > 0, and a
                // background pixel there would belong to the same hole, earlier).
                out.push(Contour {
                    points: moore_trace(mask, Pixel::new(p.x, p.y - 1), DIR_S),
                    hole: true,
                    closed: true,
                });
            }
            x += 1;
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// IPOL convention: crack following.
// ---------------------------------------------------------------------------------------

/// Crack directions: increasing index turns right (clockwise on screen).
const CRACK_DIRS: [(i32, i32); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)]; // E S W N

/// A directed crack: from lattice vertex `(x, y)` (the top-left corner of pixel `(x, y)`)
/// one unit in direction `d`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Crack {
    x: i32,
    y: i32,
    d: usize,
}

impl Crack {
    /// The pixels on the walker's right and left.
    #[inline]
    fn sides(self) -> (Pixel, Pixel) {
        let (x, y) = (self.x, self.y);
        match self.d {
            0 => (Pixel::new(x, y), Pixel::new(x, y - 1)),
            1 => (Pixel::new(x - 1, y), Pixel::new(x, y)),
            2 => (Pixel::new(x - 1, y - 1), Pixel::new(x - 1, y)),
            _ => (Pixel::new(x, y - 1), Pixel::new(x - 1, y - 1)),
        }
    }

    #[inline]
    fn end(self) -> (i32, i32) {
        let (dx, dy) = CRACK_DIRS[self.d];
        (self.x + dx, self.y + dy)
    }

    /// The crack's slot in the traced marks: (vertical?, column, row).
    #[inline]
    fn slot(self) -> (bool, i64, i64) {
        let (x, y) = (i64::from(self.x), i64::from(self.y));
        match self.d {
            0 => (false, x, y),
            1 => (true, x, y),
            2 => (false, x - 1, y),
            _ => (true, x, y - 1),
        }
    }
}

struct Cracks<'a> {
    mask: &'a Mask,
    /// Vertical cracks: column = vertex column (1..w), row = pixel row.
    vertical: Mask,
    /// Horizontal cracks: column = pixel column, row = vertex row (1..h).
    horizontal: Mask,
}

impl Cracks<'_> {
    #[inline]
    fn inside(&self, p: Pixel) -> bool {
        p.x >= 0
            && p.y >= 0
            && i64::from(p.x) < i64::from(self.mask.width())
            && i64::from(p.y) < i64::from(self.mask.height())
    }

    /// Ink on the right, paper on the left, both inside the image.
    #[inline]
    fn valid(&self, c: Crack) -> bool {
        let (r, l) = c.sides();
        self.inside(r) && self.inside(l) && fg(self.mask, r) && !fg(self.mask, l)
    }

    /// The crack between two pixels that are 4-adjacent, oriented with ink on the right,
    /// if they differ and are both inside.
    fn between(&self, a: Pixel, b: Pixel) -> Option<Crack> {
        let candidates = if a.y == b.y {
            let x = a.x.max(b.x);
            [
                Crack { x, y: a.y, d: 1 },
                Crack {
                    x,
                    y: a.y + 1,
                    d: 3,
                },
            ]
        } else {
            let y = a.y.max(b.y);
            [
                Crack { x: a.x, y, d: 0 },
                Crack {
                    x: a.x + 1,
                    y,
                    d: 2,
                },
            ]
        };
        candidates.into_iter().find(|&c| self.valid(c))
    }

    /// The next crack: turn right if possible (ink stays 4-connected), else straight, else
    /// left; none at the image border.
    #[inline]
    fn next(&self, c: Crack) -> Option<Crack> {
        let (x, y) = c.end();
        [(c.d + 1) % 4, c.d, (c.d + 3) % 4]
            .into_iter()
            .map(|d| Crack { x, y, d })
            .find(|&n| self.valid(n))
    }

    /// The crack whose [`Cracks::next`] is `c`.
    fn prev(&self, c: Crack) -> Option<Crack> {
        [c.d, (c.d + 3) % 4, (c.d + 1) % 4]
            .into_iter()
            .map(|d| {
                let (dx, dy) = CRACK_DIRS[d];
                Crack {
                    x: c.x - dx,
                    y: c.y - dy,
                    d,
                }
            })
            .find(|&p| self.valid(p) && self.next(p) == Some(c))
    }

    fn traced(&self, c: Crack) -> bool {
        let (vertical, x, y) = c.slot();
        if vertical {
            self.vertical.get(x, y)
        } else {
            self.horizontal.get(x, y)
        }
    }

    fn mark(&mut self, c: Crack) {
        let (vertical, x, y) = c.slot();
        if vertical {
            self.vertical.set(x, y, true);
        } else {
            self.horizontal.set(x, y, true);
        }
    }

    /// Follows cracks from `start` (forward, or backward with `prev`) until the image border
    /// or an already traced crack; returns the ink pixels (consecutive duplicates dropped)
    /// and whether the walk came back to `start`.
    fn follow(&mut self, start: Crack, backward: bool) -> (Vec<Pixel>, bool) {
        let mut points: Vec<Pixel> = Vec::new();
        let mut c = start;
        loop {
            self.mark(c);
            let ink = c.sides().0;
            if points.last() != Some(&ink) {
                points.push(ink);
            }
            let step = if backward { self.prev(c) } else { self.next(c) };
            match step {
                Some(n) if n == start => return (points, true),
                Some(n) if !self.traced(n) => c = n,
                _ => return (points, false),
            }
        }
    }
}

fn trace_ipol(mask: &Mask) -> Vec<Contour> {
    let (w, h) = (mask.width() as i32, mask.height() as i32);
    let mut cracks = Cracks {
        mask,
        vertical: Mask::new(mask.width().saturating_add(1), mask.height()),
        horizontal: Mask::new(mask.width(), mask.height().saturating_add(1)),
    };
    let mut out = Vec::new();

    // Open chains, from the border cracks.
    let mut border = Vec::new();
    for x in 0..w - 1 {
        border.push((Pixel::new(x, 0), Pixel::new(x + 1, 0)));
        border.push((Pixel::new(x, h - 1), Pixel::new(x + 1, h - 1)));
    }
    for y in 0..h - 1 {
        border.push((Pixel::new(0, y), Pixel::new(0, y + 1)));
        border.push((Pixel::new(w - 1, y), Pixel::new(w - 1, y + 1)));
    }
    for (a, b) in border {
        let Some(c) = cracks.between(a, b) else {
            continue;
        };
        if cracks.traced(c) {
            continue;
        }
        let backward = cracks.prev(c).is_some();
        let (points, _) = cracks.follow(c, backward);
        out.push(Contour {
            points,
            hole: false,
            closed: false,
        });
    }

    // Closed contours, from the interior cracks, column by column.
    for x in 1..w - 1 {
        for y in 1..h - 1 {
            let p = Pixel::new(x, y);
            for q in [Pixel::new(x + 1, y), Pixel::new(x, y + 1)] {
                let Some(c) = cracks.between(p, q) else {
                    continue;
                };
                if cracks.traced(c) {
                    continue;
                }
                let (mut points, closed) = cracks.follow(c, false);
                if closed && points.first() != points.last() {
                    if let Some(&first) = points.first() {
                        points.push(first);
                    }
                }
                let hole = closed && crack_area2(&cracks, c) < 0;
                out.push(Contour {
                    points,
                    hole,
                    closed,
                });
            }
        }
    }
    out
}

/// Twice the signed area of the closed crack cycle through `start` (positive when clockwise
/// on screen, i.e. for outer contours with ink on the right).
fn crack_area2(cracks: &Cracks<'_>, start: Crack) -> i64 {
    let mut area = 0i64;
    let mut c = start;
    loop {
        let (x1, y1) = c.end();
        area += i64::from(c.x) * i64::from(y1) - i64::from(x1) * i64::from(c.y);
        match cracks.next(c) {
            Some(n) if n != start => c = n,
            _ => return area,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::{load_path, Compat, LoadOptions, Threshold};
    use proptest::prelude::*;
    use std::collections::{HashMap, HashSet};
    use std::path::Path;

    /// Connected-component labels of the pixels whose value is `value`, over the image
    /// enlarged by `pad` pixels of background on every side (so with `pad = 1` all
    /// background touching the border forms one "outside" component). Independent of the
    /// code under test: a breadth-first fill. Returns labels indexed by padded coordinates
    /// (`u32::MAX` for other pixels) and the number of labels.
    struct Labels {
        w: i64,
        h: i64,
        pad: i64,
        label: Vec<u32>,
        count: u32,
    }

    impl Labels {
        fn new(mask: &Mask, value: bool, eight: bool, pad: i64) -> Labels {
            let (w, h) = (
                i64::from(mask.width()) + 2 * pad,
                i64::from(mask.height()) + 2 * pad,
            );
            let at = |x: i64, y: i64| mask.get(x - pad, y - pad);
            let mut label = vec![u32::MAX; (w * h) as usize];
            let mut count = 0;
            let mut queue = std::collections::VecDeque::new();
            for y in 0..h {
                for x in 0..w {
                    if at(x, y) != value || label[(y * w + x) as usize] != u32::MAX {
                        continue;
                    }
                    label[(y * w + x) as usize] = count;
                    queue.push_back((x, y));
                    while let Some((px, py)) = queue.pop_front() {
                        for dy in -1..=1i64 {
                            for dx in -1..=1i64 {
                                if (dx, dy) == (0, 0) || (!eight && dx != 0 && dy != 0) {
                                    continue;
                                }
                                let (qx, qy) = (px + dx, py + dy);
                                if qx < 0 || qy < 0 || qx >= w || qy >= h {
                                    continue;
                                }
                                let i = (qy * w + qx) as usize;
                                if at(qx, qy) == value && label[i] == u32::MAX {
                                    label[i] = count;
                                    queue.push_back((qx, qy));
                                }
                            }
                        }
                    }
                    count += 1;
                }
            }
            Labels {
                w,
                h,
                pad,
                label,
                count,
            }
        }

        /// Label of image pixel `p` (padded coordinates handled here).
        fn of(&self, p: Pixel) -> Option<u32> {
            let (x, y) = (i64::from(p.x) + self.pad, i64::from(p.y) + self.pad);
            if x < 0 || y < 0 || x >= self.w || y >= self.h {
                return None;
            }
            let l = self.label[(y * self.w + x) as usize];
            (l != u32::MAX).then_some(l)
        }

        /// Whether component `l` touches the border of the (unpadded) image.
        fn touches_border(&self, l: u32, mask: &Mask) -> bool {
            let (w, h) = (mask.width() as i32, mask.height() as i32);
            (0..w).any(|x| {
                self.of(Pixel::new(x, 0)) == Some(l) || self.of(Pixel::new(x, h - 1)) == Some(l)
            }) || (0..h).any(|y| {
                self.of(Pixel::new(0, y)) == Some(l) || self.of(Pixel::new(w - 1, y)) == Some(l)
            })
        }
    }

    fn fg(mask: &Mask, p: Pixel) -> bool {
        mask.get(i64::from(p.x), i64::from(p.y))
    }

    /// Twice the signed area of the polygon through the pixel centres (positive when
    /// clockwise on screen, y down).
    fn area2(points: &[Pixel]) -> i64 {
        let n = points.len();
        (0..n)
            .map(|i| {
                let (a, b) = (points[i], points[(i + 1) % n]);
                i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
            })
            .sum()
    }

    fn first_in_raster_order(labels: &Labels, l: u32) -> Option<Pixel> {
        (0..labels.h - 2 * labels.pad)
            .flat_map(|y| {
                (0..labels.w - 2 * labels.pad).map(move |x| Pixel::new(x as i32, y as i32))
            })
            .find(|&p| labels.of(p) == Some(l))
    }

    /// Checks every property of the Default convention; returns (outer, hole) counts.
    fn check_default(mask: &Mask) -> (usize, usize) {
        let contours = trace(mask, Convention::Default);
        let comps = Labels::new(mask, true, true, 0);
        let bg = Labels::new(mask, false, false, 1); // padded: label of outside = of (-1,-1)
        let outside = bg.of(Pixel::new(-1, -1));
        let holes = (0..bg.count).filter(|&l| Some(l) != outside).count();

        let n_outer = contours.iter().filter(|c| !c.hole).count();
        let n_hole = contours.iter().filter(|c| c.hole).count();
        assert_eq!(
            n_outer, comps.count as usize,
            "outer contours vs 8-components"
        );
        assert_eq!(
            n_hole, holes,
            "hole contours vs bounded 4-connected background components"
        );

        let mut seen_comps = HashSet::new();
        let mut seen_holes = HashSet::new();
        let mut covered = HashSet::new();
        for c in &contours {
            assert!(c.closed);
            let pts = &c.points;
            assert!(!pts.is_empty());
            for i in 0..pts.len() {
                let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
                if pts.len() > 1 {
                    assert!(a.is_8_adjacent(b), "{a:?} -> {b:?} not 8-adjacent in {c:?}");
                }
                covered.insert(a);
            }
            let first = pts[0];
            let comp = comps.of(first).expect("contour point must be foreground");
            // The background region this border separates from the component.
            let region = if c.hole {
                let below = Pixel::new(first.x, first.y + 1);
                let h = bg
                    .of(below)
                    .expect("a hole border starts above a hole pixel");
                assert_ne!(Some(h), outside);
                assert!(seen_holes.insert(h), "hole traced twice");
                assert_eq!(
                    first_in_raster_order(&bg, h),
                    Some(below),
                    "hole start rule"
                );
                h
            } else {
                assert!(seen_comps.insert(comp), "component traced twice");
                assert_eq!(
                    first_in_raster_order(&comps, comp),
                    Some(first),
                    "outer start rule"
                );
                bg.of(Pixel::new(first.x, first.y - 1))
                    .expect("above the first pixel is background")
            };
            // Points: exactly the pixels of the component with a 4-neighbour in the region.
            let got: HashSet<Pixel> = pts.iter().copied().collect();
            let mut want = HashSet::new();
            for y in 0..mask.height() as i32 {
                for x in 0..mask.width() as i32 {
                    let p = Pixel::new(x, y);
                    if comps.of(p) == Some(comp)
                        && p.neighbours4().iter().any(|&q| bg.of(q) == Some(region))
                    {
                        want.insert(p);
                    }
                }
            }
            assert_eq!(got, want, "contour {c:?}");
            // Orientation: never clockwise for outer borders, never counter-clockwise for holes.
            let a = area2(pts);
            if c.hole {
                assert!(a >= 0, "hole border must run clockwise on screen: {a}");
            } else {
                assert!(
                    a <= 0,
                    "outer border must run counter-clockwise on screen: {a}"
                );
            }
        }
        // Coverage: every boundary pixel is on some contour.
        for y in 0..mask.height() as i32 {
            for x in 0..mask.width() as i32 {
                let p = Pixel::new(x, y);
                let boundary = fg(mask, p) && p.neighbours4().iter().any(|&q| !fg(mask, q));
                assert_eq!(covered.contains(&p), boundary, "{p:?}");
            }
        }
        (n_outer, n_hole)
    }

    #[test]
    fn single_pixel_and_empty() {
        assert!(trace(&Mask::new(5, 5), Convention::Default).is_empty());
        assert!(trace(&Mask::new(0, 0), Convention::Default).is_empty());
        let m = Mask::from_ascii("...\n.#.\n...");
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points, vec![Pixel::new(1, 1)]);
        check_default(&m);
        // A full image: one contour around the border.
        let full = Mask::from_fn(4, 3, |_, _| true);
        assert_eq!(check_default(&full), (1, 0));
        assert_eq!(trace(&full, Convention::Default)[0].points.len(), 10);
    }

    #[test]
    fn thin_bar_goes_along_and_back() {
        let m = Mask::from_ascii(".......\n.#####.\n.......");
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 1);
        let pts = &c[0].points;
        // Each interior pixel is visited twice, the two ends once: 2 * 5 - 2 points.
        assert_eq!(pts.len(), 8);
        for x in 2..=4 {
            assert_eq!(pts.iter().filter(|p| p.x == x).count(), 2);
        }
        check_default(&m);
        // The start pixel is a cut vertex: the walk passes through it in the middle and
        // must not stop there.
        let m = Mask::from_ascii(".##\n#..");
        let c = trace(&m, Convention::Default);
        assert_eq!(c[0].points.len(), 4);
        assert_eq!(
            c[0].points
                .iter()
                .filter(|p| **p == Pixel::new(1, 0))
                .count(),
            2
        );
        check_default(&m);
        // Vertical bar too.
        let v = Mask::from_ascii("#\n#\n#\n#");
        assert_eq!(trace(&v, Convention::Default)[0].points.len(), 6);
    }

    #[test]
    fn diagonal_contacts_are_one_component() {
        let m = Mask::from_ascii("#..\n.#.\n..#");
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points.len(), 4);
        assert_eq!(check_default(&m), (1, 0));
        // Two blocks touching at a corner.
        let m = Mask::from_ascii("##..\n##..\n..##\n..##");
        assert_eq!(check_default(&m), (1, 0));
        // A diagonal ring encloses a 4-connected hole.
        let m = Mask::from_ascii(".#.\n#.#\n.#.");
        assert_eq!(check_default(&m), (1, 1));
    }

    #[test]
    fn holes_and_nesting() {
        let m = Mask::from_ascii(
            "
            #########
            #.......#
            #.#####.#
            #.#...#.#
            #.#.#.#.#
            #.#...#.#
            #.#####.#
            #.......#
            #########
            ",
        );
        assert_eq!(check_default(&m), (3, 2));
        let c = trace(&m, Convention::Default);
        // Raster order of first pixels: ring, its hole, inner ring, its hole, dot.
        let kinds: Vec<bool> = c.iter().map(|c| c.hole).collect();
        assert_eq!(kinds, vec![false, true, false, true, false]);
        // Thick shapes: strict orientation.
        assert!(area2(&c[0].points) < 0);
        assert!(area2(&c[1].points) > 0);
        // Two holes separated by a diagonal contact of background only.
        // Background touching only diagonally: three separate 4-connected holes.
        let m = Mask::from_ascii("#####\n#.#.#\n##.##\n#####");
        assert_eq!(check_default(&m), (1, 3));
    }

    #[test]
    fn border_touching_shapes() {
        let m = Mask::from_ascii("##..#\n#...#\n....#\n##..#");
        assert_eq!(check_default(&m), (3, 0));
        // A bar across the image splits the background; the outside is still one region.
        let m = Mask::from_ascii("..#..\n..#..\n..#..");
        assert_eq!(check_default(&m), (1, 0));
    }

    #[test]
    fn many_components_and_long_contours() {
        // 200 x 200 isolated pixels.
        let m = Mask::from_fn(400, 400, |x, y| x % 2 == 0 && y % 2 == 0);
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 40_000);
        assert!(c.iter().all(|c| c.points.len() == 1));
        // A 1-pixel line of 300 000 pixels: one contour of 2 * 300 000 - 2 points.
        let m = Mask::from_fn(300_000, 1, |_, _| true);
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points.len(), 599_998);
        // A large filled square and a comb with many teeth (long thin contour).
        let m = Mask::from_fn(1500, 1500, |x, y| y < 3 || x % 2 == 0);
        let c = trace(&m, Convention::Default);
        assert_eq!(c.len(), 1);
        let boundary = (0..1500i32)
            .flat_map(|y| (0..1500i32).map(move |x| Pixel::new(x, y)))
            .filter(|&p| fg(&m, p) && p.neighbours4().iter().any(|&q| !fg(&m, q)))
            .count();
        let distinct: HashSet<Pixel> = c[0].points.iter().copied().collect();
        assert_eq!(distinct.len(), boundary);
    }

    fn sample_counts() -> Vec<(&'static str, usize, usize)> {
        // comps/holes as listed in samples/README.md (counted by the corpus generator).
        vec![
            ("glyph_S_dejavusans_cap120", 1, 0),
            ("glyph_g_liberationserif_cap120", 1, 2),
            ("glyph_at_dejavusans_cap40", 1, 1),
            ("digits_liberationsans_cap40", 10, 6),
            ("word_Layers_dejavusans-bold_cap40", 6, 2),
            ("sil_horse_skimage", 1, 1),
            ("lineart_cat_symbola_h300", 4, 24),
            ("suits_black_dejavusans_cap120", 4, 1),
        ]
    }

    #[test]
    fn samples_default_convention() {
        let mut cases = sample_counts();
        // Synthetic samples carry their counts in the JSON side file.
        for name in [
            "syn_tiny_blobs",
            "syn_discs_r3_to_r200",
            "syn_ellipses_rotated",
            "syn_border_touching",
            "syn_digital_circle_1px",
            "syn_fig15_ellipse_two_holes",
            "syn_polygons_sharp",
        ] {
            let text = std::fs::read_to_string(format!("samples/{name}.json")).unwrap();
            let json: serde_json::Value = serde_json::from_str(&text).unwrap();
            let m = &json["measured"];
            let comps = m["components_8conn"].as_u64().unwrap() as usize;
            let holes = m["holes_4conn"].as_u64().unwrap() as usize;
            cases.push((name, comps, holes));
        }
        for (name, comps, holes) in cases {
            let path = format!("samples/{name}.png");
            let l = load_path(Path::new(&path), &LoadOptions::default()).unwrap();
            let (o, h) = check_default(&l.mask);
            assert_eq!((o, h), (comps, holes), "{name}");
            // Thick shapes: every outer border strictly counter-clockwise, holes clockwise.
            if name.starts_with("syn_discs") || name.starts_with("syn_fig15") {
                for c in trace(&l.mask, Convention::Default) {
                    let a = area2(&c.points);
                    assert!(if c.hole { a > 0 } else { a < 0 }, "{name}");
                }
            }
        }
    }

    /// Random small masks: noise, or a union of rectangles and discs.
    fn arb_mask() -> impl Strategy<Value = Mask> {
        let noise =
            (1u32..=24, 1u32..=24, 0u32..=100, any::<u64>()).prop_map(|(w, h, density, seed)| {
                let mut s = seed | 1;
                Mask::from_fn(w, h, |_, _| {
                    s ^= s << 13;
                    s ^= s >> 7;
                    s ^= s << 17;
                    (s % 100) < u64::from(density)
                })
            });
        let blobs = (
            1u32..=24,
            1u32..=24,
            proptest::collection::vec(
                (0i32..24, 0i32..24, 0i32..8, any::<bool>(), any::<bool>()),
                1..8,
            ),
        )
            .prop_map(|(w, h, shapes)| {
                Mask::from_fn(w, h, |x, y| {
                    let (x, y) = (x as i32, y as i32);
                    let mut v = false;
                    for &(cx, cy, r, disc, erase) in &shapes {
                        let inside = if disc {
                            (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r
                        } else {
                            (x - cx).abs() <= r && (y - cy).abs() <= r / 2 + 1
                        };
                        if inside {
                            v = !erase;
                        }
                    }
                    v
                })
            });
        prop_oneof![noise, blobs]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        #[test]
        fn default_invariants(mask in arb_mask()) {
            check_default(&mask);
        }

        #[test]
        fn ipol_invariants(mask in arb_mask()) {
            check_ipol(&mask);
        }
    }

    // ---------------------------------------------------------------- IPOL convention

    /// Checks the IPOL convention's properties; returns the number of contours.
    fn check_ipol(mask: &Mask) -> usize {
        let contours = trace(mask, Convention::Ipol);
        let (w, h) = (mask.width() as i32, mask.height() as i32);
        let inside = |p: Pixel| p.x >= 0 && p.y >= 0 && p.x < w && p.y < h;
        let ink = Labels::new(mask, true, false, 0); // 4-connected ink
        let paper = Labels::new(mask, false, true, 0); // 8-connected paper
        let mut covered = HashSet::new();
        let mut outer_of: HashMap<u32, usize> = HashMap::new();
        let mut hole_of: HashMap<u32, usize> = HashMap::new();
        for c in &contours {
            let pts = &c.points;
            assert!(!pts.is_empty());
            for win in pts.windows(2) {
                assert!(win[0].is_8_adjacent(win[1]), "{:?} -> {:?}", win[0], win[1]);
            }
            for &p in pts {
                assert!(fg(mask, p));
                assert!(
                    p.neighbours4().iter().any(|&q| inside(q) && !fg(mask, q)),
                    "{p:?} has no paper 4-neighbour"
                );
                covered.insert(p);
            }
            if !c.closed {
                assert!(!c.hole);
                // Open chains end on the image border at both ends.
                for p in [pts[0], pts[pts.len() - 1]] {
                    assert!(
                        p.x == 0 || p.y == 0 || p.x == w - 1 || p.y == h - 1,
                        "{p:?}"
                    );
                }
                continue;
            }
            assert_eq!(
                pts.first(),
                pts.last(),
                "closed contours repeat their start"
            );
            let a = area2(pts);
            let first = pts[0];
            if c.hole {
                assert!(a <= 0, "holes run anticlockwise on screen");
                // The hole: the bounded paper component P such that the contour's points are
                // exactly the pixels of the start pixel's ink component C with a 4-neighbour
                // in P (the border between a 4-connected C and an 8-connected P is one cycle;
                // ink islands inside the hole are other components).
                let got: HashSet<Pixel> = pts.iter().copied().collect();
                let comp = ink.of(first);
                let border_of = |l: u32| -> HashSet<Pixel> {
                    (0..w)
                        .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                        .filter(|&p| {
                            ink.of(p) == comp
                                && p.neighbours4().iter().any(|&q| paper.of(q) == Some(l))
                        })
                        .collect()
                };
                let l = pts
                    .iter()
                    .flat_map(|p| p.neighbours4())
                    .filter_map(|q| paper.of(q))
                    .find(|&l| !paper.touches_border(l, mask) && border_of(l) == got)
                    .expect("a hole contour is the ink border of one hole");
                assert!(hole_of.insert(l, 1).is_none(), "hole traced twice");
                // Start rule: the ink pixel left of the topmost pixel of the hole's leftmost
                // column (unless that column is 1, whose left cracks the reference does not
                // scan).
                let leftmost_top = (0..w)
                    .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                    .find(|&p| paper.of(p) == Some(l))
                    .unwrap();
                if leftmost_top.x >= 2 {
                    assert_eq!(
                        first,
                        Pixel::new(leftmost_top.x - 1, leftmost_top.y),
                        "hole start rule"
                    );
                }
            } else {
                assert!(a >= 0, "outer contours run clockwise on screen");
                let l = ink.of(first).unwrap();
                assert!(!ink.touches_border(l, mask));
                let leftmost_top = (0..w)
                    .flat_map(|x| (0..h).map(move |y| Pixel::new(x, y)))
                    .find(|&p| ink.of(p) == Some(l));
                if leftmost_top.is_some_and(|p| p.x >= 2) {
                    assert_eq!(leftmost_top, Some(first), "outer start rule");
                }
                assert!(outer_of.insert(l, 1).is_none(), "component traced twice");
            }
        }
        let closed_outer = (0..ink.count)
            .filter(|&l| !ink.touches_border(l, mask))
            .count();
        let holes = (0..paper.count)
            .filter(|&l| !paper.touches_border(l, mask))
            .count();
        assert_eq!(
            outer_of.len(),
            closed_outer,
            "closed outer contours vs inner 4-components"
        );
        assert_eq!(
            contours.iter().filter(|c| c.closed && !c.hole).count(),
            closed_outer
        );
        assert_eq!(
            hole_of.len(),
            holes,
            "hole contours vs bounded 8-connected paper"
        );
        assert_eq!(contours.iter().filter(|c| c.hole).count(), holes);
        for y in 0..h {
            for x in 0..w {
                let p = Pixel::new(x, y);
                let border =
                    fg(mask, p) && p.neighbours4().iter().any(|&q| inside(q) && !fg(mask, q));
                assert_eq!(covered.contains(&p), border, "{p:?}");
            }
        }
        contours.len()
    }

    #[test]
    fn ipol_small_cases() {
        // Two blocks touching at a corner: two contours (ink is 4-connected).
        let m = Mask::from_ascii("......\n.##...\n.##...\n...##.\n...##.\n......");
        assert_eq!(check_ipol(&m), 2);
        // A ring with a one-pixel hole, two pixels from the image border.
        let m = Mask::from_ascii("......\n......\n..###.\n..#.#.\n..###.\n......");
        let c = trace(&m, Convention::Ipol);
        assert_eq!(c.len(), 2);
        assert!(!c[0].hole && c[1].hole);
        assert_eq!(c[0].points.first(), Some(&Pixel::new(2, 2)));
        assert_eq!(c[1].points.first(), Some(&Pixel::new(2, 3)));
        // Clockwise: from the top-left pixel the outer contour goes right.
        assert_eq!(c[0].points[1], Pixel::new(3, 2));
        // Anticlockwise around the hole: from its left, go down.
        assert_eq!(c[1].points[1], Pixel::new(3, 4));
        assert_eq!(c[1].points.len(), 5);
        check_ipol(&m);
        // Paper touching diagonally is one (8-connected) hole; ink touching diagonally is two
        // components.
        let m = Mask::from_ascii(".......\n..####.\n..#.#..\n..##.#.\n..####.\n.......");
        check_ipol(&m);
        // In the reference's scan, cracks next to column 0 are not scanned: a hole in column 1
        // is then found before the outer contour around it.
        let m = Mask::from_ascii(".....\n.###.\n.#.#.\n.###.\n.....");
        let c = trace(&m, Convention::Ipol);
        assert_eq!(
            c.iter().map(|c| c.hole).collect::<Vec<_>>(),
            vec![true, false]
        );
        check_ipol(&m);
        // Border-touching shapes give open chains.
        let m = Mask::from_ascii("##...\n##...\n.....\n..###");
        let c = trace(&m, Convention::Ipol);
        assert_eq!(c.len(), 2);
        assert!(c.iter().all(|c| !c.closed && !c.hole));
        check_ipol(&m);
        // Single ink pixel.
        let m = Mask::from_ascii("...\n.#.\n...");
        assert_eq!(
            trace(&m, Convention::Ipol)[0].points,
            vec![Pixel::new(1, 1)]
        );
        assert!(trace(&Mask::new(1, 1), Convention::Ipol).is_empty());
        assert!(trace(&Mask::from_fn(3, 3, |_, _| true), Convention::Ipol).is_empty());
    }

    #[test]
    fn ipol_invariants_on_samples() {
        for e in std::fs::read_dir("samples").unwrap() {
            let path = e.unwrap().path();
            if path.extension().is_some_and(|x| x == "png") {
                let l = load_path(&path, &LoadOptions::default()).unwrap();
                check_ipol(&l.mask);
                let open = trace(&l.mask, Convention::Ipol)
                    .iter()
                    .filter(|c| !c.closed)
                    .count();
                // Only syn_border_touching has shapes cut by the image border (three).
                let expected = if path.ends_with("syn_border_touching.png") {
                    3
                } else {
                    0
                };
                assert_eq!(open, expected, "{}", path.display());
            }
        }
    }

    const IPOL: [(&str, usize); 10] = [
        ("card_suits", 4),
        ("ipol", 5),
        ("ET_head", 3),
        ("ninja_star", 1),
        ("heptagon", 1),
        ("punk_fish", 1),
        ("pif", 1),
        ("imageS", 3),
        ("disc", 1),
        ("triangle", 1),
    ];

    fn ipol_options() -> LoadOptions {
        LoadOptions {
            threshold: Threshold::Otsu,
            compat: Compat::Ipol,
            ..LoadOptions::default()
        }
    }

    #[test]
    fn ipol_reference_contour_counts() {
        for (name, count) in IPOL {
            let l = load_path(
                Path::new(&format!("samples/ipol/{name}.png")),
                &ipol_options(),
            )
            .unwrap();
            assert_eq!(check_ipol(&l.mask), count, "{name}");
        }
    }

    #[test]
    fn ipol_starts_and_directions_match_reference_outputs() {
        // The reference colours each contour's first segment yellow and the following ones
        // green, blue, red, green, blue, red, ... (measured on these outputs: yellow is never
        // used again), so walking in the reference's direction colours only change along
        // yellow -> green -> blue -> red -> green. The start pixel of a closed contour
        // is repeated at the end and painted over by the last segment, so it is skipped.
        const CYCLE: [[u8; 3]; 4] = [[255, 255, 0], [0, 255, 0], [0, 0, 255], [255, 0, 0]];
        for (name, _) in IPOL {
            let l = load_path(
                Path::new(&format!("samples/ipol/{name}.png")),
                &ipol_options(),
            )
            .unwrap();
            let out = image::open(format!(
                "samples/ipol/reference_out/StraightLine_out_{name}.png"
            ))
            .unwrap()
            .to_rgb8();
            assert_eq!(out.dimensions(), (l.mask.width(), l.mask.height()));
            let colour = |p: Pixel| out.get_pixel(p.x as u32, p.y as u32).0;
            let index = |p: Pixel| CYCLE.iter().position(|&c| c == colour(p));
            for c in trace(&l.mask, Convention::Ipol) {
                let walk = if c.closed {
                    &c.points[1..c.points.len() - 1]
                } else {
                    &c.points[..]
                };
                assert_eq!(
                    index(walk[0]),
                    Some(0),
                    "{name}: contour {:?} starts yellow",
                    c.points[0]
                );
                for win in walk.windows(2) {
                    let (a, b) = (index(win[0]).unwrap(), index(win[1]).unwrap());
                    let next = if a == 3 { 1 } else { a + 1 };
                    assert!(
                        b == a || b == next,
                        "{name}: {:?} -> {:?} goes backwards",
                        win[0],
                        win[1]
                    );
                }
            }
            // All drawn pixels of the reference are our contour pixels (and vice versa).
            let drawn = out.pixels().filter(|p| p.0 != [255, 255, 255]).count();
            let ours: HashSet<Pixel> = trace(&l.mask, Convention::Ipol)
                .into_iter()
                .flat_map(|c| c.points)
                .collect();
            assert_eq!(drawn, ours.len(), "{name}");
            assert!(ours.iter().all(|&p| colour(p) != [255, 255, 255]), "{name}");
        }
    }
}
