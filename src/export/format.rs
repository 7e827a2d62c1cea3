//! Output formats chosen by file name: SVG, PDF or EPS for the drawing (potrace's vector
//! backends), PNG for the pictures, and [`document_bytes`] to write the drawing in a format.
//!
//! The extension decides, compared without case (`x.PDF` is a PDF); standard output (`-`,
//! `/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1`) gets SVG or PNG. Any other extension, or
//! none (`/dev/null` too), is refused with [`Error::UnknownFormat`] before any work.

use super::drawing::Page;
use crate::error::Error;
use std::ffi::OsStr;
use std::fmt;
use std::path::Path;

/// A format of the drawing: the paths [`svg_document`](crate::svg_document) writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// SVG, the document as [`svg_document`](crate::svg_document) writes it.
    Svg,
    /// PDF 1.4, one page of the image's size (1 px = 1 pt).
    Pdf,
    /// Encapsulated PostScript (EPSF-3.0), bounding box the image's size (1 px = 1 pt).
    Eps,
}

/// What `-o` accepts, for messages.
const DRAWING_EXTENSIONS: &str = ".svg, .pdf or .eps";

impl Format {
    /// Every format, in the order messages list them.
    pub const ALL: [Format; 3] = [Format::Svg, Format::Pdf, Format::Eps];

    /// The format named by the extension of `path` (case-insensitive); SVG for standard
    /// output. Fails with [`Error::UnknownFormat`] for any other extension or none.
    ///
    /// ```
    /// use layertrace::Format;
    /// use std::path::Path;
    ///
    /// assert_eq!(Format::from_path(Path::new("logo.PDF")).unwrap(), Format::Pdf);
    /// assert_eq!(Format::from_path(Path::new("-")).unwrap(), Format::Svg);
    /// let e = Format::from_path(Path::new("x.txt")).unwrap_err();
    /// assert_eq!(e.to_string(), "x.txt: unknown output format 'txt' (use .svg, .pdf or .eps)");
    /// ```
    pub fn from_path(path: &Path) -> Result<Format, Error> {
        if is_stdout(path) {
            return Ok(Format::Svg);
        }
        let ext = extension(path, DRAWING_EXTENSIONS)?;
        Format::ALL
            .into_iter()
            .find(|f| ext.eq_ignore_ascii_case(f.extension()))
            .ok_or_else(|| unknown(path, Some(ext), DRAWING_EXTENSIONS))
    }

    /// The usual file extension, without the dot: `svg`, `pdf`, `eps`.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Pdf => "pdf",
            Format::Eps => "eps",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::Svg => "SVG",
            Format::Pdf => "PDF",
            Format::Eps => "EPS",
        })
    }
}

/// A format of the pictures (the decomposition and the round-trip differences).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PictureFormat {
    /// PNG, the only one.
    Png,
}

impl PictureFormat {
    /// The format named by the extension of `path` (case-insensitive; only `.png`); PNG for
    /// standard output. Fails with [`Error::UnknownFormat`] otherwise.
    pub fn from_path(path: &Path) -> Result<PictureFormat, Error> {
        if is_stdout(path) {
            return Ok(PictureFormat::Png);
        }
        let ext = extension(path, ".png")?;
        if ext.eq_ignore_ascii_case("png") {
            Ok(PictureFormat::Png)
        } else {
            Err(unknown(path, Some(ext), ".png"))
        }
    }
}

/// `-` or a name of standard output.
fn is_stdout(path: &Path) -> bool {
    path == Path::new("-") || crate::output::is_stdout_alias(path)
}

/// The extension of `path`, or [`Error::UnknownFormat`] when it has none.
fn extension<'a>(path: &'a Path, expected: &'static str) -> Result<&'a OsStr, Error> {
    path.extension()
        .filter(|e| !e.is_empty())
        .ok_or_else(|| unknown(path, None, expected))
}

fn unknown(path: &Path, ext: Option<&OsStr>, expected: &'static str) -> Error {
    Error::UnknownFormat {
        path: path.to_path_buf(),
        extension: ext.map(|e| e.to_string_lossy().into_owned()),
        expected,
    }
}

