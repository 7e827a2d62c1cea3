//! EPS export: the filled paths of an SVG document as an Encapsulated PostScript file
//! (EPSF-3.0), one pixel = one point.
//!
//! # The file
//! The DSC header (`%!PS-Adobe-3.0 EPSF-3.0`, `%%BoundingBox: 0 0 W H` rounded up to whole
//! points, `%%HiResBoundingBox` with the exact size), then the drawing inside
//! `save … restore` and a dictionary of its own (the short operator names `m l c h` are
//! defined there, not in the includer's), `showpage`, `%%EOF`. Each `<path>` is its colour
//! (`r g b setrgbcolor`), `newpath`, its segments (see [`super::drawing`] for the exact
//! numbers and the flipped y axis), then `fill` (nonzero winding, as the SVG's) or `eofill`.
//!
//! PostScript has no transparency: a translucent fill is refused (a fully transparent one
//! paints nothing and is left out).

use super::drawing::{Operators, Page, DECIMALS};
use super::path_text::number;
use std::fmt::Write as _;

/// The operators defined in the file's own dictionary.
const OPS: Operators = Operators {
    move_to: "m",
    line_to: "l",
    curve_to: "c",
    close: "h",
};

/// The EPS file of `page`; fails on a translucent fill and on malformed path data.
pub(crate) fn eps_bytes(page: &Page) -> Result<String, String> {
    if let Some(f) = page
        .fills
        .iter()
        .find(|f| f.colour.alpha > 0 && f.colour.alpha < 255)
    {
        return Err(format!(
            "a fill has opacity {:.3} and PostScript has no transparency (use an opaque colour)",
            f64::from(f.colour.alpha) / 255.0
        ));
    }
    let mut size = String::new();
    number(page.width, DECIMALS, &mut size);
    size.push(' ');
    number(page.height, DECIMALS, &mut size);
    // About 1.25 times the path data at most (see the PDF writer): reserved, not grown.
    let mut s = String::with_capacity(page.data_len() / 2 * 3 + 1024);
    let _ = write!(
        s,
        "%!PS-Adobe-3.0 EPSF-3.0\n\
         %%Creator: layertrace {}\n\
         %%BoundingBox: 0 0 {} {}\n\
         %%HiResBoundingBox: 0 0 {size}\n\
         %%LanguageLevel: 2\n\
         %%Pages: 1\n\
         %%EndComments\n\
         %%Page: 1 1\n\
         save\n\
         4 dict begin\n\
         /m {{moveto}} bind def\n\
         /l {{lineto}} bind def\n\
         /c {{curveto}} bind def\n\
         /h {{closepath}} bind def\n",
        env!("CARGO_PKG_VERSION"),
        page.width.ceil(),
        page.height.ceil(),
    );
    for f in page.fills.iter().filter(|f| f.colour.alpha > 0) {
        let c = f.colour;
        for v in [c.red, c.green, c.blue] {
            number(f64::from(v) / 255.0, DECIMALS, &mut s);
            s.push(' ');
        }
        s.push_str("setrgbcolor\nnewpath\n");
        f.write_path(page.height, &OPS, &mut s)?;
        s.push_str(if f.even_odd { "eofill\n" } else { "fill\n" });
    }
    s.push_str("end\nrestore\nshowpage\n%%Trailer\n%%EOF\n");
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eps(svg: &str) -> Result<String, String> {
        let doc = roxmltree::Document::parse(svg).unwrap();
        eps_bytes(&Page::read(&doc).unwrap())
    }

    #[test]
    fn header_and_paths() {
        let out = eps(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"3\" \
             height=\"2.5\" viewBox=\"0 0 3 2.5\">\n<path fill=\"#ff8000\" fill-rule=\"nonzero\" \
             d=\"M2 1L1 1L1 2L2 2L2 1Z\"/>\n<path fill=\"red\" fill-rule=\"evenodd\" \
             d=\"M0 0L1 0L1 1Z\"/><path fill=\"transparent\" d=\"M0 0L1 0L1 1Z\"/></svg>\n",
        )
        .unwrap();
        assert!(out.starts_with("%!PS-Adobe-3.0 EPSF-3.0\n%%Creator: layertrace "));
        assert!(out.contains("\n%%BoundingBox: 0 0 3 3\n%%HiResBoundingBox: 0 0 3 2.5\n"));
        let body = &out[out.find("/h {closepath} bind def\n").unwrap() + 24..];
        assert_eq!(
            body,
            "1 0.501961 0 setrgbcolor\nnewpath\n2 1.5 m\n1 1.5 l\n1 0.5 l\n2 0.5 l\n\
             2 1.5 l\nh\nfill\n\
             1 0 0 setrgbcolor\nnewpath\n0 2.5 m\n1 2.5 l\n1 1.5 l\nh\neofill\n\
             end\nrestore\nshowpage\n%%Trailer\n%%EOF\n"
        );
        // DSC: no line over 255 characters.
        assert!(out.lines().all(|l| l.len() <= 255));
    }

    #[test]
    fn translucent_fills_are_refused() {
        let e = eps(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"3\" height=\"3\">\
             <path fill=\"rgba(0,0,0,0.5)\" d=\"M0 0L1 0L1 1Z\"/></svg>",
        )
        .unwrap_err();
        assert!(e.contains("opacity 0.502"), "{e}");
        assert!(e.contains("no transparency"), "{e}");
    }
}
