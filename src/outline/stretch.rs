//! Stretches: runs of consecutive contour points drawn one way — along a piece's border
//! curve, along a digital straight segment, or along pixel cracks.
//!
//! A contour's path starts with one stretch per piece of its decomposition. Where the
//! renderer check finds a pixel on the wrong side, the stretch there is *refined*: a curve
//! piece becomes its exact polygon, the decomposition of its points into digital straight
//! segments by the line model (the paper's greedy, each segment with its own certificate,
//! drawn as one `L` along its largest-margin line), and a straight segment that still fails
//! is halved. Halving ends at pieces of one or two points, which have no equation and are
//! drawn along their cracks, exact by construction; so refinement always terminates, and
//! stairs of cracks only remain where the input has one-pixel features (their corners are
//! then cut, see [`super::corners`]).

use super::segment_memo::{self, Segment, SegmentLine};
use super::separation::Separation;
use super::vertices::side_pixels;
use crate::curve::Polynomial;
use crate::decompose::{neighbour_sides, OutlierRule, Piece};
use crate::level::{border_polynomial, polynomial_of};
use crate::model::{Basis, Model, PolynomialBasis};
use crate::pixel::{Pixel, PixelSet};
use crate::recognize::{max_margin_direction, MarginDirection};
use kurbo::Point;

/// Most points of one straight segment of a polygon: longer runs are cut, to meet again at
/// a vertex shared on their (nearly) common line. (The bound dates from when growing a
/// segment cost time quadratic in its length; [`Separation`] now pairs hull vertices only,
/// but the side sets and the segment's largest-margin line still grow with it.)
const MAX_SEGMENT_POINTS: usize = 160;

// A segment cut at its most points is not remembered (`segment_memo` keeps the segments
// that failed or reached their stretch's end): none is that long within the memo's steps.
const _: () = assert!(MAX_SEGMENT_POINTS > crate::steps::MAX_STEPS);

/// How a stretch is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Drawing {
    /// Along the border curve of a piece of the decomposition.
    Curve,
    /// Along the border line of a digital straight segment (the exact polygon).
    Straight,
    /// Along its pixel cracks.
    Cracks,
}

/// A run `first..=last` of a contour's points and how it is drawn.
#[derive(Clone, Debug)]
pub(crate) struct Stretch {
    /// First point (index in the contour).
    pub first: usize,
    /// Last point (inclusive).
    pub last: usize,
    /// The border curve; `None` for [`Drawing::Cracks`].
    pub poly: Option<Polynomial>,
    /// Largest distance of fitted cubics to the curve.
    pub tolerance: f64,
    /// How it is drawn.
    pub drawing: Drawing,
    /// Unique within the contour: keys the memo of drawings.
    pub id: usize,
}

impl Stretch {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.last + 1 - self.first
    }

    /// True when [`Stretcher::refine`] can straighten, split or crack it.
    pub fn refinable(&self) -> bool {
        self.drawing != Drawing::Cracks
    }
}

/// Why a piece's curve was not used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Unused {
    /// One or two points: the zero certificate.
    ZeroCertificate,
    /// No polynomial could be built.
    NoPolynomial,
    /// Its curve passes closer than the minimum clearance to a pixel centre.
    Thin,
    /// It has fewer points than the fewest drawn along a curve.
    Short,
    /// It has more points than the most drawn along a curve.
    Long,
}

/// Makes stretches, numbering them.
pub(crate) struct Stretcher<'a> {
    points: &'a [Pixel],
    next_id: usize,
    tolerance: f64,
    /// Sets [`Stretcher::polygon`] clears and refills for each segment (kept for their
    /// capacity: growing them anew cost 4% of the run).
    scratch: [PixelSet; 3],
    /// The segment's side sets in the order [`Stretcher::polygon`] found them (low, high),
    /// as [`side_pixels`] gives them up to order: its segments' borders need no second pass.
    sides: [Vec<Pixel>; 2],
    /// The separation [`Stretcher::polygon`] clears for each segment (kept for its hulls'
    /// capacity).
    separation: Separation,
    /// The line model's basis.
    line: &'static PolynomialBasis,
}

