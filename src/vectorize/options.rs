//! What [`vectorize`](crate::vectorize) does: the model, the threshold, which outputs,
//! the limits, and where the work runs.

use std::fmt;
use std::sync::Arc;

use crate::bitmap::{default_max_memory, Compat, Threshold};
use crate::decompose::{Cover, WorkBudget};
use crate::export::svg::SvgOptions;
use crate::model::Model;

/// A stage of [`vectorize`](crate::vectorize) whose progress is reported.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Decomposing the contours into pieces.
    Decompose,
    /// Drawing the contours into the SVG.
    Draw,
}

/// Progress of one stage: `done` of `total` contours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// The stage.
    pub stage: Stage,
    /// Contours done so far.
    pub done: u64,
    /// Contours in all.
    pub total: u64,
}

/// How the regions of a colour image are drawn ([`Options::colors`]).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    /// One path per colour, drawn in a fixed order; each covers the pixels of its colour
    /// and of the colours drawn after it (which paint over it), never those of the colours
    /// drawn before it. Exact in crispEdges; no background shows between regions when
    /// anti-aliased.
    #[default]
    Stack,
    /// One path per colour, the regions side by side: every border between two regions
    /// is drawn once and used by both (reversed by one), so no two paths overlap; the
    /// image's edge is drawn along it. Exact in crispEdges; anti-aliased renderers show a
    /// faint hairline along shared borders (each side is blended with the background).
    Partition,
}

impl Layout {
    /// The name on the command line and in the JSON: `stack` or `partition`.
    pub fn name(self) -> &'static str {
        match self {
            Layout::Stack => "stack",
            Layout::Partition => "partition",
        }
    }
}

/// The error of parsing a [`Layout`] name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseLayoutError(String);

impl std::fmt::Display for ParseLayoutError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "unknown layout '{}': expected stack or partition",
            self.0
        )
    }
}

impl std::error::Error for ParseLayoutError {}

impl std::str::FromStr for Layout {
    type Err = ParseLayoutError;

    /// `stack` or `partition`, as [`Layout::name`] writes them.
    ///
    /// ```
    /// use layertrace::Layout;
    /// assert_eq!("partition".parse::<Layout>(), Ok(Layout::Partition));
    /// assert!("side-by-side".parse::<Layout>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Layout, ParseLayoutError> {
        [Layout::Stack, Layout::Partition]
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| ParseLayoutError(s.to_string()))
    }
}

/// A callback told of progress, from any worker thread: once per chunk of 256 contours while
/// decomposing, once per group of 4 096 while drawing. Calls from different threads may
/// arrive out of order.
pub type ProgressFn = Arc<dyn Fn(Progress) + Send + Sync>;

