"""Tests of the Python package: every kind of input, the results, and bad input."""

import io
import json
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import layertrace

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
GLYPH = SAMPLES / "glyph_g_liberationserif_cap120.png"


def disc_mask(size=64, radius=20.0):
    y, x = np.mgrid[0:size, 0:size]
    c = size / 2
    return (x + 0.5 - c) ** 2 + (y + 0.5 - c) ** 2 <= radius**2


def test_path_matches_the_command_lines_figures():
    r = layertrace.vectorize(GLYPH)
    assert r.svg.startswith("<svg")
    assert (r.width, r.height) == (110, 163)
    assert r.fidelity == 0 and r.missing == 0 and r.extra == 0 and r.iou == 1.0
    # Chromium draws pages under 512 px both ways as one tile: no tile count.
    assert r.chromium_tiles is None
    # The same 27 pieces as `layertrace samples/glyph_g... --json` (conic, greedy).
    assert len(r.pieces) == 27
    assert r.contours == 3
    assert r.decomposition["format"] == "layertrace-decomposition/2"
    assert r.decomposition["model"] == "conic"
    first = r.pieces[0]
    assert first["contour"] == 0
    assert set(first) >= {"first", "last", "origin", "coefficients", "lower", "upper", "kind"}
    assert len(first["coefficients"]) == len(r.decomposition["basis"]) == 6
    assert r.decomposition_png.startswith(b"\x89PNG")
    assert r.diff_png.startswith(b"\x89PNG")
    assert "27 pieces" in repr(r)


def test_bytes_str_path_and_pathlike_agree():
    by_path = layertrace.vectorize(GLYPH)
    by_str = layertrace.vectorize(str(GLYPH))
    by_bytes = layertrace.vectorize(GLYPH.read_bytes())
    by_view = layertrace.vectorize(memoryview(GLYPH.read_bytes()))
    assert by_path.svg == by_str.svg == by_bytes.svg == by_view.svg
    assert by_path.pieces == by_bytes.pieces


def test_numpy_round_trip_of_a_mask():
    mask = disc_mask()
    r = layertrace.vectorize(mask, model="circle")
    assert r.fidelity == 0
    assert r.threshold == 0
    assert r.contours == 1
    # A digital disc is one circle piece or a few; every piece is a circle or a line.
    assert 1 <= len(r.pieces) <= 8
    assert all(p["kind"] in ("circle", "line") for p in r.pieces), r.pieces
    # Render the SVG's diff picture back: no red or blue pixel, the mask in black.
    diff = np.asarray(Image.open(io.BytesIO(r.diff_png)).convert("RGB"))
    assert diff.shape == (64, 64, 3)
    black = (diff == 0).all(axis=2)
    assert (black == mask).all()
    assert ((diff == 255).all(axis=2) | black).all()


def test_numpy_grey_rgb_and_rgba_agree_with_the_file():
    grey = np.asarray(Image.open(GLYPH).convert("L"))
    expected = layertrace.vectorize(GLYPH)
    for array in (
        grey,
        np.stack([grey] * 3, axis=2),
        np.dstack([np.stack([grey] * 3, axis=2), np.full(grey.shape, 255, np.uint8)]),
        grey[:, :, None],
    ):
        r = layertrace.vectorize(array)
        assert r.fidelity == 0
        assert r.svg == expected.svg, array.shape
    # A non-contiguous view (every other column) is taken as it looks.
    half = layertrace.vectorize(grey[:, ::2])
    assert half.width == 55 and half.fidelity == 0


def test_threshold_and_invert_on_arrays():
    ramp = np.tile(np.arange(256, dtype=np.uint8), (8, 1))  # dark on the left
    assert layertrace.vectorize(ramp, threshold=100).pieces  # 100 dark columns
    r = layertrace.vectorize(ramp, threshold=100, invert=True)
    assert r.fidelity == 0
    assert layertrace.vectorize(ramp, threshold="otsu").threshold > 0
    assert layertrace.vectorize(ramp, threshold="adaptive:4:20").fidelity == 0
    blank = np.full((10, 10), 255, np.uint8)
    empty = layertrace.vectorize(blank)
    assert empty.pieces == [] and empty.fidelity == 0


def test_pil_images():
    img = Image.open(GLYPH)
    expected = layertrace.vectorize(GLYPH).svg
    for mode in ("L", "RGB", "RGBA", "1", "P", "LA"):
        assert layertrace.vectorize(img.convert(mode)).svg == expected, mode


