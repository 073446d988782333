#!/usr/bin/env bash
# The README's test command and CI's (.ci/run). Installs what is missing, then runs, in this order:
#   release  GCC Release build of everything (core, CLI, GUI, tests, benchmarks) and every test, GUI
#            tests included (under Xvfb);
#   asan     clang build with AddressSanitizer + UndefinedBehaviorSanitizer running the core tests and
#            the fuzz targets' seeds (CI's clang build);
#   fuzz     each libFuzzer target (scene, project, dataset, model, image, OBJ readers) for RRF_FUZZ_SECONDS;
#   tsan     clang ThreadSanitizer build of the threaded tests.
# (the last three: scripts/sanitize.sh, docs/design.md §22). RRF_SANITIZE_JOBS=0 runs the release job
# only, for a quick local check. Every build is a unity build (cmake/Unity.cmake): CI builds from
# scratch without a compiler cache, and batches of sources halve the compile time. The whole run takes
# about 18 minutes on 2 cores (CHANGELOG.md). Exits non-zero on the first failing job; each job prints its
# time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RRF_BUILD_DIR:-$root/build}
sanitize=${RRF_SANITIZE_JOBS:-1}

if [[ "$sanitize" != 0 ]]; then
  "$root/scripts/install-deps.sh" --sanitizers
else
  "$root/scripts/install-deps.sh"
fi

# CPU seconds (user + system) of the finished child processes so far: on a shared machine a truer
# measure of what a job costs than its wall time.
# (/proc/$$/stat's cutime and cstime: this shell's, even when read from a command substitution).
clock_ticks=$(getconf CLK_TCK)
cpu_seconds() { local st; read -r -a st </proc/$$/stat; echo $(((st[15] + st[16]) / clock_ticks)); }

start=$SECONDS
echo "test: release: building ($(date +%T))"
# MPI is required here (install-deps installs Open MPI), so a missing MPI fails the configure step
# instead of compiling the MPI test (tests/test_cli_mpi.cpp) away; the sanitizer jobs build without it.
RRF_BUILD_DIR=$build "$root/scripts/build.sh" -DRRF_BUILD_GUI=ON -DRRF_BUILD_TESTS=ON -DRRF_BUILD_BENCH=ON \
  -DCMAKE_UNITY_BUILD=ON -DRRF_WITH_MPI=ON
echo "test: release: built in $((SECONDS - start)) s ($(cpu_seconds) s CPU); running every test"
(cd "$build" && ctest --output-on-failure -j "$(nproc)" --timeout 600)
echo "test: release: passed ($((SECONDS - start)) s, $(cpu_seconds) s CPU)"

if [[ "$sanitize" != 0 ]]; then
  "$root/scripts/sanitize.sh"
fi
echo "test: all jobs passed in $((SECONDS / 60)) min $((SECONDS % 60)) s ($(cpu_seconds) s CPU, load $(cut -d' ' -f1-3 /proc/loadavg))"
