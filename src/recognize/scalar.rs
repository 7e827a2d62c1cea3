//! The number types the GJK variant runs on: `f64` (fast) and exact rationals (fallback).

use super::simplex::{affine_min_norm_f64, affine_min_norm_weights_exact, Vertex, Work};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An ordered field, with the tolerance policy of the solver.
///
/// For `f64` the solver's tests compare against a tolerance proportional to the scale of the
/// data; for [`BigRational`] every tolerance is zero and every decision is exact.
pub(crate) trait Scalar:
    Clone
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// An integer, exactly (for `f64`: exactly when `|v| < 2⁵³`).
    fn from_i64(v: i64) -> Self;
    /// `|self|`.
    fn abs(&self) -> Self;
    /// The tolerance `eps · scale` for `f64`, zero for exact numbers.
    fn tolerance(scale: &Self, eps: f64) -> Self;
    /// True if the value is finite (always for exact numbers).
    fn is_finite(&self) -> bool;
    /// The weights `μ` (summing to one) of the point of the affine hull of `vertices`
    /// nearest to the origin, into `work.mu`; false if they are (numerically) affinely
    /// dependent: the step 1 of Wolfe's minor cycle, by the method suited to the number
    /// type.
    fn affine_min_norm_into(vertices: &[Vertex<Self>], eps: f64, work: &mut Work<Self>) -> bool;
    /// `Σ a_i b_i`.
    fn dot(a: &[Self], b: &[Self]) -> Self {
        a.iter()
            .zip(b)
            .fold(Self::zero(), |s, (x, y)| s + x.clone() * y.clone())
    }
    /// `Σ_i λ_i p_i`, in dimension `dim`, into `out` (its buffer reused).
    fn combination_into<P: AsRef<[Self]>>(
        weights: &[Self],
        points: &[P],
        dim: usize,
        out: &mut Vec<Self>,
    ) {
        out.clear();
        out.resize(dim, Self::zero());
        for (p, l) in points.iter().zip(weights) {
            for (xi, pi) in out.iter_mut().zip(p.as_ref()) {
                *xi = xi.clone() + l.clone() * pi.clone();
            }
        }
    }
    /// `Σ_i λ_i p_i`, in dimension `dim`.
    fn combination<P: AsRef<[Self]>>(weights: &[Self], points: &[P], dim: usize) -> Vec<Self> {
        let mut x = Vec::new();
        Self::combination_into(weights, points, dim, &mut x);
        x
    }
}

impl Scalar for f64 {
    #[inline]
    fn zero() -> f64 {
        0.0
    }
    #[inline]
    fn one() -> f64 {
        1.0
    }
    #[inline]
    fn from_i64(v: i64) -> f64 {
        v as f64
    }
    #[inline]
    fn abs(&self) -> f64 {
        f64::abs(*self)
    }
    #[inline]
    fn tolerance(scale: &f64, eps: f64) -> f64 {
        f64::abs(*scale) * eps
    }
    #[inline]
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    fn affine_min_norm_into(vertices: &[Vertex<f64>], eps: f64, work: &mut Work<f64>) -> bool {
        affine_min_norm_f64(vertices, eps, work)
    }
    /// The built-in models' lengths (line 2, circle 3, conic 5, cubic 9; poly:4 to poly:6
    /// 14, 20 and 27) unrolled: the same products summed in the same order (the minor
    /// cycle's Gram matrices are made of these; its loops over a handful of numbers were
    /// most of its time).
    #[inline]
    fn dot(a: &[f64], b: &[f64]) -> f64 {
        match a.len().min(b.len()) {
            2 => fixed_dot::<2>(a, b),
            3 => fixed_dot::<3>(a, b),
            5 => fixed_dot::<5>(a, b),
            9 => fixed_dot::<9>(a, b),
            14 => fixed_dot::<14>(a, b),
            20 => fixed_dot::<20>(a, b),
            27 => fixed_dot::<27>(a, b),
            _ => a.iter().zip(b).fold(0.0, |s, (x, y)| s + x * y),
        }
    }
}

/// `Σ a_i b_i` over the first `N` numbers, summed from 0 in order.
#[inline]
fn fixed_dot<const N: usize>(a: &[f64], b: &[f64]) -> f64 {
    let (a, b): (&[f64; N], &[f64; N]) = (a[..N].try_into().unwrap(), b[..N].try_into().unwrap());
    let mut s = 0.0;
    for i in 0..N {
        s += a[i] * b[i];
    }
    s
}

