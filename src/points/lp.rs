//! An exact revised simplex for `maximise c·x subject to A x = b, x ≥ 0`, with columns
//! added while it runs (column generation), in big integers only.
//!
//! The basis inverse is kept fraction-free: an integer matrix `M` and an integer `D > 0`
//! with `M / D = B⁻¹` and `D = |det B|`. A pivot on row `r` with entering column `a`
//! (`d = M a`, `d_r > 0`) sets `D' = d_r`, keeps row `r` of `M` and replaces every other row
//! by `(d_r M_i − d_i M_r) / D`, an exact division (the rows are those of `±adj B'`): no
//! rational number is ever reduced, and every quantity is exact. The entering column is the
//! one of largest reduced cost (Dantzig), the leaving row the least ratio (ties to the
//! lowest column); once more than `2m` pivots in a row are degenerate, Bland's rule (the lowest-index
//! entering column) takes over for the rest of the call, so the method cannot cycle on the
//! degenerate vertices the thinnest-layer programs start from. Dantzig's rule halves the
//! pivots of the cubic example of `examples/paper_3d.rs` against Bland's alone.
//!
//! The program starts from the identity basis (the first `m` columns are the unit vectors,
//! given with their objective coefficients) and `b ≥ 0`, so it needs no first phase.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::cmp::Ordering;

/// How [`Simplex::solve`] ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Status {
    /// Optimal over the columns given so far.
    Optimal,
    /// The objective reached the bound given: the optimum is at least that.
    Bounded,
    /// The objective is unbounded above.
    Unbounded,
}

/// A column: its entries (one per row) and its objective coefficient.
#[derive(Clone, Debug)]
pub(super) struct Column {
    /// `A`'s entries in this column.
    pub entries: Vec<BigInt>,
    /// `c`'s entry.
    pub objective: BigInt,
}

/// The program and its current basis.
#[derive(Clone, Debug)]
pub(super) struct Simplex {
    columns: Vec<Column>,
    /// The column of each row's basic variable.
    basis: Vec<usize>,
    /// `D · B⁻¹`, row by row.
    inverse: Vec<Vec<BigInt>>,
    /// `D = |det B|`, positive.
    det: BigInt,
    /// `D · x_B`.
    values: Vec<BigInt>,
    /// Pivots made so far.
    pub pivots: u64,
}

impl Simplex {
    /// The program `A x = b` whose first `m = b.len()` columns are the unit vectors, with the
    /// objective coefficients `unit_objective`; the identity is the starting basis.
    ///
    /// `b` must be non-negative (the starting basis is then feasible).
    pub fn new(b: Vec<BigInt>, unit_objective: Vec<BigInt>) -> Simplex {
        let m = b.len();
        debug_assert!(b.iter().all(|v| !v.is_negative()));
        debug_assert_eq!(unit_objective.len(), m);
        let columns = unit_objective
            .into_iter()
            .enumerate()
            .map(|(i, objective)| Column {
                entries: (0..m).map(|k| BigInt::from(u8::from(k == i))).collect(),
                objective,
            })
            .collect();
        let inverse = (0..m)
            .map(|i| (0..m).map(|k| BigInt::from(u8::from(k == i))).collect())
            .collect();
        Simplex {
            columns,
            basis: (0..m).collect(),
            inverse,
            det: BigInt::from(1),
            values: b,
            pivots: 0,
        }
    }

    /// Adds a column (it enters the program non-basic); returns its index.
    pub fn add(&mut self, column: Column) -> usize {
        debug_assert_eq!(column.entries.len(), self.basis.len());
        self.columns.push(column);
        self.columns.len() - 1
    }

    /// The dual solution `π = c_B B⁻¹` as integers over [`Simplex::det`]: `π = duals / det`.
    pub fn duals(&self) -> Vec<BigInt> {
        let m = self.basis.len();
        let mut pi = vec![BigInt::zero(); m];
        for (r, &col) in self.basis.iter().enumerate() {
            let c = &self.columns[col].objective;
            if c.is_zero() {
                continue;
            }
            for (p, x) in pi.iter_mut().zip(&self.inverse[r]) {
                *p += c * x;
            }
        }
        pi
    }

    /// `D = |det B|`, the common denominator of [`Simplex::duals`] and of the values.
    pub fn det(&self) -> &BigInt {
        &self.det
    }

    /// The objective value of the current basic solution, exactly.
    pub fn objective(&self) -> BigRational {
        let mut sum = BigInt::zero();
        for (&col, v) in self.basis.iter().zip(&self.values) {
            sum += &self.columns[col].objective * v;
        }
        BigRational::new(sum, self.det.clone())
    }

