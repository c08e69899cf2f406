#!/usr/bin/env bash
# End-to-end bad-input checks of the rcbench CLI: every malformed input gets a
# message naming the file, the line and the field, a nonzero exit, and no
# partial output file.
# Usage: bad_input.sh <path to rcbench>
set -u
RCBENCH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
failures=0
passes=0

# expect <name> <exit code> <text the message must contain> -- <rcbench args...>
expect() {
  local name="$1" code="$2" text="$3"
  shift 4
  rm -f timeline.csv summary.json
  "$RCBENCH" "$@" --timeline timeline.csv --summary summary.json --quiet >out.txt 2>err.txt
  local got=$?
  local ok=1
  [ "$got" -eq "$code" ] || { echo "FAIL $name: exit $got, expected $code"; ok=0; }
  grep -qF -- "$text" err.txt || { echo "FAIL $name: message lacks '$text':"; cat err.txt; ok=0; }
  if [ -e timeline.csv ] || [ -e summary.json ] || ls ./*.tmp* >/dev/null 2>&1; then
    echo "FAIL $name: partial output left behind"; ok=0
  fi
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); else failures=$((failures + 1)); fi
}

# A valid small map and trace to corrupt.
"$RCBENCH" make-map --output map.yaml >/dev/null || { echo "make-map failed"; exit 1; }
"$RCBENCH" simulate --map map.yaml --output good.log --records 5 >/dev/null || { echo "simulate failed"; exit 1; }
head -c 300 good.log > truncated.log
awk 'NR==3 { $20 = "nan" } { print }' good.log > nan.log
awk 'NR==2 { $30 = "inf" } { print }' good.log > inf.log
awk 'NR==4 { $50 = "-12" } { print }' good.log > negative.log
awk 'NR==2 { NF = NF - 2; $(NF+1) = "1.0" } { print }' good.log > short_beams.log
printf 'P2\n4 4\n255\n0 0 0 0\n0 0 0 0\n0 0 0 0\n0 0 0 0\n' > walls.pgm
printf 'image: walls.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n' > walls.yaml
printf 'image: map.pgm\nresolution: -0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n' > badres.yaml
printf 'robot_specifications->global_mapsize_x 100\nrobot_specifications->global_mapsize_y 100\nrobot_specifications->resolution 10\n\nglobal_map[0]: 10 10\n1 1 1\n' > truncated.dat

expect truncated-trace 1 "truncated.log:" -- delibot --map map.yaml --trace truncated.log
expect nan-range 1 "nan.log:3" -- delibot --map map.yaml --trace nan.log
expect inf-range 1 "inf.log:2" -- delibot --map map.yaml --trace inf.log
expect negative-range 1 "negative.log:4" -- delibot --map map.yaml --trace negative.log
expect wrong-beam-count 1 "short_beams.log:2" -- delibot --map map.yaml --trace short_beams.log
expect missing-trace 1 "nope.log" -- delibot --map map.yaml --trace nope.log
expect no-free-cell 1 "walls.yaml: the map has no free cell" -- delibot --map walls.yaml --trace good.log
expect bad-resolution 1 "resolution" -- delibot --map badres.yaml --trace good.log
expect truncated-map 1 "truncated.dat:6" -- delibot --map truncated.dat --trace good.log
expect bad-option 2 "particles" -- delibot --particles 0
expect map-without-trace 2 "--trace" -- delibot --map map.yaml
expect unknown-lf-combine 2 "--lf-combine" -- delibot --map map.yaml --trace good.log --lf-combine cube
expect injection-check-out-of-range 2 "injection check" -- delibot --map map.yaml --trace good.log --injection-check 5000
expect hypothesis-floor-out-of-range 2 "hypothesis floor" -- delibot --map map.yaml --trace good.log --hypothesis-floor 5000
expect hypothesis-window-negative 2 "hypothesis window" -- delibot --map map.yaml --trace good.log --hypothesis-floor 20 --hypothesis-window -1
expect initial-particles-not-a-count 2 "--initial-particles: 'lots' is neither auto nor a count" -- delibot --map map.yaml --trace good.log --initial-particles lots
expect initial-particles-below-the-set 2 "initial particles" -- delibot --map map.yaml --trace good.log --initial-particles 10
expect unknown-sensor-model 2 "likelihood-then-beam" -- delibot --map map.yaml --trace good.log --sensor-model staged

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
