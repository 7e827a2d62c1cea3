//! The greedy's short pieces remembered by the steps that decided them: noise, halftones
//! and scans repeat the same few short pieces hundreds of thousands of times.
//!
//! The greedy piece from point `i` depends only on the points it tried, relative to `i`:
//! its window's pixels and outliers come from those points alone (the outliers of interior
//! points, from their neighbours in the window), the recognizer is [`Recognizer::reset`] at
//! `p_i` and works on coordinates relative to it, exactly, and the budget depends on the
//! length only. A piece that failed at point `i + m` is decided by the `m` steps
//! `p_i → p_{i+1} → … → p_{i+m}`; one that reached the contour's last point by the steps to
//! it and the fact that there are no more. So a memo keyed by those steps (3 bits each: the
//! contour is 8-connected) returns the piece bit for bit, its certificate's origin moved to
//! `p_i`.
//!
//! The steps are looked up one at a time, and the first hit is the answer: a stored failure
//! ends every piece that starts with its steps, and a piece that reached the end is only
//! looked up where the contour ends at the same step. (A piece that reached the end of a
//! shorter contour may share its steps with a longer contour's failure; the end flag keeps
//! them apart.)
//!
//! The recognizer's [`Stats`] of a remembered piece are counted again by the recognizer for
//! each copy, so the decomposition's statistics are those of decomposing every piece.

use super::budget::Cut;
use super::window::Stop;
use crate::pixel::Pixel;
use crate::recognize::{Certificate, Extremes, Recognizer, Stats};
use crate::steps::{key, key_of, step, StepMap, MAX_STEPS};

/// Pieces kept before the memo starts again: bounds its memory (about 100 bytes each) on
/// images whose short pieces are all different.
const MAX_ENTRIES: usize = 1 << 17;

/// A remembered piece: its length after its first point, how it ended, its certificate
/// (origin left out), and the recognizer's work on it.
#[derive(Debug)]
struct Grown {
    steps: u8,
    cut: Option<Cut>,
    coefficients: Vec<i64>,
    extremes: Extremes,
    stats: Stats,
}

/// A piece of the greedy found in the memo.
#[derive(Debug)]
pub(super) struct Found {
    /// Index of its last point.
    pub last: usize,
    /// Its certificate, origin at its first point.
    pub certificate: Certificate,
    /// Why it ended, as [`Stop::cut`].
    pub cut: Option<Cut>,
}

/// The short pieces met so far (see the module documentation), for one model, outlier
/// rule and budget.
#[derive(Debug)]
pub(super) struct GreedyMemo {
    pieces: StepMap<Grown>,
}

impl Default for GreedyMemo {
    fn default() -> GreedyMemo {
        GreedyMemo {
            pieces: StepMap::new(MAX_ENTRIES),
        }
    }
}

impl GreedyMemo {
    /// The greedy piece of `points` from `i`, if remembered (its work counted by `rec`).
    pub(super) fn find(&self, points: &[Pixel], i: usize, rec: &mut Recognizer) -> Option<Found> {
        let n = points.len();
        let mut bits = 0u64;
        // (No key is longer than the memo's longest: none at all when it is empty.)
        for m in 1..=MAX_STEPS.min(n - 1 - i).min(self.pieces.longest()) {
            bits |= step(points[i + m - 1], points[i + m])? << (3 * (m - 1));
            let hit = self.pieces.get(key(bits, m, false)).or_else(|| {
                (i + m + 1 == n)
                    .then(|| self.pieces.get(key(bits, m, true)))
                    .flatten()
            });
            if let Some(g) = hit {
                rec.count_work(&g.stats);
                let p = points[i];
                return Some(Found {
                    last: i + usize::from(g.steps),
                    certificate: Certificate {
                        origin: vec![i64::from(p.x), i64::from(p.y)],
                        coefficients: g.coefficients.clone(),
                        extremes: g.extremes,
                    },
                    cut: g.cut,
                });
            }
        }
        None
    }

    /// Remembers the greedy piece `i..=last` of `points` that ended with `stop`, with the
    /// recognizer's work on it, when short enough.
    pub(super) fn keep(
        &mut self,
        points: &[Pixel],
        i: usize,
        last: usize,
        stop: Stop,
        certificate: &Certificate,
        stats: Stats,
    ) {
        // The steps that decided it: to the point that failed, or to the last one.
        let m = match stop {
            Stop::End => last - i,
            _ => last + 1 - i,
        };
        if m == 0 || m > MAX_STEPS || i + m >= points.len() {
            return;
        }
        let Some(k) = key_of(points[i..=i + m].iter().copied(), stop == Stop::End) else {
            return;
        };
        self.pieces.insert(
            k,
            Grown {
                steps: (last - i) as u8,
                cut: stop.cut(),
                coefficients: certificate.coefficients.clone(),
                extremes: certificate.extremes,
                stats,
            },
        );
    }
}

#[cfg(test)]
mod tests {
    use super::super::{decompose_points_within, greedy_points, OutlierRule, WorkBudget};
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};
    use crate::model::Model;
    use proptest::prelude::*;
    use std::sync::Arc;

    proptest! {
        /// Random noise: the pieces taken from the memo, and the work counted for them, are
        /// what the recognizer finds alone for each contour.
        #[test]
        fn remembered_pieces_are_the_pieces(
            bits in prop::collection::vec(any::<bool>(), 24 * 24),
            model in prop::sample::select(vec![Model::Line, Model::Circle, Model::Conic]),
            rule in prop::sample::select(vec![OutlierRule::NotInPiece, OutlierRule::Any]),
        ) {
            let mask = Mask::from_fn(24, 24, |x, y| bits[(y * 24 + x) as usize]);
            let contours = trace(&mask, Convention::Default);
            let basis = Arc::new(model.basis());
            let budget = WorkBudget::default();
            let mut memo = GreedyMemo::default();
            let mut with = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
            // Twice over: the second pass finds every short piece in the memo.
            for _ in 0..2 {
                for c in &contours {
                    let mut alone = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
                    let expected = decompose_points_within(&c.points, &mut alone, rule, budget);
                    let before = with.stats();
                    let got = greedy_points(&c.points, &mut with, rule, budget, Some(&mut memo));
                    prop_assert_eq!(&got, &expected);
                    prop_assert_eq!(&with.stats() - &before, alone.stats());
                }
            }
            // (Contours of one point have a piece of no step, which is not kept.)
            prop_assert!(contours.iter().all(|c| c.points.len() < 2) || !memo.pieces.is_empty());
        }
    }
}
