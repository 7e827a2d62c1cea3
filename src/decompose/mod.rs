//! Decomposition of contours into pieces described by Digital Level Layers: the paper's
//! greedy, or the optimal cover ([`Cover`]).
//!
//! # Outliers of a piece (paper section 1.3, Figure 7)
//! For a piece `p_i … p_j` of a contour and each interior index `k` in `i+1 … j−1`, every
//! 4-neighbour `q` of `p_k` that is not a pixel of the piece is an outlier:
//! * on the RIGHT if the direction `q − p_k` lies strictly inside the angular sweep from
//!   `p_{k+1} − p_k` to `p_{k−1} − p_k` turning clockwise on screen,
//! * on the LEFT if it lies strictly inside the sweep from `p_{k−1} − p_k` to `p_{k+1} − p_k`,
//! * on both sides at a U-turn (`p_{k−1} = p_{k+1}`), which ends the piece.
//!
//! The piece is described when one layer holds its pixels with every RIGHT outlier strictly
//! above it ([`Side::Upper`]) and every LEFT outlier strictly below ([`Side::Lower`]) — or the
//! reverse, which is the same question for `−f`. For a thick shape traced with the foreground
//! on its left, RIGHT is background and LEFT foreground; the geometric split is what lets
//! one-pixel-thin strokes be recognized.
//!
//! # Greedy
//! The first piece starts at index 0; a piece grows one pixel at a time while it is
//! described; the next piece starts at the first pixel that failed; the last piece ends at
//! the contour's last point. A two-pixel piece has no interior point, hence no outlier, and is
//! always accepted. A prefix of a described piece need not be described: the greedy stops at
//! the first failure all the same. Growth uses the incremental [`Recognizer`].
//!
//! # Optimal cover
//! [`Cover::Optimal`] covers each contour with the fewest pieces that the greedy's growth
//! could give (every prefix described), the first cut anywhere on a closed contour: the
//! reach of every start is found by sliding a window along the contour (`reach` module),
//! then a shortest path round the cycle (`optimal` module). It never has more pieces than
//! the greedy; a closed contour whose optimal cover does not start at its first point is
//! rotated in the [`Decomposition`] to start there.
//!
//! # Work budget
//! A piece may take at most [`WorkBudget::limit`] of its length in recognizer work units
//! (counted, not timed: see [`WorkBudget`]). A query that would exceed it ends the piece at
//! the last length that was certified, marked [`Cut::Budget`]; its certificate is as exact
//! as any other, only the maximality of the greedy is lost. The default budget is far above
//! what the pieces of the bundled samples need in the line, circle and conic models.

use crate::contour::{largest_first, Contour};
use crate::model::{Basis, Model};
use crate::pixel::Pixel;
use crate::pixel_flags::StretchSets;
use crate::recognize::{Certificate, Recognizer, Stats};
use rayon::prelude::*;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};

mod budget;
mod greedy_memo;
mod optimal;
mod reach;
mod shapes;
mod window;
pub use budget::{Cut, WorkBudget};
use greedy_memo::GreedyMemo;
pub use optimal::optimal_points;
use window::Window;

/// One piece of a contour: indices `first..=last` of its points and the layer describing it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Piece {
    /// Index of the first point in the contour.
    pub first: usize,
    /// Index of the last point in the contour (inclusive).
    pub last: usize,
    /// The exact layer: origin `p_first`, RIGHT outliers above, LEFT outliers below.
    pub certificate: Certificate,
    /// Why the piece ended before a point that might have extended it (`None`: it is
    /// maximal, or it ends the contour, or — in an optimal cover — the cover cuts there).
    pub cut: Option<Cut>,
}

impl Piece {
    /// Number of points of the piece.
    pub fn len(&self) -> usize {
        self.last + 1 - self.first
    }

