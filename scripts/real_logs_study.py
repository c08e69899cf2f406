#!/usr/bin/python3
"""Analysis of DeliBot on the real CMU Wean Hall logs, judged against a
scan-matching reference (scripts/workflow/studies/real_logs.yaml).

The study runs `rcbench delibot` on robotdata1..4 for several seeds, with
--ground-truth set to the reference trajectory of
scripts/scan_match_reference.py (the reference is an estimate, not ground
truth: its own error is about 0.1-1 m, larger along featureless corridors;
see that script). This script reads each point's summary (the merged CSV)
and its timeline, and writes into OUT_DIR
  real_logs_study.csv   one row per (log, seed)
  real_logs_study.md    one Markdown table per log, one row per seed
  real_logs_error.png   position error against the reference vs record,
                        one panel per log, one line per seed
Columns: the record where the filter declared convergence (-1 = never),
whether it is still converged at the end, median scan consistency and jumps
after convergence (rcbench's ground-truth-free measures), and against the
reference: the fraction of records from convergence on (every record when
tracking, i.e. when the point set --initial-pose) with error < 1 m,
the median error from convergence on and over all records, the final error
(m), plus whether any non-finite value appeared (weights, estimates). With a
reference, rcbench's "converged" is judged against it (within 0.2 m and 5
deg for 10 records); the table also gives the record from which the filter
itself claimed convergence without ground truth (mode weight and scan
consistency), the fraction within 1 m from that claim on, and two verdicts:
right (converged in the first half, then >= 95 % of records within 1 m) and
right by its own claim (the same from the filter's own claim), with totals,
(the CSV also has standing_claim_record and claims_withdrawn: the claim
standing at the end, after the filter withdrew the ones it contradicted),
and what became of the own claims whenever they came (claim_outcome: held,
wrong, or none when the filter never claimed; - without a reference).
rcbench's own err_xy_m timeline column must agree with the error computed
here (a check that the reference pairs with the right records).

Usage: scripts/real_logs_study.py MERGED_CSV OUT_DIR
"""
import csv
import io
import json
import math
import os
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402

from rcbench_files import InputError, read_poses, read_timeline_rows  # noqa: E402

GOOD_ERROR_M = 1.0
RIGHT_FRACTION = 0.95


def fail(message):
    sys.exit(f"real_logs_study: {message}")


def read_reference(path):
    """(t_s, x_m, y_m, theta_rad) rows of a ground-truth file as an array."""
    try:
        return np.array(read_poses(path))
    except InputError as e:
        fail(str(e))


def read_timeline(path):
    """(record index, estimates [n, 3], rcbench's err_xy_m column or None)."""
    try:
        rows = read_timeline_rows(path, ("iteration", "est_x_m", "est_y_m", "est_theta_rad"))
    except InputError as e:
        fail(str(e))
    it = np.array([int(r["iteration"]) for r in rows])
    est = np.array([[float(r["est_x_m"]), float(r["est_y_m"]), float(r["est_theta_rad"])] for r in rows])
    err = np.array([float(r["err_xy_m"]) for r in rows]) if "err_xy_m" in rows[0] else None
    return it, est, err


