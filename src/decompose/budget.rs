//! The work budget of a piece, and why a piece ended early.

/// How much recognizer work a piece of the greedy may take, in work units (about a
/// nanosecond each; counted, never timed, so the decomposition is the same on every machine
/// and thread count): [`base`](WorkBudget::base) plus [`per_point`](WorkBudget::per_point)
/// for each point of the piece. A piece whose next query would exceed it ends there
/// ([`Cut::Budget`]). With the per-point part, the work of a whole contour is at most
/// `(base + per_point) ×` its points: the time per contour pixel is bounded whatever the
/// shape.
///
/// What is counted (see [`Recognizer::set_work_limit`](crate::Recognizer::set_work_limit)):
/// the solves of queries that the previous certificate does not answer, that is scans of the
/// piece's point sets (`O(points · n)` each, `n` the basis dimension) and exact rational
/// solves (`(n + 1)³` big-rational operations).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WorkBudget {
    /// Units any piece may take.
    pub base: u64,
    /// Further units per point of the piece.
    pub per_point: u64,
}

impl WorkBudget {
    /// No limit: every piece is grown as far as the greedy goes (the paper's decomposition).
    pub const UNLIMITED: WorkBudget = WorkBudget {
        base: u64::MAX,
        per_point: 0,
    };

    /// The default: 2 ms plus 5 µs per point, nominally. The pieces of the bundled samples
    /// take at most about 1.1 million units in the conic model (0.1 million for circles),
    /// and their longest ones (466 points) 2 300 units per point; the exact fallback of
    /// poly:6 (dimension 27) costs 22 million units an iteration and is not afforded. The
    /// work of a growing piece grows faster than its length (each solve scans the piece, and
    /// the solves per point grow with the piece: 35 for 250 points, 69 for 1 000 on the
    /// one-pixel spiral), so the per-point part is what keeps the cost per contour pixel
    /// flat on long contours.
    pub const DEFAULT: WorkBudget = WorkBudget {
        base: 2_000_000,
        per_point: 5_000,
    };

    /// The units a piece of `points` points may take.
    pub fn limit(&self, points: usize) -> u64 {
        self.base
            .saturating_add(self.per_point.saturating_mul(points as u64))
    }
}

impl Default for WorkBudget {
    fn default() -> WorkBudget {
        WorkBudget::DEFAULT
    }
}

/// Why a piece ended although the next point might have extended it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cut {
    /// The piece's [`WorkBudget`] ran out.
    Budget,
    /// The recognizer could decide neither way (liftings overflowing `i64`, or the exact
    /// run's guard cap).
    Undecided,
}

impl Cut {
    /// `"budget"` or `"undecided"`, as in the JSON output.
    pub fn name(&self) -> &'static str {
        match self {
            Cut::Budget => "budget",
            Cut::Undecided => "undecided",
        }
    }
}
