//! Borders of a partition: the cracks between two regions of a colour image, cut into
//! chains at the junctions, each chain shared by exactly two sides.
//!
//! # Labels
//! Every pixel has a label: its palette index, [`BorderGraph::none`] for a pixel of no
//! region (transparent), [`BorderGraph::outside`] for the pixels beyond the image. A crack
//! (the side shared by two 4-adjacent pixels) is a border crack when its two labels differ
//! and at least one is a region; it is walked with the smaller label on its left (on screen,
//! y down), so a region's cracks against no region or the outside always have the region on
//! their left.
//!
//! # Junctions
//! A crack corner (a lattice point, integer coordinates) is a junction when the number of
//! border cracks meeting there is not two, or when its four pixels carry more than two
//! labels (three regions meet, or a region, no region and the outside). Elsewhere exactly
//! two cracks meet and separate the same two labels. A [`Border`] is a maximal chain of
//! border cracks from a junction to a junction, or a closed loop without a junction (an
//! island in one other region); its cracks all have the same two labels, so it is shared by
//! exactly those two sides, and each border crack belongs to one border.

/// One border: a chain of cracks between the same two labels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Border {
    /// The label on the left of the walk (a region: the smaller label).
    pub left: usize,
    /// The label on the right: a region, [`BorderGraph::none`] or [`BorderGraph::outside`].
    pub right: usize,
    /// The crack corners in walking order, the first and last junctions (the same point for a
    /// closed border, which repeats its first corner at the end).
    pub corners: Vec<(i64, i64)>,
    /// A loop without a junction.
    pub closed: bool,
}

/// Every border of a labelled image.
#[derive(Clone, Debug)]
pub struct BorderGraph {
    /// The borders: those leaving a junction in raster order of the junction (directions
    /// +x, +y, −x, −y), then the closed ones in raster order of their first corner.
    pub borders: Vec<Border>,
    /// The label of pixels of no region (the number of regions).
    pub none: usize,
    /// The label of the pixels beyond the image.
    pub outside: usize,
}

/// Unit steps of the four crack directions: +x, +y, −x, −y.
const STEPS: [(i64, i64); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];

impl BorderGraph {
    /// The borders of a `width` × `height` image whose pixel `(x, y)` has palette index
    /// `label(x, y)` (`None`: no region) among `regions` indices.
    pub fn new(
        width: u32,
        height: u32,
        regions: usize,
        label: impl Fn(i64, i64) -> Option<usize>,
    ) -> BorderGraph {
        let (w, h) = (i64::from(width), i64::from(height));
        let none = regions;
        let outside = regions + 1;
        let lab = |x: i64, y: i64| {
            if x < 0 || y < 0 || x >= w || y >= h {
                outside
            } else {
                label(x, y).unwrap_or(none)
            }
        };
        // The (left, right) pixels of the crack leaving corner (x, y) in direction d.
        let sides = |x: i64, y: i64, d: usize| {
            let [l, r] = crack_sides((x, y), (x + STEPS[d].0, y + STEPS[d].1));
            (l, r)
        };
        // Whether a border crack leaves (x, y) in direction d (walked that way).
        let leaves = |x: i64, y: i64, d: usize| {
            let ((lx, ly), (rx, ry)) = sides(x, y, d);
            let (l, r) = (lab(lx, ly), lab(rx, ry));
            l < r && l < none
        };
        let cols = (w + 1) as usize;
        let idx = |x: i64, y: i64| y as usize * cols + x as usize;
        let corners = cols * (h + 1) as usize;
        let mut out_dirs = vec![0u8; corners];
        let mut junction = vec![false; corners];
        for y in 0..=h {
            for x in 0..=w {
                let mut bits = 0u8;
                for d in 0..4 {
                    if leaves(x, y, d) {
                        bits |= 1 << d;
                    }
                }
                out_dirs[idx(x, y)] = bits;
                // Incoming cracks: a crack arriving from direction d leaves the neighbour
                // in the opposite direction.
                let mut degree = bits.count_ones();
                for (d, &(dx, dy)) in STEPS.iter().enumerate() {
                    if leaves(x + dx, y + dy, (d + 2) % 4) {
                        degree += 1;
                    }
                }
                let mut labels = [lab(x - 1, y - 1), lab(x, y - 1), lab(x - 1, y), lab(x, y)];
                labels.sort_unstable();
                let distinct = 1 + labels.windows(2).filter(|p| p[0] != p[1]).count();
                junction[idx(x, y)] = degree > 0 && (degree != 2 || distinct > 2);
            }
        }
        let mut visited = vec![0u8; corners];
        let mut borders = Vec::new();
        let walk = |x0: i64, y0: i64, d0: usize, visited: &mut Vec<u8>| -> Border {
            let ((lx, ly), (rx, ry)) = sides(x0, y0, d0);
            let (left, right) = (lab(lx, ly), lab(rx, ry));
            let mut pts = vec![(x0, y0)];
            let (mut x, mut y, mut d) = (x0, y0, d0);
            loop {
                visited[idx(x, y)] |= 1 << d;
                x += STEPS[d].0;
                y += STEPS[d].1;
                pts.push((x, y));
                let i = idx(x, y);
                if junction[i] || (x, y) == (x0, y0) {
                    break;
                }
                // Not a junction: one crack leaves.
                match (0..4).find(|&e| out_dirs[i] & !visited[i] & (1 << e) != 0) {
                    Some(e) => d = e,
                    None => break,
                }
            }
            let closed = !junction[idx(x0, y0)];
            Border {
                left,
                right,
                corners: pts,
                closed,
            }
        };
        for y in 0..=h {
            for x in 0..=w {
                let i = idx(x, y);
                if !junction[i] {
                    continue;
                }
                for d in 0..4 {
                    if out_dirs[i] & !visited[i] & (1 << d) != 0 {
                        let b = walk(x, y, d, &mut visited);
                        borders.push(b);
                    }
                }
            }
        }
        for y in 0..=h {
            for x in 0..=w {
                let i = idx(x, y);
                for d in 0..4 {
                    if out_dirs[i] & !visited[i] & (1 << d) != 0 {
                        let b = walk(x, y, d, &mut visited);
                        borders.push(b);
                    }
                }
            }
        }
        BorderGraph {
            borders,
            none,
            outside,
        }
    }

