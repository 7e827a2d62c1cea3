#!/usr/bin/env bash
# scripts/time_vs_potrace.sh — whole-process wall time of layertrace binaries relative to potrace.
#
# Usage: scripts/time_vs_potrace.sh [--runs N] [--model M] [--instructions] BIN… -- IMAGE…
#   BIN: layertrace binaries to time (e.g. builds before and after a change); IMAGE: PNG files;
#   --runs N timed runs per tool and image (default 5); --model M for every BIN (default conic);
#   --instructions: count instructions instead of timing (see below).
#
# Every IMAGE is first converted once, untimed, to a PBM with layertrace's default mask
# (composite on white, Rec. 709 luma truncated as the image crate does, foreground = luma < 128;
# a small python3 PNG reader, standard library only: 8-bit grey, grey+alpha, RGB, RGBA,
# non-interlaced; other PNGs get no potrace row). Then, per image, each tool runs once untimed
# (warm-up and success check: exit status 0 and a non-empty SVG), then N times interleaved
# (run r starts with the tool after the one run r-1 started with), each run a whole process
# timed with bash's $EPOCHREALTIME:
#   potrace FILE.pbm -b svg -o TMP/potrace.svg          (default options, as examples/compare.rs)
#   BIN IMAGE -o TMP/binK.svg --model M [--threads 1] [-q]  (--threads 1 and -q when BIN --help
#                                                        lists them)
# (each BIN run from a copy in TMP read back from disk, see below),
# and the median per tool is kept. Prints a markdown table on standard output (image | potrace
# ms | BIN ms | BIN/potrace …) and a last row with the median over images of each ratio
# (images where either tool failed are left out of that median); progress on standard error.
#
# With --instructions, each tool runs once (after the same check) under valgrind's callgrind,
# and the table gives millions of instructions instead of milliseconds: the same for every run,
# whatever else the machine does, so builds can be compared to a fraction of a percent. For
# each BIN it also gives the instructions of the decomposition alone (the paper's recognition:
# the inclusive count of `decompose_reporting`, which needs BIN's symbols, as in the release
# profile) and their ratio to potrace's whole run.
#
# Installs potrace (and valgrind for --instructions) with apt-get when missing (Debian, as
# root). Needs python3.
set -euo pipefail
export LC_ALL=C

runs=5
model=conic
instructions=0
bins=()
images=()
seen_sep=0
while [ $# -gt 0 ]; do
    if [ "$seen_sep" = 1 ]; then
        images+=("$1")
    else
        case "$1" in
            --runs) runs="${2:?--runs needs a number}"; shift ;;
            --model) model="${2:?--model needs a model}"; shift ;;
            --instructions) instructions=1 ;;
            -h|--help) sed -n '4,7s/^# \{0,1\}//p' "$0"; exit 0 ;;
            --) seen_sep=1 ;;
            *) bins+=("$1") ;;
        esac
    fi
    shift
