#!/usr/bin/python3
"""The full DeliBot accuracy study (the CI runs a reduced version:
tests/delibot/accuracy_regression_test.cc).

For each map (the generated office map, and Wean Hall when ../shared/data is
present) and each of N seeds: simulate a trace with ground truth
(`rcbench simulate`, default noise: range noise, clutter, people, dropouts,
drifting odometry), then run
  - global localization from uniform particles (default 5000 particles), and
  - tracking from the true first pose,
and report:
  - the fraction of seeds whose global localization converged (error below
    0.2 m and 5 deg for 10 consecutive records, and still so at the end);
  - the median tracking error, the runs still within 0.2 m at the end, and
    the jumps (estimate moved > 1 m between records) after convergence.
The default trace is 1000 records (100 s, about 45 m of driving), within the
range of the real Wean logs (713-2200+ records): at 500 records three of the
20 simulated Wean seeds had not yet found the true pose (they all do by
record 917). Tracking runs 500 particles (--tracking-particles): the harder
case for recovery, since one random particle is a larger share of the set
(with published augmented MCL, --injection-check 0, 4 of 40 tracked runs
jumped away).
Global localization also reports the filter's own (ground-truth-free)
claim of convergence and whether it held: at least 95 % of the records from
the claim on within 1 m of the truth (what a user without ground truth would
have relied on), and the same for the claim standing at the end (a claim the
filter contradicted later, by a jump or injected particles, is withdrawn).
Writes <out>/accuracy_study.csv and <out>/accuracy_study.md.

Held-out checks (docs/defaults.md) use other maps, seeds and noise:
--maps picks the maps (office = `rcbench make-map`, office:S = its furniture
seed S, wean = wean.dat, intel = the Intel lab at 0.1 m cells), --first-seed
the first seed, --simulate-args extra `rcbench simulate` options (quoted),
--modes global,tracking which runs. The table also counts the own claims:
made, held, wrong (made but not held) and never made.

Usage: scripts/accuracy_study.py [--rcbench build/rcbench] [--out out/accuracy]
       [--seeds 20] [--first-seed 1] [--particles 5000] [--tracking-particles 500] [--records 1000]
       [--maps office,wean] [--simulate-args "--range-sigma 0.05"] [--modes global,tracking]
       [-- EXTRA RCBENCH DELIBOT ARGS]   (e.g. -- --hypothesis-floor 20)
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys

from rcbench_files import SHARED_DATA, InputError, read_poses, read_timeline_rows, split_extra_args

WEAN = os.path.join(SHARED_DATA, "wean", "wean.dat")
INTEL = os.path.join(SHARED_DATA, "intel", "Intel.map")


def run(cmd):
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit(f"command failed ({result.returncode}): {' '.join(cmd)}\n{result.stderr}")


def first_pose(gt_path):
    """The ground truth's first pose as rcbench's --initial-pose X,Y,THETA."""
    try:
        _, x, y, theta = read_poses(gt_path)[0]
    except InputError as e:
        sys.exit(f"accuracy_study: {e}")
    return f"{x!r},{y!r},{theta!r}"


def read_errors(timeline):
    """The timeline's (iteration, err_xy_m) rows."""
    try:
        return read_timeline_rows(timeline, ("iteration", "err_xy_m"))
    except InputError as e:
        sys.exit(f"accuracy_study: {e}")


