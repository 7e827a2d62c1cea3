//! Incremental strict linear separation of two planar point sets with integer coordinates.
//!
//! A line separates `low` from `high` strictly when some normal `n` has
//! `n·p < n·q` for every `p ∈ low`, `q ∈ high`, i.e. `n·(q − p) > 0` for every pair: each
//! pair allows an open half-circle of normals, and the normals allowed by all pairs form an
//! open arc of the circle, kept as its two bounding directions. Adding a point intersects
//! the arc with the half-circles of its new pairs — only those with the vertices of the
//! other set's convex hull, and none for a point inside its own set's hull; all arithmetic
//! is on integer vectors (differences of points, turned by ±90°), so the answer is exact.
//!
//! Points are kept relative to the first one added, within [`MAX_OFFSET`] of it: every
//! vector is then a difference of two such points (at most `2^29` per coordinate), and
//! every product of two, and a sum of two products, stays below `2^59`, exact in `i64`.

/// An integer direction.
type Dir = [i64; 2];

/// Largest coordinate of a point relative to the first point of a [`Separation`]: a point
/// farther away makes the sets count as not separable (the conservative answer: the
/// callers' segments end before it; theirs span at most a few hundred pixels, in 64ths).
const MAX_OFFSET: i64 = 1 << 28;

