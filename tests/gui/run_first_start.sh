#!/bin/sh
# A first start without a project argument (issue 14 item 5): rrf-workbench copies the bundled
# Cornell box into the per-user workspace ($XDG_DATA_HOME/rrf-workbench/projects/cornell-box) and
# works there; a scripted session that renders, saves a run and saves the project must leave the
# bundled project (in the checkout and in the data directory the program reads) unchanged: the
# same files with the same contents. Fails (never skips) when xvfb-run is missing.
#   run_first_start.sh WORKBENCH SOURCE_PROJECT_DIR DATA_PROJECT_DIR OUT_DIR SCRIPT
set -eu
workbench=$1 source_dir=$2 data_dir=$3 out=$4 script=$5
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "FAIL: xvfb-run is not installed; the GUI tests need it (Debian: apt-get install xvfb xauth)" >&2
    exit 1
fi
rm -rf "$out"
mkdir -p "$out/config" "$out/data" "$out/home"
# Every file with its checksum: what `git status` would compare.
fingerprint() { (cd "$1" && find . -type f -exec sha256sum {} + | sort -k 2); }
fingerprint "$source_dir" > "$out/source.before"
fingerprint "$data_dir" > "$out/data.before"
export XDG_CONFIG_HOME="$out/config" XDG_DATA_HOME="$out/data" HOME="$out/home"
cd "$out"
xvfb-run -a -s "-screen 0 1280x720x24" "$workbench" --frames 5 --script "$script" > "$out/log.txt" 2>&1 || {
    cat "$out/log.txt"
    exit 1
}
workspace="$out/data/rrf-workbench/projects/cornell-box"
fingerprint "$source_dir" > "$out/source.after"
fingerprint "$data_dir" > "$out/data.after"
status=0
if ! grep -q "workspace copy of the bundled project: $workspace/project.json" "$out/log.txt"; then
    echo "FAIL: the workbench did not say it opened the workspace copy" >&2
    status=1
fi
if ! diff "$out/source.before" "$out/source.after" >&2; then
    echo "FAIL: the bundled project in the checkout changed" >&2
    status=1
fi
if ! diff "$out/data.before" "$out/data.after" >&2; then
    echo "FAIL: the bundled project in the data directory changed" >&2
    status=1
fi
if [ ! -d "$workspace/runs" ] || ! grep -q '"runs"' "$workspace/project.json"; then
    echo "FAIL: the session's run did not land in the workspace copy $workspace" >&2
    status=1
fi
[ "$status" -eq 0 ] || cat "$out/log.txt"
exit "$status"