    /// Whether `label` is a region (not no region, not the outside).
    pub fn is_region(&self, label: usize) -> bool {
        label < self.none
    }
}

/// The pixels on both sides of the crack from `a` to `b` (4-adjacent corners): left, right.
pub(crate) fn crack_sides(a: (i64, i64), b: (i64, i64)) -> [(i64, i64); 2] {
    let (x, y) = a;
    match (b.0 - a.0, b.1 - a.1) {
        (1, 0) => [(x, y - 1), (x, y)],
        (0, 1) => [(x, y), (x - 1, y)],
        (-1, 0) => [(x - 1, y), (x - 1, y - 1)],
        _ => [(x - 1, y - 1), (x, y - 1)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(art: &str) -> BorderGraph {
        let rows: Vec<Vec<u8>> = art
            .lines()
            .map(str::trim)
            .filter(|r| !r.is_empty())
            .map(|r| r.bytes().collect())
            .collect();
        let (w, h) = (rows[0].len() as u32, rows.len() as u32);
        let n = rows
            .iter()
            .flatten()
            .filter(|&&b| b != b'.')
            .map(|&b| usize::from(b - b'0') + 1)
            .max()
            .unwrap_or(0);
        BorderGraph::new(w, h, n, |x, y| {
            let b = rows[y as usize][x as usize];
            (b != b'.').then(|| usize::from(b - b'0'))
        })
    }

    /// Every border crack is in one border, with the border's labels on its sides.
    fn check_cover(g: &BorderGraph, art: &str) {
        let rows: Vec<&[u8]> = art
            .lines()
            .map(str::trim)
            .filter(|r| !r.is_empty())
            .map(str::as_bytes)
            .collect();
        let (w, h) = (rows[0].len() as i64, rows.len() as i64);
        let lab = |x: i64, y: i64| {
            if x < 0 || y < 0 || x >= w || y >= h {
                g.outside
            } else {
                match rows[y as usize][x as usize] {
                    b'.' => g.none,
                    b => usize::from(b - b'0'),
                }
            }
        };
        let mut seen = std::collections::HashSet::new();
        for b in &g.borders {
            assert!(b.left < b.right && g.is_region(b.left));
            for p in b.corners.windows(2) {
                let [l, r] = crack_sides(p[0], p[1]);
                assert_eq!((lab(l.0, l.1), lab(r.0, r.1)), (b.left, b.right));
                let key = if p[0] < p[1] {
                    (p[0], p[1])
                } else {
                    (p[1], p[0])
                };
                assert!(seen.insert(key), "crack twice: {key:?}");
            }
        }
        // All border cracks are covered.
        let mut count = 0;
        for y in -1..=h {
            for x in -1..=w {
                for (u, v) in [(x + 1, y), (x, y + 1)] {
                    let (a, b) = (lab(x, y), lab(u, v));
                    if a != b && a.min(b) < g.none {
                        count += 1;
                    }
                }
            }
        }
        assert_eq!(seen.len(), count);
    }

    #[test]
    fn square_in_background_is_one_loop_and_the_frame() {
        let art = "0000
                   0110
                   0110
                   0000";
        let g = graph(art);
        check_cover(&g, art);
        // The island: one closed border 0|1; the frame: one closed border 0|outside.
        assert_eq!(g.borders.len(), 2);
        assert!(g.borders.iter().all(|b| b.closed));
        assert!(g.borders.iter().any(|b| (b.left, b.right) == (0, 1)));
    }

    #[test]
    fn three_regions_meet_at_junctions() {
        let art = "0011
                   0011
                   2222";
        let g = graph(art);
        check_cover(&g, art);
        // 0|1 (vertical), 0|2, 1|2, and the outside of each of the three.
        let mut pairs: Vec<(usize, usize)> = g.borders.iter().map(|b| (b.left, b.right)).collect();
        pairs.sort();
        assert_eq!(pairs, vec![(0, 1), (0, 2), (0, 4), (1, 2), (1, 4), (2, 4)]);
        assert!(g.borders.iter().all(|b| !b.closed));
    }

    #[test]
    fn saddles_transparency_and_holes() {
        let art = "01.0
                   10.1
                   2200
                   2.20";
        let g = graph(art);
        check_cover(&g, art);
    }
}
