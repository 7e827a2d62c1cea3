//! Recognition of Digital Level Layers: the paper's GJK variant, exact in its decisions.
//!
//! # The problem
//! Given finite sets of integer points `S` (inliers), `S⁺` and `S⁻` (outliers) and a
//! [`Basis`] `f_1, …, f_n`, lift every point to `F(p) = (f_1(p), …, f_n(p)) ∈ Zⁿ`. The set `S`
//! is *described* when some `a ∈ Rⁿ` gives
//!
//! ```text
//! a·F(s⁻) < a·F(s) < a·F(s⁺)     for all s⁻ ∈ S⁻, s ∈ S, s⁺ ∈ S⁺.
//! ```
//!
//! Then the Digital Level Layer `lower ≤ a·F(p) ≤ upper` (`lower`, `upper` the extremes over
//! `S`) contains `S` and has `S⁺` strictly above and `S⁻` strictly below. Equivalently the
//! origin is not in `conv(D)`, `D = (S⁺ − S) ∪ (S − S⁻)` (lifted): `a` is then any direction
//! with `a·d > 0` on `D`. The paper's "or" (`S⁺` below, `S⁻` above) is the same problem for
//! `−a`, so one run decides both.
//!
//! # The algorithm
//! The GJK variant of the paper ([`gjk`](self) module): support points of `D` are computed
//! from the three sets directly ([`support`](self) module, `O(|S| + |S⁺| + |S⁻|)` per
//! support point); the closest point of the current simplex to the origin is found by
//! Wolfe's minor cycle, which removes the vertices not needed. It runs in `f64`, in
//! coordinates relative to a local origin and scaled by powers of two per lifted coordinate.
//! When that stalls (long, nearly flat pieces make the lifted points strongly correlated and
//! the simplices nearly degenerate), it runs again in *whitened* coordinates, where the
//! lifted points have unit covariance ([`conditioning`](self) module); a piece that has
//! needed them tries them first from then on. Any invertible linear change of coordinates
//! leaves separation unchanged, and every answer is checked on the integer data anyway.
//!
//! # What is exact, and why it terminates
//! The `f64` run only *proposes*. An answer is given only with a proof checked in exact
//! arithmetic:
//! * **described**: the float direction is rounded to an integer vector `a` and
//!   `max_{S⁻} a·F < min_S a·F ≤ max_S a·F < min_{S⁺} a·F` is verified in overflow-checked
//!   `i128` (the liftings are exact `i64`). The [`Certificate`] holds `a` and those values.
//! * **not described**: the points of the final simplex are checked, in rational arithmetic,
//!   to hold the origin in their convex hull (exact weights `λ ≥ 0`, `Σλ = 1`, `Σλd = 0`):
//!   a [`Witness`]. No `a` can then exist, since `a·d > 0` for all `d` would give
//!   `0 = a·Σλd > 0`.
//! * otherwise (float run stalled, certificate or witness not confirmed), the same algorithm
//!   runs in exact rational arithmetic, where every iteration strictly decreases the distance
//!   and no simplex repeats, so it ends (Wolfe 1976). Its iteration cap is a guard only; were
//!   it reached, the outcome would be [`Outcome::Undecided`], which callers treat as "cannot
//!   grow" and which is counted in [`Stats`] (none has been met in the tests).
//!
//! # Incremental use
//! A decomposition grows a piece one point at a time. The recognizer keeps the three sets and
//! the last certificate with its exact extreme values: a new point is checked against them in
//! `O(n)`, and GJK runs only when the old certificate no longer separates, warm-started from
//! the previous simplex (whose vertices stay points of `D`, since the sets only grow between
//! removals).

mod bareiss;
mod budget;
mod conditioning;
mod exact;
mod float;
mod gjk;
mod gram;
mod lifted;
mod margin;
mod planar;
mod proof;
pub(crate) mod relative;
mod scalar;
mod simplex;
mod stats;
mod support;

pub use proof::{Certificate, Extremes, Outcome, Side, Witness};
pub use stats::Stats;

use crate::model::Basis;
use budget::{scan_cost, Meter};
use conditioning::{LinearMap, Moments};
use exact::{decide_exactly, dot_i128, verify_certificate, ExactDecision};
use float::{float_decide, power_of_two_scale_into, FloatAnswer, FloatScratch};
use lifted::LiftedSet;
pub(crate) use margin::max_margin_direction_from;
pub use margin::{max_margin_direction, small_certificate, MarginDirection};
use num_rational::BigRational;
use relative::{relative, relative_into};
use simplex::Simplex;
use std::cell::OnceCell;
use std::sync::Arc;
use support::{Sets, Tag};