    /// Always false: a piece has at least one point.
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// Which pixels count as outliers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum OutlierRule {
    /// 4-neighbours of interior points that are not pixels of the piece (the documented rule).
    #[default]
    NotInPiece,
    /// 4-neighbours of interior points whatever they are, as the paper authors' code does.
    Any,
}

/// Which cover of each contour by pieces the decomposition computes.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Cover {
    /// The paper's greedy: from the contour's first point, each piece grown while it is
    /// described, the next one started at the point that failed.
    #[default]
    Greedy,
    /// The fewest pieces the greedy's growth could give, cut anywhere round a closed
    /// contour (a shortest path round the cycle); never more pieces than [`Cover::Greedy`].
    Optimal,
}

impl Cover {
    /// `"greedy"` or `"optimal"`, as on the command line and in the JSON output.
    pub fn name(self) -> &'static str {
        match self {
            Cover::Greedy => "greedy",
            Cover::Optimal => "optimal",
        }
    }
}

impl std::fmt::Display for Cover {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Cover {
    type Err = String;

    /// `greedy` or `optimal`.
    fn from_str(s: &str) -> Result<Cover, String> {
        match s {
            "greedy" => Ok(Cover::Greedy),
            "optimal" => Ok(Cover::Optimal),
            _ => Err(format!("unknown cover {s:?} (expected greedy or optimal)")),
        }
    }
}

/// The decomposition of every contour of an image.
#[derive(Clone, Debug)]
pub struct Decomposition {
    /// The model whose layers describe the pieces.
    pub model: Model,
    /// The contours, in tracing order.
    pub contours: Vec<Contour>,
    /// The pieces of each contour, in order along it.
    pub pieces: Vec<Vec<Piece>>,
    /// The outlier rule the pieces were recognized with.
    pub rule: OutlierRule,
    /// The cover the pieces form.
    pub cover: Cover,
    /// Work done by the recognizers (a tiny contour whose shape was already decomposed in
    /// its task counts as if decomposed again).
    pub stats: Stats,
}

impl Decomposition {
    /// Total number of pieces.
    pub fn piece_count(&self) -> usize {
        self.pieces.iter().map(Vec::len).sum()
    }
}

/// `offset` strictly inside the clockwise sweep from `start` spanning `span` steps of 45°.
#[inline]
fn strictly_inside(d: u8, start: u8, end: u8) -> bool {
    let span = match (end + 8 - start) % 8 {
        0 => 8,
        s => s,
    };
    let offset = (d + 8 - start) % 8;
    offset > 0 && offset < span
}

/// The sides of the four 4-neighbours of `cur`, an interior point between `prev` and `next`:
/// `(neighbour, on the right, on the left)`. Returns `None` if the steps are not 8-adjacent.
pub fn neighbour_sides(prev: Pixel, cur: Pixel, next: Pixel) -> Option<[(Pixel, bool, bool); 4]> {
    let a = cur.direction_to(prev)?;
    let b = cur.direction_to(next)?;
    let mut out = [(cur, false, false); 4];
    for (k, slot) in out.iter_mut().enumerate() {
        let d = 2 * k as u8;
        let q = match d {
            0 => Pixel::new(cur.x + 1, cur.y),
            2 => Pixel::new(cur.x, cur.y + 1),
            4 => Pixel::new(cur.x - 1, cur.y),
            _ => Pixel::new(cur.x, cur.y - 1),
        };
        *slot = (q, strictly_inside(d, b, a), strictly_inside(d, a, b));
    }
    Some(out)
}

/// The outliers of a piece: the 4-neighbours of its interior points on either side of it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Outliers {
    /// RIGHT of the path (`S⁺`, strictly above the layer), each pixel once.
    pub right: Vec<Pixel>,
    /// LEFT of the path (`S⁻`, strictly below the layer), each pixel once.
    pub left: Vec<Pixel>,
}