/// Options of [`vectorize`](crate::vectorize), built from [`Options::default`] (the CLI's
/// defaults: conic model, threshold 128, an SVG, nothing else) with the builder methods:
///
/// ```
/// use layertrace::{Model, Options, Threshold};
/// let options = Options::default()
///     .model(Model::Circle)
///     .threshold(Threshold::Otsu)
///     .fill("#1a237e")
///     .fidelity(true);
/// assert_eq!(options.model, Model::Circle);
/// ```
#[non_exhaustive]
#[derive(Clone)]
pub struct Options {
    /// The family of curves. Default [`Model::Conic`].
    pub model: Model,
    /// How grey levels become foreground; `None` is `Fixed(128)`, or Otsu with
    /// [`Compat::Ipol`]. Ignored for a [`Mask`](crate::Mask) input.
    pub threshold: Option<Threshold>,
    /// Light foreground on a dark background. Ignored for a mask input.
    pub invert: bool,
    /// Drop specks and fill holes whose border encloses at most this many pixels, after
    /// thresholding (potrace's turdsize, see [`Mask::clean`](crate::Mask::clean)); also
    /// applied to a mask input. Default 0: the mask is kept exactly. Meant for layertrace's
    /// own convention (8-connected objects, 4-connected holes); with [`Compat::Ipol`]'s
    /// 4-connected objects a dropped border may not be a whole contour.
    pub turdsize: u64,
    /// Whose conventions: layertrace's, or the IPOL reference program's (grey levels,
    /// 4-connected objects, crack-following borders, outliers of any colour).
    pub compat: Compat,
    /// The SVG's options; `None` draws no SVG (and checks no fidelity).
    pub svg: Option<SvgOptions>,
    /// Vectorize in colour: regions of at most this many flat colours (1 to 256; see
    /// [`colour_regions`](crate::colour_regions)), one path per colour, instead of one
    /// thresholded mask. `None` (the default): binary. Not for a mask input.
    pub colors: Option<u16>,
    /// How the colour regions are drawn. Default [`Layout::Stack`].
    pub layout: Layout,
    /// Binary, with the alpha channel as the mask (alpha at least
    /// [`OPAQUE_ALPHA`](crate::OPAQUE_ALPHA)) instead of thresholded grey levels: for
    /// one-colour icons on transparency, whatever their colour. Not with `colors`.
    pub alpha: bool,
    /// Render the SVG back with resvg and compare it with the mask.
    pub fidelity: bool,
    /// With `fidelity`, also draw the SVG as Chromium draws the document, tile by tile
    /// ([`Fidelity::tiled`](crate::Fidelity::tiled)). Default `true`; a caller that only
    /// wants the plain rendering (`--diff` without `--report`) saves those renders.
    pub tile_fidelity: bool,
    /// Write the decomposition's JSON text.
    pub json: bool,
    /// Draw the decomposition picture at this enlargement (`Some(None)`: about 800 pixels
    /// wide); `None` draws none.
    pub picture: Option<Option<u32>>,
    /// Refuse images with more pixels than this (before decoding). Default 400 million.
    pub max_pixels: u64,
    /// Refuse inputs whose work would need more bytes than this (before decoding, and again
    /// after tracing). Default [`default_max_memory`].
    pub max_memory: u64,
    /// The work budget of each piece's recognition.
    pub budget: WorkBudget,
    /// How each contour is cut into pieces. Default [`Cover::Greedy`] (the paper's).
    pub cover: Cover,
    /// Draw smooth curves within this many pixels of the border instead of the exact
    /// outline (see [`smooth_svg_document`](crate::smooth_svg_document)): every pixel the
    /// SVG renders differently lies within ν of the border. `None` (default): exact.
    /// Values outside `0 < ν <= MAX_BAND` are refused by [`vectorize`](crate::vectorize);
    /// not with [`Compat::Ipol`].
    pub smooth: Option<f64>,
    /// Run on this thread pool instead of rayon's global one.
    pub pool: Option<Arc<rayon::ThreadPool>>,
    /// Told of the progress of the long stages.
    pub progress: Option<ProgressFn>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            model: Model::Conic,
            threshold: None,
            invert: false,
            turdsize: 0,
            compat: Compat::Default,
            svg: Some(SvgOptions::default()),
            colors: None,
            layout: Layout::Stack,
            alpha: false,
            fidelity: false,
            tile_fidelity: true,
            json: false,
            picture: None,
            max_pixels: 400_000_000,
            max_memory: default_max_memory(),
            budget: WorkBudget::default(),
            cover: Cover::default(),
            smooth: None,
            pool: None,
            progress: None,
        }
    }
}

impl fmt::Debug for Options {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Options")
            .field("model", &self.model)
            .field("threshold", &self.threshold)
            .field("invert", &self.invert)
            .field("turdsize", &self.turdsize)
            .field("compat", &self.compat)
            .field("svg", &self.svg)
            .field("colors", &self.colors)
            .field("layout", &self.layout)
            .field("alpha", &self.alpha)
            .field("fidelity", &self.fidelity)
            .field("tile_fidelity", &self.tile_fidelity)
            .field("json", &self.json)
            .field("picture", &self.picture)
            .field("max_pixels", &self.max_pixels)
            .field("max_memory", &self.max_memory)
            .field("budget", &self.budget)
            .field("cover", &self.cover)
            .field("smooth", &self.smooth)
            .field("pool", &self.pool.as_ref().map(|p| p.current_num_threads()))
            .field("progress", &self.progress.is_some())
            .finish()
    }
}

impl Options {
    /// The family of curves.
    pub fn model(mut self, model: Model) -> Options {
        self.model = model;
        self
    }

