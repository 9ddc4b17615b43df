#!/usr/bin/env bash
# The GPU check: everything to run on a machine with an NVIDIA GPU, in one go, in a few minutes.
#
#   bench/gpu/device_check.sh OUTDIR [BUNDLE]
#
# BUNDLE (default .gpu) is the folder that bench/gpu/bundle.sh made on the build machine: the
# programs and the shared libraries they need, for a GPU machine with the CUDA toolkit but none of
# yuxi's Debian packages. Everything goes to OUTDIR:
#   env.txt        the device, driver, toolkit, commit and machine;
#   law_bits.txt   every contact law on the GPU against the CPU, bit for bit, over carried state,
#                  and where the device's sqrt, division, exp, log, pow, sin, cos, cbrt differ
#                  from the host's libm (bench/gpu/law_bits.cu);
#   sanitizer.txt  compute-sanitizer memcheck and racecheck on a short law_bits run;
#   gpu_tests.txt  the ctest label `gpu` (tests/gpu/, yuxi_gpu_tests): the chute under every
#                  contact law, the shaken small basin and a whole run folder, on the GPU and in
#                  the host build on this machine's CPU, bit for bit;
#   references.txt the GPU's run folders against the stored references of the host build
#                  (tests/regression/references.sh, cases device-c1 and device-basin): the
#                  chute and the small basin with its analysis, byte for byte;
#   engine.txt     the device engine's speed: LAMMPS's 32k chute, the chute replicated to 960k
#                  grains, the paper basin to 10.5 tau, and a bed of rods (clumps) beside
#                  spheres of their volume, on the GPU;
#   engine_sanitizer.txt  compute-sanitizer memcheck and racecheck on a short GPU chute run;
#   run.txt        `yuxi run --device gpu` on the chute: its run folder against `--device host`
#                  on this machine's CPU (energies.csv byte for byte), and a run resumed on the
#                  GPU from its checkpoint against the run straight through;
#   cpu_chute.txt  yuxi's CPU engine on this machine's cores, the 32k chute on 1 rank and on one
#                  rank per core: the baseline that the device engine is measured against.
# Each part has a time limit, so the whole stays under 9 minutes (3.5 as measured on an H100); a
# part that fails is logged and the others still run. The exit status is law_bits's (1: a law
# differs between the sides). YUXI_CHECK_PARTS names the parts to run, for a second look within
# the same minutes (default: all, in the order above):
#   YUXI_CHECK_PARTS="gpu_tests references engine run" bench/gpu/device_check.sh OUT
# shellcheck disable=SC2317 # the parts are called through "part_$part"
set -uo pipefail
out=${1:?usage: device_check.sh OUTDIR [BUNDLE]}
bundle=$(realpath "${2:-.gpu}")
mkdir -p "$out"
out=$(realpath "$out")

export PATH=$bundle/bin:$bundle/mpi/usr/bin:/usr/local/cuda/bin:$PATH
export LD_LIBRARY_PATH=$bundle/lib:$bundle/mpi/usr/lib/x86_64-linux-gnu/openmpi/lib:/usr/local/cuda/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export OPAL_PREFIX=$bundle/mpi/usr
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMP_NUM_THREADS=1
cores=$(grep -c ^processor /proc/cpuinfo)

part_env() {
  echo "date: $(date -u +%FT%TZ)"
  echo "commit: $(cat "$bundle/commit" 2>/dev/null || git rev-parse HEAD)"
  echo "host: $(uname -srm), $cores cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)"
  grep PRETTY_NAME /etc/os-release
  ldd --version | head -1
  nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm,clocks.max.mem --format=csv
  nvcc --version | tail -2
  compute-sanitizer --version | head -2
  mpirun --version | head -1
}

status=0
part_law_bits() {
  timeout 150 law_bits 1048576 8
  status=$?
  echo "exit $status"
}

part_sanitizer() {
  echo "== memcheck"
  timeout 90 compute-sanitizer --tool memcheck --leak-check full law_bits 16384 2 2>&1 | tail -4
  echo "== racecheck"
  timeout 60 compute-sanitizer --tool racecheck law_bits 4096 1 2>&1 | tail -3
}

part_gpu_tests() {
  YUXI_SCENES_DIR=$PWD/scenes timeout 180 yuxi_gpu_tests
  echo "exit $?"
}

