//! Border tracing (provisional: replaced by the tracing branch).
use crate::pixel::Pixel;

/// A traced border.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Contour {
    /// The path.
    pub points: Vec<Pixel>,
    /// True for a hole border.
    pub hole: bool,
    /// True for a closed path.
    pub closed: bool,
}

/// Tracing conventions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// Documented default.
    Default,
    /// The paper's code.
    Ipol,
}
