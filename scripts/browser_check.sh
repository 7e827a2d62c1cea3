#!/usr/bin/env bash
# scripts/browser_check.sh — how layertrace's SVGs look in resvg and in Chromium.
#
# Usage: scripts/browser_check.sh [-m MODEL]... OUT_DIR IMAGE...
#   -m MODEL  line, circle, conic or poly:D (repeatable; default: line circle conic poly:3).
#
# For each image and model: runs the release binary (`-o OUT_DIR/NAME-MODEL.svg --report`,
# default options otherwise), which renders the SVG with the resvg crate (crispEdges) and
# counts differing pixels and staircases; then renders the SVG in headless Chromium at 1:1
# with shape-rendering="crispEdges" set on the root element (OUT_DIR/NAME-MODEL.chromium.png,
# exactly the image's size, white background) and compares it with the image's mask with
# examples/mask_diff.rs (the library's own loader: foreground is luma < 128), the
# differences going to OUT_DIR/NAME-MODEL.chromium-diff.png (missing red, extra blue).
# Prints a markdown table on standard output: per image and model, then totals per model.
#
# Installs Debian's chromium with apt-get (as root) if neither chromium nor $CHROMIUM is
# there.
set -euo pipefail

cd "$(dirname "$0")/.."
models=()
while [ $# -gt 0 ]; do
    case "$1" in
        -m|--model) models+=("$2"); shift 2 ;;
        -h|--help) sed -n '4,5s/^# \{0,1\}//p' "$0"; exit 0 ;;
        *) break ;;
    esac
done
if [ $# -lt 2 ]; then
    sed -n '4,5s/^# \{0,1\}//p' "$0" >&2
    exit 2
fi
[ ${#models[@]} -gt 0 ] || models=(line circle conic poly:3)
out=$1
shift
mkdir -p "$out"

log() { echo "browser_check.sh: $*" >&2; }

chromium=${CHROMIUM:-chromium}
if ! command -v "$chromium" >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        log "installing chromium (apt-get)"
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; } >&2
    else
        log "chromium missing and cannot apt-get install it (not root or no apt-get)"
        exit 1
    fi
fi
log "$("$chromium" --version 2>/dev/null || echo "$chromium")"

log "building layertrace and examples/mask_diff.rs (release)"
cargo build --release --quiet --bin layertrace --example mask_diff >&2
bin=target/release/layertrace
mask_diff=target/release/examples/mask_diff

profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT

# Renders SVG ($1) at $3 x $4 pixels into PNG ($2).
screenshot() {
    local page
    page=$(mktemp --suffix=.svg -p "$profile")
    # Inherited by every path of the document, unless one says otherwise.
    sed '0,/<svg /s//<svg shape-rendering="crispEdges" /' "$1" >"$page"
    rm -f "$2"
    "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
        --hide-scrollbars --force-device-scale-factor=1 --disable-quic --no-first-run \
        --disable-component-update --disable-sync --user-data-dir="$profile/user" \
        --window-size="$3,$4" --screenshot="$(realpath -m "$2")" "file://$(realpath "$page")" \
        >/dev/null 2>&1 || true
    rm -f "$page"
    [ -s "$2" ]
}

echo "| image | model | differing px, resvg | differing px, Chromium | commands | staircase runs / segments | bytes |"
echo "|---|---|---:|---:|---:|---:|---:|"
declare -A missing t_resvg t_chrome t_cmds t_runs t_segs t_bytes
for m in "${models[@]}"; do
    t_resvg[$m]=0; t_chrome[$m]=0; missing[$m]=""; t_cmds[$m]=0; t_runs[$m]=0; t_segs[$m]=0; t_bytes[$m]=0
done
for img in "$@"; do
    name=$(basename "${img%.*}")
    for m in "${models[@]}"; do
        base="$out/$name-${m//:/}"
        report=$("$bin" "$img" -m "$m" -o "$base.svg" --report -q 2>&1)
        resvg=$(sed -n 's/^fidelity: \([0-9]*\) differing.*/\1/p' <<<"$report")
        bytes=$(sed -n 's/^svg: \([0-9]*\) bytes, \([0-9]*\) commands.*/\1/p' <<<"$report")
        cmds=$(sed -n 's/^svg: \([0-9]*\) bytes, \([0-9]*\) commands.*/\2/p' <<<"$report")
        runs=$(sed -n 's/^staircases: \([0-9]*\) runs, \([0-9]*\) segments.*/\1/p' <<<"$report")
        segs=$(sed -n 's/^staircases: \([0-9]*\) runs, \([0-9]*\) segments.*/\2/p' <<<"$report")
        read -r w h < <(python3 -c 'import re,sys; s=open(sys.argv[1]).read(); m=re.search(r"<svg[^>]*\swidth=\"(\d+)\"[^>]*\sheight=\"(\d+)\"", s); print(m[1], m[2])' "$base.svg")
        chrome="n/a"
        if screenshot "$base.svg" "$base.chromium.png" "$w" "$h"; then
            if d=$("$mask_diff" "$img" "$base.chromium.png" "$base.chromium-diff.png"); then
                chrome=${d%% *}
                t_chrome[$m]=$((t_chrome[$m] + chrome))
            else
                log "$name $m: screenshot not comparable"
            fi
        else
            log "$name $m: no screenshot"
        fi
        [ "$chrome" != "n/a" ] || missing[$m]=" (n/a rows left out)"
        echo "| $name | $m | $resvg | $chrome | $cmds | $runs / $segs | $bytes |"
        t_resvg[$m]=$((t_resvg[$m] + resvg)); t_cmds[$m]=$((t_cmds[$m] + cmds))
        t_runs[$m]=$((t_runs[$m] + runs)); t_segs[$m]=$((t_segs[$m] + segs))
        t_bytes[$m]=$((t_bytes[$m] + bytes))
    done
done
echo
echo "Totals over $# images:"
echo
echo "| model | differing px, resvg | differing px, Chromium | commands | staircase runs / segments | bytes |"
echo "|---|---:|---:|---:|---:|---:|"
for m in "${models[@]}"; do
    echo "| $m | ${t_resvg[$m]} | ${t_chrome[$m]}${missing[$m]} | ${t_cmds[$m]} | ${t_runs[$m]} / ${t_segs[$m]} | ${t_bytes[$m]} |"
done
