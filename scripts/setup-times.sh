#!/usr/bin/env bash
# The README's two set-up commands timed as a newcomer meets them: a fresh clone of this
# checkout's HEAD, an empty target folder, the cargo registry already downloaded
# (`cargo fetch`, not timed), nothing else running. Prints the wall and CPU time of each
# command, their sum and the CPU; run it before changing the times the README states.
#
#   bash scripts/setup-times.sh            # about 11 minutes on 2 cores (Intel Xeon)
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
git clone -q "$src" "$tmp/clone"
cd "$tmp/clone"
cargo fetch --locked >/dev/null 2>&1
cpu=$(grep -m1 "model name" /proc/cpuinfo 2>/dev/null | cut -d: -f2 | xargs || true)
echo "CPU: ${cpu:-unknown}, $(nproc) cores; commit $(git rev-parse --short HEAD)"
TIMEFORMAT='%R %U %S'
run() {
    local label=$1
    shift
    local t
    t=$( { time "$@" >"$tmp/$label.log" 2>&1; } 2>&1 ) || {
        echo "$label failed:" >&2
        tail -20 "$tmp/$label.log" >&2
        exit 1
    }
    read -r wall user sys <<<"$t"
    printf '%-34s %6.0f s wall, %6.0f s CPU\n' "$label" "$wall" "$(awk "BEGIN { print $user + $sys }")"
    echo "$wall" >>"$tmp/walls"
}
run "cargo run --release -- run" cargo run --release -- run
run "cargo test --workspace --release" cargo test --workspace --release
printf '%-34s %6.0f s wall\n' "both, one after the other" "$(awk '{ s += $1 } END { print s }' "$tmp/walls")"
