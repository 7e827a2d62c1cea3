//! The geometric kind of a curve.

/// The geometric kind of a [`Conic`](super::Conic), see
/// [`Conic::classify`](super::Conic::classify).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConicKind {
    /// No quadratic part: `d x + e y + f = 0` with `(d, e) ≠ 0`.
    Line,
    /// An ellipse with equal radii.
    Circle,
    /// A non-degenerate real ellipse that is not a circle.
    Ellipse,
    /// A non-degenerate parabola.
    Parabola,
    /// A non-degenerate hyperbola.
    Hyperbola,
    /// Everything else: empty real locus, a single point, two crossing lines, two parallel
    /// lines, a double line, or a constant (or non-finite) equation.
    Degenerate,
}
