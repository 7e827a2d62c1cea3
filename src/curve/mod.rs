//! Implicit curves `f(x, y) = 0` and exact SVG paths along them.
//!
//! A border piece of a shape is described by a bivariate [`Polynomial`] `f` of degree at most
//! [`MAX_DEGREE`]; the part of the level curve `f = 0` between two points is turned into SVG
//! path commands by [`level_curve_path`]:
//!
//! * lines become one `L`,
//! * circles and ellipses become exact `A` arcs ([`kurbo::SvgArc`]),
//! * parabolas become one exact quadratic Bézier `Q` (a parabola arc *is* a quadratic Bézier),
//! * hyperbolas, degenerate conics and curves of degree > 2 are traced numerically and fitted
//!   by cubic Béziers `C` whose measured distance to the true curve is reported.
//!
//! All coordinates are absolute SVG coordinates, where pixel `(x, y)` is the unit square
//! `[x, x+1] × [y, y+1]`. Distances are in pixels.
//!
//! One concept per file: [`Polynomial`] (`polynomial.rs`), [`Conic`] and its classification
//! (`conic.rs`), [`CurveKind`], the kind of a conic or of a piece's level curve (`kind.rs`),
//! [`PathCommand`] (`command.rs`), the solvers [`project`] and [`intersect_near`]
//! (`solve.rs`), [`level_curve_path`] (`path.rs`) with its exact arcs (`arcs.rs`), its traces
//! of the other curves (`trace.rs`) and their cubic fits (`fit.rs`); a cubic's power form for
//! Newton's steps (`power.rs`).

mod arcs;
mod command;
mod conic;
mod fit;
mod kind;
mod path;
mod polynomial;
mod power;
mod solve;
#[cfg(test)]
mod test_util;
mod trace;

pub use command::PathCommand;
pub use conic::{Conic, EllipseParams, HyperbolaParams, ParabolaParams};
pub use kind::CurveKind;
pub use path::{level_curve_path, LevelPath};
pub use polynomial::{Polynomial, MAX_DEGREE};
pub(crate) use power::PowerCubic;
pub use solve::{intersect_near, project};
