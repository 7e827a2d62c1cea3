#!/usr/bin/env bash
# scripts/threads_speedup.sh — whole-process speed-up of layertrace binaries from one thread to two.
#
# Usage: scripts/threads_speedup.sh [--runs N] [--threads T] [--model M] BIN… -- IMAGE
#   BIN: layertrace binaries (e.g. builds before and after a change); IMAGE: one input (the
#   issue "As fast as potrace, and no cliffs" asks for 1.8× on samples/syn_big3000_many_shapes.png
#   with two cores); --runs N timed runs per binary and thread count (default 11);
#   --threads T the second thread count (default 2); --model M (default conic).
#
# Each BIN runs once untimed with each thread count (warm-up; exit status 0 and a non-empty
# SVG), then N rounds, each round running every BIN with 1 thread and with T threads, one
# after the other; the rounds alternate the order (round r starts with the thread count the
# round r-1 ended with), so a drift of the machine's speed falls on both counts alike. Each
# run is a whole process timed with bash's $EPOCHREALTIME:
#   BIN IMAGE -o TMP/out.svg --model M --threads K -q
# Prints a markdown table on standard output: per BIN the median and fastest run with 1 and
# T threads and the speed-up by medians and by fastest runs (progress on standard error).
# The SVGs of 1 and T threads are compared too: the document does not depend on the number
# of threads, and a difference is reported as an error.
#
# Wall time on a shared machine moves by several per cent from one minute to the next: run
# both orders of the binaries (`A B` and `B A`) and compare ratios, not milliseconds.
set -euo pipefail
export LC_ALL=C

runs=11
threads=2
model=conic
bins=()
image=
seen_sep=0
while [ $# -gt 0 ]; do
    if [ "$seen_sep" = 1 ]; then
        [ -z "$image" ] || { echo "threads_speedup.sh: one IMAGE only" >&2; exit 2; }
        image="$1"
    else
        case "$1" in
            --runs) runs="${2:?--runs needs a number}"; shift ;;
            --threads) threads="${2:?--threads needs a number}"; shift ;;
            --model) model="${2:?--model needs a model}"; shift ;;
            -h|--help) sed -n '4,8s/^# \{0,1\}//p' "$0"; exit 0 ;;
            --) seen_sep=1 ;;
            *) bins+=("$1") ;;
        esac
    fi
    shift
done
if ! [[ "$runs" =~ ^[1-9][0-9]*$ && "$threads" =~ ^([2-9]|[1-9][0-9]+)$ ]] \
    || [ ${#bins[@]} -eq 0 ] || [ -z "$image" ]; then
    sed -n '4,8s/^# \{0,1\}//p' "$0" >&2
    exit 2
fi
log() { echo "threads_speedup.sh: $*" >&2; }
for b in "${bins[@]}"; do
    [ -x "$b" ] || { log "not an executable: $b"; exit 2; }
done
[ -f "$image" ] || { log "no such image: $image"; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/threads_speedup.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# Milliseconds of one whole run of BIN with K threads.
run() {
    local bin="$1" k="$2" out="$3" t0 t1
    t0=$EPOCHREALTIME
    "$bin" "$image" -o "$out" --model "$model" --threads "$k" -q 2>"$tmp/err" || {
        log "failed: $bin --threads $k ($(tail -n 1 "$tmp/err"))"
        exit 1
    }
    t1=$EPOCHREALTIME
    python3 -c "print(f'{($t1 - $t0) * 1e3:.3f}')"
}

for i in "${!bins[@]}"; do
    for k in 1 "$threads"; do
        run "${bins[$i]}" "$k" "$tmp/b$i-t$k.svg" >/dev/null
        [ -s "$tmp/b$i-t$k.svg" ] || { log "empty SVG: ${bins[$i]} --threads $k"; exit 1; }
    done
    cmp -s "$tmp/b$i-t1.svg" "$tmp/b$i-t$threads.svg" || {
        log "${bins[$i]}: the SVG with $threads threads differs from one thread's"
        exit 1
    }
done

order=(1 "$threads")
for ((r = 0; r < runs; r++)); do
    log "round $((r + 1)) of $runs"
    for i in "${!bins[@]}"; do
        for k in "${order[@]}"; do
            run "${bins[$i]}" "$k" "$tmp/run.svg" >>"$tmp/ms-$i-$k"
        done
    done
    order=("${order[1]}" "${order[0]}")
done

echo "| binary | 1 thread median ms | $threads threads median ms | speed-up by medians | 1 thread fastest ms | $threads threads fastest ms | speed-up by fastest |"
echo "|---|--:|--:|--:|--:|--:|--:|"
for i in "${!bins[@]}"; do
    python3 - "${bins[$i]}" "$tmp/ms-$i-1" "$tmp/ms-$i-$threads" <<'EOF'
import statistics, sys
name, one, many = sys.argv[1], sys.argv[2], sys.argv[3]
a = [float(v) for v in open(one)]
b = [float(v) for v in open(many)]
ma, mb = statistics.median(a), statistics.median(b)
fa, fb = min(a), min(b)
print(f"| {name} | {ma:.1f} | {mb:.1f} | **{ma / mb:.2f}×** | {fa:.1f} | {fb:.1f} | {fa / fb:.2f}× |")
EOF
done
