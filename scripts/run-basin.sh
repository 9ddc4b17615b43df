#!/usr/bin/env bash
# The main job: installs what is missing, builds yuxi in Release, runs the default fish-basin
# scene (or the scene given as the first argument) with the paper's analysis, and plots it.
# Output: runs/<scene name>/ (energies.csv, particles.pvd for ParaView, particles.lammpstrj for
# OVITO, scene.resolved.toml, analysis/*.csv, fig4-fig10 PNGs and report.md; a scene without
# an [analysis] table gets energies.png).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target yuxi

scene=("$@")
name=basin-small
if ((${#scene[@]} > 0)); then name=$(basename "${scene[0]}" .toml); fi
out=runs/$name
build/release/apps/yuxi/yuxi run "${scene[@]}" -o "$out" --overwrite
echo "results in $out (figures and report: $out/report.md)"
