#!/usr/bin/python3
"""Speed-vs-error analysis of a DeliBot study (scripts/workflow/studies/speed_vs_error.yaml).

Reads the study's merged CSV and writes into OUT_DIR
  speed_vs_error.png   median position error against host time per filter
                       update, one marker style per (engine, sensor model,
                       ray caster / field distance), marker size = particles,
                       with the Pareto front over every configuration drawn
                       and its points ringed;
  speed_vs_error_runs.csv  one row per run: engine, model, ray caster, field
                       distance, time per update (s), errors (m), convergence;
  pareto_front.csv     the non-dominated runs (no other run is both faster
                       and more accurate), fastest first.
A run without an error after convergence (it never converged) is left out
of the figure and the front, and counted in the caption.

The runs themselves are the study's points:
  snakemake --profile scripts/workflow/profiles/local --cores 2 \
      --configfile scripts/workflow/studies/speed_vs_error.yaml
Usage: scripts/speed_vs_error.py MERGED_CSV OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402

TIME = "totals.wall_per_update_s"
ERROR = "accuracy.median_err_xy_m"

# (engine, model, ray caster, field distance) -> colour, marker, label
STYLES = {("ours", "beam", "march", "-"): ("tab:red", "o", "beam / march"),
          ("ours", "beam", "dda", "-"): ("tab:blue", "s", "beam / dda"),
          ("ours", "beam", "rm", "-"): ("tab:green", "^", "beam / rm"),
          ("ours", "likelihood", "-", "unsigned"): ("tab:purple", "D", "likelihood field (unsigned, AMCL)"),
          ("ours", "likelihood", "-", "signed"): ("tab:pink", "d", "likelihood field (signed)"),
          ("mrpt", "beam", "-", "-"): ("black", "v", "MRPT beam"),
          ("mrpt", "likelihood", "-", "unsigned"): ("tab:orange", "P", "MRPT likelihood field")}


def runs_table(ok):
    """The old script's columns, one row per run, from the merged table's options and metrics."""
    def column(name, default):
        return ok[name] if name in ok.columns else default
    out = ok[["point"]].copy()
    out["engine"] = column("engine", "ours").fillna("ours")
    out["particles"] = ok["particles"]
    out["beam_step"] = ok["beam_step"]
    out["sensor_model"] = ok["sensor_model"]
    beam_ours = (out["sensor_model"] == "beam") & (out["engine"] == "ours")
    out["ray_caster"] = column("raycaster", "rm").fillna("rm").where(beam_ours, "-")
    distance = column("lf_distance", "unsigned").fillna("unsigned")
    out["lf_distance"] = distance.where(out["sensor_model"] == "likelihood", "-")
    out["time_per_update_s"] = ok[TIME]
    for src, dst in [("totals.rays_per_s", "rays_per_s"), ("totals.nodes_per_ray", "nodes_per_ray"),
                     (ERROR, "median_err_xy_m"), ("accuracy.p95_err_xy_m", "p95_err_xy_m"),
                     ("accuracy.median_err_theta_rad", "median_err_theta_rad"),
                     ("accuracy.convergence_iteration", "convergence_iteration"),
                     ("accuracy.converged_at_end", "converged_at_end"), ("threads", "threads")]:
        out[dst] = column(src, float("nan"))
    return out


def pareto_front(runs):
    """The runs no other run beats in both time and error, fastest first."""
    valid = runs[runs["median_err_xy_m"].notna() & (runs["median_err_xy_m"] >= 0)]
    ordered = valid.sort_values(["time_per_update_s", "median_err_xy_m"])
    front, best = [], float("inf")
    for idx, r in ordered.iterrows():
        if r["median_err_xy_m"] < best:
            front.append(idx)
            best = r["median_err_xy_m"]
    return ordered.loc[front]


def draw(runs, front, threads_note):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(10, 5.5))
    valid = runs[runs["median_err_xy_m"].notna() & (runs["median_err_xy_m"] >= 0)]
    for key, (color, marker, label) in STYLES.items():
        sel = valid[(valid["engine"] == key[0]) & (valid["sensor_model"] == key[1]) & (valid["ray_caster"] == key[2])
                    & (valid["lf_distance"] == key[3])]
        if len(sel):
            ax.scatter(1e3 * sel["time_per_update_s"], sel["median_err_xy_m"], s=12 + sel["particles"] / 40,
                       c=color, marker=marker, alpha=0.75, label=label)
    ax.step(1e3 * front["time_per_update_s"], front["median_err_xy_m"], where="post", color="0.3", lw=1.0,
            ls="--", label="Pareto front (no run both faster and more accurate)")
    ax.scatter(1e3 * front["time_per_update_s"], front["median_err_xy_m"], s=150, facecolors="none",
               edgecolors="0.2", linewidths=1.2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("host time per filter update (ms, log)")
    ax.set_ylabel("median position error after convergence (m, log)")
    ax.set_title(f"DeliBot speed vs error (tracking); marker size = particles\n{analysis_io.cpu_name()}, "
                 f"{threads_note}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    return fig


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    ok = ok[ok["workload"] == "delibot"]
    if ok.empty:
        sys.exit(f"{merged}: no successful DeliBot point")
    runs = runs_table(ok)
    front = pareto_front(runs)
    analysis_io.save_table(runs, out_dir, "speed_vs_error_runs.csv")
    analysis_io.save_table(front, out_dir, "pareto_front.csv")
    threads = sorted(set(int(t) for t in runs["threads"].dropna()))
    threads_note = f"ours on {','.join(map(str, threads)) or '?'} thread(s), MRPT on 1"
    unconverged = int((runs["median_err_xy_m"].isna() | (runs["median_err_xy_m"] < 0)).sum())
    fig = draw(runs, front, threads_note)
    analysis_io.save_figure(
        fig, out_dir, "speed_vs_error.png",
        f"{len(runs)} runs of {len(table)} points ({len(table) - len(ok)} failed); {unconverged} never converged and "
        f"are not drawn. The dashed step line is the Pareto front over every configuration ({len(front)} runs, "
        f"ringed; pareto_front.csv).")
    print(f"{len(runs)} runs, {len(front)} on the Pareto front")


if __name__ == "__main__":
    main()
