//! The SVG and JSON of a partition (`--layout partition`): one `<path>` per colour made of
//! the shared borders, and the borders with their two regions and their pieces.
//!
//! # SVG
//! The document of [`layers_document`](super::layers::layers_document) (same header, same
//! compact path data, `fill-rule="nonzero"`), one `<path fill="#rrggbb">` per region in
//! palette order (decreasing pixel count). The paths do not overlap, so the order does not
//! change what is painted. Each region's loops wind once round its pixels (holes are loops
//! the other way round), so `nonzero` and `evenodd` paint the same.
//!
//! # JSON
//! `layertrace-colour/1` with `"layout": "partition"`: each region's colour, pixel count
//! and the contours of its own pixels with their pieces and equations (as
//! `layertrace-decomposition/2`, in image coordinates), its `"loops"` (lists of
//! `{"border": i, "reversed": bool}`), and a top-level `"borders"` list: each border's two
//! sides (`"left"`, a region index; `"right"`, a region index, `"none"` for no region or
//! `"outside"` for the image's outside), its corners from junction to junction
//! (`"corners"`, `[x, y]` crack corners, the first repeated at the end of a closed
//! border), which outline it was cut from (`"drawn"`: `left`, `right` or `cracks`) and the
//! pieces of that region's contours beside it (`"pieces"`: `[contour, piece]` indices into
//! that region's `"contours"`, whose equations they are).
//!
//! ```text
//! {"format": "layertrace-colour/1", "width": W, "height": H, "layout": "partition",
//!  "model": "conic", "cover": "greedy",
//!  "basis": [...],
//!  "regions": [
//!  {"colour": "#rrggbb", "pixels": N, "loops": [[{"border": 0, "reversed": false},...],...],
//!   "contours": [
//!   {"hole": false, "points": [[x,y], ...],
//!    "pieces": [{...},
//!     {...}]}
//!  ]}
//!  ],
//!  "borders": [
//!   {"left": 0, "right": "outside", "closed": true, "drawn": "left", "pieces": [[0,0], ...],
//!    "corners": [[x,y], ...]}
//!  ]}
//! ```
//!
//! One region per line, its contours as in the decomposition; one border per line, its
//! corners on the next.

use std::collections::HashMap;
use std::fmt::Write as _;

use super::json::{
    basis_names, contours, contours_list, top_break, ColourDoc, ContourDoc, PIECES_BREAK,
    PIECES_LIST, REGIONS_LIST,
};
use super::json_layout::{to_text, Break, Layout, List};
use super::path_text::{drop_closing_line, write_path_data, xml_escape};
use crate::contour::crack_sides;
use crate::decompose::Decomposition;
use crate::outline::{BorderSource, CommandCounts, ContourPath, Partition};
use serde::Serialize;

/// Per crack-side pixel: the `(contour, piece)` pairs of a region's decomposition there.
type PiecesAt = HashMap<(i64, i64), Vec<(usize, usize)>>;

/// The path data of closed paths on the `2^-grid` grid, and their command counts.
pub(crate) fn path_data(paths: &[ContourPath], grid: u8) -> (String, CommandCounts) {
    let mut s = String::new();
    let mut counts = CommandCounts::default();
    for p in paths {
        let mut p = p.clone();
        drop_closing_line(&mut p);
        counts += &p.counts();
        write_path_data(&p, usize::from(grid), 0.0, &mut s);
    }
    (s, counts)
}

fn header(width: u32, height: u32) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{width}\" \
         height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n"
    )
}

/// A document with one black path of data `d` (the render check's).
pub(crate) fn single_path_document(d: &(String, CommandCounts), width: u32, height: u32) -> String {
    let mut svg = header(width, height);
    if !d.0.is_empty() {
        let _ = writeln!(svg, "<path fill-rule=\"nonzero\" d=\"{}\"/>", d.0);
    }
    svg.push_str("</svg>\n");
    svg
}

/// The document of the regions `(fill, path data)` in order; empty paths are not written.
pub(crate) fn partition_document(regions: &[(String, String)], width: u32, height: u32) -> String {
    let mut svg = header(width, height);
    for (fill, d) in regions {
        if !d.is_empty() {
            let _ = writeln!(
                svg,
                "<path fill=\"{}\" fill-rule=\"nonzero\" d=\"{}\"/>",
                xml_escape(fill),
                d
            );
        }
    }
    svg.push_str("</svg>\n");
    svg
}

/// One region of [`partition_json`].
pub(crate) struct PartitionRegion<'a> {
    pub(crate) colour: &'a str,
    pub(crate) pixels: u64,
    /// Its own pixels' contours (padded by `margin`).
    pub(crate) decomposition: &'a Decomposition,
}

