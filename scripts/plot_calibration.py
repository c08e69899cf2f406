#!/usr/bin/env python3
"""Bar chart of the calibration report: the paper's reported value beside
ours for every row of calibration.csv (written by `rcbench calibrate`).

  /usr/bin/python3 scripts/plot_calibration.py OUT/calibration.csv OUT/calibration.png

Two panels, because the rows come in two units: speedups ("x faster",
baseline time / our time; 1 = no change) and signed percent changes.
A row where the paper gives no number shows our bar alone.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

from rcbench_files import save_figure


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["paper"] = float(r["paper_value"]) if r["paper_value"] else math.nan
        r["ours"] = float(r["ours"]) if r["ours"] else math.nan
    return rows


def panel(ax, rows, unit, reference):
    names = [r["result"] for r in rows]
    ys = range(len(rows))
    h = 0.4
    ax.barh([y - h / 2 for y in ys], [r["paper"] for r in rows], h, label="paper", color="#999999")
    ax.barh([y + h / 2 for y in ys], [r["ours"] for r in rows], h, label="ours", color="#1f77b4")
    ax.axvline(reference, color="black", linewidth=0.8)
    ax.set_yticks(list(ys))
    ax.set_yticklabels(names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel(unit)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(axis="x", alpha=0.3)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_calibration.py calibration.csv calibration.png")
    rows = read_rows(sys.argv[1])
    speedups = [r for r in rows if r["unit"] == "x faster"]
    percents = [r for r in rows if r["unit"] == "% change"]
    panels = [(speedups, "x faster (baseline time / our time)", 1.0), (percents, "% change", 0.0)]
    panels = [p for p in panels if p[0]]
    heights = [max(1.5, 0.35 * len(p[0]) + 0.8) for p in panels]
    fig, axes = plt.subplots(len(panels), 1, figsize=(10, sum(heights)),
                             gridspec_kw={"height_ratios": heights}, squeeze=False)
    for ax, (subset, unit, reference) in zip(axes[:, 0], panels):
        panel(ax, subset, unit, reference)
    axes[0, 0].set_title("RoboGPU paper vs rcbench (calibration.csv)")
    fig.tight_layout()
    save_figure(fig, sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