/// The RIGHT and LEFT outliers of the piece `points[first..=last]` under `rule` (none when
/// the piece has no interior point or `last` is out of range).
///
/// ```
/// use layertrace::{piece_outliers, OutlierRule, Outliers, Pixel};
/// // A horizontal run of 5 pixels, traced left to right.
/// let run: Vec<Pixel> = (0..5).map(|x| Pixel::new(x, 0)).collect();
/// let Outliers { right, left } = piece_outliers(&run, 0, 4, OutlierRule::NotInPiece);
/// // The 4-neighbours of its interior pixels, below (y = 1) on the right, above on the left.
/// assert!(right.iter().all(|p| p.y == 1) && left.iter().all(|p| p.y == -1));
/// assert_eq!((right.len(), left.len()), (3, 3));
/// ```
pub fn piece_outliers(points: &[Pixel], first: usize, last: usize, rule: OutlierRule) -> Outliers {
    if last >= points.len() || last < first + 2 {
        return Outliers {
            right: Vec::new(),
            left: Vec::new(),
        };
    }
    // About one neighbour per point on each side.
    let mut right = Vec::with_capacity(last + 1 - first);
    let mut left = Vec::with_capacity(last + 1 - first);
    let mut seen = StretchSets::of(&points[first..=last]);
    for k in first + 1..last {
        let Some(sides) = neighbour_sides(points[k - 1], points[k], points[k + 1]) else {
            continue;
        };
        for (q, r, l) in sides {
            if rule == OutlierRule::NotInPiece && seen.is_point(q) {
                continue;
            }
            if r && seen.first_right(q) {
                right.push(q);
            }
            if l && seen.first_left(q) {
                left.push(q);
            }
        }
    }
    Outliers { right, left }
}

fn xy(p: Pixel) -> [i64; 2] {
    [p.x as i64, p.y as i64]
}

/// Decomposes one contour greedily with the given recognizer (reset for every piece), within
/// the default [`WorkBudget`].
///
/// ```
/// use layertrace::{decompose_points, Model, OutlierRule, Pixel, Recognizer};
/// use std::sync::Arc;
/// // An open chain: a 20-pixel row, then a 20-pixel column.
/// let points: Vec<Pixel> = (0..20)
///     .map(|x| Pixel::new(x, 0))
///     .chain((1..20).map(|y| Pixel::new(19, y)))
///     .collect();
/// let mut rec = Recognizer::new(Arc::new(Model::Line.basis()), &[0, 0]).unwrap();
/// let pieces = decompose_points(&points, &mut rec, OutlierRule::NotInPiece);
/// assert!(pieces.len() >= 2);
/// assert_eq!((pieces[0].first, pieces.last().unwrap().last), (0, points.len() - 1));
/// ```
pub fn decompose_points(points: &[Pixel], rec: &mut Recognizer, rule: OutlierRule) -> Vec<Piece> {
    decompose_points_within(points, rec, rule, WorkBudget::default())
}

/// [`decompose_points`] with the given work budget per piece.
pub fn decompose_points_within(
    points: &[Pixel],
    rec: &mut Recognizer,
    rule: OutlierRule,
    budget: WorkBudget,
) -> Vec<Piece> {
    greedy_points(points, rec, rule, budget, None)
}

/// [`decompose_points_within`], the short pieces taken from `memo` when remembered and
/// remembered there otherwise (`memo` must be for `rec`'s basis, `rule` and `budget`).
fn greedy_points(
    points: &[Pixel],
    rec: &mut Recognizer,
    rule: OutlierRule,
    budget: WorkBudget,
    mut memo: Option<&mut GreedyMemo>,
) -> Vec<Piece> {
    let n = points.len();
    let mut pieces = Vec::new();
    let mut w = Window::new(points, rule);
    let mut i = 0;
    while i < n {
        if let Some(found) = memo.as_deref().and_then(|m| m.find(points, i, rec)) {
            pieces.push(Piece {
                first: i,
                last: found.last,
                certificate: found.certificate,
                cut: found.cut,
            });
            i = found.last + 1;
            continue;
        }
        let before = memo.is_some().then(|| rec.stats());
        let mut certificate = w.begin(rec, i);
        let stop = w.grow(rec, n - 1, budget, &mut certificate);
        if let (Some(memo), Some(before)) = (memo.as_deref_mut(), before) {
            memo.keep(
                points,
                i,
                w.last,
                stop,
                &certificate,
                &rec.stats() - &before,
            );
        }
        pieces.push(Piece {
            first: i,
            last: w.last,
            certificate,
            cut: stop.cut(),
        });
        i = w.last + 1;
    }
    // Most contours of noisy images have one or two pieces: without this, each would keep
    // the capacity of four (about 700 bytes).
    pieces.shrink_to_fit();
    pieces
}

