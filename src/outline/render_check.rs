//! What tiny-skia draws of one contour's path, and the contour points it gets wrong.
//!
//! The path is filled with tiny-skia itself, without anti-aliasing (what resvg does under
//! `shape-rendering="crispEdges"`), into a mask covering the path's bounding box. tiny-skia
//! cuts quadratics and cubics into `2^k` chords by forward differencing in fixed point and
//! rounds vertices to 1/64 px (see [`crate::fidelity`]); its results do not change under a
//! translation by whole pixels (all of its arithmetic is on differences and on 26.6 fixed
//! point), and the mask is large enough that no edge is clipped. In the document the whole
//! `<path>` may poke out of the pixmap, and then tiny-skia clips every edge, which cuts
//! curves at their extrema first: curved paths are filled both ways here (see [`Rendered`]),
//! so the pixels they paint are those resvg paints for this contour in the whole document
//! either way. Points are on the 1/64 grid ([`super::builder`]), exact in `f32`.

use crate::curve::PathCommand;
use crate::pixel::Pixel;
use kurbo::Point;

/// The pixels tiny-skia paints for one closed path (nonzero rule), within a window, *with
/// their winding*: whether the path winds 0 round each pixel centre, exactly its own
/// orientation `s` (±1: +1 for a counter-clockwise path on screen, as outer borders are
/// drawn), or anything else.
///
/// A path can paint the right pixels alone and still be wrong in the document: a twisted
/// lobe (a self-crossing) winds `−s` round the pixels it covers, a curl `2s`; a lone
/// nonzero fill paints them like the rest, but in the document they add to the windings of
/// the other contours instead of cancelling them (a hole's path meeting its outer border's).
/// So the path is filled twice: alone (painted iff the winding is not 0), and with a
/// rectangle round the whole window wound `−s` (painted iff the winding is not `s`). A
/// pixel is then [`OUTSIDE`], [`INSIDE`] or [`WRONG`], and comparing two paths compares
/// these classes pixel by pixel, which is what the sum of all contours needs.
pub(crate) struct Rendered {
    x0: i64,
    y0: i64,
    width: i64,
    height: i64,
    /// The orientation `s` (+1 or −1) the winding is compared with.
    orientation: i8,
    /// The class of every pixel of the window, row by row.
    class: Option<Vec<u8>>,
}

/// The path winds 0 round the pixel centre.
const OUTSIDE: u8 = 0;
/// The path winds exactly its orientation round the pixel centre.
const INSIDE: u8 = 1;
/// Any other winding: wrong wherever the pixel is.
const WRONG: u8 = 2;

impl Rendered {
    /// Fills the closed path `M start commands Z`.
    #[cfg(test)]
    pub(crate) fn new(start: Point, commands: &[PathCommand]) -> Rendered {
        Rendered::within_margin(start, commands, None, 0, false)
    }

    /// [`Rendered::new`] on a window covering `like`'s too (then rows of the two line up,
    /// and [`misplaced_pixels`] compares them as byte slices).
    pub(crate) fn like(start: Point, commands: &[PathCommand], like: &Rendered) -> Rendered {
        Rendered::within_margin(start, commands, Some(like), 0, false)
    }

    /// [`Rendered::new`] with `margin` more pixels round the window (a reference that
    /// paths drawn [`Rendered::like`] it fit in, so that their rows line up).
    ///
    /// For a reference that never crosses itself (a contour's crack polygon: pixel edges,
    /// each once, meeting only at corners), whose winding is 0 or its orientation: filled
    /// once.
    pub(crate) fn with_margin(start: Point, commands: &[PathCommand], margin: i64) -> Rendered {
        Rendered::within_margin(start, commands, None, margin, true)
    }