impl Scalar for BigRational {
    fn zero() -> BigRational {
        Zero::zero()
    }
    fn one() -> BigRational {
        num_traits::One::one()
    }
    fn from_i64(v: i64) -> BigRational {
        BigRational::from_integer(BigInt::from(v))
    }
    fn abs(&self) -> BigRational {
        Signed::abs(self)
    }
    fn tolerance(_scale: &BigRational, _eps: f64) -> BigRational {
        Zero::zero()
    }
    fn is_finite(&self) -> bool {
        true
    }
    fn affine_min_norm_into(
        vertices: &[Vertex<BigRational>],
        _eps: f64,
        work: &mut Work<BigRational>,
    ) -> bool {
        match affine_min_norm_weights_exact(vertices) {
            Some(mu) => {
                work.mu = mu;
                true
            }
            None => false,
        }
    }
    /// Over the common denominator of the terms, reduced once: rational additions would
    /// each reduce by a gcd.
    fn dot(a: &[BigRational], b: &[BigRational]) -> BigRational {
        let dens: Vec<BigInt> = a
            .iter()
            .zip(b)
            .map(|(x, y)| x.denom() * y.denom())
            .collect();
        let common = common_denominator(&dens);
        let mut sum = BigInt::zero();
        for ((x, y), d) in a.iter().zip(b).zip(&dens) {
            let t = x.numer() * y.numer();
            sum += if *d == common { t } else { t * (&common / d) };
        }
        BigRational::new(sum, common)
    }
    /// [`Scalar::combination`] (below: its common denominator), the buffer replaced.
    fn combination_into<P: AsRef<[BigRational]>>(
        weights: &[BigRational],
        points: &[P],
        dim: usize,
        out: &mut Vec<BigRational>,
    ) {
        *out = Self::combination(weights, points, dim);
    }
    /// Over the common denominator of the weights when the points are integers (as every
    /// point of `D` is), one reduction per coordinate.
    fn combination<P: AsRef<[BigRational]>>(
        weights: &[BigRational],
        points: &[P],
        dim: usize,
    ) -> Vec<BigRational> {
        if !points
            .iter()
            .all(|p| p.as_ref().iter().all(|v| v.denom().is_one()))
        {
            let mut x = vec![<BigRational as Zero>::zero(); dim];
            for (p, l) in points.iter().zip(weights) {
                for (xi, pi) in x.iter_mut().zip(p.as_ref()) {
                    *xi += l * pi;
                }
            }
            return x;
        }
        let dens: Vec<BigInt> = weights.iter().map(|l| l.denom().clone()).collect();
        let common = common_denominator(&dens);
        let scaled: Vec<BigInt> = weights
            .iter()
            .map(|l| {
                if *l.denom() == common {
                    l.numer().clone()
                } else {
                    l.numer() * (&common / l.denom())
                }
            })
            .collect();
        (0..dim)
            .map(|j| {
                let sum = points
                    .iter()
                    .zip(&scaled)
                    .fold(BigInt::zero(), |s, (p, l)| s + l * p.as_ref()[j].numer());
                BigRational::new(sum, common.clone())
            })
            .collect()
    }
}

/// The least common multiple of positive denominators (equal ones cost no gcd).
fn common_denominator(dens: &[BigInt]) -> BigInt {
    let mut common = BigInt::one();
    for d in dens {
        if !d.is_one() && *d != common {
            common = num_integer::Integer::lcm(&common, d);
        }
    }
    common
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// The common-denominator dot product and combination equal term-by-term rational
        /// arithmetic, for integer and fractional points.
        #[test]
        fn common_denominator_arithmetic_is_exact(
            raw in proptest::collection::vec(
                proptest::collection::vec((-(1i64 << 40)..(1i64 << 40), 1i64..6), 5), 1..=6),
            weights in proptest::collection::vec((-1000i64..1000, 1i64..50), 6),
            integer in any::<bool>(),
        ) {
            let points: Vec<Vec<BigRational>> = raw
                .iter()
                .map(|p| p.iter().map(|&(n, d)| q(n, if integer { 1 } else { d })).collect())
                .collect();
            let w: Vec<BigRational> = weights.iter().take(points.len()).map(|&(n, d)| q(n, d)).collect();
            let naive_dot = |a: &[BigRational], b: &[BigRational]| {
                a.iter().zip(b).fold(<BigRational as Zero>::zero(), |s, (x, y)| s + x * y)
            };
            for a in &points {
                for b in &points {
                    prop_assert_eq!(<BigRational as Scalar>::dot(a, b), naive_dot(a, b));
                }
                prop_assert_eq!(<BigRational as Scalar>::dot(a, &w[..a.len().min(w.len())]),
                    naive_dot(a, &w[..a.len().min(w.len())]));
            }
            let refs: Vec<&[BigRational]> = points.iter().map(|p| &p[..]).collect();
            let mut want = vec![<BigRational as Zero>::zero(); 5];
            for (p, l) in points.iter().zip(&w) {
                for (x, v) in want.iter_mut().zip(p) {
                    *x += l * v;
                }
            }
            prop_assert_eq!(<BigRational as Scalar>::combination(&w, &refs, 5), want);
        }
    }
}
