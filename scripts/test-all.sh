#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds everything in Release (warnings are
# errors), checks formatting, builds the sanitizer tier (clang, AddressSanitizer +
# UndefinedBehaviorSanitizer, with the libFuzzer targets in the same build), runs the unit,
# validation, CLI, MPI and device-engine tests there (but those labelled heavy, minutes each
# there; the crash and resume runs labelled reliability run in Release, and their checkpoint
# code under the sanitizers through the unit tests and the checkpoint fuzzer), then
# each fuzzer on its kept corpus for a fixed number of inputs from a fixed seed, and random
# sequences of calls on the Python module built with the sanitizers, then every test
# in Release, the Python module's (pytest, with the examples' short forms) among them. Long
# validation cases: ctest --preset long.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release > /dev/null
cmake --build --preset release
scripts/check-format.sh
scripts/check-layers.sh

echo "== sanitizers (ASan + UBSan)"
cmake --preset asan > /dev/null
cmake --build --preset asan
# The device engine's host build too: its sorts on the CPU go through std::stable_sort, since
# Debian's Thrust 1.17 binds references to a null execution policy inside its own CPU sorts.
ctest --test-dir build/asan -L "unit|validation|cli|mpi|device" -LE "heavy|long|reliability" -j 2 \
  --output-on-failure

echo "== fuzzers (bounded)"
# (10,000 inputs each: the checkpoint fuzzer alone took some 7 minutes at 20,000 under the
# sanitizers, on a 2-core machine; YUXI_FUZZ_RUNS asks for more)
tests/fuzz/run.sh --runs "${YUXI_FUZZ_RUNS:-10000}"
# The Python module under the sanitizers, driven by random sequences of calls.
ctest --test-dir build/asan -L fuzz --output-on-failure

echo "== release"
ctest --preset release
