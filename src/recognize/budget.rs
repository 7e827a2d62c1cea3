//! Deterministic accounting of the recognizer's work, in *work units*, never wall time: the
//! same problem costs the same units on every machine, run and thread count, so a limit on
//! them keeps the output byte-identical.
//!
//! # Units
//! One unit is about one multiply-add on a lifted coordinate (about a nanosecond):
//! * a float support point or an exact check of an integer direction scans the three sets:
//!   `(|S| + |S⁺| + |S⁻|) · n` units ([`scan_cost`]), `n` the basis dimension;
//! * an exact support point (overflow-checked `i128`, or big integers) costs
//!   [`EXACT_SCAN_FACTOR`] times that;
//! * an iteration of the exact GJK on a simplex of up to `n + 1` vertices (Wolfe's minor
//!   cycle in big rationals) costs `(n + 1)³ ·` [`RATIONAL_OP`] units
//!   ([`rational_solve_cost`]): `O(k³)` big-rational operations of about a microsecond each
//!   (measured: one exact GJK iteration in dimension 27 takes about 20 ms, `28³ ≈ 22 000`);
//! * a direct exact solve for barycentric weights (fraction-free, in `i128` or big integers)
//!   costs `(n + 1)³ ·` [`DIRECT_OP`] units ([`direct_solve_cost`]).
//!
//! A step that the remaining budget cannot afford is not started: the meter is marked
//! exhausted instead, so a limit is exceeded by at most one support scan.

use super::support::Sets;

/// Units of one big-rational operation (about a microsecond).
pub(crate) const RATIONAL_OP: u64 = 1000;

/// Units of one operation of a fraction-free exact solve.
pub(crate) const DIRECT_OP: u64 = 100;

/// An exact support point costs this many times a float one.
pub(crate) const EXACT_SCAN_FACTOR: u64 = 4;

/// Units of one scan of the three sets.
pub(crate) fn scan_cost(sets: &Sets<'_>) -> u64 {
    let points = sets.inliers.len() + sets.upper.len() + sets.lower.len();
    let n = sets.inliers.dim();
    (points as u64).saturating_mul(n as u64).max(1)
}

/// Units of one rational solve on a simplex in dimension `n`.
pub(crate) fn rational_solve_cost(n: usize) -> u64 {
    let k = n as u64 + 1;
    k.saturating_mul(k)
        .saturating_mul(k)
        .saturating_mul(RATIONAL_OP)
}

/// Units of one direct exact solve in dimension `n`.
pub(crate) fn direct_solve_cost(n: usize) -> u64 {
    let k = n as u64 + 1;
    k.saturating_mul(k)
        .saturating_mul(k)
        .saturating_mul(DIRECT_OP)
}

/// Work spent since the last reset and the limit it may not exceed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Meter {
    /// Units spent.
    pub spent: u64,
    /// Units allowed.
    pub limit: u64,
}

impl Default for Meter {
    fn default() -> Meter {
        Meter::unlimited()
    }
}

impl Meter {
    /// No limit.
    pub const fn unlimited() -> Meter {
        Meter {
            spent: 0,
            limit: u64::MAX,
        }
    }

    /// Records `units` of work.
    pub fn charge(&mut self, units: u64) {
        self.spent = self.spent.saturating_add(units);
    }

    /// True once more than the limit has been spent.
    pub fn exhausted(&self) -> bool {
        self.spent > self.limit
    }

    /// Marks the limit as reached (a run stopped at the cap the limit gave it).
    pub fn exhaust(&mut self) {
        self.spent = self.spent.max(self.limit.saturating_add(1));
    }

    /// Charges `units` if the limit affords them; otherwise marks the meter exhausted and
    /// returns false (the caller must then not do the work).
    pub fn try_charge(&mut self, units: u64) -> bool {
        if self.spent.saturating_add(units) <= self.limit {
            self.spent += units;
            true
        } else {
            self.exhaust();
            false
        }
    }

    /// The iteration cap of a run costing `per_iteration` units an iteration: `cap`, or
    /// fewer when the limit binds; the flag tells which.
    pub fn iterations(&self, per_iteration: u64, cap: usize) -> (usize, bool) {
        let left = self.limit.saturating_sub(self.spent) / per_iteration.max(1);
        if left < cap as u64 {
            (left as usize, true)
        } else {
            (cap, false)
        }
    }
}