    /// `D` times the reduced cost of column `k`, given `duals()` (its sign is the reduced
    /// cost's).
    fn reduced(&self, k: usize, pi: &[BigInt]) -> BigInt {
        let col = &self.columns[k];
        let mut v = &self.det * &col.objective;
        for (a, p) in col.entries.iter().zip(pi) {
            if !a.is_zero() {
                v -= a * p;
            }
        }
        v
    }

    /// Pivots (Dantzig's rule, Bland's after a streak of degenerate pivots: see the module
    /// documentation) until the basis is optimal over the columns given, the objective is at
    /// least `bound` (when one is given), or the program is unbounded.
    pub fn solve(&mut self, bound: Option<&BigRational>) -> Status {
        let m = self.basis.len();
        let mut in_basis = vec![false; self.columns.len()];
        for &c in &self.basis {
            in_basis[c] = true;
        }
        // Degenerate pivots in a row; past 2m, Bland's rule for the rest of the call.
        let mut degenerate = 0;
        loop {
            if bound.is_some_and(|b| self.objective() >= *b) {
                return Status::Bounded;
            }
            let pi = self.duals();
            let candidates = (0..self.columns.len()).filter(|&k| !in_basis[k]);
            let enter = if degenerate > 2 * m {
                // Bland: the lowest-index column whose reduced cost is positive enters.
                candidates
                    .map(|k| (k, self.reduced(k, &pi)))
                    .find(|(_, r)| r.is_positive())
            } else {
                // Dantzig: the largest reduced cost (all share the denominator D).
                candidates
                    .map(|k| (k, self.reduced(k, &pi)))
                    .filter(|(_, r)| r.is_positive())
                    .fold(None, |best: Option<(usize, BigInt)>, (k, r)| match best {
                        Some((_, ref b)) if *b >= r => best,
                        _ => Some((k, r)),
                    })
            };
            let Some((enter, _)) = enter else {
                return Status::Optimal;
            };
            let a = &self.columns[enter].entries;
            let d: Vec<BigInt> = self
                .inverse
                .iter()
                .map(|row| {
                    row.iter()
                        .zip(a)
                        .filter(|(_, x)| !x.is_zero())
                        .map(|(r, x)| r * x)
                        .sum()
                })
                .collect();
            // The least ratio values[r] / d[r] over d[r] > 0; ties to the lowest column.
            let mut leave: Option<usize> = None;
            for r in (0..m).filter(|&r| d[r].is_positive()) {
                leave = Some(match leave {
                    None => r,
                    Some(s) => {
                        // values[r] / d[r] against values[s] / d[s], both d positive.
                        match (&self.values[r] * &d[s]).cmp(&(&self.values[s] * &d[r])) {
                            Ordering::Less => r,
                            Ordering::Equal if self.basis[r] < self.basis[s] => r,
                            _ => s,
                        }
                    }
                });
            }
            let Some(r) = leave else {
                return Status::Unbounded;
            };
            if self.values[r].is_zero() {
                degenerate += 1;
            } else if degenerate <= 2 * m {
                degenerate = 0;
            }
            self.pivot(r, &d);
            in_basis[self.basis[r]] = false;
            in_basis[enter] = true;
            self.basis[r] = enter;
            self.pivots += 1;
        }
    }

