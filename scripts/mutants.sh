#!/usr/bin/env bash
# Mutant harness (docs/mutants.md): plants each bug of tests/mutants/mutants.txt in a scratch copy of
# the tree, rebuilds rrf_tests there and runs the fast core tests. A mutant is KILLED when the build
# or a test fails (or the run exceeds its time limit) and SURVIVED when every test passes. On demand
# only, not in CI: each mutant recompiles the files it touches and runs the tests (about a minute).
#
#   scripts/mutants.sh [-l LIST] [-o TABLE.md] [ID ...]
#
#   LIST        mutant list (default tests/mutants/mutants.txt)
#   TABLE.md    also write the result table as Markdown (e.g. docs/mutants.md's table)
#   ID ...      run only these mutants (default: all)
# Environment: RRF_MUTANT_DIR scratch directory (default /tmp/rrf-mutants; its build/ is reused
# between runs), RRF_MUTANT_JOBS build jobs (default 2), RRF_MUTANT_TIMEOUT seconds per test run
# (default 300), RRF_MUTANT_FILTER gtest filter (default: the list file's "filter:" line).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
list=$root/tests/mutants/mutants.txt
table=""
while getopts "l:o:" opt; do
  case $opt in
    l) list=$OPTARG ;;
    o) table=$OPTARG ;;
    *) sed -n '2,16p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
only=("$@")
scratch=${RRF_MUTANT_DIR:-/tmp/rrf-mutants}
tree=$scratch/tree
build=$tree/build
jobs=${RRF_MUTANT_JOBS:-2}
limit=${RRF_MUTANT_TIMEOUT:-300}
[[ -f $list ]] || { echo "mutants.sh: no mutant list at $list" >&2; exit 2; }

# The list: "filter:" once, then blocks of "id:", "file:", "find:", "replace:", "models:" lines
# separated by blank lines ('#' lines are comments). `find` is a literal text that must occur
# exactly once in `file`; `replace` is put in its place (both taken verbatim after "key: ").
filter=${RRF_MUTANT_FILTER:-$(sed -n 's/^filter: //p' "$list" | head -1)}
[[ -n $filter ]] || filter='*'
parsed=$(mktemp)
trap 'rm -f "$parsed"' EXIT
python3 - "$list" >"$parsed" <<'PY'
import sys, json
blocks, cur = [], {}
for raw in open(sys.argv[1], encoding="utf-8"):
    line = raw.rstrip("\n")
    if line.startswith("#") or line.startswith("filter: "):
        continue
    if not line.strip():
        if cur: blocks.append(cur); cur = {}
        continue
    key, sep, value = line.partition(": ")
    if not sep or key not in ("id", "file", "find", "replace", "models", "tests"):
        sys.exit(f"mutants.txt: unexpected line: {line!r}")
    if key in cur:
        sys.exit(f"mutants.txt: mutant {cur.get('id', '?')} has two '{key}' lines")
    cur[key] = value
if cur: blocks.append(cur)
for b in blocks:
    missing = [k for k in ("id", "file", "find", "replace", "models") if k not in b]
    if missing: sys.exit(f"mutants.txt: mutant {b.get('id', '?')} lacks {', '.join(missing)}")
    print(json.dumps(b))
PY

# Scratch copy of the working tree (tracked and untracked files, not build outputs). Only files
# whose bytes differ are copied (with a new time), so make rebuilds exactly what changed since the
# last run, even after an interrupted run left a mutated file behind.
mkdir -p "$tree"
python3 - "$root" "$tree" <<'PY'
import os, shutil, sys
src, dst = sys.argv[1], sys.argv[2]
skip = lambda rel: rel == ".git" or rel.split(os.sep)[0].startswith("build")
seen = set()
for d, dirs, files in os.walk(src):
    rel_d = os.path.relpath(d, src)
    dirs[:] = [x for x in dirs if not skip(os.path.normpath(os.path.join(rel_d, x)))]
    os.makedirs(os.path.join(dst, rel_d), exist_ok=True)
    for f in files:
        rel = os.path.normpath(os.path.join(rel_d, f))
        if skip(rel): continue
        seen.add(rel)
        a, b = os.path.join(src, rel), os.path.join(dst, rel)
        if os.path.islink(a): continue
        if not os.path.exists(b) or open(a, "rb").read() != open(b, "rb").read():
            shutil.copyfile(a, b)
            shutil.copymode(a, b)
for d, dirs, files in os.walk(dst):
    rel_d = os.path.relpath(d, dst)
    dirs[:] = [x for x in dirs if not skip(os.path.normpath(os.path.join(rel_d, x)))]
    for f in files:
        rel = os.path.normpath(os.path.join(rel_d, f))
        if rel not in seen: os.remove(os.path.join(dst, rel))