done
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]] || [ ${#bins[@]} -eq 0 ] || [ ${#images[@]} -eq 0 ]; then
    sed -n '4,7s/^# \{0,1\}//p' "$0" >&2
    exit 2
fi

log() { echo "time_vs_potrace.sh: $*" >&2; }

# potrace, from Debian's packages.
if ! command -v potrace >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        log "installing potrace (apt-get)"
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq potrace; } >&2
    fi
    command -v potrace >/dev/null 2>&1 || { log "potrace missing and could not be installed"; exit 1; }
fi
log "$(potrace --version | head -n 1)"
if [ "$instructions" = 1 ]; then
    runs=1
    if ! command -v callgrind_annotate >/dev/null 2>&1; then
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
            log "installing valgrind (apt-get)"
            { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq valgrind; } >&2
        fi
        command -v callgrind_annotate >/dev/null 2>&1 || { log "valgrind missing and could not be installed"; exit 1; }
    fi
fi

# The extra arguments of each BIN, from its --help.
bin_extra=()
for b in "${bins[@]}"; do
    [ -x "$b" ] || { log "not an executable: $b"; exit 2; }
    help=$("$b" --help 2>&1 || true)
    extra=""
    if grep -q -- '--threads' <<<"$help"; then extra+=" --threads 1"; fi
    if grep -q -- '--quiet' <<<"$help"; then extra+=" -q"; fi
    bin_extra+=("$extra")
    log "$b:${extra:- (no --threads / -q)}"
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/time_vs_potrace.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
# Each BIN runs from a copy whose pages are then dropped from the page cache, so that every
# binary is read back from disk alike: a file just written starts 0.1–0.2 ms faster per
# process than one read back (its pages are cached in larger folios: fewer page faults),
# so binaries built at different times would not start alike (BENCHMARKS.md, stop 51).
runnable=()
for k in "${!bins[@]}"; do
    mkdir -p "$tmp/exe$k"
    cp "${bins[$k]}" "$tmp/exe$k/"
    runnable+=("$tmp/exe$k/$(basename "${bins[$k]}")")
done
python3 - "${runnable[@]}" <<'PY'
import os, sys
for path in sys.argv[1:]:
    fd = os.open(path, os.O_RDONLY)
    os.fsync(fd)
    os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
    os.close(fd)
PY
results="$tmp/results.tsv"   # image index, tool index, milliseconds (or instructions) or FAIL
parts="$tmp/parts.tsv"       # image index, tool index, instructions of the decomposition
: >"$results"
: >"$parts"

# PNG -> PBM (P4) with layertrace's default mask. Exit status 3: PNG kind not handled.
png_to_pbm() {
    python3 - "$1" "$2" <<'PY'
import struct, sys, zlib
src, dst = sys.argv[1], sys.argv[2]
data = open(src, "rb").read()
if data[:8] != b"\x89PNG\r\n\x1a\n":
    sys.exit("not a PNG")
pos, idat, ihdr, other = 8, [], None, set()
while pos < len(data):
    (n,) = struct.unpack(">I", data[pos:pos + 4])
    kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        ihdr = struct.unpack(">IIBBBBB", body)
    elif kind == b"IDAT":
        idat.append(body)
    else:
        other.add(kind)
    pos += 12 + n
w, h, depth, ctype, _, _, interlace = ihdr
channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
if depth != 8 or channels is None or interlace != 0 or b"tRNS" in other:
    print(f"unsupported PNG (depth {depth}, colour type {ctype}, interlace {interlace})", file=sys.stderr)
    sys.exit(3)
raw = zlib.decompress(b"".join(idat))
stride = w * channels
prev = bytearray(stride)
ink = bytes(1 if v < 128 else 0 for v in range(256))  # 1 = black = foreground
out = [f"P4\n{w} {h}\n".encode()]
pad = (-w) % 8
for y in range(h):
    f = raw[y * (stride + 1)]
    row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    bpp = channels
    if f == 1:
        for i in range(bpp, stride):
            row[i] = (row[i] + row[i - bpp]) & 255
    elif f == 2:
        for i in range(stride):
            row[i] = (row[i] + prev[i]) & 255
    elif f == 3:
        for i in range(stride):
            left = row[i - bpp] if i >= bpp else 0
            row[i] = (row[i] + ((left + prev[i]) >> 1)) & 255
    elif f == 4:
        for i in range(stride):
            a = row[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    elif f != 0:
        sys.exit(f"bad PNG filter {f}")
    prev = row
    if ctype == 0:
        grey = bytes(row)
    else:
        def over(c, a):  # channel over white, rounded
            return (c * a + 255 * (255 - a) + 127) // 255
        g = bytearray(w)
        for x in range(w):
            p = row[x * channels:(x + 1) * channels]
            if ctype == 4:
                g[x] = over(p[0], p[1])
            else:
                r, gg, bb = p[0], p[1], p[2]
                if ctype == 6:
                    r, gg, bb = over(r, p[3]), over(gg, p[3]), over(bb, p[3])
                g[x] = (2126 * r + 7152 * gg + 722 * bb) // 10000
        grey = bytes(g)
    bits = grey.translate(ink) + b"\0" * pad
    if w:
        out.append(int(bits.translate(b"01" + bytes(254)).decode(), 2).to_bytes((w + pad) // 8, "big"))
open(dst, "wb").write(b"".join(out))
PY
}

# Runs "$@" once with output discarded; prints the wall time in ms (3 decimals); status = the command's.
time_ms() {
    local t0 t1 rc=0
    t0=$EPOCHREALTIME
    "$@" >/dev/null 2>>"$tmp/stderr" || rc=$?
    t1=$EPOCHREALTIME
    local us=$(( 10#${t1/./} - 10#${t0/./} ))
    printf '%d.%03d\n' $((us / 1000)) $((us % 1000))
    return $rc
}

# Runs "$@" once under callgrind, output discarded; prints its instructions; status = the
# command's. The profile stays in $tmp/callgrind.out for `decomposition`.
count_instructions() {
    local rc=0
    valgrind --tool=callgrind --callgrind-out-file="$tmp/callgrind.out" "$@" \
        >/dev/null 2>>"$tmp/stderr" || rc=$?
    [ "$rc" = 0 ] || return $rc
    sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$tmp/callgrind.out"
}

# The inclusive instructions of layertrace's decomposition in the last profile (empty when
# the binary has no symbols). awk reads to the end: an early exit would fail the pipeline.
decomposition() {
    callgrind_annotate --inclusive=yes "$tmp/callgrind.out" 2>/dev/null \
        | awk '!found && /decompose\/mod\.rs:[a-z_:]*decompose::decompose_reporting( |$)/ {
            gsub(",", "", $1); print $1; found = 1
        }'
}

ntools=$(( ${#bins[@]} + 1 ))
# The command of tool T (0 = potrace, K = BIN K) on image I, into the array `cmd`.
set_cmd() {
    local t=$1 i=$2
    if [ "$t" = 0 ]; then
        cmd=(potrace "$tmp/$i.pbm" -b svg -o "$tmp/potrace.svg")
    else
        # shellcheck disable=SC2206  # the extra arguments are split on purpose
        cmd=("${runnable[$((t - 1))]}" "${images[$i]}" -o "$tmp/bin$t.svg" --model "$model" ${bin_extra[$((t - 1))]})
    fi
}

for i in "${!images[@]}"; do
    img=${images[$i]}
    name=$(basename "$img")
    ok=()
    for ((t = 0; t < ntools; t++)); do ok[t]=1; done
    if [ ! -f "$img" ]; then
        log "$name: no such file"
        for ((t = 0; t < ntools; t++)); do ok[t]=0; done
    elif ! png_to_pbm "$img" "$tmp/$i.pbm" 2>"$tmp/conv.err"; then
        log "$name: no PBM for potrace: $(head -n 1 "$tmp/conv.err")"
        ok[0]=0
    fi
    # Warm-up and success check.
    for ((t = 0; t < ntools; t++)); do
        [ "${ok[t]}" = 1 ] || continue
        set_cmd "$t" "$i"
        if [ "$t" = 0 ]; then out="$tmp/potrace.svg"; else out="$tmp/bin$t.svg"; fi
        rm -f "$out"
        : >"$tmp/stderr"
        if ! time_ms "${cmd[@]}" >/dev/null || [ ! -s "$out" ]; then
            log "$name: ${cmd[0]} failed: $(head -n 1 "$tmp/stderr")"
            ok[t]=0
        fi
    done
    # Timed runs, interleaved, the starting tool rotating.
    for ((r = 0; r < runs; r++)); do
        for ((k = 0; k < ntools; k++)); do
            t=$(( (r + k) % ntools ))
            [ "${ok[t]}" = 1 ] || continue
            set_cmd "$t" "$i"
            : >"$tmp/stderr"
            if [ "$instructions" = 1 ]; then
                if n=$(count_instructions "${cmd[@]}") && [ -n "$n" ]; then
                    printf '%s\t%s\t%s\n' "$i" "$t" "$n" >>"$results"
                    if [ "$t" != 0 ]; then
                        d=$(decomposition)
                        [ -z "$d" ] || printf '%s\t%s\t%s\n' "$i" "$t" "$d" >>"$parts"
                    fi
                else
                    log "$name: ${cmd[0]} failed under callgrind: $(head -n 1 "$tmp/stderr")"
                    ok[t]=0
                fi
            elif ms=$(time_ms "${cmd[@]}"); then
                printf '%s\t%s\t%s\n' "$i" "$t" "$ms" >>"$results"
            else
                log "$name: ${cmd[0]} failed in run $((r + 1)): $(head -n 1 "$tmp/stderr")"
                ok[t]=0
            fi
        done
    done
    for ((t = 0; t < ntools; t++)); do
        [ "${ok[t]}" = 1 ] || printf '%s\t%s\tFAIL\n' "$i" "$t" >>"$results"
    done
    log "$name done ($((i + 1))/${#images[@]})"
done

# The table: medians per tool and image, ratios to potrace, median ratio over images.
python3 - "$results" "$parts" "$instructions" "$ntools" "${bins[@]}" -- "${images[@]}" <<'PY'
import os, statistics, sys
results, parts, instr, ntools = sys.argv[1], sys.argv[2], sys.argv[3] == "1", int(sys.argv[4])
sep = sys.argv.index("--")
bins, images = sys.argv[5:sep], sys.argv[sep + 1:]
unit, scale = ("M instr", 1e-6) if instr else ("ms", 1.0)
base = [os.path.basename(b) for b in bins]
labels = base if len(set(base)) == len(base) else bins
times, failed = {}, set()
for line in open(results):
    i, t, v = line.rstrip("\n").split("\t")
    if v == "FAIL":
        failed.add((int(i), int(t)))
    else:
        times.setdefault((int(i), int(t)), []).append(float(v))
decomp = {}
for line in open(parts):
    i, t, v = line.rstrip("\n").split("\t")
    decomp[(int(i), int(t))] = float(v) * scale
def med(i, t):
    if (i, t) in failed or (i, t) not in times:
        return None
    return statistics.median(times[(i, t)]) * scale
head = ["image", f"potrace {unit}"]
for l in labels:
    head += [f"{l} {unit}", f"{l}/potrace"]
    if instr:
        head += [f"{l} decomposition {unit}", "decomposition/potrace"]
print("| " + " | ".join(head) + " |")
print("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
ratios = [[] for _ in bins]
dratios = [[] for _ in bins]
fmt = lambda m: "FAIL" if m is None else f"{m:.2f}"
for i, img in enumerate(images):
    p = med(i, 0)
    row = [os.path.basename(img), fmt(p)]
    for k in range(len(bins)):
        m = med(i, k + 1)
        row.append(fmt(m))
        if m is None or p is None or p == 0:
            row.append("—")
        else:
            ratios[k].append(m / p)
            row.append(f"{m / p:.2f}")
        if instr:
            d = decomp.get((i, k + 1)) if m is not None else None
            row.append("—" if d is None else f"{d:.2f}")
            if d is None or p is None or p == 0:
                row.append("—")
            else:
                dratios[k].append(d / p)
                row.append(f"{d / p:.2f}")
    print("| " + " | ".join(row) + " |")
median = lambda r: f"**{statistics.median(r):.2f}** ({len(r)} images)" if r else "—"
last = ["**median ratio**", ""]
for k in range(len(bins)):
    last += ["", median(ratios[k])]
    if instr:
        last += ["", median(dratios[k])]
print("| " + " | ".join(last) + " |")
PY
