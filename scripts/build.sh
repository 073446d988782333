#!/usr/bin/env bash
# Configures and builds RRF Workbench into build/ (Release). Extra arguments go to CMake.
# Usage: scripts/build.sh [-DRRF_BUILD_GUI=OFF ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
