//! The optimal cover: the fewest grown pieces that cover a contour, the first cut included.
//!
//! # The pieces
//! The candidates are the grown pieces (see [`reach`](super::reach)): `i ..= j` for every
//! `j ≤ reach(i)`, each with every prefix described, like the greedy's. Consecutive pieces
//! join as the greedy's do: the next piece starts at the point after the last one's last
//! point, so the pieces partition the contour's points and [`crate::contour_path`] draws
//! them unchanged.
//!
//! # The shortest cycle
//! With cuts at positions `0 … 2n` (a cut at `c` starts a piece at point `c mod n`), a piece
//! from `c` may end at any point before `e(c) = reach(c) + 1`. The positions reachable from
//! a cut `s` in at most `t` pieces are then a whole interval `s ..= R_t`, with
//! `R_{t+1} = max e(q)` over `q ≤ R_t` (a jump game): the next cut after `c` is best taken
//! at `nxt(c)`, the `q ∈ (c, e(c)]` of largest `e(q)`, and the pieces from `s` needed to come
//! round to `s + n` are the fewest `t` with `e(nxt^{t−1}(s)) ≥ s + n`. Binary lifting over
//! `nxt` gives that `t` for every start `s` in `O(n log t)`; the smallest wins, the first
//! such start on ties. A contour that does not close (open chains, and the IPOL convention's
//! closed chains, which repeat their first point at the end) is covered from index 0 alone.
//!
//! # Settling only the reaches that matter
//! The sweep leaves most reaches bounded, not exact (see [`reach`](super::reach)). The
//! search runs on the upper bounds: a cover found there with pieces within the lower bounds
//! is a real cover, and no real cover has fewer pieces, so it is optimal. Otherwise the
//! starts of the pieces that went beyond their lower bounds are settled (made exact), with
//! the middles of the unsettled runs beside them (reaches grow along a run, so the next try
//! is bisected rather than walked), and the search runs again; after
//! [`MAX_ROUNDS`] rounds every start is settled. When not even the upper bounds allow fewer
//! pieces than the greedy's, the greedy's pieces are kept without settling anything.
//!
//! Minimality holds among covers by grown pieces, and the greedy's cover is one of them
//! (its starts are grown exactly as the greedy grows them), so the optimal cover never has
//! more pieces. When it has as many, the greedy's pieces are kept as they are. Otherwise the
//! contour is rotated to start at the first cut, and every piece is recognized anew, origin
//! at its first point, for its certificate (grown one point at a time, as the greedy grows,
//! if the one-shot query fails within the budget; should that fail too, the contour keeps
//! the greedy's pieces).

use super::reach::Reach;
use super::window::{Stop, Window};
use super::{piece_outliers, xy, OutlierRule, Outliers, Piece, WorkBudget};
use crate::pixel::Pixel;
use crate::recognize::{Certificate, Outcome, Recognizer, Side};

