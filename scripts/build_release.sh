#!/usr/bin/env bash
# scripts/build_release.sh — builds the `layertrace` binary as we ship and measure it; prints
# its path on standard output (the build's progress on standard error).
#
# Usage: scripts/build_release.sh        (LAYERTRACE_PGO=0: without the profile, below)
#
# On Linux with glibc (`*-unknown-linux-gnu`) the binary is linked statically (static-pie:
# glibc, libm and libgcc inside, no dynamic loader at start-up), which saves 0.4–0.7 ms per
# process on a 2-core VM — 7–11% of a glyph's whole run, measured side by side with
# `scripts/time_vs_potrace.sh` (BENCHMARKS.md, "The shipped binary linked statically"). Cargo can only ask for that
# per target: `--target HOST` with the flag set for that target keeps it away from the
# proc-macro crates and build scripts, which are built for the host separately. The binary
# lands in target/HOST/release/. Elsewhere, or when the static link fails (no libc.a), it is
# the plain `cargo build --release` binary in target/release/.
#
# Profile-guided (PGO), there too: a first build instrumented by rustc (`-Cprofile-generate`,
# in target/pgo/) converts the training images — samples/ipol/*.png with the conic, line,
# circle and poly:3 models, samples/colour/*.png, and a generated 1100×800 image
# (scripts/pgo_training_image.awk: wider than 512 px, so the code that cuts curves at
# Chromium's tiles is trained too) — none of the 16 bundled samples that
# the speed comparisons measure; `llvm-profdata` merges the counts, and the shipped binary
# is built with them (`-Cprofile-use`): the same SVG bytes (the code is the same, laid out
# and inlined by the counts), 5% fewer instructions (BENCHMARKS.md, stop 47). It needs the
# `llvm-profdata` of rustc's LLVM version (`llvm-profdata-N`, Debian's package `llvm-N`,
# installed with apt-get when missing and run as root); without it, or when any step
# fails, the binary is built without the profile, as is asked with LAYERTRACE_PGO=0.
set -euo pipefail
cd "$(dirname "$0")/.."

log() { echo "build_release.sh: $*" >&2; }

host=$(rustc -vV | sed -n 's/^host: //p')

# The llvm-profdata whose LLVM major version is rustc's (the profile formats must match),
# installed from Debian's packages when missing; prints its path, or nothing.
profdata_tool() {
    local major
    major=$(rustc -vV | sed -n 's/^LLVM version: \([0-9]*\).*/\1/p')
    [ -n "$major" ] || return 0
    if ! command -v "llvm-profdata-$major" >/dev/null 2>&1 \
        && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        log "installing llvm-$major for llvm-profdata-$major (apt-get)"
        { apt-get install -y -qq "llvm-$major" \
            || { apt-get update -qq && apt-get install -y -qq "llvm-$major"; }; } >&2 \
            || true
    fi
    command -v "llvm-profdata-$major" 2>/dev/null || true
}

# The merged profile of the training runs (path on standard output), or nothing.
train() {
    local flags="$1" tool dir bin
    tool=$(profdata_tool)
    if [ -z "$tool" ]; then
        log "no llvm-profdata for rustc's LLVM: building without a profile"
        return 0
    fi
    dir="$PWD/target/pgo"
    rm -rf "$dir/raw"
    mkdir -p "$dir/raw"
    log "instrumented build (target/pgo)"
    CARGO_TARGET_DIR="$dir/build" cargo build --release --locked --bin layertrace \
        --target "$host" \
        --config "target.$host.rustflags = [$flags, \"-Cprofile-generate=$dir/raw\"]" >&2 \
        || return 0
    bin="$dir/build/$host/release/layertrace"
    log "training runs (samples/ipol, samples/colour, a generated 1100×800 image)"
    local f m
    for f in samples/ipol/*.png; do
        for m in conic line circle poly:3; do
            "$bin" "$f" -o "$dir/out.svg" --model "$m" --threads 1 -q >&2 || return 0
        done
    done
    for f in samples/colour/*.png; do
        "$bin" "$f" -o "$dir/out.svg" --threads 1 -q >&2 || return 0
    done
    # One image larger than Chromium's 512-px tiles, so the code that cuts curves at the
    # tiles' sides is trained too.
    awk -f scripts/pgo_training_image.awk > "$dir/large.pbm" || return 0
    "$bin" "$dir/large.pbm" -o "$dir/out.svg" --threads 1 -q >&2 || return 0
    "$tool" merge -o "$dir/merged.profdata" "$dir/raw" >&2 || return 0
    # Named by its content: cargo sees new flags (and rebuilds) whenever the profile changes.
    local sum
    sum=$(cksum < "$dir/merged.profdata" | cut -d' ' -f1)
    mv "$dir/merged.profdata" "$dir/merged-$sum.profdata"
    echo "$dir/merged-$sum.profdata"
}

case "$host" in
    *-unknown-linux-gnu)
        static='"-C", "target-feature=+crt-static"'
        flags="$static"
        if [ "${LAYERTRACE_PGO:-1}" != 0 ]; then
            profile=$(train "$static")
            if [ -n "$profile" ]; then
                flags="$static, \"-Cprofile-use=$profile\""
            fi
        fi
        if cargo build --release --locked --bin layertrace --target "$host" \
            --config "target.$host.rustflags = [$flags]" >&2; then
            echo "$PWD/target/$host/release/layertrace"
            exit 0
        fi
        if [ "$flags" != "$static" ]; then
            log "the build with the profile failed; building without it"
            if cargo build --release --locked --bin layertrace --target "$host" \
                --config "target.$host.rustflags = [$static]" >&2; then
                echo "$PWD/target/$host/release/layertrace"
                exit 0
            fi
        fi
        log "the static link failed; building the dynamic binary"
        ;;
esac
cargo build --release --locked --bin layertrace >&2
echo "$PWD/target/release/layertrace"
