//! PDF export: the filled paths of an SVG document as one page of a PDF 1.4 file.
//!
//! # The file
//! Objects: 1 the catalog, 2 the page tree, 3 the page (`MediaBox [0 0 W H]`, the SVG's size
//! with one pixel = one point), 4 its content stream (uncompressed, plain text a reader can
//! check: 1.1 to 1.25 times the size of the SVG), 5 the stream's length, then one
//! `ExtGState` per opacity used by a translucent fill, and the document information
//! (`/Producer`). The cross-reference
//! table holds the byte offset of every object, 20 bytes an entry.
//!
//! # The content
//! Each `<path>` is `q`, its colour (`r g b rg`, plus `/An gs` for a translucent fill), its
//! segments (`x y m`, `x y l`, `x1 y1 x2 y2 x y c`, `h`; see [`super::drawing`] for the
//! exact numbers and the flipped y axis), then `f` (nonzero fill rule, as the SVG's) or `f*`
//! (evenodd), and `Q`.
//!
//! Pages larger than 14 400 pt (200 inches, 14 400 pixels) exceed a limit of PDF 1.4
//! readers such as old Acrobat versions; poppler and most current readers draw them.

use super::drawing::{Operators, Page, DECIMALS};
use super::path_text::number;
use std::fmt::Write as _;

/// The path operators of PDF.
const OPS: Operators = Operators {
    move_to: "m",
    line_to: "l",
    curve_to: "c",
    close: "h",
};

/// Appends a colour component `c / 255` (exact enough for 8-bit readers: 6 decimals).
fn component(c: u8, s: &mut String) {
    number(f64::from(c) / 255.0, DECIMALS, s);
}

/// Appends object number `offsets.len() + 1` and records its offset.
fn object(out: &mut String, offsets: &mut Vec<usize>, body: &str) {
    offsets.push(out.len());
    let _ = write!(out, "{} 0 obj\n{body}\nendobj\n", offsets.len());
}

