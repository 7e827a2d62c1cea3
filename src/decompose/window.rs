//! A piece as a window `first..=last` of a contour, kept up to date as either end moves:
//! its pixels and the sides of its interior points' 4-neighbours, counted with multiplicity,
//! so that its outliers (module documentation of [`crate::decompose`]) are known at every
//! moment; and its growth with the incremental [`Recognizer`], the step the greedy repeats.
//!
//! Indices run past the contour's end (`k` stands for `k mod n`, `k < 2n`), so a window of a
//! closed contour may wrap around its first point.

use super::{neighbour_sides, xy, Cut, OutlierRule, WorkBudget};
use crate::pixel::{Pixel, PixelMap};
use crate::recognize::{Certificate, Outcome, Recognizer, Side, Witness};

/// Why [`Window::grow`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stop {
    /// The window reached the last point it was allowed.
    End,
    /// One more point is not described (the recognizer's witness, if any, proves it).
    NotDescribed,
    /// One more point could not be decided.
    Cut(Cut),
}

impl Stop {
    /// The cut of a piece that ended here.
    pub(crate) fn cut(self) -> Option<Cut> {
        match self {
            Stop::Cut(c) => Some(c),
            _ => None,
        }
    }
}

/// Adds one to `map[q]`; returns the new count.
#[inline]
fn inc(map: &mut PixelMap<u32>, q: Pixel) -> u32 {
    let c = map.entry(q).or_default();
    *c += 1;
    *c
}

/// Takes one from `map[q]`, dropping the entry at zero.
#[inline]
fn dec(map: &mut PixelMap<u32>, q: Pixel) {
    if let Some(c) = map.get_mut(&q) {
        *c -= 1;
        if *c == 0 {
            map.remove(&q);
        }
    }
}

/// The points `first..=last` of a contour with the counts that give their outliers.
pub(crate) struct Window<'a> {
    points: &'a [Pixel],
    rule: OutlierRule,
    /// First index (may be `≥ n` only together with `last`).
    pub(crate) first: usize,
    /// Last index, inclusive (`< 2n`).
    pub(crate) last: usize,
    /// Points of the window, with multiplicity.
    pixels: PixelMap<u32>,
    /// How many interior points have each pixel as a RIGHT 4-neighbour.
    right: PixelMap<u32>,
    /// How many interior points have each pixel as a LEFT 4-neighbour.
    left: PixelMap<u32>,
}

