#!/usr/bin/env bash
# A run killed with SIGKILL mid-way leaves a timeline that is a valid,
# marked prefix and no summary (summaries are written atomically, after the
# run); the same run to completion leaves the complete timeline without the
# marker, with the hindsight oracle's columns (traces/csv_table.h).
# Usage: sigkill_timeline.sh <path to rcbench>
source "$(dirname "$0")/cli_check_start.sh" "$@"

"$RCBENCH" make-map --output map.yaml >/dev/null || fail "make-map"
"$RCBENCH" simulate --map map.yaml --output long.log --records 400 >/dev/null || fail "simulate"
run=(delibot --map map.yaml --trace long.log --particles 3000 --threads 1 --quiet)

"$RCBENCH" "${run[@]}" --timeline out/timeline.csv --summary out/summary.json >killed.txt 2>&1 &
pid=$!
# Kill once a few rows are in (marker + header + 4 rows), or give up after 120 s.
for _ in $(seq 1 1200); do
  [ -f out/timeline.csv ] && [ "$(wc -l < out/timeline.csv)" -ge 6 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$pid" 2>/dev/null || fail "the run ended before it could be killed (make the trace longer)"
kill -KILL "$pid"
wait "$pid" 2>/dev/null
[ -f out/timeline.csv ] || fail "no timeline prefix"
[ ! -e out/summary.json ] || python3 -c 'import json,sys; json.load(open(sys.argv[1]))' out/summary.json ||
  fail "a summary exists and is not complete JSON"

python3 - out/timeline.csv <<'PY' || fail "the prefix does not parse"
import csv, io, sys
text = open(sys.argv[1], newline="").read()
marker = "# rcbench: INCOMPLETE"
assert text.startswith(marker), "first line is not the incomplete marker"
body = text.split("\n", 1)[1]
if not body.endswith("\n"):  # killed mid-row: the last line is cut
    body = body[: body.rfind("\n") + 1]
rows = list(csv.reader(io.StringIO(body)))
header, data = rows[0], rows[1:]
assert len(data) >= 4, f"only {len(data)} rows"
for i, row in enumerate(data):
    assert len(row) == len(header), f"row {i} has {len(row)} fields for {len(header)} columns"
    assert int(row[header.index("iteration")]) == i, f"row {i} is iteration {row[0]}"
    float(row[header.index("est_x_m")])
assert "cum_cycles_oracle" not in header, "a prefix cannot know the hindsight oracle"
print(f"killed run: marked prefix of {len(data)} rows, {len(header)} columns")
PY

"$RCBENCH" "${run[@]}" --max-records 12 --timeline out/timeline.csv --summary out/summary.json >done.txt 2>&1 ||
  { cat done.txt; fail "the complete run failed"; }
python3 - out/timeline.csv out/summary.json <<'PY' || fail "the complete timeline is wrong"
import csv, json, sys
text = open(sys.argv[1], newline="").read()
assert not text.startswith("#"), "a complete timeline still carries the marker"
rows = list(csv.reader(text.splitlines()))
header, data = rows[0], rows[1:]
assert len(data) == 12, f"{len(data)} rows for 12 records"
assert header[-2:] == ["cum_cycles_oracle", "oracle_backend"], header[-2:]
assert all(len(r) == len(header) for r in data)
json.load(open(sys.argv[2]))
print(f"complete run: {len(data)} rows, {len(header)} columns, no marker")
PY
ls out/*.tmp* >/dev/null 2>&1 && fail "temporary files left behind"
echo "sigkill_timeline: passed"