/// The PDF file of `page`; fails only on malformed path data.
pub(crate) fn pdf_bytes(page: &Page) -> Result<Vec<u8>, String> {
    // Opacities of translucent fills, each an ExtGState named /A<alpha>.
    let mut alphas: Vec<u8> = page
        .fills
        .iter()
        .map(|f| f.colour.alpha)
        .filter(|&a| a < 255)
        .collect();
    alphas.sort_unstable();
    alphas.dedup();
    const FIRST_STATE: usize = 6;
    let info = FIRST_STATE + alphas.len();

    // Written as one string, the content stream in place (its length is object 5, written
    // after it): at most about 1.25 times the path data (measured on a grid of isolated
    // pixels, the longest numbers per byte of SVG), and no copy of it.
    let mut out = String::with_capacity(page.data_len() / 2 * 3 + 1024);
    // A comment of bytes above 127 after the header marks the file as binary for transfers
    // (âãÏÓ in UTF-8: eight such bytes).
    out.push_str("%PDF-1.4\n%\u{e2}\u{e3}\u{cf}\u{d3}\n");
    let mut offsets = Vec::with_capacity(info);
    object(&mut out, &mut offsets, "<< /Type /Catalog /Pages 2 0 R >>");
    object(
        &mut out,
        &mut offsets,
        "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
    );
    let mut size = String::new();
    number(page.width, DECIMALS, &mut size);
    size.push(' ');
    number(page.height, DECIMALS, &mut size);
    let states: Vec<String> = alphas
        .iter()
        .enumerate()
        .map(|(k, a)| format!("/A{a} {} 0 R", FIRST_STATE + k))
        .collect();
    let resources = if states.is_empty() {
        "<< >>".to_string()
    } else {
        format!("<< /ExtGState << {} >> >>", states.join(" "))
    };
    let page_object = format!(
        "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {size}] /Contents 4 0 R \
         /Resources {resources} >>"
    );
    object(&mut out, &mut offsets, &page_object);

    offsets.push(out.len());
    out.push_str("4 0 obj\n<< /Length 5 0 R >>\nstream\n");
    let stream = out.len();
    for f in &page.fills {
        out.push_str("q\n");
        let c = f.colour;
        if c.alpha < 255 {
            let _ = writeln!(out, "/A{} gs", c.alpha);
        }
        for (k, v) in [c.red, c.green, c.blue].into_iter().enumerate() {
            if k > 0 {
                out.push(' ');
            }
            component(v, &mut out);
        }
        out.push_str(" rg\n");
        f.write_path(page.height, &OPS, &mut out)?;
        out.push_str(if f.even_odd { "f*\nQ\n" } else { "f\nQ\n" });
    }
    let length = out.len() - stream;
    out.push_str("\nendstream\nendobj\n");
    object(&mut out, &mut offsets, &length.to_string());
    for &a in &alphas {
        let mut o = String::from("<< /Type /ExtGState /ca ");
        component(a, &mut o);
        o.push_str(" >>");
        object(&mut out, &mut offsets, &o);
    }
    let producer = format!("<< /Producer (layertrace {}) >>", env!("CARGO_PKG_VERSION"));
    object(&mut out, &mut offsets, &producer);

    debug_assert_eq!(offsets.len(), info);
    let xref = out.len();
    let _ = write!(out, "xref\n0 {}\n0000000000 65535 f \n", info + 1);
    for o in offsets {
        // 20 bytes: the offset, the generation, `n`, and a two-byte end of line " \n".
        let _ = writeln!(out, "{o:010} 00000 n ");
    }
    let _ = write!(
        out,
        "trailer\n<< /Size {} /Root 1 0 R /Info {info} 0 R >>\nstartxref\n{xref}\n%%EOF\n",
        info + 1
    );
    Ok(out.into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pdf(svg: &str) -> Vec<u8> {
        let doc = roxmltree::Document::parse(svg).unwrap();
        pdf_bytes(&Page::read(&doc).unwrap()).unwrap()
    }

    /// The text between `from` and the next `to` after it.
    fn between<'a>(s: &'a str, from: &str, to: &str) -> &'a str {
        let i = s.find(from).unwrap() + from.len();
        &s[i..i + s[i..].find(to).unwrap()]
    }

    /// Checks the file's structure: every xref offset points at its object, the stream
    /// length is the stream's, startxref points at the table. Returns the content stream.
    fn check(bytes: &[u8]) -> String {
        let text = String::from_utf8_lossy(bytes).into_owned();
        assert!(bytes.starts_with(b"%PDF-1.4\n"));
        assert!(text.ends_with("%%EOF\n"));
        let start: usize = between(&text, "startxref\n", "\n").parse().unwrap();
        assert!(bytes[start..].starts_with(b"xref\n0 "));
        let table = &bytes[start..];
        let header = between(&text[start..], "xref\n", "\n");
        let n: usize = header.split(' ').nth(1).unwrap().parse().unwrap();
        let entries = &table[5 + header.len() + 1..];
        assert!(entries.starts_with(b"0000000000 65535 f \n"));
        for id in 1..n {
            let e = &entries[20 * id..20 * id + 20];
            assert_eq!(&e[10..], b" 00000 n \n", "entry {id}");
            let at: usize = std::str::from_utf8(&e[..10]).unwrap().parse().unwrap();
            let obj = format!("{id} 0 obj\n");
            assert!(bytes[at..].starts_with(obj.as_bytes()), "object {id}");
        }
        assert!(text.contains(&format!("/Size {n} ")));
        assert!(text.contains("<< /Length 5 0 R >>"));
        let len: usize = between(&text, "5 0 obj\n", "\n").parse().unwrap();
        let s = text.find("stream\n").unwrap() + 7;
        assert_eq!(&text[s + len..s + len + 11], "\nendstream\n");
        text[s..s + len].to_string()
    }

    #[test]
    fn one_page_with_the_paths() {
        let bytes = pdf(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"3\" \
             height=\"3\" viewBox=\"0 0 3 3\">\n<path fill=\"#ff8000\" fill-rule=\"nonzero\" \
             d=\"M2 1L1 1L1 2L2 2L2 1Z\"/>\n</svg>\n",
        );
        let content = check(&bytes);
        assert_eq!(
            content,
            "q\n1 0.501961 0 rg\n2 2 m\n1 2 l\n1 1 l\n2 1 l\n2 2 l\nh\nf\nQ\n"
        );
        let text = String::from_utf8_lossy(&bytes);
        assert!(
            text.contains("/MediaBox [0 0 3 3] /Contents 4 0 R /Resources << >> >>"),
            "{text}"
        );
        assert!(!text.contains("/ExtGState /ca"));
    }

    #[test]
    fn translucent_and_evenodd_fills() {
        let bytes = pdf(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"4.5\" height=\"2\">\
             <path fill=\"rgba(0,0,0,0.5)\" fill-rule=\"evenodd\" d=\"M0 0L1 0L1 1Z\"/>\
             <path d=\"M0 0L1 1L0 1Z\"/></svg>",
        );
        let content = check(&bytes);
        assert_eq!(
            content,
            "q\n/A128 gs\n0 0 0 rg\n0 2 m\n1 2 l\n1 1 l\nh\nf*\nQ\n\
             q\n0 0 0 rg\n0 2 m\n1 1 l\n0 1 l\nh\nf\nQ\n"
        );
        let text = String::from_utf8_lossy(&bytes);
        assert!(text.contains("/MediaBox [0 0 4.5 2]"), "{text}");
        assert!(text.contains("/ExtGState << /A128 6 0 R >>"), "{text}");
        assert!(text.contains("6 0 obj\n<< /Type /ExtGState /ca 0.501961 >>"));
    }

    #[test]
    fn an_empty_page() {
        let content = check(&pdf(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"7\" height=\"5\"></svg>",
        ));
        assert_eq!(content, "");
    }
}
