//! Support points of `D = (S⁺ − S) ∪ (S − S⁻)`, computed from the three sets directly.
//!
//! The support point of `D` in direction `−x` minimizes `x·d`. Since
//! `min_{d ∈ S⁺−S} x·d = min_{S⁺} x·F − max_{S} x·F` and
//! `min_{d ∈ S−S⁻} x·d = min_{S} x·F − max_{S⁻} x·F`, one pass over each set suffices:
//! `O(|S| + |S⁺| + |S⁻|)` instead of `O(|S|·(|S⁺| + |S⁻|))` for the explicit difference set.

use super::conditioning::LinearMap;
use super::lifted::LiftedSet;
use super::scalar::Scalar;
use super::simplex::Vertex;
use super::Side;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};

/// Where a support point comes from: `d = F(outlier) − F(inlier)` for an upper outlier
/// (`S⁺ − S`), `d = F(inlier) − F(outlier)` for a lower one (`S − S⁻`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Tag {
    /// Index in the inliers (or in an explicit point list).
    pub inlier: u32,
    /// Index in the outliers of `side`.
    pub outlier: u32,
    /// Which outlier set.
    pub side: Side,
}

impl Tag {
    /// The tag of point `i` of an explicit list.
    pub fn explicit(i: usize) -> Tag {
        Tag {
            inlier: i as u32,
            outlier: u32::MAX,
            side: Side::Upper,
        }
    }
}

/// The three sets of a recognition problem.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sets<'a> {
    /// `S`.
    pub inliers: &'a LiftedSet,
    /// `S⁺`: must lie strictly above the layer.
    pub upper: &'a LiftedSet,
    /// `S⁻`: must lie strictly below the layer.
    pub lower: &'a LiftedSet,
}

impl Sets<'_> {
    /// The exact difference vector named by `tag`.
    pub fn difference(&self, tag: &Tag) -> Vec<i64> {
        let mut d = Vec::new();
        self.difference_into(tag, &mut d);
        d
    }

    /// The exact difference vector named by `tag`, into `out` (its allocation reused).
    pub fn difference_into(&self, tag: &Tag, out: &mut Vec<i64>) {
        let (minuend, subtrahend) = self.pair(tag);
        out.clear();
        out.extend(minuend.iter().zip(subtrahend).map(|(a, b)| a - b));
    }

    /// The liftings `(a, b)` whose difference `a − b` is the point of `D` named by `tag`.
    fn pair(&self, tag: &Tag) -> (&[i64], &[i64]) {
        let s = self.inliers.lifted(tag.inlier as usize);
        match tag.side {
            Side::Upper => (self.upper.lifted(tag.outlier as usize), s),
            Side::Lower => (s, self.lower.lifted(tag.outlier as usize)),
        }
    }

    /// True when `D` is empty.
    pub fn is_empty(&self) -> bool {
        self.inliers.is_empty() || (self.upper.is_empty() && self.lower.is_empty())
    }
}

/// A source of support points: `argmin_{d ∈ D} x·d`.
pub(crate) trait SupportMap<T> {
    /// Dimension of the points of `D`.
    fn dim(&self) -> usize;
    /// The support point of `D` in direction `−x`, or `None` if `D` is empty; `buf` may
    /// hold its coordinates (a buffer of the caller's simplex, see [`Simplex::buffer`]).
    ///
    /// [`Simplex::buffer`]: super::simplex::Simplex::buffer
    fn support_point(&mut self, x: &[T], buf: Vec<T>) -> Option<Vertex<T>>;
    /// The vertex named by `tag` (to rebuild a warm-start simplex).
    fn vertex(&self, tag: &Tag) -> Vertex<T>;
}

