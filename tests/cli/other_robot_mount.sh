#!/usr/bin/env bash
# A CMU log of a robot whose laser sits 0.20 m ahead (not the Wean robot's
# 0.25 m) is read, its mount measured from its own laser poses, and it
# localizes; the same log run with a wrong --laser-offset does not, so the
# mount the reader measured is the one the filter used.
# Usage: other_robot_mount.sh <path to rcbench>
source "$(dirname "$0")/cli_check_start.sh" "$@"

"$RCBENCH" make-map --output map.yaml >/dev/null || fail "make-map"
"$RCBENCH" simulate --map map.yaml --output mount20.log --records 80 --laser-offset 0.2 >/dev/null || fail "simulate"
start=$(grep -v '^#' mount20.gt | head -1 | awk '{printf "%s,%s,%s", $2, $3, $4}')
run=(delibot --map map.yaml --trace mount20.log --ground-truth mount20.gt --particles 500 --initial-pose "$start"
     --no-pricing --quiet)

"$RCBENCH" "${run[@]}" --summary right.json >right.txt 2>&1 || { cat right.txt; fail "the 0.20 m log was refused"; }
grep -qF "laser 0.2000 m ahead, measured from the file's laser poses" right.txt || { cat right.txt; fail "mount not measured"; }
"$RCBENCH" "${run[@]}" --laser-offset 0.6 --summary wrong.json >wrong.txt 2>&1 || fail "the override run failed"
python3 - right.json wrong.json <<'PY' || fail "accuracy"
import json, sys
right = json.load(open(sys.argv[1]))["accuracy"]
wrong = json.load(open(sys.argv[2]))["accuracy"]
print(f"measured mount: converged {right['converged_at_end']}, median error {right['median_err_xy_m']:.3f} m; "
      f"--laser-offset 0.6: converged {wrong['converged_at_end']}, final error {wrong['final_err_xy_m']:.3f} m")
assert right["converged_at_end"] and 0 <= right["median_err_xy_m"] < 0.05
assert right["final_err_xy_m"] < 0.05
assert wrong["final_err_xy_m"] > 2 * right["final_err_xy_m"]
PY
echo "other_robot_mount: passed"
