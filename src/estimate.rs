//! Upper estimate of the memory the stages after tracing need, from the contours alone: a
//! caller can refuse an input before [`decompose`](crate::decompose),
//! [`svg_document`](crate::svg_document) and [`fidelity`](crate::fidelity) allocate it.
//!
//! # The model
//! For contours of `p_i` points (`P = Σ p_i`, `C` contours, `p_max` the longest), basis
//! dimension `n`, `T` worker threads and a `W × H` image, in bytes:
//! * contours (already allocated, kept by the decomposition): `C · 48 + P · 16` (a point is
//!   8 bytes, a vector's capacity at most twice its length);
//! * pieces: every piece but a contour's last has at least two points (a two-point piece
//!   is always described), so at most `p_i / 2 + 1` pieces, each a [`Piece`] plus its
//!   certificate's two vectors; plus the recognizer's sets and the greedy's maps for the
//!   longest contour in each thread;
//! * the SVG document: at most [`SVG_BYTES_PER_POINT`] per point and
//!   [`SVG_BYTES_PER_CONTOUR`] per contour (crack fallbacks are the longest: a few
//!   commands per pixel), doubled for the string's growth; plus each thread's drawing of a
//!   contour ([`DRAW_BYTES_PER_POINT`] per point of the longest);
//! * the fidelity check: the SVG parsed and rendered by resvg ([`FIDELITY_BYTES_PER_SVG_BYTE`] per
//!   byte of the document), a `W × H` RGBA pixmap and two bit masks.
//!
//! The document is alive during the fidelity check; the pieces during both. The constants
//! are measured maxima with a margin (`cargo run --release --example cost_table -- --memory
//! INPUT…` prints measured peaks next to this estimate): on the checkerboard, noise and the
//! samples the estimate is 1.8 to 3.8 times the measured peak; on long smooth contours up to
//! 40 times (a one-pixel spiral of a million points: 1.5 GB estimated, 39 MB used), since
//! before decomposing nothing rules out one piece per two points drawn along its cracks.

use crate::contour::Contour;
use crate::decompose::Piece;
use crate::model::{Basis, Model};

/// Bytes of the heap allocator's bookkeeping per allocation (glibc: 16), and the rounding
/// of small blocks.
const ALLOCATION: u64 = 32;

/// Upper bound of SVG path data per contour point (precision 3): a crack fallback writes at
/// most two `L x y` commands per pixel, merged along straight runs; fitted curves write less
/// per pixel on pieces of more than a few pixels. Measured: 19.6 bytes per point on the
/// checkerboard, 13.6 on noise (conic; 21.8 with poly:6), 0.05 on the spirals.
pub const SVG_BYTES_PER_POINT: u64 = 32;

/// Upper bound of SVG path data per contour besides its points (`M`, `Z`, the first point).
pub const SVG_BYTES_PER_CONTOUR: u64 = 32;

/// Memory of drawing one contour, per point: the contour's pixel set, its closed path as
/// kurbo elements, the winding rows of the repair check and the commands. Measured: the
/// whole run on a spiral of a million points peaks at 39 bytes per point.
pub const DRAW_BYTES_PER_POINT: u64 = 128;

/// Memory of the fidelity check per byte of SVG: the document parsed (roxmltree, usvg), its
/// path in tiny-skia's form and the edges resvg fills. Measured with the resvg round trip:
/// 4.5 on the checkerboard (163 MB of SVG, 0.7 GB more peak with `--report` than without);
/// 8 leaves a margin for cubic-heavy documents.
pub const FIDELITY_BYTES_PER_SVG_BYTE: u64 = 8;

/// The estimate, in bytes, by stage; [`bytes`](WorkEstimate::bytes) is the peak.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WorkEstimate {
    /// Upper estimate of the peak: contours + decomposition + SVG document + the larger of
    /// the SVG drawing scratch and the fidelity check.
    pub bytes: u64,
    /// The contours (allocated already by tracing).
    pub contours: u64,
    /// The pieces, and the recognizers' scratch.
    pub decomposition: u64,
    /// The SVG document.
    pub svg_document: u64,
    /// Drawing the contours (per thread, transient).
    pub svg_drawing: u64,
    /// Rasterizing the SVG back and comparing.
    pub fidelity: u64,
}

