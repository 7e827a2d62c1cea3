//! tiny-skia's edge clipper for quadratics and cubics in fills (its `edge_clipper.rs`,
//! from Skia's `SkEdgeClipper`), ported from tiny-skia 0.12 / Skia (BSD-3-Clause,
//! Copyright 2009 The Android Open Source Project, 2020 Yevhenii Reizner), operation for
//! operation, for [`super::scan`]'s fills of paths that tiny-skia clips.
//!
//! A curve is cut where it turns in y, then each part where it turns in x; each part,
//! monotonic both ways, is cut where it crosses the mask's top and bottom (the parts beyond
//! are dropped) and its sides (the parts beyond become vertical lines on the side they lie
//! beyond, which keep each row's winding), with tiny-skia's `f32` root finding for
//! quadratics and its `f64` one for cubics ([`super::path64`]), and the cut points clamped
//! to the sides as tiny-skia clamps them. Lines are clipped by [`super::line_clip`].

use super::extrema::{
    chop_cubic_at_x_extrema, chop_cubic_at_y_extrema, chop_quad_at_x_extrema,
    chop_quad_at_y_extrema,
};
use super::line_clip::clip_line;
use super::path64;
use tiny_skia_path::path_geometry::{
    chop_cubic_at2, chop_quad_at, find_unit_quad_roots, new_t_values,
};
use tiny_skia_path::{NormalizedF32Exclusive, Point as SkPoint, SCALAR_MAX};

/// An edge the clipper gives the edge builder: a line, or a quadratic or cubic monotonic
/// in x and y, in the direction of the curve it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Clipped {
    /// A line from its first point to its second.
    Line(SkPoint, SkPoint),
    /// A monotonic quadratic.
    Quad([SkPoint; 3]),
    /// A monotonic cubic.
    Cubic([SkPoint; 4]),
}

/// The mask `[0, w] × [0, h]` tiny-skia clips to, and where the edges go.
struct Clipper<F: FnMut(Clipped)> {
    /// The mask's right side.
    right: f32,
    /// The mask's bottom.
    bottom: f32,
    /// Takes each edge.
    out: F,
    /// Whether tiny-skia would have panicked (see [`mono_cubic_closest_t`]).
    failed: bool,
}

/// The mask's left side and top.
const LEFT: f32 = 0.0;
/// The mask's top.
const TOP: f32 = 0.0;

/// The edges tiny-skia's clipper makes of the quadratic `p` in the mask `[0, w] × [0, h]`
/// (`clip_quad`), each given to `out` (nothing culled to the right).
pub(super) fn clip_quad(p: [SkPoint; 3], (w, h): (f32, f32), out: impl FnMut(Clipped)) {
    let mut c = Clipper {
        right: w,
        bottom: h,
        out,
        failed: false,
    };
    let (top, bottom) = y_bounds(&p);
    if quick_reject(top, bottom, c.bottom) {
        return;
    }
    let mut mono_y = [SkPoint::zero(); 5];
    let count_y = chop_quad_at_y_extrema(&p, &mut mono_y);
    for y in 0..=count_y {
        let y_points = [mono_y[y * 2], mono_y[y * 2 + 1], mono_y[y * 2 + 2]];
        let mut mono_x = [SkPoint::zero(); 5];
        let count_x = chop_quad_at_x_extrema(&y_points, &mut mono_x);
        for x in 0..=count_x {
            c.clip_mono_quad(&[mono_x[x * 2], mono_x[x * 2 + 1], mono_x[x * 2 + 2]]);
        }
    }
}

/// The edges tiny-skia's clipper makes of the cubic `p` in the mask `[0, w] × [0, h]`
/// (`clip_cubic`), each given to `out` (nothing culled to the right). A cubic whose bounds
/// reach beyond ±2^22 px is clipped as the line between its ends.
///
/// False where tiny-skia would panic (its search for where a cubic crosses a side, when its
/// `f64` root finding found none, ending at `t = 1`: `mono_cubic_closest_t`); the edges
/// given to `out` are then not tiny-skia's.
#[must_use]
pub(super) fn clip_cubic(p: [SkPoint; 4], (w, h): (f32, f32), out: impl FnMut(Clipped)) -> bool {
    let mut c = Clipper {
        right: w,
        bottom: h,
        out,
        failed: false,
    };
    let (top, bottom) = y_bounds(&p);
    if !(bottom > TOP && top < c.bottom) {
        return true;
    }
    if too_big_for_reliable_float_math(&p) {
        let out = &mut c.out;
        clip_line([p[0], p[3]], (w, h), |a, b| out(Clipped::Line(a, b)));
        return true;
    }
    let mut mono_y = [SkPoint::zero(); 10];
    let count_y = chop_cubic_at_y_extrema(&p, &mut mono_y);
    for y in 0..=count_y {
        let y_points: [SkPoint; 4] = std::array::from_fn(|k| mono_y[y * 3 + k]);
        let mut mono_x = [SkPoint::zero(); 10];
        let count_x = chop_cubic_at_x_extrema(&y_points, &mut mono_x);
        for x in 0..=count_x {
            c.clip_mono_cubic(&std::array::from_fn(|k| mono_x[x * 3 + k]));
        }
    }
    !c.failed
}