    /// The fraction-free update of the inverse and the values for column `d = M a` entering
    /// on row `r`.
    fn pivot(&mut self, r: usize, d: &[BigInt]) {
        let dr = d[r].clone();
        let row_r = self.inverse[r].clone();
        let value_r = self.values[r].clone();
        for i in 0..self.basis.len() {
            if i == r {
                continue;
            }
            let di = &d[i];
            let row = &mut self.inverse[i];
            for (x, xr) in row.iter_mut().zip(&row_r) {
                let v = &dr * &*x - di * xr;
                *x = v / &self.det;
            }
            let v = &dr * &self.values[i] - di * &value_r;
            self.values[i] = v / &self.det;
        }
        self.det = dr;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn int(v: i64) -> BigInt {
        BigInt::from(v)
    }

    fn column(entries: &[i64], objective: i64) -> Column {
        Column {
            entries: entries.iter().map(|&v| int(v)).collect(),
            objective: int(objective),
        }
    }

    /// max 3x + 2y, x + y + s1 = 4, x + 3y + s2 = 6: the optimum 12 at x = 4.
    #[test]
    fn a_small_program_is_solved_exactly() {
        let mut s = Simplex::new(vec![int(4), int(6)], vec![int(0), int(0)]);
        s.add(column(&[1, 1], 3));
        s.add(column(&[1, 3], 2));
        assert_eq!(s.solve(None), Status::Optimal);
        assert_eq!(s.objective(), BigRational::from(int(12)));
        // The duals: π = (3, 0).
        let pi = s.duals();
        assert_eq!(
            pi.iter()
                .map(|p| BigRational::new(p.clone(), s.det().clone()))
                .collect::<Vec<_>>(),
            [BigRational::from(int(3)), BigRational::from(int(0))]
        );
    }

    /// A fractional optimum: max x + y, 2x + y ≤ 4, x + 3y ≤ 6 → x = 6/5, y = 8/5, 14/5.
    #[test]
    fn a_fractional_optimum_and_the_bound() {
        let build = || {
            let mut s = Simplex::new(vec![int(4), int(6)], vec![int(0), int(0)]);
            s.add(column(&[2, 1], 1));
            s.add(column(&[1, 3], 1));
            s
        };
        let mut s = build();
        assert_eq!(s.solve(None), Status::Optimal);
        assert_eq!(s.objective(), BigRational::new(int(14), int(5)));
        // Stopped as soon as the objective reaches 2.
        let mut s = build();
        let two = BigRational::from(int(2));
        assert_eq!(s.solve(Some(&two)), Status::Bounded);
        assert!(s.objective() >= two);
        // A column added later is taken into account from the current basis.
        let mut s = build();
        s.solve(None);
        s.add(column(&[1, 1], 2));
        assert_eq!(s.solve(None), Status::Optimal);
        assert_eq!(s.objective(), BigRational::from(int(8)));
    }

    /// Beale's example as Chvátal gives it, which cycles under Dantzig's rule with a
    /// careless leaving rule: max 10x1 − 57x2 − 9x3 − 24x4, x1 − 11x2 − 5x3 + 18x4 ≤ 0,
    /// x1 − 3x2 − x3 + 2x4 ≤ 0, x1 ≤ 1 (rows doubled), optimum 1 (by vertex enumeration).
    #[test]
    fn a_cycling_example_terminates_at_its_optimum() {
        let mut s = Simplex::new(vec![int(0), int(0), int(1)], vec![int(0); 3]);
        s.add(column(&[1, 1, 1], 10));
        s.add(column(&[-11, -3, 0], -57));
        s.add(column(&[-5, -1, 0], -9));
        s.add(column(&[18, 2, 0], -24));
        assert_eq!(s.solve(None), Status::Optimal);
        assert_eq!(s.objective(), BigRational::from(int(1)));
    }

    #[test]
    fn an_unbounded_program_is_said_so() {
        let mut s = Simplex::new(vec![int(1)], vec![int(0)]);
        s.add(column(&[-1], 1));
        assert_eq!(s.solve(None), Status::Unbounded);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Random programs: the optimum agrees with brute force over every basis (vertices).
        /// max c·x, A x ≤ b (slacks as the unit columns), 2 rows, 3 structural columns,
        /// A ≥ 0 with a positive entry in every column: bounded.
        #[test]
        fn random_programs_agree_with_vertex_enumeration(
            b in (1i64..=6, 1i64..=6).prop_map(|(x, y)| [x, y]),
            cols in proptest::collection::vec(
                ((1i64..=4, 0i64..=3).prop_map(|(x, y)| [x, y]), -4i64..=4),
                3,
            ),
        ) {
            let mut s = Simplex::new(b.iter().map(|&v| int(v)).collect(), vec![int(0), int(0)]);
            for (a, c) in &cols {
                s.add(column(a, *c));
            }
            let status = s.solve(None);
            // All columns: the two slacks, then the structural ones.
            let mut all: Vec<([i64; 2], i64)> = vec![([1, 0], 0), ([0, 1], 0)];
            all.extend(cols.iter().cloned());
            let mut best: Option<BigRational> = None;
            for i in 0..all.len() {
                for k in i + 1..all.len() {
                    let (a, c) = (all[i].0, all[k].0);
                    let det = a[0] * c[1] - a[1] * c[0];
                    if det == 0 {
                        continue;
                    }
                    // Cramer: x_i, x_k.
                    let xi = BigRational::new(int(b[0] * c[1] - b[1] * c[0]), int(det));
                    let xk = BigRational::new(int(a[0] * b[1] - a[1] * b[0]), int(det));
                    if xi.is_negative() || xk.is_negative() {
                        continue;
                    }
                    let v = xi * BigRational::from(int(all[i].1))
                        + xk * BigRational::from(int(all[k].1));
                    best = Some(best.map_or(v.clone(), |b: BigRational| b.max(v)));
                }
            }
            prop_assert_eq!(status, Status::Optimal);
            prop_assert_eq!(Some(s.objective()), best, "{:?} {:?}", b, cols);
        }
    }
}