/// Index and value of the smallest and of the largest `y·F(p)` over a set (`f64`).
///
/// The liftings of the built-in models (without the constant: line 2, circle 3, conic 5,
/// cubic 9, poly:4 to poly:6 14, 20 and 27 numbers) run with the row length known at
/// compile time: the same products summed in the same order, but unrolled (this loop is the
/// support function, the recognizer's innermost work).
#[inline]
fn float_extremes(set: &LiftedSet, y: &[f64]) -> Option<((usize, f64), (usize, f64))> {
    match if set.dim() == y.len() { y.len() } else { 0 } {
        2 => fixed_extremes::<2>(set, y),
        3 => fixed_extremes::<3>(set, y),
        5 => fixed_extremes::<5>(set, y),
        9 => fixed_extremes::<9>(set, y),
        14 => fixed_extremes::<14>(set, y),
        20 => fixed_extremes::<20>(set, y),
        27 => fixed_extremes::<27>(set, y),
        _ => extremes_by(set.float_rows(), |row: &[f64]| {
            row.iter().zip(y).map(|(a, b)| a * b).sum()
        }),
    }
}

/// [`float_extremes`] for rows of `D` numbers.
#[inline]
fn fixed_extremes<const D: usize>(
    set: &LiftedSet,
    y: &[f64],
) -> Option<((usize, f64), (usize, f64))> {
    let y: &[f64; D] = y.try_into().ok()?;
    let (rows, _) = set.float_values().as_chunks::<D>();
    extremes_by(rows.iter(), |row: &[f64; D]| {
        // Left to right, as `Iterator::sum` adds.
        let mut v = -0.0;
        for k in 0..D {
            v += row[k] * y[k];
        }
        v
    })
}

/// Index and value of the smallest (`MAX` false) or of the largest `y·F(p)` over a set
/// (with [`float_extremes`]' sums), the first of equal ones: all an upper set (its smallest)
/// or a lower set (its largest) gives a support point.
#[inline]
fn float_extreme<const MAX: bool>(set: &LiftedSet, y: &[f64]) -> Option<(usize, f64)> {
    match if set.dim() == y.len() { y.len() } else { 0 } {
        2 => fixed_extreme::<2, MAX>(set, y),
        3 => fixed_extreme::<3, MAX>(set, y),
        5 => fixed_extreme::<5, MAX>(set, y),
        9 => fixed_extreme::<9, MAX>(set, y),
        14 => fixed_extreme::<14, MAX>(set, y),
        20 => fixed_extreme::<20, MAX>(set, y),
        27 => fixed_extreme::<27, MAX>(set, y),
        _ => float_extremes(set, y).map(|(min, max)| if MAX { max } else { min }),
    }
}

/// [`fixed_extremes`]' smallest (`MAX` false) or largest value alone.
#[inline]
fn fixed_extreme<const D: usize, const MAX: bool>(
    set: &LiftedSet,
    y: &[f64],
) -> Option<(usize, f64)> {
    let y: &[f64; D] = y.try_into().ok()?;
    let (rows, _) = set.float_values().as_chunks::<D>();
    let mut best = (
        usize::MAX,
        if MAX {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        },
    );
    for (i, row) in rows.iter().enumerate() {
        let mut v = -0.0;
        for k in 0..D {
            v += row[k] * y[k];
        }
        if (MAX && v > best.1) || (!MAX && v < best.1) {
            best = (i, v);
        }
    }
    (best.0 != usize::MAX).then_some(best)
}

/// Index and value of the smallest and of the largest `value(row)` over `rows` (the first
/// of equal ones); `None` without rows.
#[inline(always)]
fn extremes_by<R>(
    rows: impl Iterator<Item = R>,
    value: impl Fn(R) -> f64,
) -> Option<((usize, f64), (usize, f64))> {
    let mut min = (usize::MAX, f64::INFINITY);
    let mut max = (usize::MAX, f64::NEG_INFINITY);
    for (i, row) in rows.enumerate() {
        let v = value(row);
        if v < min.1 {
            min = (i, v);
        }
        if v > max.1 {
            max = (i, v);
        }
    }
    (min.0 != usize::MAX).then_some((min, max))
}

