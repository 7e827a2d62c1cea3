#!/usr/bin/env bash
# scripts/noise_vs_potrace.sh — the noise cliff: layertrace binaries against potrace on random noise.
#
# Usage: scripts/noise_vs_potrace.sh [--sizes "400 1000 2000"] [--model M] BIN…
#   BIN: layertrace binaries to time side by side (e.g. builds before and after a change).
#
# For each size N, writes an N×N 8-bit PGM of 50 % random noise (python3, standard library,
# fixed seed), then runs once each, one after the other, whole processes timed by GNU time:
#   potrace FILE.pgm -b svg -o TMP/potrace.svg
#   BIN FILE.pgm -o TMP/binK.svg --model M --threads 1 -q
# and prints a markdown table: user seconds and peak RSS per tool, and each BIN's time and
# memory relative to potrace. One run each: the noise images take seconds, and the point is
# the ratio measured side by side (issue "As fast as potrace, and no cliffs": noise 2000²
# within 3× potrace's time, memory within 3×).
#
# Installs potrace with apt-get when it is missing (Debian, as root). Needs python3 and
# /usr/bin/time.
set -euo pipefail
export LC_ALL=C

sizes="400 1000 2000"
model=conic
bins=()
while [ $# -gt 0 ]; do
    case "$1" in
        --sizes) sizes="${2:?--sizes needs a list}"; shift ;;
        --model) model="${2:?--model needs a model}"; shift ;;
        -h|--help) sed -n '4,5s/^# \{0,1\}//p' "$0"; exit 0 ;;
        *) bins+=("$1") ;;
    esac
    shift
done
if [ ${#bins[@]} -eq 0 ]; then
    sed -n '4,5s/^# \{0,1\}//p' "$0" >&2
    exit 2
fi
log() { echo "noise_vs_potrace.sh: $*" >&2; }
for b in "${bins[@]}"; do
    [ -x "$b" ] || { log "not an executable: $b"; exit 2; }
done
[ -x /usr/bin/time ] || { log "/usr/bin/time missing (Debian package 'time')"; exit 1; }
if ! command -v potrace >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        log "installing potrace (apt-get)"
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq potrace; } >&2
    fi
    command -v potrace >/dev/null 2>&1 || { log "potrace missing and could not be installed"; exit 1; }
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/noise_vs_potrace.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# "user-seconds max-RSS-KB" of one whole process.
measure() {
    /usr/bin/time -f "%U %M" -o "$tmp/time" "$@" >/dev/null 2>"$tmp/err" || {
        log "failed: $* ($(tail -n 1 "$tmp/err"))"
        echo "FAIL FAIL"
        return
    }
    cat "$tmp/time"
}

header="| noise | potrace s | potrace MB |"
rule="|---|--:|--:|"
for k in "${!bins[@]}"; do
    header+=" bin$k s | bin$k MB | time × | memory × |"
    rule+="--:|--:|--:|--:|"
done
echo "$header"
echo "$rule"
for n in $sizes; do
    img="$tmp/noise$n.pgm"
    python3 - "$n" "$img" <<'EOF'
import random, sys
n, path = int(sys.argv[1]), sys.argv[2]
rng = random.Random(n)
data = bytes(0 if rng.random() < 0.5 else 255 for _ in range(n * n))
with open(path, "wb") as f:
    f.write(b"P5\n%d %d\n255\n" % (n, n) + data)
EOF
    log "${n}² potrace"
    read -r pt pm < <(measure potrace "$img" -b svg -o "$tmp/potrace.svg")
    row="| ${n}² | $pt | $((pm / 1024)) |"
    for k in "${!bins[@]}"; do
        log "${n}² bin$k ${bins[$k]}"
        read -r bt bm < <(measure "${bins[$k]}" "$img" -o "$tmp/bin$k.svg" --model "$model" --threads 1 -q)
        if [ "$bt" = FAIL ] || [ "$pt" = FAIL ]; then
            row+=" $bt | – | – | – |"
        else
            row+=" $bt | $((bm / 1024)) | $(python3 -c "print(f'{$bt / max($pt, 0.01):.1f}')") | $(python3 -c "print(f'{$bm / $pm:.2f}')") |"
        fi
    done
    echo "$row"
done