def claim_held(rows, claim):
    """At least 95 % of the records from the claim on within 1 m of the truth."""
    if claim < 0:
        return False
    after = [float(r["err_xy_m"]) for r in rows if int(r["iteration"]) >= claim]
    return bool(after) and sum(e < 1.0 for e in after) >= 0.95 * len(after)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--out", default="out/accuracy")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--particles", type=int, default=5000)
    ap.add_argument("--tracking-particles", type=int, default=500)
    ap.add_argument("--records", type=int, default=1000)
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--maps", default="office,wean", help="office, office:SEED, wean, intel (comma-separated)")
    ap.add_argument("--simulate-args", default="", help="extra rcbench simulate options, one quoted string")
    ap.add_argument("--modes", default="global,tracking", help="global, tracking or both (comma-separated)")
    own, extra = split_extra_args(sys.argv[1:])
    args = ap.parse_args(own)
    os.makedirs(args.out, exist_ok=True)
    modes = [m for m in args.modes.split(",") if m]
    if not modes or any(m not in ("global", "tracking") for m in modes):
        sys.exit(f"accuracy_study: --modes '{args.modes}': expected global and/or tracking")

    maps = []  # (name, map path, extra rcbench map options)
    for name in args.maps.split(","):
        if name == "office" or name.startswith("office:"):
            office = os.path.join(args.out, name.replace(":", "_seed") + ".yaml")
            run([args.rcbench, "make-map", "--output", office] +
                (["--seed", name.split(":", 1)[1]] if ":" in name else []))
            maps.append((name.replace(":", "_seed"), office, []))
        elif name in ("wean", "intel"):
            path = WEAN if name == "wean" else INTEL
            if os.path.exists(path):
                maps.append((name, os.path.normpath(path), [] if name == "wean" else ["--map-resolution", "0.1"]))
            else:
                print(f"shared data absent ({path}): {name} skipped", file=sys.stderr)
        else:
            sys.exit(f"accuracy_study: unknown map '{name}' (office, office:SEED, wean, intel)")

    rows = []
    for name, map_path, map_args in maps:
        for seed in range(args.first_seed, args.first_seed + args.seeds):
            trace = os.path.join(args.out, f"{name}_{seed}.log")
            gt = os.path.join(args.out, f"{name}_{seed}.gt")
            run([args.rcbench, "simulate", "--map", map_path, *map_args, "--output", trace, "--ground-truth", gt,
                 "--records", str(args.records), "--seed", str(seed), *args.simulate_args.split()])
            result = {"map": name, "seed": seed}
            for mode in modes:
                summary = os.path.join(args.out, f"{name}_{seed}_{mode}.json")
                cmd = [args.rcbench, "delibot", "--map", map_path, *map_args, "--trace", trace, "--ground-truth", gt,
                       "--particles", str(args.particles if mode == "global" else args.tracking_particles), "--seed", str(seed),
                       "--summary", summary, "--quiet", "--no-pricing", *extra]
                timeline = os.path.join(args.out, f"{name}_{seed}_global.csv")
                if mode == "global":
                    cmd += ["--timeline", timeline]
                else:
                    cmd += ["--initial-pose", first_pose(gt)]
                run(cmd)
                with open(summary) as f:
                    report = json.load(f)
                a, t = report["accuracy"], report["totals"]
                result[f"{mode}_converged"] = int(a["convergence_iteration"] >= 0 and a["converged_at_end"])
                result[f"{mode}_convergence_iteration"] = a["convergence_iteration"]
                result[f"{mode}_median_err_xy_m"] = a["median_err_xy_m"]
                result[f"{mode}_final_err_xy_m"] = a["final_err_xy_m"]
                result[f"{mode}_jumps"] = a["jumps_after_convergence"]
                result[f"{mode}_time_per_update_s"] = t["wall_per_update_s"]
                if mode == "global":
                    claim = a["convergence_iteration_without_ground_truth"]
                    result["global_own_claim_record"] = claim
                    errors = read_errors(timeline)
                    result["global_own_claim_held"] = int(claim_held(errors, claim))
                    standing = a.get("standing_claim_iteration", -1)
                    result["global_standing_claim_record"] = standing
                    result["global_standing_claim_held"] = int(claim_held(errors, standing))
            rows.append(result)
            print(f"{name} seed {seed}: " + ", ".join(
                f"{k}={result[k]}" for k in ("global_converged", "global_convergence_iteration",
                                             "global_own_claim_record", "global_own_claim_held",
                                             "tracking_median_err_xy_m") if k in result), flush=True)

    with open(os.path.join(args.out, "accuracy_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = ["| map | seeds | global localization converged | median convergence record | "
             "jumps after global convergence | global: median error after convergence (m) | "
             "global: own claims made / held / wrong / never | global: median own claim record | "
             "global: claim standing at the end held | tracking median error (m) | worst tracking median (m) | "
             "tracking still localized at the end | tracking jumps |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def cell(values, fmt):
        return fmt.format(statistics.median(values)) if values else "-"

    for name, _, _ in maps:
        sel = [r for r in rows if r["map"] == name]
        line = f"| {name} | {len(sel)} | "
        if "global" in modes:
            conv = [r for r in sel if r["global_converged"]]
            its = [r["global_convergence_iteration"] for r in conv]
            errs = [r["global_median_err_xy_m"] for r in sel if r["global_median_err_xy_m"] >= 0]
            claimed = [r for r in sel if r["global_own_claim_record"] >= 0]
            held = sum(r["global_own_claim_held"] for r in sel)
            line += (f"{len(conv)}/{len(sel)} ({100 * len(conv) / len(sel):.0f}%) | {cell(its, '{}')} | "
                     f"{sum(r['global_jumps'] for r in conv)} | {cell(errs, '{:.3f}')} | "
                     f"{len(claimed)} / {held} / {len(claimed) - held} / {len(sel) - len(claimed)} | "
                     f"{cell([r['global_own_claim_record'] for r in claimed], '{}')} | "
                     f"{sum(r['global_standing_claim_held'] for r in sel)}/{len(sel)} | ")
        else:
            line += "- | - | - | - | - | - | - | "
        if "tracking" in modes:
            trk = [r["tracking_median_err_xy_m"] for r in sel]
            line += (f"{statistics.median(trk):.3f} | {max(trk):.3f} | "
                     f"{sum(1 for r in sel if r['tracking_converged'])}/{len(sel)} | "
                     f"{sum(r['tracking_jumps'] for r in sel)} |")
        else:
            line += "- | - | - | - |"
        lines.append(line)
    with open(os.path.join(args.out, "accuracy_study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
