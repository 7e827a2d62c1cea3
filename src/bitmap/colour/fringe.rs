//! Anti-aliasing fringes: thin runs of in-between colour along an edge between two regions.
//!
//! An anti-aliased edge between a red and a yellow region leaves one or two pixels of
//! orange along it; quantized, they become a sliver region of their own (or join a real
//! orange region elsewhere in the image). A pixel is a fringe pixel when, along one of the
//! four axes (horizontal, vertical, the two diagonals, in that order), the run of its
//! colour through it is 1 or 2 pixels long and ends on both sides on two *different* opaque
//! colours `a` and `b` with its own colour `c` between them: `c` projects onto the segment
//! `ab` of RGB space strictly inside it, at most a quarter of `|ab|` away from it. It joins
//! whichever of `a` and `b` is nearer to `c`. A thin line of a colour not between its two
//! sides (a black outline between yellow and white), or between two regions of the same
//! colour (a grey line on white), is kept.
//!
//! All pixels are decided on the image before the pass; passes repeat (at most
//! [`PASSES`]) while pixels change, so a two-pixel fringe of two different blends also
//! goes.

use super::{Colour, ColourImage};

/// The most passes over the image.
const PASSES: usize = 3;

/// The four axes, in the order they are tried.
const AXES: [(i64, i64); 4] = [(1, 0), (0, 1), (1, 1), (1, -1)];

/// Whether `c` is between `a` and `b` (see the module documentation).
fn between(a: Colour, c: Colour, b: Colour) -> bool {
    let v = |c: Colour| [f64::from(c.r), f64::from(c.g), f64::from(c.b)];
    let (a, c, b) = (v(a), v(c), v(b));
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ac = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let len2 = ab.iter().map(|x| x * x).sum::<f64>();
    if len2 == 0.0 {
        return false;
    }
    let t = ab.iter().zip(&ac).map(|(x, y)| x * y).sum::<f64>() / len2;
    if t <= 0.0 || t >= 1.0 {
        return false;
    }
    let off2: f64 = (0..3).map(|i| (ac[i] - t * ab[i]).powi(2)).sum();
    off2 <= len2 / 16.0
}

/// Moves the fringe pixels of `index` (row-major palette indices of a `width` × `height`
/// image, [`ColourImage::NONE`] for none) into the nearer neighbouring region; returns how
/// many pixel changes were made.
pub(super) fn clean(index: &mut [u16], width: u32, height: u32, palette: &[Colour]) -> u64 {
    let (w, h) = (i64::from(width), i64::from(height));
    let at = |index: &[u16], x: i64, y: i64| -> Option<u16> {
        if x < 0 || y < 0 || x >= w || y >= h {
            return None;
        }
        match index[(y * w + x) as usize] {
            ColourImage::NONE => None,
            k => Some(k),
        }
    };
    let mut changed = 0u64;
    for _ in 0..PASSES {
        let before = index.to_vec();
        let mut changes = 0u64;
        for y in 0..h {
            for x in 0..w {
                let Some(c) = at(&before, x, y) else {
                    continue;
                };
                for (dx, dy) in AXES {
                    // The run of `c` through (x, y): at most one more pixel on either side.
                    let back = usize::from(at(&before, x - dx, y - dy) == Some(c));
                    let fwd = usize::from(at(&before, x + dx, y + dy) == Some(c));
                    if back + fwd > 1 {
                        continue;
                    }
                    let (b0, f0) = (back as i64 + 1, fwd as i64 + 1);
                    let ends = (
                        at(&before, x - b0 * dx, y - b0 * dy),
                        at(&before, x + f0 * dx, y + f0 * dy),
                    );
                    let (Some(a), Some(b)) = ends else {
                        continue;
                    };
                    if a == c || b == c || a == b {
                        continue;
                    }
                    let (ca, cc, cb) = (
                        palette[usize::from(a)],
                        palette[usize::from(c)],
                        palette[usize::from(b)],
                    );
                    if between(ca, cc, cb) {
                        index[(y * w + x) as usize] = if cc.distance2(ca) <= cc.distance2(cb) {
                            a
                        } else {
                            b
                        };
                        changes += 1;
                        break;
                    }
                }
            }
        }
        changed += changes;
        if changes == 0 {
            break;
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    const RED: Colour = Colour {
        r: 220,
        g: 20,
        b: 20,
    };
    const ORANGE: Colour = Colour {
        r: 230,
        g: 120,
        b: 20,
    };
    const YELLOW: Colour = Colour {
        r: 240,
        g: 230,
        b: 20,
    };
    const BLACK: Colour = Colour { r: 0, g: 0, b: 0 };

    fn run(palette: &[Colour], row: &[u16]) -> (Vec<u16>, u64) {
        // Three identical rows: the vertical runs are long, only the horizontal one counts.
        let mut index: Vec<u16> = row.iter().chain(row).chain(row).copied().collect();
        let n = clean(&mut index, row.len() as u32, 3, palette);
        (index[row.len()..2 * row.len()].to_vec(), n)
    }

    #[test]
    fn thin_blends_join_the_nearer_side() {
        let p = [RED, ORANGE, YELLOW, BLACK];
        // One orange pixel between red and yellow: nearer to red (distance 100 vs 110).
        let (row, n) = run(&p, &[0, 0, 0, 1, 2, 2, 2]);
        assert_eq!(row, [0, 0, 0, 0, 2, 2, 2]);
        assert_eq!(n, 3);
        // Two pixels: both join.
        let (row, _) = run(&p, &[0, 0, 1, 1, 2, 2]);
        assert_eq!(row, [0, 0, 0, 0, 2, 2]);
        // Three pixels wide: a region of its own.
        let (row, n) = run(&p, &[0, 0, 1, 1, 1, 2, 2]);
        assert_eq!((row, n), (vec![0, 0, 1, 1, 1, 2, 2], 0));
        // Black is not between red and yellow: a thin line kept.
        let (row, n) = run(&p, &[0, 0, 3, 2, 2]);
        assert_eq!((row, n), (vec![0, 0, 3, 2, 2], 0));
        // The same colour on both sides: a thin line kept.
        let (row, n) = run(&p, &[0, 0, 1, 0, 0]);
        assert_eq!((row, n), (vec![0, 0, 1, 0, 0], 0));
        // At the image border or next to no region: kept.
        let (row, n) = run(&p, &[1, 2, 2]);
        assert_eq!((row, n), (vec![1, 2, 2], 0));
        let (row, n) = run(&p, &[0, 1, ColourImage::NONE]);
        assert_eq!((row, n), (vec![0, 1, ColourImage::NONE], 0));
    }

    #[test]
    fn betweenness() {
        assert!(between(RED, ORANGE, YELLOW));
        assert!(!between(RED, BLACK, YELLOW));
        assert!(!between(RED, RED, YELLOW));
        assert!(!between(RED, ORANGE, RED));
    }
}
