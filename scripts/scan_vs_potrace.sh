#!/usr/bin/env bash
# scripts/scan_vs_potrace.sh — the scan case against potrace on the same mask.
#
# Usage: scripts/scan_vs_potrace.sh [IMAGE] [OUTDIR]
#   IMAGE default tests/data/scan_text_1200x800_q70.jpg (made by scripts/make_scan.py);
#   OUTDIR default target/scan: SVGs, masks (PBM) and PNG drawings of the SVGs to look at.
#
# For each set of options, layertrace traces the image (-o, --report), examples/scan_mask
# writes the very mask it traced as a PBM, and potrace 1.16 traces that PBM (`potrace -s
# -t 0`: no speck filter of its own, its other defaults); the table gives contours and paths
# (moveto commands), SVG bytes of both and their ratio, and layertrace's differing pixels in
# resvg. A last line runs potrace's own `-t 4` on the uncleaned adaptive mask, to compare the
# two speck filters. Installs potrace with apt-get if it is missing (Debian, as root). Not a
# timed benchmark.
set -euo pipefail

cd "$(dirname "$0")/.."
image=${1:-tests/data/scan_text_1200x800_q70.jpg}
out=${2:-target/scan}
mkdir -p "$out"

if ! command -v potrace >/dev/null 2>&1; then
    echo "scan_vs_potrace.sh: installing potrace" >&2
    apt-get install -y potrace >/dev/null
fi
cargo build --release --quiet --bin layertrace --example scan_mask
bin=target/release/layertrace
mask=target/release/examples/scan_mask

echo "potrace: $(potrace --version | head -1)"
echo "image: $image"
echo
echo "| options | foreground px | contours | layertrace SVG bytes | differing px | potrace paths | potrace SVG bytes | ratio |"
echo "|---|---|---|---|---|---|---|---|"
row() {
    local name=$1 threshold=$2 turdsize=$3 extra=${4:-}
    local tag=${name//[^a-zA-Z0-9]/_}
    # shellcheck disable=SC2086
    report=$("$bin" "$image" --threshold "$threshold" --turdsize "$turdsize" $extra \
        -o "$out/$tag.svg" --report 2>&1)
    contours=$(sed -n 's/.*, \([0-9]*\) contours.*/\1/p' <<<"$report")
    differing=$(sed -n 's/^fidelity: \([0-9]*\) differing.*/\1/p' <<<"$report")
    fg=$("$mask" mask "$image" "$threshold" "$turdsize" "$out/$tag.pbm" | sed -n 's/^foreground \([0-9]*\),.*/\1/p')
    potrace -s -t 0 "$out/$tag.pbm" -o "$out/$tag.potrace.svg"
    ours=$(stat -c %s "$out/$tag.svg")
    theirs=$(stat -c %s "$out/$tag.potrace.svg")
    paths=$(grep -o '[Mm]' "$out/$tag.potrace.svg" | wc -l)
    ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')
    echo "| $name | $fg | $contours | $ours | $differing | $paths | $theirs | $ratio |"
    read -r width height < <(sed -n 2p "$out/$tag.pbm")
    "$mask" render "$out/$tag.svg" "$width" "$height" "$out/$tag.png"
}
row "--threshold 128" 128 0
row "--threshold otsu" otsu 0
row "--threshold adaptive" adaptive 0
row "--threshold adaptive --turdsize 4" adaptive 4
row "--threshold adaptive --turdsize 4 --grid 2" adaptive 4 "--grid 2"
row "--threshold adaptive --turdsize 4 --model line --grid 2" adaptive 4 "--model line --grid 2"

# potrace's own speck filter on the uncleaned adaptive mask.
potrace -s -t 4 "$out/__threshold_adaptive.pbm" -o "$out/potrace_t4.svg"
echo
echo "potrace -t 4 on the uncleaned adaptive mask: $(grep -o '[Mm]' "$out/potrace_t4.svg" | wc -l) paths, $(stat -c %s "$out/potrace_t4.svg") bytes"
echo "drawings of layertrace's SVGs (resvg, crisp edges): $out/*.png"