    /// How grey levels become foreground.
    pub fn threshold(mut self, threshold: Threshold) -> Options {
        self.threshold = Some(threshold);
        self
    }

    /// Light foreground on a dark background.
    pub fn invert(mut self, invert: bool) -> Options {
        self.invert = invert;
        self
    }

    /// Drop specks and holes of at most `turdsize` pixels.
    pub fn turdsize(mut self, turdsize: u64) -> Options {
        self.turdsize = turdsize;
        self
    }

    /// Whose conventions (see [`Compat`]).
    pub fn compat(mut self, compat: Compat) -> Options {
        self.compat = compat;
        self
    }

    /// The SVG's options (drawing an SVG).
    pub fn svg(mut self, svg: SvgOptions) -> Options {
        self.svg = Some(svg);
        self
    }

    /// No SVG (only the decomposition, and the JSON or the picture if asked).
    pub fn no_svg(mut self) -> Options {
        self.svg = None;
        self
    }

    /// The SVG's fill colour (drawing an SVG).
    pub fn fill(mut self, fill: impl Into<String>) -> Options {
        self.svg.get_or_insert_with(SvgOptions::default).fill = fill.into();
        self
    }

    /// The SVG's coordinate grid, 1/2^`grid` px (drawing an SVG).
    pub fn grid(mut self, grid: u8) -> Options {
        self.svg.get_or_insert_with(SvgOptions::default).grid = grid;
        self
    }

    /// Vectorize in colour with at most `colors` colours (see [`Options::colors`]).
    pub fn colors(mut self, colors: u16) -> Options {
        self.colors = Some(colors);
        self
    }

    /// How colour regions are drawn.
    pub fn layout(mut self, layout: Layout) -> Options {
        self.layout = layout;
        self
    }

    /// The alpha channel as the mask (see [`Options::alpha`]).
    pub fn alpha(mut self, alpha: bool) -> Options {
        self.alpha = alpha;
        self
    }

    /// Render the SVG back and compare it with the mask.
    pub fn fidelity(mut self, fidelity: bool) -> Options {
        self.fidelity = fidelity;
        self
    }

    /// With the fidelity check, also draw the SVG in Chromium's tiles (see
    /// [`Options::tile_fidelity`]).
    pub fn tile_fidelity(mut self, tile_fidelity: bool) -> Options {
        self.tile_fidelity = tile_fidelity;
        self
    }

    /// Write the decomposition's JSON text.
    pub fn json(mut self, json: bool) -> Options {
        self.json = json;
        self
    }

    /// Draw the decomposition picture (`None`: about 800 pixels wide).
    pub fn picture(mut self, scale: Option<u32>) -> Options {
        self.picture = Some(scale);
        self
    }

    /// Refuse images with more pixels than this.
    pub fn max_pixels(mut self, max_pixels: u64) -> Options {
        self.max_pixels = max_pixels;
        self
    }

    /// Refuse inputs whose work would need more bytes than this.
    pub fn max_memory(mut self, max_memory: u64) -> Options {
        self.max_memory = max_memory;
        self
    }

    /// The work budget of each piece's recognition.
    pub fn budget(mut self, budget: WorkBudget) -> Options {
        self.budget = budget;
        self
    }

    /// How each contour is cut into pieces (see [`Cover`]).
    pub fn cover(mut self, cover: Cover) -> Options {
        self.cover = cover;
        self
    }

    /// Smooth curves within `nu` pixels of the border (see [`Options::smooth`]).
    pub fn smooth(mut self, nu: f64) -> Options {
        self.smooth = Some(nu);
        self
    }

    /// Run on this thread pool.
    pub fn pool(mut self, pool: Arc<rayon::ThreadPool>) -> Options {
        self.pool = Some(pool);
        self
    }

    /// Tell `progress` how the long stages advance.
    pub fn progress(mut self, progress: ProgressFn) -> Options {
        self.progress = Some(progress);
        self
    }

    /// The threshold used on grey levels: the given one, else 128, or Otsu's with
    /// [`Compat::Ipol`].
    pub fn effective_threshold(&self) -> Threshold {
        self.threshold.unwrap_or(match self.compat {
            Compat::Ipol => Threshold::Otsu,
            _ => Threshold::Fixed(128),
        })
    }
}
