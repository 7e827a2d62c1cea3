//! Tiny contours decomposed once per shape: a contour's pieces depend only on its points
//! relative to its first one (every piece is recognized relative to its own first point, in
//! exact integer arithmetic and floats on the same relative values), so the repeated small
//! contours of noise and halftones are decomposed once per shape within a task and the
//! pieces moved to the others (only the certificates' origins change). The recognizer's
//! [`Stats`] of a shape are counted again for each copy, so the decomposition's stats are
//! those of decomposing every contour (a piece cut by its budget is counted once per copy,
//! as its `Cut` is).

use rustc_hash::FxHashMap as HashMap;

use super::Piece;
use crate::contour::Contour;
use crate::recognize::{Recognizer, Stats};

/// What decides a tiny contour's pieces: its [`Contour::tiny_shape`] and whether its pieces
/// may wrap round (see `wraps`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct ShapeKey {
    wraps: bool,
    points: Vec<(i32, i32)>,
}

/// The pieces of the tiny shapes met so far (with their rotation, for optimal covers), their
/// certificates' origins relative to the contour's first point.
#[derive(Debug, Default)]
pub(super) struct PieceMemo {
    pieces: HashMap<ShapeKey, Decomposed>,
    /// The stats of the copies taken from the memo.
    copied: Stats,
}

/// A shape's pieces (rotated by `rotation`), and the recognizer's work on them.
#[derive(Debug)]
struct Decomposed {
    rotation: usize,
    pieces: Vec<Piece>,
    stats: Stats,
}

impl PieceMemo {
    /// The pieces of `contour` (rotated by the returned count, as the cover computed
    /// them): from the memo when its shape is known, otherwise from `decompose` run with
    /// `rec`, kept when the contour is tiny.
    pub(super) fn pieces(
        &mut self,
        contour: &Contour,
        wraps: bool,
        rec: &mut Recognizer,
        decompose: impl FnOnce(&mut Recognizer) -> (usize, Vec<Piece>),
    ) -> (usize, Vec<Piece>) {
        let Some(points) = contour.tiny_shape() else {
            return decompose(rec);
        };
        let key = ShapeKey { wraps, points };
        let first = contour.points[0];
        let shift = |pieces: &[Piece], dx: i64, dy: i64| -> Vec<Piece> {
            pieces
                .iter()
                .map(|p| {
                    let mut p = p.clone();
                    if let [x, y] = p.certificate.origin.as_mut_slice() {
                        *x += dx;
                        *y += dy;
                    }
                    p
                })
                .collect()
        };
        let (fx, fy) = (i64::from(first.x), i64::from(first.y));
        if let Some(d) = self.pieces.get(&key) {
            self.copied += &d.stats;
            return (d.rotation, shift(&d.pieces, fx, fy));
        }
        let before = rec.stats();
        let (rotation, pieces) = decompose(rec);
        let stats = &rec.stats() - &before;
        self.pieces.insert(
            key,
            Decomposed {
                rotation,
                pieces: shift(&pieces, -fx, -fy),
                stats,
            },
        );
        (rotation, pieces)
    }

    /// The stats of the copies taken from the memo so far.
    pub(super) fn copied_stats(&self) -> &Stats {
        &self.copied
    }
}

#[cfg(test)]
mod tests {
    use crate::bitmap::repeated_blob;
    use crate::contour::{trace, Convention};
    use crate::decompose::{decompose_cover, decompose_points, Cover, OutlierRule, WorkBudget};
    use crate::model::Model;
    use crate::recognize::Recognizer;
    use proptest::prelude::*;
    use std::sync::Arc;

    proptest! {
        /// A random blob repeated far apart: every copy's pieces (taken from the memo but
        /// the first) are the pieces a fresh recognizer finds for that contour alone.
        #[test]
        fn memo_pieces_are_the_pieces(
            bits in prop::collection::vec(any::<bool>(), 12),
            offsets in prop::collection::vec((0u32..60, 0u32..60), 1..4),
            model in prop::sample::select(vec![Model::Line, Model::Circle, Model::Conic]),
        ) {
            let mask = repeated_blob(&bits, &offsets);
            let rule = OutlierRule::NotInPiece;
            let contours = trace(&mask, Convention::Default);
            let d = decompose_cover(contours.clone(), model, rule, WorkBudget::default(), Cover::Greedy);
            let basis = Arc::new(model.basis());
            for (c, pieces) in contours.iter().zip(&d.pieces) {
                let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
                let alone = decompose_points(&c.points, &mut rec, rule);
                prop_assert_eq!(pieces, &alone);
            }
        }
    }
}
