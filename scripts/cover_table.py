#!/usr/bin/env python3
"""scripts/cover_table.py — greedy vs optimal cover: pieces, SVG commands, differing pixels, time.

Usage: scripts/cover_table.py [--bin BIN] [--runs N] [--models line,circle,conic] IMAGE...

For every model and IMAGE, runs `BIN IMAGE -o TMP.svg --model M --cover C --report` once for
C = greedy and optimal and reads the summary line (pieces) and the --report lines (SVG
commands, differing pixels in resvg); then times the whole process `BIN IMAGE -o TMP.svg
--model M --cover C -q` N times (default 3), the two covers interleaved, and keeps the median
wall time of each (--runs 0: no timing). Prints one markdown table per model (one row per image and a total row:
sums, and the ratio of the summed times) on standard output; progress on standard error.
BIN defaults to target/release/layertrace.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

COVERS = ("greedy", "optimal")


def report(binary, image, model, cover, svg):
    """(pieces, commands, differing pixels) from one --report run."""
    r = subprocess.run(
        [binary, image, "-o", svg, "--model", model, "--cover", cover, "--report"],
        capture_output=True, text=True, check=True)
    err = r.stderr
    pieces = int(re.search(r"contours? \([^)]*\), (\d+) pieces?", err).group(1))
    commands = int(re.search(r"svg: \d+ bytes, (\d+) commands", err).group(1))
    px = int(re.search(r"fidelity: (\d+) differing pixels", err).group(1))
    return pieces, commands, px


def wall(binary, image, model, cover, svg):
    t = time.perf_counter()
    subprocess.run([binary, image, "-o", svg, "--model", model, "--cover", cover, "-q"],
                   check=True, capture_output=True)
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="target/release/layertrace")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--models", default="line,circle,conic")
    ap.add_argument("images", nargs="+")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="cover_table.")
    svg = os.path.join(tmp, "x.svg")
    for model in a.models.split(","):
        print(f"\n### model {model}\n")
        print("| image | pieces greedy | pieces optimal | commands greedy | commands optimal "
              "| px greedy | px optimal | ms greedy | ms optimal | time ratio |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        tot = {c: [0, 0, 0, 0.0] for c in COVERS}
        for image in a.images:
            print(f"{model} {image}", file=sys.stderr)
            row = {}
            for c in COVERS:
                row[c] = list(report(a.bin, image, model, c, svg))
            times = {c: [] for c in COVERS}
            for r in range(a.runs):
                order = COVERS if r % 2 == 0 else COVERS[::-1]
                for c in order:
                    times[c].append(wall(a.bin, image, model, c, svg))
            for c in COVERS:
                row[c].append(statistics.median(times[c]) * 1e3 if times[c] else float("nan"))
                for k in range(4):
                    tot[c][k] += row[c][k]
            g, o = row["greedy"], row["optimal"]
            print(f"| {os.path.basename(image)} | {g[0]} | {o[0]} | {g[1]} | {o[1]} | {g[2]} | {o[2]} "
                  f"| {g[3]:.1f} | {o[3]:.1f} | {o[3] / g[3]:.2f} |", flush=True)
        g, o = tot["greedy"], tot["optimal"]
        print(f"| **total** | {g[0]} | {o[0]} | {g[1]} | {o[1]} | {g[2]} | {o[2]} "
              f"| {g[3]:.0f} | {o[3]:.0f} | {o[3] / g[3]:.2f} |", flush=True)


if __name__ == "__main__":
    main()
