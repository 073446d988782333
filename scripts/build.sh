#!/usr/bin/env bash
# Configures and builds RRF Workbench into build/ (Release). Extra arguments go to CMake.
# Usage: scripts/build.sh [-DRRF_BUILD_GUI=OFF ...]
# RRF_BUILD_TARGETS="rrf rrf-workbench" builds only those targets (default: everything).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
source "$root/scripts/generator.sh"
# shellcheck disable=SC2046  # the generator arguments are two words or none
cmake -S "$root" -B "$build" $(rrf_generator_args "$build") -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# shellcheck disable=SC2086  # the target list is words
cmake --build "$build" -j "$(nproc)" ${RRF_BUILD_TARGETS:+--target $RRF_BUILD_TARGETS}
