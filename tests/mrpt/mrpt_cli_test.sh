#!/usr/bin/env bash
# rcbench delibot on MRPT's own example log, through our engine and MRPT's,
# and the corrupt / truncated rawlog that must fail cleanly.
# Usage: mrpt_cli_test.sh <rcbench binary>
set -u
rcbench="$1"
data=/usr/share/mrpt/datasets
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

if [[ ! -f $data/localization_demo.rawlog || ! -f $data/localization_demo.simplemap.gz ]]; then
  echo "SKIP: MRPT datasets absent in $data (install mrpt-common, see scripts/setup)"
  exit 0
fi

for engine in ours mrpt; do
  "$rcbench" delibot --map $data/localization_demo.simplemap.gz --trace $data/localization_demo.rawlog \
    --engine $engine --particles 300 --sensor-model likelihood --beam-step 12 --max-range 80 --quiet \
    --timeline "$work/$engine.csv" --summary "$work/$engine.json" > "$work/$engine.out" 2>&1 \
    || { cat "$work/$engine.out"; fail "$engine engine exited nonzero"; }
  rows=$(($(wc -l < "$work/$engine.csv") - 1))
  [[ $rows -eq 37 ]] || fail "$engine timeline has $rows rows, expected 37 (one per scan)"
  grep -q "\"engine\": \"$engine\"" "$work/$engine.json" || fail "$engine summary lacks its engine"
  grep -q "rawlog, 37 laser records, 361 beams" "$work/$engine.out" || fail "$engine run did not report the rawlog"
done

# Truncated and corrupt rawlogs: clear error naming the file, nonzero exit,
# no timeline written.
head -c 15000 $data/localization_demo.rawlog > "$work/truncated.rawlog"
printf 'garbage, not an MRPT archive\n' > "$work/corrupt.rawlog"
for bad in truncated corrupt; do
  "$rcbench" delibot --map $data/localization_demo.simplemap.gz --trace "$work/$bad.rawlog" --engine mrpt \
    --quiet --timeline "$work/$bad.csv" > "$work/$bad.out" 2>&1
  code=$?
  [[ $code -ne 0 ]] || fail "$bad rawlog exited 0"
  [[ $code -lt 128 ]] || fail "$bad rawlog crashed (exit $code)"
  grep -q "$work/$bad.rawlog" "$work/$bad.out" || { cat "$work/$bad.out"; fail "$bad rawlog error does not name the file"; }
  [[ ! -e $work/$bad.csv ]] || fail "$bad rawlog left a partial timeline"
done
echo "PASS"
