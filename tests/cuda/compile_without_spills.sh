#!/usr/bin/env bash
# Compiles a CUDA source for sm_90 as the CUDA build does (C++20, FMA contraction off, every
# warning an error) and fails if a kernel of yuxi's spills registers to local memory. CUDA's own
# helpers (`__cuda_*`, such as the slow path of correctly rounded double division) are named but
# not counted: they are NVIDIA's. Compile only: no GPU is needed.
#   compile_without_spills.sh NVCC SOURCE OBJECT -I...
set -euo pipefail
nvcc=$1 source=$2 object=$3
shift 3
log=$(mktemp)
trap 'rm -f "$log"' EXIT
"$nvcc" -x cu -std=c++20 --expt-relaxed-constexpr --fmad=false --Werror all-warnings \
  -Xcompiler=-ffp-contract=off -O3 -arch=sm_90 -Xptxas=-v "$@" -c "$source" -o "$object" \
  2> "$log" || { cat "$log"; exit 1; }
awk '
  /Function properties for/ { name = $NF; next }
  /bytes spill stores/ {
    stores = $5 + 0
    if (stores > 0) {
      if (name ~ /^__cuda_/) print "spills (NVIDIA helper, not counted): " name
      else { print "SPILLS: " name ": " $0; bad = 1 }
    }
  }
  END { exit bad }
' "$log"
echo "$(grep -c 'Compiling entry function' "$log") kernels compiled, none of yuxi's spills"