PY
# ccache keys on paths relative to the base directory: the same objects as the worktree's build.
export CCACHE_BASEDIR=$tree
cmake -S "$tree" -B "$build" -G "Unix Makefiles" -DCMAKE_BUILD_TYPE=Release -DRRF_BUILD_GUI=OFF -DRRF_BUILD_BENCH=OFF >/dev/null
# The first build makes every target rrf_tests depends on (the CLI, the data directory); after that
# only the core library and the test binary are rebuilt ("/fast": without re-checking dependencies),
# since the filtered tests never start the CLI. A mutant then costs the files it touches plus a link.
buildAll() { cmake --build "$build" -j "$jobs" --target rrf_tests </dev/null >"$scratch/build.log" 2>&1; }
buildTests() {
  (cd "$build" && make -j "$jobs" rrf_core/fast && make -j "$jobs" rrf_tests/fast) </dev/null >"$scratch/build.log" 2>&1
}
runTests() {  # [filter]: default the list's filter
  (cd "$build" && timeout "$limit" ./rrf_tests --gtest_filter="${1:-$filter}" --gtest_fail_fast --gtest_brief=1 \
      </dev/null >"$scratch/test.log" 2>&1)
}

echo "mutants.sh: baseline (unmutated) build and tests, filter '$filter'"
buildAll || { echo "baseline build failed: $scratch/build.log" >&2; exit 1; }
t0=$(date +%s)
runTests || { echo "baseline tests fail: $scratch/test.log" >&2; exit 1; }
echo "mutants.sh: baseline passes in $(( $(date +%s) - t0 )) s"

killed=0; survived=0; stale=0
# The table grows row by row, so an interrupted run still leaves what it found.
if [[ -n $table ]]; then
  printf '| mutant | file | what it models | result |\n|---|---|---|---|\n' >"$table"
fi
addRow() {
  if [[ -n $table ]]; then printf '%s\n' "$1" >>"$table"; fi
}
while IFS= read -r json; do
  get() { python3 -c 'import sys, json; print(json.loads(sys.argv[1]).get(sys.argv[2], ""))' "$json" "$1"; }
  id=$(get id); file=$(get file); models=$(get models); hint=$(get tests)
  if ((${#only[@]})); then
    skip=1; for o in "${only[@]}"; do [[ $o == "$id" ]] && skip=0; done
    ((skip)) && continue
  fi
  target=$tree/$file
  # Plant the bug: the pattern must match exactly once, else the list is out of date.
  if ! python3 - "$json" "$target" <<'PY'
import sys, json
m = json.loads(sys.argv[1]); path = sys.argv[2]
find, replace = (m[k].replace("\\n", "\n") for k in ("find", "replace"))
src = open(path, encoding="utf-8").read()
n = src.count(find)
if n != 1:
    sys.exit(f"{m['id']}: pattern occurs {n} times in {m['file']} (expected once): {m['find']!r}")
open(path, "w", encoding="utf-8").write(src.replace(find, replace))
PY
  then
    # The code moved on: the list needs updating. Counted apart, and the run fails.
    stale=$((stale + 1))
    printf '%-34s %s\n' "$id" "STALE (pattern not found once in $file)"
    addRow "| \`$id\` | \`$file\` | ${models//|/\\|} | stale pattern |"
    continue
  fi
  t0=$(date +%s)
  if ! buildTests; then
    result="killed (does not build)"
  else
    # The tests named by the mutant's optional "tests:" line first (a quick kill); a mutant
    # survives only if the whole filter passes.
    rc=0
    if [[ -n $hint ]]; then runTests "$hint" || rc=$?; fi
    if ((rc == 0)); then runTests || rc=$?; fi
    if ((rc == 0)); then result="SURVIVED"
    elif ((rc == 124)); then result="killed (timeout ${limit} s)"
    else
      failed=$(grep -m1 -o '\[  FAILED  \] [A-Za-z0-9_]*\.[A-Za-z0-9_/]*' "$scratch/test.log" | sed 's/\[  FAILED  \] //' || true)
      result="killed by ${failed:-a crash}"
    fi
  fi
  # Restore the file (a fresh copy: its new time makes make rebuild it, from ccache).
  cp "$root/$file" "$target"
  secs=$(( $(date +%s) - t0 ))
  if [[ $result == SURVIVED ]]; then survived=$((survived + 1)); else killed=$((killed + 1)); fi
  printf '%-34s %-58s %4d s  %s\n' "$id" "$result" "$secs" "$models"
  addRow "| \`$id\` | \`$file\` | ${models//|/\\|} | $result |"
done <"$parsed"
buildTests || true  # leave the scratch build unmutated for the next run

echo "mutants.sh: $killed killed, $survived survived, $stale stale of $((killed + survived + stale))"
if [[ -n $table ]]; then
  {
    echo
    echo "$killed killed, $survived survived, $stale stale of $((killed + survived + stale)) ($(date -u +%Y-%m-%d), filter \`$filter\`)."
  } >>"$table"
fi
((survived == 0 && stale == 0))
