//! The fewest-vertex polygon within the border band: the first step of a smooth outline.
//!
//! A contour's crack polygon `v_0 … v_{m−1}` (pixel corners, unit steps) winds round
//! exactly the pixels it encloses. A smooth outline may differ from it only at *free* pixels
//! (within ν of the border, see [`crate::bitmap::Band`]); the other pixels near the contour
//! are *constraints*, each labelled with the side of the contour it lies on (inside the
//! crack polygon or outside).
//!
//! # Which edges are allowed
//! The polygon's vertices are crack corners. An edge `v_i → v_j` replaces the crack path
//! `v_i … v_j`; it is allowed when
//! - every crack corner between lies within a distance `limit` (a little over ν) of its
//!   line (the outline stays near the border, so thin strokes do not collapse), and
//! - every constraint pixel whose centre projects inside the edge and lies within `limit`
//!   of its line is on its own side of it (the region between the edge and the crack path,
//!   which lies within `limit` of the line, holds no constraint pixel),
//!
//! all in exact integer arithmetic (corners and doubled centres). Thin parts, where pixels of
//! the far side of the contour come within ν, only forbid more edges. Each vertex's *reach*
//! is its farthest allowed edge; the polygon follows reaches from the start that needs the
//! fewest vertices (the reach grows along the contour, so greedy jumps are optimal from a
//! given start).

use super::band_cells::Cells;
use kurbo::Point;

/// An integer point (pixel corner, or doubled centre).
type IPoint = [i64; 2];

fn cross(a: IPoint, b: IPoint) -> i128 {
    i128::from(a[0]) * i128::from(b[1]) - i128::from(a[1]) * i128::from(b[0])
}

fn dot(a: IPoint, b: IPoint) -> i128 {
    i128::from(a[0]) * i128::from(b[0]) + i128::from(a[1]) * i128::from(b[1])
}

/// The constraint pixels near each crack corner, and the test of an edge.
pub(crate) struct Reach {
    /// Crack corners, doubled.
    corners: Vec<IPoint>,
    /// Per corner, the range of `attached` near it.
    starts: Vec<u32>,
    /// Doubled centres of constraint pixels and the sign `cross(edge, centre − start)`
    /// must have.
    attached: Vec<(IPoint, i8)>,
    /// How far from an edge the corners it replaces may lie.
    limit: f64,
}

impl Reach {
    /// The constraints of the closed crack polygon `corners` (integer points) with the
    /// labels of `cells`, for edges within `limit` of the corners they replace.
    pub(crate) fn new(corners: &[Point], cells: &Cells, limit: f64) -> Reach {
        let r = limit.ceil() as i64 + 1;
        let dbl: Vec<IPoint> = corners
            .iter()
            .map(|p| [2 * p.x.round() as i64, 2 * p.y.round() as i64])
            .collect();
        let mut starts = Vec::with_capacity(corners.len() + 1);
        let mut attached = Vec::new();
        for c in &dbl {
            starts.push(attached.len() as u32);
            let (cx, cy) = (c[0] / 2, c[1] / 2);
            for y in cy - r..cy + r {
                for x in cx - r..cx + r {
                    if let Some(sign) = cells.required_sign(x, y) {
                        attached.push(([2 * x + 1, 2 * y + 1], sign));
                    }
                }
            }
        }
        starts.push(attached.len() as u32);
        Reach {
            corners: dbl,
            starts,
            attached,
            limit,
        }
    }

    fn corner(&self, k: usize) -> IPoint {
        self.corners[k % self.corners.len()]
    }

    /// True when the edge from corner `i` to corner `j` (`i < j < i + m`, indices taken
    /// cyclically) is allowed (see the module documentation).
    pub(crate) fn allowed(&self, i: usize, j: usize) -> bool {
        let m = self.corners.len();
        let a = self.corner(i);
        let b = self.corner(j);
        let d = [b[0] - a[0], b[1] - a[1]];
        let l2 = dot(d, d);
        if l2 == 0 {
            return false;
        }
        // Doubled coordinates: distances are doubled too.
        let lim2 = (2.0 * self.limit).powi(2) * l2 as f64;
        for k in i + 1..j {
            let v = self.corner(k);
            let c = cross(d, [v[0] - a[0], v[1] - a[1]]) as f64;
            if c * c > lim2 {
                return false;
            }
        }
        for k in i..=j {
            let k = k % m;
            for &(c, sign) in &self.attached[self.starts[k] as usize..self.starts[k + 1] as usize] {
                let w = [c[0] - a[0], c[1] - a[1]];
                let t = dot(w, d);
                if t <= 0 || t >= l2 {
                    continue;
                }
                let cr = cross(d, w);
                let crf = cr as f64;
                if crf * crf > lim2 {
                    continue;
                }
                if cr == 0 || (cr > 0) != (sign > 0) {
                    return false;
                }
            }
        }
        true
    }

    /// The reach of every corner: the farthest corner (as an index `> i`, at most
    /// `i + max_jump`) it has an allowed edge to.
    fn reaches(&self, max_jump: usize) -> Vec<usize> {
        let m = self.corners.len();
        let mut reach = vec![0usize; m];
        let mut prev = 1usize;
        for i in 0..m {
            let mut j = prev.max(i + 1).min(i + max_jump);
            while j > i + 1 && !self.allowed(i, j) {
                j -= 1;
            }
            while j < i + max_jump && self.allowed(i, j + 1) {
                j += 1;
            }
            reach[i] = j;
            prev = j;
        }
        reach
    }

    /// The polygon's vertices (corner indices, ascending, the first below `m`) with the
    /// fewest vertices among the greedy polygons; at least three when the crack polygon has
    /// three corners or more.
    pub(crate) fn fewest_vertices(&self) -> Vec<usize> {
        let m = self.corners.len();
        if m < 3 {
            return (0..m).collect();
        }
        let max_jump = (m / 3).max(1);
        let reach = self.reaches(max_jump);
        let abs_reach = |p: usize| reach[p % m] + (p - p % m);
        let walk = |s: usize, best: usize| -> Option<Vec<usize>> {
            let mut verts = vec![s];
            let mut pos = s;
            loop {
                let r = abs_reach(pos);
                let next = if r >= s + m {
                    if self.allowed(pos, s + m) {
                        return Some(verts);
                    }
                    r.min(s + m - 1)
                } else {
                    r
                };
                if next <= pos || verts.len() >= best {
                    return None;
                }
                verts.push(next);
                pos = next;
            }
        };
        let mut best: Option<Vec<usize>> = None;
        let first = reach[0].min(m - 1);
        for s in 0..=first {
            let limit = best.as_ref().map_or(m + 1, |b| b.len());
            if let Some(v) = walk(s, limit) {
                best = Some(v);
            }
        }
        best.unwrap_or_else(|| (0..m).collect())
    }
}
