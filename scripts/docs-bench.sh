#!/usr/bin/env bash
# Regenerates the run-time-against-error table of docs/performance.md and figures from
# `mrdw bench report` (about 3 minutes on 2 cores): runs the report into reports/bench/,
# copies its figures to docs/bench/ and replaces the table between docs/performance.md's
# bench-summary markers with the report's bench_summary.md. Review and commit the diff.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin mrdw
target/release/mrdw bench report --out reports/bench
mkdir -p docs/bench
cp reports/bench/*.png docs/bench/
python3 - <<'PY'
import re
page = open("docs/performance.md").read()
table = open("reports/bench/bench_summary.md").read()
table = re.sub(r"<!--.*?-->\n\n", "", table, flags=re.S)
start = "<!-- bench-summary:start (scripts/docs-bench.sh) -->\n"
end = "<!-- bench-summary:end -->\n"
i, j = page.index(start) + len(start), page.index(end)
open("docs/performance.md", "w").write(page[:i] + table + page[j:])
PY
echo "docs/performance.md table and docs/bench/ updated from reports/bench/ ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs))"
