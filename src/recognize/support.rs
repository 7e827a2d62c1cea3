//! Support points of `D = (S⁺ − S) ∪ (S − S⁻)`, computed from the three sets directly.
//!
//! The support point of `D` in direction `−x` minimizes `x·d`. Since
//! `min_{d ∈ S⁺−S} x·d = min_{S⁺} x·F − max_{S} x·F` and
//! `min_{d ∈ S−S⁻} x·d = min_{S} x·F − max_{S⁻} x·F`, one pass over each set suffices:
//! `O(|S| + |S⁺| + |S⁻|)` instead of `O(|S|·(|S⁺| + |S⁻|))` for the explicit difference set.

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
        let s = self.inliers.lifted(tag.inlier as usize);
        match tag.side {
            Side::Upper => {
                let o = self.upper.lifted(tag.outlier as usize);
                o.iter().zip(s).map(|(a, b)| a - b).collect()
            }
            Side::Lower => {
                let o = self.lower.lifted(tag.outlier as usize);
                s.iter().zip(o).map(|(a, b)| a - b).collect()
            }
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
    /// The support point of `D` in direction `−x`, or `None` if `D` is empty.
    fn support_point(&mut self, x: &[T]) -> Option<Vertex<T>>;
    /// The vertex named by `tag` (to rebuild a warm-start simplex).
    fn vertex(&self, tag: &Tag) -> Vertex<T>;
}

/// Index and value of the smallest and of the largest `y·F(p)` over a set (`f64`).
#[inline]
fn float_extremes(set: &LiftedSet, y: &[f64]) -> Option<((usize, f64), (usize, f64))> {
    let mut min = (usize::MAX, f64::INFINITY);
    let mut max = (usize::MAX, f64::NEG_INFINITY);
    for (i, row) in set.float_rows().enumerate() {
        let v: f64 = row.iter().zip(y).map(|(a, b)| a * b).sum();
        if v < min.1 {
            min = (i, v);
        }
        if v > max.1 {
            max = (i, v);
        }
    }
    (min.0 != usize::MAX).then_some((min, max))
}

/// Chooses the smaller of the two candidate support points.
fn pick<V: PartialOrd + Clone>(
    inl: Option<((usize, V), (usize, V))>,
    upper: Option<((usize, V), (usize, V))>,
    lower: Option<((usize, V), (usize, V))>,
    sub: impl Fn(&V, &V) -> V,
) -> Option<Tag> {
    let ((imin, vmin), (imax, vmax)) = inl?;
    let a = upper.map(|((j, umin), _)| (sub(&umin, &vmax), imax, j, Side::Upper));
    let b = lower.map(|(_, (j, lmax))| (sub(&vmin, &lmax), imin, j, Side::Lower));
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

/// Support points in `f64`, in coordinates scaled by powers of two (`d'_i = s_i d_i`) so
/// that every coordinate has a magnitude near one: separation is invariant under this
/// diagonal map, and the closest-point solves are far better conditioned.
pub(crate) struct FloatSupport<'a> {
    /// The problem.
    pub sets: Sets<'a>,
    /// The scale `s_i` of each lifted coordinate.
    pub scale: &'a [f64],
    /// Scratch: the direction in unscaled coordinates.
    pub y: Vec<f64>,
}

impl SupportMap<f64> for FloatSupport<'_> {
    fn dim(&self) -> usize {
        self.scale.len()
    }

    fn support_point(&mut self, x: &[f64]) -> Option<Vertex<f64>> {
        self.y.clear();
        self.y.extend(x.iter().zip(self.scale).map(|(a, s)| a * s));
        let inl = float_extremes(self.sets.inliers, &self.y);
        let up = float_extremes(self.sets.upper, &self.y);
        let lo = float_extremes(self.sets.lower, &self.y);
        let tag = pick(inl, up, lo, |a, b| a - b)?;
        Some(self.vertex(&tag))
    }

    fn vertex(&self, tag: &Tag) -> Vertex<f64> {
        let d = self.sets.difference(tag);
        Vertex {
            point: d
                .iter()
                .zip(self.scale)
                .map(|(&v, s)| v as f64 * s)
                .collect(),
            tag: *tag,
        }
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
    let mut out: Option<((usize, BigInt), (usize, BigInt))> = None;
    for (i, row) in set.lifted_rows().enumerate() {
        let v = row
            .iter()
            .zip(x)
            .fold(BigInt::zero(), |s, (&a, b)| s + b * a);
        out = Some(match out {
            None => ((i, v.clone()), (i, v)),
            Some((min, max)) => (
                if v < min.1 { (i, v.clone()) } else { min },
                if v > max.1 { (i, v) } else { max },
            ),
        });
    }
    out
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

    fn support_point(&mut self, x: &[BigRational]) -> Option<Vertex<BigRational>> {
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
                let tag = pick(inl, up, lo, |a, b| a - b)?;
                return Some(self.vertex(&tag));
            }
        }
        let inl = big_extremes(self.sets.inliers, &xi);
        let up = big_extremes(self.sets.upper, &xi);
        let lo = big_extremes(self.sets.lower, &xi);
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

    fn support_point(&mut self, x: &[T]) -> Option<Vertex<T>> {
        let mut best: Option<(usize, T)> = None;
        for (i, p) in self.points.iter().enumerate() {
            let v = p
                .iter()
                .zip(x)
                .fold(T::zero(), |s, (a, b)| s + a.clone() * b.clone());
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
