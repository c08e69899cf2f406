#!/usr/bin/env bash
# End-to-end check of `rcbench carribot --backend`: on a tiny map a footprint
# robot plans the same path under every backend policy, every kernel launch
# is priced (cycles per backend in the timeline), the adaptive policy prints
# the scheduler summary with its agreement with the oracle, the threshold
# policy its threshold, and an unreachable goal exits with code 3.
# Usage: carribot_backends.sh <path to rcbench>
set -u
RCBENCH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

printf 'type octile\nheight 6\nwidth 10\nmap\n..........\n..........\n....@.....\n....@.....\n..........\n..........\n' > tiny.map
query=(carribot --map tiny.map --start 1,1 --goal 8,4 --footprint 0.6x1.2 --quiet)

# Every policy per expansion; two in precomputed mode (one launch set-up).
runs="per-expansion:adaptive per-expansion:threshold per-expansion:oracle per-expansion:static:simt per-expansion:static:ttaplus
      per-expansion:static:ttaplus-p per-expansion:static:ttaplus-cr per-expansion:static:robocore
      precomputed:adaptive precomputed:static:robocore"
for run in $runs; do
  mode="${run%%:*}" backend="${run#*:}"
  {
    name="${mode}_${backend/:/_}"
    "$RCBENCH" "${query[@]}" --collision-mode "$mode" --backend "$backend" --path "$name.path.csv" \
      --timeline "$name.timeline.csv" >"$name.out" 2>&1 || { fail "$name: exit $?"; cat "$name.out"; continue; }
    cmp -s "$name.path.csv" "${mode}_adaptive.path.csv" || fail "$name: path differs from adaptive's"
    header=$(head -1 "$name.timeline.csv")
    for column in backend cycles_simt cycles_ttaplus cycles_ttaplus_p cycles_ttaplus_cr cycles_robocore energy_j nodes_per_query; do
      [[ ",$header," == *",$column,"* ]] || fail "$name: timeline lacks $column"
    done
    grep -q "modelled time (every launch priced on every backend" "$name.out" || fail "$name: no scheduler summary"
    grep -q "oracle" "$name.out" || fail "$name: no oracle line"
  }
done
grep -q "threshold .* nodes per kernel query" per-expansion_threshold.out || fail "threshold: no threshold line"
grep -q "the oracle's choice in [0-9.]*% of priced launches" per-expansion_adaptive.out || fail "adaptive: no agreement with the oracle"
# Precomputed: a set-up row (the kernel fills the configuration space), then the query.
[ "$(grep -c ',setup,' precomputed_adaptive.timeline.csv)" -eq 1 ] || fail "precomputed: no setup row"

# Unreachable goal: exit code 3, a message, and the timeline still written.
printf 'type octile\nheight 3\nwidth 9\nmap\n....@....\n....@....\n....@....\n' > rooms.map
"$RCBENCH" carribot --map rooms.map --start 0,0 --goal 8,2 --footprint 0.4x0.4 --backend adaptive \
  --timeline rooms.csv --quiet >rooms.out 2>&1
code=$?
[ "$code" -eq 3 ] || fail "unreachable goal: exit $code, expected 3"
grep -q "unreachable" rooms.out || fail "unreachable goal: no message"
grep -q "no_path" rooms.csv || fail "unreachable goal: timeline lacks no_path"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "carribot --backend: all checks passed"
