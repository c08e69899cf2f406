#!/usr/bin/env bash
# End-to-end bad-input checks of the rcbench CLI. Every case asserts three
# things (docs/robustness.md):
#   1. the message names the file and line ("file:line") and the field
#      (usage errors: the option), or the numbers of a size that cannot fit;
#   2. the exit code is the documented one (common/exit_codes.h);
#   3. no output is left behind: no summary, no temporary file, and a
#      timeline only as a prefix marked incomplete on its first line.
# Valid inputs from other robots and logs with a known clock glitch are read,
# not refused (the "accepted" cases at the end).
# Usage: bad_input.sh <path to rcbench>
set -u
RCBENCH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
failures=0
passes=0
MARKER='# rcbench: INCOMPLETE'

# No output but a marked timeline prefix; prints what is wrong.
outputs_clean() {
  local ok=0
  if [ -e summary.json ]; then echo "  summary.json left behind"; ok=1; fi
  if [ -e timeline.csv ] && [ "$(head -c ${#MARKER} timeline.csv)" != "$MARKER" ]; then
    echo "  timeline.csv left behind without the incomplete marker"; ok=1
  fi
  if ls ./*.tmp* ./out/*.tmp* >/dev/null 2>&1; then echo "  temporary file left behind"; ok=1; fi
  return $ok
}

# expect <name> <exit code> <where> <field> -- <rcbench args...>
#   where: text naming the place, "file:line" for input errors
#   field: "field 'name'" for input errors, the option for usage errors
expect() {
  local name="$1" code="$2" where="$3" field="$4"
  shift 5
  rm -f timeline.csv summary.json
  "$RCBENCH" "$@" --timeline timeline.csv --summary summary.json --quiet >out.txt 2>err.txt
  local got=$?
  local ok=1
  [ "$got" -eq "$code" ] || { echo "FAIL $name: exit $got, expected $code"; ok=0; }
  grep -qF -- "$where" err.txt || { echo "FAIL $name: message lacks '$where':"; cat err.txt; ok=0; }
  grep -qF -- "$field" err.txt || { echo "FAIL $name: message lacks '$field':"; cat err.txt; ok=0; }
  outputs_clean || { echo "FAIL $name: output left behind"; ok=0; }
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); else failures=$((failures + 1)); fi
}

# accept <name> <text the output must contain> -- <rcbench args...>: exit 0.
accept() {
  local name="$1" text="$2"
  shift 3
  "$RCBENCH" "$@" --quiet >out.txt 2>err.txt
  local got=$?
  local ok=1
  [ "$got" -eq 0 ] || { echo "FAIL $name: exit $got, expected 0:"; cat err.txt; ok=0; }
  cat out.txt err.txt | grep -qF -- "$text" || { echo "FAIL $name: output lacks '$text':"; cat out.txt err.txt; ok=0; }
  if [ $ok -eq 1 ]; then passes=$((passes + 1)); else failures=$((failures + 1)); fi
}

# A valid small map and trace to corrupt: line 1 is an L record of 188
# fields (L x y theta xl yl thetal r1..r180 ts).
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
# A header that declares 10^10 cells: refused before anything is allocated.
printf 'robot_specifications->resolution 10\nglobal_map[0]: 100000 100000\n' > huge.dat
# 2000 x 2000 cells of 10 cm, declared only: over a 1 MiB memory cap.
printf 'robot_specifications->resolution 10\nglobal_map[0]: 2000 2000\n' > big.dat
# Record 3's laser pose puts the laser 0.30 m ahead, records 1-2 0.25 m.
awk 'NR==3 { $5 = $2 + 5 * cos($4); $6 = $3 + 5 * sin($4) + 0 } { print }' OFMT='%.6f' good.log > moved_mount.log
# Record 3 is 1 s earlier than record 2: not a clock glitch.
awk 'NR==3 { $NF = $NF - 1.0 - 0.2 } { print }' OFMT='%.6f' good.log > backwards.log

expect truncated-trace 1 "truncated.log:1" "field 'range" -- delibot --map map.yaml --trace truncated.log
expect nan-range 1 "nan.log:3" "field 'range 13'" -- delibot --map map.yaml --trace nan.log
expect inf-range 1 "inf.log:2" "field 'range 23'" -- delibot --map map.yaml --trace inf.log
expect negative-range 1 "negative.log:4" "field 'range 43'" -- delibot --map map.yaml --trace negative.log
expect wrong-beam-count 1 "short_beams.log:2" "field 'ts'" -- delibot --map map.yaml --trace short_beams.log
expect missing-trace 1 "nope.log" "cannot open" -- delibot --map map.yaml --trace nope.log
expect no-free-cell 1 "walls.yaml: the map has no free cell" "no free cell" -- delibot --map walls.yaml --trace good.log
expect bad-resolution 1 "badres.yaml:2" "field 'resolution'" -- delibot --map badres.yaml --trace good.log
expect truncated-map 1 "truncated.dat:6" "field 'map row 0'" -- delibot --map truncated.dat --trace good.log
expect huge-map 1 "huge.dat:2" "100000 x 100000 cells" -- delibot --map huge.dat --trace good.log
expect map-over-memory-cap 1 "big.dat:2" "memory cap" -- delibot --map big.dat --trace good.log --max-memory 0.001
expect moved-mount 1 "moved_mount.log:3" "field 'xl/yl'" -- delibot --map map.yaml --trace moved_mount.log
expect time-backwards 1 "backwards.log:3" "field 'ts'" -- delibot --map map.yaml --trace backwards.log
expect bad-option 2 "particles" "[1, 10^7]" -- delibot --particles 0
expect particles-over-memory-cap 2 "memory cap" "--particles" -- delibot --map map.yaml --trace good.log --particles 10000000 --max-memory 0.5
expect map-without-trace 2 "--trace" "--map" -- delibot --map map.yaml
expect unknown-lf-combine 2 "--lf-combine" "cube" -- delibot --map map.yaml --trace good.log --lf-combine cube
expect injection-check-out-of-range 2 "injection check" "[0, 1000]" -- delibot --map map.yaml --trace good.log --injection-check 5000
expect hypothesis-floor-out-of-range 2 "hypothesis floor" "particles / 2" -- delibot --map map.yaml --trace good.log --hypothesis-floor 5000
expect hypothesis-window-negative 2 "hypothesis window" "[0, 10^4] nats" -- delibot --map map.yaml --trace good.log --hypothesis-floor 20 --hypothesis-window -1
expect bad-backend 2 "--backend" "fastest" -- delibot --map map.yaml --trace good.log --backend fastest
expect occupied-thresh-range 2 "--occupied-thresh" "1.5" -- delibot --map truncated.dat --trace good.log --occupied-thresh 1.5
expect thresholds-crossed 2 "--free-thresh" "below --occupied-thresh" -- delibot --map truncated.dat --trace good.log --free-thresh 0.7 --occupied-thresh 0.6
expect thresholds-on-ros-yaml 2 "occupied/free thresholds" "ros" -- delibot --map map.yaml --trace good.log --free-thresh 0.1
expect laser-offset-range 2 "--laser-offset" "[0, 10] m" -- delibot --map map.yaml --trace good.log --laser-offset 11
expect initial-particles-not-a-count 2 "--initial-particles" "'lots' is neither auto nor a count" -- delibot --map map.yaml --trace good.log --initial-particles lots
expect initial-particles-below-the-set 2 "initial particles" "initial particles" -- delibot --map map.yaml --trace good.log --initial-particles 10
expect unknown-sensor-model 2 "--sensor-model" "likelihood-then-beam" -- delibot --map map.yaml --trace good.log --sensor-model staged

# An output that cannot be written: exit 1, the path named, nothing left.
rm -f timeline.csv
"$RCBENCH" delibot --map map.yaml --trace good.log --max-records 2 --quiet --timeline timeline.csv \
  --summary /proc/rcbench/summary.json >out.txt 2>err.txt
got=$?
if [ "$got" -eq 1 ] && grep -qF "/proc/rcbench/summary.json: cannot create the output folder" err.txt &&
  outputs_clean && [ ! -e timeline.csv ]; then
  passes=$((passes + 1))
else
  echo "FAIL unwritable-summary: exit $got:"; cat err.txt; failures=$((failures + 1))
fi

# Valid inputs: read, not refused.
awk 'NR==3 { $NF = $NF - 0.3 } { print }' OFMT='%.6f' good.log > glitch.log
accept clock-glitch-is-a-counted-warning "1 laser record(s) step back in time" -- delibot --map map.yaml --trace glitch.log --max-records 5
"$RCBENCH" simulate --map map.yaml --output mount20.log --records 5 --laser-offset 0.2 >/dev/null || { echo "simulate 0.2 failed"; exit 1; }
accept another-robots-mount "laser 0.2000 m ahead, measured from the file's laser poses" -- delibot --map map.yaml --trace mount20.log --max-records 2
accept laser-offset-override "laser 0.3000 m ahead (--laser-offset)" -- delibot --map map.yaml --trace mount20.log --max-records 2 --laser-offset 0.3
# 10 x 10 cells of P(free) 1, three of 0.7 (P(occupied) 0.3), one never observed.
awk 'BEGIN { print "robot_specifications->resolution 10"; print "global_map[0]: 10 10";
  for (x = 0; x < 10; ++x) { line = ""; for (y = 0; y < 10; ++y) {
    v = (x == 5 && y < 3) ? "0.7" : (x == 9 && y == 0 ? "-1" : "1"); line = line (y ? " " : "") v }; print line } }' > halo.dat
accept default-thresholds-on-dat-map "between thresholds 3 (3.0% of all" -- carribot --map halo.dat --start 0,9 --goal 9,9
accept thresholds-on-dat-map "free 99 (99.0%)" -- carribot --map halo.dat --start 0,9 --goal 9,9 --free-thresh 0.35

# A PNG map cut short or with one byte changed: libpng printed "libpng
# error: Read Error" (or a CRC error) on stderr before our message. Now our
# message, naming the image and the chunk, is the only line (exit 1).
"$RCBENCH" carribot --map halo.dat --start 0,9 --goal 9,9 --plot plot.png --quiet >/dev/null 2>&1 ||
  { echo "carribot --plot failed"; exit 1; }
head -c $(($(wc -c < plot.png) - 20)) plot.png > cut.png
cp plot.png changed.png
printf 'Z' | dd of=changed.png bs=1 seek=37 conv=notrunc 2>/dev/null  # the second chunk's type
# A JPEG map cut short: libjpeg printed "Premature end of JPEG file" and
# filled the rest grey. Now our message, naming the image and libjpeg's stage
# (maps/image_jpeg_check.h), is the only line (exit 1). The map: 16 x 16
# white cells, 101 bytes written by OpenCV, less its APP0 and DHT (libjpeg
# then uses T.81 Annex K's tables).
printf '%s' '/9j/2wBDAAIBAQEBAQIBAQECAgICAgQDAgICAgUEBAMEBgUGBgYFBgYGBwkIBgcJBwYGCAsICQoK
CgoKBggLDAsKDAkKCgr/wAALCAAQABABAREA/9oACAEBAAA/AP38ooor/9k=' | base64 -d > white.jpg
accept jpeg-map "free 256 (100.0%)" -- carribot --map white.jpg --resolution 0.1 --start 0,9 --goal 9,9
head -c 98 white.jpg > cut.jpg  # 4 of the 5 bytes of scan data, no EOI

# Each corrupt image: exit 1, one line on stderr naming the image, the field
# (its start, when given) and the problem. Cases: image|field|problem.
for case in "cut.png||truncated" "changed.png||CRC mismatch" "cut.jpg|scan data'|truncated"; do
  IFS='|' read -r image field problem <<< "$case"
  "$RCBENCH" carribot --map "$image" --resolution 0.1 --start 0,9 --goal 9,9 --quiet >out.txt 2>err.txt
  got=$?
  if [ "$got" -eq 1 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -qF "$image: field '$field" err.txt &&
    grep -qF "$problem" err.txt; then
    passes=$((passes + 1))
  else
    echo "FAIL corrupt-image $image: exit $got, stderr:"; cat err.txt; failures=$((failures + 1))
  fi
done

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