/// Most contours decomposed per parallel task: statistics are kept per task, not per
/// contour (two million tiny contours would otherwise hold 200 MB of them).
const CONTOURS_PER_TASK: usize = 256;

/// Fewest tasks the contours are split into (when there are that many contours), so that
/// threads share the work evenly: 350 contours in tasks of 256 left one of two threads a
/// quarter of the work (the 3000² sample decomposed 1.31× faster on 2 threads, now 1.9×).
/// The pieces do not depend on it.
const MIN_TASKS: usize = 64;

/// Up to this many contours, they are decomposed largest first (sorting millions of noise
/// specks would cost more than it balances).
const SORTED_CONTOURS: usize = 1 << 16;

/// Decomposes every contour with `model`, contours in parallel (rayon), within the default
/// [`WorkBudget`]; the result does not depend on the number of threads.
///
/// ```
/// use layertrace::{decompose, trace, Convention, Mask, Model, OutlierRule};
/// let mask = Mask::from_ascii(
///     "..........
///      .########.
///      .########.
///      .########.
///      ..........",
/// );
/// let d = decompose(trace(&mask, Convention::Default), Model::Line, OutlierRule::NotInPiece);
/// assert_eq!(d.contours.len(), 1);
/// // A rectangle's border: a few straight pieces (one may turn a corner: a digital line
/// // can), covering the contour in order, each with an exact certificate.
/// let pieces = &d.pieces[0];
/// assert!((2..=4).contains(&pieces.len()));
/// assert!(pieces.windows(2).all(|w| w[1].first == w[0].last + 1));
/// ```
pub fn decompose(contours: Vec<Contour>, model: Model, rule: OutlierRule) -> Decomposition {
    decompose_within(contours, model, rule, WorkBudget::default())
}

/// [`decompose`] with the given work budget per piece.
///
/// ```
/// use layertrace::{decompose_within, trace, Convention, Mask, Model, OutlierRule, WorkBudget};
/// let mask = Mask::from_fn(40, 40, |x, y| (x as i32 - 20).pow(2) + (y as i32 - 20).pow(2) < 250);
/// let contours = trace(&mask, Convention::Default);
/// let d = decompose_within(contours, Model::Conic, OutlierRule::NotInPiece, WorkBudget::default());
/// assert!(d.piece_count() >= 1);
/// ```
pub fn decompose_within(
    contours: Vec<Contour>,
    model: Model,
    rule: OutlierRule,
    budget: WorkBudget,
) -> Decomposition {
    decompose_reporting(contours, model, rule, budget, Cover::Greedy, &|_| {})
}

