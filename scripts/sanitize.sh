#!/usr/bin/env bash
# The sanitizer and fuzz jobs of CI (scripts/test.sh runs them after the release job; docs/design.md
# §22). Each job builds with clang 14 into its own directory, in unity batches (cmake/Unity.cmake),
# and fails on any sanitizer report, failed test or fuzz finding:
#
#   asan   clang, -O1, AddressSanitizer + UndefinedBehaviorSanitizer; core, rrf, rrf_tests and the
#          fuzz targets (core and the fuzz targets also carry libFuzzer's coverage feedback). This
#          build is the project's clang build; it runs the core tests (rrf_tests, less the slow ones
#          in $asan_skip) and the fuzz targets' seeds and regressions once (CTest fuzz_*_corpus)
#   fuzz   each fuzz target of that build mutates its seeds for RRF_FUZZ_SECONDS (default 12), two
#          targets at a time; a crashing input is kept under <asan build>/fuzz-findings/. Six
#          targets at 12 s take three rounds of 12 s, which keeps the whole CI run within its 20 minutes.
#   tsan   clang, -O0, ThreadSanitizer: core + rrf_threaded_tests only (renderer, generator,
#          training, job runner; cmake/ThreadedTests.cmake), the tests in $tsan_filter
#
# Usage: scripts/sanitize.sh [asan|fuzz|tsan]...   (no argument: all three, in that order)
# Build directories: RRF_ASAN_BUILD_DIR (default build-asan), RRF_TSAN_BUILD_DIR (default build-tsan).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
asan_build=${RRF_ASAN_BUILD_DIR:-$root/build-asan}
tsan_build=${RRF_TSAN_BUILD_DIR:-$root/build-tsan}
fuzz_seconds=${RRF_FUZZ_SECONDS:-12}
jobs=$(nproc)
jobs_to_run=("$@")
[[ ${#jobs_to_run[@]} -eq 0 ]] && jobs_to_run=(asan fuzz tsan)

# Tests left to the Release suite (rrf_tests under scripts/test.sh) because under the sanitizers they
# take minutes while exercising nothing the faster tests do not: whole pipelines and convergence
# studies built from the same renderer, generator and trainer code that the other tests run.
asan_skip='EndToEnd\.SmallRunLearnsAndBrokenPipelinesFail|EndToEnd\.SppSweepShowsTheMonteCarloSlope'
asan_skip+='|DefaultPipeline\.QuickRunOfTheProjectDefaultsStaysWithinItsMeasuredBound'
# The slowest of the rest under ASan (a quarter of its test time, measured in the session-5 run): the
# kd-tree training studies, the NEE furnace's convergence and LM's two-thread identity run in the
# Release suite; the other training, tracer and LM tests still run here.
asan_skip+='|PartitionedTraining\..*|PathTracer\.WhiteFurnaceNEE|LevenbergMarquardt\.BitIdenticalForOneOrTwoThreads'
# This one runs rrf under `ulimit -v 4 GiB`, where an AddressSanitizer build cannot even start (its
# shadow memory alone reserves terabytes of address space); the Release suite runs it.
asan_skip+='|CliHostile\.RequestsBeyondMemoryAreRefusedWithTheEstimate'
# The slowest convergence studies under ASan, whose time is all in loops that faster tests run too
# (quadratures, per-block comparisons of two estimators, a frequency-encoding fit); the Release suite
# runs them.
asan_skip+='|GlossyCaustics\.FiniteLobesAndAClippingFaceMatchAQuadratureOverTheFace'
asan_skip+='|EncodedLearning\.FrequencyEncodingFitsWhatARawNetworkOfTheSameSizeCannot'
asan_skip+='|Bdpt\.EqualsThePathTracerPerBlockOn.*|Bdpt\.LightTracingWithPathTracingEqualsThePathTracer'
asan_skip+='|NoiseFloor\.ConvergedPredictionScoresWithinTheReferenceFloor|GlossyGather\.ManyBatchesKeepTheClosedForm'
# More of the same kind, each family keeping faster tests here (Bdpt.WhiteFurnace, the NoiseFloor
# formulas, Renderer.NeeAndNaiveAgreeAtEveryMaxDepth, the other DataGenerator and LM tests): estimator
# agreements, learning studies, and the generator's byte identity across thread counts and shards,
# whose code the faster generator and CLI shard tests run under the sanitizers too.
asan_skip+='|GlossyCaustics\.GatherFromTheLightSideEqualsTheCosineRays|Bdpt\.CausticOfANearMirrorMatchesTheMirroredLightsIrradiance'
asan_skip+='|NoiseFloor\.CorrectedRecoversAKnownPerturbationFromANoisyReference|Renderer\.NeeAndNaiveConvergeToTheSameImageMean'
asan_skip+='|DerivedInputs\.ALobeAroundTheMirrorDirectionIsLearntFarBetterWithTheInput|LevenbergMarquardt\.RecoversTeacherNetwork'
asan_skip+='|TrainingGoal\.NoisyTargetsReachTheGoalOnlyWhenTheirNoiseIsKnown'
asan_skip+='|DataGenerator\.SameSeedGivesTheSameBytesForAnyThreadCount|DataGenerator\.ShardsMergeIntoTheBytesOfTheUnshardedRun'
# The threaded tests whose subject is our own threads: cancel from another thread, training runs, the
# workbench's job runner and job sessions, and one thread-count test. Left out: the convergence and
# statistics tests, and the bit-identical-for-any-thread-count tests of the generator and trainers,
# whose threads are TBB tasks that TSan cannot check here (see run_tsan) and which take minutes under
# TSan (Eigen unoptimised, every access instrumented); the generator's CLI tests check another process.
tsan_filter='Renderer.BitIdenticalForAnyThreadCount:Bdpt.IdenticalForAnyThreadCount*:Renderer.Cancel*:DataGenerator.Cancelled*'
tsan_filter+=':LevenbergMarquardt.Cancel*:Adam.Cancel*:ObjectTraining.Cancelled*:TrainingRun.*'
tsan_filter+=':JobRunner.*:JobSession.*'

"$root/scripts/install-deps.sh" --no-gui --sanitizers
source "$root/scripts/generator.sh"
# llvm-symbolizer turns sanitizer stacks into file:line; Debian keeps it in LLVM's own bin directory.
export PATH="/usr/lib/llvm-14/bin:$PATH"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}

configure() {  # configure <build dir> <-O level> <cmake args...>
  local dir=$1 opt=$2
  shift 2
  # ASan at -O1: the speed of its tests matters as much as that of the compiler. TSan at -O0: its few
  # tests take seconds either way, and the compile is what it costs. NDEBUG stays off, so the
  # asserts of the code and of Eigen are checked too. Unity batches of 16 sources halve the compile
  # time (cmake/Unity.cmake lists the sources that must stay on their own). Without MPI: Open MPI's
  # own allocations would be leak reports, and the release job runs the MPI test.
  # Full paths, as CMake caches them: a bare name would differ from the cache and reset it every run.
  # shellcheck disable=SC2046  # the generator arguments are two words or none
  cmake -S "$root" -B "$dir" $(rrf_generator_args "$dir") -DCMAKE_C_COMPILER="$(command -v clang-14)" -DCMAKE_CXX_COMPILER="$(command -v clang++-14)" \
        -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="$opt" -DCMAKE_C_FLAGS_SANITIZE="$opt" \
        -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 \
        -DRRF_BUILD_GUI=OFF -DRRF_BUILD_BENCH=OFF -DRRF_WITH_MPI=OFF "$@" >/dev/null
}

# CPU seconds (user + system) of the finished child processes so far: on a shared machine a truer
# measure of what a job costs than its wall time.
# (/proc/$$/stat's cutime and cstime: this shell's, even when read from a command substitution).
clock_ticks=$(getconf CLK_TCK)
cpu_seconds() { local st; read -r -a st </proc/$$/stat; echo $(((st[15] + st[16]) / clock_ticks)); }
stamp() { echo "sanitize: $1 ($(date +%T), ${SECONDS} s since start, $(cpu_seconds) s CPU)"; }

run_asan() {
  stamp "asan: building (clang, address+undefined, fuzzer coverage)"
  configure "$asan_build" -O1 -DRRF_SANITIZE="address;undefined" -DRRF_BUILD_FUZZ=ON -DRRF_BUILD_TESTS=ON
  cmake --build "$asan_build" -j "$jobs"
  stamp "asan: running rrf_tests (less $asan_skip) and the fuzz corpora"
  (cd "$asan_build" && ctest --output-on-failure -j "$jobs" --timeout 600 \
     -E "^(${asan_skip}|install_run|core_layering|json_confined)\$")
  stamp "asan: passed"
}

fuzz_one() {  # fuzz_one <target>: mutates tests/fuzz/corpus/<target> for $fuzz_seconds
  local t=$1 out=$asan_build/fuzz-findings/$t
  local work=$asan_build/fuzz-corpus/$t
  # A target's own dictionary (tests/fuzz/<target>.dict: OBJ statements, image magic numbers) where
  # it has one, else the JSON one that the four JSON readers share.
  local dict=$root/tests/fuzz/$t.dict
  [[ -f $dict ]] || dict=$root/tests/fuzz/json.dict
  mkdir -p "$out" "$work"
  # New inputs go to the scratch corpus (first directory), never into the source tree.
  if "$asan_build/fuzz_$t" "$work" "$root/tests/fuzz/corpus/$t" -max_total_time="$fuzz_seconds" \
       -dict="$dict" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
       -artifact_prefix="$out/" -print_final_stats=1 \
       >"$out/log.txt" 2>&1; then
    echo "sanitize: fuzz $t: $(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$out/log.txt" | grep -o '[0-9]*$') runs in ${fuzz_seconds}s, no finding"
  else
    echo "sanitize: fuzz $t: FINDING (inputs in $out):"
    tail -n 60 "$out/log.txt"
    return 1
  fi
}

run_fuzz() {
  [[ -x "$asan_build/fuzz_scene" ]] || run_asan
  stamp "fuzz: ${fuzz_seconds}s per target, ${jobs} at a time"
  local targets=() status=0 pids=()
  for src in "$root"/tests/fuzz/*.cpp; do targets+=("$(basename "$src" .cpp)"); done
  for ((i = 0; i < ${#targets[@]}; i += jobs)); do
    pids=()
    for t in "${targets[@]:i:jobs}"; do
      fuzz_one "$t" &
      pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p" || status=1; done
  done
  [[ $status -eq 0 ]] || { echo "sanitize: fuzz: findings above" >&2; return 1; }
  stamp "fuzz: passed"
}

run_tsan() {
  stamp "tsan: building core + rrf_threaded_tests (clang, thread)"
  configure "$tsan_build" -O0 -DRRF_SANITIZE=thread -DRRF_BUILD_TESTS=ON
  cmake --build "$tsan_build" -j "$jobs" --target rrf_threaded_tests
  # libtbb is not built with TSan: the happens-before its scheduler gives between a parallel_for and
  # its tasks is invisible, so every access made inside a TBB task looks racy (reports inside
  # oneapi/tbb/partitioner.h and the like). Reports with a libtbb frame are suppressed; what TSan checks
  # is the synchronisation of our own threads (std::thread, mutexes, atomics): job runner and job
  # sessions, cancel flags, progress and snapshots handed between a worker and the thread that waits.
  # libembree3 is not built with TSan either and runs its own work on TBB workers (its device state is
  # read by a worker through uninstrumented libstdc++ after the main thread built it under an Embree
  # mutex TSan cannot pair): reports with a libembree3 frame are suppressed for the same reason.
  printf 'race:libtbb.so\nrace:libembree3.so\n' >"$tsan_build/tsan.supp"
  stamp "tsan: running rrf_threaded_tests ($tsan_filter)"
  TSAN_OPTIONS="$TSAN_OPTIONS:suppressions=$tsan_build/tsan.supp" \
    "$tsan_build/rrf_threaded_tests" --gtest_filter="$tsan_filter" --gtest_brief=1
  stamp "tsan: passed"
}

for job in "${jobs_to_run[@]}"; do
  case "$job" in
    asan) run_asan ;;
    fuzz) run_fuzz ;;
    tsan) run_tsan ;;
    *) echo "usage: scripts/sanitize.sh [asan|fuzz|tsan]..." >&2; exit 2 ;;
  esac
done
