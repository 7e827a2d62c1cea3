//! The number types the GJK variant runs on: `f64` (fast) and exact rationals (fallback).

use super::simplex::{
    affine_min_norm_weights_by_elimination, affine_min_norm_weights_exact, Vertex,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
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
    /// nearest to the origin, `None` if they are (numerically) affinely dependent: the
    /// step 1 of Wolfe's minor cycle, by the method suited to the number type.
    fn affine_min_norm_weights(vertices: &[Vertex<Self>], eps: f64) -> Option<Vec<Self>>;
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
    fn affine_min_norm_weights(vertices: &[Vertex<f64>], eps: f64) -> Option<Vec<f64>> {
        affine_min_norm_weights_by_elimination(vertices, eps)
    }
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
    fn affine_min_norm_weights(
        vertices: &[Vertex<BigRational>],
        _eps: f64,
    ) -> Option<Vec<BigRational>> {
        affine_min_norm_weights_exact(vertices)
    }
}