/// An upper estimate of the memory that decomposing `contours` with `model`, writing the SVG
/// and checking its fidelity on a `width × height` image will need, with `threads` worker
/// threads (see the module documentation for the model). Linear in the number of points and
/// contours, so it is computed in one pass before anything is allocated.
///
/// ```
/// use layertrace::{trace, work_estimate, Convention, Mask, Model};
/// let mask = Mask::from_fn(200, 200, |x, y| (x / 10 + y / 10) % 2 == 0);
/// let contours = trace(&mask, Convention::Default);
/// let e = work_estimate(&contours, Model::Conic, 200, 200, 1);
/// assert!(e.contours > 0 && e.decomposition > 0);
/// assert!(e.bytes >= e.contours + e.decomposition + e.svg_document);
/// ```
pub fn work_estimate(
    contours: &[Contour],
    model: Model,
    width: u32,
    height: u32,
    threads: usize,
) -> WorkEstimate {
    let basis = model.basis();
    let (n, pd) = (basis.dim() as u64, basis.point_dim() as u64);
    let threads = threads.max(1) as u64;
    let piece = std::mem::size_of::<Piece>() as u64 + 2 * ALLOCATION + 8 * (pd + n);
    let contour = std::mem::size_of::<Contour>() as u64 + ALLOCATION;
    let (mut points, mut count, mut longest, mut pieces) = (0u64, 0u64, 0u64, 0u64);
    for c in contours {
        let p = c.points.len() as u64;
        points += p;
        count += 1;
        longest = longest.max(p);
        pieces += p / 2 + 1;
    }
    let contours_bytes = count * contour + points * 16;
    // Per point of a piece in the recognizer: the point and its lifting (i64 and f64) in up
    // to three sets' worth (the inliers, and about one outlier per inlier and side), twice
    // for growth; the greedy's two pixel maps.
    let scratch_per_point = 2 * 3 * 8 * (pd + 2 * n) + 2 * 64;
    let decomposition = count * (24 + ALLOCATION)
        + pieces * piece
        + threads * (longest * scratch_per_point + 64 * 1024);
    let svg_document = 2 * (points * SVG_BYTES_PER_POINT + count * SVG_BYTES_PER_CONTOUR) + 4096;
    let svg_drawing = threads * longest * DRAW_BYTES_PER_POINT + 2 * 4096 * 256;
    let pixels = u64::from(width) * u64::from(height);
    let fidelity = svg_document / 2 * FIDELITY_BYTES_PER_SVG_BYTE + pixels * 4 + pixels / 4;
    WorkEstimate {
        bytes: contours_bytes + decomposition + svg_document + svg_drawing.max(fidelity),
        contours: contours_bytes,
        decomposition,
        svg_document,
        svg_drawing,
        fidelity,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bitmap::Mask;
    use crate::contour::{trace, Convention};

    fn checker(n: u32) -> Vec<Contour> {
        trace(
            &Mask::from_fn(n, n, |x, y| (x + y) % 2 == 0),
            Convention::Default,
        )
    }

    /// More contours never need less; the estimate grows linearly with the points, and a
    /// richer model or more threads never need less.
    #[test]
    fn estimate_is_monotone_and_linear() {
        let small = checker(20);
        let large = checker(40);
        let e = |c: &[Contour], m: Model, t: usize| work_estimate(c, m, 40, 40, t);
        let (a, b) = (e(&small, Model::Conic, 1), e(&large, Model::Conic, 1));
        assert!(b.bytes > a.bytes);
        // Four times the pixels, about four times the contours and points: between 3 and 5
        // times the parts that grow with them (the drawing's fixed part does not).
        let grows = |e: &WorkEstimate| e.contours + e.decomposition + e.svg_document + e.fidelity;
        assert!(
            grows(&b) > 3 * grows(&a) && grows(&b) < 5 * grows(&a),
            "{a:?} {b:?}"
        );
        assert!(e(&large, Model::Poly(6), 1).bytes > b.bytes);
        assert!(e(&large, Model::Conic, 4).bytes > b.bytes);
        assert!(e(&large, Model::Line, 1).bytes < b.bytes);
        // The parts add up.
        assert_eq!(
            b.bytes,
            b.contours + b.decomposition + b.svg_document + b.svg_drawing.max(b.fidelity)
        );
        // Doubling every contour doubles the per-contour parts.
        let twice: Vec<Contour> = large.iter().chain(&large).cloned().collect();
        let t = e(&twice, Model::Conic, 1);
        assert_eq!(t.contours, 2 * b.contours);
        assert_eq!(t.svg_document - 4096, 2 * (b.svg_document - 4096));
    }

    /// The estimate covers what a decomposition and its SVG actually hold: the pieces'
    /// memory (counted from the result) and the document's length.
    #[test]
    fn estimate_covers_the_pieces_and_the_document() {
        use crate::decompose::{decompose, OutlierRule};
        use crate::export::svg::{svg_document, SvgOptions};
        let contours = checker(30);
        let est = work_estimate(&contours, Model::Conic, 30, 30, 1);
        let d = decompose(contours, Model::Conic, OutlierRule::NotInPiece);
        let piece_bytes: usize = d
            .pieces
            .iter()
            .flatten()
            .map(|p| {
                std::mem::size_of::<Piece>()
                    + 8 * (p.certificate.origin.len() + p.certificate.coefficients.len())
            })
            .sum();
        assert!(est.decomposition as usize >= piece_bytes);
        let svg = svg_document(&d, 30, 30, &SvgOptions::default());
        assert!(est.svg_document as usize >= svg.svg.len());
    }
}
