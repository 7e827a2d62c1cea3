"""Tests of colours, the alpha mask and smooth outlines from Python, and of point-set
recognition (`layertrace.recognize`), each answer re-checked here from the data alone."""

import random
import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import layertrace

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
GLYPH = SAMPLES / "glyph_g_liberationserif_cap120.png"
# (sample, colors), as tests/colour.rs.
COLOUR_CASES = [
    ("colour/colour_logo_crisp.png", 8),
    ("colour/colour_logo_aa.png", 4),
    ("colour/colour_sprite_pico8_32.png", 16),
    ("colour/colour_photo_like.png", 8),
]


def fills(svg):
    return re.findall(r'<path[^>]*fill="(#[0-9a-f]{6})"', svg)


@pytest.mark.parametrize("name,colors", COLOUR_CASES)
def test_colour_samples_are_exact_and_seamless(name, colors):
    r = layertrace.vectorize(SAMPLES / name, colors=colors)
    assert r.decomposition["format"].startswith("layertrace-colour/")
    assert r.fidelity == 0 and r.seams == 0 and r.extra == 0
    assert r.missing is None and r.iou is None and r.decomposition_png is None
    assert 2 <= len(r.colours) <= colors
    assert all(c["differing"] == 0 for c in r.colours)
    # One path per colour, in drawing order (the JSON's regions), filled with its colour.
    regions = r.decomposition["regions"]
    assert fills(r.svg) == [reg["colour"] for reg in regions]
    assert sorted(fills(r.svg)) == sorted(c["colour"] for c in r.colours)
    assert sum(c["pixels"] for c in r.colours) <= r.width * r.height
    assert {p["region"] for p in r.pieces} == set(range(len(regions)))
    for p in r.pieces:
        assert p["colour"] == regions[p["region"]]["colour"]
    assert r.diff_png.startswith(b"\x89PNG")


@pytest.mark.parametrize("name,colors", COLOUR_CASES[:2])
def test_partition_is_exact_too(name, colors):
    stack = layertrace.vectorize(SAMPLES / name, colors=colors)
    r = layertrace.vectorize(SAMPLES / name, colors=colors, layout="partition")
    assert r.decomposition["layout"] == "partition"
    assert r.fidelity == 0 and all(c["differing"] == 0 for c in r.colours)
    assert sorted(fills(r.svg)) == sorted(fills(stack.svg))
    assert r.decomposition["borders"]


def test_a_numpy_flag_keeps_its_own_colours():
    h, w = 40, 60
    flag = np.zeros((h, w, 3), dtype=np.uint8)
    flag[:, :20] = (0, 85, 164)
    flag[:, 20:40] = (255, 255, 255)
    flag[:, 40:] = (239, 65, 53)
    y, x = np.mgrid[0:h, 0:w]
    flag[(x - 30) ** 2 + (y - 20) ** 2 <= 64] = (255, 204, 0)  # a disc across two bands
    r = layertrace.vectorize(flag, colors=4)
    assert r.fidelity == 0 and r.seams == 0
    assert sorted(c["colour"] for c in r.colours) == sorted(
        ["#0055a4", "#ffffff", "#ef4135", "#ffcc00"]
    )
    # The array and the same pixels as a PNG file give the same drawing.
    png = Image.fromarray(flag)
    from io import BytesIO

    buf = BytesIO()
    png.save(buf, format="PNG")
    assert layertrace.vectorize(buf.getvalue(), colors=4).svg == r.svg


def test_alpha_draws_a_white_shape_on_transparency():
    h, w = 48, 48
    rgba = np.zeros((h, w, 4), dtype=np.uint8)
    y, x = np.mgrid[0:h, 0:w]
    inside = (x - 24) ** 2 + (y - 24) ** 2 <= 15**2
    rgba[inside] = (255, 255, 255, 255)
    r = layertrace.vectorize(rgba, alpha=True)
    assert r.contours == 1 and r.fidelity == 0
    assert r.width == w


