//! Colour images: decoding to RGBA, and turning the pixels into regions of flat colour.
//!
//! [`colour_regions`] gives every pixel a region (an index into a palette of at most `N`
//! colours) or none (mostly transparent pixels, alpha below [`OPAQUE_ALPHA`]):
//! * an image with at most `N` distinct opaque colours keeps them exactly;
//! * any other is quantized ([`quantize`](self::quantize)) and its anti-aliasing fringes
//!   cleaned ([`fringe`](self::fringe)).
//!
//! [`alpha_mask`] is the binary mask of the opaque pixels (`--alpha`).

mod fringe;
mod quantize;

use rustc_hash::FxHashMap as HashMap;
use std::fmt;
use std::io::{Cursor, Read};
use std::path::Path;

use image::{ImageReader, Limits, RgbaImage};

use super::input::{display_name, open, Input};
use super::load::{check_dimensions, decode_error};
use super::mask::Mask;
use crate::error::Error;

/// Pixels with an alpha below this belong to no region (and are background for
/// [`alpha_mask`]): fully transparent ones, and the outer half of an anti-aliased edge
/// against transparency, so that opaque shapes are not fattened by half a pixel.
pub const OPAQUE_ALPHA: u8 = 128;

/// The most colours [`colour_regions`] makes (`--colors` 1 to 256).
pub const MAX_COLOURS: u16 = 256;

/// An opaque sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Colour {
    /// Red, 0 to 255.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Colour {
    /// The colour of these three channels.
    pub fn new(r: u8, g: u8, b: u8) -> Colour {
        Colour { r, g, b }
    }

    /// The three channels as an array.
    pub fn rgb(self) -> [u8; 3] {
        [self.r, self.g, self.b]
    }

    /// Euclidean distance in RGB (0 to 255 per channel).
    pub fn distance(self, other: Colour) -> f64 {
        f64::from(self.distance2(other)).sqrt()
    }

    /// Squared Euclidean distance in RGB.
    pub(crate) fn distance2(self, other: Colour) -> u32 {
        let d = |a: u8, b: u8| (i32::from(a) - i32::from(b)).unsigned_abs().pow(2);
        d(self.r, other.r) + d(self.g, other.g) + d(self.b, other.b)
    }
}

impl fmt::Display for Colour {
    /// `#rrggbb`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

/// An image of regions: every pixel has the index of its colour in the palette, or none.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColourImage {
    width: u32,
    height: u32,
    /// Row-major; [`ColourImage::NONE`] for a pixel of no region.
    index: Vec<u16>,
    palette: Vec<Colour>,
}

impl ColourImage {
    /// The index of a pixel in no region.
    const NONE: u16 = u16::MAX;

