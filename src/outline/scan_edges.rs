//! The edges of one scan of [`super::scan`]: whether tiny-skia's edge clipper runs in each
//! of its fills ([`clips`]: `scan::path::fill_path`'s rule in tiny-skia 0.12), and each
//! line and curve of the path set up in each fill as tiny-skia sets it up there — as it is,
//! or through the edge clipper ([`super::line_clip`], [`super::curve_clip`]) — once for all
//! fills where they draw it alike.

use super::curve_clip::{clip_cubic, clip_quad, Clipped};
use super::edges::{Crossings, Tag};
use super::line_clip::clip_line;
use tiny_skia_path::Point as SkPoint;

/// A point of the path as tiny-skia gets it in each fill of a scan: as it is, moved by
/// `shift`, moved by `−shift` (see [`super::scan::painted_moved`]).
pub(super) type Moved = [SkPoint; 3];

/// tiny-skia's `CONSERVATIVE_ROUND_BIAS`: half a pixel and 1.5/64.
const CONSERVATIVE_ROUND_BIAS: f64 = 0.5 + 1.5 / 64.0;

/// Whether tiny-skia (`scan::path::fill_path`) runs its edge clipper on a path with
/// points whose least and largest coordinates (in `f32`, as it gets them) are among
/// `points`, in a `w × h` mask: unless its bounds rounded out conservatively (by
/// [`CONSERVATIVE_ROUND_BIAS`]) lie inside the mask. Rounding a coordinate to `f32` keeps
/// the order, so the bounds of the `f32` points are the `f32` of the bounds.
pub(super) fn clips(points: [SkPoint; 4], (w, h): (i64, i64)) -> bool {
    let lo = |f: fn(&SkPoint) -> f32| points.iter().map(f).fold(f32::INFINITY, f32::min);
    let hi = |f: fn(&SkPoint) -> f32| points.iter().map(f).fold(f32::NEG_INFINITY, f32::max);
    let down = |v: f32| (f64::from(v) - CONSERVATIVE_ROUND_BIAS).ceil();
    let up = |v: f32| (f64::from(v) + CONSERVATIVE_ROUND_BIAS).floor();
    let contained = down(lo(|p| p.x)) >= 0.0
        && down(lo(|p| p.y)) >= 0.0
        && up(hi(|p| p.x)) <= w as f64
        && up(hi(|p| p.y)) <= h as f64;
    !contained
}

/// Whether a coordinate `v` (`f32`, as tiny-skia gets it) of a path lies where tiny-skia
/// leaves the path unclipped along a side of the mask `len` px long: within
/// `(−0.4765625, len + 0.4765625)`, the coordinates whose conservative rounding
/// (`ceil(v − 0.5 − 1.5/64)`, `floor(v + 0.5 + 1.5/64)`, in `f64`, see [`clips`]) lies in
/// `[0, len]` (`v ∓ 0.5234375` is exact in `f64`). Not a number: false.
#[inline]
pub(super) fn contained(v: f32, len: f32) -> bool {
    const IN: f32 = 1.0 - CONSERVATIVE_ROUND_BIAS as f32;
    v > -IN && v < len + IN
}

/// Why the edges of a scan were not all built.
pub(super) enum Stop {
    /// The scan does not apply (see [`super::scan::painted`]).
    GiveUp,
    /// A point lies where tiny-skia would clip the path, in a scan built unclipped.
    Clips,
}

/// How the edges of one scan are drawn: in `fills` fills, each clipped to `mask` (its
/// width and height) as tiny-skia's edge clipper clips it where `clip` says.
pub(super) struct Draw {
    /// How many fills (1 or 3).
    fills: usize,
    /// Whether tiny-skia clips each fill.
    clip: [bool; 3],
    /// The mask's width and height.
    mask: (f32, f32),
    /// Every fill is clipped.
    all: bool,
}

/// The set-up of one kind of curve of `P` points.
pub(super) struct CurveKind<const P: usize> {
    /// In every fill, from one set of edges where it moves with the path
    /// ([`Crossings::quad_in_fills`]).
    in_fills: fn(&mut Crossings, [Moved; P], usize),
    /// Unclipped, cut where it turns ([`Crossings::quad`]).
    whole: fn(&mut Crossings, [SkPoint; P]),
    /// Through tiny-skia's edge clipper ([`super::curve_clip::clip_quad`]); false where
    /// tiny-skia would panic.
    clip: fn(&mut Crossings, [SkPoint; P], (f32, f32)) -> bool,
}