/// Decomposes one contour with the fewest grown pieces (see the module documentation).
/// `closed`: the contour's last point is followed by its first (pieces may wrap round).
///
/// Returns the rotation `s` and the pieces of the rotated contour (`points[s..]` followed
/// by `points[..s]`); `s` is 0 when the contour keeps its start, always so when it is not
/// `closed`.
pub fn optimal_points(
    points: &[Pixel],
    closed: bool,
    rec: &mut Recognizer,
    rule: OutlierRule,
    budget: WorkBudget,
) -> (usize, Vec<Piece>) {
    let n = points.len();
    if n <= 2 {
        return (0, super::decompose_points_within(points, rec, rule, budget));
    }
    let mut reach = Reach::new(points, closed, rec, rule, budget);
    let bound = reach.greedy.len();
    let mut rounds = 0;
    let (s, cuts, upper) = loop {
        let upper = reach.upper();
        let ends: Vec<usize> = upper.iter().map(|&l| l + 1).collect();
        let found = if closed {
            fewest_round(&ends, bound)
        } else {
            Some((0, fewest_from_start(&ends))).filter(|(_, c)| c.len() < bound)
        };
        // Not even the upper bounds allow fewer pieces than the greedy's.
        let Some((s, cuts)) = found else {
            return (0, reach.greedy);
        };
        // The pieces of that cover beyond the lower bound of their start: settle those
        // starts (all of them after many rounds) and try again.
        let low = reach.lower();
        let starts: Vec<usize> = if rounds >= MAX_ROUNDS {
            (0..n).filter(|&i| !reach.is_exact(i)).collect()
        } else {
            cuts.iter()
                .enumerate()
                .filter(|&(k, &c)| {
                    let end = cuts.get(k + 1).copied().unwrap_or(s + n);
                    end - 1 > low[c % n] + (c - c % n)
                })
                .map(|(_, &c)| c % n)
                .collect()
        };
        let settled = !starts.is_empty();
        for c in starts {
            // Also the middles of the unsettled runs beside it: reaches grow along a run
            // between hazards, so the cover's next try is bisected instead of walked.
            let run = |step: &dyn Fn(usize) -> usize| {
                let mut k = c;
                let mut len = 0;
                while len < n && !reach.is_exact(step(k)) {
                    k = step(k);
                    len += 1;
                }
                len
            };
            let before = run(&|k| (k + n - 1) % n);
            let after = run(&|k| (k + 1) % n);
            for i in [
                c,
                (c + n - before.div_ceil(2)) % n,
                (c + after.div_ceil(2)) % n,
            ] {
                reach.settle(i, low[i], rec);
            }
        }
        if !settled {
            break (s, cuts, upper);
        }
        rounds += 1;
    };
    let rotated: Vec<Pixel> = points[s..].iter().chain(&points[..s]).copied().collect();
    let mut pieces = Vec::with_capacity(cuts.len());
    for (k, &c) in cuts.iter().enumerate() {
        let end = cuts.get(k + 1).copied().unwrap_or(s + n);
        let (first, last) = (c - s, end - 1 - s);
        let full = c % n;
        let maximal = reach.is_exact(full) && end - 1 == upper[full] + (c - full);
        let Some(certificate) = certify(&rotated, first, last, rec, rule, budget) else {
            return (0, reach.greedy);
        };
        pieces.push(Piece {
            first,
            last,
            certificate,
            cut: if maximal { reach.cut(full) } else { None },
        });
    }
    (s, pieces)
}

/// Rounds of settling the starts a candidate cover needs before all are settled.
const MAX_ROUNDS: usize = 40;

/// The cuts from 0 of the fewest pieces covering `0..n` (`ends[c]`: exclusive end of the
/// longest piece from `c`, at most `n`), by layers of the jump game.
fn fewest_from_start(ends: &[usize]) -> Vec<usize> {
    let n = ends.len();
    let mut cuts = vec![0];
    let (mut lo, mut hi) = (0, ends[0]);
    while hi < n {
        // The cut in the last layer from which the next piece reaches furthest.
        let mut best = hi;
        for q in lo + 1..=hi {
            if ends[q] >= ends[best] {
                best = q;
            }
        }
        cuts.push(best);
        lo = hi;
        hi = ends[best];
    }
    cuts
}

/// Position of the largest value of `e` on an interval, ties to the right: a segment tree.
struct ArgMax<'a> {
    e: &'a [usize],
    size: usize,
    tree: Vec<u32>,
}

