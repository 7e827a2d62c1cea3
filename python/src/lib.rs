//! `layertrace._layertrace`: the native half of the Python package (PyO3).
//!
//! One function, [`vectorize`], takes an encoded image (bytes), a path, raw pixels (grey,
//! RGB or RGBA, row by row) or a mask (one byte per pixel, non-zero = foreground) and
//! returns a dict of everything layertrace makes; the Python module `layertrace` wraps it
//! (NumPy arrays and PIL images are turned into raw pixels there). The work runs with the
//! GIL released. Every error is a `layertrace.Error` (a `ValueError`) carrying the CLI's
//! one-line message.

use std::path::PathBuf;

use layertrace::{
    colour_diff_image, diff_image, png_bytes, recognition_json, recognize_points, threshold_image,
    vectorize as run, Compat, Cover, Error as LtError, Layout, LoadOptions, Mask, Model, Options,
    PointSets, Threshold,
};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

create_exception!(
    _layertrace,
    Error,
    PyValueError,
    "Bad input or options: the message is the layertrace command line's."
);

/// What was given, borrowed for the time of the work (the GIL released).
enum Input<'a> {
    Bytes(&'a [u8]),
    Path(PathBuf),
    /// Raw pixels: width, height, channels (1 grey, 3 RGB, 4 RGBA).
    Pixels(&'a [u8], u32, u32, u8),
    /// One byte per pixel, non-zero = foreground.
    Mask(&'a [u8], u32, u32),
}

/// The figures of one colour of a colour run.
struct ColourMade {
    colour: String,
    pixels: u64,
    differing: u64,
}

/// Everything the work made, before it becomes a dict.
struct Made {
    svg: String,
    json: String,
    width: u32,
    height: u32,
    threshold: u8,
    contours: usize,
    pieces: usize,
    commands: usize,
    /// Binary runs: differing, missing, extra, IoU.
    fidelity: Option<(u64, u64, u64, f64)>,
    /// Binary runs of images Chromium draws in several tiles: differing pixels there.
    tiled: Option<u64>,
    /// Colour runs: differing pixels, painted outside the regions, seam pixels, per colour.
    colour_fidelity: Option<(u64, u64, u64, Vec<ColourMade>)>,
    /// Smooth runs: differing pixels farther than NU from the border, and the largest
    /// distance of a differing pixel.
    band: Option<(u64, f64)>,
    /// Binary runs only.
    decomposition_png: Option<Vec<u8>>,
    diff_png: Option<Vec<u8>>,
}

fn model(s: &str) -> Result<Model, String> {
    Model::parse_image_model(s).map_err(|e| e.to_string())
}

/// `stack` or `partition`, as the command line's `--layout`.
fn layout(s: &str) -> Result<Layout, String> {
    s.parse().map_err(|e: layertrace::ParseLayoutError| e.to_string())
}

/// `N` (0..=255), `otsu`, or `adaptive[:R[:K]]`, as the command line's `--threshold`.
fn threshold(s: &str) -> Result<Threshold, String> {
    s.trim()
        .parse()
        .map_err(|e: layertrace::ParseThresholdError| e.to_string())
}

fn work(input: Input<'_>, options: &Options) -> Result<Made, LtError> {
    let (out, threshold) = match input {
        Input::Bytes(bytes) => {
            let out = run(bytes, options)?;
            let t = out.threshold;
            (out, t)
        }
        Input::Path(path) => {
            let out = run(&path, options)?;
            let t = out.threshold;
            (out, t)
        }
        Input::Pixels(data, width, height, channels) => {
            let name = PathBuf::from("<array>");
            check_size(&name, width, height, options)?;
            let (w, h) = (width, height);
            let raw = data.to_vec();
            let bad = || {
                LtError::Arguments(format!(
                    "{w}x{h}x{channels} pixels need {} bytes, got {}",
                    u64::from(w) * u64::from(h) * u64::from(channels),
                    data.len()
                ))
            };
            let img = match channels {
                1 => image::GrayImage::from_raw(w, h, raw).map(image::DynamicImage::ImageLuma8),
                3 => image::RgbImage::from_raw(w, h, raw).map(image::DynamicImage::ImageRgb8),
                4 => image::RgbaImage::from_raw(w, h, raw).map(image::DynamicImage::ImageRgba8),
                c => {
                    return Err(LtError::Arguments(format!(
                        "an image has 1 (grey), 3 (RGB) or 4 (RGBA) channels, not {c}"
                    )))
                }
            }
            .ok_or_else(bad)?;
            if options.colors.is_some() || options.alpha {
                // Colours and the alpha mask are read from an encoded image: a PNG made in
                // memory, lossless.
                let mut png = Vec::new();
                img.write_with_encoder(image::codecs::png::PngEncoder::new_with_quality(
                    &mut png,
                    image::codecs::png::CompressionType::Fast,
                    image::codecs::png::FilterType::NoFilter,
                ))
                .map_err(|e| LtError::Arguments(format!("cannot encode the pixels: {e}")))?;
                let out = run(png.as_slice(), options)?;
                let t = out.threshold;
                (out, t)
            } else {
                let load = LoadOptions {
                    threshold: options.effective_threshold(),
                    invert: options.invert,
                    compat: Compat::Default,
                    max_pixels: options.max_pixels,
                    max_memory: options.max_memory,
                    turdsize: 0, // applied by `run` to the mask
                };
                let loaded = threshold_image(&img, &load);
                (run(&loaded.mask, options)?, loaded.threshold)
            }
        }
        Input::Mask(data, width, height) => {
            let name = PathBuf::from("<mask>");
            check_size(&name, width, height, options)?;
            let w = width as usize;
            if data.len() as u64 != u64::from(width) * u64::from(height) {
                return Err(LtError::Arguments(format!(
                    "a {width}x{height} mask needs {} bytes, got {}",
                    u64::from(width) * u64::from(height),
                    data.len()
                )));
            }
            let mask = Mask::from_fn(width, height, |x, y| data[y as usize * w + x as usize] != 0);
            (run(&mask, options)?, 0)
        }
    };
    let picture_error =
        |e: image::ImageError| LtError::Arguments(format!("cannot encode a picture: {e}"));
    let colour_fidelity = out.colour.as_ref().and_then(|c| c.fidelity.as_ref());
    let diff_png = match (&out.fidelity, &out.colour, colour_fidelity) {
        (Some(f), _, _) => {
            Some(png_bytes(&diff_image(&out.mask, &f.rendered)).map_err(picture_error)?)
        }
        (None, Some(c), Some(f)) => Some(
            png_bytes(&colour_diff_image(&c.regions.image, &f.rendered)).map_err(picture_error)?,
        ),
        _ => None,
    };
    Ok(Made {
        svg: out.svg_text().to_string(),
        json: out.json.clone().unwrap_or_default(),
        width: out.mask.width(),
        height: out.mask.height(),
        threshold,
        contours: out.decomposition.contours.len(),
        pieces: out.decomposition.piece_count(),
        commands: out.svg.as_ref().map_or(0, |s| s.commands.total()),
        fidelity: out.fidelity.as_ref().map(|f| {
            (
                f.report.differing,
                f.report.missing,
                f.report.extra,
                f.report.iou,
            )
        }),
        tiled: out
            .fidelity
            .as_ref()
            .and_then(|f| f.tiled.map(|t| t.differing)),
        colour_fidelity: colour_fidelity.map(|f| {
            let colours = f
                .colours
                .iter()
                .map(|d| ColourMade {
                    colour: d.colour.to_string(),
                    pixels: d.pixels,
                    differing: d.differing,
                })
                .collect();
            (f.differing, f.extra, f.seams, colours)
        }),
        band: out
            .fidelity
            .as_ref()
            .and_then(|f| f.band)
            .or_else(|| colour_fidelity.and_then(|f| f.band))
            .map(|b| (b.beyond, b.max_distance)),
        decomposition_png: out.picture.clone(),
        diff_png,
    })
}

/// Zero-sized and too large arrays are refused as image files are.
fn check_size(
    name: &std::path::Path,
    width: u32,
    height: u32,
    options: &Options,
) -> Result<(), LtError> {
    if width == 0 || height == 0 {
        return Err(LtError::Empty {
            path: name.to_path_buf(),
            width,
            height,
        });
    }
    if u64::from(width) * u64::from(height) > options.max_pixels {
        return Err(LtError::TooLarge {
            path: name.to_path_buf(),
            width,
            height,
            max_pixels: options.max_pixels,
        });
    }
    Ok(())
}

/// Vectorizes one image; see `layertrace.vectorize` for the Python-facing documentation.
///
/// `kind` is `"bytes"` (`data`: an encoded image file), `"path"` (`path`), `"pixels"`
/// (`data`: `height` rows of `width` pixels of `channels` bytes) or `"mask"` (`data`: one
/// byte per pixel, non-zero = foreground). Returns a dict of str, int, float and bytes.
#[pyfunction]
#[pyo3(signature = (kind, data=None, path=None, width=0, height=0, channels=0, *,
                    model="conic", threshold=None, invert=false, turdsize=0, cover="greedy",
                    fidelity=true, picture_scale=None, max_pixels=400_000_000, colors=None,
                    layout="stack", alpha=false, smooth=None))]
