//! Builds a path command by command on the renderer's vertex grid, tracking the pen and
//! merging collinear lines.
//!
//! Every point written is snapped to the grid of multiples of `2^-grid` pixel. With
//! `grid <= 6` that is a subgrid of the 1/64-pixel grid on which tiny-skia and Skia place
//! vertices (26.6 fixed point), and such numbers are exact in `f32`: what is written is
//! what the renderer rasterizes, so the render check ([`super::render_check`]) sees the
//! renderer's own input. Elliptical arcs become cubics here: usvg would turn an `A` into
//! cubics of its own (within 0.1 px) and Chromium into conics, so neither the check nor two
//! renderers would agree on what an `A` draws.

use crate::curve::PathCommand;
use kurbo::{Arc, PathEl, Point, SvgArc};

/// Largest distance (pixels) of the cubics that replace an elliptical arc to the arc.
pub const ARC_TO_CUBIC_TOLERANCE: f64 = 0.01;

/// Snaps `v` to the nearest multiple of `1 / scale`.
fn snap_value(v: f64, scale: f64) -> f64 {
    round(v * scale) / scale
}

/// `v.round()` (halves away from zero, the sign kept) without its library call: x86-64's
/// baseline has no rounding instruction, and snapping called it for every point (1% of the
/// instructions on glyphs). Exact: below 2^52 the fraction `v − trunc(v)` is.
fn round(v: f64) -> f64 {
    if v.is_nan() || v.abs() >= 4_503_599_627_370_496.0 {
        return v.round();
    }
    let t = v as i64 as f64;
    let f = v - t;
    let r = if f >= 0.5 {
        t + 1.0
    } else if f <= -0.5 {
        t - 1.0
    } else {
        t
    };
    r.copysign(v)
}

/// Builds the path while tracking the pen.
pub(crate) struct Builder {
    /// `2^grid`: points are multiples of its inverse.
    scale: f64,
    start: Option<Point>,
    pen: Point,
    commands: Vec<PathCommand>,
    /// Where the last command began, when it is a line (to merge the next, collinear one).
    line_from: Option<Point>,
    /// Per command: drawn while [`Builder::smooth`] was set.
    tags: Vec<bool>,
    /// Commands added now may be smoothed ([`super::smooth`]).
    pub smooth: bool,
}

impl Builder {
    /// A builder snapping to multiples of `2^-grid` pixel (`grid` at most 20).
    pub(crate) fn new(grid: u8) -> Builder {
        Builder::with_capacity(grid, 0)
    }

    /// [`Builder::new`] with room for `commands` commands (no reallocation up to there).
    pub(crate) fn with_capacity(grid: u8, commands: usize) -> Builder {
        Builder {
            scale: f64::from(1u32 << grid.min(20)),
            start: None,
            pen: Point::ZERO,
            commands: Vec::with_capacity(commands),
            line_from: None,
            tags: Vec::with_capacity(commands),
            smooth: false,
        }
    }

    /// `p` on the grid.
    pub(crate) fn snap(&self, p: Point) -> Point {
        Point::new(snap_value(p.x, self.scale), snap_value(p.y, self.scale))
    }

    /// The commands so far.
    pub(crate) fn into_commands(self) -> (Option<Point>, Vec<PathCommand>) {
        (self.start, self.commands)
    }

    /// The commands so far and, per command, whether it may be smoothed.
    pub(crate) fn into_tagged(self) -> (Option<Point>, Vec<PathCommand>, Vec<bool>) {
        (self.start, self.commands, self.tags)
    }

    /// A line to `p` (snapped); one that continues the previous line in the same direction
    /// extends it instead, and one of length zero is dropped.
    pub(crate) fn goto(&mut self, p: Point) {
        let p = self.snap(p);
        match self.start {
            None => {
                self.start = Some(p);
                self.pen = p;
            }
            Some(_) => {
                if p == self.pen {
                    return;
                }
                let (d0, d1) = (self.pen - self.line_from.unwrap_or(p), p - self.pen);
                match self.commands.last_mut() {
                    // Grid coordinates: the cross product is exact.
                    Some(PathCommand::Line(end))
                        if self.line_from.is_some() && d0.cross(d1) == 0.0 && d0.dot(d1) > 0.0 =>
                    {
                        *end = p;
                    }
                    _ => {
                        self.line_from = Some(self.pen);
                        self.commands.push(PathCommand::Line(p));
                        self.tags.push(self.smooth);
                    }
                }
                self.pen = p;
            }
        }
    }

    /// Lines through `pts`.
    pub(crate) fn polyline(&mut self, pts: &[Point]) {
        for &p in pts {
            self.goto(p);
        }
    }

    /// Appends `cmds` (starting at the pen), every point snapped; arcs become cubics within
    /// [`ARC_TO_CUBIC_TOLERANCE`], lines go through [`Builder::goto`], and curves that
    /// collapse onto the grid (all points equal) are dropped.
    pub(crate) fn extend(&mut self, cmds: &[PathCommand]) {
        for c in cmds {
            match *c {
                PathCommand::Line(p) => self.goto(p),
                PathCommand::Quad(c1, p) => self.curve(&[c1, p]),
                PathCommand::Cubic(c1, c2, p) => self.curve(&[c1, c2, p]),
                PathCommand::Arc(a) => {
                    let svg = SvgArc {
                        from: self.pen,
                        ..a
                    };
                    match Arc::from_svg_arc(&svg) {
                        Some(arc) => {
                            for el in arc.append_iter(ARC_TO_CUBIC_TOLERANCE) {
                                match el {
                                    PathEl::CurveTo(c1, c2, p) => self.curve(&[c1, c2, p]),
                                    PathEl::QuadTo(c1, p) => self.curve(&[c1, p]),
                                    PathEl::LineTo(p) => self.goto(p),
                                    _ => {}
                                }
                            }
                        }
                        None => self.goto(a.to),
                    }
                }
            }
        }
    }

