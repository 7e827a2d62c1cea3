//! The one-call entry point: an image in; the SVG, the decomposition and whatever else was
//! asked out.

mod colour;
mod options;
mod partition;
mod partition_run;

pub use colour::{ColourLayer, ColourVectorized};
pub use options::{Layout, Options, ParseLayoutError, Progress, ProgressFn, Stage};

use std::path::{Path, PathBuf};

use crate::bitmap::{
    alpha_mask, decode_rgba, has_transparency, load_memory, load_path, load_rgba, Band, Cleaned,
    Compat, LoadOptions, Mask, MAX_BAND,
};
use crate::contour::{trace, Contour, Convention};
use crate::decompose::{decompose_reporting, Decomposition, OutlierRule};
use crate::error::Error;
use crate::estimate::work_estimate;
use crate::export::json::{decomposition_json, JsonHeader};
use crate::export::picture::{decomposition_picture, default_scale};
use crate::export::svg::{svg_document_reporting, SvgOutput};
use crate::fidelity::{
    band_check, compare, rasterize_svg, rasterize_svg_in_tiles, BandCheck, FidelityReport,
};
use crate::output::png_bytes;

/// What [`vectorize`] reads.
#[derive(Clone, Copy, Debug)]
pub enum Source<'a> {
    /// An image file (any format the `image` crate decodes; the format is guessed from the
    /// content); `-` is standard input.
    Path(&'a Path),
    /// An encoded image file held in memory.
    Bytes(&'a [u8]),
    /// A binary image: foreground `true`, used as it is (no threshold, no inversion).
    Mask(&'a Mask),
}

impl<'a> From<&'a Path> for Source<'a> {
    fn from(path: &'a Path) -> Source<'a> {
        Source::Path(path)
    }
}

impl<'a> From<&'a PathBuf> for Source<'a> {
    fn from(path: &'a PathBuf) -> Source<'a> {
        Source::Path(path)
    }
}

impl<'a> From<&'a [u8]> for Source<'a> {
    fn from(bytes: &'a [u8]) -> Source<'a> {
        Source::Bytes(bytes)
    }
}

impl<'a> From<&'a Vec<u8>> for Source<'a> {
    fn from(bytes: &'a Vec<u8>) -> Source<'a> {
        Source::Bytes(bytes)
    }
}

impl<'a> From<&'a Mask> for Source<'a> {
    fn from(mask: &'a Mask) -> Source<'a> {
        Source::Mask(mask)
    }
}

impl Source<'_> {
    /// How errors name the input: the path, `<stdin>`, `<memory>` or `<mask>`.
    pub fn name(&self) -> PathBuf {
        match self {
            Source::Path(p) if *p == Path::new("-") => PathBuf::from("<stdin>"),
            Source::Path(p) => p.to_path_buf(),
            Source::Bytes(_) => PathBuf::from("<memory>"),
            Source::Mask(_) => PathBuf::from("<mask>"),
        }
    }
}

/// The rendering of the SVG compared with the mask.
#[derive(Clone, Debug)]
pub struct Fidelity {
    /// Pixel counts of the comparison.
    pub report: FidelityReport,
    /// The SVG as `resvg --shape-rendering crispEdges` draws it.
    pub rendered: Mask,
    /// With [`Options::smooth`]: how far from the border the differing pixels are.
    pub band: Option<BandCheck>,
    /// The comparison with the SVG as Chromium draws the document opened at 1:1, in
    /// raster tiles that cut the path at their borders ([`rasterize_svg_in_tiles`]); `None`
    /// when Chromium draws the document as one tile (under 512 px both ways: it is then
    /// drawn as `rendered`), or when [`Options::tile_fidelity`] is off.
    pub tiled: Option<FidelityReport>,
}

/// Everything [`vectorize`] made.
#[derive(Clone, Debug)]
pub struct Vectorized {
    /// The foreground mask that was vectorized.
    pub mask: Mask,
    /// The grey threshold used (foreground = grey < threshold before inversion; the mean of
    /// the local thresholds for an adaptive one); 0 for a mask input.
    pub threshold: u8,
    /// What [`Options::turdsize`] dropped.
    pub cleaned: Cleaned,
    /// The contours and their pieces, each with its exact certificate.
    pub decomposition: Decomposition,
    /// The SVG document and its statistics, unless [`Options::svg`] is `None`.
    pub svg: Option<SvgOutput>,
    /// The SVG rendered back and compared, if [`Options::fidelity`] and an SVG were asked.
    pub fidelity: Option<Fidelity>,
    /// The decomposition as JSON (format `layertrace-decomposition/2`), if asked.
    pub json: Option<String>,
    /// The decomposition picture as PNG bytes, if asked.
    pub picture: Option<Vec<u8>>,
    /// The regions and layers of a colour run ([`Options::colors`]); `None` for a binary
    /// one. A colour run's `mask` holds the pixels of every region, its `decomposition`
    /// every layer's contours in drawing order, its `json` the
    /// `layertrace-colour/1` text, and its `fidelity` is `None` (see
    /// [`ColourVectorized::fidelity`]).
    pub colour: Option<ColourVectorized>,
}

impl Vectorized {
    /// The SVG text ("" when none was asked).
    pub fn svg_text(&self) -> &str {
        self.svg.as_ref().map_or("", |s| s.svg.as_str())
    }
}

/// Vectorizes an image in one call: decode and threshold it, trace every border, decompose
/// the borders into pieces with exact certificates, draw the SVG, and make what else
/// `options` asks for (fidelity check, JSON, picture).
///
/// Errors (unreadable, corrupt or too large input, more memory than
/// [`Options::max_memory`]) are returned, never panicked; no file is written.
///
/// ```
/// use layertrace::{vectorize, Mask, Options};
///
/// // A 10 × 10 square on a 16 × 16 bitmap.
/// let mask = Mask::from_fn(16, 16, |x, y| (3..13).contains(&x) && (3..13).contains(&y));
/// let out = vectorize(&mask, &Options::default().fidelity(true))?;
/// assert!(out.svg_text().starts_with("<svg"));
/// assert_eq!(out.fidelity.unwrap().report.differing, 0); // exact as resvg draws it
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn vectorize<'a>(
    source: impl Into<Source<'a>>,
    options: &Options,
) -> Result<Vectorized, Error> {
    let source = source.into();
    match &options.pool {
        Some(pool) => pool.install(|| run(source, options)),
        None => run(source, options),
    }
}

