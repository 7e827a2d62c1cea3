//! The geometric kind of a curve: one enum for conics and for pieces' level curves.

/// The geometric kind of a curve: of a [`Conic`](super::Conic), as
/// [`Conic::classify`](super::Conic::classify) finds it, and of a piece's level curve, as
/// [`curve_kind`](crate::curve_kind) and [`piece_kind`](crate::piece_kind) report it in the
/// JSON output and the CLI summary (see [`CurveKind::name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum CurveKind {
    /// A straight line. As a conic: no quadratic part, `d x + e y + f = 0` with
    /// `(d, e) ≠ 0`.
    Line,
    /// A circle: an ellipse with equal radii.
    Circle,
    /// A non-degenerate real ellipse that is not a circle.
    Ellipse,
    /// A non-degenerate parabola.
    Parabola,
    /// A non-degenerate hyperbola.
    Hyperbola,
    /// Any other conic: empty real locus, a single point, two crossing lines, two parallel
    /// lines, a double line, or a constant (or non-finite) equation; also the zero function,
    /// or no polynomial at all.
    Degenerate,
    /// A curve of degree higher than 2 (never the kind of a [`Conic`](super::Conic)).
    Algebraic,
}

impl CurveKind {
    /// The JSON name: `line`, `circle`, `ellipse`, `parabola`, `hyperbola`, `degenerate`,
    /// `algebraic`.
    pub fn name(self) -> &'static str {
        match self {
            CurveKind::Line => "line",
            CurveKind::Circle => "circle",
            CurveKind::Ellipse => "ellipse",
            CurveKind::Parabola => "parabola",
            CurveKind::Hyperbola => "hyperbola",
            CurveKind::Degenerate => "degenerate",
            CurveKind::Algebraic => "algebraic",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names are part of the JSON output and the CLI summary: they must not change.
    #[test]
    fn names_are_the_json_names() {
        let all = [
            (CurveKind::Line, "line"),
            (CurveKind::Circle, "circle"),
            (CurveKind::Ellipse, "ellipse"),
            (CurveKind::Parabola, "parabola"),
            (CurveKind::Hyperbola, "hyperbola"),
            (CurveKind::Degenerate, "degenerate"),
            (CurveKind::Algebraic, "algebraic"),
        ];
        for (kind, name) in all {
            assert_eq!(kind.name(), name);
        }
    }
}
