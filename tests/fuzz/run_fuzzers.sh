#!/usr/bin/env bash
# Runs every libFuzzer target of a RC_BUILD_FUZZERS build for a bounded time
# on a scratch copy of its seed corpus (tests/fuzz/corpus/<target>), so the
# repository is never written. Any crash, leak, timeout, sanitizer report or
# oversized allocation fails the run; its input is kept in the artifact
# folder, to be added to the corpus with a regression test (docs/robustness.md).
# Reproducible: libFuzzer gets a fixed -seed (RC_FUZZ_SEED, default 1; 0
# would mean a fresh random seed per run), so every run of the same tree
# mutates the same inputs in the same order and CI gives the same result.
# The time limit still decides how far along that sequence a run gets: a
# slower machine tries a prefix of what a faster one tries.
# Usage: run_fuzzers.sh <fuzzer build folder> <seconds per target> [artifact folder] [target...]
set -u
BUILD="$1"
SECONDS_EACH="$2"
SEED="${RC_FUZZ_SEED:-1}"
ARTIFACTS="${3:-$(pwd)/fuzz-artifacts}"
shift $(( $# >= 3 ? 3 : $# ))
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$ARTIFACTS"
SCRATCH="$(mktemp -d)"
trap 'rm -rf "$SCRATCH"' EXIT
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in "$HERE"/corpus/*/; do targets+=("$(basename "$dir")"); done
fi
failed=()
for target in "${targets[@]}"; do
  binary="$BUILD/$target"
  [ -x "$binary" ] || { echo "run_fuzzers: no binary $binary"; failed+=("$target"); continue; }
  mkdir -p "$SCRATCH/$target"
  # Seed folders outside tests/ (the SEEDS of tests/fuzz/CMakeLists.txt).
  seeds=()
  [ "$target" = fuzz_micro_program ] && seeds+=("$HERE/../../robocore/programs")
  start=$SECONDS
  # -timeout: one input may take 10 s (a hang otherwise); -rss_limit_mb and
  # -malloc_limit_mb: a parser must refuse an impossible size before it
  # allocates, so one allocation above 1 GiB is a finding.
  if "$binary" "$SCRATCH/$target" "$HERE/corpus/$target" "${seeds[@]}" -max_total_time="$SECONDS_EACH" -seed="$SEED" -timeout=10 \
      -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$ARTIFACTS/$target-" \
      >"$ARTIFACTS/$target.log" 2>&1; then
    runs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$ARTIFACTS/$target.log" | grep -Eo '[0-9]+$')
    echo "fuzz $target: ${runs:-?} inputs in $((SECONDS - start)) s (seed $SEED), no finding"
  else
    echo "fuzz $target: FINDING with seed $SEED (log: $ARTIFACTS/$target.log)"
    grep -E "ERROR|SUMMARY|finding|terminate|==[0-9]+==" "$ARTIFACTS/$target.log" | head -5
    failed+=("$target")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "run_fuzzers: findings or failures in: ${failed[*]}"
  exit 1
fi