fn run(source: Source<'_>, options: &Options) -> Result<Vectorized, Error> {
    let name = source.name();
    if let Some(nu) = options.smooth {
        if !(nu > 0.0 && nu <= MAX_BAND) {
            return Err(Error::Arguments(format!(
                "smooth: {nu} is not a distance in (0, {MAX_BAND}] pixels"
            )));
        }
        if options.compat == Compat::Ipol {
            return Err(Error::Arguments(
                "smooth: not with the IPOL conventions (--compat ipol)".into(),
            ));
        }
    }
    if let Some(colors) = options.colors {
        if options.alpha {
            return Err(Error::Arguments(
                "--alpha is for one-colour icons; --colors already keeps transparent pixels out"
                    .into(),
            ));
        }
        let c = colour::run(&name, source, colors, options)?;
        return Ok(Vectorized {
            mask: c.mask,
            threshold: 0,
            cleaned: Cleaned::default(),
            decomposition: c.merged,
            svg: c.svg,
            fidelity: None,
            json: c.json,
            picture: None,
            colour: Some(c.colour),
        });
    }
    let load = LoadOptions {
        threshold: options.effective_threshold(),
        invert: options.invert,
        compat: options.compat,
        max_pixels: options.max_pixels,
        max_memory: options.max_memory,
        turdsize: options.turdsize,
    };
    let (mask, threshold, cleaned) = match source {
        Source::Path(path) if options.alpha => {
            let mut mask = alpha_mask(&load_rgba(path, options.max_pixels, options.max_memory)?);
            let cleaned = mask.clean(options.turdsize);
            (mask, 0, cleaned)
        }
        Source::Bytes(bytes) if options.alpha => {
            let rgba = decode_rgba(bytes, &name, options.max_pixels, options.max_memory)?;
            let mut mask = alpha_mask(&rgba);
            let cleaned = mask.clean(options.turdsize);
            (mask, 0, cleaned)
        }
        Source::Path(path) => {
            let l = load_path(path, &load)?;
            (l.mask, l.threshold, l.cleaned)
        }
        Source::Bytes(bytes) => {
            let l = load_memory(bytes, &load)?;
            (l.mask, l.threshold, l.cleaned)
        }
        Source::Mask(mask) => {
            let mut mask = mask.clone();
            let cleaned = mask.clean(options.turdsize);
            (mask, 0, cleaned)
        }
    };
    if mask.count_foreground() == 0 && !options.alpha {
        no_foreground(source, &name, threshold, options)?;
    }
    let ipol = options.compat == Compat::Ipol;
    let (convention, rule) = if ipol {
        (Convention::Ipol, OutlierRule::Any)
    } else {
        (Convention::Default, OutlierRule::NotInPiece)
    };
    let contours = trace(&mask, convention);
    check_memory(&name, options, &contours, &mask)?;

    let progress = |stage: Stage| {
        let total = contours.len() as u64;
        let report = options.progress.clone();
        move |done: usize| {
            if let Some(f) = &report {
                f(Progress {
                    stage,
                    done: done as u64,
                    total,
                })
            }
        }
    };
    let on_decompose = progress(Stage::Decompose);
    let on_draw = progress(Stage::Draw);
    let d = decompose_reporting(
        contours,
        options.model,
        rule,
        options.budget,
        options.cover,
        &on_decompose,
    );

    let json = options.json.then(|| {
        decomposition_json(
            &d,
            &JsonHeader {
                width: mask.width(),
                height: mask.height(),
                threshold,
                invert: options.invert,
            },
        )
    });
    let picture = match options.picture {
        None => None,
        Some(scale) => {
            let scale = scale.unwrap_or_else(|| default_scale(mask.width(), mask.height()));
            let img = decomposition_picture(&mask, &d, scale, picture_max_pixels(options)).ok_or(
                Error::PictureTooLarge {
                    path: name.clone(),
                    scale,
                },
            )?;
            Some(png_bytes(&img).map_err(|source| Error::Encode {
                path: name.clone(),
                source,
            })?)
        }
    };
    let band = match (options.smooth, &options.svg) {
        (Some(nu), Some(_)) => Band::new(&mask, nu),
        _ => None,
    };
    let svg = options.svg.as_ref().map(|o| {
        svg_document_reporting(&d, mask.width(), mask.height(), o, band.as_ref(), &on_draw)
    });
    let fidelity = match (&svg, options.fidelity) {
        (Some(svg), true) => {
            let rendered = rasterize_svg(&svg.svg, mask.width(), mask.height())?;
            let (w, h) = (i64::from(mask.width()), i64::from(mask.height()));
            let tiled = if options.tile_fidelity && !crate::outline::tiles::one_tile(w, h) {
                let t = rasterize_svg_in_tiles(&svg.svg, mask.width(), mask.height())?;
                Some(compare(&mask, &t))
            } else {
                None
            };
            Some(Fidelity {
                report: compare(&mask, &rendered),
                tiled,
                band: band.as_ref().map(|b| band_check(&mask, &rendered, b.nu())),
                rendered,
            })
        }
        _ => None,
    };
    Ok(Vectorized {
        mask,
        threshold,
        cleaned,
        decomposition: d,
        svg,
        fidelity,
        json,
        picture,
        colour: None,
    })
}

