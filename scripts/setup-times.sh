#!/usr/bin/env bash
# Writes docs/times.md, the one table of run times every other page links to: the
# README's two set-up commands as a newcomer meets them (a fresh clone of this checkout's
# HEAD, an empty target folder, the cargo registry already downloaded by `cargo fetch`,
# not timed), then `mrdw run SCENE` for every embedded scene as a whole process, each with
# wall and CPU seconds (user + system, all threads), so that a slower or shared machine
# can be told from a fault: a CPU time near the table's with a longer wall time means
# fewer or busier cores. Run it on a quiet machine; review and commit docs/times.md.
#
#   bash scripts/setup-times.sh            # about 80 minutes on 2 cores
#   bash scripts/setup-times.sh --setup    # the two set-up commands alone, about 12 minutes
#
# Not timed (hours; their CPU hours are in their provenance): fig6-full, fig6-converged.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
only_setup=0
[[ ${1:-} == --setup ]] && only_setup=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
git clone -q "$src" "$tmp/clone"
cd "$tmp/clone"
cargo fetch --locked >/dev/null 2>&1
cpu=$(grep -m1 "model name" /proc/cpuinfo 2>/dev/null | cut -d: -f2 | xargs || true)
cores=$(nproc)
TIMEFORMAT='%R %U %S'
rows=()
human() { awk -v s="$1" 'BEGIN { s = int(s + 0.5); if (s < 60) printf "%d s", s;
    else printf "%d min %d s", s / 60, s % 60 }'; }
run() {
    local label=$1
    shift
    local t
    t=$( { time "$@" >"$tmp/log" 2>&1; } 2>&1 ) || {
        echo "$label failed:" >&2
        tail -20 "$tmp/log" >&2
        exit 1
    }
    read -r wall user sys <<<"$t"
    local cpu_s
    cpu_s=$(awk "BEGIN { print $user + $sys }")
    printf '%-44s %8.1f s wall %8.1f s CPU\n' "$label" "$wall" "$cpu_s" >&2
    rows+=("| $label | $(human "$wall") | $(human "$cpu_s") |")
    echo "$wall" >>"$tmp/walls"
}
run '`cargo run --release -- run`' cargo run --release -- run
run '`cargo test --workspace --release`' cargo test --workspace --release
both=$(human "$(awk '{ s += $1 } END { print s }' "$tmp/walls")")
setup_rows=("${rows[@]}")
rows=()
if ((!only_setup)); then
    for scene in $(target/release/mrdw scenes | awk '{ print $1 }'); do
        case $scene in fig6-full | fig6-converged) continue ;; esac
        run "\`$scene\`" target/release/mrdw run "$scene" --out "$tmp/reports/$scene" \
            --work "$tmp/work/$scene"
    done
fi
out="$src/docs/times.md"
{
    echo "# Run times"
    echo
    echo "The one table of run times: every other page links here. Written by"
    echo "\`bash scripts/setup-times.sh\` on $(date -u +%Y-%m-%d), ${cpu:-unknown CPU}, $cores cores,"
    echo "nothing else running. CPU time is user + system over all threads: on a machine"
    echo "with other cores or other load, the CPU time should stay near these and the wall"
    echo "time moves; a CPU time far above the table's points to a fault, not the machine."
    echo
    echo "## The README's set-up commands (fresh clone, empty target folder)"
    echo
    echo "| command | wall | CPU |"
    echo "|---|---|---|"
    printf '%s\n' "${setup_rows[@]}"
    echo
    echo "Both, one after the other: $both wall."
    if ((!only_setup)); then
        echo
        echo "## Every embedded scene (\`mrdw run SCENE\`, all cores, $(date -u +%Y-%m-%d))"
        echo
        echo "| scene | wall | CPU |"
        echo "|---|---|---|"
        printf '%s\n' "${rows[@]}"
        echo
        echo "Not timed here: \`fig6-full\` and \`fig6-converged\` take hours (resumable;"
        echo "the CPU hours of the committed checkpoints are in compare/data/fig6-converged/)."
    elif [[ -f $out ]]; then
        # Keep the scene table of the last full run, under its own date.
        sed -n '/^## Every embedded scene/,$p' "$out" >"$tmp/scenes"
        if [[ -s $tmp/scenes ]]; then
            echo
            echo "(The scene table below is from the last full run of the script.)"
            echo
            cat "$tmp/scenes"
        fi
    fi
} >"$tmp/times.md"
mv "$tmp/times.md" "$out"
echo "wrote $out" >&2