    /// An image from its pixels' palette indices (`None`: no region), row-major, or `None`
    /// when the sizes disagree or an index is outside the palette.
    pub fn new(
        width: u32,
        height: u32,
        pixels: &[Option<u16>],
        palette: Vec<Colour>,
    ) -> Option<ColourImage> {
        let n = usize::try_from(u64::from(width) * u64::from(height)).ok()?;
        if pixels.len() != n || palette.len() > usize::from(MAX_COLOURS) {
            return None;
        }
        let mut index = Vec::with_capacity(n);
        for p in pixels {
            match *p {
                Some(k) if usize::from(k) < palette.len() => index.push(k),
                Some(_) => return None,
                None => index.push(Self::NONE),
            }
        }
        Some(ColourImage {
            width,
            height,
            index,
            palette,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colours, by index.
    pub fn palette(&self) -> &[Colour] {
        &self.palette
    }

    /// The palette index of pixel `(x, y)`; `None` outside the image or for a pixel of no
    /// region.
    pub fn get(&self, x: i64, y: i64) -> Option<usize> {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return None;
        }
        let i = y as usize * self.width as usize + x as usize;
        match self.index[i] {
            Self::NONE => None,
            k => Some(usize::from(k)),
        }
    }

    /// True when every pixel within `radius` of `(x, y)` (a square of side `2 radius + 1`)
    /// belongs to some region or lies outside the image: no pixel of no region is near.
    /// Where this holds, an anti-aliased drawing of the regions must be opaque, so a
    /// see-through pixel there is a seam.
    /// A negative `radius` is taken as 0.
    pub fn regions_around(&self, x: i64, y: i64, radius: i64) -> bool {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let r = radius.max(0);
        (-r..=r).all(|dy| {
            (-r..=r).all(|dx| {
                // Saturated coordinates are outside the image, as the true ones are.
                let (u, v) = (x.saturating_add(dx), y.saturating_add(dy));
                u < 0 || v < 0 || u >= w || v >= h || self.get(u, v).is_some()
            })
        })
    }

    /// The colour of pixel `(x, y)`, if it has one.
    pub fn colour(&self, x: i64, y: i64) -> Option<Colour> {
        self.get(x, y).map(|k| self.palette[k])
    }

    /// Pixels of each colour, by index.
    pub fn counts(&self) -> Vec<u64> {
        let mut counts = vec![0u64; self.palette.len()];
        for &k in &self.index {
            if k != Self::NONE {
                counts[usize::from(k)] += 1;
            }
        }
        counts
    }

    /// The mask of the pixels whose palette index passes `keep`.
    pub fn mask_where(&self, mut keep: impl FnMut(usize) -> bool) -> Mask {
        let mut mask = Mask::new(self.width, self.height);
        for (i, &k) in self.index.iter().enumerate() {
            if k != Self::NONE && keep(usize::from(k)) {
                mask.set_index(i);
            }
        }
        mask
    }

    /// The pixels as RGBA: each region's colour, opaque; no region transparent black.
    pub fn to_rgba(&self) -> RgbaImage {
        RgbaImage::from_fn(self.width, self.height, |x, y| {
            match self.colour(i64::from(x), i64::from(y)) {
                Some(c) => image::Rgba([c.r, c.g, c.b, 255]),
                None => image::Rgba([0, 0, 0, 0]),
            }
        })
    }
}

/// How [`colour_regions`] made its regions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Regions {
    /// The regions.
    pub image: ColourImage,
    /// Whether the colours are the input's own (at most `N` distinct colours), not
    /// quantized.
    pub exact: bool,
    /// Pixels of anti-aliasing fringes moved into a neighbouring region (0 when exact).
    pub fringe: u64,
}

/// The regions of at most `max_colours` colours (1 to [`MAX_COLOURS`]; other values act as
/// the nearest of these) of an RGBA image.
///
/// Pixels with alpha below [`OPAQUE_ALPHA`] belong to no region; the others keep their
/// RGB, whatever their alpha. With at most `max_colours` distinct colours among them these
/// are the palette, exactly (ordered by decreasing pixel count, then by value). Otherwise
/// the colours are quantized (NeuQuant's palette refined by a few
/// k-means steps), each pixel takes the nearest palette colour, and the thin fringes of
/// in-between colour along edges between two regions join the nearer of the two
/// (`fringe::clean`); colours left without pixels are dropped.
///
/// ```
/// use layertrace::colour_regions;
/// // Two flat colours: kept exactly.
/// let img = image::RgbaImage::from_fn(8, 4, |x, _| {
///     if x < 4 { image::Rgba([200, 30, 30, 255]) } else { image::Rgba([30, 30, 200, 255]) }
/// });
/// let r = colour_regions(&img, 4);
/// assert!(r.exact);
/// assert_eq!(r.image.palette().len(), 2);
/// assert_ne!(r.image.get(0, 0), r.image.get(7, 0));
/// ```
pub fn colour_regions(rgba: &RgbaImage, max_colours: u16) -> Regions {
    let max_colours = max_colours.clamp(1, MAX_COLOURS);
    let (width, height) = rgba.dimensions();
    // Counted run by run of equal colours (flat regions make long runs): one hash lookup
    // per run, not per pixel.
    let mut histogram: HashMap<Colour, u64> = HashMap::default();
    let mut run: Option<(Colour, u64)> = None;
    for p in rgba.pixels() {
        if p[3] >= OPAQUE_ALPHA {
            let c = Colour::new(p[0], p[1], p[2]);
            match &mut run {
                Some((r, k)) if *r == c => *k += 1,
                _ => {
                    if let Some((r, k)) = run.replace((c, 1)) {
                        *histogram.entry(r).or_default() += k;
                    }
                }
            }
        }
    }
    if let Some((r, k)) = run {
        *histogram.entry(r).or_default() += k;
    }
    let exact = histogram.len() <= usize::from(max_colours);
    let mut palette: Vec<(Colour, u64)> = if exact {
        histogram.iter().map(|(&c, &n)| (c, n)).collect()
    } else {
        quantize::palette(&histogram, usize::from(max_colours))
            .into_iter()
            .map(|c| (c, 0))
            .collect()
    };
    if exact {
        palette.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    }
    let colours: Vec<Colour> = palette.iter().map(|p| p.0).collect();
    // Every distinct colour's palette index, found once.
    let lookup: HashMap<Colour, u16> = histogram
        .keys()
        .map(|&c| (c, quantize::nearest(&colours, c) as u16))
        .collect();
    let mut last: Option<(Colour, u16)> = None;
    let mut index: Vec<u16> = rgba
        .pixels()
        .map(|p| {
            if p[3] >= OPAQUE_ALPHA {
                let c = Colour::new(p[0], p[1], p[2]);
                match last {
                    Some((l, i)) if l == c => i,
                    _ => {
                        let i = lookup[&c];
                        last = Some((c, i));
                        i
                    }
                }
            } else {
                ColourImage::NONE
            }
        })
        .collect();
    let fringe = if exact {
        0
    } else {
        let original: Vec<Colour> = rgba
            .pixels()
            .map(|p| Colour::new(p[0], p[1], p[2]))
            .collect();
        fringe::clean(&mut index, &original, width, height, &colours)
    };
    let image = compact(width, height, index, colours);
    Regions {
        image,
        exact,
        fringe,
    }
}

/// The image with the palette colours that no pixel uses dropped, and the others
/// renumbered by decreasing pixel count (then by value): a stable order.
fn compact(width: u32, height: u32, mut index: Vec<u16>, colours: Vec<Colour>) -> ColourImage {
    let mut counts = vec![0u64; colours.len()];
    for &k in &index {
        if k != ColourImage::NONE {
            counts[usize::from(k)] += 1;
        }
    }
    let mut used: Vec<usize> = (0..colours.len()).filter(|&k| counts[k] > 0).collect();
    used.sort_by(|&a, &b| counts[b].cmp(&counts[a]).then(colours[a].cmp(&colours[b])));
    let mut renumber = vec![ColourImage::NONE; colours.len()];
    for (new, &old) in used.iter().enumerate() {
        renumber[old] = new as u16;
    }
    for k in &mut index {
        if *k != ColourImage::NONE {
            *k = renumber[usize::from(*k)];
        }
    }
    ColourImage {
        width,
        height,
        index,
        palette: used.iter().map(|&k| colours[k]).collect(),
    }
}

/// The mask of the pixels with alpha at least [`OPAQUE_ALPHA`] (`--alpha`: the alpha
/// channel as the foreground of a one-colour icon, whatever its colour).
///
/// ```
/// use layertrace::{alpha_mask, OPAQUE_ALPHA};
/// // A white disc on transparency: the shape is where alpha is opaque enough.
/// let icon = image::RgbaImage::from_fn(9, 9, |x, y| {
///     let inside = (x as i32 - 4).pow(2) + (y as i32 - 4).pow(2) <= 9;
///     image::Rgba([255, 255, 255, if inside { 255 } else { 0 }])
/// });
/// let mask = alpha_mask(&icon);
/// assert!(mask.get(4, 4) && !mask.get(0, 0));
/// assert!(OPAQUE_ALPHA > 0);
/// ```
pub fn alpha_mask(rgba: &RgbaImage) -> Mask {
    let mut mask = Mask::new(rgba.width(), rgba.height());
    for (i, p) in rgba.pixels().enumerate() {
        if p[3] >= OPAQUE_ALPHA {
            mask.set_index(i);
        }
    }
    mask
}

/// Whether any pixel of the image is less than opaque.
///
/// ```
/// use layertrace::has_transparency;
/// let mut img = image::RgbaImage::from_pixel(4, 4, image::Rgba([0, 0, 0, 255]));
/// assert!(!has_transparency(&img));
/// img.put_pixel(1, 1, image::Rgba([0, 0, 0, 200]));
/// assert!(has_transparency(&img));
/// ```
pub fn has_transparency(rgba: &RgbaImage) -> bool {
    rgba.pixels().any(|p| p[3] < 255)
}

/// Reads and decodes the image at `path` (`-`: standard input) as 8-bit RGBA, refusing it
/// before decoding when it has more than `max_pixels` pixels or its decoding would need
/// more than `max_memory` bytes.
///
/// ```
/// use layertrace::load_rgba;
/// use std::path::Path;
/// let logo = load_rgba(Path::new("samples/colour/colour_logo_crisp.png"), u64::MAX, u64::MAX)?;
/// assert!(logo.width() > 0 && logo.height() > 0);
/// // A pixel limit below the image's size refuses it before decoding.
/// assert!(load_rgba(Path::new("samples/colour/colour_logo_crisp.png"), 10, u64::MAX).is_err());
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn load_rgba(path: &Path, max_pixels: u64, max_memory: u64) -> Result<RgbaImage, Error> {
    let name = display_name(path);
    let bytes = match open(path, &name, max_pixels, max_memory)? {
        Input::Bytes(bytes) => bytes,
        Input::File(mut file) => {
            let mut bytes = Vec::new();
            file.read_to_end(&mut bytes).map_err(|source| Error::Read {
                path: name.clone(),
                source,
            })?;
            bytes
        }
    };
    decode_rgba(&bytes, &name, max_pixels, max_memory)
}

/// Decodes an encoded image held in memory as 8-bit RGBA (errors name it `name`).
///
/// ```
/// use layertrace::decode_rgba;
/// use std::path::Path;
/// let bytes = std::fs::read("samples/colour/colour_logo_crisp.png").unwrap();
/// let rgba = decode_rgba(&bytes, Path::new("logo.png"), u64::MAX, u64::MAX)?;
/// assert!(rgba.width() > 0);
/// // Errors name the input as given.
/// let e = decode_rgba(b"not an image", Path::new("bad.png"), u64::MAX, u64::MAX).unwrap_err();
/// assert!(e.to_string().contains("bad.png"));
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn decode_rgba(
    bytes: &[u8],
    name: &Path,
    max_pixels: u64,
    max_memory: u64,
) -> Result<RgbaImage, Error> {
    if bytes.is_empty() {
        return Err(Error::NoData {
            path: name.to_path_buf(),
        });
    }
    let decode_err = |source: image::ImageError| Error::Decode {
        path: name.to_path_buf(),
        source,
    };
    let mut reader = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|source| Error::Read {
            path: name.to_path_buf(),
            source,
        })?;
    let format = reader.format();
    let mut limits = Limits::default();
    limits.max_alloc = Some(max_memory);
    reader.limits(limits);
    let (width, height) = reader.into_dimensions().map_err(decode_err)?;
    check_dimensions(name, width, height, max_pixels)?;
    // The decoded image, its RGBA copy and the region indices.
    let needed = u64::from(width) * u64::from(height) * (8 + 4 + 2) + bytes.len() as u64;
    if needed > max_memory {
        return Err(Error::NeedsMemory {
            path: name.to_path_buf(),
            needed,
            limit: max_memory,
        });
    }
    let mut reader = ImageReader::new(Cursor::new(bytes));
    if let Some(f) = format {
        reader.set_format(f);
    } else {
        return Err(decode_error(
            name,
            image::error::ImageFormatHint::Unknown,
            "unknown image format",
        ));
    }
    let mut limits = Limits::default();
    limits.max_alloc = Some(max_memory);
    reader.limits(limits);
    Ok(reader.decode().map_err(decode_err)?.to_rgba8())
}

#[cfg(test)]
mod tests;