/// The incremental recognizer: owns the three sets, the scratch simplex and the last
/// certificate.
#[derive(Debug)]
pub struct Recognizer {
    basis: Arc<dyn Basis>,
    origin: Vec<i64>,
    inliers: LiftedSet,
    upper: LiftedSet,
    lower: LiftedSet,
    /// Largest `|F_i|` over every point added since the last reset.
    max_abs: Vec<i64>,
    /// Mean and scatter of the liftings of the inliers (brought up to date when needed).
    moments: Moments,
    /// The float runs of this piece have needed whitened coordinates: try them first.
    whiten: bool,
    simplex: Simplex<f64>,
    /// The last verified certificate (coefficients, extremes) and whether it still holds.
    cert: Option<(Vec<i64>, Extremes)>,
    cert_valid: bool,
    /// The proof of the last [`Outcome::NotDescribed`] answer as found: the pairs by index
    /// in the sets (their tags) and the exact weights. Most callers never look at it (the
    /// greedy decomposition only needs the answer), so it becomes a [`Witness`] only when
    /// asked for, or before a removal renumbers the outliers it names.
    rejection: Option<(Vec<Tag>, Vec<BigRational>)>,
    witness: OnceCell<Witness>,
    overflow: bool,
    stats: Stats,
    rel: Vec<i64>,
    lift: Vec<i64>,
    /// Scratch of the float runs.
    float_scratch: FloatScratch,
    /// Scratch: the powers of two of [`float::power_of_two_scale`] for `max_abs`.
    scale: Vec<f64>,
    /// The diagonal map of `scale`, set in place at each solve (a new one per solve was two
    /// allocations of each).
    scaled: LinearMap,
    /// Work since the last reset, and its limit.
    meter: Meter,
}

impl Recognizer {
    /// A recognizer for `basis`, with points taken relative to `origin`.
    ///
    /// Returns `None` if `origin` does not have the basis' point dimension.
    pub fn new(basis: Arc<dyn Basis>, origin: &[i64]) -> Option<Recognizer> {
        let (pd, n) = (basis.point_dim(), basis.dim());
        if origin.len() != pd {
            return None;
        }
        Some(Recognizer {
            origin: origin.to_vec(),
            inliers: LiftedSet::new(pd, n),
            upper: LiftedSet::new(pd, n),
            lower: LiftedSet::new(pd, n),
            max_abs: vec![0; n],
            moments: Moments::new(n),
            whiten: false,
            simplex: Simplex::default(),
            cert: None,
            cert_valid: false,
            rejection: None,
            witness: OnceCell::new(),
            overflow: false,
            stats: Stats::default(),
            rel: vec![0; pd],
            lift: vec![0; n],
            float_scratch: FloatScratch::default(),
            scale: Vec::with_capacity(n),
            scaled: LinearMap::diagonal(&vec![1.0; n]),
            meter: Meter::unlimited(),
            basis,
        })
    }

    /// Empties the sets and moves the local origin (keeps allocations and statistics).
    pub fn reset(&mut self, origin: &[i64]) {
        debug_assert_eq!(origin.len(), self.origin.len());
        self.origin.clear();
        self.origin.extend_from_slice(origin);
        self.inliers.clear();
        self.upper.clear();
        self.lower.clear();
        self.max_abs.iter_mut().for_each(|m| *m = 0);
        self.moments.clear();
        self.whiten = false;
        self.simplex.clear();
        self.cert = None;
        self.cert_valid = false;
        self.forget_witness();
        self.overflow = false;
        self.meter.spent = 0;
    }

    /// Limits the work of this piece of queries: once more than `limit` work units have been
    /// spent since the last [`reset`](Recognizer::reset) (this one's included), a query that
    /// needs a solve answers [`Outcome::OverBudget`] instead (the limit stays across resets).
    /// Units are counted, not timed (about a nanosecond each: one multiply-add of a float
    /// support scan; rational solves are charged `(n+1)³` microseconds), so the answers do
    /// not depend on the machine. Default: no limit.
    pub fn set_work_limit(&mut self, limit: u64) {
        self.meter.limit = limit;
    }

    /// Work units spent since the last reset.
    pub fn work(&self) -> u64 {
        self.meter.spent
    }