impl<'a> Stretcher<'a> {
    /// For the points of one contour; `tolerance` is the fitting tolerance asked for.
    pub fn new(points: &'a [Pixel], tolerance: f64) -> Stretcher<'a> {
        Stretcher {
            points,
            next_id: 0,
            tolerance,
            scratch: Default::default(),
            sides: Default::default(),
            separation: Separation::new(),
            line: Model::line_basis(),
        }
    }

    /// True when `basis` is the line model's (as far as its dimension tells: 2).
    pub fn is_line_basis(&self, basis: &dyn Basis) -> bool {
        basis.dim() == self.line.dim()
    }

    fn id(&mut self) -> usize {
        self.next_id += 1;
        self.next_id
    }

    /// The stretch of a piece of the decomposition in `basis`, or why its curve is unused
    /// (with the stretch to draw instead: cracks, to be refined when long enough). A curve
    /// piece's curve is tried only when its number of points lies in `sizes`.
    pub fn piece(
        &mut self,
        basis: &dyn Basis,
        piece: &Piece,
        min_clearance: f64,
        sizes: &std::ops::RangeInclusive<usize>,
    ) -> (Stretch, Option<Unused>) {
        let id = self.id();
        let mut s = Stretch {
            first: piece.first,
            last: piece.last,
            poly: None,
            tolerance: self.tolerance,
            drawing: Drawing::Cracks,
            id,
        };
        if piece.certificate.is_zero() {
            return (s, Some(Unused::ZeroCertificate));
        }
        // A line keeps the background beside its end pixels on its far side too, where it
        // can (as the polygon's segments do); curves keep the piece's own border curve,
        // closer to the true shape (the render check decides where they are drawn).
        // `NotInPiece` whatever rule the decomposition used: the drawing must keep the
        // background beside the piece outside, and for a piece described under `Any` the
        // two rules give the same outliers (none can be one of its pixels, which lie in the
        // layer, not strictly beside it).
        let straight = self.is_line_basis(basis);
        let points = piece.last + 1 - piece.first;
        if !straight && points < *sizes.start() {
            return (s, Some(Unused::Short));
        }
        if !straight && points > *sizes.end() {
            return (s, Some(Unused::Long));
        }
        let border = straight
            .then(|| self.closed_border(basis, piece.first, piece.last, false))
            .flatten()
            .or_else(|| border_polynomial(basis, self.points, piece, OutlierRule::NotInPiece));
        match border {
            // (Lines are cheap to check: only curves are sent to their polygon untried.)
            Some((_, clearance)) if !straight && clearance < min_clearance => {
                (s, Some(Unused::Thin))
            }
            Some((poly, clearance)) => {
                s.poly = Some(poly);
                s.drawing = if straight {
                    Drawing::Straight
                } else {
                    Drawing::Curve
                };
                s.tolerance = self.fit_tolerance(clearance);
                (s, None)
            }
            None => (s, Some(Unused::NoPolynomial)),
        }
    }

    /// The exact polygon of `first..=last`: its straight segments, grown greedily while a
    /// line separates strictly the segment's pixel centres and the foreground beside them
    /// from the background beside *every* one of its pixels, the two end pixels included
    /// (the paper's pieces leave the ends free, which lets a line cut the background pixel
    /// beside an end) — exact, incremental ([`Separation`]). Each is drawn along its
    /// largest-margin line. A single pixel always is such a segment, so every point is
    /// covered.
    pub fn polygon(&mut self, first: usize, last: usize) -> Vec<Stretch> {
        let mut out = Vec::new();
        self.polygon_into(first, last, &mut out);
        out
    }

    /// [`Stretcher::polygon`] appended to `out`: a stretch is some 500 bytes, and moving
    /// them from a vector of their own into the caller's cost 0.4% of 400² noise's
    /// instructions.
    pub fn polygon_into(&mut self, first: usize, last: usize, out: &mut Vec<Stretch>) {
        let points = self.points;
        let n = points.len();
        let xy = |p: Pixel| [i64::from(p.x), i64::from(p.y)];
        // (Segments of two points or more, mostly: growing the vector copied them, 0.5% of
        // 1000² noise's instructions.)
        out.reserve(((last + 2).saturating_sub(first) / 2).min(32));
        let mut i = first;
        let [mut in_piece, mut high, mut low] = std::mem::take(&mut self.scratch);
        let [mut low_list, mut high_list] = std::mem::take(&mut self.sides);
        let mut sep = std::mem::replace(&mut self.separation, Separation::new());
        while i <= last {
            // Short segments repeat (noise, halftones): each grown once per shape.
            if let Some(segment) = segment_memo::find(points, i, last) {
                let border = segment.line.and_then(|line| {
                    let origin = xy(points[i]);
                    polynomial_of(self.line, &origin, &line.direction, line.level)
                        .map(|poly| (poly, line.clearance))
                });
                debug_assert_eq!(
                    border,
                    self.closed_border(self.line, i, segment.last, false)
                );
                out.push(self.straight_or_cracks(i, segment.last, border));
                i = segment.last + 1;
                continue;
            }
            sep.clear();
            in_piece.clear();
            high.clear();
            low.clear();
            low_list.clear();
            high_list.clear();
            let mut j = i;
            let mut failed_at = None;
            loop {
                // (What point `j` adds is dropped again if it ends the segment.)
                let lengths = (low_list.len(), high_list.len());
                let p = points[j];
                let mut ok = true;
                if low.insert(p) {
                    low_list.push(p);
                    ok &= sep.add_low(xy(p));
                }
                in_piece.insert(p);
                let (prev, next) = (points[(j + n - 1) % n], points[(j + 1) % n]);
                if let Some(sides) = neighbour_sides(prev, p, next) {
                    for (q, right, left) in sides {
                        if in_piece.contains(&q) {
                            continue;
                        }
                        if right && high.insert(q) {
                            high_list.push(q);
                            ok &= sep.add_high(xy(q));
                        }
                        if left && !right && low.insert(q) {
                            low_list.push(q);
                            ok &= sep.add_low(xy(q));
                        }
                    }
                }
                if !ok {
                    failed_at = Some(j);
                }
                if !ok && j > i {
                    low_list.truncate(lengths.0);
                    high_list.truncate(lengths.1);
                    j -= 1;
                    break;
                }
                if !ok || j == last || j + 1 - i >= MAX_SEGMENT_POINTS {
                    break;
                }
                j += 1;
            }
            // The sides found are the segment's (see `sides`): a later point of the
            // segment beside an earlier one on the right would have ended it.
            let found = self.border_between(self.line, i, &low_list, &high_list, false);
            let segment = Segment {
                last: j,
                line: found.as_ref().and_then(|(_, clearance, m)| {
                    Some(SegmentLine {
                        direction: m.direction.as_slice().try_into().ok()?,
                        level: m.level,
                        clearance: *clearance,
                    })
                }),
            };
            let border = found.map(|(poly, clearance, _)| (poly, clearance));
            debug_assert_eq!(border, self.closed_border(self.line, i, j, false));
            // (Not a segment cut at its most points: nothing failed there. A line is kept
            // with the segment, or none was found.)
            if (failed_at.is_some() || j == last) && segment.line.is_some() == border.is_some() {
                segment_memo::keep(points, i, last, &segment, failed_at);
            }
            out.push(self.straight_or_cracks(i, j, border));
            i = j + 1;
        }
        self.scratch = [in_piece, high, low];
        self.sides = [low_list, high_list];
        self.separation = sep;
    }

    /// The stretch of the straight segment `first..=last` along the line of largest margin
    /// between its points (with the foreground beside them) and the background beside
    /// them; cracks when there is none.
    fn segment(&mut self, first: usize, last: usize) -> Stretch {
        let border = self.closed_border(self.line, first, last, false);
        self.straight_or_cracks(first, last, border)
    }

    /// The stretch of the straight segment `first..=last` along `border` (its
    /// [`Stretcher::closed_border`] in the line basis), or along its cracks without one.
    fn straight_or_cracks(
        &mut self,
        first: usize,
        last: usize,
        border: Option<(Polynomial, f64)>,
    ) -> Stretch {
        let id = self.id();
        match border {
            Some((poly, clearance)) => Stretch {
                first,
                last,
                poly: Some(poly),
                tolerance: self.fit_tolerance(clearance),
                drawing: Drawing::Straight,
                id,
            },
            None => Stretch {
                first,
                last,
                poly: None,
                tolerance: self.tolerance,
                drawing: Drawing::Cracks,
                id,
            },
        }
    }

    /// Fitted cubics must not cross a pixel centre: they stay within half the clearance (at
    /// least 1/1000 px) and never beyond the asked tolerance.
    fn fit_tolerance(&self, clearance: f64) -> f64 {
        (clearance / 2.0).clamp(1e-3, self.tolerance.max(1e-3))
    }

    /// The level curve in `basis` of largest margin between the points `first..=last` of the
    /// closed contour with the foreground pixels beside them (LEFT) on one side, and the
    /// background pixels beside *all* of them, the two ends included, on the other; with its
    /// clearance (smallest first-order distance to those pixel centres). `scaled` as in
    /// [`max_margin_direction`]. Returns `None` when no such curve is found.
    fn closed_border(
        &self,
        basis: &dyn Basis,
        first: usize,
        last: usize,
        scaled: bool,
    ) -> Option<(Polynomial, f64)> {
        let (low, high) = side_pixels(self.points, first, last);
        self.border_between(basis, first, &low, &high, scaled)
            .map(|(poly, clearance, _)| (poly, clearance))
    }

    /// [`Stretcher::closed_border`] from the sides of `first..` (its [`side_pixels`], in
    /// any order), with the direction and level the curve was made from.
    fn border_between(
        &self,
        basis: &dyn Basis,
        first: usize,
        low: &[Pixel],
        high: &[Pixel],
        scaled: bool,
    ) -> Option<(Polynomial, f64, MarginDirection)> {
        let xy = |p: &Pixel| [i64::from(p.x), i64::from(p.y)];
        let (low, high): (Vec<[i64; 2]>, Vec<[i64; 2]>) =
            (low.iter().map(xy).collect(), high.iter().map(xy).collect());
        let origin = xy(&self.points[first]);
        let margin = max_margin_direction(basis, &origin, &low, &high, scaled)?;
        let poly = polynomial_of(basis, &origin, &margin.direction, margin.level)?;
        let clearance = low
            .iter()
            .chain(&high)
            .map(|p| poly.distance_estimate(Point::new(p[0] as f64 + 0.5, p[1] as f64 + 0.5)))
            .fold(f64::INFINITY, f64::min);
        Some((poly, clearance, margin))
    }

    /// `first..=last` along its cracks.
    pub fn cracks(&mut self, first: usize, last: usize) -> Stretch {
        Stretch {
            first,
            last,
            poly: None,
            tolerance: self.tolerance,
            drawing: Drawing::Cracks,
            id: self.id(),
        }
    }

    /// What replaces a stretch the renderer drew wrongly, or that could not be drawn: a
    /// curve becomes its polygon; a straight segment (or a curve whose polygon is itself)
    /// is halved, each half again a polygon; a one-point segment becomes its cracks.
    /// Returns `None` for stretches that cannot be refined ([`Stretch::refinable`]).
    pub fn refine(&mut self, s: &Stretch) -> Option<Vec<Stretch>> {
        if !s.refinable() {
            return None;
        }
        if s.drawing == Drawing::Curve {
            let poly = self.polygon(s.first, s.last);
            if poly.len() > 1 || poly[0].drawing != Drawing::Straight {
                return Some(poly);
            }
        }
        if s.len() == 1 {
            return Some(vec![self.cracks(s.first, s.last)]);
        }
        let mid = s.first + s.len() / 2 - 1;
        if s.drawing == Drawing::Straight {
            // Part of a straight segment is one (its outliers are a subset): each half
            // gets its own largest-margin line, no recognition needed.
            // (A piece of the line model need not be one with its end pixels' background:
            // a half without such a line is decomposed again.)
            let mut out = Vec::new();
            for (a, b) in [(s.first, mid), (mid + 1, s.last)] {
                let half = self.segment(a, b);
                if half.drawing == Drawing::Straight || a == b {
                    out.push(half);
                } else {
                    self.polygon_into(a, b, &mut out);
                }
            }
            return Some(out);
        }
        let mut out = self.polygon(s.first, mid);
        self.polygon_into(mid + 1, s.last, &mut out);
        Some(out)
    }
}
