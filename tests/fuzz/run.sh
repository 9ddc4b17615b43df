#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer) and runs
# each for a bounded time on its kept corpus (tests/fuzz/corpus/<target>), adding what it finds
# to the corpus. A crash, leak or sanitizer report fails the script and leaves the reproducer in
# build/fuzz/artifacts/.
# usage: tests/fuzz/run.sh [SECONDS_PER_TARGET]   (default 60)
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz --target fuzz_scene fuzz_lammps_data fuzz_checkpoint
mkdir -p build/fuzz/artifacts
status=0
for target in fuzz_scene fuzz_lammps_data fuzz_checkpoint; do
  corpus=tests/fuzz/corpus/${target#fuzz_}
  echo "== $target: ${seconds} s on $(ls "$corpus" | wc -l) corpus files"
  if ! build/fuzz/tests/fuzz/$target "$corpus" -max_total_time="$seconds" -max_len=65536 \
      -rss_limit_mb=4096 -timeout=20 -artifact_prefix=build/fuzz/artifacts/$target- \
      -print_final_stats=1 > "build/fuzz/$target.log" 2>&1; then
    echo "FINDING in $target:"
    tail -40 "build/fuzz/$target.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build/fuzz/$target.log" || true
  fi
done
exit $status