/// A region of the partition: its loops, then its contours.
#[derive(Serialize)]
struct RegionDoc<'a> {
    colour: &'a str,
    pixels: u64,
    loops: Vec<Vec<LoopStep>>,
    contours: Vec<ContourDoc>,
}

/// One border of a loop.
#[derive(Serialize)]
struct LoopStep {
    border: usize,
    reversed: bool,
}

/// A border: its two sides, how it was drawn, the pieces beside it and its corners.
#[derive(Serialize)]
struct BorderDoc {
    left: Side,
    right: Side,
    closed: bool,
    drawn: &'static str,
    /// `[contour, piece]`.
    pieces: Vec<[usize; 2]>,
    corners: Vec<[i64; 2]>,
}

/// A border's side: a region index, or `"none"` or `"outside"`.
#[derive(Serialize)]
#[serde(untagged)]
enum Side {
    Region(usize),
    Other(&'static str),
}

const PARTITION: Layout = Layout {
    breaks: &[
        top_break("model"),
        top_break("basis"),
        top_break("regions"),
        top_break("borders"),
        Break {
            parent: "regions",
            key: "contours",
            line: "\n  ",
        },
        PIECES_BREAK,
        Break {
            parent: "borders",
            key: "corners",
            line: "\n   ",
        },
    ],
    lists: &[
        REGIONS_LIST,
        contours_list("regions"),
        PIECES_LIST,
        List {
            parent: "",
            key: "borders",
            line: "\n  ",
            first: true,
            close: "\n ",
        },
    ],
};

/// The JSON text of a partition (see the module documentation).
pub(crate) fn partition_json(
    regions: &[PartitionRegion<'_>],
    partition: &Partition,
    margin: i64,
    (model, cover): (crate::model::Model, crate::decompose::Cover),
    width: u32,
    height: u32,
) -> String {
    let region_docs = regions
        .iter()
        .zip(&partition.loops)
        .map(|(r, loops)| RegionDoc {
            colour: r.colour,
            pixels: r.pixels,
            loops: loops
                .iter()
                .map(|l| {
                    l.iter()
                        .map(|&(border, reversed)| LoopStep { border, reversed })
                        .collect()
                })
                .collect(),
            contours: contours(r.decomposition, margin),
        })
        .collect();
    // Per region: the pieces beside each of its contour pixels (image coordinates).
    let mut beside: Vec<PiecesAt> = Vec::new();
    for r in regions {
        let mut m = PiecesAt::new();
        for (ci, (c, pieces)) in r
            .decomposition
            .contours
            .iter()
            .zip(&r.decomposition.pieces)
            .enumerate()
        {
            for (pi, p) in pieces.iter().enumerate() {
                for q in &c.points[p.first..=p.last] {
                    let key = (i64::from(q.x) - margin, i64::from(q.y) - margin);
                    let v = m.entry(key).or_default();
                    if v.last() != Some(&(ci, pi)) {
                        v.push((ci, pi));
                    }
                }
            }
        }
        beside.push(m);
    }
    let side = |l: usize| {
        if l < partition.none {
            Side::Region(l)
        } else if l == partition.none {
            Side::Other("none")
        } else {
            Side::Other("outside")
        }
    };
    let border_docs = partition
        .borders
        .iter()
        .map(|pb| {
            let b = &pb.border;
            let owner = match pb.source {
                BorderSource::Left => Some((b.left, 0)),
                BorderSource::Right => Some((b.right, 1)),
                BorderSource::Cracks => None,
            };
            let mut pieces: Vec<(usize, usize)> = Vec::new();
            if let Some((region, which)) = owner {
                for c in b.corners.windows(2) {
                    let px = crack_sides(c[0], c[1])[which];
                    if let Some(v) = beside[region].get(&px) {
                        pieces.extend(v.iter().copied());
                    }
                }
            }
            pieces.sort_unstable();
            pieces.dedup();
            BorderDoc {
                left: side(b.left),
                right: side(b.right),
                closed: b.closed,
                drawn: pb.source.name(),
                pieces: pieces.iter().map(|&(c, p)| [c, p]).collect(),
                corners: b.corners.iter().map(|&(x, y)| [x, y]).collect(),
            }
        })
        .collect();
    let doc = ColourDoc {
        format: "layertrace-colour/1",
        width,
        height,
        layout: "partition",
        model: model.name(),
        cover: cover.name(),
        basis: basis_names(model),
        regions: region_docs,
        borders: Some(border_docs),
    };
    to_text(&doc, &PARTITION)
}
