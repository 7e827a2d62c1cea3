//! Border tracing: turning a [`Mask`] into chains of boundary pixels.
//!
//! Two conventions are offered (see [`Convention`]); both are iterative and run in time
//! linear in the number of pixels plus the total contour length:
//! - `moore`: the default convention, Moore-neighbour tracing of each component and hole;
//! - `runs`: the components and holes, from the rows' runs joined by a union–find;
//! - `crack`: the IPOL convention, crack following as the article's reference code does;
//! - `borders`: the borders between the regions of a colour image ([`BorderGraph`]), cut at
//!   their junctions, for the partition layout.

mod borders;
mod crack;
mod moore;
mod runs;
#[cfg(test)]
mod tests;

pub(crate) use borders::crack_sides;
pub use borders::{Border, BorderGraph};

use crate::bitmap::Mask;
use crate::pixel::Pixel;
use crack::trace_ipol;
use moore::trace_default;

/// One traced border: a chain of foreground pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Contour {
    /// The pixels in tracing order; consecutive points are 8-adjacent and distinct.
    /// [`Convention::Default`] does not repeat the first point at the end;
    /// [`Convention::Ipol`] does for closed contours.
    pub points: Vec<Pixel>,
    /// True for the border of a hole (a bounded background region), false for an outer
    /// border (and for every open chain).
    pub hole: bool,
    /// False only for [`Convention::Ipol`] chains that end on the image border.
    pub closed: bool,
}

/// Contours of at most this many points are *tiny*: noise, halftones and dotted lines are
/// made of them, and their shapes repeat (see [`Contour::tiny_shape`]).
pub(crate) const TINY_POINTS: usize = 32;

impl Contour {
    /// The pixels the contour spans: columns `x0..x1` and rows `y0..y1`, as
    /// `[x0, y0, x1, y1]`. Returns `None` for an empty contour.
    pub(crate) fn pixel_box(&self) -> Option<[i64; 4]> {
        let first = self.points.first()?;
        let mut b = [i64::from(first.x), i64::from(first.y), 0, 0];
        b[2] = b[0] + 1;
        b[3] = b[1] + 1;
        for p in &self.points {
            let (x, y) = (i64::from(p.x), i64::from(p.y));
            b = [b[0].min(x), b[1].min(y), b[2].max(x + 1), b[3].max(y + 1)];
        }
        Some(b)
    }

    /// The points relative to the first one, when the contour is tiny (1 to
    /// [`TINY_POINTS`] points): what the per-shape memos of the decomposition and of the
    /// outline key on. `None` for an empty or larger contour.
    pub(crate) fn tiny_shape(&self) -> Option<Vec<(i32, i32)>> {
        let first = *self.points.first()?;
        (self.points.len() <= TINY_POINTS).then(|| {
            self.points
                .iter()
                .map(|p| (p.x - first.x, p.y - first.y))
                .collect()
        })
    }
}

/// Indices of `contours` by decreasing number of points, equal ones in their order: how the
/// parallel stages take them, so that no thread is left alone with a large contour at the
/// end (results go back in the contours' order).
pub(crate) fn largest_first(contours: &[Contour]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..contours.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(contours[k].points.len()));
    order
}

/// Which connectivity, start points, orientation and point lists [`trace`] produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Convention {
    /// layertrace's convention: 8-connected foreground, 4-connected background, outside the
    /// image is background.
    ///
    /// One closed contour per 8-connected foreground component (its outer border) and one
    /// per hole (bounded 4-connected background component). A contour's points are the
    /// foreground pixels having a 4-neighbour in the background region it separates from the
    /// foreground: the surrounding region for an outer border, the hole for a hole border.
    /// Foreground is on the left of the walk on screen (y down): outer borders run
    /// counter-clockwise, hole borders clockwise. An outer border starts at its component's
    /// first pixel in raster order (smallest y, then smallest x); a hole border at the pixel
    /// directly above the hole's first pixel in raster order. The first point is not
    /// repeated at the end. A pixel may appear several times (one-pixel-thin parts); an
    /// isolated pixel gives a one-point contour. Contours are listed in raster order of the
    /// first pixel of their component or hole.
    #[default]
    Default,
    /// The reference code of the IPOL 2014 article (`gjknd_1.1`): 4-connected foreground
    /// (ink), 8-connected background (paper).
    ///
    /// Contours follow the cracks (pixel edges) between ink and paper inside the image, ink on
    /// the walker's right (outer contours clockwise on screen, holes anticlockwise); each
    /// crack contributes its ink pixel, consecutive duplicates dropped. Chains reaching the
    /// image border are open (`closed = false`, the image border is not a crack); they are
    /// found first, by scanning the border cracks (vertical cracks of the top then bottom row,
    /// column by column, then horizontal cracks of the left then right column, row by row),
    /// and listed from the end found first, in whichever direction leads into the image.
    /// Closed contours are then found by scanning the interior cracks column by column
    /// (x, then y; at each pixel the crack on its right before the crack below it): an outer
    /// contour normally starts at the topmost pixel of its leftmost column, a hole at the ink
    /// pixel just left of the topmost pixel of the hole's leftmost column. A closed contour
    /// repeats its start pixel at the end.
    Ipol,
}

/// Traces every border of `mask` in the given convention (see [`Convention`]).
///
/// Pixel coordinates are `i32`: a mask wider or taller than `i32::MAX - 2` pixels gives no
/// contours (the loader's pixel limit keeps images far below that).
///
/// In the default convention the borders are traced in parallel on the current rayon pool:
/// within [`vectorize`](crate::vectorize), the pool of its options (`Options::pool`),
/// rayon's global pool when called on its own. The contours do not depend on the number of
/// threads.
///
/// ```
/// use layertrace::{trace, Convention, Mask};
/// let mask = Mask::from_ascii(
///     ".....
///      .###.
///      .#.#.
///      .###.
///      .....",
/// );
/// let contours = trace(&mask, Convention::Default);
/// // The ring's outer border and its hole's border.
/// assert_eq!(contours.len(), 2);
/// assert_eq!(contours.iter().filter(|c| c.hole).count(), 1);
/// ```
pub fn trace(mask: &Mask, convention: Convention) -> Vec<Contour> {
    let limit = (i32::MAX - 2) as u32;
    if mask.width() > limit || mask.height() > limit {
        return Vec::new();
    }
    match convention {
        Convention::Default => trace_default(mask),
        Convention::Ipol => trace_ipol(mask),
    }
}

/// True when `p` is a foreground pixel (false outside the image).
#[inline]
fn fg(mask: &Mask, p: Pixel) -> bool {
    mask.get(i64::from(p.x), i64::from(p.y))
}