def judge(log_name, seed, summary_path, timeline_path, reference, tracking):
    with open(summary_path) as f:
        s = json.load(f)
    a = s["accuracy"]
    it, est, rc_err = read_timeline(timeline_path)
    conv = int(a["convergence_iteration"])
    claim = int(a.get("convergence_iteration_without_ground_truth", conv))
    row = {"log": log_name, "seed": seed, "records": len(it), "converged_record": conv, "own_claim_record": claim,
           "standing_claim_record": int(a.get("standing_claim_iteration", -1)),
           "claims_withdrawn": int(a.get("claims_withdrawn", 0)),
           "converged_at_end": int(bool(a["converged_at_end"])),
           "median_consistency": a["median_consistency_after_convergence"],
           "jumps_after_convergence": a["jumps_after_convergence"],
           "fraction_err_below_1m": float("nan"), "median_err_xy_m": float("nan"),
           "median_err_xy_all_m": float("nan"), "final_err_xy_m": float("nan"),
           "fraction_err_below_1m_after_claim": float("nan"), "right": 0, "right_by_own_claim": 0,
           "claim_outcome": "-",
           "non_finite": int(bool(a.get("non_finite_weights", False)) or not np.isfinite(est).all())}
    err = None
    if reference is not None:
        if it.max() >= len(reference):
            fail(f"{timeline_path}: record {it.max()} but the reference has {len(reference)} poses")
        err = np.hypot(est[:, 0] - reference[it, 1], est[:, 1] - reference[it, 2])
        # rcbench pairs the reference with the records itself; both must agree
        if rc_err is not None and np.nanmax(np.abs(rc_err - err)) > 1e-3:
            fail(f"{timeline_path}: rcbench's err_xy_m differs from the reference by up to "
                 f"{np.nanmax(np.abs(rc_err - err)):.3g} m (wrong reference file?)")
        row["median_err_xy_all_m"] = float(np.median(err))
        # tracking starts localized: judge every record; global: from convergence on
        first = 0 if tracking else conv
        after = err[it >= first] if first >= 0 else np.array([])
        row["fraction_err_below_1m"] = float((after < GOOD_ERROR_M).mean()) if len(after) else 0.0
        row["median_err_xy_m"] = float(np.median(after)) if len(after) else float("nan")
        row["final_err_xy_m"] = float(err[-1])
        after_claim = err[it >= claim] if claim >= 0 else np.array([])
        row["fraction_err_below_1m_after_claim"] = (float((after_claim < GOOD_ERROR_M).mean())
                                                    if len(after_claim) else 0.0)
        # A run is right when it converges in the first half of the log and
        # is within 1 m of the reference in >= 95 % of the records from then
        # on; "by its own claim" starts from the filter's ground-truth-free
        # convergence, the record a user without a reference would trust.
        half = len(it) / 2
        row["right"] = int(0 <= first < half and row["fraction_err_below_1m"] >= RIGHT_FRACTION)
        row["right_by_own_claim"] = int(0 <= claim < half and
                                        row["fraction_err_below_1m_after_claim"] >= RIGHT_FRACTION)
        # What a user without a reference would have met, whenever the claim
        # came: it held, it was wrong, or the filter never claimed (the
        # cautious failure: it said it was not sure).
        if claim < 0:
            row["claim_outcome"] = "none"
        else:
            row["claim_outcome"] = ("held" if row["fraction_err_below_1m_after_claim"] >= RIGHT_FRACTION
                                    else "wrong")
    return row, it, err


def claim_outcomes(rows):
    """The own claims, whenever they came: held, wrong, or never made."""
    held = [r for r in rows if r["claim_outcome"] == "held"]
    late = sum(1 for r in held if r["own_claim_record"] >= r["records"] / 2)
    wrong = sum(1 for r in rows if r["claim_outcome"] == "wrong")
    never = [r for r in rows if r["claim_outcome"] == "none"]
    ends_near = sum(1 for r in rows if r["final_err_xy_m"] < GOOD_ERROR_M)
    text = (f"Own claims, whenever made: {len(held)} held ({late} of them in the second half of the log), "
            f"{wrong} wrong, {len(never)} never claimed")
    if never:
        text += f" (final error of those: median {float(np.median([r['final_err_xy_m'] for r in never])):.2f} m)"
    return text + f"; {ends_near} of {len(rows)} runs end within {GOOD_ERROR_M:g} m of the reference."


def fmt(v, digits=2):
    if isinstance(v, float):
        return "-" if math.isnan(v) else f"{v:.{digits}f}"
    return str(v)


def markdown(rows, logs, extra, tracking):
    out = [f"rcbench delibot {' '.join(extra) if extra else '(default options)'}"
           f"{', tracking from the reference start' if tracking else ', global localization'}; error = distance to the "
           f"scan-matching reference (not ground truth), "
           f"{'over every record' if tracking else 'from the convergence record on'}.", ""]
    for log in logs:
        mine = [r for r in rows if r["log"] == log]
        out.append(f"### {log}")
        out.append("")
        out.append("| seed | converged at record | converged at end | median consistency | jumps "
                   "| records with error < 1 m | median error (m) | median error, all records (m) "
                   "| final error (m) | non-finite | own claim at record | < 1 m from the claim on "
                   "| right | right by its own claim |")
        out.append("|---:|---:|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---|---|")
        for r in mine:
            out.append(f"| {r['seed']} | {r['converged_record']} | {'yes' if r['converged_at_end'] else 'no'} "
                       f"| {fmt(r['median_consistency'])} | {r['jumps_after_convergence']} "
                       f"| {percent(r['fraction_err_below_1m'])} "
                       f"| {fmt(r['median_err_xy_m'])} | {fmt(r['median_err_xy_all_m'])} | {fmt(r['final_err_xy_m'])} "
                       f"| {'yes' if r['non_finite'] else 'no'} | {r['own_claim_record']} "
                       f"| {percent(r['fraction_err_below_1m_after_claim'])} "
                       f"| {'yes' if r['right'] else 'no'} | {'yes' if r['right_by_own_claim'] else 'no'} |")
        out.append("")
    # The verdicts need the reference (claim_outcome is "-" without one).
    if not tracking and all(r["claim_outcome"] != "-" for r in rows):
        out.append(f"Right (converged in the first half, then >= {100 * RIGHT_FRACTION:.0f} % of records within "
                   f"{GOOD_ERROR_M:g} m of the reference): {sum(r['right'] for r in rows)} of {len(rows)}; "
                   f"by the filter's own (ground-truth-free) claim: {sum(r['right_by_own_claim'] for r in rows)} "
                   f"of {len(rows)}.")
        out.append("")
        out.append(claim_outcomes(rows))
        out.append("")
    return "\n".join(out)


