"""The report's figures that any study gets from its points' own outputs,
whatever its analysis scripts draw:

  schedule     cumulative modelled time per backend with the policy and the
               oracle, and nodes per ray with the switch points (a priced
               DeliBot point; scripts/plot_schedule.py draws it);
  trajectory   the estimate against the ground truth, on the map (a DeliBot
               point run with --ground-truth);
  astar        A* paths on their maps (CarriBot points with a --plot PNG);
  anytime      RRT* best cost over planning time (MoveBot points;
               scripts/plot_anytime.py reads the curves);
  exit_axes    how the collision queries' node tests ended, per SACT axis
               (`rcbench collide` timelines).

Each function takes the merged table (ok points only) and returns a list of
(title, caption, PNG bytes); an empty list when the study has no such point.
Every curve is drawn from a file a point wrote.
"""
import csv
import io
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SCRIPTS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, SCRIPTS_DIR)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import merge  # noqa: E402
import plot_anytime  # noqa: E402
import plot_schedule  # noqa: E402
from rcbench_files import read_poses  # noqa: E402

MAX_CURVES = 12


def png_of(fig):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    return buf.getvalue()


def describe(row, table):
    """A short label of a point: its labels and the options that vary in its group."""
    group = table[table["group"] == row["group"]]
    parts = []
    for c in group.columns:
        if c in merge.RECORD_COLUMNS or "." in c:
            continue
        values = group[c].dropna().astype(str).unique()
        v = row[c]
        if isinstance(v, float) and v.is_integer():
            v = int(v)
        if len(values) > 1 and not str(v).startswith(("out/", "/")) and len(str(v)) < 40:
            parts.append(f"{c}={v}")
    return ", ".join(parts) or row["point"]


def _timeline(row):
    return os.path.join(row["folder"], "timeline.csv")


def schedule(table):
    rows = [r for _, r in table[table["workload"] == "delibot"].iterrows()
            if os.path.exists(_timeline(r))]
    for r in rows:
        with open(_timeline(r)) as f:
            header = f.readline().strip().split(",")
        if "cum_cycles_policy" in header:
            with open(_timeline(r)) as f:
                timeline = list(csv.DictReader(f))
            fig = plot_schedule.draw(timeline, title=f"DeliBot: {describe(r, table)}")
            return [("Cumulative modelled time and nodes per ray",
                     f"Point {r['point']}: every sensor update priced on every backend; the chosen policy and "
                     f"the hindsight oracle; below, nodes per ray with the adaptive threshold and the switch "
                     f"points.", png_of(fig))]
    return []


def _map_image(path):
    """(image array, extent [x0, x1, y0, y1] m) of a ROS YAML map or a CMU .dat map; None otherwise."""
    if path.endswith((".yaml", ".yml")):
        import yaml
        from PIL import Image
        with open(path) as f:
            meta = yaml.safe_load(f)
        image = np.asarray(Image.open(os.path.join(os.path.dirname(path), meta["image"])).convert("L"))
        res = float(meta["resolution"])
        h, w = image.shape
        # rcbench's frame is the grid's: cell (0, 0) at the bottom-left pixel (maps/ros_map_io.h)
        return image, [0.0, w * res, 0.0, h * res], "upper"
    if path.endswith(".dat"):
        import scan_match_reference
        occupied, res = scan_match_reference.read_cmu_map(path)
        image = np.where(occupied.T, 0, 255).astype(np.uint8)
        return image, [0.0, occupied.shape[0] * res, 0.0, occupied.shape[1] * res], "lower"
    return None


