//! SVG path commands in absolute coordinates, and their conversion to kurbo path elements.

use kurbo::{Arc, PathEl, Point, SvgArc};

/// Tolerance (in pixels) used by [`PathCommand::to_path_els`] to approximate arcs by cubics.
pub const ARC_FLATTEN_TOLERANCE: f64 = 1e-3;

/// One SVG path command, in absolute coordinates; the start point is the end of the previous
/// command.
#[derive(Clone, Copy, Debug)]
pub enum PathCommand {
    /// `L x y`.
    Line(Point),
    /// `A rx ry x_rotation large_arc sweep x y`, exact elliptical arc.
    Arc(SvgArc),
    /// `Q x1 y1 x y`: control point, end point.
    Quad(Point, Point),
    /// `C x1 y1 x2 y2 x y`: two control points, end point.
    Cubic(Point, Point, Point),
}

impl PartialEq for PathCommand {
    fn eq(&self, other: &PathCommand) -> bool {
        use PathCommand::*;
        match (*self, *other) {
            (Line(p), Line(q)) => p == q,
            (Quad(a, p), Quad(b, q)) => a == b && p == q,
            (Cubic(a1, a2, p), Cubic(b1, b2, q)) => a1 == b1 && a2 == b2 && p == q,
            (Arc(a), Arc(b)) => {
                a.from == b.from
                    && a.to == b.to
                    && a.radii == b.radii
                    && a.x_rotation == b.x_rotation
                    && a.large_arc == b.large_arc
                    && a.sweep == b.sweep
            }
            _ => false,
        }
    }
}

impl PathCommand {
    /// The command moved by `v`.
    pub fn translated(self, v: kurbo::Vec2) -> PathCommand {
        match self {
            PathCommand::Line(p) => PathCommand::Line(p + v),
            PathCommand::Quad(a, p) => PathCommand::Quad(a + v, p + v),
            PathCommand::Cubic(a, b, p) => PathCommand::Cubic(a + v, b + v, p + v),
            PathCommand::Arc(mut a) => {
                a.from += v;
                a.to += v;
                PathCommand::Arc(a)
            }
        }
    }

    /// The end point.
    pub fn end(&self) -> Point {
        match *self {
            PathCommand::Line(p) | PathCommand::Quad(_, p) | PathCommand::Cubic(_, _, p) => p,
            PathCommand::Arc(a) => a.to,
        }
    }

    /// Converts to kurbo path elements (without the initial `MoveTo`), starting at `start`.
    ///
    /// Arcs go through [`kurbo::Arc::from_svg_arc`] (with `from` replaced by `start`) and are
    /// approximated by cubics within 0.001 px; an arc that SVG treats as a
    /// straight line becomes a `LineTo`.
    pub fn to_path_els(&self, start: Point) -> Vec<PathEl> {
        let mut out = Vec::new();
        self.push_path_els(start, &mut out);
        out
    }

    /// [`PathCommand::to_path_els`] appended to `out` (a [`kurbo::BezPath`], say): no vector
    /// per command.
    pub fn push_path_els(&self, start: Point, out: &mut impl Extend<PathEl>) {
        match *self {
            PathCommand::Line(p) => out.extend([PathEl::LineTo(p)]),
            PathCommand::Quad(c, p) => out.extend([PathEl::QuadTo(c, p)]),
            PathCommand::Cubic(c1, c2, p) => out.extend([PathEl::CurveTo(c1, c2, p)]),
            PathCommand::Arc(a) => {
                let svg = SvgArc { from: start, ..a };
                match Arc::from_svg_arc(&svg) {
                    Some(arc) => out.extend(arc.append_iter(ARC_FLATTEN_TOLERANCE)),
                    None => out.extend([PathEl::LineTo(a.to)]),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_util::*;
    use crate::curve::LevelPath;
    use crate::curve::{level_curve_path, EllipseParams, Polynomial};
    use kurbo::ParamCurve;

    #[test]
    fn path_els_follow_the_commands() {
        let k = ellipse_conic(Point::new(40.0, 30.0), 15.0, 6.0, 0.8, 90.0);
        let poly = Polynomial::from(k);
        let EllipseParams {
            centre: c,
            radii: r,
            rotation: a,
        } = k.ellipse_params().unwrap();
        let from = ellipse_point(c, r.x, r.y, a, 0.5);
        let to = ellipse_point(c, r.x, r.y, a, 4.0);
        let guide: Vec<Point> = (1..20)
            .map(|i| ellipse_point(c, r.x, r.y, a, 0.5 + 3.5 * i as f64 / 20.0))
            .collect();
        let LevelPath { commands: cmds, .. } =
            level_curve_path(&poly, from, to, &guide, 0.05).unwrap();
        let mut path = kurbo::BezPath::new();
        path.move_to(from);
        let mut cur = from;
        for cmd in &cmds {
            cmd.push_path_els(cur, &mut path);
            cur = cmd.end();
        }
        let segs: Vec<kurbo::PathSeg> = path.segments().collect();
        assert!(!segs.is_empty());
        assert_point_close(segs.last().unwrap().end(), to, 1e-9, "kurbo path end");
        for seg in &segs {
            for i in 0..=8 {
                let d = poly.distance_estimate(seg.eval(i as f64 / 8.0));
                assert_le(
                    d,
                    2.0 * ARC_FLATTEN_TOLERANCE,
                    "flattened arc near the ellipse",
                );
            }
        }
        // Lines, quads and cubics map one to one.
        let p = Point::new(1.0, 2.0);
        assert_eq!(
            PathCommand::Line(p).to_path_els(Point::ZERO),
            vec![PathEl::LineTo(p)]
        );
        assert_eq!(
            PathCommand::Quad(p, p).to_path_els(Point::ZERO),
            vec![PathEl::QuadTo(p, p)]
        );
        assert_eq!(
            PathCommand::Cubic(p, p, p).to_path_els(Point::ZERO),
            vec![PathEl::CurveTo(p, p, p)]
        );
    }
}
