//! tiny-skia's edges as the row crossings its scan walker sees: the set-up of lines,
//! quadratics and cubics in its fixed point, for [`super::scan`].
//!
//! # tiny-skia's arithmetic, step by step
//! For a path whose bounds, rounded out, lie inside the mask, tiny-skia 0.12
//! (`scan::path::fill_path`) builds edges without clipping (`edge_builder.rs`, `build`):
//! - a quadratic is first cut where it turns in y (`chop_quad_at_y_extrema`, in `f32`), a
//!   cubic likewise (`chop_cubic_at_y_extrema`);
//! - every point in `f32` becomes 26.6 fixed point by truncation, `(v · 64) as i32`;
//! - a line (`LineEdge`), oriented downwards (winding +1, or −1 when its ends were
//!   swapped), covers the rows `round(y0) ..= round(y1) − 1` with `round(v) = (v + 32) >>
//!   6`, none when they are equal; its slope is `fdot6::div(x1 − x0, y1 − y0)` in 16.16,
//!   its x at the first row's centre `x0 + fdot16::mul(slope, dy)` with `dy = (top << 6) +
//!   32 − y0`, and each later row adds the slope;
//! - a quadratic (`QuadraticEdge`) or cubic (`CubicEdge`) is a chain of such lines between
//!   the points of a forward difference in 16.16 over `2^shift` steps, `shift` from the
//!   distance of its control points to its chord (`diff_to_shift`, `cubic_delta_from_line`).
//!
//! The set-up is tiny-skia's code (BSD-3-Clause, Copyright 2006 The Android Open Source
//! Project, 2020 Yevhenii Reizner); the cuts at extrema are in [`super::extrema`].

use super::extrema::{
    chop_cubic_at_x_extrema, chop_cubic_at_y_extrema, chop_quad_at_x_extrema,
    chop_quad_at_y_extrema,
};
use tiny_skia_path::Point as SkPoint;

/// Most steps of a curve's forward difference: `2^MAX_COEFF_SHIFT` (tiny-skia's).
const MAX_COEFF_SHIFT: i32 = 6;
/// A row crossing of an edge: its row in the window, its x in 16.16 (the pixel boundary is
/// `round(x)`), its winding, and which fills it belongs to ([`Tag`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Crossing {
    pub(super) row: i32,
    pub(super) x: i32,
    pub(super) winding: i8,
    pub(super) tag: Tag,
}

/// Which of the fills of one scan a crossing belongs to: bit `k` for fill `k` (see
/// [`super::scan::painted_moved`]: 0 the path as it is, 1 and 2 moved), and [`Tag::MOVES`] when it is the
/// path's and moves with it (its x is then the unmoved one, the fill's offset added).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Tag(pub(super) u8);

impl Tag {
    /// The crossing moves with the fill's offset.
    pub(super) const MOVES: u8 = 1 << 7;
    /// In every fill, moving with the path.
    pub(super) const SHARED: Tag = Tag(0b111 | Tag::MOVES);
    /// The reference's: in every fill, never moved.
    pub(super) const FIXED: Tag = Tag(0b111);
}

/// tiny-skia's `fdot6::div`: `a / b` in 16.16.
fn fdot6_div(a: i32, b: i32) -> i32 {
    if i16::try_from(a).is_ok() {
        (a << 16) / b
    } else {
        ((i64::from(a) << 16) / i64::from(b)).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }
}

/// tiny-skia's `fdot16::mul`.
fn fdot16_mul(a: i32, b: i32) -> i32 {
    ((i64::from(a) * i64::from(b)) >> 16) as i32
}

/// A point in 26.6 fixed point, as tiny-skia's edges take it.
fn fdot6(p: SkPoint) -> (i32, i32) {
    ((p.x * 64.0) as i32, (p.y * 64.0) as i32)
}

/// tiny-skia's `diff_to_shift` without anti-aliasing: how many times to halve a curve
/// whose control points stray `(dx, dy)` (26.6) from its chord.
fn diff_to_shift(dx: i32, dy: i32, shift_aa: i32) -> i32 {
    let (dx, dy) = (dx.abs(), dy.abs());
    let mut dist = if dx > dy {
        dx + (dy >> 1)
    } else {
        dy + (dx >> 1)
    };
    dist = (dist + (1 << (2 + shift_aa))) >> (3 + shift_aa);
    (32 - dist.leading_zeros() as i32) >> 1
}

/// tiny-skia's `cubic_delta_from_line`.
fn cubic_delta_from_line(a: i32, b: i32, c: i32, d: i32) -> i32 {
    let one_third = ((a * 8 - b * 15 + 6 * c + d) * 19) >> 9;
    let two_third = ((a + 6 * b - c * 15 + d * 8) * 19) >> 9;
    one_third.abs().max(two_third.abs())
}

/// The row crossings of a path's edges within rows `0..height`.
pub(super) struct Crossings {
    pub(super) out: Vec<Crossing>,
    pub(super) height: i32,
    /// What the crossings pushed now belong to.
    pub(super) tag: Tag,
    /// Whether curves are also cut where they turn in x (the clipped way: tiny-skia's
    /// edge clipper cuts them so before clipping each part, which inside the window
    /// leaves it as it is).
    pub(super) x_chops: bool,
}