/// The drawing `svg` (a document as [`svg_document`](crate::svg_document) writes it) as
/// the bytes of a file in `format`. SVG is the document itself, not copied; PDF (1.4, one
/// page, uncompressed) and EPS (EPSF-3.0) are written from the document's paths, with the
/// same coordinates exactly (y flipped: their origin is at the bottom left), the same
/// fill colour and fill rule, page size the image size with 1 px = 1 pt.
///
/// Fails with [`Error::Convert`] when the document is not one these writers read (other
/// elements, transforms, strokes: see [`svg_document`](crate::svg_document) for what it
/// holds), and for EPS when a fill is translucent (PostScript has no transparency).
///
/// ```
/// use layertrace::{document_bytes, Format};
///
/// let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"3\" \
///            height=\"3\" viewBox=\"0 0 3 3\">\n<path fill=\"black\" fill-rule=\"nonzero\" \
///            d=\"M2 1L1 1L1 2L2 2L2 1Z\"/>\n</svg>\n";
/// let pdf = document_bytes(svg.to_string(), Format::Pdf).unwrap();
/// assert!(pdf.starts_with(b"%PDF-1.4\n"));
/// let eps = document_bytes(svg.to_string(), Format::Eps).unwrap();
/// assert!(eps.starts_with(b"%!PS-Adobe-3.0 EPSF-3.0\n"));
/// ```
pub fn document_bytes(svg: String, format: Format) -> Result<Vec<u8>, Error> {
    let convert = |reason: String| Error::Convert { format, reason };
    match format {
        Format::Svg => Ok(svg.into_bytes()),
        Format::Pdf | Format::Eps => {
            let doc = roxmltree::Document::parse(&svg)
                .map_err(|e| convert(format!("not an SVG document: {e}")))?;
            let page = Page::read(&doc).map_err(convert)?;
            match format {
                Format::Pdf => super::pdf::pdf_bytes(&page).map_err(convert),
                _ => super::eps::eps_bytes(&page)
                    .map(String::into_bytes)
                    .map_err(convert),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_extension() {
        for (name, want) in [
            ("a.svg", Format::Svg),
            ("dir.pdf/a.SVG", Format::Svg),
            ("a.b.Pdf", Format::Pdf),
            ("a.eps", Format::Eps),
            ("A.EPS", Format::Eps),
            ("-", Format::Svg),
            ("/dev/stdout", Format::Svg),
        ] {
            assert_eq!(Format::from_path(Path::new(name)).unwrap(), want, "{name}");
        }
        for (name, message) in [
            (
                "x.txt",
                "x.txt: unknown output format 'txt' (use .svg, .pdf or .eps)",
            ),
            (
                "x.png",
                "x.png: unknown output format 'png' (use .svg, .pdf or .eps)",
            ),
            (
                "x",
                "x: no extension to name the output format (use .svg, .pdf or .eps)",
            ),
            (
                "x.",
                "x.: no extension to name the output format (use .svg, .pdf or .eps)",
            ),
            (
                ".svg",
                ".svg: no extension to name the output format (use .svg, .pdf or .eps)",
            ),
            (
                "/dev/null",
                "/dev/null: no extension to name the output format (use .svg, .pdf or .eps)",
            ),
        ] {
            let e = Format::from_path(Path::new(name)).unwrap_err();
            assert!(matches!(e, Error::UnknownFormat { .. }));
            assert_eq!(e.to_string(), message);
        }
        assert_eq!(
            PictureFormat::from_path(Path::new("d.PNG")).unwrap(),
            PictureFormat::Png
        );
        assert_eq!(
            PictureFormat::from_path(Path::new("-")).unwrap(),
            PictureFormat::Png
        );
        let e = PictureFormat::from_path(Path::new("d.svg")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "d.svg: unknown output format 'svg' (use .png)"
        );
        assert!(PictureFormat::from_path(Path::new("d")).is_err());
    }

    #[test]
    fn conversion_errors_are_one_line() {
        let e = document_bytes("<svg".into(), Format::Pdf).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("cannot write PDF: not an SVG document: "),
            "{e}"
        );
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"2\" height=\"2\">\
                   <path fill=\"rgba(0,0,0,0.5)\" d=\"M0 0L1 1L0 1Z\"/></svg>";
        let e = document_bytes(svg.into(), Format::Eps).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("cannot write EPS: a fill has opacity"),
            "{e}"
        );
        // PDF has transparency.
        assert!(document_bytes(svg.into(), Format::Pdf).is_ok());
        assert_eq!(
            document_bytes(svg.into(), Format::Svg).unwrap(),
            svg.as_bytes()
        );
        for e in [
            document_bytes("<svg".into(), Format::Eps).unwrap_err(),
            document_bytes(
                "<svg xmlns=\"http://www.w3.org/2000/svg\"/>".into(),
                Format::Pdf,
            )
            .unwrap_err(),
        ] {
            assert_eq!(e.to_string().lines().count(), 1, "{e}");
        }
    }
}