    /// A quadratic (two points) or cubic (three points) from the pen, snapped; a curve whose
    /// control points fall on its chord after snapping is a line.
    fn curve(&mut self, pts: &[Point]) {
        if self.start.is_none() {
            return;
        }
        let s: Vec<Point> = pts.iter().map(|&p| self.snap(p)).collect();
        let end = s[s.len() - 1];
        let straight = s[..s.len() - 1]
            .iter()
            .all(|&c| on_segment(self.pen, end, c));
        if straight {
            self.goto(end);
            return;
        }
        self.commands.push(if s.len() == 2 {
            PathCommand::Quad(s[0], s[1])
        } else {
            PathCommand::Cubic(s[0], s[1], s[2])
        });
        self.tags.push(false);
        self.line_from = None;
        self.pen = end;
    }
}

/// Whether `p` lies on the segment from `from` to `to`, ends included (exact on the grid's
/// points; a segment of no length holds only its point).
#[inline]
pub(super) fn on_segment(from: Point, to: Point, p: Point) -> bool {
    let (chord, v) = (to - from, p - from);
    v.cross(chord) == 0.0 && v.dot(chord) >= 0.0 && v.dot(chord) <= chord.hypot2()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_is_f64_round() {
        let mut v: Vec<f64> = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4_503_599_627_370_495.5,
            4.6e15,
            -4.6e15,
            1e300,
            f64::INFINITY,
            -f64::INFINITY,
            0.3,
            -0.3,
            12345.678,
            -12345.5,
        ];
        let mut x = 0.123_f64;
        for _ in 0..10_000 {
            x = (x * 9301.0 + 49297.0) % 233_280.0;
            v.push((x - 116_640.0) / 64.0);
            v.push((x - 116_640.0) / 7.0);
        }
        for v in v {
            assert_eq!(round(v).to_bits(), v.round().to_bits(), "{v}");
        }
        assert!(round(f64::NAN).is_nan());
    }

    #[test]
    fn collinear_lines_merge_and_turns_do_not() {
        let mut b = Builder::new(6);
        let p = |x: f64, y: f64| Point::new(x, y);
        b.polyline(&[
            p(0.0, 0.0),
            p(0.0, 1.0),
            p(0.0, 2.0),
            p(0.0, 3.0),
            p(1.0, 3.0),
        ]);
        b.polyline(&[p(2.0, 3.0), p(1.5, 3.0), p(1.5, 4.0)]);
        b.extend(&[PathCommand::Cubic(p(1.6, 4.5), p(1.4, 5.0), p(1.5, 5.5))]);
        b.goto(p(1.5, 6.0));
        let ends: Vec<Point> = b.commands.iter().map(|c| c.end()).collect();
        // Down the column in one line; the turn, the reversal along the row and the line
        // after a curve are kept.
        assert_eq!(
            ends,
            vec![
                p(0.0, 3.0),
                p(2.0, 3.0),
                p(1.5, 3.0),
                p(1.5, 4.0),
                p(1.5, 5.5),
                p(1.5, 6.0)
            ]
        );
    }

    #[test]
    fn points_land_on_the_grid_and_arcs_become_cubics() {
        let mut b = Builder::new(4);
        b.goto(Point::new(10.03, 0.0));
        b.extend(&[PathCommand::Arc(SvgArc {
            from: Point::new(10.0, 0.0),
            to: Point::new(0.0, 10.0),
            radii: kurbo::Vec2::new(10.0, 10.0),
            x_rotation: 0.0,
            large_arc: false,
            sweep: true,
        })]);
        let (start, cmds) = b.into_commands();
        assert_eq!(start, Some(Point::new(10.0, 0.0)));
        assert!(!cmds.is_empty(), "{cmds:?}");
        let mut pen = Point::new(10.0, 0.0);
        for c in &cmds {
            let PathCommand::Cubic(c1, c2, p) = *c else {
                panic!("not a cubic: {c:?}");
            };
            for q in [c1, c2, p] {
                assert_eq!((q.x * 16.0).fract(), 0.0);
                assert_eq!((q.y * 16.0).fract(), 0.0);
            }
            // Within the arc tolerance plus the snapping (√2/32) of the circle of radius 10.
            let cubic = kurbo::CubicBez::new(pen, c1, c2, p);
            for k in 0..=16 {
                let q = kurbo::ParamCurve::eval(&cubic, f64::from(k) / 16.0);
                let e = (q.to_vec2().hypot() - 10.0).abs();
                assert!(e < ARC_TO_CUBIC_TOLERANCE + 0.045, "{q:?} is {e} off");
            }
            pen = p;
        }
        assert_eq!(cmds.last().unwrap().end(), Point::new(0.0, 10.0));
        // A flat cubic whose control points snap onto its chord is a line.
        let mut b = Builder::new(2);
        b.goto(Point::new(0.0, 0.0));
        b.extend(&[PathCommand::Cubic(
            Point::new(1.0, 0.01),
            Point::new(2.0, -0.01),
            Point::new(3.0, 0.0),
        )]);
        assert_eq!(b.commands, vec![PathCommand::Line(Point::new(3.0, 0.0))]);
    }
}