    /// The basis.
    pub fn basis(&self) -> &Arc<dyn Basis> {
        &self.basis
    }

    /// Work counters since creation.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Counts `work` as done by this recognizer: the work of an answer remembered from an
    /// earlier query on the same sets, so that the stats stay those of asking again.
    pub(crate) fn count_work(&mut self, work: &Stats) {
        self.stats += work;
    }

    /// Number of inliers.
    pub fn inlier_count(&self) -> usize {
        self.inliers.len()
    }

    /// Number of outliers on `side`.
    pub fn outlier_count(&self, side: Side) -> usize {
        self.set(side).len()
    }

    fn set(&self, side: Side) -> &LiftedSet {
        match side {
            Side::Upper => &self.upper,
            Side::Lower => &self.lower,
        }
    }

    /// Lifts `p − origin` into `self.lift`; false on overflow.
    fn lift_point(&mut self, p: &[i64]) -> bool {
        debug_assert_eq!(p.len(), self.origin.len());
        if relative_into(p, &self.origin, &mut self.rel).is_none() {
            return false;
        }
        if self.basis.lift(&self.rel, &mut self.lift).is_none() {
            return false;
        }
        for (m, v) in self.max_abs.iter_mut().zip(&self.lift) {
            *m = (*m).max(v.saturating_abs());
        }
        true
    }

    /// The current certificate's value at the last lifted point.
    fn cert_value(&self) -> Option<i128> {
        self.cert
            .as_ref()
            .and_then(|(a, _)| dot_i128(a, &self.lift))
    }

    /// Adds an inlier (absolute coordinates).
    pub fn add_inlier(&mut self, p: &[i64]) {
        if !self.lift_point(p) {
            self.overflow = true;
            return;
        }
        self.inliers.push(&self.rel, &self.lift);
        if self.cert_valid {
            let v = self.cert_value();
            if let (Some(v), Some((_, e))) = (v, self.cert.as_mut()) {
                e.lower = e.lower.min(v);
                e.upper = e.upper.max(v);
                self.cert_valid = e.separates();
            } else {
                self.cert_valid = false;
            }
        }
    }

    /// Adds an outlier on `side` (absolute coordinates).
    pub fn add_outlier(&mut self, p: &[i64], side: Side) {
        if !self.lift_point(p) {
            self.overflow = true;
            return;
        }
        match side {
            Side::Upper => self.upper.push(&self.rel, &self.lift),
            Side::Lower => self.lower.push(&self.rel, &self.lift),
        }
        if self.cert_valid {
            let v = self.cert_value();
            if let (Some(v), Some((_, e))) = (v, self.cert.as_mut()) {
                match side {
                    Side::Upper => e.above = Some(e.above.map_or(v, |m| m.min(v))),
                    Side::Lower => e.below = Some(e.below.map_or(v, |m| m.max(v))),
                }
                self.cert_valid = e.separates();
            } else {
                self.cert_valid = false;
            }
        }
    }

    /// Removes one outlier equal to `p` from `side`; returns false if there is none.
    ///
    /// A removal only relaxes the problem: a valid certificate stays valid (its extremes are
    /// recomputed exactly). The warm-start simplex is dropped, since its vertices name
    /// outliers by index.
    pub fn remove_outlier(&mut self, p: &[i64], side: Side) -> bool {
        // The last answer's witness names outliers by index: made now, before a removal
        // renumbers them.
        if self.rejection.is_some() {
            let _ = self.witness();
        }
        // A point too far from the origin to be lifted was never added.
        let Some(rel) = relative(p, &self.origin) else {
            return false;
        };
        let set = match side {
            Side::Upper => &mut self.upper,
            Side::Lower => &mut self.lower,
        };
        self.meter.charge(set.len() as u64);
        let Some(i) = set.find(&rel) else {
            return false;
        };
        set.swap_remove(i);
        self.simplex.clear();
        if self.cert_valid {
            if let Some((a, e)) = self.cert.as_mut() {
                let sets = Sets {
                    inliers: &self.inliers,
                    upper: &self.upper,
                    lower: &self.lower,
                };
                self.meter.charge(scan_cost(&sets));
                match verify_certificate(&sets, a) {
                    Some(new) => *e = new,
                    None => self.cert_valid = false,
                }
            }
        }
        true
    }