/// Quadratics' [`CurveKind`].
pub(super) const QUAD: CurveKind<3> = CurveKind {
    in_fills: |e, p, fills| e.quad_in_fills(|k| p.map(|m| m[k]), fills),
    whole: Crossings::quad,
    clip: |e, p, mask| {
        clip_quad(p, mask, |c| clipped_edge(e, c));
        true
    },
};

/// Cubics' [`CurveKind`].
pub(super) const CUBIC: CurveKind<4> = CurveKind {
    in_fills: |e, p, fills| e.cubic_in_fills(|k| p.map(|m| m[k]), fills),
    whole: Crossings::cubic,
    clip: |e, p, mask| clip_cubic(p, mask, |c| clipped_edge(e, c)),
};

/// Sets up an edge of tiny-skia's edge clipper.
fn clipped_edge(edges: &mut Crossings, c: Clipped) {
    match c {
        Clipped::Line(a, b) => edges.line(a, b),
        Clipped::Quad(p) => edges.mono_quad(&p),
        Clipped::Cubic(p) => edges.mono_cubic(&p),
    }
}

impl Draw {
    /// How edges are drawn in `fills` fills, each clipped to `mask` where `clip` says.
    pub(super) fn new(fills: usize, clip: [bool; 3], mask: (f32, f32)) -> Draw {
        let clip_of = &clip[..fills];
        Draw {
            fills,
            clip,
            mask,
            all: clip_of.iter().all(|&c| c),
        }
    }

    /// Whether every point, in every fill, lies within `margin` px inside the mask.
    #[inline]
    fn inside<const P: usize>(&self, p: &[Moved; P], margin: f32) -> bool {
        let (w, h) = self.mask;
        p.iter().all(|m| {
            m[..self.fills]
                .iter()
                .all(|q| q.x >= margin && q.y >= margin && q.x <= w - margin && q.y <= h - margin)
        })
    }

    /// The line `p` in each fill: once for all (`shared`: [`Tag::SHARED`] for the path's,
    /// moving with it, [`Tag::FIXED`] for the reference's) where every fill draws it
    /// alike, else once per fill.
    #[inline]
    pub(super) fn line(&self, edges: &mut Crossings, p: [Moved; 2], shared: Tag) {
        edges.tag = shared;
        // Inside the mask, on its sides included, the clipper leaves a line as it is (a
        // horizontal line on the top or bottom, which it drops, covers no row).
        if self.all && self.inside(&p, 0.0) {
            edges.line(p[0][0], p[1][0]);
        } else if self.all && shared == Tag::FIXED {
            // The reference's: the same in every fill.
            clip_line([p[0][0], p[1][0]], self.mask, |a, b| edges.line(a, b));
        } else {
            for k in 0..self.fills {
                if self.fills > 1 {
                    edges.tag = Tag(1 << k);
                }
                if self.clip[k] {
                    clip_line([p[0][k], p[1][k]], self.mask, |a, b| edges.line(a, b));
                } else {
                    edges.line(p[0][k], p[1][k]);
                }
            }
            edges.tag = Tag::SHARED;
        }
    }

    /// Whether the points `p` all lie on or beyond one side of the mask (as `mask_fill`'s
    /// `Segment::beyond` tells them).
    fn beyond_a_side(&self, p: &[SkPoint]) -> bool {
        let (w, h) = self.mask;
        p.iter().all(|q| q.x <= 0.0)
            || p.iter().all(|q| q.x >= w)
            || p.iter().all(|q| q.y <= 0.0)
            || p.iter().all(|q| q.y >= h)
    }

