#!/usr/bin/python3
"""Figure of scan-matching references: the map (black = occupied), each log's
scan end points drawn at its reference poses (red), the reference path (blue,
start green), one panel per log, with the first window's score against its
runner-up and the best whole-log objectives of the start hypotheses.

scripts/scan_match_reference.py --figure FILE draws it while it runs; this
script draws the same figure later from that script's outputs
(<ref-dir>/<name>.ref.txt and <name>.windows.csv). Read back from the CSV,
which keeps 6 significant digits, the titles can differ in the last printed
digit from the figure drawn during the run.

Usage: scripts/plot_reference.py --map wean.dat --ref-dir out/reference
       --out docs/figures/real_logs_reference.png LOG [LOG ...]
"""
import argparse
import csv
import io
import math
import os
import sys

import numpy as np

from cmu_inputs import beam_endpoints, read_cmu_log, read_cmu_map
from rcbench_files import InputError, read_poses, write_atomic


def draw_figure(path, occupied, res, results, max_range_m):
    """results: [(name, Log, reference poses [n, 3], window rows as dicts)], one panel each.
    The window rows are scan_match_reference.py's: kind "global" first, then
    "start_hypothesis" rows and "chain" rows."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(results)
    cols = 2 if n > 1 else 1
    rowsn = (n + cols - 1) // cols
    fig, axes = plt.subplots(rowsn, cols, figsize=(6.5 * cols, 4.0 * rowsn), squeeze=False)
    ext = [0, occupied.shape[0] * res, 0, occupied.shape[1] * res]
    for ax, (name, log, ref, rows) in zip(axes.ravel(), results):
        ax.imshow(np.where(occupied, 0.0, 1.0).T, origin="lower", cmap="gray", extent=ext, vmin=0, vmax=1.3)
        p = np.concatenate([beam_endpoints(ref[k], log.ranges[k], max_range_m) for k in range(0, len(ref), 3)])
        ax.scatter(p[:, 0], p[:, 1], s=0.2, c="tab:red", linewidths=0, rasterized=True)
        ax.plot(ref[:, 0], ref[:, 1], "-", c="tab:blue", lw=1.0)
        ax.plot(ref[0, 0], ref[0, 1], "o", c="tab:green", ms=6)
        ax.set_xlim(p[:, 0].min() - 1, p[:, 0].max() + 1)
        ax.set_ylim(p[:, 1].min() - 1, p[:, 1].max() + 1)
        local = [r for r in rows if r["kind"] == "chain"]
        flagged = sum(1 for r in local if r["flags"])
        g = rows[0]
        hyp = sorted((r for r in rows if r["kind"] == "start_hypothesis"), key=lambda r: -r["objective"])
        whole = ", ".join(f"{r['objective']:.3f}{'*' if r['flags'].startswith('chosen') else ''}"
                          f" from ({r['x_m']:.0f}, {r['y_m']:.0f})" for r in hyp[:3])
        ax.set_title(f"{name}: start ({ref[0, 0]:.2f}, {ref[0, 1]:.2f}) m, "
                     f"{math.degrees(ref[0, 2]) % 360:.0f} deg; first window {g['score']:.3f} vs runner-up "
                     f"{g['runner_up_score']:.3f}\nbest whole-log objectives of {len(hyp)} starts: {whole}\n"
                     f"{flagged} of {len(local)} windows flagged", fontsize=8)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_aspect("equal")
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    fig.suptitle("Scan-matching reference: map (black = occupied), scan endpoints at the reference poses (red), "
                 "path (blue, start green)", fontsize=10)
    fig.tight_layout()
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=80)
    write_atomic(path, png.getvalue())


def read_window_rows(path):
    """The rows of a <name>.windows.csv, numbers as floats ("nan" included)."""
    text_columns = {"kind", "flags"}
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from None
    if not rows or rows[0].get("kind") != "global":
        raise InputError(f"{path}: expected scan_match_reference.py's windows CSV, first row of kind 'global'")
    out = []
    for line_no, r in enumerate(rows, 2):
        row = {}
        for k, v in r.items():
            if k in text_columns:
                row[k] = v
                continue
            try:
                row[k] = float(v)
            except (TypeError, ValueError):
                raise InputError(f"{path}:{line_no}: field '{k}': '{v}' is not a number") from None
        out.append(row)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("logs", nargs="+", help="CMU robotdata .log files, as given to scan_match_reference.py")
    ap.add_argument("--map", required=True, help="CMU .dat map (values are P(free))")
    ap.add_argument("--ref-dir", default="out/reference", help="scan_match_reference.py's --out-dir")
    ap.add_argument("--out", required=True, help="PNG to write")
    ap.add_argument("--max-range", type=float, default=8.0, help="draw ranges up to this (m)")
    args = ap.parse_args()
    try:
        occupied, res = read_cmu_map(args.map)
        results = []
        for path in args.logs:
            name = os.path.splitext(os.path.basename(path))[0]
            log = read_cmu_log(path)
            ref = np.array([p[1:] for p in read_poses(os.path.join(args.ref_dir, name + ".ref.txt"))])
            if len(ref) != len(log.times):
                raise InputError(f"{os.path.join(args.ref_dir, name + '.ref.txt')}: {len(ref)} poses, "
                                 f"{path} has {len(log.times)} laser records")
            rows = read_window_rows(os.path.join(args.ref_dir, name + ".windows.csv"))
            results.append((name, log, ref, rows))
    except InputError as e:
        sys.exit(f"plot_reference: {e}")
    draw_figure(args.out, occupied, res, results, args.max_range)
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