/// The least and largest y of the points (`Rect::from_points`'s top and bottom; the
/// points are finite).
fn y_bounds(p: &[SkPoint]) -> (f32, f32) {
    p.iter()
        .fold((p[0].y, p[0].y), |(lo, hi), q| (lo.min(q.y), hi.max(q.y)))
}

/// tiny-skia's `quick_reject`: the bounds `[top, bottom]` wholly above or below the mask.
fn quick_reject(top: f32, bottom: f32, clip_bottom: f32) -> bool {
    top >= clip_bottom || bottom <= TOP
}

/// tiny-skia's `too_big_for_reliable_float_math` of the bounds of `p`.
fn too_big_for_reliable_float_math(p: &[SkPoint; 4]) -> bool {
    let limit = (1 << 22) as f32;
    let lo = |f: fn(&SkPoint) -> f32| p.iter().map(f).fold(f32::INFINITY, f32::min);
    let hi = |f: fn(&SkPoint) -> f32| p.iter().map(f).fold(f32::NEG_INFINITY, f32::max);
    lo(|q| q.x) < -limit || lo(|q| q.y) < -limit || hi(|q| q.x) > limit || hi(|q| q.y) > limit
}

/// tiny-skia's `sort_increasing_y`: `src` (monotonic in y) in increasing y; whether it was
/// reversed.
fn sort_increasing_y<const N: usize>(src: &[SkPoint; N]) -> ([SkPoint; N], bool) {
    if src[0].y > src[N - 1].y {
        let mut dst = *src;
        dst.reverse();
        (dst, true)
    } else {
        (*src, false)
    }
}

/// tiny-skia's `chop_mono_quad_at`: where the monotonic quadratic of coordinates `c0, c1,
/// c2` reaches `target`, if its root finding finds it.
fn chop_mono_quad_at(c0: f32, c1: f32, c2: f32, target: f32) -> Option<NormalizedF32Exclusive> {
    let a = c0 - c1 - c1 + c2;
    let b = 2.0 * (c1 - c0);
    let c = c0 - target;
    let mut roots = new_t_values();
    let count = find_unit_quad_roots(a, b, c, &mut roots);
    (count != 0).then_some(roots[0])
}

/// tiny-skia's `chop_quad_in_y`: `pts` (increasing in y) cut to the mask's rows.
fn chop_quad_in_y(bottom: f32, pts: &mut [SkPoint; 3]) {
    let mut tmp = [SkPoint::zero(); 5];
    // Partly above.
    if pts[0].y < TOP {
        if let Some(t) = chop_mono_quad_at(pts[0].y, pts[1].y, pts[2].y, TOP) {
            // The second part, its numerics cleaned up.
            chop_quad_at(pts, t, &mut tmp);
            tmp[2].y = TOP;
            tmp[3].y = tmp[3].y.max(TOP);
            pts[0] = tmp[2];
            pts[1] = tmp[3];
        } else {
            // Inexact numerics: clamped to the top.
            for p in pts.iter_mut() {
                if p.y < TOP {
                    p.y = TOP;
                }
            }
        }
    }
    // Partly below.
    if pts[2].y > bottom {
        if let Some(t) = chop_mono_quad_at(pts[0].y, pts[1].y, pts[2].y, bottom) {
            chop_quad_at(pts, t, &mut tmp);
            tmp[1].y = tmp[1].y.min(bottom);
            tmp[2].y = bottom;
            pts[1] = tmp[1];
            pts[2] = tmp[2];
        } else {
            for p in pts.iter_mut() {
                if p.y > bottom {
                    p.y = bottom;
                }
            }
        }
    }
}

