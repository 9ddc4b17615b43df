#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds everything in Release (warnings are
# errors), checks formatting, and runs every test with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
scripts/check-format.sh
ctest --preset release
