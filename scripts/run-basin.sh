#!/usr/bin/env bash
# The main job: installs what is missing, builds yuxi in Release, runs the default fish-basin
# scene (or the scene given as the first argument) and plots its energies.
# Output: runs/<scene name>/ (energies.csv, energies.png, particles.pvd for ParaView,
# particles.lammpstrj for OVITO, scene.resolved.toml).
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
# Debian's matplotlib belongs to the system interpreter, whatever python3 is first on PATH.
/usr/bin/python3 scripts/plot_energy.py "$out/energies.csv" "$out/energies.png"
echo "results in $out (energy plot: $out/energies.png)"
