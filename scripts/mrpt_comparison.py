#!/usr/bin/python3
"""Our Monte Carlo localizer beside MRPT's (rcbench delibot --engine mrpt).

On one simulated trace with ground truth (`rcbench simulate`), runs both
engines at equal particle counts, both sensor models, in one invocation on
one machine, and writes
  <out>/mrpt_comparison.md    Markdown table: error and host time per update
  <out>/mrpt_comparison.csv   speed_vs_error.csv's columns plus "engine"
  <out>/mrpt_comparison.png   error against time per update, ours vs MRPT
With --wean, also runs both on the real Wean logs (no ground truth: the
table gives convergence, scan consistency and time per update instead).

Both engines run with --threads 1 by default: MRPT's filter is
single-threaded, so this compares the algorithms, not the core count.
Tracking mode (start around the true first pose) by default, as in
scripts/speed_vs_error.py; --global for global localization.

Usage: scripts/mrpt_comparison.py [--rcbench build/rcbench] [--out out/mrpt]
       [--map FILE] [--records N] [--particles 250,500,1000,2000] [--quick]
       [--global] [--wean DIR] [--threads N]
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import speed_vs_error as sve  # run(), first_pose(), cpu_name(): one definition


def delibot(args, map_args, trace, gt, engine, particles, model, beam_step, summary, extra=()):
    cmd = [args.rcbench, "delibot", *map_args, "--trace", trace, "--particles", str(particles),
           "--beam-step", str(beam_step), "--sensor-model", model, "--seed", str(args.seed),
           "--engine", engine, "--summary", summary, "--threads", str(args.threads), "--quiet",
           "--no-pricing", *extra]
    if gt:
        cmd += ["--ground-truth", gt]
        if not args.global_loc:
            cmd += ["--initial-pose", sve.first_pose(gt)]
    sve.run(cmd)
    with open(summary) as f:
        return json.load(f)


def row_of(s, engine, particles, beam_step, model, caster, trace_name):
    t, a = s["totals"], s["accuracy"]
    return {
        "trace": trace_name, "engine": engine, "particles": particles, "beam_step": beam_step,
        "sensor_model": model, "ray_caster": caster if engine == "ours" else "mrpt",
        "time_per_update_s": t["wall_per_update_s"],
        "median_err_xy_m": a.get("median_err_xy_m", -1), "p95_err_xy_m": a.get("p95_err_xy_m", -1),
        "median_err_theta_rad": a.get("median_err_theta_rad", -1),
        "final_err_xy_m": a.get("final_err_xy_m", -1),
        "convergence_iteration": a["convergence_iteration"], "converged_at_end": int(a["converged_at_end"]),
        "median_consistency": a["median_consistency_after_convergence"],
        "jumps_after_convergence": a["jumps_after_convergence"],
    }


def fmt_err(v):
    return "-" if v is None or v < 0 else f"{v:.3f}"


def markdown(rows, with_truth):
    out = []
    if with_truth:
        out.append("| model | particles | ours: median / p95 error (m) | MRPT: median / p95 error (m) "
                   "| ours: ms per update | MRPT: ms per update | MRPT / ours time |")
        out.append("|---|---:|---:|---:|---:|---:|---:|")
    else:
        out.append("| trace | model | particles | ours: converged at / consistency / jumps "
                   "| MRPT: converged at / consistency / jumps | ours: ms per update | MRPT: ms per update |")
        out.append("|---|---|---:|---:|---:|---:|---:|")
    keys = sorted({(r["trace"], r["sensor_model"], r["particles"]) for r in rows},
                  key=lambda k: (k[0], k[1], k[2]))
    for trace, model, p in keys:
        pair = {r["engine"]: r for r in rows if (r["trace"], r["sensor_model"], r["particles"]) == (trace, model, p)}
        if set(pair) != {"ours", "mrpt"}:
            continue
        o, m = pair["ours"], pair["mrpt"]
        to, tm = 1e3 * o["time_per_update_s"], 1e3 * m["time_per_update_s"]
        if with_truth:
            out.append(f"| {model} | {p} | {fmt_err(o['median_err_xy_m'])} / {fmt_err(o['p95_err_xy_m'])} "
                       f"| {fmt_err(m['median_err_xy_m'])} / {fmt_err(m['p95_err_xy_m'])} "
                       f"| {to:.2f} | {tm:.2f} | {tm / to:.1f}x |")
        else:
            def conv(r):
                it = r["convergence_iteration"]
                return (f"{it} / {r['median_consistency']:.2f} / {r['jumps_after_convergence']}"
                        if it >= 0 else "never / - / -")
            out.append(f"| {trace} | {model} | {p} | {conv(o)} | {conv(m)} | {to:.2f} | {tm:.2f} |")
    return "\n".join(out)


def plot(rows, path, title):
    try:
        import matplotlib
    except ImportError:
        print(f"matplotlib not installed: {path} not drawn (the table and CSV are complete)")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5.5))
    styles = {("ours", "beam"): ("tab:blue", "s", "-"), ("mrpt", "beam"): ("tab:blue", "s", "--"),
              ("ours", "likelihood"): ("tab:purple", "D", "-"), ("mrpt", "likelihood"): ("tab:purple", "D", "--")}
    for (engine, model), (color, marker, line) in styles.items():
        sel = sorted((r for r in rows if r["engine"] == engine and r["sensor_model"] == model
                      and r["median_err_xy_m"] >= 0), key=lambda r: r["particles"])
        if not sel:
            continue
        ax.plot([1e3 * r["time_per_update_s"] for r in sel], [r["median_err_xy_m"] for r in sel],
                linestyle=line, marker=marker, color=color, alpha=0.8,
                markerfacecolor=color if engine == "ours" else "white",
                label=f"{'ours' if engine == 'ours' else 'MRPT'} {model}")
        for r in sel:
            ax.annotate(str(r["particles"]), (1e3 * r["time_per_update_s"], r["median_err_xy_m"]),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("host time per filter update (ms, log)")
    ax.set_ylabel("median position error after convergence (m, log)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def write_csv(rows, path):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--out", default="out/mrpt")
    ap.add_argument("--map", default="", help="map to simulate on (default: the generated office map)")
    ap.add_argument("--records", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--beam-step", type=int, default=6)
    ap.add_argument("--particles", default="250,500,1000,2000")
    ap.add_argument("--quick", action="store_true", help="250 and 1000 particles only")
    ap.add_argument("--global", dest="global_loc", action="store_true", help="global localization, not tracking")
    ap.add_argument("--wean", default="", help="folder with wean.dat and robotdata*.log: also run the real logs")
    ap.add_argument("--wean-particles", type=int, default=2000)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    particles = [250, 1000] if args.quick else [int(p) for p in args.particles.split(",")]

    trace = os.path.join(args.out, "sim_trace.log")
    gt = os.path.join(args.out, "sim_trace.gt")
    sim = [args.rcbench, "simulate", "--output", trace, "--ground-truth", gt, "--records", str(args.records),
           "--seed", str(args.seed)]
    if args.map:
        sim += ["--map", args.map]
        map_args = ["--map", args.map]
    else:
        office = os.path.join(args.out, "office.yaml")
        sve.run([args.rcbench, "make-map", "--output", office])
        map_args = ["--map", office]
    sve.run(sim)

    summary = os.path.join(args.out, "run_summary.json")
    rows = []
    for model in ("likelihood", "beam"):
        for p in particles:
            for engine in ("ours", "mrpt"):
                s = delibot(args, map_args, trace, gt, engine, p, model, args.beam_step, summary)
                rows.append(row_of(s, engine, p, args.beam_step, model, "rm", "simulated"))
                r = rows[-1]
                print(f"{engine:4s} {model:10s} {p:5d} particles: {1e3 * r['time_per_update_s']:.2f} ms/update, "
                      f"median error {r['median_err_xy_m']:.3f} m", flush=True)

    wean_rows = []
    if args.wean:
        wean_map = ["--map", os.path.join(args.wean, "wean.dat")]
        for log in sorted(f for f in os.listdir(args.wean) if f.startswith("robotdata") and f.endswith(".log")):
            for model in ("likelihood", "beam"):
                for engine in ("ours", "mrpt"):
                    s = delibot(args, wean_map, os.path.join(args.wean, log), "", engine, args.wean_particles, model,
                                args.beam_step, summary)
                    wean_rows.append(row_of(s, engine, args.wean_particles, args.beam_step, model, "rm", log))
                    r = wean_rows[-1]
                    print(f"{log} {engine:4s} {model:10s}: {1e3 * r['time_per_update_s']:.2f} ms/update, "
                          f"converged at {r['convergence_iteration']}", flush=True)
    os.remove(summary)

    mode = "global localization" if args.global_loc else "tracking from the true first pose"
    where = f"{sve.cpu_name()}, {args.threads} thread(s)"
    md = [f"Simulated trace ({args.records} records, seed {args.seed}, {mode}), every {args.beam_step}th beam; "
          f"{where}.", "", markdown(rows, True)]
    if wean_rows:
        md += ["", f"Real Wean logs, global localization, {args.wean_particles} particles, no ground truth: "
               "first record of 10 sensor updates in a row with the estimate's mode holding >= 0.8 of the weight "
               "and scan consistency >= 0.5 (rcbench's ground-truth-free criterion), median scan "
               "consistency after it, and estimate jumps > 1 m after it.", "", markdown(wean_rows, False)]
    md_path = os.path.join(args.out, "mrpt_comparison.md")
    with open(md_path + ".tmp", "w") as f:
        f.write("\n".join(md) + "\n")
    os.replace(md_path + ".tmp", md_path)
    csv_path = os.path.join(args.out, "mrpt_comparison.csv")
    write_csv(rows + wean_rows, csv_path)
    png_path = os.path.join(args.out, "mrpt_comparison.png")
    plot(rows, png_path, f"DeliBot vs MRPT CMonteCarloLocalization2D ({mode}); labels = particles\n{where}")
    print("\n".join(md))
    print(f"wrote {md_path} and {csv_path}" + (f" and {png_path}" if os.path.exists(png_path) else ""))


if __name__ == "__main__":
    main()
