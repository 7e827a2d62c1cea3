"""layertrace: bitmap to SVG with exact curves, by Digital Level Layers.

Implements *Digital Level Layers for Digital Curve Decomposition and Vectorization*
(L. Provot, Y. Gérard, F. Feschet, IPOL 2014): every border of the shapes is cut into
pieces, each described exactly by a digital line, circle, conic or polynomial layer, and
drawn as one SVG path that resvg renders back to the input's pixels.

>>> import layertrace
>>> result = layertrace.vectorize("glyph.png", model="conic")      # doctest: +SKIP
>>> result.fidelity, len(result.pieces)                             # doctest: +SKIP
(0, 27)

The work runs in Rust with the GIL released: threads vectorize in parallel.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Union

from fractions import Fraction

from ._layertrace import Error, __version__
from ._layertrace import recognize as _recognize
from ._layertrace import vectorize as _vectorize

__all__ = ["vectorize", "Result", "recognize", "Recognition", "Error", "__version__"]


class Result:
    """What :func:`vectorize` made.

    Attributes:
        svg: the SVG document (one path, or one per colour with ``colors``; no path when
            nothing is foreground).
        pieces: every piece of every contour, in order, as a dict: ``contour`` (its
            index in ``decomposition["contours"]``), ``first`` and ``last`` (indices of its
            border pixels in that contour's ``points``), ``origin`` (the point the
            coefficients are relative to), ``coefficients`` (exact integers over the
            model's ``basis``), ``lower`` and ``upper`` (the layer's bounds) and ``kind``
            (line, circle, ellipse, parabola, ...): the content of ``layertrace --json``.
            With ``colors``, each piece also has ``region`` (its index in
            ``decomposition["regions"]``) and ``colour``, and ``contour`` counts within
            the region; the region's points are in its padded mask's coordinates (the
            image's ``(x, y)`` is ``(x + 1, y + 1)``).
        decomposition: the whole JSON document as a dict: format
            ``layertrace-decomposition/2`` (size, threshold, model, basis, and the contours
            with their border points and pieces), or ``layertrace-colour/1`` with
            ``colors`` (the same per colour region, in drawing order).
        json: the same document as text.
        fidelity: pixels that differ between the input's mask (with ``colors``: the
            regions' colours) and the SVG as resvg draws it in crispEdges, or None when
            ``fidelity=False`` was given.
        missing, extra: foreground pixels the drawing misses, and draws in excess. With
            ``colors``, ``missing`` is None and ``extra`` counts pixels painted outside
            every region (transparent in the input).
        iou: intersection over union of the two foregrounds (None with ``colors``).
        chromium_tiles: for images Chromium draws in more than one raster tile (512 pixels
            or more either way; without ``colors``), the pixels that differ when the SVG is
            drawn as Chromium draws the document opened at 1:1, tile by tile, the tiles
            cutting the path at their borders; None otherwise (a page under 512 pixels both
            ways is one tile, drawn as ``fidelity`` counts).
        colours: with ``colors`` and the fidelity check, one dict per colour, most pixels
            first (the drawing order is ``decomposition["regions"]``'s): ``colour`` (``"#rrggbb"``), ``pixels`` and ``differing``; else None.
        beyond, max_distance: with ``smooth`` and the fidelity check, the differing pixels
            farther than NU from the border (0: the guarantee holds) and the largest
            distance of a differing pixel to the border; else None.
        seams: with ``colors`` and the fidelity check, opaque pixels where a contrasting
            background shows through when the SVG is drawn anti-aliased; else None.
        decomposition_png: a picture of the pieces (PNG bytes), in the paper's style;
            None with ``colors``.
        diff_png: the differences (PNG bytes): the mask black on white, missing pixels
            red, extra pixels blue (with ``colors``: the image faded, differing pixels
            marked); None without the fidelity check.
        width, height: the image's size in pixels.
        threshold: the grey threshold used (0 for a boolean mask).
        contours: the number of contours (borders of shapes and holes).
        commands: the number of SVG path commands.
    """

    __slots__ = (
        "svg", "json", "decomposition", "pieces", "fidelity", "missing", "extra", "iou",
        "chromium_tiles",
        "decomposition_png", "diff_png", "width", "height", "threshold", "contours",
        "commands", "colours", "seams", "beyond", "max_distance",
    )

    def __init__(self, made: Dict[str, Any]) -> None:
        self.svg: str = made["svg"]
        self.json: str = made["json"]
        self.decomposition: Dict[str, Any] = json.loads(self.json)
        if "regions" in self.decomposition:
            self.pieces: List[Dict[str, Any]] = [
                {"region": r, "colour": region["colour"], "contour": i, **piece}
                for r, region in enumerate(self.decomposition["regions"])
                for i, contour in enumerate(region["contours"])
                for piece in contour["pieces"]
            ]
        else:
            self.pieces = [
                {"contour": i, **piece}
                for i, contour in enumerate(self.decomposition["contours"])
                for piece in contour["pieces"]
            ]
        self.fidelity: Optional[int] = made["fidelity"]
        self.missing: Optional[int] = made["missing"]
        self.extra: Optional[int] = made["extra"]
        self.iou: Optional[float] = made["iou"]
        self.chromium_tiles: Optional[int] = made["chromium_tiles"]
        self.colours: Optional[List[Dict[str, Any]]] = made["colours"]
        self.seams: Optional[int] = made["seams"]
        self.beyond: Optional[int] = made["beyond"]
        self.max_distance: Optional[float] = made["max_distance"]
        self.decomposition_png: Optional[bytes] = made["decomposition_png"]
        self.diff_png: Optional[bytes] = made["diff_png"]
        self.width: int = made["width"]
        self.height: int = made["height"]
        self.threshold: int = made["threshold"]
        self.contours: int = made["contours"]
        self.commands: int = made["commands"]

    def __repr__(self) -> str:
        return (
            f"<layertrace.Result {self.width}x{self.height}: {len(self.pieces)} pieces, "
            f"{self.contours} contours, fidelity {self.fidelity}, {len(self.svg)} SVG bytes>"
        )


def _pixels(image: Any) -> Dict[str, Any]:
    """A NumPy array or PIL image as raw pixels (or a mask) for the native module."""
    try:  # a PIL image
        from PIL import Image
    except ImportError:
        Image = None
    if Image is not None and isinstance(image, Image.Image):
        if image.mode not in ("L", "RGB", "RGBA"):
            # 1, P, LA, I;16, CMYK, ...: to what the thresholding reads, alpha kept.
            has_alpha = "A" in image.getbands() or "transparency" in image.info
            image = image.convert("RGBA" if has_alpha else ("L" if image.mode in ("1", "I", "I;16", "F") else "RGB"))
        channels = {"L": 1, "RGB": 3, "RGBA": 4}[image.mode]
        width, height = image.size
        return dict(kind="pixels", data=image.tobytes(), width=width, height=height,
                    channels=channels)

    import numpy as np

    array = np.asarray(image)
    if array.dtype == np.bool_:
        if array.ndim != 2:
            raise Error(f"a boolean mask is H×W, not of shape {array.shape}")
        height, width = array.shape
        return dict(kind="mask", data=np.ascontiguousarray(array, dtype=np.uint8).tobytes(),
                    width=width, height=height)
    if array.dtype != np.uint8:
        raise Error(
            f"an image array is uint8 (grey, RGB or RGBA) or bool (a mask), not {array.dtype}"
        )
    if array.ndim == 2:
        height, width = array.shape
        channels = 1
    elif array.ndim == 3 and array.shape[2] in (1, 3, 4):
        height, width, channels = array.shape
    else:
        raise Error(
            f"an image array is H×W (grey), H×W×3 (RGB) or H×W×4 (RGBA), not of shape {array.shape}"
        )
    return dict(kind="pixels", data=np.ascontiguousarray(array).tobytes(), width=width,
                height=height, channels=channels)


def vectorize(
    image: Union[bytes, bytearray, memoryview, str, "os.PathLike[str]", Any],
    model: str = "conic",
    threshold: Union[int, str, None] = None,
    invert: bool = False,
    turdsize: int = 0,
    cover: str = "greedy",
    fidelity: bool = True,
    picture_scale: Optional[int] = None,
    max_pixels: int = 400_000_000,
    colors: Optional[int] = None,
    layout: str = "stack",
    alpha: bool = False,
    smooth: Optional[float] = None,
) -> Result:
    """Vectorizes an image: the SVG, the exact pieces, the fidelity check and pictures.

    Args:
        image: an encoded image file's bytes (PNG, BMP, PNM, TIFF, GIF, JPEG, WebP), the
            path of one (str or os.PathLike), a NumPy array (H×W grey ``uint8``, H×W×3
            RGB, H×W×4 RGBA, or a ``bool`` mask whose True pixels are the foreground,
            used as it is) or a PIL image.
        model: the family of curves: ``"line"``, ``"circle"``, ``"conic"`` or
            ``"poly:D"`` (D = 1..6).
        threshold: foreground is grey < this (0..255), ``"otsu"``, or
            ``"adaptive[:R[:K]]"`` (Sauvola's local threshold); None is 128. Ignored for
            a boolean mask.
        invert: light foreground on a dark background. Ignored for a boolean mask.
        turdsize: drop specks and fill holes whose border encloses at most this many
            pixels (potrace's ``-t``); 0 keeps the mask exactly.
        cover: ``"greedy"`` (the paper's cut) or ``"optimal"`` (fewest pieces).
        fidelity: render the SVG back with resvg and count differing pixels.
        picture_scale: enlargement of ``decomposition_png``, 1..64 (None: about 800
            pixels wide).
        max_pixels: refuse larger images (checked before decoding).
        colors: vectorize in at most this many flat colours (2..256), one path per
            colour: an image with at most that many colours keeps them exactly, others
            are quantized and their anti-aliasing fringes cleaned; fully transparent
            pixels belong to no region. Not with ``threshold``, ``invert``, ``turdsize``,
            ``alpha`` or a boolean mask.
        layout: how ``colors`` draws the regions: ``"stack"`` (each colour's path also
            covers the colours drawn after it: exact, and no seams when anti-aliased) or
            ``"partition"`` (every border between two regions decomposed once and used by
            both: no overlap, for editors; anti-aliased renderers show hairlines along the
            shared borders). Both are exact in crispEdges.
        alpha: the alpha channel is the shape (alpha at least 128), whatever its colour,
            for one-colour icons on transparency such as a white logo.
        smooth: a distance NU in pixels (0 < NU <= 16): pixels within NU of a border
            may change, every other pixel is kept, and the outline is drawn with fewer,
            smoother curves (the command line's ``--smooth``). None: exact.

    Returns:
        A :class:`Result`.

    Raises:
        layertrace.Error: (a ``ValueError``) bad input or options, with the message of
            the ``layertrace`` command line, e.g. ``cannot decode <memory>: ...``.
        FileNotFoundError is not raised: a missing file is a ``layertrace.Error`` too.
    """
    if isinstance(threshold, bool) or not (threshold is None or isinstance(threshold, (int, str))):
        raise Error(f"threshold is an int 0..255, 'otsu' or 'adaptive[:R[:K]]', not {threshold!r}")
    options = dict(
        model=model,
        threshold=None if threshold is None else str(threshold),
        invert=bool(invert),
        turdsize=int(turdsize),
        cover=cover,
        fidelity=bool(fidelity),
        picture_scale=picture_scale,
        max_pixels=int(max_pixels),
        colors=None if colors is None else int(colors),
        layout=str(layout),
        alpha=bool(alpha),
        smooth=None if smooth is None else float(smooth),
    )
    if colors is not None and (isinstance(colors, bool) or not 2 <= int(colors) <= 256):
        raise Error(f"colors is a number of colours from 2 to 256, not {colors!r}")
    if colors is not None and (threshold is not None or invert or turdsize):
        raise Error("colors does not take threshold, invert or turdsize: every colour is kept")
    if turdsize < 0:
        raise Error(f"turdsize is a whole number of pixels, 0 or more, not {turdsize}")
    if isinstance(image, (bytes, bytearray, memoryview)):
        made = _vectorize("bytes", data=bytes(image), **options)
    elif isinstance(image, (str, os.PathLike)):
        made = _vectorize("path", path=os.fspath(image), **options)
    else:
        made = _vectorize(**_pixels(image), **options)
    return Result(made)


class Recognition:
    """What :func:`recognize` found: a layer of the model, or the proof there is none.

    Attributes:
        described: True when a layer holds the inliers with the points above strictly
            above it and the points below strictly below.
        layer: when described, ``{"coefficients": [...], "lower": ..., "upper": ...}``
            (exact Python ints; ``above``/``below`` the nearest outliers' values, when
            there are any) in the points' own coordinates:
            ``lower <= sum(c_i * f_i(p)) <= upper`` for the model's ``basis``.
        witness: when not described, a list of terms ``{"weight": Fraction, "inlier":
            [...], "outlier": [...], "side": "above" | "below"}``: non-negative weights
            summing to 1 that put the origin in the convex hull of the lifted
            differences, so no layer can separate the sets.
        thinnest: True when there were no outliers: ``layer`` is then the thinnest layer
            of the model holding the inliers, and ``thickness`` its exact thickness
            ``(upper - lower) / max |c_i|`` (constant excluded), a ``Fraction``; else
            False and None.
        basis: the names of the basis functions, in coefficient order.
        model, dimension: as given; stats: the recognizer's counters.
        document: the whole ``layertrace-recognition/1`` JSON as a dict; json: its text.
    """

    __slots__ = ("described", "layer", "witness", "thinnest", "thickness", "basis", "model",
                 "dimension", "stats", "document", "json")

    def __init__(self, text: str) -> None:
        self.json: str = text
        self.document: Dict[str, Any] = json.loads(text)
        d = self.document
        self.described: bool = d["result"] == "described"
        self.layer: Optional[Dict[str, Any]] = d.get("layer")
        self.witness: Optional[List[Dict[str, Any]]] = None
        if "witness" in d:
            self.witness = [
                {**term, "weight": Fraction(term["weight"])} for term in d["witness"]["terms"]
            ]
        self.thinnest: bool = bool(d.get("thinnest", False))
        self.thickness: Optional[Fraction] = (
            Fraction(d["thickness"]) if "thickness" in d else None
        )
        self.basis: List[str] = d["basis"]
        self.model: Optional[str] = d["model"]
        self.dimension: int = d["dimension"]
        self.stats: Dict[str, int] = d["stats"]

    def __repr__(self) -> str:
        what = "described" if self.described else f"not described ({len(self.witness or [])} terms)"
        return f"<layertrace.Recognition {self.model}: {what}>"


def _points(points: Any, name: str) -> List[List[int]]:
    """A sequence of integer points (lists, tuples or an N×D NumPy integer array)."""
    if points is None:
        return []
    try:
        import numpy as np
    except ImportError:
        np = None
    if np is not None and isinstance(points, np.ndarray):
        if points.size == 0:
            return []
        if points.ndim != 2 or not np.issubdtype(points.dtype, np.integer):
            raise Error(f"{name}: an N×D array of integers, not {points.dtype} of shape {points.shape}")
        return points.tolist()
    out = []
    for i, p in enumerate(points):
        try:
            coords = list(p)
        except TypeError:
            raise Error(f"{name}[{i}]: a point is a sequence of integers, not {p!r}") from None
        for c in coords:
            if isinstance(c, bool) or not isinstance(c, int) and not (
                np is not None and isinstance(c, np.integer)
            ):
                raise Error(f"{name}[{i}]: coordinates are integers, not {c!r}")
            if not -(2**63) <= int(c) < 2**63:
                raise Error(f"{name}[{i}]: coordinate {c} does not fit 64 bits")
        out.append([int(c) for c in coords])
    return out


def recognize(
    inliers: Any,
    above: Any = None,
    below: Any = None,
    model: str = "conic",
) -> Recognition:
    """Is there a Digital Level Layer of ``model`` holding ``inliers``, with ``above``
    strictly above it and ``below`` strictly below? The command ``layertrace recognize``.

    Args:
        inliers: integer points, 2-D or 3-D (a list of tuples or an N×D integer array).
        above, below: outliers (may be None or empty). With neither, the answer is the
            thinnest layer holding the inliers (``Recognition.thinnest``).
        model: ``"line"``, ``"circle"``, ``"conic"``, ``"poly:D"`` for 2-D points;
            ``"quadric3"``, ``"poly3:D"`` for 3-D points.

    Returns:
        A :class:`Recognition`, whose proof (layer or witness) was checked exactly.

    Raises:
        layertrace.Error: unknown model, points of the wrong dimension, no inliers,
            coordinates that are not integers or too large.

    >>> r = layertrace.recognize([(0, 0), (1, 0), (2, 1), (3, 1)],
    ...                          above=[(0, 1)], below=[(1, -1)], model="line")  # doctest: +SKIP
    >>> r.described, r.layer["coefficients"]                                     # doctest: +SKIP
    (True, [-1, 2, 0])
    """
    return Recognition(
        _recognize(
            _points(inliers, "inliers"), _points(above, "above"), _points(below, "below"),
            str(model),
        )
    )
