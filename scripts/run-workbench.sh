#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and opens the workbench on the
# bundled Cornell-box project. Without a display it runs the same pipeline headless with the CLI
# and prints where the outputs went.
# Without a project the bundled Cornell box is not edited in place: like rrf-workbench, the script
# works on the per-user workspace copy ($XDG_DATA_HOME/rrf-workbench/projects/cornell-box, else
# ~/.local/share/rrf-workbench/...), made on first use, so the checkout stays clean.
# Usage: scripts/run-workbench.sh [project.json]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
"$root/scripts/install-deps.sh"
# Only the programs and their data, in unity batches (cmake/Unity.cmake) as CI builds them: the
# tests and benchmarks are the test command's (scripts/test.sh), which builds them into the same tree.
RRF_BUILD_DIR=$build RRF_BUILD_TARGETS="rrf rrf-workbench rrf_data" "$root/scripts/build.sh" -DCMAKE_UNITY_BUILD=ON

if [[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" && -x "$build/rrf-workbench" ]]; then
  exec "$build/rrf-workbench" "$@"
fi

if [[ $# -ge 1 ]]; then
  project=$1
  out=${RRF_OUT_DIR:-$(dirname "$project")/rrf-out}
else
  workspace=${XDG_DATA_HOME:-$HOME/.local/share}/rrf-workbench/projects
  project=$workspace/cornell-box/project.json
  if [[ ! -f "$project" ]]; then
    mkdir -p "$workspace"
    rm -rf "$workspace/cornell-box.partial"
    cp -R "$root/projects/cornell-box" "$workspace/cornell-box.partial"
    mv "$workspace/cornell-box.partial" "$workspace/cornell-box"
    echo "Copied the bundled Cornell box to the workspace: $workspace/cornell-box"
  fi
  out=${RRF_OUT_DIR:-$workspace/cornell-box/rrf-out}
fi

echo "No display: running the pipeline headless with the rrf CLI on $project."
"$build/rrf" pipeline "$project" --out "$out"
echo "Outputs: $out (images, models, report); references: $(dirname "$project")/references"
