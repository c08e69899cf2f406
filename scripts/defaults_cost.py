#!/usr/bin/python3
"""What DeliBot's defaults cost per sensor update, beside the previous
defaults and MRPT's localizer, on the built-in demo's inputs.

The demo's inputs (the generated office map and 400 simulated records, seed
1: what `rcbench delibot` without options runs) are made with `rcbench
make-map` and `rcbench simulate`. Every configuration runs with --threads 1
--no-pricing, global localization, seed 1, and again tracking from the
true first pose; the configurations alternate within each of --repeats
rounds, and the CPU time of each run (user + system, from the OS) divided
by its sensor updates is reported as the median over the rounds, so that
a loaded machine slows every configuration alike. Then one priced run of
each of our configurations gives the rays cast and the modelled cycles per
update (the backends price ray casts only: the likelihood field's look-ups
are not priced).

Configurations:
  defaults           rcbench delibot's defaults (docs/defaults.md)
  defaults unaudited the same with --no-claim-audit: what the claim audit costs
  previous defaults  the beam model (product), 2000 uniform particles,
                     augmented MCL, no floor, no claim audit: the defaults
                     before docs/defaults.md
  mrpt beam          MRPT's CMonteCarloLocalization2D, ray tracing, 2000 particles
  mrpt beam N        the same with N particles (--mrpt-particles), tracking only

Writes <out>/defaults_cost.csv and <out>/defaults_cost.md.

Usage: scripts/defaults_cost.py [--rcbench build/rcbench] [--out out/defaults_cost]
       [--repeats 3] [--mrpt-particles 250,500,1000]
"""
import argparse
import csv
import json
import os
import resource
import statistics
import subprocess
import sys

from rcbench_files import InputError, read_poses, read_timeline_rows

PREVIOUS_DEFAULTS = ["--sensor-model", "beam", "--beam-combine", "product", "--initial-particles", "0",
                     "--hypothesis-floor", "0", "--recovery-alpha-slow", "0.001", "--no-claim-audit"]
UNAUDITED = ["--no-claim-audit"]


