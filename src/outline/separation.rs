//! Incremental strict linear separation of two planar point sets with integer coordinates.
//!
//! A line separates `low` from `high` strictly when some normal `n` has
//! `n·p < n·q` for every `p ∈ low`, `q ∈ high`, i.e. `n·(q − p) > 0` for every pair: each
//! pair allows an open half-circle of normals, and the normals allowed by all pairs form an
//! open arc of the circle, kept as its two bounding directions. Adding a point intersects
//! the arc with the half-circles of its new pairs; all arithmetic is on integer vectors
//! (differences of points, turned by ±90°), so the answer is exact.

/// An integer direction.
type Dir = [i64; 2];

fn cross(a: Dir, b: Dir) -> i128 {
    i128::from(a[0]) * i128::from(b[1]) - i128::from(a[1]) * i128::from(b[0])
}

fn dot(a: Dir, b: Dir) -> i128 {
    i128::from(a[0]) * i128::from(b[0]) + i128::from(a[1]) * i128::from(b[1])
}

/// The open arc of directions turning counter-clockwise (in the `x`, `y` frame) from `lo`
/// to `hi`, at most a half-circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Normals {
    /// No constraint yet.
    All,
    /// The open arc from `lo` to `hi`.
    Arc { lo: Dir, hi: Dir },
    /// No separating line.
    None,
}

/// True when `n` lies strictly inside the arc from `lo` to `hi` (at most a half-circle).
fn inside(n: Dir, lo: Dir, hi: Dir) -> bool {
    cross(lo, n) > 0 && cross(n, hi) > 0
}

/// True when `a` and `b` point the same way.
fn same(a: Dir, b: Dir) -> bool {
    cross(a, b) == 0 && dot(a, b) > 0
}

/// Two point sets, grown point by point, and whether a line still separates them strictly.
#[derive(Clone, Debug)]
pub(crate) struct Separation {
    low: Vec<Dir>,
    high: Vec<Dir>,
    normals: Normals,
}

impl Separation {
    /// Empty sets (separable).
    pub(crate) fn new() -> Separation {
        Separation {
            low: Vec::new(),
            high: Vec::new(),
            normals: Normals::All,
        }
    }

    /// True while a line separates the sets strictly.
    pub(crate) fn separable(&self) -> bool {
        self.normals != Normals::None
    }

    /// Adds a point to the low side; returns [`Separation::separable`].
    pub(crate) fn add_low(&mut self, p: Dir) -> bool {
        for i in 0..self.high.len() {
            let q = self.high[i];
            self.constrain([q[0] - p[0], q[1] - p[1]]);
        }
        self.low.push(p);
        self.separable()
    }

    /// Adds a point to the high side; returns [`Separation::separable`].
    pub(crate) fn add_high(&mut self, q: Dir) -> bool {
        for i in 0..self.low.len() {
            let p = self.low[i];
            self.constrain([q[0] - p[0], q[1] - p[1]]);
        }
        self.high.push(q);
        self.separable()
    }

    /// Keeps the normals `n` with `n·d > 0`.
    fn constrain(&mut self, d: Dir) {
        // Most pairs allow the whole arc already: an arc under a half-circle lies in the
        // half-circle of `d` when both its ends do (its normals are positive combinations
        // of `lo` and `hi`), and then nothing changes.
        if let Normals::Arc { lo, hi } = self.normals {
            if d != [0, 0] && dot(lo, d) >= 0 && dot(hi, d) >= 0 && cross(lo, hi) > 0 {
                return;
            }
        }
        // The half-circle round d, from d turned by −90° to d turned by +90°.
        let (r1, r2) = ([d[1], -d[0]], [-d[1], d[0]]);
        self.normals = match self.normals {
            Normals::None => Normals::None,
            _ if d == [0, 0] => Normals::None,
            Normals::All => Normals::Arc { lo: r1, hi: r2 },
            Normals::Arc { lo, hi } => {
                let new_lo = if inside(r1, lo, hi) {
                    Some(r1)
                } else if inside(lo, r1, r2) || same(lo, r1) {
                    Some(lo)
                } else {
                    None
                };
                let new_hi = if inside(r2, lo, hi) {
                    Some(r2)
                } else if inside(hi, r1, r2) || same(hi, r2) {
                    Some(hi)
                } else {
                    None
                };
                match (new_lo, new_hi) {
                    (Some(lo), Some(hi)) => {
                        let c = cross(lo, hi);
                        if c > 0 || (c == 0 && dot(lo, hi) < 0) {
                            Normals::Arc { lo, hi }
                        } else {
                            Normals::None
                        }
                    }
                    _ => Normals::None,
                }
            }
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Brute force: some normal among many directions separates strictly.
    fn brute(low: &[Dir], high: &[Dir]) -> bool {
        // Candidate normals: perpendiculars of all pair differences, turned slightly both
        // ways, plus the differences themselves (separating normals of finite sets lie in
        // an open arc whose bisector is a combination of these; a fine sweep suffices for
        // the small coordinates used here).
        (0..20_000).any(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 20_000.0;
            let n = (t.cos(), t.sin());
            let f = |p: &Dir| n.0 * p[0] as f64 + n.1 * p[1] as f64;
            let max_low = low.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
            let min_high = high.iter().map(f).fold(f64::INFINITY, f64::min);
            max_low < min_high - 1e-9
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// The incremental answer agrees with a sweep of directions on small random sets.
        #[test]
        fn agrees_with_a_sweep(
            points in prop::collection::vec(((-6i64..6, -6i64..6), any::<bool>()), 1..9)
        ) {
            let mut s = Separation::new();
            let (mut low, mut high) = (Vec::new(), Vec::new());
            for ((x, y), is_low) in points {
                let p = [x, y];
                if low.contains(&p) || high.contains(&p) {
                    continue;
                }
                if is_low {
                    s.add_low(p);
                    low.push(p);
                } else {
                    s.add_high(p);
                    high.push(p);
                }
                prop_assert_eq!(s.separable(), brute(&low, &high), "{:?} {:?}", low, high);
            }
        }
    }

    #[test]
    fn collinear_and_crossing() {
        let mut s = Separation::new();
        assert!(s.add_low([0, 0]));
        assert!(s.add_low([2, 0]));
        assert!(s.add_high([1, 1]));
        assert!(s.add_high([5, 1]));
        // A low point above the high ones' line through (1, 1)…(5, 1) but separable still.
        assert!(s.add_low([10, 0]));
        // Now one between the high points: no line.
        assert!(!s.add_low([3, 1]));
    }
}