def test_colour_options_are_checked():
    for call, message in [
        (dict(colors=1), "colors"),
        (dict(colors=300), "colors"),
        (dict(colors=4, threshold=100), "threshold"),
        (dict(colors=4, layout="mosaic"), "layout"),
        (dict(colors=4, alpha=True), "alpha"),
        (dict(smooth=0.0), "smooth"),
        (dict(smooth=99.0), "smooth"),
    ]:
        with pytest.raises(layertrace.Error, match=message):
            layertrace.vectorize(SAMPLES / COLOUR_CASES[0][0], **call)
    with pytest.raises(layertrace.Error, match="mask"):
        layertrace.vectorize(np.ones((8, 8), dtype=bool), colors=2)


def test_smooth_keeps_every_pixel_beyond_nu_and_draws_fewer_commands():
    exact = layertrace.vectorize(GLYPH)
    smooth = layertrace.vectorize(GLYPH, smooth=1.0)
    assert smooth.commands < exact.commands
    # Pixels may change only within 1 px of the border.
    assert smooth.fidelity > 0
    assert smooth.beyond == 0 and 0.5 <= smooth.max_distance <= 1.0
    assert exact.fidelity == 0 and exact.beyond is None
    # With colours too.
    colour = layertrace.vectorize(SAMPLES / COLOUR_CASES[1][0], colors=4, smooth=1.0)
    assert colour.beyond == 0 and colour.seams == 0


# --- point sets ---------------------------------------------------------------------

def line_value(layer, p):
    a, b, c = layer["coefficients"]
    return a * p[0] + b * p[1] + c


def digital_line(a, b, mu, omega, xs):
    """Points (x, y) with mu <= a x + b y < mu + omega, b > 0, one per column."""
    pts = []
    for x in xs:
        for y in range(-200, 200):
            if mu <= a * x + b * y < mu + omega:
                pts.append((x, y))
    return pts


def test_a_digital_line_is_described_and_the_layer_holds():
    rng = random.Random(7)
    for _ in range(20):
        # b >= |a| and thickness b: one point per column, so y ± 3 is never an inlier.
        b = rng.randint(1, 5)
        a = rng.randint(-b, b)
        pts = digital_line(a, b, 0, b, range(-15, 16))
        assert len(pts) == 31
        above = [(x, y + 3) for (x, y) in pts[::5]]
        below = [(x, y - 3) for (x, y) in pts[::7]]
        r = layertrace.recognize(pts, above=above, below=below, model="line")
        assert r.described and r.witness is None
        L = r.layer
        assert all(L["lower"] <= line_value(L, p) <= L["upper"] for p in pts)
        sign = 1 if all(line_value(L, q) > L["upper"] for q in above) else -1
        if sign == 1:
            assert all(line_value(L, q) < L["lower"] for q in below)
        else:
            assert all(line_value(L, q) < L["lower"] for q in above)
            assert all(line_value(L, q) > L["upper"] for q in below)


def test_a_bent_set_is_not_described_and_the_witness_proves_it():
    # A "V": points on two lines; the vertex's neighbours above and below.
    pts = [(x, abs(x)) for x in range(-6, 7)]
    above = [(0, 3)]
    below = [(0, -1), (6, 5)]
    r = layertrace.recognize(np.array(pts), above=np.array(above), below=np.array(below),
                             model="line")
    assert not r.described and r.layer is None
    terms = r.witness
    assert terms and all(t["weight"] >= 0 for t in terms)
    assert sum(t["weight"] for t in terms) == 1
    # Σ w·d = 0, with d = F(outlier) − F(inlier) above and F(inlier) − F(outlier) below,
    # F = (x, y): the constant cancels in differences.
    total = [Fraction(0), Fraction(0)]
    for t in terms:
        o, i = t["outlier"], t["inlier"]
        assert tuple(i) in set(pts)
        d = [o[k] - i[k] for k in range(2)]
        if t["side"] == "below":
            d = [-v for v in d]
            assert tuple(o) in set(below)
        else:
            assert tuple(o) in set(above)
        total = [total[k] + t["weight"] * d[k] for k in range(2)]
    assert total == [0, 0]