/// tiny-skia's `chop_cubic_in_y`: `pts` (increasing in y) cut to the mask's rows; false
/// where tiny-skia would panic.
fn chop_cubic_in_y(bottom: f32, pts: &mut [SkPoint; 4]) -> bool {
    let mut ok = true;
    // Partly above.
    if pts[0].y < TOP {
        let mut tmp = [SkPoint::zero(); 7];
        ok &= chop_mono_cubic_at_y(pts, TOP, &mut tmp);
        // A poor cut leaving the first three points above: cut the second part again.
        if tmp[3].y < TOP && tmp[4].y < TOP && tmp[5].y < TOP {
            let tmp2 = [tmp[3], tmp[4], tmp[5], tmp[6]];
            ok &= chop_mono_cubic_at_y(&tmp2, TOP, &mut tmp);
        }
        tmp[3].y = TOP;
        tmp[4].y = tmp[4].y.max(TOP);
        pts[0] = tmp[3];
        pts[1] = tmp[4];
        pts[2] = tmp[5];
    }
    // Partly below.
    if pts[3].y > bottom {
        let mut tmp = [SkPoint::zero(); 7];
        ok &= chop_mono_cubic_at_y(pts, bottom, &mut tmp);
        tmp[3].y = bottom;
        tmp[2].y = tmp[2].y.min(bottom);
        pts[1] = tmp[1];
        pts[2] = tmp[2];
        pts[3] = tmp[3];
    }
    ok
}

/// tiny-skia's edge clipper's `chop_mono_cubic_at_x`: cut where the cubic crosses `x`, in
/// `f64` ([`path64`]), else at tiny-skia's closest `t` in `f32`; false where tiny-skia
/// would panic.
fn chop_mono_cubic_at_x(src: &[SkPoint; 4], x: f32, dst: &mut [SkPoint; 7]) -> bool {
    if path64::chop_mono_cubic_at_x(src, x, dst) {
        return true;
    }
    let values = src.map(|p| p.x);
    let t = mono_cubic_closest_t(&values, x);
    chop_cubic_at2(src, t.unwrap_or(NormalizedF32Exclusive::HALF), dst);
    t.is_some()
}

/// tiny-skia's edge clipper's `chop_mono_cubic_at_y`.
fn chop_mono_cubic_at_y(src: &[SkPoint; 4], y: f32, dst: &mut [SkPoint; 7]) -> bool {
    if path64::chop_mono_cubic_at_y(src, y, dst) {
        return true;
    }
    let values = src.map(|p| p.y);
    let t = mono_cubic_closest_t(&values, y);
    chop_cubic_at2(src, t.unwrap_or(NormalizedF32Exclusive::HALF), dst);
    t.is_some()
}

/// tiny-skia's `mono_cubic_closest_t`: the `t` of a binary search for where the cubic of
/// coordinates `src` comes closest to `x`; `None` where the search ends at 1 (its steps,
/// halved each time, round `t` up to 1 in `f32` after about 24), which tiny-skia does not
/// take (it panics).
fn mono_cubic_closest_t(src: &[f32; 4], mut x: f32) -> Option<NormalizedF32Exclusive> {
    let mut t = 0.5f32;
    let mut last_t;
    let mut best_t = t;
    let mut step = 0.25f32;
    let d = src[0];
    let a = src[3] + 3.0 * (src[1] - src[2]) - d;
    let b = 3.0 * (src[2] - src[1] - src[1] + d);
    let c = 3.0 * (src[1] - d);
    x -= d;
    let mut closest = SCALAR_MAX;
    loop {
        let loc = ((a * t + b) * t + c) * t;
        let dist = (loc - x).abs();
        if closest > dist {
            closest = dist;
            best_t = t;
        }
        last_t = t;
        t += if loc < x { step } else { -step };
        step *= 0.5;
        if !(closest > 0.25 && last_t != t) {
            break;
        }
    }
    NormalizedF32Exclusive::new(best_t)
}

impl<F: FnMut(Clipped)> Clipper<F> {
    /// tiny-skia's `push_vline`: the vertical line at `x` from `y0` to `y1`, or back.
    fn push_vline(&mut self, x: f32, mut y0: f32, mut y1: f32, reverse: bool) {
        if reverse {
            std::mem::swap(&mut y0, &mut y1);
        }
        (self.out)(Clipped::Line(
            SkPoint::from_xy(x, y0),
            SkPoint::from_xy(x, y1),
        ));
    }

    /// tiny-skia's `push_quad`.
    fn push_quad(&mut self, pts: &[SkPoint; 3], reverse: bool) {
        (self.out)(Clipped::Quad(if reverse {
            [pts[2], pts[1], pts[0]]
        } else {
            *pts
        }));
    }

