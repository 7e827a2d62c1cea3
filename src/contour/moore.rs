//! Moore-neighbour tracing: the default convention's borders, one per 8-connected
//! component and per hole, each found by [`super::runs`].

use super::runs::component_starts;
use super::{fg, Contour};
use crate::bitmap::Mask;
use crate::pixel::Pixel;
use rayon::prelude::*;

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

/// For each direction `d`, the direction from the neighbour in direction `d` to the one in
/// direction `d + 1` (a unit step: consecutive neighbours are 4-adjacent); the same from
/// every pixel, so [`moore_step`] looks it up.
const TO_NEXT: [usize; 8] = {
    let mut table = [0; 8];
    let mut d = 0;
    while d < 8 {
        let (q, c) = (DIRS[d], DIRS[(d + 1) % 8]);
        let mut k = 0;
        while k < 8 {
            if DIRS[k].0 == c.0 - q.0 && DIRS[k].1 == c.1 - q.1 {
                table[d] = k;
            }
            k += 1;
        }
        d += 1;
    }
    table
};

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
            return Some((q, TO_NEXT[d]));
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
    // (Room for the small contours of noise, most of them: growing the vector from its
    // first four points was 0.2% of 1000² noise's instructions.)
    let mut points = Vec::with_capacity(8);
    points.push(p0);
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

/// Traces [`super::Convention::Default`], the components in parallel (rayon; the order
/// stays raster order of their first pixels).
pub(super) fn trace_default(mask: &Mask) -> Vec<Contour> {
    component_starts(mask)
        .into_par_iter()
        .map(|s| {
            if s.hole {
                // The pixel above a hole's first pixel is foreground (y > 0, and a
                // background pixel there would belong to the same hole, earlier).
                Contour {
                    points: moore_trace(mask, Pixel::new(s.at.x, s.at.y - 1), DIR_S),
                    hole: true,
                    closed: true,
                }
            } else {
                // All of N, NW, NE and W precede the first pixel in raster order:
                // background.
                Contour {
                    points: moore_trace(mask, s.at, DIR_N),
                    hole: false,
                    closed: true,
                }
            }
        })
        .collect()
}
