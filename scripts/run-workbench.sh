#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and opens the workbench on the
# bundled Cornell-box project. Without a display it runs the same pipeline headless with the CLI
# and prints where the outputs went.
# Usage: scripts/run-workbench.sh [project.json]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
project=${1:-$root/projects/cornell-box/project.json}
"$root/scripts/install-deps.sh"
RRF_BUILD_DIR=$build "$root/scripts/build.sh"

if [[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" && -x "$build/rrf-workbench" ]]; then
  exec "$build/rrf-workbench" "$project"
fi

echo "No display: running the pipeline headless with the rrf CLI."
out=${RRF_OUT_DIR:-$root/rrf-out}
"$build/rrf" pipeline "$project" --out "$out"
