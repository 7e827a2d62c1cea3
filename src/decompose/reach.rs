//! The reach of every start: for each index `i` of a contour, the last index `r(i)` of the
//! longest *grown* piece starting at `i` — the piece the greedy's growth from `i` would give,
//! every prefix of it described (module documentation of [`crate::decompose`]).
//!
//! # Why grown pieces
//! "Described" is not closed under taking sub-pieces here: a piece's outliers are the
//! neighbours of its interior points that are not its own pixels, so dropping an end point
//! can turn it into an outlier, and a prefix may have an outlier that a longer piece holds
//! as a pixel. The pieces the optimal cover uses are therefore the grown ones, those the
//! greedy's growth accepts: any prefix of a grown piece is grown, and `r(i)` says exactly
//! which pieces start at `i`: `i ..= j` for every `j ≤ r(i)`.
//!
//! # Sliding the start (a saturated segmentation, as DGtal's `SaturatedSegmentation`)
//! The prefixes `i + 1 ..= j` have a subset of the constraints of the prefixes `i ..= j` —
//! fewer inliers, fewer interior points — unless the dropped point `p_i` becomes an outlier
//! of one of them, which first happens at `j = h(i)` (the *hazard*: `p_i` a 4-neighbour on a
//! side of an interior point, not yet met again). So `r(i + 1) ≥ r(i)` whenever
//! `h(i) > r(i)`, and `r(i) ≤ r(i + 1)` is also an upper bound when `h(i) > r(i + 1) + 1`.
//!
//! One sweep ([`Reach::new`]) gives every start a lower bound, exact at some starts: the
//! greedy's own starts (`0`, then one past each greedy piece) and the starts after a hazard
//! are grown afresh exactly as the greedy grows; a start inheriting its predecessor's reach
//! is exact when the witness that stopped the predecessor still holds (all its pairs still
//! inliers and outliers). Other starts are left with the lower bound: asking the recognizer
//! about each would cost a query from scratch per start. [`Reach::lower`] and
//! [`Reach::upper`] chain the exact values along hazard-free stretches into bounds for
//! every start, and [`Reach::settle`] makes one start exact (window reloaded into the
//! recognizer, grown as the greedy grows), on demand of the shortest-cycle search.
//!
//! # Work budget
//! Every growth and every reloaded query is limited by [`WorkBudget::limit`] of the window's
//! length, as the greedy's. A window cut by the budget (or undecided) counts as exact: its
//! cut is kept, and the starts inheriting it keep it too; no start retries a query that ran
//! out.

use super::window::{Stop, Window};
use super::{neighbour_sides, Cut, OutlierRule, Piece, WorkBudget};
use crate::pixel::{Pixel, PixelMap};
use crate::recognize::{Certificate, Outcome, Recognizer, Witness};

/// The reaches of the starts of one contour, exact or bounded, and the greedy's pieces.
pub(crate) struct Reach<'a> {
    points: &'a [Pixel],
    closed: bool,
    budget: WorkBudget,
    /// The reach found for each start: exact where `exact`, else a lower bound.
    own: Vec<usize>,
    exact: Vec<bool>,
    cut: Vec<Option<Cut>>,
    /// `h(i)`: first `j` at which `p_i` is an outlier of `i + 1 ..= j` (`usize::MAX`: none).
    hazard: Vec<usize>,
    /// The greedy decomposition (pieces from index 0, not wrapping).
    pub(crate) greedy: Vec<Piece>,
    window: Window<'a>,
    certificate: Certificate,
}

