#!/usr/bin/env bash
# Regenerates the figures docs/results.md shows, one folder per scene in docs/figures/:
# runs each scene below into reports/<scene>/ and copies its figures (all of them, or
# the key ones named after the scene). lambda(H) is rendered from the study's committed
# checkpoints (compare/data/fig6-converged; its MRD ensembles, not committed, are
# recomputed first: about two CPU-minutes); every other scene is run in full. About 100
# minutes on 2 cores (the rough partial-slip, rough-slip, rough-adhesion and Eq. (93)
# scenes are most of it). Review and commit the diff.
#
#   scripts/docs-figures.sh [SCENE...]    # default: every scene below
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin mrdw
# scene[:figure,figure,...] (no list: every figure of the report).
all=(
  fig6-converged:lambda_study_lambda_vs_bandwidth.png,lambda_study_scatter_quantiles.png
  fig6-large:hurst_sweep_fig6.png,hurst_sweep_lambda.png
  fig7-3d:sliding_friction_3d.png
  static-friction-3d:static_friction_3d_periodic.png,static_friction_3d_disc.png
  rough-sphere:rough_sphere_stiffness.png,rough_sphere_radius.png
  viscoelastic-rough:viscoelastic_rough_radok.png,viscoelastic_rough_approach.png
  adhesion-3d adhesion-tabor adhesion-tabor-exponential rough-adhesion-3d
  rough-adhesion-3d-punch tangential-3d
  tangential-3d-free tangential-viscoelastic-3d tangential-stiffness-3d
  rough-partial-slip-3d rough-slip-3d rough-slip-3d-punch
  calibrate-rolloff:curves.png,curves_4.png
  plastic-sphere plastic-cone rough-plastic-3d impact ring-down ring-down-wave:ring_down_wave.png,normal_wave.png friction-forced oblique-impact oblique-impact-spin:oblique_rebound.png oblique-cycle contact-resonance
  rough-ring-down:rough_damping.png,rough_damping_mrd_over_3d.png,rough_loss_ratio.png
  forced-resonance
  viscoelastic-impact adhesive-impact references
)
wanted=("$@")
for entry in "${all[@]}"; do
  scene=${entry%%:*}
  if ((${#wanted[@]})) && [[ ! " ${wanted[*]} " =~ " $scene " ]]; then
    continue
  fi
  if [[ $scene == fig6-converged ]]; then
    target/release/mrdw run "$scene" --out "reports/$scene" --work compare/data/fig6-converged \
      --report-only >/dev/null
  else
    target/release/mrdw run "$scene" --out "reports/$scene" >/dev/null
  fi
  mkdir -p "docs/figures/$scene"
  if [[ $entry == *:* ]]; then
    IFS=, read -r -a figures <<<"${entry#*:}"
    for f in "${figures[@]}"; do cp "reports/$scene/$f" "docs/figures/$scene/"; done
  else
    cp "reports/$scene"/*.png "docs/figures/$scene/"
  fi
  echo "docs/figures/$scene/: $(cd "docs/figures/$scene" && ls *.png | xargs)"
done
bash scripts/docs-gallery.sh
