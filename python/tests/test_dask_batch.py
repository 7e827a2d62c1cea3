"""The Dask example, run as a user runs it: a LocalCluster of 2 workers over samples/."""

import csv
import subprocess
import sys
from pathlib import Path

import layertrace

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "python" / "examples" / "dask_batch.py"
SAMPLES = ROOT / "samples"

sys.path.insert(0, str(EXAMPLE.parent))
import dask_batch  # noqa: E402


def test_dask_batch_over_samples(tmp_path):
    out = tmp_path / "out"
    n = 6
    done = subprocess.run(
        [sys.executable, str(EXAMPLE), str(SAMPLES), str(out), "--workers", "2",
         "--limit", str(n)],
        capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stderr
    assert f"{n} of {n} images vectorized" in done.stderr
    expected = dask_batch.images(SAMPLES)[:n]
    with open(out / "figures.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["name"] for r in rows] == [p.name for p in expected]
    assert list(rows[0]) == dask_batch.FIELDS
    for row, path in zip(rows, expected):
        svg = out / (path.stem + ".svg")
        reference = layertrace.vectorize(path)
        # Every SVG is written, whole, and is what the library makes of the image.
        assert svg.read_text() == reference.svg, path
        assert row["error"] == ""
        assert int(row["pieces"]) == len(reference.pieces) > 0
        assert int(row["contours"]) == reference.contours
        assert int(row["commands"]) == reference.commands
        assert int(row["differing_px"]) == 0
        assert (int(row["width"]), int(row["height"])) == (reference.width, reference.height)
        assert int(row["svg_bytes"]) == svg.stat().st_size
        assert float(row["seconds"]) > 0
    # Nothing else in the output folder (no leftover temporaries).
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [p.stem + ".svg" for p in expected] + ["figures.csv"]
    )


def test_a_bad_image_is_a_row_with_its_error(tmp_path):
    bad = tmp_path / "broken.png"
    bad.write_bytes(b"\x89PNG\r\n\x1a\n garbage")
    row = dask_batch.convert(str(bad), str(tmp_path), "conic")
    assert row["name"] == "broken.png"
    assert "cannot decode" in row["error"] and "broken.png" in row["error"]
    assert not (tmp_path / "broken.svg").exists()
