//! Equations in the points' own coordinates.
//!
//! The recognizer finds `a` relative to a local origin `o`: `f(p) = Σ a_i f_i(p − o)`. For
//! a basis whose span (with the constant) is closed under translation, as every built-in
//! model's is, the same function is `Σ b_i f_i(p) + c` with exact integers `b_i`, `c`: the
//! polynomial `f` is expanded in monomials of `p` (binomially) and written back in the basis
//! by exact Gaussian elimination. The layer `lower ≤ f ≤ upper` is then
//! `lower − c ≤ Σ b_i f_i(p) ≤ upper − c`. Values are big integers: the absolute
//! coefficients grow with the distance of the points from `(0, …, 0)`.

use super::Layer;
use crate::model::{Basis, Terms};
use crate::recognize::Certificate;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;
use std::collections::{BTreeMap, BTreeSet};

/// A polynomial: exponent vector → coefficient (no zero coefficients).
type Poly = BTreeMap<Vec<u32>, BigInt>;

/// `poly += c · monomial`.
fn add_term(poly: &mut Poly, exponents: Vec<u32>, c: BigInt) {
    if c.is_zero() {
        return;
    }
    let entry = poly.entry(exponents).or_default();
    *entry += c;
    if entry.is_zero() {
        poly.retain(|_, v| !v.is_zero());
    }
}

/// The product of two polynomials.
fn multiply(a: &Poly, b: &Poly) -> Poly {
    let mut out = Poly::new();
    for (ea, ca) in a {
        for (eb, cb) in b {
            let e = ea.iter().zip(eb).map(|(x, y)| x + y).collect();
            add_term(&mut out, e, ca * cb);
        }
    }
    out
}

/// `(p_k − o)^e` as a polynomial in `d` variables: `Σ_j C(e, j) p_k^j (−o)^(e−j)`.
fn shifted_power(d: usize, k: usize, o: i64, e: u32) -> Poly {
    let mut out = Poly::new();
    let mut binomial = BigInt::from(1);
    for j in 0..=e {
        let mut exponents = vec![0; d];
        exponents[k] = j;
        let c = &binomial * (-BigInt::from(o)).pow(e - j);
        add_term(&mut out, exponents, c);
        binomial = binomial * BigInt::from(e - j) / BigInt::from(j + 1);
    }
    out
}

/// A basis function as a polynomial.
fn as_poly(terms: &Terms) -> Poly {
    let mut out = Poly::new();
    for (c, e) in terms {
        add_term(&mut out, e.clone(), BigInt::from(*c));
    }
    out
}

/// `Σ a_i f_i(p − origin)` expanded in monomials of `p`.
fn translated(functions: &[Terms], a: &[i64], origin: &[i64]) -> Poly {
    let d = origin.len();
    let mut q = Poly::new();
    for (f, &ai) in functions.iter().zip(a) {
        if ai == 0 {
            continue;
        }
        for (c, e) in f {
            let mut term = Poly::from([(vec![0; d], BigInt::from(*c) * ai)]);
            for (k, (&ek, &ok)) in e.iter().zip(origin).enumerate() {
                if ek > 0 {
                    term = multiply(&term, &shifted_power(d, k, ok, ek));
                }
            }
            for (e, c) in term {
                add_term(&mut q, e, c);
            }
        }
    }
    q
}