    /// The certificate of the last [`Outcome::Described`] answer, if the sets have not changed
    /// since in a way that breaks it.
    pub fn certificate(&self) -> Option<Certificate> {
        if !self.cert_valid {
            return None;
        }
        let (a, e) = self.cert.as_ref()?;
        Some(Certificate {
            origin: self.origin.clone(),
            coefficients: a.clone(),
            extremes: *e,
        })
    }

    /// Copies the current certificate into `out`, reusing its allocations (no allocation on
    /// the hot path of a decomposition). Returns false, leaving `out` alone, when there is
    /// none (see [`Recognizer::certificate`]).
    pub fn certificate_into(&self, out: &mut Certificate) -> bool {
        if !self.cert_valid {
            return false;
        }
        let Some((a, e)) = self.cert.as_ref() else {
            return false;
        };
        out.origin.clone_from(&self.origin);
        out.coefficients.clone_from(a);
        out.extremes = *e;
        true
    }

    /// The witness of the last [`Outcome::NotDescribed`] answer.
    pub fn witness(&self) -> Option<&Witness> {
        let (tags, weights) = self.rejection.as_ref()?;
        Some(
            self.witness
                .get_or_init(|| self.witness_of(tags, weights.clone())),
        )
    }

    /// No witness any more (a new query, or new sets).
    fn forget_witness(&mut self) {
        self.rejection = None;
        self.witness.take();
    }

    /// Decides whether the current sets are described.
    pub fn recognize(&mut self) -> Outcome {
        self.stats.queries += 1;
        self.forget_witness();
        if self.overflow {
            self.stats.undecided += 1;
            return Outcome::Undecided;
        }
        if self.cert_valid {
            self.stats.certificate_reused += 1;
            return Outcome::Described;
        }
        let before = self.meter.spent;
        let outcome = if self.meter.exhausted() {
            self.cert_valid = false;
            Outcome::OverBudget
        } else {
            self.solve()
        };
        self.stats.work += self.meter.spent - before;
        match outcome {
            Outcome::Undecided => self.stats.undecided += 1,
            Outcome::OverBudget => self.stats.over_budget += 1,
            _ => {}
        }
        outcome
    }

    fn accept(&mut self, a: Vec<i64>, e: Extremes) -> Outcome {
        self.cert = Some((a, e));
        self.cert_valid = true;
        Outcome::Described
    }

    fn solve(&mut self) -> Outcome {
        let n = self.max_abs.len();
        let sets = Sets {
            inliers: &self.inliers,
            upper: &self.upper,
            lower: &self.lower,
        };
        if sets.is_empty() {
            // Nothing to separate: the zero function describes any set of inliers.
            return self.accept(vec![0; n], Extremes::default());
        }
        self.stats.float_runs += 1;
        // The float runs in power-of-two scaled coordinates, or in whitened ones (better
        // conditioned when the liftings are strongly correlated, see the `conditioning`
        // module) once the piece has needed them. When both may be used, the first one gives
        // up at its first stall, the other one takes over, and the first one has a thorough
        // try last. Each attempt is warm-started from the simplex the previous one left.
        power_of_two_scale_into(&self.max_abs, &mut self.scale);
        self.scaled.set_diagonal(&self.scale);
        let scaled = &self.scaled;
        let mut run = |map: &LinearMap, thorough: bool| {
            float_decide(
                sets,
                map,
                &mut self.simplex,
                &self.max_abs,
                &mut self.stats,
                thorough,
                &mut self.float_scratch,
                &mut self.meter,
            )
        };
        let may_whiten = self.inliers.len() >= LinearMap::min_points(n);
        let first = if self.whiten {
            self.moments.catch_up(&self.inliers);
            LinearMap::whitening(&self.moments)
        } else {
            None
        };
        let answer = match first {
            Some(w) => run(&w, false)
                .or_else(|| run(scaled, true))
                .or_else(|| run(&w, true)),
            None => {
                let mut answer = run(scaled, !may_whiten);
                if answer.is_none() && may_whiten {
                    self.moments.catch_up(&self.inliers);
                    answer = match LinearMap::whitening(&self.moments) {
                        Some(w) => {
                            self.whiten = true;
                            run(&w, true).or_else(|| run(scaled, true))
                        }
                        None => run(scaled, true),
                    };
                    self.stats.whitened += u64::from(self.whiten);
                }
                answer
            }
        };
        match answer {
            Some(FloatAnswer::Described(a, e)) => return self.accept(a, e),
            Some(FloatAnswer::NotDescribed(tags, weights)) => return self.reject(tags, weights),
            None => {}
        }
        if self.meter.exhausted() {
            self.cert_valid = false;
            return Outcome::OverBudget;
        }
        // The float run could not prove its answer: decide in exact arithmetic.
        self.stats.exact_fallbacks += 1;
        let warm: Vec<Tag> = self.simplex.tags();
        self.simplex.clear();
        let dec = decide_exactly(&sets, &warm, &self.max_abs, &mut self.meter);
        match dec {
            ExactDecision::Described(a, e) => self.accept(a, e),
            ExactDecision::NotDescribed(tags, weights) => self.reject(tags, weights),
            ExactDecision::Undecided => {
                self.cert_valid = false;
                Outcome::Undecided
            }
            ExactDecision::OverBudget => {
                self.cert_valid = false;
                Outcome::OverBudget
            }
        }
    }

