#!/usr/bin/env bash
# The exit-code table (common/exit_codes.h) holds for every subcommand:
# 2 for a bad command line (an unknown option, a bad --backend), 1 for a
# file that cannot be read, 3 for no path (carribot, movebot), and every
# --help states the table.
# Usage: exit_codes.sh <path to rcbench>
set -u
RCBENCH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
failures=0
checks=0
# code <expected> <name> -- <rcbench args...>
code() {
  local expected="$1" name="$2"
  shift 3
  "$RCBENCH" "$@" >out.txt 2>err.txt
  local got=$?
  checks=$((checks + 1))
  if [ "$got" -ne "$expected" ]; then
    echo "FAIL $name: exit $got, expected $expected"; cat err.txt; failures=$((failures + 1))
  fi
}

"$RCBENCH" make-map --output map.yaml >/dev/null || { echo "make-map failed"; exit 1; }
"$RCBENCH" simulate --map map.yaml --output good.log --records 3 >/dev/null || { echo "simulate failed"; exit 1; }
printf 'type octile\nheight 3\nwidth 5\nmap\n..@..\n..@..\n..@..\n' > wall.map
printf 'version 1\n0\twall.map\t5\t3\t0\t0\t4\t0\t4\n' > wall.map.scen
printf 'not json' > bad.json

for sub in delibot carribot simulate make-map backends collide calibrate movebot; do
  code 2 "$sub unknown option" -- "$sub" --no-such-option
  "$RCBENCH" "$sub" --help > help.txt 2>&1
  grep -q "Exit codes: 0 success; 1 bad input" help.txt || { echo "FAIL $sub --help lacks the exit-code table"; failures=$((failures + 1)); }
done

# --simd takes a level the CPU runs; any level it runs gives a run (the
# same results: tests/delibot/default_settings_test.cc).
code 2 "--simd unknown" -- --simd sse2 delibot --map map.yaml --trace good.log
code 0 "--simd scalar" -- --simd scalar delibot --map map.yaml --trace good.log --quiet --max-records 2 \
  --summary simd.json
checks=$((checks + 1))
python3 -c 'import json, sys; sys.exit(json.load(open("simd.json"))["config"]["simd"] != "scalar")' ||
  { echo "FAIL --simd scalar: the summary's config.simd is not scalar"; failures=$((failures + 1)); }
grep -q avx512 /proc/cpuinfo || code 2 "--simd above the CPU" -- --simd avx512 delibot --map map.yaml --trace good.log

# A bad --backend is a usage error everywhere it exists.
code 2 "delibot --backend" -- delibot --map map.yaml --trace good.log --backend fastest
code 2 "carribot --backend" -- carribot --map wall.map --start 0,0 --goal 1,0 --backend fastest
code 2 "movebot --backend" -- movebot --iterations 10 --backend fastest
code 2 "collide --backend" -- collide --scene shelf --backend fastest
code 2 "delibot --priced-launches" -- delibot --map map.yaml --trace good.log --priced-launches -1
code 2 "delibot --replay-sms" -- delibot --map map.yaml --trace good.log --replay-sms -1
code 2 "delibot --replay-block-stride" -- delibot --map map.yaml --trace good.log --replay-block-stride 0
code 2 "delibot --first-set-model tracking, one-stage model" -- delibot --map map.yaml --trace good.log --sensor-model beam --first-set-model tracking
code 2 "delibot --claim-audit with the MRPT engine" -- delibot --map map.yaml --trace good.log --engine mrpt --claim-audit
code 2 "delibot --claim-audit-scans with --no-claim-audit" -- delibot --map map.yaml --trace good.log --no-claim-audit --claim-audit-scans 30
code 2 "delibot --claim-audit with --no-claim-audit" -- delibot --map map.yaml --trace good.log --claim-audit --no-claim-audit
code 2 "delibot --claim-audit-scans 0" -- delibot --map map.yaml --trace good.log --claim-audit-scans 0

# A file that cannot be read is bad input.
code 1 "delibot missing map" -- delibot --map absent.yaml --trace good.log
code 1 "carribot missing map" -- carribot --map absent.map --start 0,0 --goal 1,0
code 1 "carribot missing scen" -- carribot --map wall.map --scen absent.scen
code 1 "simulate missing map" -- simulate --map absent.yaml --output x.log
code 1 "collide missing boxes" -- collide --obbs absent.csv --scene shelf
code 1 "movebot missing obstacles" -- movebot --obstacles absent.txt
code 1 "backends bad params" -- backends --backend-params bad.json

