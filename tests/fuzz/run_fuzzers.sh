#!/usr/bin/env bash
# Runs libFuzzer targets of a RC_BUILD_FUZZERS build on a scratch corpus
# seeded from tests/fuzz/corpus/<target> (the repository is never written).
# Any crash, leak, timeout, sanitizer report or oversized allocation fails
# the run; its input is kept in the artifact folder, to be added to the
# corpus with a regression test (docs/robustness.md).
#
# Two modes:
# - ci: each target runs the fixed number of inputs listed in ci_runs.txt.
#   The run is reproducible: a fixed libFuzzer -seed (RC_FUZZ_SEED, default
#   1), the seed files in sorted order, no corpus reloads, and address-space
#   randomization off (setarch -R; libFuzzer's comparison tables are indexed
#   by code address). Every machine then tries the same inputs in the same
#   order, so CI finds exactly what a run here finds, however fast it is.
# - <seconds>: each target for that long, to explore (findings depend on
#   the machine's speed; set RC_FUZZ_SEED to vary the sequence).
# Usage: run_fuzzers.sh <fuzzer build folder> ci|<seconds> [artifact folder] [target...]
set -u
BUILD="$1"
MODE="$2"
SEED="${RC_FUZZ_SEED:-1}"
ARTIFACTS="${3:-$(pwd)/fuzz-artifacts}"
shift $(( $# >= 3 ? 3 : $# ))
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$ARTIFACTS"
ARTIFACTS="$(cd "$ARTIFACTS" && pwd)"
SCRATCH="$(mktemp -d)"
trap 'rm -rf "$SCRATCH"' EXIT
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in "$HERE"/corpus/*/; do targets+=("$(basename "$dir")"); done
fi

# Address-space randomization off where the kernel lets us (a container's
# seccomp profile may not); without it a ci run still runs, but is only
# reproducible on this machine's draw of addresses.
NORANDOM=()
if [ "$MODE" = ci ]; then
  if setarch "$(uname -m)" -R true 2>/dev/null; then
    NORANDOM=(setarch "$(uname -m)" -R)
  else
    echo "run_fuzzers: setarch -R is refused here; inputs may differ from another machine's run"
  fi
fi

# The inputs a target runs in ci mode (ci_runs.txt: "<target> <inputs>").
ci_runs() {
  awk -v t="$1" '$1 == t { print $2 }' "$HERE/ci_runs.txt"
}

failed=()
for target in "${targets[@]}"; do
  binary="$BUILD/$target"
  [ -x "$binary" ] || { echo "run_fuzzers: no binary $binary"; failed+=("$target"); continue; }
  if [ "$MODE" = ci ]; then
    runs="$(ci_runs "$target")"
    [ -n "$runs" ] || { echo "run_fuzzers: $target has no line in ci_runs.txt"; failed+=("$target"); continue; }
    limit=(-runs="$runs" -reload=0)
  else
    limit=(-max_total_time="$MODE")
  fi
  # Each target runs in a folder of its own, from fixed relative names
  # (./fuzzer, corpus/, seeds/000001..., art/) under a fixed environment:
  # code compares pointers, libFuzzer keeps compared values as mutation
  # material, and the stack's addresses shift with the length of the
  # arguments and the environment, so ci mode keeps those the same on
  # every machine. The seeds are in sorted order (folders are read in
  # directory order, which differs between file systems); seed folders
  # outside tests/ are the SEEDS of tests/fuzz/CMakeLists.txt.
  work="$SCRATCH/$target"
  mkdir -p "$work/corpus" "$work/seeds"
  seed_dirs=("$HERE/corpus/$target")
  [ "$target" = fuzz_micro_program ] && seed_dirs+=("$HERE/../../robocore/programs")
  count=0
  while IFS= read -r file; do
    count=$((count + 1))
    ln -s "$file" "$work/seeds/$(printf %06d "$count")"
  done < <(find "${seed_dirs[@]}" -type f | LC_ALL=C sort)
  (cd "$work" && ls seeds | sed 's|^|seeds/|' | paste -sd, > seeds.txt)
  ln -s "$(cd "$(dirname "$binary")" && pwd)/$target" "$work/fuzzer"
  ln -s "$ARTIFACTS" "$work/art"
  start=$SECONDS
  # -timeout: one input may take 10 s (a hang otherwise); -rss_limit_mb and
  # -malloc_limit_mb: a parser must refuse an impossible size before it
  # allocates, so one allocation above 1 GiB is a finding.
  if (cd "$work" && env -i PATH=/usr/bin:/bin ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
        UBSAN_OPTIONS=print_stacktrace=1 "${NORANDOM[@]}" ./fuzzer corpus -seed_inputs=@seeds.txt "${limit[@]}" \
        -seed="$SEED" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 \
        -artifact_prefix="art/$target-") >"$ARTIFACTS/$target.log" 2>&1; then
    done_runs=$(grep -aEo 'stat::number_of_executed_units: *[0-9]+' "$ARTIFACTS/$target.log" | grep -Eo '[0-9]+$')
    echo "fuzz $target: ${done_runs:-?} inputs in $((SECONDS - start)) s (seed $SEED), no finding"
  else
    echo "fuzz $target: FINDING with seed $SEED (log: $ARTIFACTS/$target.log)"
    grep -aE "ERROR|SUMMARY|finding|terminate|==[0-9]+==" "$ARTIFACTS/$target.log" | head -5
    failed+=("$target")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "run_fuzzers: findings or failures in: ${failed[*]}"
  exit 1
fi