fn cross(a: Dir, b: Dir) -> i64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: Dir, b: Dir) -> i64 {
    a[0] * b[0] + a[1] * b[1]
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

/// The convex hull of a growing point set: its vertices counter-clockwise, no three on a
/// line (one or two vertices while the points are one point or on one line).
#[derive(Debug, Default)]
struct Hull {
    vertices: Vec<Dir>,
    /// Scratch for rebuilding.
    sorted: Vec<Dir>,
}

/// A copy has the vertices only (the scratch is cleared before every use); `clone_from`
/// keeps the target's buffers.
impl Clone for Hull {
    fn clone(&self) -> Hull {
        Hull {
            vertices: self.vertices.clone(),
            sorted: Vec::new(),
        }
    }

    fn clone_from(&mut self, source: &Hull) {
        self.vertices.clone_from(&source.vertices);
    }
}

fn sub(a: Dir, b: Dir) -> Dir {
    [a[0] - b[0], a[1] - b[1]]
}

impl Hull {
    /// Adds `p`; returns false (and changes nothing) when `p` lies in the closed hull
    /// already, border included. Linear in the number of vertices (rebuilt from scratch
    /// past 128, one bit per edge).
    fn add(&mut self, p: Dir) -> bool {
        let v = &mut self.vertices;
        let k = v.len();
        if k <= 2 || k > 128 {
            let inside = match k {
                0 => false,
                1 => v[0] == p,
                2 => {
                    cross(sub(v[1], v[0]), sub(p, v[0])) == 0
                        && dot(sub(p, v[0]), sub(p, v[1])) <= 0
                }
                _ => (0..k).all(|i| cross(sub(v[(i + 1) % k], v[i]), sub(p, v[i])) >= 0),
            };
            if !inside {
                match k {
                    0 | 1 => v.push(p),
                    2 => {
                        let turn = cross(sub(v[1], v[0]), sub(p, v[0]));
                        if turn > 0 {
                            v.push(p);
                        } else if turn < 0 {
                            v.insert(1, p);
                        } else if dot(sub(p, v[0]), sub(v[1], v[0])) < 0 {
                            // On the line beyond v[0].
                            v[0] = p;
                        } else {
                            v[1] = p;
                        }
                    }
                    _ => self.rebuild(p),
                }
            }
            return !inside;
        }
        // Edge i (v[i] → v[i+1]) sees p when p is strictly on its right; `sees` also marks
        // the edges p lies on the line of.
        // (Consecutive pairs without a division per edge: the last edge closes the hull.)
        let mut sees = 0u128;
        let mut outside = false;
        for i in 0..k {
            let (a, b) = (v[i], if i + 1 < k { v[i + 1] } else { v[0] });
            let s = cross(sub(b, a), sub(p, a));
            outside |= s < 0;
            if s <= 0 {
                sees |= 1 << i;
            }
        }
        if !outside {
            return false;
        }
        // The edges that see p (with those p lies on the line of, next to them) form one
        // chain: the vertices inside it go, and p follows the chain's first vertex.
        let next = &mut self.sorted;
        next.clear();
        for j in 0..k {
            let before = if j == 0 { k - 1 } else { j - 1 };
            if !(sees >> before & 1 == 1 && sees >> j & 1 == 1) {
                next.push(v[j]);
                if sees >> j & 1 == 1 {
                    next.push(p);
                }
            }
        }
        std::mem::swap(v, next);
        true
    }

    /// The hull of the vertices and `p`, by Andrew's monotone chain.
    fn rebuild(&mut self, p: Dir) {
        let sorted = &mut self.sorted;
        sorted.clear();
        sorted.extend_from_slice(&self.vertices);
        sorted.push(p);
        sorted.sort_unstable();
        sorted.dedup();
        let hull = &mut self.vertices;
        hull.clear();
        if sorted.len() <= 2 {
            hull.extend_from_slice(sorted);
            return;
        }
        // Lower chain left to right, then upper chain right to left; each chain's last
        // point is the next one's first.
        let m = sorted.len();
        for pass in 0..2 {
            let floor = hull.len();
            for k in 0..m {
                let q = if pass == 0 {
                    sorted[k]
                } else {
                    sorted[m - 1 - k]
                };
                while hull.len() >= floor + 2 {
                    let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                    if cross(sub(b, a), sub(q, a)) > 0 {
                        break;
                    }
                    hull.pop();
                }
                hull.push(q);
            }
            hull.pop();
        }
    }
}

/// Two point sets, grown point by point, and whether a line still separates them strictly.
///
/// Only the vertices of the two convex hulls constrain the normals: a point of a set is a
/// convex combination `Σ λᵢ vᵢ` of its hull's vertices, so `n·(q − p) > 0` for every
/// vertex pair gives it for every pair. A point added inside its set's hull adds nothing,
/// and a point added outside is paired with the other hull's vertices only; this keeps
/// growing a segment linear in its length (pairing every point with every point of the
/// other side was the polygon's largest cost).
#[derive(Debug)]
pub(crate) struct Separation {
    low: Hull,
    high: Hull,
    normals: Normals,
    /// The first point added: the others are kept relative to it.
    origin: Option<Dir>,
}

/// `clone_from` keeps the target's buffers (a trial copy per step costs no allocation).
impl Clone for Separation {
    fn clone(&self) -> Separation {
        Separation {
            low: self.low.clone(),
            high: self.high.clone(),
            normals: self.normals,
            origin: self.origin,
        }
    }

    fn clone_from(&mut self, source: &Separation) {
        self.low.clone_from(&source.low);
        self.high.clone_from(&source.high);
        self.normals = source.normals;
        self.origin = source.origin;
    }
}

impl Separation {
    /// Empty sets (separable).
    pub(crate) fn new() -> Separation {
        Separation {
            low: Hull::default(),
            high: Hull::default(),
            normals: Normals::All,
            origin: None,
        }
    }

    /// Empties both sets (separable again), keeping the hulls' buffers.
    pub(crate) fn clear(&mut self) {
        for h in [&mut self.low, &mut self.high] {
            h.vertices.clear();
            h.sorted.clear();
        }
        self.normals = Normals::All;
        self.origin = None;
    }

    /// True while a line separates the sets strictly.
    pub(crate) fn separable(&self) -> bool {
        self.normals != Normals::None
    }

    /// A normal `n` of a separating line (`n·p < n·q` for every low `p` and high `q`), or
    /// `None` when no line separates the sets.
    pub(crate) fn normal(&self) -> Option<Dir> {
        match self.normals {
            Normals::None => None,
            Normals::All => Some([1, 0]),
            Normals::Arc { lo, hi } if cross(lo, hi) > 0 => Some([lo[0] + hi[0], lo[1] + hi[1]]),
            // A half-circle: its middle, `lo` turned counter-clockwise.
            Normals::Arc { lo, .. } => Some([-lo[1], lo[0]]),
        }
    }

    /// `p` relative to the first point added (`p` itself becomes it when it is the first),
    /// or `None` (and the sets not separable) when farther than [`MAX_OFFSET`].
    fn relative(&mut self, p: Dir) -> Option<Dir> {
        let o = *self.origin.get_or_insert(p);
        let r = [p[0].checked_sub(o[0]), p[1].checked_sub(o[1])];
        match r {
            [Some(x), Some(y)] if x.abs() <= MAX_OFFSET && y.abs() <= MAX_OFFSET => Some([x, y]),
            _ => {
                self.normals = Normals::None;
                None
            }
        }
    }

    /// Adds a point to the low side; returns [`Separation::separable`].
    pub(crate) fn add_low(&mut self, p: Dir) -> bool {
        if !self.separable() {
            return false;
        }
        let Some(p) = self.relative(p) else {
            return false;
        };
        if self.low.add(p) {
            for &q in &self.high.vertices {
                self.normals = constrain(self.normals, sub(q, p));
            }
        }
        self.separable()
    }

    /// Adds a point to the high side; returns [`Separation::separable`].
    pub(crate) fn add_high(&mut self, q: Dir) -> bool {
        if !self.separable() {
            return false;
        }
        let Some(q) = self.relative(q) else {
            return false;
        };
        if self.high.add(q) {
            for &p in &self.low.vertices {
                self.normals = constrain(self.normals, sub(q, p));
            }
        }
        self.separable()
    }
}

/// The normals `n` of `normals` with `n·d > 0`.
fn constrain(normals: Normals, d: Dir) -> Normals {
    // Most pairs allow the whole arc already: an arc under a half-circle lies in the
    // half-circle of `d` when both its ends do (its normals are positive combinations
    // of `lo` and `hi`), and then nothing changes.
    if let Normals::Arc { lo, hi } = normals {
        if d != [0, 0] && dot(lo, d) >= 0 && dot(hi, d) >= 0 && cross(lo, hi) > 0 {
            return normals;
        }
    }
    // The half-circle round d, from d turned by −90° to d turned by +90°.
    let (r1, r2) = ([d[1], -d[0]], [-d[1], d[0]]);
    match normals {
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
            let points = points.into_iter().map(|((x, y), is_low)| ([x, y], is_low));
            // Repeated points are left out.
            replay(points, true, |s, low, high| {
                prop_assert_eq!(s.separable(), brute(low, high), "{:?} {:?}", low, high);
                Ok(())
            })?;
        }
    }

    /// Adds `points` (each to the low side when its flag says so) one by one, leaving out
    /// repeated points when `skip_repeats`, and calls `check` with the separation and the
    /// sets after each. The separation is one used before and cleared (as
    /// [`super::super::stretch::Stretcher::polygon`] reuses one), which must answer as a new
    /// one.
    fn replay(
        points: impl IntoIterator<Item = (Dir, bool)>,
        skip_repeats: bool,
        mut check: impl FnMut(&Separation, &[Dir], &[Dir]) -> Result<(), TestCaseError>,
    ) -> Result<(), TestCaseError> {
        let mut s = Separation::new();
        for p in [[0, 0], [3, 1], [-2, 5]] {
            s.add_low(p);
            s.add_high([p[0] + 1, p[1]]);
        }
        s.add_high([0, 0]);
        prop_assert!(!s.separable());
        s.clear();
        let (mut low, mut high) = (Vec::new(), Vec::new());
        for (p, is_low) in points {
            if skip_repeats && (low.contains(&p) || high.contains(&p)) {
                continue;
            }
            if is_low {
                s.add_low(p);
                low.push(p);
            } else {
                s.add_high(p);
                high.push(p);
            }
            check(&s, &low, &high)?;
        }
        Ok(())
    }

    /// Every pair constrains: the definition, quadratic.
    fn all_pairs(low: &[Dir], high: &[Dir]) -> bool {
        let mut n = Normals::All;
        for p in low {
            for q in high {
                n = constrain(n, sub(*q, *p));
            }
        }
        n != Normals::None
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// Pairing the hulls' vertices only answers as pairing every point, on sets large
        /// enough for points inside the hulls, on their borders and on lines.
        #[test]
        fn hull_vertices_answer_as_all_pairs(
            points in prop::collection::vec(((-5i64..5, -3i64..3), any::<bool>()), 1..40)
        ) {
            // A point in both sets is allowed: no line separates them then.
            let points = points.into_iter().map(|((x, y), is_low)| ([x + y, y], is_low));
            replay(points, false, |s, low, high| {
                prop_assert_eq!(s.separable(), all_pairs(low, high), "{:?} {:?}", low, high);
                Ok(())
            })?;
        }

        /// Far from the origin the answers are those of the same points near it (the
        /// separation keeps points relative to its first one), and the normal found is the
        /// same.
        #[test]
        fn moved_far_away_answers_the_same(
            points in prop::collection::vec(((-6i64..6, -6i64..6), any::<bool>()), 1..12),
            far in (-(1i64 << 40)..(1i64 << 40), -(1i64 << 40)..(1i64 << 40)),
        ) {
            let (mut near, mut moved) = (Separation::new(), Separation::new());
            for ((x, y), is_low) in points {
                let (p, q) = ([x, y], [x + far.0, y + far.1]);
                let (a, b) = if is_low {
                    (near.add_low(p), moved.add_low(q))
                } else {
                    (near.add_high(p), moved.add_high(q))
                };
                prop_assert_eq!(a, b);
                prop_assert_eq!(near.normal(), moved.normal());
            }
        }

        /// The hull holds exactly the points of the set's convex hull.
        #[test]
        fn hull_contains_its_points_only(
            points in prop::collection::vec((-6i64..6, -6i64..6), 1..30),
            probe in (-7i64..7, -7i64..7),
        ) {
            let mut h = Hull::default();
            let pts: Vec<Dir> = points.iter().map(|&(x, y)| [x, y]).collect();
            for (i, &p) in pts.iter().enumerate() {
                // Added iff outside the hull of the points before it.
                prop_assert_eq!(h.add(p), i == 0 || all_pairs(&pts[..i], &[p]));
                prop_assert!(!h.add(p));
            }
            // A probe is in the hull iff no line separates it strictly from the points.
            let q = [probe.0, probe.1];
            prop_assert_eq!(!h.clone().add(q), !all_pairs(&pts, &[q]));
        }
    }

    #[test]
    fn a_point_beyond_the_offset_limit_is_not_separable() {
        let mut s = Separation::new();
        assert!(s.add_low([i64::MAX, 0]) && s.add_high([i64::MAX, MAX_OFFSET]));
        assert!(!s.add_high([i64::MIN, 0]));
        let mut s = Separation::new();
        assert!(s.add_low([0, 0]) && !s.add_high([0, MAX_OFFSET + 1]));
        assert!(!s.separable());
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
