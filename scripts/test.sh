#!/usr/bin/env bash
# The README's test command: installs what is missing, builds everything (core, CLI, GUI, tests,
# benchmarks) and runs every test, GUI tests included (under Xvfb). Exits non-zero on any failure.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
"$root/scripts/install-deps.sh"
RRF_BUILD_DIR=$build "$root/scripts/build.sh" -DRRF_BUILD_GUI=ON -DRRF_BUILD_TESTS=ON -DRRF_BUILD_BENCH=ON
cd "$build"
ctest --output-on-failure -j "$(nproc)" --timeout 600
