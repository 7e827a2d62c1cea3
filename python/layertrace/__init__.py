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

from ._layertrace import Error, __version__
from ._layertrace import vectorize as _vectorize

__all__ = ["vectorize", "Result", "Error", "__version__"]


class Result:
    """What :func:`vectorize` made.

    Attributes:
        svg: the SVG document (one path; empty when nothing is foreground).
        pieces: every piece of every contour, in order, as a dict: ``contour`` (its
            index in ``decomposition["contours"]``), ``first`` and ``last`` (indices of its
            border pixels in that contour's ``points``), ``origin`` (the point the
            coefficients are relative to), ``coefficients`` (exact integers over the
            model's ``basis``), ``lower`` and ``upper`` (the layer's bounds) and ``kind``
            (line, circle, ellipse, parabola, ...): the content of ``layertrace --json``.
        decomposition: the whole JSON document (format ``layertrace-decomposition/2``)
            as a dict: size, threshold, model, basis, and the contours with their border
            points and pieces.
        json: the same document as text.
        fidelity: pixels that differ between the input's mask and the SVG as resvg draws
            it (``missing + extra``), or None when ``fidelity=False`` was given.
        missing, extra: foreground pixels the drawing misses, and draws in excess.
        iou: intersection over union of the two foregrounds.
        decomposition_png: a picture of the pieces (PNG bytes), in the paper's style.
        diff_png: the differences (PNG bytes): the mask black on white, missing pixels
            red, extra pixels blue; None without the fidelity check.
        width, height: the image's size in pixels.
        threshold: the grey threshold used (0 for a boolean mask).
        contours: the number of contours (borders of shapes and holes).
        commands: the number of SVG path commands.
    """

    __slots__ = (
        "svg", "json", "decomposition", "pieces", "fidelity", "missing", "extra", "iou",
        "decomposition_png", "diff_png", "width", "height", "threshold", "contours",
        "commands",
    )

    def __init__(self, made: Dict[str, Any]) -> None:
        self.svg: str = made["svg"]
        self.json: str = made["json"]
        self.decomposition: Dict[str, Any] = json.loads(self.json)
        self.pieces: List[Dict[str, Any]] = [
            {"contour": i, **piece}
            for i, contour in enumerate(self.decomposition["contours"])
            for piece in contour["pieces"]
        ]
        self.fidelity: Optional[int] = made["fidelity"]
        self.missing: Optional[int] = made["missing"]
        self.extra: Optional[int] = made["extra"]
        self.iou: Optional[float] = made["iou"]
        self.decomposition_png: bytes = made["decomposition_png"]
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
    )
    if turdsize < 0:
        raise Error(f"turdsize is a whole number of pixels, 0 or more, not {turdsize}")
    if isinstance(image, (bytes, bytearray, memoryview)):
        made = _vectorize("bytes", data=bytes(image), **options)
    elif isinstance(image, (str, os.PathLike)):
        made = _vectorize("path", path=os.fspath(image), **options)
    else:
        made = _vectorize(**_pixels(image), **options)
    return Result(made)