/// [`decompose_within`] with the given cover. With [`Cover::Optimal`] a closed contour may
/// come back rotated (the same cycle of points, started where the shortest path round the
/// cycle cuts it).
///
/// ```
/// use layertrace::{decompose_cover, trace, Convention, Cover, Mask, Model, OutlierRule};
/// use layertrace::WorkBudget;
/// let mask = Mask::from_fn(40, 30, |x, y| (x as i32 - 20).pow(2) * 2 + (y as i32 - 15).pow(2) * 3 < 600);
/// let cover = |c| {
///     let contours = trace(&mask, Convention::Default);
///     decompose_cover(contours, Model::Line, OutlierRule::NotInPiece, WorkBudget::default(), c)
/// };
/// // The optimal cover never has more pieces than the paper's greedy one.
/// assert!(cover(Cover::Optimal).piece_count() <= cover(Cover::Greedy).piece_count());
/// ```
pub fn decompose_cover(
    contours: Vec<Contour>,
    model: Model,
    rule: OutlierRule,
    budget: WorkBudget,
    cover: Cover,
) -> Decomposition {
    decompose_reporting(contours, model, rule, budget, cover, &|_| {})
}

/// A contour's rotation (its new first point) and its pieces.
type Rotated = (usize, Vec<Piece>);

/// True when the contour's last point is followed by its first and pieces may wrap round:
/// closed and not repeating its first point at the end (as the IPOL convention does).
fn wraps(c: &Contour) -> bool {
    c.closed && c.points.first() != c.points.last()
}

