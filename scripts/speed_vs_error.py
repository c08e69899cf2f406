#!/usr/bin/python3
"""Speed-vs-error study for DeliBot.

Sweeps particles x beam step x ray caster x sensor model (the likelihood
field with AMCL's unsigned distance and with the signed one) on simulated traces
with ground truth (made by `rcbench simulate`), runs `rcbench delibot` for
each configuration, plus MRPT's CMonteCarloLocalization2D (`--engine mrpt`)
at the same particle counts and beam steps as a reference curve (leave it
out with --no-mrpt), and writes
  <out>/speed_vs_error.csv   one row per run (time per update in s, errors in m)
  <out>/speed_vs_error.png   localization error against time per update
Tracking mode (the filter starts around the true first pose) isolates the
per-update cost/accuracy trade-off from the luck of global convergence; pass
--global for global localization instead.

Usage: scripts/speed_vs_error.py [--rcbench build/rcbench] [--out out/study]
       [--map FILE] [--quick] [--global] [--threads N] [--no-mrpt]
MRPT's filter runs on one thread whatever --threads says; pass --threads 1
to compare the engines at equal hardware.
"""
import argparse
import csv
import itertools
import json
import os
import platform
import subprocess
import sys


def run(cmd):
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit(f"command failed ({result.returncode}): {' '.join(cmd)}\n{result.stderr}")
    return result.stdout


def first_pose(gt_path):
    with open(gt_path) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                _, x, y, theta = line.split()
                return f"{x},{y},{theta}"
    sys.exit(f"{gt_path}: no pose")


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--out", default="out/study")
    ap.add_argument("--map", default="", help="map to simulate on (default: the generated office map)")
    ap.add_argument("--records", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="a small sweep (for a smoke test)")
    ap.add_argument("--global", dest="global_loc", action="store_true", help="global localization, not tracking")
    ap.add_argument("--no-mrpt", action="store_true", help="leave out MRPT's localizer (the reference curve)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    trace = os.path.join(args.out, "sweep_trace.log")
    gt = os.path.join(args.out, "sweep_trace.gt")
    sim = [args.rcbench, "simulate", "--output", trace, "--ground-truth", gt, "--records", str(args.records),
           "--seed", str(args.seed)]
    map_args = []
    if args.map:
        sim += ["--map", args.map]
        map_args = ["--map", args.map]
    else:
        office = os.path.join(args.out, "office.yaml")
        run([args.rcbench, "make-map", "--output", office])
        map_args = ["--map", office]
    run(sim)

    particles = [250, 1000] if args.quick else [250, 500, 1000, 2000, 5000]
    beam_steps = [6] if args.quick else [3, 6, 12]
    configs = []
    for p, k in itertools.product(particles, beam_steps):
        for caster in (["dda"] if args.quick else ["march", "dda", "rm"]):
            configs.append((p, k, "beam", caster))
        configs.append((p, k, "likelihood", "-"))
        configs.append((p, k, "likelihood", "signed"))
        if not args.no_mrpt:
            configs += [(p, k, "beam", "mrpt"), (p, k, "likelihood", "mrpt")]

    rows = []
    for i, (p, k, model, caster) in enumerate(configs):
        summary_path = os.path.join(args.out, "sweep_summary.json")
        cmd = [args.rcbench, "delibot", *map_args, "--trace", trace, "--ground-truth", gt, "--particles", str(p),
               "--beam-step", str(k), "--sensor-model", model, "--seed", str(args.seed), "--summary", summary_path,
               "--threads", str(args.threads), "--quiet", "--no-pricing"]
        if caster == "mrpt":
            cmd += ["--engine", "mrpt"]
        elif caster == "signed":
            cmd += ["--lf-distance", "signed"]
        elif caster != "-":
            cmd += ["--raycaster", caster]
        if not args.global_loc:
            cmd += ["--initial-pose", first_pose(gt)]
        run(cmd)
        with open(summary_path) as f:
            s = json.load(f)
        t, a = s["totals"], s["accuracy"]
        rows.append({
            "engine": "mrpt" if caster == "mrpt" else "ours",
            "particles": p, "beam_step": k, "sensor_model": model,
            "ray_caster": caster if model == "beam" and caster != "mrpt" else "-",
            "lf_distance": ("signed" if caster == "signed" else "unsigned") if model == "likelihood" else "-",
            "time_per_update_s": t["wall_per_update_s"], "rays_per_s": t["rays_per_s"],
            "nodes_per_ray": t["nodes_per_ray"],
            "median_err_xy_m": a.get("median_err_xy_m", -1), "p95_err_xy_m": a.get("p95_err_xy_m", -1),
            "median_err_theta_rad": a.get("median_err_theta_rad", -1),
            "convergence_iteration": a["convergence_iteration"], "converged_at_end": int(a["converged_at_end"]),
        })
        print(f"[{i + 1}/{len(configs)}] {p} particles, step {k}, {model}/{caster}: "
              f"{1e3 * t['wall_per_update_s']:.2f} ms/update, median error {a.get('median_err_xy_m', -1):.3f} m",
              flush=True)

    csv_path = os.path.join(args.out, "speed_vs_error.csv")
    with open(csv_path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(csv_path + ".tmp", csv_path)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5.5))
    # (engine, model, ray caster, field distance) -> colour, marker, label
    styles = {("ours", "beam", "march", "-"): ("tab:red", "o", "beam / march"),
              ("ours", "beam", "dda", "-"): ("tab:blue", "s", "beam / dda"),
              ("ours", "beam", "rm", "-"): ("tab:green", "^", "beam / rm"),
              ("ours", "likelihood", "-", "unsigned"): ("tab:purple", "D", "likelihood field (unsigned, AMCL)"),
              ("ours", "likelihood", "-", "signed"): ("tab:pink", "d", "likelihood field (signed)"),
              ("mrpt", "beam", "-", "-"): ("black", "v", "MRPT beam"),
              ("mrpt", "likelihood", "-", "unsigned"): ("tab:orange", "P", "MRPT likelihood field")}
    for key, (color, marker, label) in styles.items():
        sel = [r for r in rows if (r["engine"], r["sensor_model"], r["ray_caster"], r["lf_distance"]) == key
               and r["median_err_xy_m"] >= 0]
        if not sel:
            continue
        ax.scatter([1e3 * r["time_per_update_s"] for r in sel], [r["median_err_xy_m"] for r in sel],
                   s=[12 + r["particles"] / 40 for r in sel], c=color, marker=marker, alpha=0.75, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("host time per filter update (ms, log)")
    ax.set_ylabel("median position error after convergence (m, log)")
    mode = "global localization" if args.global_loc else "tracking"
    ax.set_title(f"DeliBot speed vs error ({mode}); marker size = particles\n{cpu_name()}, "
                 f"ours on {args.threads or os.cpu_count()} thread(s), MRPT on 1", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    png_path = os.path.join(args.out, "speed_vs_error.png")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {csv_path} and {png_path}")


if __name__ == "__main__":
    main()