    fn within_margin(
        start: Point,
        commands: &[PathCommand],
        like: Option<&Rendered>,
        margin: i64,
        simple: bool,
    ) -> Rendered {
        let (mut lo, mut hi) = (start, start);
        let mut grow = |p: Point| {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        };
        for c in commands {
            match *c {
                PathCommand::Line(p) => grow(p),
                PathCommand::Quad(a, p) => {
                    grow(a);
                    grow(p);
                }
                PathCommand::Cubic(a, b, p) => {
                    grow(a);
                    grow(b);
                    grow(p);
                }
                PathCommand::Arc(a) => {
                    // Not produced by the builder; bound the whole ellipse.
                    let r = a.radii.x.abs().max(a.radii.y.abs());
                    grow(a.to - kurbo::Vec2::new(r, r) * 2.0);
                    grow(a.to + kurbo::Vec2::new(r, r) * 2.0);
                }
            }
        }
        // Two pixels of margin: the scan converter keeps clipping off only when the
        // conservatively rounded bounds are inside the mask.
        let mut x0 = lo.x.floor() as i64 - 2 - margin;
        let mut y0 = lo.y.floor() as i64 - 2 - margin;
        let mut x1 = hi.x.ceil() as i64 + 2 + margin;
        let mut y1 = hi.y.ceil() as i64 + 2 + margin;
        if let Some(r) = like {
            x0 = x0.min(r.x0);
            y0 = y0.min(r.y0);
            x1 = x1.max(r.x0 + r.width);
            y1 = y1.max(r.y0 + r.height);
        }
        let (width, height) = (x1 - x0, y1 - y0);
        let orientation = match like {
            Some(r) => r.orientation,
            None => orientation(start, commands),
        };
        let mut out = Rendered {
            x0,
            y0,
            width,
            height,
            orientation,
            class: None,
        };
        let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
            return out;
        };
        let fill = |frame: Option<(f32, f32, i8)>, clipped: bool| {
            let path = tiny_path(start, commands, x0 as f64, y0 as f64, frame, clipped)?;
            let mut mask = tiny_skia::Mask::new(w, h)?;
            mask.fill_path(
                &path,
                tiny_skia::FillRule::Winding,
                false,
                tiny_skia::Transform::identity(),
            );
            Some(mask)
        };
        if simple {
            out.class = fill(None, false).map(|alone| {
                alone
                    .data()
                    .iter()
                    .map(|&a| if a != 0 { INSIDE } else { OUTSIDE })
                    .collect()
            });
            return out;
        }
        let frame = Some((width as f32, height as f32, orientation));
        let classes = |clipped: bool| -> Option<Vec<u8>> {
            let (alone, framed) = (fill(None, clipped)?, fill(frame, clipped)?);
            Some(
                alone
                    .data()
                    .iter()
                    .zip(framed.data())
                    .map(|(&a, &f)| match (a != 0, f != 0) {
                        (false, _) => OUTSIDE,
                        (true, false) => INSIDE,
                        (true, true) => WRONG,
                    })
                    .collect(),
            )
        };
        let Some(mut class) = classes(false) else {
            return out;
        };
        // tiny-skia (as Skia) draws curves differently when the whole path — in the
        // document: every contour, one `<path>` — pokes out of the pixmap: its edge clipper
        // then cuts every cubic at its x and y extrema and quadratics at theirs before
        // subdividing, which moves the chords. Whether the document will is not known while
        // one contour is drawn, so a path with curves must be right both ways. Lines are
        // cut only where they cross the clip, outside this window.
        if commands.iter().any(|c| !matches!(c, PathCommand::Line(_))) {
            let Some(clipped) = classes(true) else {
                return out;
            };
            for (c, k) in class.iter_mut().zip(clipped) {
                if *c != k {
                    *c = WRONG;
                }
            }
        }
        out.class = Some(class);
        out
    }

    /// The class of the pixel: [`OUTSIDE`] out of the window, [`WRONG`] everywhere when
    /// the path could not be filled.
    fn class(&self, x: i64, y: i64) -> u8 {
        let (x, y) = (x - self.x0, y - self.y0);
        if x < 0 || y < 0 || x >= self.width || y >= self.height {
            return OUTSIDE;
        }
        match &self.class {
            Some(c) => c[(y * self.width + x) as usize],
            None => WRONG,
        }
    }

    /// True when the path winds exactly its orientation round the pixel's centre.
    #[cfg(test)]
    pub(crate) fn painted(&self, p: Pixel) -> bool {
        self.class(p.x.into(), p.y.into()) == INSIDE
    }
}

/// The sign of the area the path's vertices and control points enclose (shoelace): +1 for
/// counter-clockwise on screen (y down), as outer borders are drawn; −1 otherwise.
fn orientation(start: Point, commands: &[PathCommand]) -> i8 {
    let mut area = 0.0;
    let mut pen = start;
    let mut edge = |p: Point| {
        area += pen.x * p.y - p.x * pen.y;
        pen = p;
    };
    for c in commands {
        match *c {
            PathCommand::Line(p) | PathCommand::Arc(kurbo::SvgArc { to: p, .. }) => edge(p),
            PathCommand::Quad(a, p) => {
                edge(a);
                edge(p);
            }
            PathCommand::Cubic(a, b, p) => {
                edge(a);
                edge(b);
                edge(p);
            }
        }
    }
    edge(start);
    // Screen coordinates: counter-clockwise as seen has a negative shoelace sum.
    if area <= 0.0 {
        1
    } else {
        -1
    }
}