impl<'a> Reach<'a> {
    /// The sweep: greedy pieces, exact reaches where they come cheap, lower bounds elsewhere
    /// (`closed`: pieces may wrap round the end).
    pub(crate) fn new(
        points: &'a [Pixel],
        closed: bool,
        rec: &mut Recognizer,
        rule: OutlierRule,
        budget: WorkBudget,
    ) -> Reach<'a> {
        let n = points.len();
        let mut r = Reach {
            points,
            closed,
            budget,
            own: vec![0; n],
            exact: vec![false; n],
            cut: vec![None; n],
            hazard: hazards(points, closed, rule),
            greedy: Vec::new(),
            window: Window::new(points, rule),
            certificate: Certificate::zero(vec![0; 2], rec.basis().dim()),
        };
        let mut w = Window::new(points, rule);
        let mut next_greedy = 0;
        // The witness that the window plus its next point is not described, if known.
        let mut witness: Option<Witness> = None;
        for i in 0..n {
            let inherit =
                i > 0 && i != next_greedy && w.last >= i && r.hazard[i - 1] > r.own[i - 1];
            if !inherit {
                r.certificate = w.begin(rec, i);
                let mut stop = if i == next_greedy {
                    let stop = w.grow(rec, n - 1, budget, &mut r.certificate);
                    r.greedy.push(Piece {
                        first: i,
                        last: w.last,
                        certificate: r.certificate.clone(),
                        cut: stop.cut(),
                    });
                    next_greedy = w.last + 1;
                    stop
                } else {
                    Stop::End
                };
                if stop == Stop::End && w.last < r.cap(i) {
                    stop = w.grow(rec, r.cap(i), budget, &mut r.certificate);
                }
                r.own[i] = w.last;
                r.exact[i] = true;
                r.cut[i] = stop.cut();
                witness = match stop {
                    Stop::NotDescribed => rec.witness().cloned(),
                    _ => None,
                };
                continue;
            }
            w.shift();
            r.own[i] = w.last;
            r.cut[i] = r.cut[i - 1];
            r.exact[i] = r.exact[i - 1] && (r.cut[i].is_some() || w.last >= r.cap(i));
            if r.exact[i] || !r.exact[i - 1] {
                continue;
            }
            w.push(None);
            r.exact[i] = witness.as_ref().is_some_and(|wt| w.holds(wt));
            w.pop();
        }
        r
    }

    /// The last index a piece from `i` may reach: `i + n − 1` round a closed contour.
    fn cap(&self, i: usize) -> usize {
        let n = self.points.len();
        if self.closed {
            i + n - 1
        } else {
            n - 1
        }
    }

    /// Whether the reach of `i` is known exactly.
    pub(crate) fn is_exact(&self, i: usize) -> bool {
        self.exact[i]
    }

    /// Why the longest piece from `i` stopped early, if it did (exact starts only).
    pub(crate) fn cut(&self, i: usize) -> Option<Cut> {
        self.cut[i]
    }

    /// A lower bound of every reach: the reach found, or the previous start's bound when the
    /// shift keeps every prefix described (`h(i − 1)` beyond it).
    pub(crate) fn lower(&self) -> Vec<usize> {
        let mut low = self.own.clone();
        for i in 1..low.len() {
            let prev = low[i - 1];
            if prev >= i && self.hazard[i - 1] > prev && low[i] < prev {
                low[i] = prev.min(self.cap(i));
            }
        }
        low
    }

    /// An upper bound of every reach: the reach where exact, else the next start's bound when
    /// the shift keeps every prefix up to one past it described, else the cap.
    pub(crate) fn upper(&self) -> Vec<usize> {
        let n = self.points.len();
        let mut up = vec![0; n];
        // The bound of the start after the last: round a closed contour, start 0 (exact),
        // one lap on.
        let mut next = if self.closed && self.exact[0] {
            Some(self.own[0] + n)
        } else {
            None
        };
        for i in (0..n).rev() {
            up[i] = if self.exact[i] {
                self.own[i]
            } else {
                match next {
                    Some(u) if self.hazard[i] > u.saturating_add(1) => u.min(self.cap(i)),
                    _ => self.cap(i),
                }
            };
            next = Some(up[i]);
        }
        up
    }

    /// Makes the reach of `i` exact, `low` being a lower bound of it: the window `i ..= low`
    /// is grown, so the recognizer is asked about `low + 1` and grown on from there.
    pub(crate) fn settle(&mut self, i: usize, low: usize, rec: &mut Recognizer) {
        if self.exact[i] {
            return;
        }
        let (cap, budget) = (self.cap(i), self.budget);
        let w = &mut self.window;
        w.start(i);
        while w.last < low.min(cap) {
            w.push(None);
        }
        let stop = if w.last >= cap {
            Stop::End
        } else {
            w.push(None);
            w.load(rec);
            rec.set_work_limit(budget.limit(w.len()));
            match rec.recognize() {
                Outcome::Described if rec.certificate_into(&mut self.certificate) => {
                    w.grow(rec, cap, budget, &mut self.certificate)
                }
                o => {
                    w.pop();
                    match o {
                        Outcome::OverBudget => Stop::Cut(Cut::Budget),
                        Outcome::Undecided => Stop::Cut(Cut::Undecided),
                        _ => Stop::NotDescribed,
                    }
                }
            }
        };
        self.own[i] = w.last;
        self.cut[i] = stop.cut();
        self.exact[i] = true;
    }
}

/// `h(i)` of every start (see the module documentation): the first `j ≤ cap` at which
/// `p_i` is an outlier of `i + 1 ..= j`, that is one past the first interior point `k ≥
/// i + 2` having `p_i` as a 4-neighbour on a side, if `p_i` does not come again before it.
/// Never with [`OutlierRule::Any`].
fn hazards(points: &[Pixel], closed: bool, rule: OutlierRule) -> Vec<usize> {
    let n = points.len();
    if rule == OutlierRule::Any {
        return vec![usize::MAX; n];
    }
    let mut occurrences: PixelMap<Vec<usize>> = PixelMap::default();
    for (k, p) in points.iter().enumerate() {
        occurrences.entry(*p).or_default().push(k);
    }
    let at = |k: usize| points[k % n];
    // The indices `≥ from` (up to `2n` round a closed contour) where `q` lies, in order.
    let after = |q: Pixel, from: usize| -> Vec<usize> {
        let Some(occ) = occurrences.get(&q) else {
            return Vec::new();
        };
        let laps = if closed { 2 } else { 1 };
        let mut v: Vec<usize> = (0..laps)
            .flat_map(|lap| occ.iter().map(move |&k| k + lap * n))
            .filter(|&k| k >= from)
            .collect();
        v.sort_unstable();
        v
    };
    (0..n)
        .map(|i| {
            let p = points[i];
            let cap = if closed { i + n - 1 } else { n - 1 };
            let again = after(p, i + 1).first().copied().unwrap_or(usize::MAX);
            let mut h = usize::MAX;
            for q in [
                Pixel::new(p.x + 1, p.y),
                Pixel::new(p.x - 1, p.y),
                Pixel::new(p.x, p.y + 1),
                Pixel::new(p.x, p.y - 1),
            ] {
                for k in after(q, i + 2) {
                    if k >= again || k + 1 > cap || k + 1 >= h {
                        break;
                    }
                    let sides = neighbour_sides(at(k - 1), at(k), at(k + 1));
                    if sides.is_some_and(|s| s.iter().any(|&(r, a, b)| r == p && (a || b))) {
                        h = k + 1;
                        break;
                    }
                }
            }
            h
        })
        .collect()
}
