//! Fraction-free (Bareiss) solution of integer linear systems, for the exact steps.
//!
//! Bareiss elimination keeps every entry an integer: after step `c`, each remaining entry is
//! a minor of the matrix, and the update `(m_cc m_rj − m_rc m_cj) / m_{c−1,c−1}` divides
//! exactly. With `D` the last pivot (the determinant of the eliminated `k × k` system, up to
//! sign), the solution `x` has integer multiples `X = D x` (Cramer's rule), found by a back
//! substitution whose divisions `m_rr X_r = D m_rk − Σ_{c>r} m_rc X_c` are exact too: no
//! rational is formed, let alone reduced, until the caller divides by `D` once.

use num_bigint::BigInt;
use num_traits::{One, Zero};

/// Solves the system whose augmented matrix `m` has `k` unknowns (rows of `k + 1` entries;
/// at least `k` rows, more for an overdetermined system), in place.
///
/// Returns `(X, D)` with `x = X / D` the unique solution (`D ≠ 0`), or `None` if the
/// columns are linearly dependent or the extra equations do not hold.
pub(crate) fn solve(m: &mut [Vec<BigInt>], k: usize) -> Option<(Vec<BigInt>, BigInt)> {
    let rows = m.len();
    if k == 0 || rows < k {
        return None;
    }
    let mut prev = BigInt::one();
    for c in 0..k {
        let p = (c..rows).find(|&r| !m[r][c].is_zero())?;
        m.swap(c, p);
        for r in c + 1..rows {
            for cc in c + 1..=k {
                let v = (&m[c][c] * &m[r][cc] - &m[r][c] * &m[c][cc]) / &prev;
                m[r][cc] = v;
            }
            m[r][c] = BigInt::zero();
        }
        prev = m[c][c].clone();
    }
    // The remaining equations must hold.
    if (k..rows).any(|r| !m[r][k].is_zero()) {
        return None;
    }
    let d = prev;
    let mut x = vec![BigInt::zero(); k];
    for r in (0..k).rev() {
        let mut s = &d * &m[r][k];
        for c in r + 1..k {
            s -= &m[r][c] * &x[c];
        }
        x[r] = s / &m[r][r];
    }
    Some((x, d))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn big(rows: &[&[i64]]) -> Vec<Vec<BigInt>> {
        rows.iter()
            .map(|r| r.iter().map(|&v| BigInt::from(v)).collect())
            .collect()
    }

    #[test]
    fn square_overdetermined_and_singular() {
        // 2x + y = 5, x − y = 1: x = 2, y = 1.
        let (x, d) = solve(&mut big(&[&[2, 1, 5], &[1, -1, 1]]), 2).unwrap();
        assert_eq!(x[0].clone() / &d, BigInt::from(2));
        assert_eq!(x[1].clone() / &d, BigInt::from(1));
        assert_eq!(&x[0] % &d, BigInt::zero());
        // x = 3/2 from 2x = 3: X = 3, D = 2.
        let (x, d) = solve(&mut big(&[&[2, 3]]), 1).unwrap();
        assert_eq!((x[0].clone(), d), (BigInt::from(3), BigInt::from(2)));
        // A consistent extra equation, then an inconsistent one.
        assert!(solve(&mut big(&[&[1, 2], &[2, 4]]), 1).is_some());
        assert!(solve(&mut big(&[&[1, 2], &[2, 5]]), 1).is_none());
        // Dependent columns.
        assert!(solve(&mut big(&[&[1, 2, 3], &[2, 4, 6]]), 2).is_none());
    }
}
