#!/usr/bin/env bash
# The models' reach fitted to the trace (returns_beyond_reach.h), end to
# end: on a trace through the generated 60 m hall, where about 40 % of the
# returns lie beyond 10 m, `rcbench delibot` without --max-range widens the
# reach (note and summary agree), and with --max-range 10 keeps it and says
# what it leaves out; on the office, nothing is fitted or said.
# Usage: fitted_reach.sh <path to rcbench>
source "$(dirname "$0")/cli_check_start.sh" "$@"

"$RCBENCH" make-map --kind hall --output hall.yaml >/dev/null || fail "make-map hall"
"$RCBENCH" simulate --map hall.yaml --output hall.log --records 60 --seed 701 >/dev/null || fail "simulate hall"
"$RCBENCH" make-map --output office.yaml >/dev/null || fail "make-map office"
"$RCBENCH" simulate --map office.yaml --output office.log --records 60 --seed 701 >/dev/null || fail "simulate office"
run=(delibot --max-records 2 --particles 200 --initial-particles 1000 --no-pricing --quiet)

"$RCBENCH" "${run[@]}" --map hall.yaml --trace hall.log --summary fitted.json >fitted.txt 2>&1 || { cat fitted.txt; fail "fitted run"; }
"$RCBENCH" "${run[@]}" --map hall.yaml --trace hall.log --max-range 10 --summary given.json >given.txt 2>&1 \
  || { cat given.txt; fail "given run"; }
"$RCBENCH" "${run[@]}" --map office.yaml --trace office.log --summary office.json >office.txt 2>&1 \
  || { cat office.txt; fail "office run"; }
grep -q "of the trace's returns lie beyond 10 m: the models reach" fitted.txt || { cat fitted.txt; fail "no widening note"; }
grep -q "lie at or beyond --max-range 10 m" given.txt || { cat given.txt; fail "no note for the given reach"; }
if grep -q "returns lie" office.txt; then cat office.txt; fail "a note on the office"; fi
python3 - fitted.txt fitted.json given.json office.json <<'PY' || fail "reach"
import json, re, sys
note = open(sys.argv[1]).read()
fitted, given, office = (json.load(open(p))["config"]["max_range_m"] for p in sys.argv[2:])
said = float(re.search(r"the models reach ([0-9.]+) m", note).group(1))
print(f"fitted reach {fitted} m (note: {said} m), given {given} m, office {office} m")
assert 20.0 < fitted < 81.83 and abs(fitted - said) < 0.05
assert given == 10.0 and office == 10.0
PY
echo "PASS"
