#!/usr/bin/python3
"""Cost-versus-time (anytime) curves of MoveBot runs.

Reads one or more anytime CSVs written by `rcbench movebot --anytime FILE`
(columns time_s, iterations, best_cost_rad; an empty cost means no solution
yet) and draws best cost against planning time, one step line per file.

Usage: scripts/plot_anytime.py OUT.png RUN.csv [RUN.csv ...] [--labels a,b,...]
       [--x time_s|iterations]
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rcbench_files import save_figure  # noqa: E402


def read_curve(path, x_column):
    xs, ys = [], []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        for column in (x_column, "best_cost_rad"):
            if column not in reader.fieldnames:
                raise ValueError(f"{path}: no column '{column}' (is it an anytime CSV from rcbench movebot --anytime?)")
        for line, row in enumerate(reader, start=2):
            try:
                x = float(row[x_column])
                y = float(row["best_cost_rad"]) if row["best_cost_rad"] else None
            except ValueError as e:
                raise ValueError(f"{path}:{line}: {e}") from None
            if y is not None:
                xs.append(x)
                ys.append(y)
    return xs, ys


def label_axes(ax, x_column):
    ax.set_xlabel("planning time (s)" if x_column == "time_s" else "RRTstar iterations")
    ax.set_ylabel("best path cost (rad, joint-space length)")
    ax.set_title("MoveBot anytime curve (OMPL RRTstar)")
    ax.grid(True, alpha=0.3)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output")
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--labels", default="")
    parser.add_argument("--x", default="time_s", choices=["time_s", "iterations"])
    args = parser.parse_args()
    labels = args.labels.split(",") if args.labels else [os.path.basename(p) for p in args.runs]
    if len(labels) != len(args.runs):
        sys.exit("--labels needs one label per run")
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for path, label in zip(args.runs, labels):
        try:
            xs, ys = read_curve(path, args.x)
        except ValueError as e:
            sys.exit(str(e))
        if not xs:
            print(f"{path}: no solution in the run; nothing to draw", file=sys.stderr)
            continue
        ax.step(xs, ys, where="post", label=label)
    label_axes(ax, args.x)
    ax.legend()
    fig.tight_layout()
    save_figure(fig, args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
