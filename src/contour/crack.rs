//! Crack following: the IPOL convention ([`super::Convention::Ipol`]), the cracks (pixel
//! edges) between 4-connected ink and 8-connected paper, as the article's reference code
//! follows them.

use super::{fg, Contour};
use crate::bitmap::Mask;
use crate::pixel::Pixel;

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

/// Traces [`super::Convention::Ipol`].
pub(super) fn trace_ipol(mask: &Mask) -> Vec<Contour> {
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
