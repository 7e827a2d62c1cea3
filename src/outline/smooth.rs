//! Renderer-safe cubics through an exact polygon: two straight segments become one smooth
//! cubic that tiny-skia still draws as (nearly) those two segments.
//!
//! tiny-skia and Skia draw a cubic as `2^k` chords between its points at `t = i / 2^k`, `k`
//! chosen from how far the curve bends; a flat cubic (`k = 1`) is drawn as the two chords
//! `B(0) → B(½) → B(1)`. So where the renderer check had to replace a curve by its exact
//! polygon `… A → M → B …` (digital straight segments), the cubic from `A` to `B` with
//! `B(½) = M`,
//!
//! ```text
//! B(½) = (A + 3 P1 + 3 P2 + B) / 8 = M,   P1 = A + α t_A,   P2 = B − β t_B,
//! ```
//!
//! with the tangents `t_A`, `t_B` of the polygon's vertices (the directions from the
//! previous vertex to the next, as a Catmull–Rom spline has them, so consecutive cubics
//! join smoothly), is drawn as that same polygon by the renderer and as a smooth curve by
//! everything that draws curves exactly (a vector editor, a zoomed-in view): half the
//! commands and no visible corners. Each such cubic is kept only if it changes no pixel
//! (its control points are snapped to the grid, and bent ones get more chords): the loop
//! from the cubic back along its two segments, filled alone by tiny-skia in a window of its
//! own, must paint nothing. The others go back to their two segments.

use super::builder::Builder;
use super::render_check::{finely_flattened, misplaced_pixels, EdgeClipping, Reference};
use crate::curve::PathCommand;
use kurbo::{Point, Vec2};

/// Largest turn (degrees) between two segments merged into a cubic: sharper turns are
/// corners of the shape, not polygon vertices of a curve.
pub const MAX_TURN_DEGREES: f64 = 40.0;

/// A merge of commands `i` and `i + 1` (two lines) into one cubic.
#[derive(Clone, Copy)]
struct Merge {
    /// Index of the first line.
    i: usize,
    cubic: PathCommand,
}

/// `v / |v|`; `None` for a zero vector.
fn unit(v: Vec2) -> Option<Vec2> {
    let h = v.hypot();
    (h > 0.0 && h.is_finite()).then(|| v / h)
}

/// The cubic from `a` through `m` (at `t = ½`) to `b` with tangent directions `ta` at `a`
/// and `tb` at `b`, control points snapped by `builder`. Returns `None` when the tangents
/// do not give control points ahead of `a` and behind `b` within the chord's length.
fn cubic_through(
    a: Point,
    m: Point,
    b: Point,
    ta: Vec2,
    tb: Vec2,
    snap: &Builder,
) -> Option<[Point; 2]> {
    // α t_A − β t_B = (8/3) (M − (A + B)/2).
    let rhs = (m - a.midpoint(b)) * (8.0 / 3.0);
    let det = ta.cross(-tb);
    if det.abs() < 1e-9 {
        return None;
    }
    let alpha = rhs.cross(-tb) / det;
    let beta = ta.cross(rhs) / det;
    let reach = (b - a).hypot();
    if !(alpha > 0.0 && beta > 0.0 && alpha < 0.75 * reach && beta < 0.75 * reach) {
        return None;
    }
    Some([snap.snap(a + ta * alpha), snap.snap(b - tb * beta)])
}

/// Replaces pairs of consecutive lines flagged in `smooth` (both of the pair) by cubics where
/// the path still paints exactly what `reference` paints; see the module documentation.
/// `start`, `commands` describe the closed path; `grid` is the builder's.
pub(crate) fn smooth_polygon(
    start: Point,
    commands: &[PathCommand],
    smooth: &[bool],
    reference: &Reference,
    grid: u8,
    clipping: EdgeClipping,
    canvas: Option<kurbo::Rect>,
) -> Vec<PathCommand> {
    let n = commands.len();
    let snap = Builder::new(grid);
    let vertex = |j: usize| if j == 0 { start } else { commands[j - 1].end() };
    let is_line = |j: usize| matches!(commands[j], PathCommand::Line(_));
    // Tangent at vertex j (the end of command j − 1): from vertex j − 1 to vertex j + 1.
    let tangent = |j: usize| -> Option<Vec2> {
        let prev = if j == 0 { vertex(n) } else { vertex(j - 1) };
        let next = if j >= n { vertex(1) } else { vertex(j + 1) };
        unit(next - prev)
    };
    let cos_max = MAX_TURN_DEGREES.to_radians().cos();
    let mut merges: Vec<Merge> = Vec::new();
    let mut i = 0;
    while i + 1 < n {
        let ok = smooth[i] && smooth[i + 1] && is_line(i) && is_line(i + 1);
        let (a, m, b) = (vertex(i), vertex(i + 1), vertex(i + 2));
        let turn_ok = match (unit(m - a), unit(b - m)) {
            (Some(u), Some(v)) => u.dot(v) >= cos_max,
            _ => false,
        };
        let cubic = (ok && turn_ok)
            .then(|| Some((tangent(i)?, tangent(i + 2)?)))
            .flatten()
            .and_then(|(ta, tb)| cubic_through(a, m, b, ta, tb, &snap));
        match cubic {
            Some([p1, p2]) => {
                merges.push(Merge {
                    i,
                    cubic: PathCommand::Cubic(p1, p2, b),
                });
                i += 2;
            }
            None => i += 1,
        }
    }
    let assemble = |merges: &[Merge]| -> Vec<PathCommand> {
        let mut out = Vec::with_capacity(n);
        let mut k = 0;
        let mut j = 0;
        while j < n {
            if k < merges.len() && merges[k].i == j {
                out.push(merges[k].cubic);
                j += 2;
                k += 1;
            } else {
                out.push(commands[j]);
                j += 1;
            }
        }
        out
    };
    // Each merge on its own: the closed loop `A —cubic→ B → M → A` winds, round each pixel
    // centre, the change the merge makes to the path's winding there (tiny-skia's scan
    // converter sums each edge's crossings by itself, and a line drawn both ways cancels).
    // The polygon is exact, so a merge whose loop paints no pixel in either of tiny-skia's
    // edge modes, nor finely flattened, leaves every pixel as it was; and merges that each
    // change nothing change nothing together. Small windows instead of whole-contour fills.
    merges.retain(|m| {
        let a = vertex(m.i);
        let mid = vertex(m.i + 1);
        let lp = [m.cubic, PathCommand::Line(mid), PathCommand::Line(a)];
        // The empty reference at A: the window is the loop's.
        let nothing = Reference::new(a, &[]);
        misplaced_pixels(&nothing, a, &lp, clipping, canvas).is_empty()
            && finely_flattened(a, &lp).is_none_or(|fine| {
                misplaced_pixels(&nothing, a, &fine, EdgeClipping::Never, None).is_empty()
            })
    });
    let out = assemble(&merges);
    debug_assert!(
        misplaced_pixels(reference, start, &out, clipping, canvas).is_empty(),
        "a smoothed path misplaces pixels"
    );
    out
}