/// The path translated by `(−dx, −dy)` (whole pixels: exact for grid points) as tiny-skia's,
/// with the rectangle `(0, 0)–(w, h)` wound against `orientation` (see [`Rendered`]).
fn tiny_path(
    start: Point,
    commands: &[PathCommand],
    dx: f64,
    dy: f64,
    frame: Option<(f32, f32, i8)>,
    clipped: bool,
) -> Option<tiny_skia::Path> {
    let f = |p: Point| ((p.x - dx) as f32, (p.y - dy) as f32);
    let mut pb = tiny_skia::PathBuilder::with_capacity(commands.len() + 2, commands.len() * 3 + 1);
    let (x, y) = f(start);
    pb.move_to(x, y);
    let mut pen = start;
    for c in commands {
        match *c {
            PathCommand::Line(p) => {
                let (x, y) = f(p);
                pb.line_to(x, y);
            }
            PathCommand::Quad(a, p) => {
                let ((ax, ay), (x, y)) = (f(a), f(p));
                pb.quad_to(ax, ay, x, y);
            }
            PathCommand::Cubic(a, b, p) => {
                let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(p));
                pb.cubic_to(ax, ay, bx, by, x, y);
            }
            PathCommand::Arc(_) => {
                for el in c.to_path_els(pen) {
                    match el {
                        kurbo::PathEl::CurveTo(a, b, p) => {
                            let ((ax, ay), (bx, by), (x, y)) = (f(a), f(b), f(p));
                            pb.cubic_to(ax, ay, bx, by, x, y);
                        }
                        kurbo::PathEl::LineTo(p) => {
                            let (x, y) = f(p);
                            pb.line_to(x, y);
                        }
                        _ => {}
                    }
                }
            }
        }
        pen = c.end();
    }
    pb.close();
    if clipped {
        // A flat sliver just outside the window: paints nothing, but the path's bounds no
        // longer fit the mask, so tiny-skia runs its edge clipper on every edge.
        pb.move_to(-1.0, -1.0);
        pb.line_to(-0.5, -1.0);
        pb.close();
    }
    let Some((w, h, orientation)) = frame else {
        return pb.finish();
    };
    // Counter-clockwise on screen is (0,0) → (0,h) → (w,h) → (w,0).
    pb.move_to(0.0, 0.0);
    if orientation > 0 {
        pb.line_to(w, 0.0);
        pb.line_to(w, h);
        pb.line_to(0.0, h);
    } else {
        pb.line_to(0.0, h);
        pb.line_to(w, h);
        pb.line_to(w, 0.0);
    }
    pb.close();
    pb.finish()
}

/// Largest distance (pixels) of the polyline [`finely_flattened`] draws to the true curves.
pub const FINE_FLATTENING: f64 = 0.01;

/// The path with its curves flattened within [`FINE_FLATTENING`]: what a renderer more
/// precise than tiny-skia draws. A path both this and tiny-skia's chords draw exactly is
/// drawn exactly by renderers in between (Skia's versions in browsers subdivide curves a
/// little differently), not only by tiny-skia. `None` when the path has no curve.
pub(crate) fn finely_flattened(start: Point, commands: &[PathCommand]) -> Option<Vec<PathCommand>> {
    if commands.iter().all(|c| matches!(c, PathCommand::Line(_))) {
        return None;
    }
    let mut out = Vec::with_capacity(commands.len() * 4);
    let mut path = kurbo::BezPath::new();
    path.move_to(start);
    let mut pen = start;
    for c in commands {
        for el in c.to_path_els(pen) {
            path.push(el);
        }
        pen = c.end();
    }
    kurbo::flatten(path, FINE_FLATTENING, |el| {
        if let kurbo::PathEl::LineTo(p) = el {
            out.push(PathCommand::Line(p));
        }
    });
    Some(out)
}

