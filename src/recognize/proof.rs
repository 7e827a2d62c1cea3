//! The proofs of a recognition: a [`Certificate`] (the integer layer) or a [`Witness`]
//! (exact weights putting the origin in the hull of `D`), and the [`Outcome`] that says which.

use super::exact::dot_i128;
use super::relative::relative;
use crate::model::Basis;
use num_rational::BigRational;
use num_traits::ToPrimitive;

/// Which outlier set a point belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// `S⁺`: strictly above the layer (`a·F > upper`).
    Upper,
    /// `S⁻`: strictly below the layer (`a·F < lower`).
    Lower,
}

/// The exact values of a layer's function `a·F` on the three sets: the layer is
/// `lower ≤ a·F ≤ upper`, and it separates when `below < lower` and `upper < above`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Extremes {
    /// `min_S a·F`.
    pub lower: i128,
    /// `max_S a·F`.
    pub upper: i128,
    /// `min_{S⁺} a·F` (`> upper`), `None` if `S⁺` is empty.
    pub above: Option<i128>,
    /// `max_{S⁻} a·F` (`< lower`), `None` if `S⁻` is empty.
    pub below: Option<i128>,
}

impl Extremes {
    /// True when the layer `[lower, upper]` strictly separates the outliers.
    pub fn separates(&self) -> bool {
        self.above.is_none_or(|v| v > self.upper) && self.below.is_none_or(|v| v < self.lower)
    }

    /// Every value divided by `g > 0`: the extremes of `(a / g)·F` when `g` divides `a`
    /// (every value is then a multiple of `g`, so the division is exact).
    pub(crate) fn divided_by(self, g: i128) -> Extremes {
        Extremes {
            lower: self.lower / g,
            upper: self.upper / g,
            above: self.above.map(|v| v / g),
            below: self.below.map(|v| v / g),
        }
    }
}

/// Proof that a set is described: the integer layer `lower ≤ a·F(p − origin) ≤ upper`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Certificate {
    /// The local origin the points are taken relative to.
    pub origin: Vec<i64>,
    /// `a`, one integer per basis function (the constant's coefficient is zero).
    pub coefficients: Vec<i64>,
    /// The values of `a·F` on the inliers (the layer's bounds) and on the outliers.
    pub extremes: Extremes,
}

impl Certificate {
    /// The zero function's layer `0 ≤ 0 ≤ 0` at `origin`, over a basis of `dim` functions:
    /// what describes any set without outliers.
    pub fn zero(origin: Vec<i64>, dim: usize) -> Certificate {
        Certificate {
            origin,
            coefficients: vec![0; dim],
            extremes: Extremes::default(),
        }
    }

    /// `a·F(p − origin)` exactly, or `None` on overflow or dimension mismatch.
    pub fn value(&self, basis: &dyn Basis, p: &[i64]) -> Option<i128> {
        if p.len() != self.origin.len() || self.coefficients.len() != basis.dim() {
            return None;
        }
        let rel = relative(p, &self.origin)?;
        let mut f = vec![0; basis.dim()];
        basis.lift(&rel, &mut f)?;
        dot_i128(&self.coefficients, &f)
    }

    /// True when every coefficient is zero (only possible when there are no outliers).
    pub fn is_zero(&self) -> bool {
        self.coefficients.iter().all(|&c| c == 0)
    }
}

/// Proof that a set is not described: points `d_k = ±(F(outlier) − F(inlier))` of `D` and
/// exact weights `λ_k ≥ 0`, `Σλ = 1`, with `Σ λ_k d_k = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Witness {
    /// The local origin: `F` is evaluated at `p − origin`.
    pub origin: Vec<i64>,
    /// `(inlier, outlier, side)` of each point of `D` used, absolute coordinates.
    pub pairs: Vec<(Vec<i64>, Vec<i64>, Side)>,
    pub(super) weights: Vec<BigRational>,
}

impl Witness {
    /// The weights, as `f64` approximations (the exact ones are checked by
    /// [`Witness::verify`]).
    pub fn weights(&self) -> Vec<f64> {
        self.weights
            .iter()
            .map(|w| w.to_f64().unwrap_or(f64::NAN))
            .collect()
    }

    /// The exact weights `λ_k`, in the order of [`Witness::pairs`].
    pub fn exact_weights(&self) -> &[BigRational] {
        &self.weights
    }

    /// Re-checks the witness exactly: weights non-negative summing to one, and the weighted
    /// sum of the differences zero.
    pub fn verify(&self, basis: &dyn Basis) -> bool {
        use num_traits::{One, Zero};
        if self.pairs.is_empty() || self.pairs.len() != self.weights.len() {
            return false;
        }
        let n = basis.dim();
        let mut sum = vec![BigRational::zero(); n];
        let mut total = BigRational::zero();
        let (mut fi, mut fo) = (vec![0; n], vec![0; n]);
        for ((inl, out, side), w) in self.pairs.iter().zip(&self.weights) {
            let (Some(ri), Some(ro)) = (relative(inl, &self.origin), relative(out, &self.origin))
            else {
                return false;
            };
            if *w < BigRational::zero()
                || basis.lift(&ri, &mut fi).is_none()
                || basis.lift(&ro, &mut fo).is_none()
            {
                return false;
            }
            total += w;
            for k in 0..n {
                let d = match side {
                    Side::Upper => fo[k] as i128 - fi[k] as i128,
                    Side::Lower => fi[k] as i128 - fo[k] as i128,
                };
                sum[k] += w * BigRational::from_integer(d.into());
            }
        }
        total == BigRational::one() && sum.iter().all(Zero::is_zero)
    }
}

/// The answer of [`Recognizer::recognize`](crate::Recognizer::recognize).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// A verified [`Certificate`] exists ([`Recognizer::certificate`](crate::Recognizer::certificate)).
    Described,
    /// A verified [`Witness`] exists ([`Recognizer::witness`](crate::Recognizer::witness)).
    NotDescribed,
    /// Neither could be established (exact guard cap, or liftings overflowing `i64`).
    Undecided,
    /// Not decided within the work limit ([`Recognizer::set_work_limit`](crate::Recognizer::set_work_limit)).
    OverBudget,
}