#[allow(clippy::too_many_arguments)]
fn vectorize<'py>(
    py: Python<'py>,
    kind: &str,
    data: Option<&[u8]>,
    path: Option<PathBuf>,
    width: u32,
    height: u32,
    channels: u8,
    model: &str,
    threshold: Option<&str>,
    invert: bool,
    turdsize: u64,
    cover: &str,
    fidelity: bool,
    picture_scale: Option<u32>,
    max_pixels: u64,
    colors: Option<u16>,
    layout: &str,
    alpha: bool,
    smooth: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let bad = |m: String| Error::new_err(m);
    let mut options = Options::default()
        .model(self::model(model).map_err(bad)?)
        .invert(invert)
        .turdsize(turdsize)
        .cover(cover.parse::<Cover>().map_err(|e| bad(e.to_string()))?)
        .fidelity(fidelity)
        .json(true)
        .picture(picture_scale)
        .max_pixels(max_pixels.max(1))
        .alpha(alpha)
        .layout(self::layout(layout).map_err(bad)?);
    if let Some(n) = colors {
        if !(2..=256).contains(&n) {
            return Err(bad(format!("colors {n} is not from 2 to 256")));
        }
        options = options.colors(n);
    }
    if let Some(nu) = smooth {
        options = options.smooth(nu);
    }
    if let Some(t) = threshold {
        options = options.threshold(self::threshold(t).map_err(bad)?);
    }
    if let Some(scale) = picture_scale {
        if !(1..=64).contains(&scale) {
            return Err(bad(format!("picture_scale {scale} is not from 1 to 64")));
        }
    }
    let need = || data.ok_or_else(|| bad(format!("kind '{kind}' needs data")));
    let input = match kind {
        "bytes" => Input::Bytes(need()?),
        "path" => Input::Path(path.ok_or_else(|| bad("kind 'path' needs a path".into()))?),
        "pixels" => Input::Pixels(need()?, width, height, channels),
        "mask" => Input::Mask(need()?, width, height),
        other => return Err(bad(format!("unknown input kind '{other}'"))),
    };
    let made = py
        .allow_threads(|| work(input, &options))
        .map_err(|e| Error::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("svg", made.svg)?;
    d.set_item("json", made.json)?;
    d.set_item("width", made.width)?;
    d.set_item("height", made.height)?;
    d.set_item("threshold", made.threshold)?;
    d.set_item("contours", made.contours)?;
    d.set_item("piece_count", made.pieces)?;
    d.set_item("commands", made.commands)?;
    for key in [
        "fidelity",
        "missing",
        "extra",
        "iou",
        "chromium_tiles",
        "seams",
        "colours",
        "beyond",
        "max_distance",
    ] {
        d.set_item(key, py.None())?;
    }
    if let Some((differing, missing, extra, iou)) = made.fidelity {
        d.set_item("fidelity", differing)?;
        d.set_item("missing", missing)?;
        d.set_item("extra", extra)?;
        d.set_item("iou", iou)?;
    }
    if let Some(t) = made.tiled {
        d.set_item("chromium_tiles", t)?;
    }
    if let Some((beyond, max_distance)) = made.band {
        d.set_item("beyond", beyond)?;
        d.set_item("max_distance", max_distance)?;
    }
    if let Some((differing, extra, seams, colours)) = made.colour_fidelity {
        d.set_item("fidelity", differing)?;
        d.set_item("extra", extra)?;
        d.set_item("seams", seams)?;
        let list = pyo3::types::PyList::empty(py);
        for c in colours {
            let item = PyDict::new(py);
            item.set_item("colour", c.colour)?;
            item.set_item("pixels", c.pixels)?;
            item.set_item("differing", c.differing)?;
            list.append(item)?;
        }
        d.set_item("colours", list)?;
    }
    match made.decomposition_png {
        Some(png) => d.set_item("decomposition_png", PyBytes::new(py, &png))?,
        None => d.set_item("decomposition_png", py.None())?,
    }
    match made.diff_png {
        Some(png) => d.set_item("diff_png", PyBytes::new(py, &png))?,
        None => d.set_item("diff_png", py.None())?,
    }
    Ok(d)
}

/// Recognizes point sets: is there a layer of `model` holding `inliers`, with `above`
/// strictly above and `below` strictly below? Returns the `layertrace-recognition/1` JSON
/// text of `layertrace recognize` (the proof either way, checked exactly).
#[pyfunction]
#[pyo3(signature = (inliers, above, below, model))]
fn recognize(
    py: Python<'_>,
    inliers: Vec<Vec<i64>>,
    above: Vec<Vec<i64>>,
    below: Vec<Vec<i64>>,
    model: &str,
) -> PyResult<String> {
    let model = model
        .parse::<Model>()
        .map_err(|e| Error::new_err(e.to_string()))?;
    let sets = PointSets::new(inliers).with_above(above).with_below(below);
    py.allow_threads(|| recognize_points(&sets, model).map(|r| recognition_json(&r)))
        .map_err(|e| Error::new_err(e.to_string()))
}

/// The native module.
#[pymodule]
fn _layertrace(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(vectorize, m)?)?;
    m.add_function(wrap_pyfunction!(recognize, m)?)?;
    m.add("Error", m.py().get_type::<Error>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