def test_options_reach_the_library():
    line = layertrace.vectorize(GLYPH, model="line")
    assert line.decomposition["model"] == "line"
    assert {p["kind"] for p in line.pieces} <= {"line", "degenerate"}  # and degenerate pieces
    optimal = layertrace.vectorize(GLYPH, model="line", cover="optimal")
    assert len(optimal.pieces) <= len(line.pieces)
    assert layertrace.vectorize(GLYPH, model="poly:2").fidelity == 0
    unchecked = layertrace.vectorize(GLYPH, fidelity=False)
    assert unchecked.fidelity is None and unchecked.diff_png is None
    big = layertrace.vectorize(GLYPH, picture_scale=2)
    assert Image.open(io.BytesIO(big.decomposition_png)).size[0] >= 220
    speck = np.zeros((20, 20), bool)
    speck[3, 3] = True
    speck[8:16, 8:16] = True
    assert layertrace.vectorize(speck, turdsize=2).contours == 1
    assert layertrace.vectorize(speck).contours == 2


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: layertrace.vectorize(b"not an image"), "cannot decode <memory>"),
        (lambda: layertrace.vectorize(b""), "<memory>"),
        (lambda: layertrace.vectorize(GLYPH.read_bytes()[:300]), "truncated"),
        (lambda: layertrace.vectorize("/nonexistent/x.png"), "cannot read /nonexistent/x.png"),
        (lambda: layertrace.vectorize(GLYPH, model="quadric3"), "3-D point sets"),
        (lambda: layertrace.vectorize(GLYPH, model="spline"), "unknown model 'spline'"),
        (lambda: layertrace.vectorize(GLYPH, threshold=300), "neither a number 0..=255"),
        (lambda: layertrace.vectorize(GLYPH, threshold="adaptive:0"), "R (the window radius)"),
        (lambda: layertrace.vectorize(GLYPH, cover="best"), "best"),
        (lambda: layertrace.vectorize(GLYPH, max_pixels=100), "more than the limit of 100"),
        (lambda: layertrace.vectorize(np.zeros((0, 5), np.uint8)), "image is empty (5x0"),
        (lambda: layertrace.vectorize(np.zeros((4, 4, 2), np.uint8)), "H×W×3 (RGB)"),
        (lambda: layertrace.vectorize(np.zeros((4, 4), np.float32)), "not float32"),
        (lambda: layertrace.vectorize(np.zeros((4, 4, 3), bool)), "boolean mask is H×W"),
        (lambda: layertrace.vectorize(disc_mask(), max_pixels=10), "<mask>: image is 64x64"),
        (lambda: layertrace.vectorize(GLYPH, picture_scale=0), "picture_scale 0"),
        (lambda: layertrace.vectorize(GLYPH, turdsize=-1), "turdsize"),
    ],
)
def test_bad_input_raises_the_command_lines_message(call, message):
    with pytest.raises(layertrace.Error) as info:
        call()
    assert message in str(info.value)
    assert isinstance(info.value, ValueError)
    assert "\n" not in str(info.value)


def test_the_gil_is_released():
    # While one thread vectorizes a large image, another keeps running Python code.
    big = np.zeros((1500, 1500), bool)
    y, x = np.mgrid[0:1500, 0:1500]
    big[((x // 7 + y // 11) % 3 == 0) & ((x - 750) ** 2 + (y - 750) ** 2 < 700**2)] = True
    ticks = []
    done = threading.Event()

    def work():
        layertrace.vectorize(big, model="line", fidelity=False)
        done.set()

    t = threading.Thread(target=work)
    start = time.perf_counter()
    t.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    elapsed = time.perf_counter() - start
    assert elapsed > 0.05, "the image is too small to show anything"
    # With the GIL held, the loop would not run at all until the work ended.
    assert len(ticks) > 10, (len(ticks), elapsed)


def test_json_is_the_command_lines_format():
    r = layertrace.vectorize(GLYPH)
    assert json.loads(r.json) == r.decomposition
    total = sum(len(c["pieces"]) for c in r.decomposition["contours"])
    assert total == len(r.pieces)


def test_large_images_are_exact_in_chromiums_tiles():
    # A 600-px page is drawn in 256-px tiles: the disc crosses their borders at 254, 256,
    # 508 and 510. (A page under 512 px both ways is one tile.)
    r = layertrace.vectorize(disc_mask(size=600, radius=280.0))
    assert r.fidelity == 0
    assert r.chromium_tiles == 0