impl<'a> ArgMax<'a> {
    fn new(e: &'a [usize]) -> ArgMax<'a> {
        let size = e.len().next_power_of_two();
        let mut tree = vec![0u32; 2 * size];
        for (i, t) in tree[size..].iter_mut().enumerate() {
            *t = i.min(e.len() - 1) as u32;
        }
        let mut a = ArgMax { e, size, tree };
        for i in (1..size).rev() {
            a.tree[i] = a.better(a.tree[2 * i], a.tree[2 * i + 1]);
        }
        a
    }

    fn better(&self, a: u32, b: u32) -> u32 {
        let (ea, eb) = (self.e[a as usize], self.e[b as usize]);
        if ea > eb || (ea == eb && a > b) {
            a
        } else {
            b
        }
    }

    /// The best position in `lo..=hi`.
    fn query(&self, lo: usize, hi: usize) -> usize {
        let (mut l, mut r) = (lo + self.size, hi + self.size + 1);
        let mut best = lo as u32;
        while l < r {
            if l & 1 == 1 {
                best = self.better(best, self.tree[l]);
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                best = self.better(best, self.tree[r]);
            }
            l /= 2;
            r /= 2;
        }
        best as usize
    }
}

/// The first start `s < n` and the cuts (positions `s ≤ c < s + n`) of the fewest pieces
/// covering the closed contour, if fewer than `bound`; `ends[c]` is the exclusive end of the
/// longest piece from `c` (at most `c + n`).
fn fewest_round(ends: &[usize], bound: usize) -> Option<(usize, Vec<usize>)> {
    let n = ends.len();
    let m = 2 * n;
    let e: Vec<usize> = (0..m)
        .map(|p| if p < n { ends[p] } else { ends[p - n] + n })
        .collect();
    let tree = ArgMax::new(&e);
    let nxt: Vec<u32> = (0..m)
        .map(|p| {
            let hi = e[p].min(m - 1);
            if hi <= p {
                p as u32
            } else {
                tree.query(p + 1, hi) as u32
            }
        })
        .collect();
    // up[j][p] = nxt^(2^j)(p), for 2^levels > bound.
    let levels = (usize::BITS - bound.leading_zeros()).max(1) as usize;
    let mut up = vec![nxt];
    for j in 1..levels {
        let prev = &up[j - 1];
        let next: Vec<u32> = prev.iter().map(|&q| prev[q as usize]).collect();
        up.push(next);
    }
    let mut best: Option<(usize, usize)> = None;
    for s in 0..n {
        let target = s + n;
        let t = if e[s] >= target {
            1
        } else {
            let (mut pos, mut t) = (s, 1usize);
            for j in (0..levels).rev() {
                let q = up[j][pos] as usize;
                if e[q] < target {
                    pos = q;
                    t += 1 << j;
                }
            }
            t + 1
        };
        if t < best.map_or(bound, |b| b.1) {
            best = Some((s, t));
        }
    }
    let (s, _) = best?;
    let mut cuts = vec![s];
    let mut pos = s;
    while e[pos] < s + n {
        pos = up[0][pos] as usize;
        cuts.push(pos);
    }
    Some((s, cuts))
}

/// The certificate of the piece `first..=last` of `points`, origin at its first point: one
/// query on the whole piece, or else growth from its first point as the greedy grows.
fn certify(
    points: &[Pixel],
    first: usize,
    last: usize,
    rec: &mut Recognizer,
    rule: OutlierRule,
    budget: WorkBudget,
) -> Option<Certificate> {
    let mut w = Window::new(points, rule);
    let mut certificate = w.begin(rec, first);
    if last == first {
        return Some(certificate);
    }
    let Outliers { right, left } = piece_outliers(points, first, last, rule);
    for p in &points[first + 1..=last] {
        rec.add_inlier(&xy(*p));
    }
    for q in &right {
        rec.add_outlier(&xy(*q), Side::Upper);
    }
    for q in &left {
        rec.add_outlier(&xy(*q), Side::Lower);
    }
    rec.set_work_limit(budget.limit(last + 1 - first));
    if rec.recognize() == Outcome::Described && rec.certificate_into(&mut certificate) {
        return Some(certificate);
    }
    let mut certificate = w.begin(rec, first);
    match w.grow(rec, last, budget, &mut certificate) {
        Stop::End => Some(certificate),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pieces per start of the layers and of the lifting agree with a plain search.
    #[test]
    fn jump_game_on_a_cycle() {
        // ends[c] exclusive; from 1 the piece reaches far, from 0 not.
        let ends = vec![2, 6, 3, 5, 6, 7];
        let (s, cuts) = fewest_round(&ends, 6).unwrap();
        // From 1: 1..6 then 0 (6) alone → 2 pieces; from 0: 0..2, 1?…
        assert_eq!(cuts.len(), 2, "{s} {cuts:?}");
        assert_eq!(fewest_from_start(&[2, 6, 3, 5, 6, 6]), vec![0, 1]);
    }
}
