#!/usr/bin/env bash
# Builds the libFuzzer targets (the `asan` preset: clang, AddressSanitizer +
# UndefinedBehaviorSanitizer, the sanitizer tier's build) and runs each for a bounded time on its
# kept corpus (tests/fuzz/corpus/<target>). A crash, leak or sanitizer report fails the script
# and leaves the reproducer in build/asan/fuzz-artifacts/; fixed
# findings are kept in the corpus as regression-* inputs.
# usage: tests/fuzz/run.sh [SECONDS_PER_TARGET]   (default 60: explore, corpus grows)
#        tests/fuzz/run.sh --runs N                 (N inputs per target from a fixed seed:
#                                                    reproducible, as CI runs it)
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=60
limit=()
if [[ "${1:-}" == "--runs" ]]; then
  limit=(-runs="$2" -seed=2008)
  seconds=0
elif [[ -n "${1:-}" ]]; then
  seconds=$1
fi
if ((seconds > 0)); then limit=(-max_total_time="$seconds"); fi
build=build/asan
cmake --preset asan > /dev/null
cmake --build --preset asan --target fuzz_scene fuzz_lammps_data fuzz_checkpoint fuzz_stl \
  fuzz_sphere_list
mkdir -p $build/fuzz-artifacts
status=0
for target in fuzz_scene fuzz_lammps_data fuzz_checkpoint fuzz_stl fuzz_sphere_list; do
  corpus=tests/fuzz/corpus/${target#fuzz_}
  echo "== $target: ${limit[*]} on $(ls "$corpus" | wc -l) corpus files"
  # New inputs go to a scratch folder; the kept corpus is only read. To keep what a run found:
  # build/asan/tests/fuzz/<target> -merge=1 tests/fuzz/corpus/<name> build/asan/fuzz-new/<target>
  mkdir -p "$build/fuzz-new/$target"
  if ! $build/tests/fuzz/$target "$build/fuzz-new/$target" "$corpus" "${limit[@]}" -max_len=65536 \
      -rss_limit_mb=4096 -timeout=20 -artifact_prefix=$build/fuzz-artifacts/$target- \
      -print_final_stats=1 > "$build/fuzz-$target.log" 2>&1; then
    echo "FINDING in $target:"
    tail -40 "$build/fuzz-$target.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/fuzz-$target.log" || true
  fi
done
exit $status