/// [`Error::NoForeground`] when the image behind an empty mask has transparency (a light
/// logo on transparency: `--alpha` draws it); the image is decoded again for this only.
/// Standard input, read once, is not checked.
fn no_foreground(
    source: Source<'_>,
    name: &Path,
    threshold: u8,
    options: &Options,
) -> Result<(), Error> {
    let rgba = match source {
        Source::Path(path) if path != Path::new("-") => {
            load_rgba(path, options.max_pixels, options.max_memory)
        }
        Source::Bytes(bytes) => decode_rgba(bytes, name, options.max_pixels, options.max_memory),
        _ => return Ok(()),
    };
    match rgba {
        Ok(rgba) if has_transparency(&rgba) => Err(Error::NoForeground {
            path: name.to_path_buf(),
            threshold,
        }),
        _ => Ok(()),
    }
}

/// The largest decomposition picture drawn (larger ones are refused).
fn picture_max_pixels(options: &Options) -> u64 {
    options.max_pixels.max(1 << 24)
}

/// Refuses a run whose work after tracing would need more than [`Options::max_memory`]
/// bytes, before it allocates anything: the decomposition, and what the asked outputs need
/// on top of it.
pub(super) fn check_memory(
    name: &Path,
    options: &Options,
    contours: &[Contour],
    mask: &Mask,
) -> Result<(), Error> {
    let (w, h) = (mask.width(), mask.height());
    let threads = match &options.pool {
        Some(p) => p.current_num_threads(),
        None => rayon::current_num_threads(),
    };
    let e = work_estimate(contours, options.model, w, h, threads);
    let mut needed = e.contours + e.decomposition;
    if options.svg.is_some() {
        needed += e.svg_document
            + if options.fidelity {
                e.svg_drawing.max(e.fidelity)
            } else {
                e.svg_drawing
            };
    }
    if options.json {
        // The JSON text: measured at most 160 bytes per contour point (a one-pixel
        // checkerboard, every contour a single piece), doubled for the string's growth.
        let points: u64 = contours.iter().map(|c| c.points.len() as u64).sum();
        needed += 2 * 160 * (points + contours.len() as u64);
    }
    if let Some(scale) = options.picture {
        // A picture over decomposition_picture's own bound is refused there, not drawn.
        let k = u64::from(scale.unwrap_or_else(|| default_scale(w, h)));
        let pixels = u64::from(w) * k * u64::from(h) * k;
        needed += 3 * pixels.min(picture_max_pixels(options));
    }
    if needed > options.max_memory {
        return Err(Error::NeedsMemory {
            path: name.to_path_buf(),
            needed,
            limit: options.max_memory,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests;
