//! The reach of every start: for each index `i` of a contour, the last index of the longest
//! *grown* piece starting at `i` — the piece the greedy's growth from `i` would give, every
//! prefix of it described (module documentation of [`crate::decompose`]).
//!
//! # Why grown pieces, and what sliding the start costs
//! "Described" is not closed under taking sub-pieces here: a piece's outliers are the
//! neighbours of its interior points that are not its own pixels, so dropping an end point
//! can turn it into an outlier, and a prefix may have an outlier that a longer piece holds
//! as a pixel. The pieces the optimal cover uses are therefore the grown ones, those the
//! greedy's growth accepts: every prefix of them is described (as for the greedy's own
//! pieces), so any prefix of a grown piece is grown, and the reach of `i` says exactly which
//! pieces start at `i`: `i ..= j` for every `j ≤ reach(i)`.
//!
//! Sliding the start from `i` to `i + 1` (a saturated segmentation, as DGtal's
//! `SaturatedSegmentation`, with the same amortization): the prefixes `i + 1 ..= j` of the
//! window have a subset of the constraints of the prefixes `i ..= j` — fewer inliers, fewer
//! interior points — *unless* the dropped point `p_i` becomes an outlier of one of them
//! ([`Window::shift_adds_outlier`]). Without that, they are described and
//! `reach(i + 1) ≥ reach(i)`; whether the window grows further is first asked of the
//! witness that stopped it (still a proof when all its pairs are still inliers and
//! outliers), and only then of the recognizer, reloaded with the window and grown as the
//! greedy grows. With that, the window is grown afresh from `i + 1`.
//!
//! The greedy's own starts (`0`, then one past each greedy piece) are always grown afresh,
//! exactly as the greedy grows them: their reaches are the greedy's piece ends, and the
//! greedy's pieces, certificates and cuts come out of the same sweep.
//!
//! # Work budget
//! Every growth and every reloaded query is limited by [`WorkBudget::limit`] of the window's
//! length, as the greedy's. A window cut by the budget (or undecided) keeps its reach and its
//! cut for the following starts until one of them must be grown afresh: no start retries
//! the query that ran out.

use super::window::{Stop, Window};
use super::{Cut, OutlierRule, Piece, WorkBudget};
use crate::pixel::Pixel;
use crate::recognize::{Certificate, Outcome, Recognizer, Witness};

/// The reaches of every start of a contour, and the greedy's pieces.
#[derive(Clone, Debug)]
pub(crate) struct Reach {
    /// `last[i]`: last index of the longest grown piece from `i` (unwrapped: up to
    /// `i + n − 1` on a closed contour, `n − 1` on an open one).
    pub(crate) last: Vec<usize>,
    /// Why the longest piece from `i` stopped early (work budget, undecided), if it did.
    pub(crate) cut: Vec<Option<Cut>>,
    /// The greedy decomposition (pieces from index 0, not wrapping).
    pub(crate) greedy: Vec<Piece>,
}

/// The reach of every start of `points` (`cyclic`: pieces may wrap around the end).
pub(crate) fn reaches(
    points: &[Pixel],
    cyclic: bool,
    rec: &mut Recognizer,
    rule: OutlierRule,
    budget: WorkBudget,
) -> Reach {
    let n = points.len();
    let cap = |i: usize| if cyclic { i + n - 1 } else { n - 1 };
    let mut last = vec![0; n];
    let mut cut = vec![None; n];
    let mut greedy = Vec::new();
    let mut next_greedy = 0;
    let mut w = Window::new(points, rule);
    // The witness that the window plus its next point is not described, if there is one.
    let mut witness: Option<Witness> = None;
    let mut cert = Certificate {
        origin: vec![0; 2],
        coefficients: vec![0; rec.basis().dim()],
        lower: 0,
        upper: 0,
        above: None,
        below: None,
    };
    for i in 0..n {
        let inherit = i > 0 && i != next_greedy && w.last >= i && !w.shift_adds_outlier();
        if !inherit {
            cert = w.begin(rec, i);
            let mut stop = if i == next_greedy {
                let stop = w.grow(rec, n - 1, budget, &mut cert);
                greedy.push(Piece {
                    first: i,
                    last: w.last,
                    certificate: cert.clone(),
                    cut: stop.cut(),
                });
                next_greedy = w.last + 1;
                stop
            } else {
                Stop::End
            };
            if stop == Stop::End && w.last < cap(i) {
                stop = w.grow(rec, cap(i), budget, &mut cert);
            }
            last[i] = w.last;
            cut[i] = stop.cut();
            witness = match stop {
                Stop::NotDescribed => rec.witness().cloned(),
                _ => None,
            };
            continue;
        }
        w.shift();
        let g = w.last;
        last[i] = g;
        cut[i] = cut[i - 1];
        if cut[i].is_some() || g >= cap(i) {
            continue;
        }
        // Is the window plus its next point described? The last witness may still say no.
        w.push(None);
        if witness.as_ref().is_some_and(|wt| w.holds(wt)) {
            w.pop();
            continue;
        }
        w.load(rec);
        rec.set_work_limit(budget.limit(w.len()));
        let stop = match rec.recognize() {
            Outcome::Described if rec.certificate_into(&mut cert) => {
                w.grow(rec, cap(i), budget, &mut cert)
            }
            Outcome::OverBudget => {
                w.pop();
                Stop::Cut(Cut::Budget)
            }
            Outcome::Undecided => {
                w.pop();
                Stop::Cut(Cut::Undecided)
            }
            _ => {
                w.pop();
                Stop::NotDescribed
            }
        };
        last[i] = w.last;
        cut[i] = stop.cut();
        witness = match stop {
            Stop::NotDescribed => rec.witness().cloned(),
            _ => None,
        };
    }
    Reach { last, cut, greedy }
}