def trajectory(table):
    candidates = table[(table["workload"] == "delibot")]
    if "ground_truth" not in candidates.columns:
        return []
    for _, r in candidates.iterrows():
        gt_path, map_path = r.get("ground_truth"), r.get("map")
        if not (isinstance(gt_path, str) and os.path.exists(gt_path) and os.path.exists(_timeline(r))):
            continue
        with open(_timeline(r)) as f:
            timeline = list(csv.DictReader(f))
        truth = np.array(read_poses(gt_path))
        it = np.array([int(t["iteration"]) for t in timeline])
        est = np.array([[float(t["est_x_m"]), float(t["est_y_m"])] for t in timeline])
        fig, ax = plt.subplots(figsize=(8, 6))
        drawn = _map_image(map_path) if isinstance(map_path, str) and os.path.exists(map_path) else None
        if drawn:
            image, extent, origin = drawn
            ax.imshow(image, cmap="gray", extent=extent, origin=origin, vmin=0, vmax=255, interpolation="nearest")
        ax.plot(est[:, 0], est[:, 1], ".", color="tab:red", ms=3, label="estimate (per record)")
        ax.plot(truth[:, 1], truth[:, 2], "-", color="tab:green", lw=1.5, alpha=0.8, label="ground truth")
        if len(it) and it.max() < len(truth):
            ax.plot(truth[it[0], 1], truth[it[0], 2], "o", color="tab:green", ms=8, label="start")
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.legend(fontsize=8, loc="best")
        ax.set_title(f"Estimated trajectory vs ground truth: {describe(r, table)}", fontsize=9)
        if drawn:
            pad = 2.0
            xs = np.concatenate([truth[:, 1], est[:, 0]])
            ys = np.concatenate([truth[:, 2], est[:, 1]])
            ax.set_xlim(max(extent[0], xs.min() - pad), min(extent[1], xs.max() + pad))
            ax.set_ylim(max(extent[2], ys.min() - pad), min(extent[3], ys.max() + pad))
        return [("Estimated trajectory against ground truth",
                 f"Point {r['point']}: the filter's estimate at every laser record (red) and the ground truth "
                 f"(green) on the map {map_path}.", png_of(fig))]
    return []


def astar(table):
    out = []
    for _, r in table[table["workload"] == "carribot"].iterrows():
        png = os.path.join(r["folder"], "path.png")
        if os.path.exists(png):
            with open(png, "rb") as f:
                out.append((f"A* path: {describe(r, table)}",
                            f"Point {r['point']}: `rcbench carribot --plot` on {r.get('map')}.", f.read()))
    return out[:6]


def anytime(table):
    rows = [r for _, r in table[table["workload"] == "movebot"].iterrows()
            if os.path.exists(os.path.join(r["folder"], "anytime.csv"))]
    if not rows:
        return []
    fig, ax = plt.subplots(figsize=(7, 4.2))
    drawn = 0
    for r in rows[:MAX_CURVES]:
        xs, ys = plot_anytime.read_curve(os.path.join(r["folder"], "anytime.csv"), "time_s")
        if xs:
            ax.step(xs, ys, where="post", label=describe(r, table))
            drawn += 1
    plot_anytime.label_axes(ax, "time_s")
    if drawn:
        ax.legend(fontsize=7)
    shown = min(len(rows), MAX_CURVES)
    return [("RRT* cost over time", f"Best path cost against planning time, one line per MoveBot point with a "
             f"solution: {drawn} of the {shown} points shown" + (f" (of {len(rows)})" if len(rows) > shown else "")
             + " found one within their budget.", png_of(fig))]


def exit_axes(table):
    rows = [r for _, r in table[table["workload"] == "collide"].iterrows() if os.path.exists(_timeline(r))]
    if not rows:
        return []
    fig, ax = plt.subplots(figsize=(9, 4))
    names = None
    width = 0.8 / min(len(rows), MAX_CURVES)
    for k, r in enumerate(rows[:MAX_CURVES]):
        with open(_timeline(r)) as f:
            exits = [(e["key"], float(e["value"])) for e in csv.DictReader(f) if e["section"] == "node_test_exit"]
        total = sum(v for _, v in exits) or 1.0
        names = [n for n, _ in exits]
        ax.bar(np.arange(len(exits)) + k * width, [100 * v / total for _, v in exits], width,
               label=describe(r, table))
    ax.set_xticks(np.arange(len(names)) + 0.4 - width / 2)
    ax.set_xticklabels(names, rotation=60, fontsize=7, ha="right")
    ax.set_ylabel("share of node tests (%)")
    ax.set_title("How the collision kernel's node tests ended (SACT axis that separated, or overlap)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    return [("Collision exit-axis distribution",
             "Share of all node tests that ended at each of the 15 SACT axes (a separation), in an overlap, a "
             "sphere pre-test, or with no test; from the `node_test_exit` section of each `rcbench collide` "
             "timeline.", png_of(fig))]


GENERIC = [schedule, trajectory, astar, anytime, exit_axes]


def all_figures(table):
    ok = table[table["status"] == "ok"]
    figures = []
    for make in GENERIC:
        try:
            figures += make(ok)
        except Exception as e:  # a figure that cannot be drawn is named in the report, not hidden
            figures.append((f"{make.__name__}: not drawn", f"{type(e).__name__}: {e}", None))
    return figures

