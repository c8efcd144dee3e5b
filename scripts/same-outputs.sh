#!/usr/bin/env bash
# Runs every embedded scene with two builds of `mrdw` and compares the CSVs byte for
# byte; the other files of each report (figures, summary.json without wall times) are
# compared too and listed when they differ, without failing (a redesign may correct the
# recorded stage list, for example).
#
#   scripts/same-outputs.sh BASE_REF [SKIP_REGEX]
#
# BASE_REF is a git revision (built in a temporary worktree); the other build is the
# work tree. SKIP_REGEX names scenes to leave out (default: fig6-full, a 48-minute run,
# and fig6-converged, a study of many CPU hours).
# Exit status 0 when every compared file is identical.
#
# With ONLY set (a regex), only the scenes it matches are run; with BASE_BIN set (a
# built `mrdw` of BASE_REF), that binary is the base and nothing is built for it.
#
# With RTOL set (e.g. RTOL=1e-6), a CSV that differs is compared number by number
# instead: it passes ("close") when every value differs from the base by at most RTOL
# times its column's largest magnitude. Columns of run statistics (iterations, times,
# seconds) are left out of that comparison. For solver changes that move results
# within the solver tolerance.
set -euo pipefail
cd "$(dirname "$0")/.."
base_ref=${1:?usage: scripts/same-outputs.sh BASE_REF [SKIP_REGEX]}
skip=${2:-^(fig6-full|fig6-converged)$}
tmp=$(mktemp -d)
trap 'git worktree remove --force "$tmp/base" >/dev/null 2>&1 || true; rm -rf "$tmp"' EXIT

if [ -n "${BASE_BIN:-}" ]; then
  base_bin=$BASE_BIN
else
  git worktree add --detach "$tmp/base" "$base_ref" >/dev/null
  (cd "$tmp/base" && cargo build --release --quiet --bin mrdw)
  base_bin=$tmp/base/target/release/mrdw
fi
cargo build --release --quiet --bin mrdw
new_bin=$PWD/target/release/mrdw

# summary.json without its timings (keys ending in _s, *seconds*, wall_time*).
untimed() {
  python3 -c '
import json, sys
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items()
                if not (k.endswith("_s") or "seconds" in k or k.startswith("wall_time"))}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
print(json.dumps(strip(json.load(open(sys.argv[1]))), indent=1, sort_keys=True))
' "$1"
}

# Largest column-scaled difference between two CSVs (prints it; exit 1 above RTOL).
close() {
  python3 -c '
import csv, sys
rtol = float(sys.argv[3])
# The header comments (lines starting with #) are not table rows.
rows = lambda f: list(csv.reader(l for l in open(f) if not l.startswith("#")))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
if len(a) != len(b) or a[0] != b[0]:
    print("shape/header differ"); sys.exit(1)
stat = ("iteration", "seconds", "time", "_s ", "(s)")
worst = 0.0
for c, name in enumerate(a[0]):
    if any(w in name.lower() + " " for w in stat):
        continue
    # Cells equal as text (empty ones too) pass; the others must both be numbers.
    pairs = [(r[c], s[c]) for r, s in zip(a[1:], b[1:]) if r[c] != s[c]]
    try:
        pairs = [(float(u), float(v)) for u, v in pairs]
    except ValueError:
        print(f"text column {name} differs"); sys.exit(1)
    if not pairs:
        continue
    numbers = [abs(float(r[c])) for r in a[1:] + b[1:] if r[c] not in ("", "nan")]
    scale = max(numbers + [1e-300])
    worst = max([worst] + [abs(u - v) / scale for u, v in pairs])
print(f"{worst:.1e}")
sys.exit(0 if worst <= rtol else 1)
' "$1" "$2" "${RTOL}"
}

status=0
for scene in $("$new_bin" scenes | awk '{print $1}'); do
  if [[ $scene =~ $skip ]] || { [ -n "${ONLY:-}" ] && ! [[ $scene =~ $ONLY ]]; }; then
    echo "skip  $scene"
    continue
  fi
  if ! "$base_bin" show "$scene" >/dev/null 2>&1; then
    echo "new   $scene (not in $base_ref)"
    continue
  fi
  "$base_bin" run "$scene" --out "$tmp/a/$scene" >/dev/null 2>&1
  "$new_bin" run "$scene" --out "$tmp/b/$scene" >/dev/null 2>&1
  differ=()
  near=()
  d=""
  other=()
  ncsv=0
  for f in "$tmp/a/$scene"/*; do
    name=$(basename "$f")
    g=$tmp/b/$scene/$name
    case $name in
      *.csv)
        ncsv=$((ncsv + 1))
        if ! cmp -s "$f" "$g"; then
          if [ -n "${RTOL:-}" ] && d=$(close "$f" "$g"); then
            near+=("$name ($d)")
          else
            differ+=("$name${d:+ ($d)}")
          fi
        fi ;;
      summary.json)
        diff -q <(untimed "$f") <(untimed "$g") >/dev/null 2>&1 || other+=("$name") ;;
      *) cmp -s "$f" "$g" || other+=("$name") ;;
    esac
  done
  for g in "$tmp/b/$scene"/*.csv; do
    [ -e "$tmp/a/$scene/$(basename "$g")" ] || differ+=("$(basename "$g") (new)")
  done
  note=""
  [ ${#other[@]} -eq 0 ] || note="; other files differ: ${other[*]}"
  if [ ${#differ[@]} -eq 0 ] && [ ${#near[@]} -gt 0 ]; then
    echo "close $scene: ${near[*]}$note"
  elif [ ${#differ[@]} -eq 0 ]; then
    echo "same  $scene ($ncsv CSVs identical$note)"
  else
    echo "DIFF  $scene: ${differ[*]}$note"
    status=1
  fi
done
exit $status
