#!/usr/bin/env python3
"""Tornado plots of the cost-model sensitivity sweep: for each calibration
result, the range each swept parameter moves it over (sensitivity.csv,
written by `rcbench calibrate --sensitivity`), widest first.

  /usr/bin/python3 scripts/plot_sensitivity.py OUT/sensitivity.csv OUT/sensitivity.png [--results N] [--parameters N]

One panel per speedup result (the headline ratios: "x faster"; the units
come from calibration.csv beside the sweep; the first N with the widest
ranges, default all): a bar per parameter from the lowest to the highest
value its variants gave, the default as a vertical line, and the neutral
point (1x, where the comparison flips) as a dashed line. A red bar crosses
it: an assumption that flips the conclusion.
"""
import argparse
import csv
import math
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

from rcbench_files import save_figure


def read(path):
    baseline = {}
    spans = defaultdict(lambda: defaultdict(list))
    order = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if not row["result"]:
                continue
            name, value = row["ratio"], float(row["result"])
            if name not in baseline and not row["parameter"]:
                baseline[name] = value
                order.append(name)
            elif row["parameter"]:
                spans[name][row["parameter"]].append(value)
    return order, baseline, spans


def speedup_results(calibration_csv):
    with open(calibration_csv, newline="") as f:
        return {row["result"] for row in csv.DictReader(f) if row["unit"] == "x faster"}


def figure(sensitivity_csv, results=0, parameters=12):
    """The tornado figure of one sweep (calibration.csv must sit beside sensitivity.csv)."""
    order, baseline, spans = read(sensitivity_csv)
    speedups = speedup_results(os.path.join(os.path.dirname(os.path.abspath(sensitivity_csv)), "calibration.csv"))
    panels = []
    for name in order:
        if name not in speedups:
            continue
        bars = []
        for parameter, values in spans[name].items():
            lo, hi = min(values + [baseline[name]]), max(values + [baseline[name]])
            if hi - lo > 1e-12 * max(1.0, abs(baseline[name])):
                bars.append((hi - lo, parameter, lo, hi))
        bars.sort(reverse=True)
        panels.append((name, bars[:parameters]))
    if results > 0:
        panels.sort(key=lambda p: -(p[1][0][0] if p[1] else 0))
        panels = panels[:results]
    cols = 2
    rows = max(1, math.ceil(len(panels) / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(14, 2.2 + 0.34 * parameters * rows), squeeze=False)
    for ax, (name, bars) in zip(axes.flat, panels):
        base = baseline[name]
        neutral = 1.0
        for y, (_, parameter, lo, hi) in enumerate(reversed(bars)):
            flips = (lo - neutral) * (hi - neutral) < 0
            ax.barh(y, hi - lo, left=lo, color="tab:red" if flips else "tab:blue", height=0.6)
        ax.set_yticks(range(len(bars)))
        ax.set_yticklabels([b[1] for b in reversed(bars)], fontsize=7)
        ax.axvline(base, color="black", linewidth=1)
        ax.axvline(neutral, color="gray", linestyle="--", linewidth=1)
        if all(b[2] > 0 for b in bars) and base > 0:
            ax.set_xscale("log")
        ax.set_title(name, fontsize=8)
        ax.tick_params(axis="x", labelsize=7)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    fig.suptitle("Sensitivity of each result to one parameter at a time (red: the range crosses the neutral point)",
                 fontsize=10)
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--results", type=int, default=0, help="panels (0: every result)")
    parser.add_argument("--parameters", type=int, default=12, help="bars per panel, widest first")
    args = parser.parse_args()
    save_figure(figure(args.csv, args.results, args.parameters), args.png, dpi=110)


if __name__ == "__main__":
    main()
