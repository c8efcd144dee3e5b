#!/usr/bin/env bash
# Regenerates the figures docs/results.md shows for the 3D answers to the paper's
# adhesion and tangential claims (Sections 5-7): runs each scene below into
# reports/<scene>/ and copies its figures to docs/figures/<scene>/. About 70 minutes on
# 2 cores (the rough partial-slip, rough-slip and rough-adhesion scenes are most of it). Review and
# commit the diff.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin mrdw
scenes=(adhesion-3d adhesion-tabor rough-adhesion-3d rough-adhesion-3d-punch tangential-3d tangential-3d-free tangential-viscoelastic-3d tangential-stiffness-3d rough-partial-slip-3d rough-slip-3d rough-slip-3d-punch)
for scene in "${scenes[@]}"; do
  target/release/mrdw run "$scene" --out "reports/$scene" >/dev/null
  mkdir -p "docs/figures/$scene"
  cp "reports/$scene"/*.png "docs/figures/$scene/"
  echo "docs/figures/$scene/: $(cd "docs/figures/$scene" && ls *.png | xargs)"
done
