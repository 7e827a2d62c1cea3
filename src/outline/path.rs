//! The closed path of one contour and the counts of what went into it.

use crate::curve::PathCommand;
use kurbo::{BezPath, PathEl, Point, Rect};

/// Number of path commands of each type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CommandCounts {
    /// `M`: one per contour.
    pub move_to: usize,
    /// `L`: straight pieces, bridges between pieces, crack fallbacks.
    pub line: usize,
    /// `A`: circular and elliptical arcs.
    pub arc: usize,
    /// `Q`: parabola arcs.
    pub quad: usize,
    /// `C`: fitted cubics.
    pub cubic: usize,
    /// `Z`: one per contour.
    pub close: usize,
}

impl CommandCounts {
    /// All commands.
    pub fn total(&self) -> usize {
        self.move_to + self.line + self.arc + self.quad + self.cubic + self.close
    }
}

impl std::ops::AddAssign<&CommandCounts> for CommandCounts {
    fn add_assign(&mut self, o: &CommandCounts) {
        self.move_to += o.move_to;
        self.line += o.line;
        self.arc += o.arc;
        self.quad += o.quad;
        self.cubic += o.cubic;
        self.close += o.close;
    }
}

/// Pieces not drawn along their own border curve, by reason. A piece of three points or more
/// whose curve is not used is drawn as its exact polygon (digital straight segments); one of
/// one or two points along its cracks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct FallbackCounts {
    /// Stretches of one or two points (no equation: the zero certificate) drawn along their
    /// cracks, pieces of the decomposition and remainders of polygons alike.
    pub zero_certificate: usize,
    /// `border_polynomial` gave no polynomial: the piece is drawn as its polygon.
    pub no_polynomial: usize,
    /// The border curve passes closer to a pixel centre than the minimum clearance asked
    /// for: the piece is drawn as its polygon.
    pub thin: usize,
    /// The piece has fewer contour points than the fewest drawn along a curve: drawn as its
    /// polygon.
    pub short: usize,
    /// The piece has more contour points than the most drawn along a curve: drawn as its
    /// polygon.
    pub long: usize,
    /// The curve could not be drawn between its junctions (no point near a junction,
    /// `level_curve_path` failed, or the drawing strays from the pixels): drawn as its
    /// polygon.
    pub curve: usize,
    /// The renderer check found a pixel on the wrong side near the piece's curve: drawn as
    /// its polygon.
    pub rendered: usize,
    /// Digital straight segments halved because the renderer drew them wrongly.
    pub split: usize,
    /// The pieces did not cover the contour consecutively, or repairs did not converge:
    /// the whole contour was drawn along its cracks (counted once per contour).
    pub invalid_pieces: usize,
}

impl FallbackCounts {
    /// All fallbacks.
    pub fn total(&self) -> usize {
        self.zero_certificate
            + self.no_polynomial
            + self.thin
            + self.short
            + self.long
            + self.curve
            + self.rendered
            + self.split
            + self.invalid_pieces
    }
}

impl std::ops::AddAssign<&FallbackCounts> for FallbackCounts {
    fn add_assign(&mut self, o: &FallbackCounts) {
        self.zero_certificate += o.zero_certificate;
        self.no_polynomial += o.no_polynomial;
        self.thin += o.thin;
        self.short += o.short;
        self.long += o.long;
        self.curve += o.curve;
        self.rendered += o.rendered;
        self.split += o.split;
        self.invalid_pieces += o.invalid_pieces;
    }
}

/// How consecutive pieces were joined.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JoinCounts {
    /// At the intersection of the two curves.
    pub intersection: usize,
    /// Otherwise: projections (or crack ends) bridged by a segment when distinct.
    pub bridged: usize,
    /// Straight segments that do not intersect near their junction, ending at one shared
    /// vertex instead of a bridge.
    pub shared: usize,
    /// Repaired: the two end pixels drawn along their cracks.
    pub cracked: usize,
}

impl std::ops::AddAssign<&JoinCounts> for JoinCounts {
    fn add_assign(&mut self, o: &JoinCounts) {
        self.intersection += o.intersection;
        self.bridged += o.bridged;
        self.shared += o.shared;
        self.cracked += o.cracked;
    }
}

/// The closed path of one contour, in absolute SVG coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContourPath {
    /// The `M` point. Meaningless when `commands` is empty (a contour without points).
    pub start: Point,
    /// The commands after the `M`; the path is closed after the last one (`Z`).
    pub commands: Vec<PathCommand>,
    /// Largest measured distance of fitted cubics to their curve (0 for exact forms).
    pub max_fit_error: f64,
    /// Pieces drawn along their cracks, by reason.
    pub fallbacks: FallbackCounts,
    /// Joins between consecutive pieces.
    pub joins: JoinCounts,
}

impl ContourPath {
    /// The bounds of every point written (vertices and control points; arcs as their whole
    /// ellipse), as tiny-skia's and Skia's `Path::bounds` see the path; `None` for an empty
    /// contour.
    pub fn point_bounds(&self) -> Option<Rect> {
        if self.commands.is_empty() {
            return None;
        }
        let mut b = Rect::from_points(self.start, self.start);
        for c in &self.commands {
            match *c {
                PathCommand::Line(p) => b = b.union_pt(p),
                PathCommand::Quad(a, p) => b = b.union_pt(a).union_pt(p),
                PathCommand::Cubic(a, q, p) => b = b.union_pt(a).union_pt(q).union_pt(p),
                PathCommand::Arc(a) => {
                    let r = a.radii.x.abs().max(a.radii.y.abs()) * 2.0;
                    b = b
                        .union_pt(a.to - kurbo::Vec2::new(r, r))
                        .union_pt(a.to + kurbo::Vec2::new(r, r));
                }
            }
        }
        Some(b)
    }

    /// The path as a kurbo [`BezPath`] (arcs approximated by cubics within
    /// 0.001 px), closed; empty for an empty contour.
    pub fn to_bez_path(&self) -> BezPath {
        let mut path = BezPath::new();
        if self.commands.is_empty() {
            return path;
        }
        path.push(PathEl::MoveTo(self.start));
        let mut pen = self.start;
        for c in &self.commands {
            c.push_path_els(pen, &mut path);
            pen = c.end();
        }
        path.push(PathEl::ClosePath);
        path
    }

    /// The number of SVG commands of each type (`M` and `Z` included).
    pub fn counts(&self) -> CommandCounts {
        let mut n = CommandCounts::default();
        if self.commands.is_empty() {
            return n;
        }
        n.move_to = 1;
        n.close = 1;
        for c in &self.commands {
            match c {
                PathCommand::Line(_) => n.line += 1,
                PathCommand::Arc(_) => n.arc += 1,
                PathCommand::Quad(..) => n.quad += 1,
                PathCommand::Cubic(..) => n.cubic += 1,
            }
        }
        n
    }
}
