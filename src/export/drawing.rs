//! The filled paths of an SVG document, read for the PDF and EPS writers: page size, fill
//! colour and rule, and path segments with the y axis flipped (PDF and PostScript put the
//! origin at the bottom left), one pixel = one point.
//!
//! # What is read
//! The documents [`svg_document`](crate::svg_document) writes: a root `<svg>` with `width`
//! and `height` (plain numbers or `px`), optionally `version` and a `viewBox` equal to
//! `0 0 width height`, holding `<path>` elements with `d`, `fill` (a colour or `none`;
//! default black) and `fill-rule` (`nonzero`, the default, or `evenodd`). Anything else —
//! other elements, groups, transforms, strokes, styles, other units — is refused with a
//! one-line reason rather than drawn differently.
//!
//! # Exactness
//! Numbers are parsed into `f64` by svgtypes (`f64::from_str`, correctly rounded), so every
//! multiple of `2^-grid` the SVG holds is that number exactly; flipping (`height - y`) keeps
//! it exact, and [`DECIMALS`] decimals write every multiple of 1/64 (the finest grid)
//! exactly. A quadratic Bézier `Q c p` after point `a` becomes the cubic with control points
//! `a + 2/3 (c - a)` and `p + 2/3 (c - p)` — the same curve; those thirds are the only
//! rounded numbers (to `10^-DECIMALS`). usvg is not used here: its paths hold `f32`.

use super::path_text::number;
use std::fmt::Write as _;

/// Decimals written for coordinates: every multiple of 1/64 (the finest grid of
/// [`SvgOptions::grid`](crate::SvgOptions::grid)) needs at most 6.
pub(crate) const DECIMALS: usize = 6;

/// The SVG namespace, the only one whose elements are read.
const SVG_NS: &str = "http://www.w3.org/2000/svg";

/// A page: its size in points and its filled paths, in document order.
#[derive(Debug)]
pub(crate) struct Page<'a> {
    /// Width in points (the SVG's width in pixels).
    pub width: f64,
    /// Height in points.
    pub height: f64,
    /// The paths, painted in this order.
    pub fills: Vec<Fill<'a>>,
}

/// One filled `<path>`.
#[derive(Debug)]
pub(crate) struct Fill<'a> {
    /// The fill colour (alpha included; a `none` fill is not listed at all).
    pub colour: svgtypes::Color,
    /// `fill-rule="evenodd"` (else nonzero).
    pub even_odd: bool,
    /// The path data as written in the SVG.
    data: &'a str,
}

/// The names of the path operators of the output language.
pub(crate) struct Operators {
    /// Starts a subpath at `x y`.
    pub move_to: &'static str,
    /// A straight segment to `x y`.
    pub line_to: &'static str,
    /// A cubic Bézier `x1 y1 x2 y2 x y`.
    pub curve_to: &'static str,
    /// Closes the subpath.
    pub close: &'static str,
}

impl<'a> Page<'a> {
    /// Bytes of path data of all fills (to size the output).
    pub(crate) fn data_len(&self) -> usize {
        self.fills.iter().map(|f| f.data.len()).sum()
    }

    /// Reads the page of a parsed SVG document (see the module documentation for what is
    /// accepted); the error is a one-line reason.
    pub(crate) fn read<'input>(doc: &'a roxmltree::Document<'input>) -> Result<Page<'a>, String> {
        let root = doc.root_element();
        if !is_svg(root, "svg") {
            return Err(format!(
                "the root element <{}> is not an <svg> of the SVG namespace",
                root.tag_name().name()
            ));
        }
        let mut size = [None, None];
        let mut view_box = None;
        for a in root.attributes() {
            match (a.namespace(), a.name()) {
                (None, "width") => size[0] = Some(length("width", a.value())?),
                (None, "height") => size[1] = Some(length("height", a.value())?),
                (None, "viewBox") => view_box = Some(a.value()),
                (None, "version") => {}
                _ => return Err(unsupported("svg", a.name())),
            }
        }
        let [Some(width), Some(height)] = size else {
            return Err("the <svg> element needs both width and height".into());
        };
        if let Some(v) = view_box {
            let ok = v
                .parse::<svgtypes::ViewBox>()
                .is_ok_and(|b| b.x == 0.0 && b.y == 0.0 && b.w == width && b.h == height);
            if !ok {
                return Err(format!(
                    "viewBox '{v}' is not '0 0 width height' (no scaling is supported)"
                ));
            }
        }
        let mut fills = Vec::new();
        for node in root.children() {
            if node.is_text() && node.text().is_some_and(|t| !t.trim().is_empty()) {
                return Err("the <svg> element holds text".into());
            }
            if !node.is_element() {
                continue; // whitespace, comments, processing instructions
            }
            if !is_svg(node, "path") {
                return Err(format!(
                    "element <{}> is not supported (only <path>)",
                    node.tag_name().name()
                ));
            }
            if let Some(fill) = Fill::read(node)? {
                fills.push(fill);
            }
        }
        Ok(Page {
            width,
            height,
            fills,
        })
    }
}