impl<'a> Window<'a> {
    /// An empty window of `points` (call [`begin`](Window::begin) or
    /// [`start`](Window::start) before anything else).
    pub(crate) fn new(points: &'a [Pixel], rule: OutlierRule) -> Window<'a> {
        Window {
            points,
            rule,
            first: 0,
            last: 0,
            pixels: PixelMap::default(),
            right: PixelMap::default(),
            left: PixelMap::default(),
        }
    }

    /// The point of index `k` (`k < 2n`), wrapping around the contour.
    #[inline]
    pub(crate) fn at(&self, k: usize) -> Pixel {
        let n = self.points.len();
        self.points[if k >= n { k - n } else { k }]
    }

    /// Number of points of the window.
    pub(crate) fn len(&self) -> usize {
        self.last + 1 - self.first
    }

    /// True when `q` is an outlier of the window on `side`.
    #[inline]
    fn is_outlier(&self, q: &Pixel, side: Side) -> bool {
        let counts = match side {
            Side::Upper => &self.right,
            Side::Lower => &self.left,
        };
        counts.contains_key(q) && (self.rule == OutlierRule::Any || !self.pixels.contains_key(q))
    }

    /// The window of the single point `i` (the recognizer is left alone).
    pub(crate) fn start(&mut self, i: usize) {
        self.pixels.clear();
        self.right.clear();
        self.left.clear();
        self.first = i;
        self.last = i;
        let p = self.at(i);
        inc(&mut self.pixels, p);
    }

    /// [`start`](Window::start) at `i` with `rec` reset to hold its point; returns the
    /// point's certificate (the zero function when the recognizer gives none).
    pub(crate) fn begin(&mut self, rec: &mut Recognizer, i: usize) -> Certificate {
        self.start(i);
        let p = xy(self.at(i));
        rec.reset(&p);
        rec.add_inlier(&p);
        // One point, no outlier: described by the zero function.
        match rec.recognize() {
            Outcome::Described => rec.certificate(),
            _ => None,
        }
        .unwrap_or_else(|| Certificate::zero(p.to_vec(), rec.basis().dim()))
    }

    /// Appends the point after `last`, and tells `rec` (if given) of the sets' changes: the
    /// new point leaves the outliers (rule [`OutlierRule::NotInPiece`]) and becomes an
    /// inlier; the old last point, now interior, brings its neighbours as outliers.
    pub(crate) fn push(&mut self, mut rec: Option<&mut Recognizer>) {
        let p = self.at(self.last + 1);
        if let Some(rec) = rec.as_deref_mut() {
            if self.rule == OutlierRule::NotInPiece && !self.pixels.contains_key(&p) {
                if self.right.contains_key(&p) {
                    rec.remove_outlier(&xy(p), Side::Upper);
                }
                if self.left.contains_key(&p) {
                    rec.remove_outlier(&xy(p), Side::Lower);
                }
            }
            rec.add_inlier(&xy(p));
        }
        inc(&mut self.pixels, p);
        if self.last > self.first {
            let (prev, cur) = (self.at(self.last - 1), self.at(self.last));
            if let Some(sides) = neighbour_sides(prev, cur, p) {
                let free =
                    |w: &Window, q: &Pixel| w.rule == OutlierRule::Any || !w.pixels.contains_key(q);
                for (q, right, left) in sides {
                    if right && inc(&mut self.right, q) == 1 && free(self, &q) {
                        if let Some(rec) = rec.as_deref_mut() {
                            rec.add_outlier(&xy(q), Side::Upper);
                        }
                    }
                    if left && inc(&mut self.left, q) == 1 && free(self, &q) {
                        if let Some(rec) = rec.as_deref_mut() {
                            rec.add_outlier(&xy(q), Side::Lower);
                        }
                    }
                }
            }
        }
        self.last += 1;
    }

    /// Removes the neighbours of the interior point `k` (between `k − 1` and `k + 1`).
    fn forget_interior(&mut self, k: usize) {
        if let Some(sides) = neighbour_sides(self.at(k - 1), self.at(k), self.at(k + 1)) {
            for (q, right, left) in sides {
                if right {
                    dec(&mut self.right, q);
                }
                if left {
                    dec(&mut self.left, q);
                }
            }
        }
    }

    /// Removes the last point (the counts only: a recognizer is out of step afterwards).
    pub(crate) fn pop(&mut self) {
        debug_assert!(self.last > self.first);
        if self.last >= self.first + 2 {
            self.forget_interior(self.last - 1);
        }
        let p = self.at(self.last);
        dec(&mut self.pixels, p);
        self.last -= 1;
    }

    /// Removes the first point (the counts only).
    pub(crate) fn shift(&mut self) {
        debug_assert!(self.last > self.first);
        if self.last >= self.first + 2 {
            self.forget_interior(self.first + 1);
        }
        let p = self.at(self.first);
        dec(&mut self.pixels, p);
        self.first += 1;
    }

    /// Resets `rec` to hold the window's sets, origin at its first point (outliers in sorted
    /// order, so that the recognizer's work does not depend on the history of the counts).
    pub(crate) fn load(&self, rec: &mut Recognizer) {
        rec.reset(&xy(self.at(self.first)));
        for k in self.first..=self.last {
            rec.add_inlier(&xy(self.at(k)));
        }
        for (counts, side) in [(&self.right, Side::Upper), (&self.left, Side::Lower)] {
            let mut out: Vec<Pixel> = counts
                .keys()
                .filter(|q| self.is_outlier(q, side))
                .copied()
                .collect();
            out.sort_unstable();
            for q in out {
                rec.add_outlier(&xy(q), side);
            }
        }
    }

    /// True when every pair of `witness` is an inlier and an outlier (on its side) of the
    /// window: the witness then proves that the window is not described.
    pub(crate) fn holds(&self, witness: &Witness) -> bool {
        let px = |v: &[i64]| match (v.first(), v.get(1)) {
            (Some(&x), Some(&y)) => i32::try_from(x)
                .ok()
                .zip(i32::try_from(y).ok())
                .map(|(x, y)| Pixel::new(x, y)),
            _ => None,
        };
        !witness.pairs.is_empty()
            && witness
                .pairs
                .iter()
                .all(|(s, o, side)| match (px(s), px(o)) {
                    (Some(s), Some(o)) => {
                        self.pixels.contains_key(&s) && self.is_outlier(&o, *side)
                    }
                    _ => false,
                })
    }

    /// Grows the window one point at a time while it is described, up to index `end`, `rec`
    /// holding the window's sets; `certificate` follows the last described window. Each
    /// query may take [`WorkBudget::limit`] of the grown length. On return the window is the
    /// last described one, and `rec` holds it plus the point that failed, if any.
    pub(crate) fn grow(
        &mut self,
        rec: &mut Recognizer,
        end: usize,
        budget: WorkBudget,
        certificate: &mut Certificate,
    ) -> Stop {
        while self.last < end {
            self.push(Some(rec));
            rec.set_work_limit(budget.limit(self.len()));
            let stop = match rec.recognize() {
                Outcome::Described if rec.certificate_into(certificate) => continue,
                Outcome::OverBudget => Stop::Cut(Cut::Budget),
                Outcome::Undecided => Stop::Cut(Cut::Undecided),
                _ => Stop::NotDescribed,
            };
            self.pop();
            return stop;
        }
        Stop::End
    }
}
