"""Vectorize a folder of images on a Dask cluster, writing SVGs and a CSV of figures.

    python examples/dask_batch.py IN_DIR OUT_DIR [--model conic] [--workers 2]
    python examples/dask_batch.py IN_DIR OUT_DIR --scheduler tcp://host:8786

Each image is one task of a dask.bag: the task reads the file, calls layertrace.vectorize
(which releases the GIL) and writes OUT_DIR/NAME.svg itself, so only the small row of
figures travels back to the client. Without --scheduler a distributed.LocalCluster of
--workers processes runs the tasks; with it, the same code runs on a real cluster (the
workers must see IN_DIR and OUT_DIR, e.g. on a shared file system, and have layertrace
installed). OUT_DIR/figures.csv has one row per image, in name order:

    name, width, height, pieces, contours, commands, differing_px, svg_bytes, seconds, error

A failed image has its message in `error` and the exit code is 1; the others are written.
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional

import dask.bag as db
from distributed import Client, LocalCluster

import layertrace

EXTENSIONS = {".png", ".bmp", ".pbm", ".pgm", ".ppm", ".pnm", ".tif", ".tiff", ".gif",
              ".jpg", ".jpeg", ".webp"}
FIELDS = ["name", "width", "height", "pieces", "contours", "commands", "differing_px",
          "svg_bytes", "seconds", "error"]


def images(folder: Path) -> List[Path]:
    """The image files of `folder` (by extension), in name order."""
    return sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in EXTENSIONS)


def convert(path: str, out_dir: str, model: str) -> Dict[str, object]:
    """One task: vectorize `path`, write its SVG into `out_dir`, return its figures."""
    name = Path(path).name
    start = time.perf_counter()
    try:
        r = layertrace.vectorize(path, model=model)
    except layertrace.Error as e:
        return dict(name=name, error=str(e))
    svg = Path(out_dir) / (Path(path).stem + ".svg")
    tmp = svg.with_name(svg.name + ".part")
    tmp.write_text(r.svg)
    tmp.replace(svg)  # whole or not at all
    return dict(
        name=name, width=r.width, height=r.height, pieces=len(r.pieces), contours=r.contours,
        commands=r.commands, differing_px=r.fidelity, svg_bytes=len(r.svg.encode()),
        seconds=round(time.perf_counter() - start, 4), error="",
    )


def run(in_dir: Path, out_dir: Path, model: str = "conic", workers: int = 2,
        scheduler: Optional[str] = None, limit: Optional[int] = None) -> List[Dict[str, object]]:
    """Vectorizes the images of `in_dir` (the first `limit` of them) into `out_dir`."""
    files = images(in_dir)[:limit]
    if not files:
        raise SystemExit(f"{in_dir}: no image files")
    out_dir.mkdir(parents=True, exist_ok=True)
    if scheduler:
        client = Client(scheduler)
        cluster = None
    else:
        # One thread per worker process: layertrace itself runs its work on all cores.
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        bag = db.from_sequence([str(f) for f in files], npartitions=len(files))
        rows = bag.map(convert, str(out_dir), model).compute()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    rows.sort(key=lambda r: str(r["name"]))
    with open(out_dir / "figures.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    return rows


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("in_dir", type=Path)
    parser.add_argument("out_dir", type=Path)
    parser.add_argument("--model", default="conic", help="line, circle, conic or poly:D")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("--limit", type=int, help="only the first N images (in name order)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    rows = run(args.in_dir, args.out_dir, args.model, args.workers, args.scheduler, args.limit)
    failed = [r for r in rows if r["error"]]
    for r in failed:
        print(f"dask_batch: {r['name']}: {r['error']}", file=sys.stderr)
    print(f"dask_batch: {len(rows) - len(failed)} of {len(rows)} images vectorized into "
          f"{args.out_dir} in {time.perf_counter() - start:.1f} s", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
