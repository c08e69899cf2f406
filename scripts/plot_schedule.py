#!/usr/bin/python3
"""Plots a DeliBot timeline in the shape of the RoboGPU paper's DeliBot figure.

Top: cumulative modelled execution time over iterations, one line each for
SIMT, TTA+, RoboCore, the chosen policy (adaptive unless the run said
otherwise) and the hindsight oracle. Bottom: nodes per ray over iterations,
with the adaptive threshold and the switch points marked.

Usage: scripts/plot_schedule.py TIMELINE.csv OUT.png [--title TEXT] [--clock-hz 1.365e9]
"""
import argparse
import csv
import math

from rcbench_files import save_figure


CLOCK_HZ = 1.365e9  # the default modelled core clock (Hz), to show cycles as seconds


def draw(rows, title="", clock_hz=CLOCK_HZ):
    """The two-panel figure of a priced timeline's rows (dicts of strings)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    it = [int(r["iteration"]) for r in rows]
    ms = lambda col: [1e3 * float(r[col]) / clock_hz for r in rows]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for col, label, style in [("cum_cycles_simt", "SIMT (CUDA cores)", "-"), ("cum_cycles_ttaplus", "TTA+", "--"),
                              ("cum_cycles_ttaplus_cr", "TTA+ (cond. return)", ":"),
                              ("cum_cycles_robocore", "RoboCore", "-."),
                              ("cum_cycles_policy", "adaptive (chosen policy)", "-"),
                              ("cum_cycles_oracle", "oracle (hindsight)", "--")]:
        if col in rows[0]:
            top.plot(it, ms(col), style, label=label, linewidth=2.2 if "policy" in col or "oracle" in col else 1.4)
    top.set_ylabel("cumulative modelled time (ms)")
    top.legend(fontsize=8)
    top.grid(alpha=0.3)
    top.set_title(title or "DeliBot: cumulative execution time and switching", fontsize=10)

    npr = [float(r["nodes_per_ray"]) if r["nodes_per_ray"] else math.nan for r in rows]
    bottom.plot(it, npr, ".", markersize=3, label="nodes per ray")
    thresholds = [float(r["threshold_nodes_per_ray"]) for r in rows if r.get("threshold_nodes_per_ray")]
    if thresholds and math.isfinite(thresholds[0]):
        bottom.axhline(thresholds[0], color="tab:red", linestyle="--", label=f"threshold {thresholds[0]:.0f}")
    elif thresholds:
        bottom.text(0.01, 0.92, "no crossover: threshold = +inf (CUDA cores cheaper at every length)",
                    transform=bottom.transAxes, fontsize=8, color="tab:red")
    switches = [int(r["iteration"]) for r in rows if r.get("switched") == "1"]
    for k, s in enumerate(switches):
        bottom.axvline(s, color="tab:gray", alpha=0.5, linewidth=0.8, label="switch" if k == 0 else None)
    bottom.set_xlabel("iteration (laser record)")
    bottom.set_ylabel("nodes per ray")
    bottom.legend(fontsize=8)
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("timeline")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    ap.add_argument("--clock-hz", type=float, default=CLOCK_HZ, help="modelled core clock (Hz), for seconds")
    args = ap.parse_args()
    with open(args.timeline) as f:
        rows = list(csv.DictReader(f))
    if not rows or "cum_cycles_policy" not in rows[0]:
        raise SystemExit(f"{args.timeline}: no backend pricing columns (run rcbench delibot without --no-pricing)")
    save_figure(draw(rows, args.title, args.clock_hz), args.png, dpi=110)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