    /// The curve `p` of `kind` in each fill: once for all where every fill is clipped and
    /// the curve lies a pixel inside the mask in each (the clipper then
    /// only cuts it where it turns in x, [`Crossings::x_chops`]); else once per fill,
    /// through the clipper where that fill is clipped. False where tiny-skia would panic
    /// (the crossings are then not its).
    #[must_use]
    #[inline]
    pub(super) fn curve<const P: usize>(
        &self,
        edges: &mut Crossings,
        p: [Moved; P],
        kind: &CurveKind<P>,
    ) -> bool {
        if self.all && self.inside(&p, 1.0) {
            edges.x_chops = true;
            (kind.in_fills)(edges, p, self.fills);
        } else {
            for k in 0..self.fills {
                if self.fills > 1 {
                    edges.tag = Tag(1 << k);
                }
                let pk = p.map(|m| m[k]);
                if self.clip[k] {
                    if self.beyond_a_side(&pk) {
                        // As `mask_fill` hands it to tiny-skia: one line (its `Collapsing`),
                        // which the clipper turns into the same vertical line on the side,
                        // or drops, as the curve's parts.
                        clip_line([pk[0], pk[P - 1]], self.mask, |a, b| edges.line(a, b));
                    } else if !(kind.clip)(edges, pk, self.mask) {
                        return false;
                    }
                } else {
                    edges.x_chops = false;
                    (kind.whole)(edges, pk);
                }
            }
            edges.tag = Tag::SHARED;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::render_check::{Reference, Window};
    use super::super::scan::tests::tiny_skia_indices;
    use super::super::scan::{painted, painted_moved};
    use super::*;
    use crate::curve::PathCommand;
    use kurbo::Point;
    use proptest::prelude::*;

    /// The window of the tests: `w × h` pixels at (100, 50).
    fn window(w: i64, h: i64) -> Window {
        Window {
            x0: 100,
            y0: 50,
            x1: 100 + w,
            y1: 50 + h,
        }
    }

    /// A coordinate from random numbers, along a side of `len` px of the window starting
    /// at `origin`: with `sel` below 64, on one of its sides or up to 2/64 px off it
    /// (curves ending on or grazing a side); else `u` in `−len .. 2 len` on the `1/grid`
    /// grid, moved `far` times as far from the window's middle.
    fn coordinate(sel: u8, u: u16, origin: i64, len: i64, grid: f64, far: f64) -> f64 {
        let len = len as f64;
        let v = if sel < 64 {
            let side = if sel & 1 == 0 { 0.0 } else { len };
            side + f64::from(i32::from(sel >> 1 & 7) - 3) / 64.0 * f64::from(sel >> 4 & 1)
        } else {
            let v = (f64::from(u) / 65535.0 * 3.0 * len - len) * grid;
            let mid = len / 2.0;
            mid + (v.round() / grid - mid) * far
        };
        origin as f64 + v
    }

    /// A random path (lines, quadratics, cubics; control points `far` times as far from
    /// the window's middle as their ends may be) round and across the `w × h` window, and a
    /// random polygon of whole points round it as the reference.
    #[allow(clippy::type_complexity)]
    fn random_path(
        path: &[(u8, [(u8, u16); 6])],
        refp: &[(i32, i32)],
        (w, h): (i64, i64),
        grid: f64,
        far: f64,
    ) -> (Point, Vec<PathCommand>, Reference) {
        let win = window(w, h);
        let q = |(sx, ux): (u8, u16), (sy, uy): (u8, u16), far: f64| {
            Point::new(
                coordinate(sx, ux, win.x0, w, grid, far),
                coordinate(sy, uy, win.y0, h, grid, far),
            )
        };
        let commands: Vec<PathCommand> = path
            .iter()
            .map(|&(k, v)| match k % 3 {
                0 => PathCommand::Line(q(v[0], v[1], 1.0)),
                1 => PathCommand::Quad(q(v[0], v[1], far), q(v[2], v[3], 1.0)),
                _ => PathCommand::Cubic(q(v[0], v[1], far), q(v[2], v[3], far), q(v[4], v[5], 1.0)),
            })
            .collect();
        let start = commands[commands.len() - 1].end();
        let r = |&(x, y): &(i32, i32)| {
            Point::new(
                (win.x0 + i64::from(x)) as f64,
                (win.y0 + i64::from(y)) as f64,
            )
        };
        let rc: Vec<PathCommand> = refp[1..].iter().map(|p| PathCommand::Line(r(p))).collect();
        (start, commands, Reference::new(r(&refp[0]), &rc))
    }

    /// A point's random coordinates: a selector (sides) and a value.
    fn coords() -> impl Strategy<Value = [(u8, u16); 6]> {
        prop::array::uniform6((any::<u8>(), any::<u16>()))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1024))]
        /// The same pixels as tiny-skia's own fill for random paths of lines, quadratics and
        /// cubics round and across their window on every side — ending on its sides,
        /// grazing them, lying wholly beyond each, control points far outside — curves
        /// drawn clipped or not (tiny-skia then clips them where the path's bounds leave
        /// the mask), against random references, some of which leave the window too.
        #[test]
        fn curves_across_the_window_as_in_tiny_skia(
            path in prop::collection::vec((any::<u8>(), coords()), 1..8),
            refp in prop::collection::vec((-6i32..46, -6i32..46), 3..8),
            w in 1i64..40,
            h in 1i64..40,
            grid in prop::sample::select(vec![1.0, 2.0, 64.0, 1000.0]),
            far in prop::sample::select(vec![1.0, 1.0, 3.0, 50.0, 1e5, 1e7]),
            clipped in any::<bool>(),
        ) {
            let (start, commands, reference) = random_path(&path, &refp, (w, h), grid, far);
            let win = window(w, h);
            let theirs = std::panic::catch_unwind(|| {
                tiny_skia_indices(&reference, start, &commands, &win, clipped)
            });
            // Left to tiny-skia only where it panics.
            let ours = painted(&reference, start, &commands, &win, clipped);
            prop_assert_eq!(ours, theirs.ok());
        }

