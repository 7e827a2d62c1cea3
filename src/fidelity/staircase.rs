//! Pixel staircases in SVG path data: what a viewer sees as jaggies when zooming in.
//!
//! A *staircase* is a maximal run of at least 4 consecutive straight segments, each
//! axis-aligned and at most 2 pixels long, alternating horizontal and vertical (the counter
//! is [`crate::outline::staircase`]'s, shared with the outline).
//! The definition is the one of the project's shared tool `tools/staircase.py`, which this
//! module reproduces exactly (its counts are the reference):
//! * segments are read from the raw path data of every `d` attribute of the document (user
//!   units, no transform applied), one path after the other;
//! * `L`, `H`, `V` (absolute or relative, and the implicit line-tos after `M`) are straight
//!   segments, and so is the closing segment of `Z` when the current point is not already
//!   the subpath's start (compared exactly);
//! * a segment is horizontal when its vertical extent is below `1e-9` and its horizontal
//!   one in `(0, MAX_STEP]`, vertical the other way round; any other straight segment
//!   (longer, slanted or of length 0) ends a run;
//! * a curve (`C`, `S`, `Q`, `T`, `A`), a move-to and the end of a subpath (`Z`) end a run:
//!   runs are not joined across the start of a closed subpath, so a staircase that crosses
//!   the start point counts as the two pieces on either side of it.

use crate::error::Error;
use crate::outline::staircase::Counter;
pub use crate::outline::staircase::StaircaseCount;
use svgtypes::{PathParser, PathSegment};

/// Staircases in one path's data (`d` attribute). Parsing stops at the first error, as
/// SVG renderers do.
pub(crate) fn path_staircases(d: &str) -> StaircaseCount {
    let mut c = Counter::default();
    let (mut cur, mut start) = ((0.0, 0.0), (0.0, 0.0));
    for seg in PathParser::from(d) {
        let Ok(seg) = seg else { break };
        let base = |abs: bool| if abs { (0.0, 0.0) } else { cur };
        match seg {
            PathSegment::MoveTo { abs, x, y } => {
                let b = base(abs);
                cur = (b.0 + x, b.1 + y);
                start = cur;
                c.other();
            }
            PathSegment::LineTo { abs, x, y } => {
                let b = base(abs);
                let next = (b.0 + x, b.1 + y);
                c.line(cur, next);
                cur = next;
            }
            PathSegment::HorizontalLineTo { abs, x } => {
                let next = (base(abs).0 + x, cur.1);
                c.line(cur, next);
                cur = next;
            }
            PathSegment::VerticalLineTo { abs, y } => {
                let next = (cur.0, base(abs).1 + y);
                c.line(cur, next);
                cur = next;
            }
            PathSegment::ClosePath { .. } => {
                if cur != start {
                    c.line(cur, start);
                }
                cur = start;
                c.other();
            }
            PathSegment::CurveTo { abs, x, y, .. }
            | PathSegment::SmoothCurveTo { abs, x, y, .. }
            | PathSegment::Quadratic { abs, x, y, .. }
            | PathSegment::SmoothQuadratic { abs, x, y }
            | PathSegment::EllipticalArc { abs, x, y, .. } => {
                let b = base(abs);
                cur = (b.0 + x, b.1 + y);
                c.other();
            }
        }
    }
    c.finish()
}

/// Staircases in every `d` attribute of an SVG document, summed.
///
/// Fails with [`Error::SvgParse`] when the document is not well-formed XML.
///
/// ```
/// use layertrace::staircases;
/// // Four unit steps alternating right and down: one run of 4 staircase segments.
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0h1v1h1v1h1v1L0 3Z"/></svg>"#;
/// let s = staircases(svg)?;
/// assert_eq!(s.runs, 1);
/// assert!(s.segments >= 4);
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn staircases(svg: &str) -> Result<StaircaseCount, Error> {
    let doc = roxmltree::Document::parse(svg).map_err(|e| Error::SvgParse {
        source: usvg::Error::ParsingFailed(e),
    })?;
    let mut total = StaircaseCount::default();
    for d in doc.descendants().filter_map(|n| n.attribute("d")) {
        total += path_staircases(d);
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runs(d: &str) -> (u64, u64) {
        let c = path_staircases(d);
        (c.runs, c.segments)
    }

    #[test]
    fn four_steps_count_three_do_not() {
        assert_eq!(runs("M0 0H1V1H2V2"), (1, 4));
        assert_eq!(runs("M0 0H1V1H2"), (0, 0));
        // Relative commands and implicit line-tos after `m`.
        assert_eq!(runs("m0 0 1 0 0 1 1 0 0 1 1 0"), (1, 5));
        assert_eq!(runs("M0 0l2 0v-2h-2"), (0, 0));
        assert_eq!(runs("M0 0l2 0v-2h-2v1.5"), (1, 4));
    }

    #[test]
    fn long_slanted_or_repeated_segments_break_a_run() {
        // A 3 px step cuts 7 steps into 3 + 3.
        assert_eq!(runs("M0 0H1V1H2V4H3V5H4"), (0, 0));
        // ... and 4 + 3 px + 4 steps into two staircases.
        assert_eq!(runs("M0 0H1V1H2V2V5H3V6H4V7"), (2, 8));
        // A slanted segment, two horizontal steps in a row, a zero-length segment.
        assert_eq!(runs("M0 0H1V1H2L3 2V3H4V4H5"), (1, 4));
        assert_eq!(runs("M0 0H1V1H2H3V2H4V3"), (1, 4));
        assert_eq!(runs("M0 0H1V1H2V2L2 2H3V3H4V4"), (2, 8));
        // A curve or an arc in between.
        assert_eq!(runs("M0 0H1V1Q2 1 2 2H3V3H4"), (0, 0));
        assert_eq!(runs("M0 0H1V1H2V2A1 1 0 0 1 3 3H4V4H5V5"), (2, 8));
    }

    #[test]
    fn closing_segment_counts_but_runs_do_not_wrap() {
        // A 1×1 square: H, V, H and the closing V.
        let c = path_staircases("M0 0H1V1H0Z");
        assert_eq!((c.runs, c.segments, c.lines), (1, 4, 4));
        // Explicitly closed: the closing segment has length 0 and is not drawn.
        assert_eq!(path_staircases("M0 0H1V1H0V0Z").lines, 4);
        // Three steps before and two after the start point of a closed subpath: the run is
        // cut at the start (as in tools/staircase.py), so no staircase.
        let wrap = "M0 0H1V1H10V-1H-1V-2H0Z";
        assert_eq!(runs(wrap), (0, 0));
        // Rotated so that the start is elsewhere, the same outline has one.
        assert_eq!(runs("M10 1V-1H-1V-2H0V0H1V1Z"), (1, 5));
        // `M` and `Z` end runs; a new subpath starts afresh.
        assert_eq!(runs("M0 0H1V1M5 5H6V6H7V7"), (1, 4));
    }

    #[test]
    fn documents_sum_their_paths() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="9" height="9">
            <path d="M0 0H1V1H2V2"/><g><path d='M0 0H1V1H2V2H3'/></g></svg>"#;
        let c = staircases(svg).unwrap();
        assert_eq!((c.runs, c.segments, c.lines), (2, 9, 9));
        assert!(matches!(staircases("<svg"), Err(Error::SvgParse { .. })));
        // Parsing stops at an error.
        assert_eq!(runs("M0 0H1V1H2V2X H3"), (1, 4));
    }
}