part_references() {
  for case in device-c1 device-basin; do
    YUXI_DEVICE=gpu timeout 90 tests/regression/references.sh "$bundle/bin/yuxi_cuda" mpirun \
      "$case" /tmp/yuxi-references
    echo "$case: exit $?"
  done
}

part_engine() {
  echo "== GPU, 32k chute, 1000 steps"
  timeout 120 device_chute_cuda scenes/chute-lammps.toml 1000 --cuda
  echo "== GPU, chute replicated 5 x 6 (960k grains), 2000 steps"
  timeout 120 device_chute_cuda scenes/chute-lammps.toml 2000 --cuda --replicate 5 6 1
  echo "== GPU, the paper basin (scenes/basin-paper.toml), 105,000 steps: t = 0 to 10.5 tau"
  timeout 200 device_chute_cuda scenes/basin-paper.toml 105000 --cuda
  echo "== GPU, clumps: the rod bed tiled 16 x 16 (179,200 particles, 51,200 rods), 4000 steps;"
  echo "   then the same with each rod a sphere of its volume (a member's cost in spheres)"
  timeout 60 device_chute_cuda scenes/clumps/rod-bed.toml 4000 --cuda --replicate 16 16 1
  timeout 60 device_chute_cuda scenes/clumps/rod-bed-spheres.toml 4000 --cuda --replicate 16 16 1
}

part_engine_sanitizer() {
  echo "== memcheck, 20 steps"
  timeout 120 compute-sanitizer --tool memcheck device_chute_cuda scenes/chute-lammps.toml 20 --cuda 2>&1 | tail -4
  echo "== racecheck, 5 steps"
  timeout 90 compute-sanitizer --tool racecheck device_chute_cuda scenes/chute-lammps.toml 5 --cuda 2>&1 | tail -3
}

# yuxi run on the GPU: 1,000 steps of the chute into a run folder, the same on this CPU through
# the host build, and the GPU run again in two halves through a checkpoint.
run_chute() { # DEVICE PROGRAM FOLDER T_END [--resume]
  timeout 120 "$2" run scenes/chute-lammps.toml --device "$1" --t-end "$4" -o "$3" --no-progress \
    --no-plots > "$3.log" 2>&1
  echo "== yuxi run --device $1 to t = $4: exit $?"
  grep -E 'particle-steps/s|device engine' "$3.log" || tail -5 "$3.log"
}
part_run() {
  rm -rf /tmp/yuxi-run-*
  run_chute gpu yuxi_cuda /tmp/yuxi-run-gpu 0.1
  run_chute host yuxi /tmp/yuxi-run-host 0.1
  run_chute gpu yuxi_cuda /tmp/yuxi-run-half 0.05
  timeout 60 yuxi_cuda run --resume /tmp/yuxi-run-half --t-end 0.1 --no-progress --no-plots \
    > /tmp/yuxi-run-half.resume.log 2>&1
  echo "== resumed on the GPU to t = 0.1: exit $?"
  same() { cmp -s "$1" "$2" && echo "the same bytes" || echo DIFFER; }
  echo "GPU and host build, energies.csv: $(same /tmp/yuxi-run-gpu/energies.csv /tmp/yuxi-run-host/energies.csv)"
  echo "GPU resumed and straight, energies.csv: $(same /tmp/yuxi-run-half/energies.csv /tmp/yuxi-run-gpu/energies.csv)"
}

chute() {
  local np=$1 steps=$2
  rm -rf /tmp/yuxi-chute
  timeout 120 mpirun --oversubscribe --bind-to none -np "$np" yuxi run scenes/chute-lammps.toml \
    --t-end "$(awk -v s="$steps" 'BEGIN {printf "%.6f", s * 1e-4}')" -o /tmp/yuxi-chute \
    --no-progress --no-plots > /tmp/yuxi-chute.log 2>&1
  echo "== chute, $np ranks, $steps steps: exit $?"
  grep -E 'particle-steps/s|time:|memory:' /tmp/yuxi-chute.log || tail -20 /tmp/yuxi-chute.log
}
part_cpu_chute() {
  chute 1 2000
  chute "$cores" 10000
}

parts=${YUXI_CHECK_PARTS:-env law_bits sanitizer gpu_tests references engine engine_sanitizer run cpu_chute}
for part in $parts; do
  if ! declare -F "part_$part" > /dev/null; then
    echo "device_check.sh: no part named '$part'" >&2
    exit 2
  fi
  "part_$part" > "$out/$part.txt" 2>&1
done
exit "$status"