impl Crossings {
    /// A line between 26.6 points, `y0 ≤ y1`, of the given winding (tiny-skia's
    /// `LineEdge::update`); whether it covers any row.
    pub(super) fn piece(&mut self, x0: i32, y0: i32, x1: i32, y1: i32, winding: i8) -> bool {
        let (top, bottom) = ((y0 + 32) >> 6, (y1 + 32) >> 6);
        if top == bottom {
            return false;
        }
        let slope = fdot6_div(x1 - x0, y1 - y0);
        let dy = (top << 6) + 32 - y0;
        let mut x = (x0 + fdot16_mul(slope, dy)) << 10;
        for row in top..bottom {
            if (0..self.height).contains(&row) {
                self.out.push(Crossing {
                    row,
                    x,
                    winding,
                    tag: self.tag,
                });
            }
            x = x.wrapping_add(slope);
        }
        true
    }

    /// A line (`LineEdge::new`).
    pub(super) fn line(&mut self, p0: SkPoint, p1: SkPoint) {
        let ((mut x0, mut y0), (mut x1, mut y1)) = (fdot6(p0), fdot6(p1));
        let mut winding = 1;
        if y0 > y1 {
            std::mem::swap(&mut x0, &mut x1);
            std::mem::swap(&mut y0, &mut y1);
            winding = -1;
        }
        self.piece(x0, y0, x1, y1, winding);
    }

    /// A curve of `P` points, cut where it turns in y (`chop_y`) and, when the clipper runs,
    /// in x (`chop_x`), each part drawn by `mono`: consecutive parts share an end point, so
    /// part `i` of the `M` points written is `i (P − 1) .. i (P − 1) + P`.
    fn monotonic_parts<const P: usize, const M: usize>(
        &mut self,
        p: [SkPoint; P],
        chop_y: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
        chop_x: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
        mono: fn(&mut Self, &[SkPoint]),
    ) {
        let step = P - 1;
        let mut mono_y = [SkPoint::zero(); M];
        let n = chop_y(&p, &mut mono_y);
        for i in 0..=n {
            let part: [SkPoint; P] = std::array::from_fn(|k| mono_y[i * step + k]);
            if self.x_chops {
                let mut mono_x = [SkPoint::zero(); M];
                let m = chop_x(&part, &mut mono_x);
                for j in 0..=m {
                    mono(self, &mono_x[j * step..j * step + P]);
                }
            } else {
                mono(self, &part);
            }
        }
    }

    /// A quadratic with its points in each of the `fills` fills (`each(k)`), as
    /// [`Crossings::curve_in_fills`].
    pub(super) fn quad_in_fills(&mut self, each: impl Fn(usize) -> [SkPoint; 3], fills: usize) {
        self.curve_in_fills(
            each,
            fills,
            chop_quad_at_y_extrema,
            chop_quad_at_x_extrema,
            Crossings::quad,
        );
    }

    /// A cubic with its points in each of the `fills` fills (`each(k)`), as
    /// [`Crossings::curve_in_fills`].
    pub(super) fn cubic_in_fills(&mut self, each: impl Fn(usize) -> [SkPoint; 4], fills: usize) {
        self.curve_in_fills(
            each,
            fills,
            chop_cubic_at_y_extrema,
            chop_cubic_at_x_extrema,
            Crossings::cubic,
        );
    }

    /// A quadratic or cubic (`draw`) with its points in each of the `fills` fills
    /// (`each(k)`): once for all when it is not cut where it turns (its edges move with it),
    /// else once per fill, its crossings in that fill alone.
    #[inline]
    fn curve_in_fills<const P: usize, const M: usize>(
        &mut self,
        each: impl Fn(usize) -> [SkPoint; P],
        fills: usize,
        chop_y: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
        chop_x: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
        draw: fn(&mut Self, [SkPoint; P]),
    ) {
        if fills > 1 && self.is_cut(&each(0), chop_y, chop_x) {
            for k in 0..fills {
                self.tag = Tag(1 << k);
                draw(self, each(k));
            }
            self.tag = Tag::SHARED;
        } else {
            draw(self, each(0));
        }
    }

    /// Whether a curve of `P` points is cut where it turns in y (or, when the clipper runs,
    /// in x): an uncut curve's edges move with it (see [`super::scan::painted_moved`]).
    fn is_cut<const P: usize, const M: usize>(
        &self,
        p: &[SkPoint; P],
        chop_y: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
        chop_x: fn(&[SkPoint; P], &mut [SkPoint; M]) -> usize,
    ) -> bool {
        let mut mono_y = [SkPoint::zero(); M];
        if chop_y(p, &mut mono_y) > 0 {
            return true;
        }
        if !self.x_chops {
            return false;
        }
        let part: [SkPoint; P] = std::array::from_fn(|k| mono_y[k]);
        let mut mono_x = [SkPoint::zero(); M];
        chop_x(&part, &mut mono_x) > 0
    }

