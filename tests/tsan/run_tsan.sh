#!/usr/bin/env bash
# ThreadSanitizer over every OpenMP loop (docs/robustness.md). GCC's libgomp
# is not TSan-instrumented, so its barriers look like races; clang with its
# own OpenMP runtime (Debian: libomp-dev) loads archer (libarcher.so), which
# tells TSan about OpenMP's synchronization. The run fails unless archer
# says it is active, and on any TSan report.
# Usage (from the repository root): run_tsan.sh <build folder> [jobs]
set -euo pipefail
BUILD="$1"
JOBS="${2:-2}"
cmake -S . -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only" -DRC_SANITIZE=thread -DBUILD_BENCHMARKS=OFF
cmake --build "$BUILD" -j"$JOBS" --target openmp_loops_test collision_test

export OMP_NUM_THREADS=4
export TSAN_OPTIONS="halt_on_error=1 abort_on_error=1 ignore_noninstrumented_modules=1"
export ARCHER_OPTIONS="verbose=1"
LOG="$(mktemp)"
trap 'rm -f "$LOG"' EXIT
run() {
  "$@" >"$LOG" 2>&1 || { cat "$LOG"; echo "run_tsan: FAILED: $*"; exit 1; }
  grep -q "Archer detected OpenMP application with TSan" "$LOG" ||
    { cat "$LOG"; echo "run_tsan: archer did not load; OpenMP synchronization would be unknown to TSan"; exit 1; }
  grep -q "WARNING: ThreadSanitizer" "$LOG" && { cat "$LOG"; echo "run_tsan: a TSan report"; exit 1; }
  tail -1 "$LOG"
}
run "$BUILD/tests/tsan/openmp_loops_test"
# The SACT property test's own parallel loop.
run "$BUILD/tests/collision/collision_test" --gtest_filter='SactPropertyArtifact.*'
echo "run_tsan: every OpenMP loop ran under ThreadSanitizer with archer, no report"