def percent(fraction):
    return "-" if math.isnan(fraction) else f"{100 * fraction:.0f} %"


def plot(logs, curves, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = 2 if len(logs) > 1 else 1
    nrows = (len(logs) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(6.5 * cols, 3.6 * nrows), squeeze=False)
    for ax, log in zip(axes.ravel(), logs):
        for (name, seed), (it, err) in sorted(curves.items()):
            if name != log or err is None:
                continue
            line, = ax.plot(it, np.maximum(err, 0.03), lw=0.9, label=f"seed {seed}")  # log axis floor
            conv = next(r["converged_record"] for r in rows if r["log"] == name and r["seed"] == seed)
            if conv >= 0:
                ax.axvline(conv, color=line.get_color(), ls=":", lw=0.8)
        ax.axhline(GOOD_ERROR_M, color="k", lw=0.6, ls="--")
        ax.set_yscale("log")
        ax.set_ylim(0.03, 100.0)
        ax.set_title(f"{log} (dotted: declared convergence; dashed: 1 m)", fontsize=9)
        ax.set_xlabel("laser record")
        ax.set_ylabel("error vs reference (m)")
        ax.legend(fontsize=7)
    for ax in axes.ravel()[len(logs):]:
        ax.axis("off")
    fig.tight_layout()
    return fig


def judged_rows(ok):
    """(rows, curves, tracking) of every successful point: judge() per (log, seed)."""
    rows, curves = [], {}
    tracking_flags = set()
    references = {}
    for _, p in ok.iterrows():
        log, seed = p["log"], int(p["seed"])
        ref_path = p.get("ground_truth")
        reference = None
        if isinstance(ref_path, str) and ref_path:
            if ref_path not in references:
                references[ref_path] = read_reference(ref_path)
            reference = references[ref_path]
        tracking = isinstance(p.get("initial_pose"), str) and p.get("initial_pose") != ""
        tracking_flags.add(tracking)
        row, it, err = judge(log, seed, os.path.join(p["folder"], "summary.json"),
                             os.path.join(p["folder"], "timeline.csv"), reference, tracking)
        rows.append({"point": p["point"], **row})
        curves[(log, seed)] = (it, err)
    if len(tracking_flags) > 1:
        fail("the table mixes tracking and global-localization points; split them into two studies")
    return rows, curves, tracking_flags == {True}


def common_options(ok):
    """'option=value' of the options every point shares (files left out): the recipe."""
    record = {"point", "group", "workload", "status", "error", "exit_code", "wall_s", "host", "started_utc",
              "rcbench_sha256", "folder", "log", "seed", "map", "trace", "ground_truth"}
    shared = [c for c in ok.columns if c not in record and "." not in c and ok[c].astype(str).nunique() == 1]
    return [f"{c}={ok[c].iloc[0]}" for c in shared if not pd.isna(ok[c].iloc[0])]


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    if "log" not in table.columns or "seed" not in table.columns:
        fail(f"{merged}: no 'log' and 'seed' columns: not a real-log study's table")
    if ok.empty:
        fail(f"{merged}: no successful point")
    rows, curves, tracking = judged_rows(ok)
    logs = list(dict.fromkeys(r["log"] for r in rows))
    described = common_options(ok)
    text = io.StringIO()
    w = csv.DictWriter(text, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    analysis_io.save_text(text.getvalue(), out_dir, "real_logs_study.csv")
    md = markdown(rows, logs, described, tracking)
    analysis_io.save_text(md + "\n", out_dir, "real_logs_study.md")
    if any(e is not None for _, e in curves.values()):
        fig = plot(logs, curves, rows)
        analysis_io.save_figure(fig, out_dir, "real_logs_error.png",
                                "Position error against the scan-matching reference, per log, one line per seed "
                                "(dotted: declared convergence; dashed: 1 m).", dpi=80)
    print(md)


if __name__ == "__main__":
    main()