/// The coefficients `x` with `Σ x_j columns[j] = target`, free unknowns set to zero; `None`
/// when there is none. Exact Gauss–Jordan elimination over the rationals.
fn solve(columns: &[Poly], target: &Poly) -> Option<Vec<BigRational>> {
    let monomials: BTreeSet<&Vec<u32>> = columns
        .iter()
        .flat_map(|c| c.keys())
        .chain(target.keys())
        .collect();
    let m = columns.len();
    let entry =
        |p: &Poly, e: &Vec<u32>| BigRational::from_integer(p.get(e).cloned().unwrap_or_default());
    let mut rows: Vec<Vec<BigRational>> = monomials
        .iter()
        .map(|e| {
            columns
                .iter()
                .map(|c| entry(c, e))
                .chain(std::iter::once(entry(target, e)))
                .collect()
        })
        .collect();
    let mut pivots = Vec::new();
    for col in 0..m {
        let r = pivots.len();
        let Some(i) = (r..rows.len()).find(|&i| !rows[i][col].is_zero()) else {
            continue;
        };
        rows.swap(r, i);
        let pivot = rows[r][col].clone();
        for v in rows[r].iter_mut() {
            *v /= &pivot;
        }
        let pivot_row = rows[r].clone();
        for (i, row) in rows.iter_mut().enumerate() {
            if i == r || row[col].is_zero() {
                continue;
            }
            let factor = row[col].clone();
            for (v, p) in row.iter_mut().zip(&pivot_row) {
                if !p.is_zero() {
                    *v -= &factor * p;
                }
            }
        }
        pivots.push(col);
    }
    if rows[pivots.len()..].iter().any(|row| !row[m].is_zero()) {
        return None;
    }
    let mut x = vec![BigRational::zero(); m];
    for (r, &col) in pivots.iter().enumerate() {
        x[col] = rows[r][m].clone();
    }
    Some(x)
}

/// The certificate's layer in absolute coordinates (see the module docs), or `None` when
/// the basis is not polynomial, its span is not closed under this translation, or the
/// coefficients are not integers.
pub(crate) fn absolute(basis: &dyn Basis, cert: &Certificate) -> Option<Layer> {
    let functions = crate::model::terms_of(basis)?;
    let d = basis.point_dim();
    if functions.len() != cert.coefficients.len() || cert.origin.len() != d {
        return None;
    }
    let q = translated(&functions, &cert.coefficients, &cert.origin);
    let mut columns: Vec<Poly> = functions.iter().map(as_poly).collect();
    columns.push(Poly::from([(vec![0; d], BigInt::from(1))]));
    let x = solve(&columns, &q)?;
    if x.iter().any(|v| !v.is_integer()) {
        return None;
    }
    let mut x: Vec<BigInt> = x.into_iter().map(|v| v.to_integer()).collect();
    let c = x.pop()?;
    let shift = |v: i128| BigInt::from(v) - &c;
    Some(Layer {
        coefficients: x,
        lower: shift(cert.extremes.lower),
        upper: shift(cert.extremes.upper),
        above: cert.extremes.above.map(shift),
        below: cert.extremes.below.map(shift),
    })
}