impl<'a> Fill<'a> {
    /// Reads a `<path>`: `None` for a path that paints nothing (`fill="none"`, no data).
    fn read<'input>(node: roxmltree::Node<'a, 'input>) -> Result<Option<Fill<'a>>, String> {
        let mut fill = Fill {
            colour: svgtypes::Color::black(),
            even_odd: false,
            data: "",
        };
        for a in node.attributes() {
            match (a.namespace(), a.name(), a.value()) {
                (None, "d", d) => fill.data = d,
                (None, "fill", v) => match svgtypes::Paint::from_str(v) {
                    Ok(svgtypes::Paint::None) => return Ok(None),
                    Ok(svgtypes::Paint::Color(c)) => fill.colour = c,
                    _ => return Err(format!("fill '{v}' is not supported (a colour or none)")),
                },
                (None, "fill-rule", "nonzero") => fill.even_odd = false,
                (None, "fill-rule", "evenodd") => fill.even_odd = true,
                (None, "fill-rule", v) => return Err(format!("fill-rule '{v}' is not valid")),
                _ => return Err(unsupported("path", a.name())),
            }
        }
        Ok((!fill.data.trim().is_empty()).then_some(fill))
    }

    /// Appends the path, one segment per line (`x y m`, `x1 y1 x2 y2 x y c`, …, named by
    /// `ops`), with `y` flipped to `height - y`; quadratics become the same cubics. Fails
    /// on malformed path data (the error is svgtypes' reason).
    pub(crate) fn write_path(
        &self,
        height: f64,
        ops: &Operators,
        s: &mut String,
    ) -> Result<(), String> {
        let point = |x: f64, y: f64, s: &mut String| {
            number(x, DECIMALS, s);
            s.push(' ');
            number(height - y, DECIMALS, s);
        };
        // The current point and the start of the subpath, in SVG coordinates.
        let (mut current, mut start) = ((0.0, 0.0), (0.0, 0.0));
        for segment in svgtypes::SimplifyingPathParser::from(self.data) {
            use svgtypes::SimplePathSegment as S;
            match segment.map_err(|e| format!("path data: {e}"))? {
                S::MoveTo { x, y } => {
                    point(x, y, s);
                    let _ = writeln!(s, " {}", ops.move_to);
                    (current, start) = ((x, y), (x, y));
                }
                S::LineTo { x, y } => {
                    point(x, y, s);
                    let _ = writeln!(s, " {}", ops.line_to);
                    current = (x, y);
                }
                S::Quadratic { x1, y1, x, y } => {
                    let (ax, ay) = current;
                    let c1 = (ax + 2.0 / 3.0 * (x1 - ax), ay + 2.0 / 3.0 * (y1 - ay));
                    let c2 = (x + 2.0 / 3.0 * (x1 - x), y + 2.0 / 3.0 * (y1 - y));
                    cubic(c1, c2, (x, y), &point, ops, s);
                    current = (x, y);
                }
                S::CurveTo {
                    x1,
                    y1,
                    x2,
                    y2,
                    x,
                    y,
                } => {
                    cubic((x1, y1), (x2, y2), (x, y), &point, ops, s);
                    current = (x, y);
                }
                S::ClosePath => {
                    s.push_str(ops.close);
                    s.push('\n');
                    current = start;
                }
            }
        }
        Ok(())
    }
}

/// Appends `x1 y1 x2 y2 x y c`.
fn cubic(
    c1: (f64, f64),
    c2: (f64, f64),
    p: (f64, f64),
    point: &impl Fn(f64, f64, &mut String),
    ops: &Operators,
    s: &mut String,
) {
    point(c1.0, c1.1, s);
    s.push(' ');
    point(c2.0, c2.1, s);
    s.push(' ');
    point(p.0, p.1, s);
    let _ = writeln!(s, " {}", ops.curve_to);
}

/// The element is `name` in the SVG namespace.
fn is_svg(node: roxmltree::Node, name: &str) -> bool {
    node.tag_name().name() == name && node.tag_name().namespace() == Some(SVG_NS)
}

fn unsupported(element: &str, attribute: &str) -> String {
    format!("attribute '{attribute}' of <{element}> is not supported")
}