# Values a run cannot use are refused, never replaced by a default.
code 2 "carribot --resolution nan" -- carribot --map wall.map --start 0,0 --goal 1,0 --resolution nan
code 2 "delibot --map-resolution nan" -- delibot --map map.yaml --trace good.log --map-resolution nan
code 2 "delibot --max-range inf" -- delibot --map map.yaml --trace good.log --max-range inf
code 2 "simulate --map-format without --map" -- simulate --map-format cmu --output sim.log --records 3
code 2 "delibot --map-resolution without --map" -- delibot --map-resolution 0.1 --max-records 2
code 2 "delibot --initial-pose nan" -- delibot --map map.yaml --trace good.log --initial-pose nan,1,0
code 2 "delibot --initial-pose off the map" -- delibot --map map.yaml --trace good.log --initial-pose 500,500,0
grep -q "^rcbench: usage: --initial-pose" err.txt || { echo "FAIL --initial-pose: no usage line"; failures=$((failures + 1)); }
# A JSON number beyond a double's range is bad input on every path in.
printf '{"gpu": {"sms": 1e400}}' > overflow.json
printf 'pos,joint,c_x,c_y,c_z,a_x1,a_y1,a_z1,a_x2,a_y2,a_z2,a_x3,a_y3,a_z3,h_x,h_y,h_z\n0,0,0,0,0.1,1,0,0,0,1,0,0,0,1,0.1,0.1,0.1\n' > one.csv
code 1 "backends --backend-params 1e400" -- backends --backend-params overflow.json
code 1 "collide --backend-params 1e400" -- collide --obbs one.csv --scene shelf --backend-params overflow.json
# MoveBot: a start outside the joint limits or folded into itself is a bad
# command line, one in collision with the scene bad input naming the
# scene's file.
printf '0, 0, 0, 5, 5, 5, 0.1, 0.1, 0.1\n' > far.txt
printf '0, 0, 0, 0, 0, 0.3, 2, 2, 2\n' > around.txt
code 2 "movebot --start beyond a joint limit" -- movebot --obstacles far.txt --iterations 10 --start 2,0,0,0,0
code 2 "movebot --start nan" -- movebot --obstacles far.txt --iterations 10 --start nan,0,0,0,0
code 1 "movebot start in collision" -- movebot --obstacles around.txt --iterations 10
grep -q "around.txt.*in collision" err.txt || { echo "FAIL movebot collision: file not named"; failures=$((failures + 1)); }
code 2 "movebot goal in self-collision" -- movebot --obstacles far.txt --iterations 10 --goal 0,0,1.5,1.5,0
grep -q "goal.*in self-collision: link 0 (upper arm) and link 2 (wrist) overlap" err.txt ||
  { echo "FAIL movebot self-collision: links not named"; failures=$((failures + 1)); }
# simulate on a map with no free cell: bad input, not an internal error.
printf 'type octile\nheight 2\nwidth 2\nmap\n@@\n@@\n' > full.map
code 1 "simulate no free cell" -- simulate --map full.map --output sim.log --records 3
[ -e sim.log ] && { echo "FAIL simulate no free cell: wrote sim.log"; failures=$((failures + 1)); }

# An output path that cannot be written fails before the run, so no other
# output of the run is left behind.
mkdir -p a_folder
code 1 "carribot --path a folder" -- carribot --map wall.map --start 0,0 --goal 1,0 --timeline t1.csv --path a_folder
code 1 "carribot --plot under a file" -- carribot --map wall.map --start 0,0 --goal 1,0 --timeline t1.csv --plot good.log/x.png
code 1 "delibot --summary a folder" -- delibot --map map.yaml --trace good.log --timeline t1.csv --summary a_folder
code 1 "movebot --path a folder" -- movebot --obstacles far.txt --iterations 10 --timeline t1.csv --path a_folder
code 1 "simulate --ground-truth a folder" -- simulate --map map.yaml --output t1.log --ground-truth a_folder --records 3
code 1 "collide --timeline a folder" -- collide --obbs one.csv --scene shelf --output t1.csv --timeline a_folder
code 1 "make-map --output a folder" -- make-map --output a_folder
code 1 "carribot two outputs, one path" -- carribot --map wall.map --start 0,0 --goal 1,0 --timeline t1.csv --path t1.csv
for f in t1.csv t1.log a_folder.pgm; do
  [ -e "$f" ] && { echo "FAIL an output was left behind: $f"; failures=$((failures + 1)); }
done

# No path: carribot's goal behind a wall; outputs are still written.
code 3 "carribot unreachable" -- carribot --map wall.map --scen wall.map.scen --timeline t.csv --quiet
[ -f t.csv ] || { echo "FAIL carribot unreachable: no timeline"; failures=$((failures + 1)); }

echo "$checks checks, $failures failed"
[ "$failures" -eq 0 ]
