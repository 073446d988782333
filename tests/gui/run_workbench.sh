#!/bin/sh
# Runs rrf-workbench under Xvfb on a private copy of the Cornell-box project and checks the
# screenshot. Fails (never skips) when xvfb-run is missing.
#   run_workbench.sh WORKBENCH CHECKER PROJECT_DIR OUT_DIR VIEWS [SCRIPT]
# RRF_GUI_SIZE=WxH (default 1600x1000) sets the screen and the window size.
set -eu
workbench=$1 checker=$2 project_dir=$3 out=$4 views=$5 script=${6:-}
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "FAIL: xvfb-run is not installed; the GUI tests need it (Debian: apt-get install xvfb xauth)" >&2
    exit 1
fi
rm -rf "$out"
mkdir -p "$out/project" "$out/config"
cp "$project_dir"/*.json "$out/project/"
# A project whose scene is an OBJ + MTL (projects/mesh-room) needs those beside it.
for f in "$project_dir"/*.obj "$project_dir"/*.mtl; do
    if [ -e "$f" ]; then cp "$f" "$out/project/"; fi
done
# Keep the user's config (recent projects, imgui.ini) out of the test and vice versa.
export XDG_CONFIG_HOME="$out/config"
# ... and its GLSL program binaries (app/gl/program_binary_cache.h): a session starts cold and finds
# what it cached itself. (Mesa's own shader cache stays where it is: cold, every session compiles slowly.)
export RRF_PROGRAM_CACHE="$out/programs"
size=${RRF_GUI_SIZE:-1600x1000}
set -- "$out/project/project.json" --frames 60 --screenshot "$out/shot.png" --size "$size"
if [ -n "$script" ]; then
    set -- "$@" --script "$script"
fi
cd "$out"
xvfb-run -a -s "-screen 0 ${size}x24" "$workbench" "$@"
"$checker" "$out/shot.png" --views "$views" ${RRF_SHOT_SCENE_VIEWS:+--scene-views "$RRF_SHOT_SCENE_VIEWS"}