/// A positive width or height in user units (no unit or `px`).
fn length(name: &str, v: &str) -> Result<f64, String> {
    match v.parse::<svgtypes::Length>() {
        Ok(l)
            if matches!(
                l.unit,
                svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px
            ) && l.number.is_finite()
                && l.number > 0.0 =>
        {
            Ok(l.number)
        }
        _ => Err(format!("{name} '{v}' is not a positive number of pixels")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OPS: Operators = Operators {
        move_to: "m",
        line_to: "l",
        curve_to: "c",
        close: "h",
    };

    /// The paths of `svg` as written, or the error.
    fn paths(svg: &str) -> Result<(f64, f64, Vec<String>), String> {
        let doc = roxmltree::Document::parse(svg).map_err(|e| e.to_string())?;
        let page = Page::read(&doc)?;
        let mut out = Vec::new();
        for f in &page.fills {
            let mut s = format!(
                "{} {} {} {} {}\n",
                f.colour.red, f.colour.green, f.colour.blue, f.colour.alpha, f.even_odd
            );
            f.write_path(page.height, &OPS, &mut s)?;
            out.push(s);
        }
        Ok((page.width, page.height, out))
    }

    fn doc(attrs: &str, body: &str) -> String {
        format!("<svg xmlns=\"{SVG_NS}\" version=\"1.1\" {attrs}>{body}</svg>\n")
    }

    #[test]
    fn segments_flipped_and_exact() {
        let svg = doc(
            "width=\"3\" height=\"3\" viewBox=\"0 0 3 3\"",
            "<path fill=\"#1a237e\" fill-rule=\"nonzero\" d=\"M2 1L1 1L1 2.015625L2 2L2 1Z\"/>",
        );
        let (w, h, p) = paths(&svg).unwrap();
        assert_eq!((w, h), (3.0, 3.0));
        assert_eq!(
            p,
            ["26 35 126 255 false\n2 2 m\n1 2 l\n1 0.984375 l\n2 1 l\n2 2 l\nh\n"]
        );
    }

    #[test]
    fn quadratics_become_the_same_cubics() {
        // From (0, 0), control (3, 3), to (6, 0): cubic controls (2, 2) and (4, 2).
        let svg = doc(
            "width=\"6\" height=\"4\"",
            "<path d=\"M0 0Q3 3 6 0Z M6 0 q -3 3 -6 0 z\"/>",
        );
        let (_, _, p) = paths(&svg).unwrap();
        assert_eq!(
            p,
            ["0 0 0 255 false\n0 4 m\n2 2 4 2 6 4 c\nh\n6 4 m\n4 2 2 2 0 4 c\nh\n"]
        );
        // Thirds are rounded to 10^-6.
        let svg = doc("width=\"1\" height=\"1\"", "<path d=\"M0 0Q1 0 1 1\"/>");
        let (_, _, p) = paths(&svg).unwrap();
        assert_eq!(p, ["0 0 0 255 false\n0 1 m\n0.666667 1 1 0.666667 1 0 c\n"]);
    }

    #[test]
    fn fills_rules_and_empty_paths() {
        let svg = doc(
            "width=\"2px\" height=\"2\"",
            "<!-- c --><path fill=\"none\" d=\"M0 0L1 1Z\"/><path d=\"\"/>\
             <path fill=\"rgba(255,0,0,0.5)\" fill-rule=\"evenodd\" d=\"M0 0H1V1Z\"/>",
        );
        let (w, _, p) = paths(&svg).unwrap();
        assert_eq!(w, 2.0);
        assert_eq!(p, ["255 0 0 128 true\n0 2 m\n1 2 l\n1 1 l\nh\n"]);
    }

    #[test]
    fn unsupported_documents_are_refused() {
        for (svg, reason) in [
            (doc("width=\"2\"", ""), "needs both width and height"),
            (doc("width=\"2\" height=\"2mm\"", ""), "height '2mm'"),
            (doc("width=\"-2\" height=\"2\"", ""), "width '-2'"),
            (
                doc("width=\"2\" height=\"2\" viewBox=\"0 0 1 1\"", ""),
                "viewBox '0 0 1 1'",
            ),
            (
                doc("width=\"2\" height=\"2\" fill=\"red\"", ""),
                "'fill' of <svg>",
            ),
            (doc("width=\"2\" height=\"2\"", "<g/>"), "element <g>"),
            (doc("width=\"2\" height=\"2\"", "hello"), "holds text"),
            (
                doc(
                    "width=\"2\" height=\"2\"",
                    "<path transform=\"scale(2)\" d=\"M0 0\"/>",
                ),
                "'transform' of <path>",
            ),
            (
                doc(
                    "width=\"2\" height=\"2\"",
                    "<path fill=\"url(#g)\" d=\"M0 0\"/>",
                ),
                "fill 'url(#g)'",
            ),
            (
                doc(
                    "width=\"2\" height=\"2\"",
                    "<path fill-rule=\"odd\" d=\"M0 0\"/>",
                ),
                "fill-rule 'odd'",
            ),
            (
                doc("width=\"2\" height=\"2\"", "<path d=\"M0 0L1 x\"/>"),
                "path data",
            ),
            (
                "<svg width=\"2\" height=\"2\"/>".to_string(),
                "not an <svg> of the SVG namespace",
            ),
        ] {
            let e = paths(&svg).unwrap_err();
            assert!(e.contains(reason), "{svg}: {e}");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
    }
}