        /// The three fills of one scan are tiny-skia's fills of the path as it is and moved
        /// by `±shift`, for random paths on the 1/64-px grid round and across their window
        /// (points within 2^17 px, where `f32` holds the grid),
        /// curves clipped or not: each fill clipped where tiny-skia clips that path.
        #[test]
        fn moved_fills_across_the_window_as_in_tiny_skia(
            path in prop::collection::vec((any::<u8>(), coords()), 1..8),
            refp in prop::collection::vec((-6i32..46, -6i32..46), 3..8),
            w in 1i64..40,
            h in 1i64..40,
            grid in prop::sample::select(vec![1.0, 4.0, 64.0]),
            far in prop::sample::select(vec![1.0, 1.0, 3.0, 50.0, 1000.0]),
            clipped in any::<bool>(),
            k in 1u8..3,
        ) {
            let (start, commands, reference) = random_path(&path, &refp, (w, h), grid, far);
            let win = window(w, h);
            let shift = f64::from(k) / 64.0;
            let all = painted_moved(&reference, start, &commands, &win, clipped, shift, false);
            let mut panics = false;
            for (fill, d) in [0.0, shift, -shift].into_iter().enumerate() {
                let v = kurbo::Vec2::new(d, 0.0);
                let moved: Vec<PathCommand> = commands.iter().map(|c| c.translated(v)).collect();
                let expected = std::panic::catch_unwind(|| {
                    tiny_skia_indices(&reference, start + v, &moved, &win, clipped)
                });
                match (&all, expected) {
                    (Some(all), Ok(expected)) => prop_assert_eq!(&all[fill], &expected, "fill {}", fill),
                    (_, Err(_)) => panics = true,
                    (None, Ok(_)) => {}
                }
            }
            // Left to tiny-skia only where it panics on one of the three.
            prop_assert_eq!(all.is_none(), panics);
        }
    }

    #[test]
    fn contained_coordinates_are_those_rounded_into_the_mask() {
        let lo = SkPoint::from_xy(0.0, 0.0);
        for len in [1i64, 7, 256, 8191] {
            for k in -2000i32..2000 {
                for v in [
                    k as f32 / 1024.0,
                    len as f32 + k as f32 / 1024.0,
                    (k as f32 / 1024.0).next_up(),
                    (len as f32 + k as f32 / 1024.0).next_down(),
                ] {
                    let p = SkPoint::from_xy(v, v);
                    let rounded_in = !clips([p, lo, lo, lo], (len, len));
                    assert_eq!(contained(v, len as f32), rounded_in, "{v} in {len}");
                }
            }
        }
    }

    #[test]
    fn tiny_skia_clips_paths_whose_rounded_out_bounds_leave_the_mask() {
        let p = |x: f32, y: f32| SkPoint::from_xy(x, y);
        let (lo, hi) = (p(5.0, 5.0), p(6.0, 6.0));
        // Bounds within 0.4765625 px (half a pixel less 1.5/64) of the sides stay inside.
        assert!(!clips([p(-0.47, 0.0), lo, hi, p(10.47, 10.47)], (10, 10)));
        assert!(clips([p(-0.48, 0.0), lo, hi, hi], (10, 10)));
        assert!(clips([lo, hi, hi, p(10.48, 1.0)], (10, 10)));
        assert!(clips([lo, hi, p(1.0, 10.48), hi], (10, 10)));
        assert!(clips([p(1.0, -0.4765625), lo, hi, hi], (10, 10)));
    }
}
