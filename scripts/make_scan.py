#!/usr/bin/env python3
"""Makes tests/data/scan_text_1200x800_q70.jpg: a page of text as a cheap scanner or a phone
photographs it, the test case of the scan options (--threshold adaptive, --turdsize).

A 1200x800 page: a title and paragraphs of text in Pillow's scalable default font
(ImageFont.load_default(size), Aileron), slightly blurred as optics do, lit unevenly (light
falling from the top right to the bottom left, a dark shadow along the binding at the left
edge that the text runs into), Gaussian sensor noise, dust specks of one to a few pixels,
a few larger blots, small light specks inside the title's letters (holes), a paper tint, and
JPEG quality 70. Deterministic for one Pillow version (pure-Python random, fixed seed).

Needs Python 3 and Pillow (`pip install pillow`); the tests read the committed JPEG, so
they do not need Python. Usage: python3 scripts/make_scan.py [OUT.jpg]
"""

import math
import random
import sys

from PIL import Image, ImageDraw, ImageFilter, ImageFont

W, H = 1200, 800
OUT = sys.argv[1] if len(sys.argv) > 1 else "tests/data/scan_text_1200x800_q70.jpg"
PAPER, INK = 0.92, 0.10  # reflectances
NOISE = 6.0  # sensor noise, grey levels (standard deviation)
SHADOW_DEPTH, SHADOW_WIDTH = 0.68, 130.0  # binding shadow: 1 - depth at x = 0
CAST_DEPTH, CAST_SOFTNESS = 0.5, 150.0  # a cast shadow: depth inside, edge width

TITLE = "Digital Level Layers"
TEXT = (
    "A scanned page is never as clean as a drawing. The paper is not white but grey, "
    "lit more on one side than on the other, and darker still where the book bends "
    "into its binding. Dust leaves specks of a pixel or two, the sensor adds noise, and "
    "the compression smears every edge into small blocks. A fixed threshold keeps the "
    "specks and turns the shadow into ink; Otsu's threshold, chosen for the whole page, "
    "fails in the same way. A local threshold compares each pixel with the mean and the "
    "deviation of its neighbourhood instead, so that the letters stay black in the "
    "shadow while the paper around them stays white, and a size filter drops what is "
    "too small to be a letter or a hole in one. The quick brown fox jumps over the lazy "
    "dog; pack my box with five dozen liquor jugs; 0123456789."
)


def wrap(draw, text, font, width):
    lines, line = [], ""
    for word in text.split():
        candidate = (line + " " + word).strip()
        if draw.textlength(candidate, font=font) <= width:
            line = candidate
        else:
            lines.append(line)
            line = word
    lines.append(line)
    return lines


def main():
    rng = random.Random(17)
    # Ink coverage: 255 paper, 0 ink, anti-aliased.
    page = Image.new("L", (W, H), 255)
    draw = ImageDraw.Draw(page)
    title = ImageFont.load_default(54)
    body = ImageFont.load_default(23)
    draw.text((40, 40), TITLE, font=title, fill=0)
    y = 130
    for _ in range(2):
        for line in wrap(draw, TEXT, body, W - 90):
            draw.text((38, y), line, font=body, fill=0)
            y += 33
        y += 20
    # Light specks in the title's strokes (small holes), dust, a few blots.
    for _ in range(25):
        x, yy = rng.uniform(45, 700), rng.uniform(45, 100)
        if page.getpixel((int(x), int(yy))) == 0:
            draw.ellipse((x - 0.7, yy - 0.7, x + 0.7, yy + 0.7), fill=255)
    for _ in range(320):
        x, yy, r = rng.uniform(0, W), rng.uniform(0, H), rng.uniform(0.4, 1.3)
        draw.ellipse((x - r, yy - r, x + r, yy + r), fill=rng.randint(0, 120))
    for _ in range(12):
        x, yy, r = rng.uniform(0, W), rng.uniform(0, H), rng.uniform(2.5, 5.0)
        draw.ellipse((x - r, yy - r * 0.7, x + r, yy + r * 0.7), fill=rng.randint(0, 60))
    page = page.filter(ImageFilter.GaussianBlur(0.7))

    cover = page.tobytes()
    out = bytearray(W * H * 3)
    tint = (1.0, 0.97, 0.90)
    for yy in range(H):
        for x in range(W):
            # Light: 1.0 at the top right, 0.75 at the bottom left; the binding shadow.
            light = 1.0 - 0.25 * (0.5 * (1 - x / W) + 0.5 * yy / H)
            light *= 1.0 - SHADOW_DEPTH * math.exp(-((x / SHADOW_WIDTH) ** 2))
            # A broad soft shadow (a hand or a phone) over the lower right.
            d = math.hypot((x - 1150) / 1.3, yy - 820) - 380.0
            light *= 1.0 - CAST_DEPTH / (1.0 + math.exp(d / CAST_SOFTNESS))
            c = cover[yy * W + x] / 255.0
            reflect = INK + (PAPER - INK) * c
            v = 255.0 * light * reflect + rng.gauss(0.0, NOISE)
            i = 3 * (yy * W + x)
            for k in range(3):
                out[i + k] = max(0, min(255, round(v * tint[k])))
    img = Image.frombytes("RGB", (W, H), bytes(out))
    img.save(OUT, quality=70)
    print(f"{OUT}: {W}x{H}, JPEG q70")


if __name__ == "__main__":
    main()
