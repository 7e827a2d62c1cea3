#!/usr/bin/env python3
"""layertrace --colors against vtracer --colormode color (stacked and cutout) on the colour
samples, layertrace in both layouts (stack and partition): differing pixels, seam pixels,
overlapping pixels, path commands, SVG bytes, time (README, "Colour images").

Needs: `pip install vtracer` (the Python binding of vtracer 0.6), and
`cargo build --release --bin layertrace --example colour_compare`.
Run from the repository root: `python3 scripts/colour_vs_vtracer.py [OUT_DIR]`.

Every SVG is measured by examples/colour_compare.rs against layertrace's regions of the
image in N colours (see that file for the definitions). Time: the best of 3 runs, wall
clock; layertrace as a whole process (decoding, writing the SVG, process start), vtracer
as the in-process call of its Python binding (decoding and writing included, no process
start), with its default settings (vtracer has no colour count; it clusters colours its own
way).
"""
import os
import subprocess
import sys
import tempfile
import time

import vtracer

CASES = [
    ("samples/colour/colour_logo_crisp.png", 8),
    ("samples/colour/colour_logo_aa.png", 4),
    ("samples/colour/colour_sprite_pico8_32.png", 16),
    ("samples/colour/colour_chart_aa.png", 6),
    ("samples/colour/colour_photo_like.png", 8),
    ("samples/ipol/card_suits.png", 3),
]
LAYERTRACE = "target/release/layertrace"
COMPARE = "target/release/examples/colour_compare"


def best_of(n, f):
    best = float("inf")
    for _ in range(n):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="colour_vs_vtracer")
    os.makedirs(out, exist_ok=True)
    print("| image | N | tool | colours | differing px | seam px | overlap px | commands | bytes "
          "| time (ms) |")
    print("|---|--:|---|--:|--:|--:|--:|--:|--:|--:|")
    for image, n in CASES:
        name = os.path.splitext(os.path.basename(image))[0]
        svgs = {
            "layertrace stack": os.path.join(out, f"{name}.layertrace.svg"),
            "layertrace partition": os.path.join(out, f"{name}.layertrace-partition.svg"),
            "vtracer stacked": os.path.join(out, f"{name}.vtracer-stacked.svg"),
            "vtracer cutout": os.path.join(out, f"{name}.vtracer-cutout.svg"),
        }
        times = {
            "layertrace stack": best_of(3, lambda: subprocess.run(
                [LAYERTRACE, image, "--colors", str(n), "-o", svgs["layertrace stack"], "-q"],
                check=True)),
            "layertrace partition": best_of(3, lambda: subprocess.run(
                [LAYERTRACE, image, "--colors", str(n), "--layout", "partition",
                 "-o", svgs["layertrace partition"], "-q"],
                check=True)),
            "vtracer stacked": best_of(3, lambda: vtracer.convert_image_to_svg_py(
                image, svgs["vtracer stacked"], colormode="color", hierarchical="stacked")),
            "vtracer cutout": best_of(3, lambda: vtracer.convert_image_to_svg_py(
                image, svgs["vtracer cutout"], colormode="color", hierarchical="cutout")),
        }
        res = subprocess.run([COMPARE, image, str(n)] + list(svgs.values()),
                             check=True, capture_output=True, text=True).stdout.splitlines()
        colours = res[0].split(": ")[1].split(" ")[0]
        for (tool, path), line in zip(svgs.items(), res[1:]):
            fields = dict(kv.split(" ") for kv in line.split(": ", 1)[1].split(", "))
            with open(path) as f:
                fills = len({a.split('"')[1] for a in f.read().split("fill=")[1:]})
            shown = colours if tool.startswith("layertrace") else f"{fills} fills"
            print(f"| {name} | {n} | {tool} | {shown} | {fields['differing']} | {fields['seams']} "
                  f"| {fields['overlaps']} | {fields['commands']} | {fields['bytes']} | {1e3 * times[tool]:.1f} |")


if __name__ == "__main__":
    main()