/// The pixels that `path` and `reference` class differently (winding 0, exactly the
/// orientation, or wrong: see [`Rendered`]), row by row (rows that agree are compared as
/// byte slices).
pub(crate) fn misplaced_pixels(reference: &Rendered, path: &Rendered) -> Vec<Pixel> {
    let x0 = reference.x0.min(path.x0);
    let y0 = reference.y0.min(path.y0);
    let x1 = (reference.x0 + reference.width).max(path.x0 + path.width);
    let y1 = (reference.y0 + reference.height).max(path.y0 + path.height);
    fn row(r: &Rendered, y: i64) -> (i64, &[u8]) {
        match &r.class {
            Some(c) if y >= r.y0 && y < r.y0 + r.height => {
                let w = r.width as usize;
                let start = (y - r.y0) as usize * w;
                (r.x0, &c[start..start + w])
            }
            _ => (r.x0, &[]),
        }
    }
    let mut bad = Vec::new();
    for y in y0..y1 {
        let (ra, a) = row(reference, y);
        let (rb, b) = row(path, y);
        if ra == rb && a == b && !a.is_empty() {
            continue;
        }
        for x in x0..x1 {
            if reference.class(x, y) != path.class(x, y) {
                if let (Ok(px), Ok(py)) = (i32::try_from(x), i32::try_from(y)) {
                    bad.push(Pixel::new(px, py));
                }
            }
        }
    }
    bad
}

/// Indices of the contour points nearest to each of `pixels` (each index once, ascending).
/// With the contour's crack polygon as the reference of [`misplaced_pixels`] — exactly the
/// pixels the contour encloses — a path that differs nowhere paints exactly those, so the
/// nonzero sum of all contours' paths is the image: this catches a curve cutting a pixel
/// of a neighbouring contour too, not only the contour's own pixels and the background
/// beside them.
pub(crate) fn nearest_points(points: &[Pixel], pixels: &[Pixel]) -> Vec<usize> {
    let mut out: Vec<usize> = pixels
        .iter()
        .filter_map(|q| {
            points
                .iter()
                .enumerate()
                .min_by_key(|(_, p)| {
                    let (dx, dy) = (i64::from(p.x - q.x), i64::from(p.y - q.y));
                    dx * dx + dy * dy
                })
                .map(|(i, _)| i)
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Indices of the contour points within `radius` (in x and in y) of any of `pixels`.
pub(crate) fn points_near(points: &[Pixel], pixels: &[Pixel], radius: i32) -> Vec<usize> {
    (0..points.len())
        .filter(|&i| {
            let p = points[i];
            pixels
                .iter()
                .any(|q| (p.x - q.x).abs() <= radius && (p.y - q.y).abs() <= radius)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// Pixel centres strictly inside a polygon are painted, those outside are not (no centre
    /// on an edge here).
    #[test]
    fn polygon_paints_the_centres_inside() {
        let start = p(0.0, 0.0);
        let cmds = [
            PathCommand::Line(p(0.0, 5.0)),
            PathCommand::Line(p(7.25, 5.0)),
            PathCommand::Line(p(3.0, 0.0)),
        ];
        let r = Rendered::new(start, &cmds);
        for y in -3..9 {
            for x in -3..12 {
                let c = p(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let inside = c.y > 0.0 && c.y < 5.0 && c.x > 0.0 && {
                    // Right edge from (3, 0) to (7.25, 5).
                    let t = c.y / 5.0;
                    c.x < 3.0 + 4.25 * t
                };
                assert_eq!(r.painted(Pixel { x, y }), inside, "({x}, {y})");
            }
        }
    }

    /// A far-off translation does not change what is painted relative to the path.
    #[test]
    fn translation_invariant() {
        let cmds = |d: f64| {
            vec![
                PathCommand::Cubic(p(d + 3.0, d + 9.0), p(d + 9.0, d + 11.0), p(d + 12.0, d)),
                PathCommand::Line(p(d + 5.0, d - 1.5)),
            ]
        };
        let a = Rendered::new(p(0.0, 0.0), &cmds(0.0));
        let b = Rendered::new(p(4000.0, 4000.0), &cmds(4000.0));
        let mut painted = 0;
        for y in -3..15 {
            for x in -3..15 {
                let q = Pixel { x, y };
                let q2 = Pixel {
                    x: x + 4000,
                    y: y + 4000,
                };
                assert_eq!(a.painted(q), b.painted(q2), "({x}, {y})");
                painted += usize::from(a.painted(q));
            }
        }
        assert!(painted > 30, "{painted}");
    }
}