def run(cmd):
    """Runs cmd; returns its CPU seconds (user + system of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode != 0:
        sys.exit(f"command failed ({result.returncode}): {' '.join(cmd)}\n{result.stderr}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--out", default="out/defaults_cost")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--mrpt-particles", default="250,500,1000")
    args = ap.parse_args()
    if args.repeats < 1:
        sys.exit("defaults_cost: --repeats must be >= 1")
    os.makedirs(args.out, exist_ok=True)
    office = os.path.join(args.out, "office.yaml")
    trace = os.path.join(args.out, "office_run.log")
    gt = os.path.join(args.out, "office_run.gt")
    run([args.rcbench, "make-map", "--output", office])
    run([args.rcbench, "simulate", "--map", office, "--output", trace, "--ground-truth", gt, "--records", "400",
         "--seed", "1"])
    try:
        _, x, y, theta = read_poses(gt)[0]
    except InputError as e:
        sys.exit(f"defaults_cost: {e}")
    start = ["--initial-pose", f"{x!r},{y!r},{theta!r}"]

    configs = [("defaults", "global", []), ("defaults unaudited", "global", UNAUDITED),
               ("previous defaults", "global", PREVIOUS_DEFAULTS),
               ("mrpt beam", "global", ["--engine", "mrpt", "--sensor-model", "beam"]),
               ("defaults", "tracking", start), ("defaults unaudited", "tracking", UNAUDITED + start),
               ("previous defaults", "tracking", PREVIOUS_DEFAULTS + start),
               ("mrpt beam", "tracking", ["--engine", "mrpt", "--sensor-model", "beam"] + start)]
    for n in [int(v) for v in args.mrpt_particles.split(",") if v]:
        configs.append((f"mrpt beam {n}", "tracking",
                        ["--engine", "mrpt", "--sensor-model", "beam", "--particles", str(n)] + start))

    def base(name, mode, priced):
        tag = f"{name.replace(' ', '_')}_{mode}{'_priced' if priced else ''}"
        return tag, [args.rcbench, "delibot", "--map", office, "--trace", trace, "--ground-truth", gt, "--seed", "1",
                     "--threads", "1", "--quiet", "--summary", os.path.join(args.out, tag + ".json"),
                     "--timeline", os.path.join(args.out, tag + ".csv")]

    cpu = {(name, mode): [] for name, mode, _ in configs}
    for round_index in range(args.repeats):
        for name, mode, extra in configs:
            tag, cmd = base(name, mode, False)
            seconds = run(cmd + ["--no-pricing"] + extra)
            with open(os.path.join(args.out, tag + ".json")) as f:
                updates = json.load(f)["totals"]["sensor_updates"]
            cpu[(name, mode)].append(seconds / max(1, updates))
            print(f"round {round_index + 1}: {name} {mode}: {1e3 * seconds / max(1, updates):.2f} ms CPU per update",
                  flush=True)

    rows = []
    for name, mode, extra in configs:
        tag, cmd = base(name, mode, False)
        with open(os.path.join(args.out, tag + ".json")) as f:
            summary = json.load(f)
        a, t = summary["accuracy"], summary["totals"]
        row = {"config": name, "mode": mode, "particles": summary["config"]["particles"],
               "sensor_model": summary["config"]["sensor_model"],
               "cpu_ms_per_update": 1e3 * statistics.median(cpu[(name, mode)]),
               "convergence_record": a["convergence_iteration"],
               "own_claim_record": a["convergence_iteration_without_ground_truth"],
               "claims_withdrawn": a.get("claims_withdrawn", 0),
               "median_err_xy_m": a["median_err_xy_m"], "p95_err_xy_m": a["p95_err_xy_m"],
               "sensor_updates": t["sensor_updates"], "rays_per_update": "", "nodes_per_update": "",
               "priced_rays_per_update": "", "best_static_cycles_per_update": "", "best_static_backend": ""}
        if not name.startswith("mrpt"):
            row["rays_per_update"] = t["rays"] / max(1, t["sensor_updates"])
            row["nodes_per_update"] = t["nodes"] / max(1, t["sensor_updates"])
            tag, cmd = base(name, mode, True)
            run(cmd + extra)
            with open(os.path.join(args.out, tag + ".json")) as f:
                priced = json.load(f)
            try:
                rows_t = read_timeline_rows(os.path.join(args.out, tag + ".csv"), ("rays", "nodes_per_ray"))
            except InputError as e:
                sys.exit(f"defaults_cost: {e}")
            # Ray casts have several nodes per ray; the likelihood field's
            # look-ups one each (and are not priced).
            cast = sum(int(r["rays"]) for r in rows_t if r["nodes_per_ray"] and float(r["nodes_per_ray"]) > 1.5)
            row["priced_rays_per_update"] = cast / max(1, t["sensor_updates"])
            backends = priced.get("backends", {})
            statics = backends.get("static_total_cycles", {})
            if statics:
                best = min(statics, key=statics.get)
                row["best_static_backend"] = best
                row["best_static_cycles_per_update"] = statics[best] / max(1, t["sensor_updates"])
        rows.append(row)

    with open(os.path.join(args.out, "defaults_cost.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    def num(v, fmt):
        return fmt.format(v) if isinstance(v, (int, float)) and v != "" else "-"

    lines = ["| configuration | mode | particles | CPU ms per update (median) | converged / own claim (record) | "
             "claims withdrawn | median / p95 error (m) | rays per update (all / priced) | "
             "modelled cycles per update (best static backend) |",
             "|---|---|---:|---:|---|---:|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['config']} | {r['mode']} | {r['particles']} | {r['cpu_ms_per_update']:.2f} | "
                     f"{r['convergence_record']} / {r['own_claim_record']} | {r['claims_withdrawn']} | "
                     f"{num(r['median_err_xy_m'], '{:.3f}')} / {num(r['p95_err_xy_m'], '{:.3f}')} | "
                     f"{num(r['rays_per_update'], '{:.0f}')} / {num(r['priced_rays_per_update'], '{:.0f}')} | "
                     f"{num(r['best_static_cycles_per_update'], '{:.0f}')}"
                     f"{' (' + r['best_static_backend'] + ')' if r['best_static_backend'] else ''} |")
    with open(os.path.join(args.out, "defaults_cost.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