/// `Σ coefficients[i] · f_i(p)` exactly: in `i128` when the lifting fits `i64` and nothing
/// overflows, otherwise in big integers from the basis' polynomials (`None` if it has none,
/// or `p` or `coefficients` do not fit the basis).
pub(crate) fn evaluate(basis: &dyn Basis, coefficients: &[BigInt], p: &[i64]) -> Option<BigInt> {
    let n = basis.dim();
    if coefficients.len() != n || p.len() != basis.point_dim() {
        return None;
    }
    let mut f = vec![0i64; n];
    if basis.lift(p, &mut f).is_some() {
        let fast = coefficients.iter().zip(&f).try_fold(0i128, |s, (a, &v)| {
            let a = i128::try_from(a).ok()?;
            s.checked_add(a.checked_mul(i128::from(v))?)
        });
        if let Some(v) = fast {
            return Some(BigInt::from(v));
        }
    }
    let functions = crate::model::terms_of(basis)?;
    let mut sum = BigInt::zero();
    for (terms, a) in functions.iter().zip(coefficients) {
        if a.is_zero() {
            continue;
        }
        let mut value = BigInt::zero();
        for (c, e) in terms {
            let mut t = BigInt::from(*c);
            for (&x, &k) in p.iter().zip(e) {
                t *= BigInt::from(x).pow(k);
            }
            value += t;
        }
        sum += a * value;
    }
    Some(sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::recognize::Extremes;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        /// For every built-in model: the absolute layer's value differs from the
        /// certificate's by the same constant at every point, exactly (so the shifted bounds
        /// hold where the certificate's do).
        #[test]
        fn translation_is_exact_for_every_model(
            origin in proptest::collection::vec(-1000i64..=1000, 3),
            coefficients in proptest::collection::vec(-50i64..=50, 28),
            lower in -1000i128..=1000,
            offsets in proptest::collection::vec(proptest::collection::vec(-30i64..=30, 3), 20),
        ) {
            for model in [
                Model::Line,
                Model::Circle,
                Model::Conic,
                Model::Poly(3),
                Model::Poly(6),
                Model::Quadric3,
                Model::Poly3(3),
            ] {
                let basis = model.basis();
                let d = basis.point_dim();
                prop_assert!(basis.dim() <= coefficients.len());
                let cert = Certificate {
                    origin: origin[..d].to_vec(),
                    coefficients: coefficients[..basis.dim()].to_vec(),
                    extremes: Extremes {
                        lower,
                        upper: 2000,
                        above: Some(3000),
                        below: None,
                    },
                };
                let layer = absolute(&basis, &cert).expect("built-in spans are closed");
                let shift = BigInt::from(cert.extremes.lower) - &layer.lower;
                prop_assert_eq!(BigInt::from(cert.extremes.upper) - &layer.upper, shift.clone());
                prop_assert_eq!(BigInt::from(3000) - layer.above.clone().unwrap(), shift.clone());
                prop_assert_eq!(&layer.below, &None);
                for o in &offsets {
                    let p: Vec<i64> = cert.origin.iter().zip(o).map(|(c, o)| c + o).collect();
                    let local = cert.value(&basis, &p).unwrap();
                    let abs = evaluate(&basis, &layer.coefficients, &p).unwrap();
                    prop_assert_eq!(BigInt::from(local) - abs, shift.clone(), "{} at {:?}", model, p);
                }
            }
        }

        /// The fast (i64) evaluation of a degree-6 polynomial agrees with big integers.
        #[test]
        fn big_integer_evaluation_agrees_with_the_fast_path(
            p in (-40i64..=40, -40i64..=40).prop_map(|(x, y)| [x, y]),
        ) {
            let basis = Model::Poly(6).basis();
            let coefficients: Vec<BigInt> = (0..basis.dim() as i64)
                .map(|i| BigInt::from(i - 13))
                .collect();
            let fast = evaluate(&basis, &coefficients, &p).unwrap();
            let mut slow = BigInt::zero();
            for (terms, a) in basis.polynomials().unwrap().iter().zip(&coefficients) {
                for (c, e) in terms {
                    slow += a * c * BigInt::from(p[0]).pow(e[0]) * BigInt::from(p[1]).pow(e[1]);
                }
            }
            prop_assert_eq!(fast, slow);
        }
    }

    /// Far from the origin the lifting overflows i64: the big-integer path answers.
    #[test]
    fn far_points_are_evaluated_in_big_integers() {
        let basis = Model::Poly(6).basis();
        let coefficients: Vec<BigInt> = (0..basis.dim() as i64)
            .map(|i| BigInt::from(i - 13))
            .collect();
        let far = [1 << 20, -(1 << 20)];
        assert!(evaluate(&basis, &coefficients, &far).is_some());
    }

    /// A basis whose span is not closed under translation (`x^2` without `x`) has no
    /// absolute form for a shifted origin.
    #[test]
    fn spans_not_closed_under_translation_give_none() {
        let b = crate::model::PolynomialBasis::new(
            2,
            vec![vec![(1, vec![2, 0])], vec![(1, vec![0, 1])]],
            vec!["x^2".into(), "y".into()],
        )
        .unwrap();
        let cert = Certificate {
            origin: vec![3, 0],
            coefficients: vec![1, 1],
            extremes: Extremes {
                lower: 0,
                upper: 1,
                above: None,
                below: None,
            },
        };
        assert!(absolute(&b, &cert).is_none());
        let at_zero = Certificate {
            origin: vec![0, 5],
            ..cert
        };
        let layer = absolute(&b, &at_zero).unwrap();
        assert_eq!(layer.coefficients, [BigInt::from(1), BigInt::from(1)]);
        // x^2 + (y - 5): the constant -5 moves into the bounds.
        assert_eq!(layer.lower, BigInt::from(5));
    }
}
