#!/usr/bin/env bash
# scripts/compare.sh — side-by-side comparison of layertrace with potrace and vtracer.
#
# Usage: scripts/compare.sh [--big] [--runs N] [IMAGE…]
#   default images: every samples/*.png except syn_big3000_many_shapes.png;
#   --big also runs samples/syn_big3000_many_shapes.png; --runs N timed runs (default 5).
#
# Installs what is missing (Debian, as root): potrace with apt-get, vtracer with
# `cargo install vtracer --locked` into target/tools. Needs no network once both are there
# and the crate builds. Then builds layertrace as shipped (scripts/build_release.sh: static on
# Linux with glibc; $LAYERTRACE, if set, is timed instead) and examples/compare.rs (release),
# and prints the markdown tables on standard output (progress on standard error).
set -euo pipefail

cd "$(dirname "$0")/.."
VTRACER_VERSION=0.6.5
TOOLS=target/tools

big=0
runs=5
images=()
while [ $# -gt 0 ]; do
    case "$1" in
        --big) big=1 ;;
        --runs) runs="$2"; shift ;;
        -h|--help) sed -n '4,6s/^# \{0,1\}//p' "$0"; exit 0 ;;
        *) images+=("$1") ;;
    esac
    shift
done
if [ ${#images[@]} -eq 0 ]; then
    for f in samples/*.png; do
        [ "$(basename "$f")" = syn_big3000_many_shapes.png ] || images+=("$f")
    done
    if [ "$big" = 1 ]; then images+=(samples/syn_big3000_many_shapes.png); fi
fi

log() { echo "compare.sh: $*" >&2; }

# potrace, from Debian's packages.
if ! command -v potrace >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        log "installing potrace (apt-get)"
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq potrace; } >&2 \
            || log "could not install potrace; its rows will be skipped"
    else
        log "potrace missing and cannot apt-get install it (not root or no apt-get); its rows will be skipped"
    fi
fi

# vtracer, from crates.io, into target/tools (kept between runs).
if [ ! -x "$TOOLS/bin/vtracer" ]; then
    log "installing vtracer $VTRACER_VERSION into $TOOLS (cargo install)"
    cargo install vtracer --version "$VTRACER_VERSION" --locked --root "$TOOLS" >&2 \
        || log "could not install vtracer; its rows will be skipped"
fi

log "building layertrace as shipped (scripts/build_release.sh) and the compare example (release)"
LAYERTRACE="${LAYERTRACE:-$(scripts/build_release.sh)}"
export LAYERTRACE
cargo build --release --example compare >&2

if [ -x "$TOOLS/bin/vtracer" ]; then export VTRACER="${VTRACER:-$TOOLS/bin/vtracer}"; fi
exec target/release/examples/compare --runs "$runs" --work target/compare "${images[@]}"