    fn reject(&mut self, tags: Vec<Tag>, weights: Vec<BigRational>) -> Outcome {
        self.rejection = Some((tags, weights));
        self.witness.take();
        self.cert_valid = false;
        Outcome::NotDescribed
    }

    /// The witness of the pairs `tags` (indices in the current sets) with `weights`, in
    /// absolute coordinates.
    fn witness_of(&self, tags: &[Tag], weights: Vec<BigRational>) -> Witness {
        let abs = |rel: &[i64]| -> Vec<i64> {
            rel.iter().zip(&self.origin).map(|(a, b)| a + b).collect()
        };
        let pairs = tags
            .iter()
            .map(|t| {
                let inl = abs(self.inliers.point(t.inlier as usize));
                let out = abs(self.set(t.side).point(t.outlier as usize));
                (inl, out, t.side)
            })
            .collect();
        Witness {
            origin: self.origin.clone(),
            pairs,
            weights,
        }
    }
}

/// The answer of [`recognize`]: the outcome and the proof that goes with it.
#[derive(Clone, Debug)]
pub struct Recognition {
    /// Whether the set is described.
    pub outcome: Outcome,
    /// The layer, when [`Outcome::Described`].
    pub certificate: Option<Certificate>,
    /// The proof that no layer exists, when [`Outcome::NotDescribed`].
    pub witness: Option<Witness>,
}

/// Decides one recognition problem from scratch (convenience for tests and one-off use);
/// the origin is the first inlier.
///
/// ```
/// use layertrace::{recognize, Model, Outcome, Recognition};
/// use std::sync::Arc;
/// let basis = Arc::new(Model::Line.basis());
/// // Three collinear points, one point above the line and one below: described.
/// let inliers = vec![vec![0, 0], vec![2, 1], vec![4, 2]];
/// let r = recognize(basis.clone(), &inliers, &[vec![0, 1]], &[vec![4, 1]]);
/// assert_eq!(r.outcome, Outcome::Described);
/// let c = r.certificate.unwrap();
/// assert!(inliers.iter().all(|p| {
///     let v = c.value(&*basis, p).unwrap();
///     c.extremes.lower <= v && v <= c.extremes.upper
/// }));
/// // An "above" point between two inliers: no line layer has it strictly above, and the
/// // witness proves it exactly.
/// let Recognition { outcome, witness, .. } =
///     recognize(basis.clone(), &[vec![0, 0], vec![4, 0]], &[vec![2, 0]], &[]);
/// assert_eq!(outcome, Outcome::NotDescribed);
/// assert!(witness.unwrap().verify(&*basis));
/// ```
pub fn recognize(
    basis: Arc<dyn Basis>,
    inliers: &[Vec<i64>],
    upper: &[Vec<i64>],
    lower: &[Vec<i64>],
) -> Recognition {
    let origin = inliers
        .first()
        .cloned()
        .unwrap_or_else(|| vec![0; basis.point_dim()]);
    let Some(mut r) = Recognizer::new(basis, &origin) else {
        return Recognition {
            outcome: Outcome::Undecided,
            certificate: None,
            witness: None,
        };
    };
    for p in inliers {
        r.add_inlier(p);
    }
    for p in upper {
        r.add_outlier(p, Side::Upper);
    }
    for p in lower {
        r.add_outlier(p, Side::Lower);
    }
    Recognition {
        outcome: r.recognize(),
        certificate: r.certificate(),
        witness: r.witness().cloned(),
    }
}

#[cfg(test)]
mod tests;