/// Chooses the smaller of the two candidate support points, from the inliers' extremes, the
/// upper set's least value and the lower set's largest.
fn pick<V: PartialOrd + Clone>(
    inl: Option<((usize, V), (usize, V))>,
    upper_min: Option<(usize, V)>,
    lower_max: Option<(usize, V)>,
    sub: impl Fn(&V, &V) -> V,
) -> Option<Tag> {
    let ((imin, vmin), (imax, vmax)) = inl?;
    let a = upper_min.map(|(j, umin)| (sub(&umin, &vmax), imax, j, Side::Upper));
    let b = lower_max.map(|(j, lmax)| (sub(&vmin, &lmax), imin, j, Side::Lower));
    let best = match (a, b) {
        (Some(a), Some(b)) => {
            if b.0 < a.0 {
                b
            } else {
                a
            }
        }
        (Some(a), None) => a,
        (None, Some(b)) => b,
        (None, None) => return None,
    };
    Some(Tag {
        inlier: best.1 as u32,
        outlier: best.2 as u32,
        side: best.3,
    })
}

/// Support points in `f64`, in coordinates mapped by an invertible linear map `T`
/// (`d' = T d`, see [`LinearMap`]): separation is invariant under `T`, chosen to make the
/// closest-point solves well conditioned.
pub(crate) struct FloatSupport<'a> {
    /// The problem.
    pub sets: Sets<'a>,
    /// The map `T`.
    pub map: &'a LinearMap,
    /// Scratch: the direction `Tᵀx` in lifted coordinates.
    pub y: &'a mut Vec<f64>,
}

impl FloatSupport<'_> {
    /// The point of `map·D` named by `tag`, into `out`'s buffer.
    pub fn point_into(&self, tag: &Tag, out: &mut Vec<f64>) {
        let (a, b) = self.sets.pair(tag);
        self.map.apply_with_into(|j| a[j] - b[j], out);
    }
}

impl SupportMap<f64> for FloatSupport<'_> {
    fn dim(&self) -> usize {
        self.map.dim()
    }

    fn support_point(&mut self, x: &[f64], mut buf: Vec<f64>) -> Option<Vertex<f64>> {
        self.map.pull_back_into(x, self.y);
        let inl = float_extremes(self.sets.inliers, self.y);
        let up = float_extreme::<false>(self.sets.upper, self.y);
        let lo = float_extreme::<true>(self.sets.lower, self.y);
        let tag = pick(inl, up, lo, |a, b| a - b)?;
        self.point_into(&tag, &mut buf);
        Some(Vertex { point: buf, tag })
    }

    fn vertex(&self, tag: &Tag) -> Vertex<f64> {
        let mut point = Vec::new();
        self.point_into(tag, &mut point);
        Vertex { point, tag: *tag }
    }
}

/// `x` multiplied by the least common multiple of its denominators: an integer vector with
/// the same direction.
pub(crate) fn integer_direction(x: &[BigRational]) -> Vec<BigInt> {
    let mut l = BigInt::one();
    for v in x {
        let d = v.denom();
        l = num_integer_lcm(&l, d);
    }
    x.iter()
        .map(|v| (v * BigRational::from_integer(l.clone())).to_integer())
        .collect()
}

fn num_integer_lcm(a: &BigInt, b: &BigInt) -> BigInt {
    use num_integer::Integer;
    a.lcm(b)
}

