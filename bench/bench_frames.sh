#!/bin/sh
# Frame times of the workbench's UI thread (issue 14, item 10): runs rrf-workbench under Xvfb on a
# private copy of the Cornell-box project, driven by bench/frames_session.json, and prints the median
# and 95th percentile frame time idle, while rendering, while training and while dragging the light
# (GLSL prediction and a restarted ground truth every frame). A frame is the UI thread's work (jobs
# polled, panels drawn, GL rendered and swapped), not the wait for events before it.
#   bench/bench_frames.sh [WORKBENCH] [WxH]     (defaults: build/rrf-workbench, 1280x720)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
workbench=${1:-build/rrf-workbench}
size=${2:-1280x720}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cp "$here/../projects/cornell-box/"*.json "$out/"
export XDG_CONFIG_HOME="$out/config" XDG_DATA_HOME="$out/data"
echo "bench_frames: $workbench at $size ($(nproc) cores)"
xvfb-run -a -s "-screen 0 ${size}x24" "$workbench" "$out/project.json" --size "$size" \
    --script "$here/frames_session.json" --frames 1 >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; exit 1; }
grep '^frames ' "$out/log.txt"
grep -i 'GL_RENDERER\|renderer:' "$out/log.txt" | head -1 || true