def test_without_outliers_the_thinnest_layer():
    rng = random.Random(11)
    for _ in range(15):
        pts = sorted({(rng.randint(-8, 8), rng.randint(-8, 8)) for _ in range(rng.randint(3, 9))})
        r = layertrace.recognize(pts, model="line")
        assert r.described and r.thinnest and r.witness is None
        L = r.layer
        a, b, _ = L["coefficients"]
        values = [line_value(L, p) for p in pts]
        assert min(values) == L["lower"] and max(values) == L["upper"]
        assert r.thickness == Fraction(L["upper"] - L["lower"], max(abs(a), abs(b)))
        # Brute force: the L∞-thinnest strip has the direction of a line through two points.
        best = None
        for i, p in enumerate(pts):
            for q in pts[i + 1:]:
                na, nb = q[1] - p[1], p[0] - q[0]  # normal of the line through p and q
                vals = [na * x + nb * y for (x, y) in pts]
                t = Fraction(max(vals) - min(vals), max(abs(na), abs(nb)))
                best = t if best is None else min(best, t)
        assert r.thickness == best, (pts, r.thickness, best)
    collinear = layertrace.recognize([(k, 2 * k + 1) for k in range(6)], model="line")
    assert collinear.thickness == 0 and collinear.layer["lower"] == collinear.layer["upper"]
    separated = layertrace.recognize([(0, 0), (1, 0)], above=[(0, 1)], model="line")
    assert separated.described and not separated.thinnest and separated.thickness is None


def test_a_quadric_shell_in_3d():
    shell, outside, inside = [], [], []
    for x in range(-6, 7):
        for y in range(-6, 7):
            for z in range(-6, 7):
                v = x * x + 2 * y * y + 3 * z * z
                if 30 <= v <= 45:
                    shell.append((x, y, z))
                elif 46 <= v <= 60:
                    outside.append((x, y, z))
                elif v <= 29:
                    inside.append((x, y, z))
    r = layertrace.recognize(shell, above=outside, below=inside, model="quadric3")
    if not r.described:  # the orientation is the recognizer's: try the other one
        r = layertrace.recognize(shell, above=inside, below=outside, model="quadric3")
    assert r.described and r.dimension == 3
    assert len(r.layer["coefficients"]) == len(r.basis) == 10
    names = r.basis

    def value(p):
        x, y, z = p
        env = {"x": x, "y": y, "z": z}
        total = 0
        for c, name in zip(r.layer["coefficients"], names):
            term = 1
            for factor in name.split("*"):
                if factor == "1":
                    continue
                base, _, power = factor.partition("^")
                term *= env[base] ** int(power or 1)
            total += c * term
        return total

    assert all(r.layer["lower"] <= value(p) <= r.layer["upper"] for p in shell)


def test_bad_point_sets_raise():
    for call, message in [
        (dict(inliers=[(0, 0)], model="sphere"), "model"),
        (dict(inliers=[(0, 0), (1, 2, 3)], model="line"), "coordinate"),
        (dict(inliers=[(0.5, 1)], model="line"), "integers"),
        (dict(inliers=[(True, 1)], model="line"), "integers"),
        (dict(inliers=[(2**70, 1)], model="line"), "64 bits"),
        (dict(inliers=[], model="line"), "inliers"),
        (dict(inliers=np.zeros((3, 2), dtype=float), model="line"), "integers"),
        (dict(inliers=[(0, 0, 0)], model="conic"), "2-D"),
    ]:
        with pytest.raises(layertrace.Error, match=message):
            layertrace.recognize(**call)
