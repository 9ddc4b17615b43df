#!/usr/bin/env bash
# Installs the Debian packages yuxi builds and runs with, if any is missing.
# Needs root (or sudo) and the Debian package registry.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libtomlplusplus-dev libcli11-dev libfmt-dev libspdlog-dev libboost-dev
  libgtest-dev libgmock-dev libbenchmark-dev libthrust-dev
  libopenmpi-dev openmpi-bin
  python3 python3-matplotlib python3-numpy python3-pytest python3-mpi4py
  pybind11-dev python3-pybind11
  clang-format zlib1g-dev clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi
echo "installing: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