fn big_extremes(set: &LiftedSet, x: &[BigInt]) -> Option<((usize, BigInt), (usize, BigInt))> {
    // Floating-point filter: with x̃ = x / 2^s rounded to f64 (relative error 2^-53 per
    // coordinate), every computed x̃·F(p) is within e(p) = 2^-48 · n · Σ|x̃_k F_k(p)| (+ a
    // tiny absolute term) of the true scaled value. Only the points whose interval can reach
    // the extreme are evaluated exactly, in big integers.
    let bits = x.iter().map(|v| v.bits()).max().unwrap_or(0);
    let shift = bits.saturating_sub(60);
    let xf: Vec<f64> = x
        .iter()
        .map(|v| (v >> shift as usize).to_f64().unwrap_or(0.0))
        .collect();
    let n = x.len().max(1) as f64;
    let rel = n * (-48.0f64).exp2();
    let mut approx: Vec<(f64, f64)> = Vec::with_capacity(set.len());
    for row in set.float_rows() {
        let (mut v, mut a) = (0.0f64, 0.0f64);
        for (f, xk) in row.iter().zip(&xf) {
            v += f * xk;
            a += (f * xk).abs();
        }
        approx.push((v, rel * a + 1e-300 + 1.0));
    }
    if approx.is_empty() {
        return None;
    }
    // The shift truncated x by less than one unit per coordinate: account for it.
    let trunc: Vec<f64> = set
        .float_rows()
        .map(|row| row.iter().map(|f| f.abs()).sum::<f64>())
        .collect();
    let err = |i: usize| approx[i].1 + trunc[i];
    let lo_bound = (0..approx.len())
        .map(|i| approx[i].0 + err(i))
        .fold(f64::INFINITY, f64::min);
    let hi_bound = (0..approx.len())
        .map(|i| approx[i].0 - err(i))
        .fold(f64::NEG_INFINITY, f64::max);
    let exact = |i: usize| {
        set.lifted(i)
            .iter()
            .zip(x)
            .fold(BigInt::zero(), |s, (&a, b)| s + b * a)
    };
    let mut min: Option<(usize, BigInt)> = None;
    let mut max: Option<(usize, BigInt)> = None;
    for i in 0..approx.len() {
        let near_min = approx[i].0 - err(i) <= lo_bound;
        let near_max = approx[i].0 + err(i) >= hi_bound;
        if !(near_min || near_max) {
            continue;
        }
        let v = exact(i);
        if near_min && min.as_ref().is_none_or(|m| v < m.1) {
            min = Some((i, v.clone()));
        }
        if near_max && max.as_ref().is_none_or(|m| v > m.1) {
            max = Some((i, v));
        }
    }
    Some((min?, max?))
}

/// Extremes of `a·F` over a set in overflow-checked `i128`: `None` on overflow,
/// `Some(None)` for an empty set.
#[allow(clippy::type_complexity)]
fn i128_extremes(set: &LiftedSet, a: &[i64]) -> Option<Option<((usize, i128), (usize, i128))>> {
    let mut out: Option<((usize, i128), (usize, i128))> = None;
    for (i, row) in set.lifted_rows().enumerate() {
        let v = super::exact::dot_i128(a, row)?;
        // Bounded so that any difference of two values fits as well.
        if v.unsigned_abs() >= 1u128 << 125 {
            return None;
        }
        out = Some(match out {
            None => ((i, v), (i, v)),
            Some((min, max)) => (
                if v < min.1 { (i, v) } else { min },
                if v > max.1 { (i, v) } else { max },
            ),
        });
    }
    Some(out)
}

/// Exact support points, on unscaled integer data.
pub(crate) struct ExactSupport<'a> {
    /// The problem.
    pub sets: Sets<'a>,
}