/// [`decompose_cover`], calling `done` with the number of contours decomposed so far after
/// each chunk of them (from the worker threads).
pub(crate) fn decompose_reporting(
    contours: Vec<Contour>,
    model: Model,
    rule: OutlierRule,
    budget: WorkBudget,
    cover: Cover,
    done: &(dyn Fn(usize) + Sync),
) -> Decomposition {
    let finished = std::sync::atomic::AtomicUsize::new(0);
    let basis: Arc<dyn Basis> = Arc::new(model.basis());
    let one = |c: &Contour, rec: &mut Recognizer, greedy: &mut GreedyMemo| match cover {
        Cover::Greedy => (0, greedy_points(&c.points, rec, rule, budget, Some(greedy))),
        _ => optimal_points(&c.points, wraps(c), rec, rule, budget),
    };
    let per_task = contours
        .len()
        .div_ceil(MIN_TASKS)
        .clamp(1, CONTOURS_PER_TASK);
    // Largest contours first where there are few enough to sort, a task per job.
    let order: Vec<usize> = if contours.len() <= SORTED_CONTOURS {
        largest_first(&contours)
    } else {
        (0..contours.len()).collect()
    };
    // Short pieces repeat across contours (noise, scans): remembered per worker thread.
    // (Not in `map_init`'s state, which is made afresh for every job: here every chunk.
    // 2000² noise, one thread: 84% of the pieces outside tiny contours are found in the
    // worker's memo, 11% were in a memo per chunk.)
    let greedy_memos: Vec<Mutex<GreedyMemo>> = (0..rayon::current_num_threads().max(1))
        .map(|_| Mutex::default())
        .collect();
    // A recognizer per worker thread too, which keeps its buffers from job to job (one per
    // job grew its sets' vectors anew: 0.7% of a glyph's instructions in `realloc`). It is
    // reset for every piece; a poisoned one is made afresh.
    let recognizers: Vec<Mutex<Option<Recognizer>>> =
        (0..greedy_memos.len()).map(|_| Mutex::default()).collect();
    let results: Vec<(Vec<Rotated>, Stats)> = order
        .par_chunks(per_task)
        .with_max_len(1)
        .map(|chunk| {
            // Each worker locks its own, and nothing here runs rayon jobs: no waiting. Both
            // locks are released before `done`, which is the caller's.
            let worker = rayon::current_thread_index().unwrap_or(0) % greedy_memos.len();
            let found = {
                let mut slot = recognizers[worker].lock().unwrap_or_else(|e| {
                    let mut slot = e.into_inner();
                    *slot = None;
                    slot
                });
                if slot.is_none() {
                    *slot = Recognizer::new(basis.clone(), &[0, 0]);
                }
                slot.as_mut().map(|rec| {
                    let before = rec.stats();
                    // Tiny contours repeat (noise, halftones): each shape once per task (per
                    // worker instead: no fewer instructions on noise).
                    let mut memo = shapes::PieceMemo::default();
                    // (A memo whose holder panicked holds pieces as exact as any.)
                    let mut greedy = greedy_memos[worker]
                        .lock()
                        .unwrap_or_else(std::sync::PoisonError::into_inner);
                    let pieces: Vec<Rotated> = chunk
                        .iter()
                        .map(|&k| {
                            let c = &contours[k];
                            memo.pieces(c, wraps(c), rec, |rec| one(c, rec, &mut greedy))
                        })
                        .collect();
                    let mut stats = &rec.stats() - &before;
                    stats += memo.copied_stats();
                    (pieces, stats)
                })
            };
            let n = finished.fetch_add(chunk.len(), Ordering::Relaxed) + chunk.len();
            done(n);
            found.unwrap_or_else(|| (vec![(0, Vec::new()); chunk.len()], Stats::default()))
        })
        .collect();
    let mut contours = contours;
    let mut stats = Stats::default();
    let mut pieces = vec![Vec::new(); contours.len()];
    let mut at = order.iter();
    for (p, s) in results {
        stats += &s;
        for ((rotation, p), &k) in p.into_iter().zip(&mut at) {
            if rotation > 0 {
                contours[k].points.rotate_left(rotation);
            }
            pieces[k] = p;
        }
    }
    Decomposition {
        model,
        contours,
        pieces,
        rule,
        cover,
        stats,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recognize::{recognize, Outcome, Recognition};

    fn px(v: &[(i32, i32)]) -> Vec<Pixel> {
        v.iter().map(|&(x, y)| Pixel::new(x, y)).collect()
    }

    #[test]
    fn sides_of_a_straight_step() {
        // Walking right on screen: down is on the right, up on the left.
        let s = neighbour_sides(Pixel::new(0, 0), Pixel::new(1, 0), Pixel::new(2, 0)).unwrap();
        let down = s.iter().find(|t| t.0 == Pixel::new(1, 1)).unwrap();
        let up = s.iter().find(|t| t.0 == Pixel::new(1, -1)).unwrap();
        assert_eq!((down.1, down.2), (true, false));
        assert_eq!((up.1, up.2), (false, true));
        // The step neighbours themselves are on no side.
        let right = s.iter().find(|t| t.0 == Pixel::new(2, 0)).unwrap();
        assert_eq!((right.1, right.2), (false, false));
        // U-turn: every other neighbour on both sides.
        let u = neighbour_sides(Pixel::new(0, 0), Pixel::new(1, 0), Pixel::new(0, 0)).unwrap();
        assert_eq!(u.iter().filter(|t| t.1 && t.2).count(), 3);
    }

    /// The border of a filled axis-aligned square, counter-clockwise on screen from its top-left
    /// pixel (foreground on the left): down the left side, right along the bottom, up, left.
    fn square(n: i32) -> Vec<Pixel> {
        let mut v = Vec::new();
        for y in 0..n - 1 {
            v.push((0, y));
        }
        for x in 0..n - 1 {
            v.push((x, n - 1));
        }
        for y in (1..n).rev() {
            v.push((n - 1, y));
        }
        for x in (1..n).rev() {
            v.push((x, 0));
        }
        px(&v)
    }

    #[test]
    fn a_square_gives_four_lines() {
        let pts = square(12);
        let basis: Arc<dyn Basis> = Arc::new(Model::Line.basis());
        let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
        let pieces = decompose_points(&pts, &mut rec, OutlierRule::NotInPiece);
        assert_eq!(pieces.len(), 4, "{pieces:?}");
        assert_eq!(pieces[0].first, 0);
        assert_eq!(pieces.last().unwrap().last, pts.len() - 1);
        for w in pieces.windows(2) {
            assert_eq!(w[0].last + 1, w[1].first);
        }
        check_pieces(&pts, &pieces, Model::Line, OutlierRule::NotInPiece);
    }

    /// Every certificate re-checked on the piece's own sets; greedy maximality.
    pub(crate) fn check_pieces(pts: &[Pixel], pieces: &[Piece], model: Model, rule: OutlierRule) {
        let arc: Arc<dyn Basis> = Arc::new(model.basis());
        let basis = arc.as_ref();
        for (k, p) in pieces.iter().enumerate() {
            let Outliers { right, left } = piece_outliers(pts, p.first, p.last, rule);
            let c = &p.certificate;
            let v = |q: Pixel| c.value(basis, &xy(q)).unwrap();
            for q in &pts[p.first..=p.last] {
                let f = v(*q);
                assert!(
                    c.extremes.lower <= f && f <= c.extremes.upper,
                    "inlier {q:?} of piece {k}"
                );
            }
            for q in &right {
                assert!(v(*q) > c.extremes.upper, "right outlier {q:?} of piece {k}");
            }
            for q in &left {
                assert!(v(*q) < c.extremes.lower, "left outlier {q:?} of piece {k}");
            }
            // Maximality: the piece plus the next point is not described.
            if p.last + 1 < pts.len() {
                let Outliers {
                    right: r2,
                    left: l2,
                } = piece_outliers(pts, p.first, p.last + 1, rule);
                let inl: Vec<Vec<i64>> = pts[p.first..=p.last + 1]
                    .iter()
                    .map(|&q| xy(q).to_vec())
                    .collect();
                let r2: Vec<Vec<i64>> = r2.iter().map(|&q| xy(q).to_vec()).collect();
                let l2: Vec<Vec<i64>> = l2.iter().map(|&q| xy(q).to_vec()).collect();
                let Recognition { outcome: o, .. } = recognize(arc.clone(), &inl, &r2, &l2);
                assert_eq!(o, Outcome::NotDescribed, "piece {k} could have grown");
            }
        }
    }

    #[test]
    fn digital_circle_is_few_circle_pieces() {
        // Border of a disc of radius 30, traced in order by angle.
        let r = 30.0f64;
        let inside =
            |x: i32, y: i32| ((x as f64 + 0.5).powi(2) + (y as f64 + 0.5).powi(2)) <= r * r;
        let mut border: Vec<Pixel> = Vec::new();
        for y in -40..40 {
            for x in -40..40 {
                if inside(x, y)
                    && (!inside(x + 1, y)
                        || !inside(x - 1, y)
                        || !inside(x, y + 1)
                        || !inside(x, y - 1))
                {
                    border.push(Pixel::new(x, y));
                }
            }
        }
        // Order by angle (screen coordinates): counter-clockwise on screen = decreasing atan2.
        border.sort_by(|a, b| {
            let fa = -((a.y as f64 + 0.5).atan2(a.x as f64 + 0.5));
            let fb = -((b.y as f64 + 0.5).atan2(b.x as f64 + 0.5));
            fa.partial_cmp(&fb).unwrap()
        });
        // Must be an 8-connected path for this test to mean anything.
        assert!(border.windows(2).all(|w| w[0].is_8_adjacent(w[1])));
        let mut counts = Vec::new();
        for model in [Model::Line, Model::Circle, Model::Conic] {
            let basis: Arc<dyn Basis> = Arc::new(model.basis());
            let mut rec = Recognizer::new(basis.clone(), &[0, 0]).unwrap();
            let pieces = decompose_points(&border, &mut rec, OutlierRule::NotInPiece);
            check_pieces(&border, &pieces, model, OutlierRule::NotInPiece);
            counts.push(pieces.len());
        }
        // A digital circle border is a few annuli (the band of border pixels is not one
        // layer all round: diagonal stairs reach further in than axis-parallel runs).
        assert!(
            counts[2] <= counts[1] && counts[1] <= 4,
            "circle/conic pieces {counts:?}"
        );
        assert!(counts[0] >= 4 * counts[1], "line pieces {counts:?}");
    }
}

#[cfg(test)]
mod cover_tests;
