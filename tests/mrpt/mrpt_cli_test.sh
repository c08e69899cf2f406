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

# rcbench opens MRPT from its module (librcbench_mrpt.so); MRPT's
# allocations must still count against the allocation budget of rcbench's
# operator new. A scan declaring about 4e9 ranges (the demo log's first scan,
# its 361-range count with the two high bytes set) is an input error, not a
# 16 GB allocation.
/usr/bin/python3 - "$data/localization_demo.rawlog" "$work/huge_scan.rawlog" <<'PY' || fail "cannot write huge_scan.rawlog"
import gzip, struct, sys
data = bytearray(gzip.decompress(open(sys.argv[1], "rb").read()))
scan = data.find(b"CObservation2DRangeScan")
count = data.find(struct.pack("<I", 361), data.find(b"CPose3D", scan))
assert scan >= 0 and count >= 0
data[count + 2] = data[count + 3] = 0xF0
open(sys.argv[2], "wb").write(data)
PY
"$rcbench" delibot --map $data/localization_demo.simplemap.gz --trace "$work/huge_scan.rawlog" --quiet \
  --timeline "$work/huge.csv" > "$work/huge.out" 2>&1
code=$?
[[ $code -eq 1 ]] || { cat "$work/huge.out"; fail "a scan of 4e9 ranges exited $code, expected 1 (input error)"; }
grep -q "would take more than" "$work/huge.out" || { cat "$work/huge.out"; fail "no allocation-budget error"; }
[[ ! -e $work/huge.csv ]] || fail "the huge scan left a partial timeline"

# The binary itself does not link MRPT: a run that reads no MRPT file never
# loads it.
if ldd "$rcbench" | grep -q libmrpt; then fail "rcbench links MRPT directly (it belongs in librcbench_mrpt.so)"; fi
echo "PASS"
