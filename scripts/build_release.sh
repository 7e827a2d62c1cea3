#!/usr/bin/env bash
# scripts/build_release.sh — builds the `layertrace` binary as we ship and measure it; prints
# its path on standard output (the build's progress on standard error).
#
# Usage: scripts/build_release.sh
#
# On Linux with glibc (`*-unknown-linux-gnu`) the binary is linked statically (static-pie:
# glibc, libm and libgcc inside, no dynamic loader at start-up), which saves 0.4–0.7 ms per
# process on a 2-core VM — 7–11% of a glyph's whole run, measured side by side with
# `scripts/time_vs_potrace.sh` (BENCHMARKS.md, "The shipped binary linked statically"). Cargo can only ask for that
# per target: `--target HOST` with the flag set for that target keeps it away from the
# proc-macro crates and build scripts, which are built for the host separately. The binary
# lands in target/HOST/release/. Elsewhere, or when the static link fails (no libc.a), it is
# the plain `cargo build --release` binary in target/release/.
set -euo pipefail
cd "$(dirname "$0")/.."

host=$(rustc -vV | sed -n 's/^host: //p')
case "$host" in
    *-unknown-linux-gnu)
        if cargo build --release --locked --bin layertrace --target "$host" \
            --config "target.$host.rustflags = [\"-C\", \"target-feature=+crt-static\"]" >&2; then
            echo "$PWD/target/$host/release/layertrace"
            exit 0
        fi
        echo "build_release.sh: the static link failed; building the dynamic binary" >&2
        ;;
esac
cargo build --release --locked --bin layertrace >&2
echo "$PWD/target/release/layertrace"
