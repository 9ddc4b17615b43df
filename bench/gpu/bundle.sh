#!/usr/bin/env bash
# Packs what the GPU check needs into one folder, for a GPU machine that has the CUDA toolkit
# but none of yuxi's Debian packages: the programs built here, the shared libraries they load
# (all but the C and C++ runtimes, which the other machine has in a newer version), and Open
# MPI's launcher with its plugins, relocatable through OPAL_PREFIX.
#
#   bench/gpu/bundle.sh BUNDLE [BUILD] [CUDA_BUILD]
#
# BUILD is the release build (default build/release), CUDA_BUILD one configured with
# -DYUXI_CUDA=ON (default build/cuda; `cmake --build CUDA_BUILD --target device_chute yuxi
# yuxi_gpu_tests`), for the GPU's architecture alone (-DCMAKE_CUDA_ARCHITECTURES=90 for an H100
# or H200): the bundle travels with the working tree, which may carry 64 MiB in all.
#
# Then on the GPU machine: bench/gpu/device_check.sh OUTDIR BUNDLE.
set -euo pipefail
bundle=${1:?usage: bundle.sh BUNDLE [BUILD]}
build=${2:-build/release}
cuda_build=${3:-build/cuda}
nvcc=${NVCC:-$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)}
multiarch=$(gcc -print-multiarch)
mpi_lib=/usr/lib/$multiarch/openmpi
pmix_lib=/usr/lib/$multiarch/pmix2

rm -rf "$bundle"
mkdir -p "$bundle/bin" "$bundle/lib" "$bundle/mpi/usr/bin" "$bundle/mpi/usr/lib/$multiarch" \
  "$bundle/mpi/usr/share"

"$nvcc" -std=c++20 --expt-relaxed-constexpr --fmad=false -Xcompiler -ffp-contract=off -O3 \
  -arch=sm_90 -Isrc bench/gpu/law_bits.cu -o "$bundle/bin/law_bits"
cp "$build/apps/yuxi/yuxi" "$bundle/bin/"
cp "$cuda_build/bench/device_chute" "$bundle/bin/device_chute_cuda"
cp "$cuda_build/apps/yuxi/yuxi" "$bundle/bin/yuxi_cuda"
cp "$cuda_build/tests/yuxi_gpu_tests" "$bundle/bin/"

cp /usr/bin/orterun /usr/bin/orted "$bundle/mpi/usr/bin/"
ln -s orterun "$bundle/mpi/usr/bin/mpirun"
cp -a "$mpi_lib" "$bundle/mpi/usr/lib/$multiarch/"
cp -a /usr/share/openmpi "$bundle/mpi/usr/share/"
if [[ -d $pmix_lib ]]; then
  mkdir -p "$bundle/mpi/usr/lib/$multiarch/pmix2"
  cp -a "$pmix_lib/lib" "$bundle/mpi/usr/lib/$multiarch/pmix2/"
  rm -f "$bundle/mpi/usr/lib/$multiarch/pmix2/lib/"*.a
fi

{
  ldd "$bundle/bin/yuxi" "$bundle/bin/yuxi_cuda" "$bundle/bin/yuxi_gpu_tests" \
    "$bundle/bin/device_chute_cuda" /usr/bin/orterun /usr/bin/orted
  find "$mpi_lib" "$pmix_lib" -name '*.so*' -exec ldd {} \;
} 2>/dev/null | awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -v -E '/(libc|libm|libstdc\+\+|libgcc_s|libpthread|libdl|librt|ld-linux-x86-64)\.so' |
  xargs cp -L -t "$bundle/lib/"
# (without their symbols: the bundle travels with the working tree, in a limited size)
strip --strip-unneeded "$bundle"/bin/* "$bundle"/lib/*.so* 2>/dev/null || true
git rev-parse HEAD >"$bundle/commit"
du -sh "$bundle"