    /// tiny-skia's `push_cubic`.
    fn push_cubic(&mut self, pts: &[SkPoint; 4], reverse: bool) {
        (self.out)(Clipped::Cubic(if reverse {
            [pts[3], pts[2], pts[1], pts[0]]
        } else {
            *pts
        }));
    }

    /// tiny-skia's `clip_mono_quad`: `src` monotonic in x and y.
    fn clip_mono_quad(&mut self, src: &[SkPoint; 3]) {
        let (mut pts, mut reverse) = sort_increasing_y(src);
        // Wholly above or below.
        if pts[2].y <= TOP || pts[0].y >= self.bottom {
            return;
        }
        chop_quad_in_y(self.bottom, &mut pts);
        if pts[0].x > pts[2].x {
            pts.swap(0, 2);
            reverse = !reverse;
        }
        let (left, right) = (LEFT, self.right);
        if pts[2].x <= left {
            // Wholly to the left.
            self.push_vline(left, pts[0].y, pts[2].y, reverse);
            return;
        }
        if pts[0].x >= right {
            // Wholly to the right (not culled).
            self.push_vline(right, pts[0].y, pts[2].y, reverse);
            return;
        }
        let mut tmp = [SkPoint::zero(); 5];
        // Partly to the left.
        if pts[0].x < left {
            if let Some(t) = chop_mono_quad_at(pts[0].x, pts[1].x, pts[2].x, left) {
                chop_quad_at(&pts, t, &mut tmp);
                self.push_vline(left, tmp[0].y, tmp[2].y, reverse);
                tmp[2].x = left;
                tmp[3].x = tmp[3].x.max(left);
                pts[0] = tmp[2];
                pts[1] = tmp[3];
            } else {
                // Inexact numerics: clamped to the left side.
                self.push_vline(left, pts[0].y, pts[2].y, reverse);
                return;
            }
        }
        // Partly to the right.
        if pts[2].x > right {
            if let Some(t) = chop_mono_quad_at(pts[0].x, pts[1].x, pts[2].x, right) {
                chop_quad_at(&pts, t, &mut tmp);
                tmp[1].x = tmp[1].x.min(right);
                tmp[2].x = right;
                self.push_quad(&[tmp[0], tmp[1], tmp[2]], reverse);
                self.push_vline(right, tmp[2].y, tmp[4].y, reverse);
            } else {
                pts[1].x = pts[1].x.min(right);
                pts[2].x = pts[2].x.min(right);
                self.push_quad(&pts, reverse);
            }
        } else {
            self.push_quad(&pts, reverse);
        }
    }

    /// tiny-skia's `clip_mono_cubic`: `src` monotonic in x and y.
    fn clip_mono_cubic(&mut self, src: &[SkPoint; 4]) {
        let (mut pts, mut reverse) = sort_increasing_y(src);
        // Wholly above or below.
        if pts[3].y <= TOP || pts[0].y >= self.bottom {
            return;
        }
        self.failed |= !chop_cubic_in_y(self.bottom, &mut pts);
        if pts[0].x > pts[3].x {
            pts.swap(0, 3);
            pts.swap(1, 2);
            reverse = !reverse;
        }
        let (left, right) = (LEFT, self.right);
        if pts[3].x <= left {
            self.push_vline(left, pts[0].y, pts[3].y, reverse);
            return;
        }
        if pts[0].x >= right {
            self.push_vline(right, pts[0].y, pts[3].y, reverse);
            return;
        }
        // Partly to the left.
        if pts[0].x < left {
            let mut tmp = [SkPoint::zero(); 7];
            self.failed |= !chop_mono_cubic_at_x(&pts, left, &mut tmp);
            self.push_vline(left, tmp[0].y, tmp[3].y, reverse);
            // The chopper's numerics forced to the right of the side.
            tmp[3].x = left;
            tmp[4].x = tmp[4].x.max(left);
            pts[0] = tmp[3];
            pts[1] = tmp[4];
            pts[2] = tmp[5];
        }
        // Partly to the right.
        if pts[3].x > right {
            let mut tmp = [SkPoint::zero(); 7];
            self.failed |= !chop_mono_cubic_at_x(&pts, right, &mut tmp);
            tmp[3].x = right;
            tmp[2].x = tmp[2].x.min(right);
            self.push_cubic(&[tmp[0], tmp[1], tmp[2], tmp[3]], reverse);
            self.push_vline(right, tmp[3].y, tmp[6].y, reverse);
        } else {
            self.push_cubic(&pts, reverse);
        }
    }
}
