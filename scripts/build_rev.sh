#!/usr/bin/env bash
# scripts/build_rev.sh — the layertrace binary of an earlier commit, to time side by side.
#
# Usage: scripts/build_rev.sh REV…
#   REV: anything git names a commit by (a hash, a tag, HEAD~3). Prints one absolute path per
#   REV on standard output: target/revs/HASH/layertrace (HASH the commit's first 12 hex digits).
#
# Each commit's tree is exported with `git archive` (no worktree is registered) into a
# scratch folder and built there with that commit's own Cargo.toml and Cargo.lock
# (`cargo build --release --locked --bin layertrace`: the plain release build its README
# gave, no profile-guided or static build), then only the binary is kept and the scratch
# folder removed (a build's target/ takes 1–2 GB). A binary already built is reused.
#
# For the speed issues' "measured side by side in one run" against an earlier build:
#   scripts/time_vs_potrace.sh --runs 7 $(scripts/build_rev.sh f9e379f) target/release/layertrace \
#       -- ../shared/samples/*.png
# (f9e379f is the build the issue "Exact in the renderers people use" measured its 2.7× on.)
set -euo pipefail

usage() { sed -n '4,6s/^# \{0,1\}//p' "$0" >&2; exit 2; }
[ $# -gt 0 ] || usage
case "$1" in -h|--help) sed -n '4,6s/^# \{0,1\}//p' "$0"; exit 0 ;; esac

cd "$(dirname "$0")/.."
root=$PWD
log() { echo "build_rev.sh: $*" >&2; }
for rev in "$@"; do
    hash=$(git rev-parse --verify --quiet "$rev^{commit}") || { log "not a commit: $rev"; exit 2; }
    short=${hash:0:12}
    out="$root/target/revs/$short"
    if [ -x "$out/layertrace" ]; then
        echo "$out/layertrace"
        continue
    fi
    mkdir -p "$out"
    work=$(mktemp -d "$out/build.XXXXXX")
    trap 'rm -rf "$work"' EXIT
    git archive "$hash" | tar -x -C "$work"
    locked=()
    [ -f "$work/Cargo.lock" ] && locked=(--locked)
    log "building $short (about two minutes)"
    # (Its own target folder, whatever CARGO_TARGET_DIR the caller has set.)
    (cd "$work" && CARGO_TARGET_DIR="$work/target" \
        cargo build --release "${locked[@]}" --quiet --bin layertrace)
    # Copied under a temporary name and renamed: an interrupted build leaves no binary to reuse.
    cp "$work/target/release/layertrace" "$out/layertrace.part"
    mv "$out/layertrace.part" "$out/layertrace"
    rm -rf "$work"
    trap - EXIT
    echo "$out/layertrace"
done