impl SupportMap<BigRational> for ExactSupport<'_> {
    fn dim(&self) -> usize {
        self.sets.inliers.lifted(0).len()
    }

    fn support_point(
        &mut self,
        x: &[BigRational],
        _buf: Vec<BigRational>,
    ) -> Option<Vertex<BigRational>> {
        let xi = integer_direction(x);
        // Fast path: the reduced direction fits in i64 and no product overflows i128.
        let g = xi
            .iter()
            .fold(BigInt::zero(), |g, v| num_integer::Integer::gcd(&g, v));
        let small: Option<Vec<i64>> = if g.is_zero() {
            None
        } else {
            xi.iter().map(|v| (v / &g).to_i64()).collect()
        };
        if let Some(a) = small {
            let inl = i128_extremes(self.sets.inliers, &a);
            let up = i128_extremes(self.sets.upper, &a);
            let lo = i128_extremes(self.sets.lower, &a);
            if let (Some(inl), Some(up), Some(lo)) = (inl, up, lo) {
                let (up, lo) = (up.map(|(min, _)| min), lo.map(|(_, max)| max));
                let tag = pick(inl, up, lo, |a, b| a - b)?;
                return Some(self.vertex(&tag));
            }
        }
        let inl = big_extremes(self.sets.inliers, &xi);
        let up = big_extremes(self.sets.upper, &xi).map(|(min, _)| min);
        let lo = big_extremes(self.sets.lower, &xi).map(|(_, max)| max);
        let tag = pick(inl, up, lo, |a, b| a - b)?;
        Some(self.vertex(&tag))
    }

    fn vertex(&self, tag: &Tag) -> Vertex<BigRational> {
        Vertex {
            point: self
                .sets
                .difference(tag)
                .into_iter()
                .map(BigRational::from_i64)
                .collect(),
            tag: *tag,
        }
    }
}

/// Support points of an explicit finite list (used to check witnesses).
pub(crate) struct ListSupport<T> {
    /// The points.
    pub points: Vec<Vec<T>>,
}

impl<T: Scalar> SupportMap<T> for ListSupport<T> {
    fn dim(&self) -> usize {
        self.points.first().map_or(0, Vec::len)
    }

    fn support_point(&mut self, x: &[T], _buf: Vec<T>) -> Option<Vertex<T>> {
        let mut best: Option<(usize, T)> = None;
        for (i, p) in self.points.iter().enumerate() {
            let v = T::dot(p, x);
            if best.as_ref().is_none_or(|(_, b)| v < *b) {
                best = Some((i, v));
            }
        }
        best.map(|(i, _)| self.vertex(&Tag::explicit(i)))
    }

    fn vertex(&self, tag: &Tag) -> Vertex<T> {
        Vertex {
            point: self.points[tag.inlier as usize].clone(),
            tag: *tag,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// The float-filtered exact extremes equal the plain big-integer ones, for directions
        /// from tiny to 200 bits and liftings up to 2^40.
        #[test]
        fn filtered_extremes_are_exact(
            rows in proptest::collection::vec(proptest::collection::vec(-(1i64 << 40)..(1i64 << 40), 5), 1..40),
            dir in proptest::collection::vec((any::<i64>(), 0u32..140), 5),
            small in proptest::collection::vec(-3i64..3, 5),
            tiny in any::<bool>(),
        ) {
            let mut set = LiftedSet::new(1, 5);
            for (i, r) in rows.iter().enumerate() {
                // Small values too, so that ties happen.
                let r: Vec<i64> = if tiny { r.iter().map(|v| v % 4).collect() } else { r.clone() };
                set.push(&[i as i64], &r);
            }
            let x: Vec<BigInt> = if tiny {
                small.iter().map(|&v| BigInt::from(v)).collect()
            } else {
                dir.iter().map(|&(v, s)| BigInt::from(v) << s as usize).collect()
            };
            let naive: Vec<BigInt> = set
                .lifted_rows()
                .map(|row| row.iter().zip(&x).fold(BigInt::zero(), |s, (&a, b)| s + b * a))
                .collect();
            let ((imin, vmin), (imax, vmax)) = big_extremes(&set, &x).unwrap();
            prop_assert_eq!(&vmin, naive.iter().min().unwrap());
            prop_assert_eq!(&vmax, naive.iter().max().unwrap());
            prop_assert_eq!(&naive[imin], &vmin);
            prop_assert_eq!(&naive[imax], &vmax);
        }
    }
}
