#!/usr/bin/python3
"""Our Monte Carlo localizer beside MRPT's: analysis of
scripts/workflow/studies/mrpt_comparison.yaml.

The study runs both engines (rcbench delibot --engine ours|mrpt) at equal
particle counts and both sensor models, on one thread each, on a simulated
trace with ground truth (group "simulated", tracking from the true first
pose) and on the real Wean logs (group "wean", global localization, no
ground truth). This script writes into OUT_DIR
  mrpt_comparison.md    Markdown tables: error and host time per update on
                        the simulated trace; convergence, scan consistency
                        and time per update on the real logs
  mrpt_comparison.csv   one row per run
  mrpt_comparison.png   error against time per update, ours vs MRPT, one
                        curve per engine and model, labels = particles
Usage: scripts/mrpt_comparison.py MERGED_CSV OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402


def runs(ok):
    trace = ok["log"] if "log" in ok.columns else pd.Series("simulated", index=ok.index)
    out = pd.DataFrame({
        "trace": trace.fillna("simulated"), "engine": ok["engine"].fillna("ours"), "particles": ok["particles"],
        "beam_step": ok["beam_step"], "sensor_model": ok["sensor_model"],
        "time_per_update_s": ok["totals.wall_per_update_s"],
        "median_err_xy_m": ok.get("accuracy.median_err_xy_m"), "p95_err_xy_m": ok.get("accuracy.p95_err_xy_m"),
        "median_err_theta_rad": ok.get("accuracy.median_err_theta_rad"),
        "final_err_xy_m": ok.get("accuracy.final_err_xy_m"),
        "convergence_iteration": ok["accuracy.convergence_iteration"],
        "converged_at_end": ok["accuracy.converged_at_end"],
        "median_consistency": ok["accuracy.median_consistency_after_convergence"],
        "jumps_after_convergence": ok["accuracy.jumps_after_convergence"],
    })
    return out


def fmt_err(v):
    return "-" if pd.isna(v) or v < 0 else f"{v:.3f}"


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
    for (trace, model, p), pair in rows.groupby(["trace", "sensor_model", "particles"]):
        by_engine = {r["engine"]: r for _, r in pair.iterrows()}
        if set(by_engine) != {"ours", "mrpt"}:
            continue
        o, m = by_engine["ours"], by_engine["mrpt"]
        to, tm = 1e3 * o["time_per_update_s"], 1e3 * m["time_per_update_s"]
        if with_truth:
            out.append(f"| {model} | {p} | {fmt_err(o['median_err_xy_m'])} / {fmt_err(o['p95_err_xy_m'])} "
                       f"| {fmt_err(m['median_err_xy_m'])} / {fmt_err(m['p95_err_xy_m'])} "
                       f"| {to:.2f} | {tm:.2f} | {tm / to:.1f}x |")
        else:
            def conv(r):
                it = int(r["convergence_iteration"])
                return (f"{it} / {r['median_consistency']:.2f} / {int(r['jumps_after_convergence'])}"
                        if it >= 0 else "never / - / -")
            out.append(f"| {trace} | {model} | {p} | {conv(o)} | {conv(m)} | {to:.2f} | {tm:.2f} |")
    return "\n".join(out)


def plot(rows, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5.5))
    styles = {("ours", "beam"): ("tab:blue", "s", "-"), ("mrpt", "beam"): ("tab:blue", "s", "--"),
              ("ours", "likelihood"): ("tab:purple", "D", "-"), ("mrpt", "likelihood"): ("tab:purple", "D", "--")}
    for (engine, model), (color, marker, line) in styles.items():
        sel = rows[(rows["engine"] == engine) & (rows["sensor_model"] == model) & (rows["median_err_xy_m"] >= 0)]
        sel = sel.sort_values("particles")
        if sel.empty:
            continue
        ax.plot(1e3 * sel["time_per_update_s"], sel["median_err_xy_m"], linestyle=line, marker=marker, color=color,
                alpha=0.8, markerfacecolor=color if engine == "ours" else "white",
                label=f"{'ours' if engine == 'ours' else 'MRPT'} {model}")
        for _, r in sel.iterrows():
            ax.annotate(str(int(r["particles"])), (1e3 * r["time_per_update_s"], r["median_err_xy_m"]),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("host time per filter update (ms, log)")
    ax.set_ylabel("median position error after convergence (m, log)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    if "engine" not in table.columns:
        sys.exit(f"{merged}: no 'engine' column: not the MRPT comparison's table")
    all_runs = runs(ok)
    analysis_io.save_table(all_runs, out_dir, "mrpt_comparison.csv")
    simulated = all_runs[ok["group"] == "simulated"]
    real = all_runs[ok["group"] != "simulated"]
    where = f"{analysis_io.cpu_name()}, 1 thread"
    md = [f"Simulated trace, tracking from the true first pose; {where}.", "", markdown(simulated, True)]
    if len(real):
        md += ["", "Real Wean logs, global localization, no ground truth: first record of 10 sensor updates in a "
               "row with the estimate's mode holding >= 0.8 of the weight and scan consistency >= 0.5 (rcbench's "
               "ground-truth-free criterion), median scan consistency after it, and estimate jumps > 1 m after it.",
               "", markdown(real, False)]
    text = "\n".join(md) + "\n"
    analysis_io.save_text(text, out_dir, "mrpt_comparison.md")
    if len(simulated):
        fig = plot(simulated, f"DeliBot vs MRPT CMonteCarloLocalization2D (tracking); labels = particles\n{where}")
        analysis_io.save_figure(fig, out_dir, "mrpt_comparison.png",
                                "Median position error against host time per update on the simulated trace; solid: "
                                "ours, dashed: MRPT; labels: particles.")
    print(text)


if __name__ == "__main__":
    main()
