//! [`Stats`]: counters of the recognizer's work, for benchmarks and reports.

/// Counters of the work done, for benchmarks and reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Calls to [`Recognizer::recognize`](crate::Recognizer::recognize).
    pub queries: u64,
    /// Queries answered by the previous certificate alone.
    pub certificate_reused: u64,
    /// Float GJK runs.
    pub float_runs: u64,
    /// Float GJK iterations, in all.
    pub float_iterations: u64,
    /// Queries whose float runs stalled in scaled coordinates and went on in whitened ones
    /// (the piece's later queries then try whitened coordinates first).
    pub whitened: u64,
    /// Queries that needed the exact fallback.
    pub exact_fallbacks: u64,
    /// Queries answered [`Outcome::Undecided`](crate::Outcome::Undecided).
    pub undecided: u64,
    /// Queries answered [`Outcome::OverBudget`](crate::Outcome::OverBudget).
    pub over_budget: u64,
    /// Work units spent (see [`Recognizer::set_work_limit`](crate::Recognizer::set_work_limit)).
    pub work: u64,
}

impl std::ops::AddAssign<&Stats> for Stats {
    /// Adds another set of counters.
    fn add_assign(&mut self, o: &Stats) {
        self.queries += o.queries;
        self.certificate_reused += o.certificate_reused;
        self.float_runs += o.float_runs;
        self.float_iterations += o.float_iterations;
        self.whitened += o.whitened;
        self.exact_fallbacks += o.exact_fallbacks;
        self.undecided += o.undecided;
        self.over_budget += o.over_budget;
        self.work += o.work;
    }
}

impl std::ops::Sub<&Stats> for &Stats {
    type Output = Stats;

    /// The counters of the work done since `earlier` (counters of the same recognizer, taken
    /// earlier: every field is at least `earlier`'s).
    fn sub(self, earlier: &Stats) -> Stats {
        Stats {
            queries: self.queries - earlier.queries,
            certificate_reused: self.certificate_reused - earlier.certificate_reused,
            float_runs: self.float_runs - earlier.float_runs,
            float_iterations: self.float_iterations - earlier.float_iterations,
            whitened: self.whitened - earlier.whitened,
            exact_fallbacks: self.exact_fallbacks - earlier.exact_fallbacks,
            undecided: self.undecided - earlier.undecided,
            over_budget: self.over_budget - earlier.over_budget,
            work: self.work - earlier.work,
        }
    }
}