    /// A quadratic, cut where it turns in y.
    pub(super) fn quad(&mut self, p: [SkPoint; 3]) {
        self.monotonic_parts(
            p,
            chop_quad_at_y_extrema,
            chop_quad_at_x_extrema,
            Self::mono_quad,
        );
    }

    /// A quadratic monotonic in y (`QuadraticEdge`).
    pub(super) fn mono_quad(&mut self, p: &[SkPoint]) {
        let ((mut x0, mut y0), (x1, y1), (mut x2, mut y2)) =
            (fdot6(p[0]), fdot6(p[1]), fdot6(p[2]));
        let mut winding = 1;
        if y0 > y2 {
            std::mem::swap(&mut x0, &mut x2);
            std::mem::swap(&mut y0, &mut y2);
            winding = -1;
        }
        if (y0 + 32) >> 6 == (y2 + 32) >> 6 {
            return;
        }
        let dx = ((x1 << 1) - x0 - x2) >> 2;
        let dy = ((y1 << 1) - y0 - y2) >> 2;
        let shift = diff_to_shift(dx, dy, 0).clamp(1, MAX_COEFF_SHIFT);
        let curve_shift = shift - 1;
        // A and B at half their value (tiny-skia's overflow guard).
        let a = (x0 - x1 - x1 + x2) << 9;
        let b = (x1 - x0) << 10;
        let (mut qx, mut qdx, qddx) = (x0 << 10, b + (a >> shift), a >> (shift - 1));
        let a = (y0 - y1 - y1 + y2) << 9;
        let b = (y1 - y0) << 10;
        let (mut qy, mut qdy, qddy) = (y0 << 10, b + (a >> shift), a >> (shift - 1));
        let (last_x, last_y) = (x2 << 10, y2 << 10);
        let mut count = 1 << shift;
        while count > 0 {
            count -= 1;
            let (nx, ny) = if count > 0 {
                let n = (qx + (qdx >> curve_shift), qy + (qdy >> curve_shift));
                qdx += qddx;
                qdy += qddy;
                n
            } else {
                (last_x, last_y)
            };
            self.piece(qx >> 10, qy >> 10, nx >> 10, ny >> 10, winding);
            (qx, qy) = (nx, ny);
        }
    }

    /// A cubic, cut where it turns in y.
    pub(super) fn cubic(&mut self, p: [SkPoint; 4]) {
        self.monotonic_parts(
            p,
            chop_cubic_at_y_extrema,
            chop_cubic_at_x_extrema,
            Self::mono_cubic,
        );
    }

    /// A cubic monotonic in y (`CubicEdge`).
    pub(super) fn mono_cubic(&mut self, p: &[SkPoint]) {
        let ((mut x0, mut y0), (mut x1, mut y1)) = (fdot6(p[0]), fdot6(p[1]));
        let ((mut x2, mut y2), (mut x3, mut y3)) = (fdot6(p[2]), fdot6(p[3]));
        let mut winding = 1;
        if y0 > y3 {
            std::mem::swap(&mut x0, &mut x3);
            std::mem::swap(&mut x1, &mut x2);
            std::mem::swap(&mut y0, &mut y3);
            std::mem::swap(&mut y1, &mut y2);
            winding = -1;
        }
        if (y0 + 32) >> 6 == (y3 + 32) >> 6 {
            return;
        }
        let dx = cubic_delta_from_line(x0, x1, x2, x3);
        let dy = cubic_delta_from_line(y0, y1, y2, y3);
        let shift = (diff_to_shift(dx, dy, 2) + 1).min(MAX_COEFF_SHIFT);
        let (mut up_shift, mut down_shift) = (6, shift - 4);
        if down_shift < 0 {
            down_shift = 0;
            up_shift = 10 - shift;
        }
        let coefficients = |v0: i32, v1: i32, v2: i32, v3: i32| {
            let b = (3 * (v1 - v0)) << up_shift;
            let c = (3 * (v0 - v1 - v1 + v2)) << up_shift;
            let d = (v3 + 3 * (v1 - v2) - v0) << up_shift;
            (
                v0 << 10,
                b + (c >> shift) + (d >> (2 * shift)),
                2 * c + ((3 * d) >> (shift - 1)),
                (3 * d) >> (shift - 1),
            )
        };
        let (mut cx, mut cdx, mut cddx, cdddx) = coefficients(x0, x1, x2, x3);
        let (mut cy, mut cdy, mut cddy, cdddy) = coefficients(y0, y1, y2, y3);
        let (last_x, last_y) = (x3 << 10, y3 << 10);
        let mut count = -(1 << shift);
        while count < 0 {
            count += 1;
            let (nx, mut ny) = if count < 0 {
                let n = (cx + (cdx >> down_shift), cy + (cdy >> down_shift));
                cdx += cddx >> shift;
                cddx += cdddx;
                cdy += cddy >> shift;
                cddy += cdddy;
                n
            } else {
                (last_x, last_y)
            };
            // tiny-skia pins what its fixed point does not keep monotonic.
            if ny < cy {
                ny = cy;
            }
            self.piece(cx >> 10, cy >> 10, nx >> 10, ny >> 10, winding);
            (cx, cy) = (nx, ny);
        }
    }
}
