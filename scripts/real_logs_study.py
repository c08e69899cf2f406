#!/usr/bin/python3
"""DeliBot on the real CMU Wean Hall logs, judged against a scan-matching reference.

Runs `rcbench delibot` (global localization, or with --track-from-reference
tracking from the reference's first pose) on robotdata1..4 for several
seeds, with --ground-truth set to the reference trajectory of
scripts/scan_match_reference.py when <reference-dir>/robotdataN.ref.txt
exists (the reference is an estimate, not ground truth: its own error is
about 0.1-1 m, larger along featureless corridors; see that script). Every
run uses --quiet --no-pricing --threads 1 plus the arguments after `--`;
two runs at a time (--jobs). Reads each run's --summary JSON and --timeline
CSV and writes
  <out>/real_logs_study.csv   one row per (log, seed)
  <out>/real_logs_study.md    one Markdown table per log, one row per seed
  --figure FILE               position error against the reference vs record,
                              one panel per log, one line per seed
Columns: the record where the filter declared convergence (-1 = never),
whether it is still converged at the end, median scan consistency and jumps
after convergence (rcbench's ground-truth-free measures), and against the
reference: the fraction of records from convergence on (every record when
tracking) with error < 1 m,
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

Usage: scripts/real_logs_study.py [--rcbench build/rcbench] [--data-dir DIR]
       [--reference-dir out/reference] [--seeds 5] [--out out/real_logs]
       [--figure F.png (default <out>/real_logs_error.png)] [--track-from-reference]
       [-- EXTRA RCBENCH ARGS]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from rcbench_files import SHARED_DATA, InputError, read_poses, read_timeline_rows, split_extra_args

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


def run_one(job):
    cmd, log_name, seed = job
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        return log_name, seed, f"exit {result.returncode}: {' '.join(cmd)}\n{result.stderr.strip()}"
    return log_name, seed, None


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


def write_atomic(path, text):
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def plot(path, logs, curves, rows):
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
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-", suffix=".png")
    os.close(fd)
    fig.savefig(tmp, dpi=80)
    os.replace(tmp, path)


def main():
    argv, extra = split_extra_args(sys.argv[1:])
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--data-dir", default=os.path.join(SHARED_DATA, "wean"), help="holds wean.dat and robotdataN.log")
    ap.add_argument("--logs", default="1,2,3,4", help="which robotdataN.log (comma-separated N)")
    ap.add_argument("--reference-dir", default="out/reference", help="holds robotdataN.ref.txt (optional)")
    ap.add_argument("--seeds", type=int, default=5, help="seeds 1..S per log (count)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (count)")
    ap.add_argument("--track-from-reference", action="store_true",
                    help="tracking mode: --initial-pose at the reference's first pose (needs the reference)")
    ap.add_argument("--out", default="out/real_logs")
    # Default inside --out: a study run must not overwrite the committed figures.
    ap.add_argument("--figure", default="", help="PNG of error against record (default <out>/real_logs_error.png)")
    args = ap.parse_args(argv)
    if args.seeds < 1 or args.jobs < 1:
        fail("--seeds and --jobs must be >= 1")
    if not (os.path.isfile(args.rcbench) and os.access(args.rcbench, os.X_OK)):
        fail(f"rcbench not found or not executable at '{args.rcbench}' (build it, or pass --rcbench)")
    map_path = os.path.join(args.data_dir, "wean.dat")
    try:
        numbers = [int(v) for v in args.logs.split(",")]
    except ValueError:
        fail(f"--logs '{args.logs}' is not a comma-separated list of integers")
    logs = [f"robotdata{n}" for n in numbers]
    for p in [map_path] + [os.path.join(args.data_dir, log + ".log") for log in logs]:
        if not os.path.isfile(p):
            fail(f"data file '{p}' is missing (see --data-dir)")

    references, jobs = {}, []
    run_dir = os.path.join(args.out, "runs")
    os.makedirs(run_dir, exist_ok=True)
    for log in logs:
        ref_path = os.path.join(args.reference_dir, log + ".ref.txt")
        references[log] = (ref_path, read_reference(ref_path)) if os.path.isfile(ref_path) else (None, None)
        if references[log][0] is None:
            print(f"real_logs_study: no reference {ref_path}; {log} gets no error columns", file=sys.stderr)
        for seed in range(1, args.seeds + 1):
            stem = os.path.join(run_dir, f"{log}_seed{seed}")
            cmd = [args.rcbench, "delibot", "--map", map_path, "--trace", os.path.join(args.data_dir, log + ".log"),
                   "--seed", str(seed), "--quiet", "--no-pricing", "--threads", "1",
                   "--summary", stem + ".json", "--timeline", stem + ".csv", *extra]
            if references[log][0]:
                cmd += ["--ground-truth", references[log][0]]
                if args.track_from_reference:
                    x, y, theta = references[log][1][0, 1:]
                    cmd += ["--initial-pose", f"{x!r},{y!r},{theta!r}"]
            elif args.track_from_reference:
                fail(f"--track-from-reference needs {ref_path}")
            jobs.append((cmd, log, seed))

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        failures = [f"{log} seed {seed}: {msg}" for log, seed, msg in pool.map(run_one, jobs) if msg]
    if failures:
        fail("rcbench failed:\n" + "\n".join(failures))

    rows, curves = [], {}
    for _, log, seed in jobs:
        stem = os.path.join(run_dir, f"{log}_seed{seed}")
        row, it, err = judge(log, seed, stem + ".json", stem + ".csv", references[log][1],
                             args.track_from_reference)
        rows.append(row)
        curves[(log, seed)] = (it, err)

    import io
    text = io.StringIO()
    w = csv.DictWriter(text, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    write_atomic(os.path.join(args.out, "real_logs_study.csv"), text.getvalue())
    md = markdown(rows, logs, extra, args.track_from_reference)
    write_atomic(os.path.join(args.out, "real_logs_study.md"), md + "\n")
    figure = args.figure or os.path.join(args.out, "real_logs_error.png")
    figure = figure if any(e is not None for _, e in curves.values()) else ""
    if figure:
        plot(figure, logs, curves, rows)
    print(md)
    print(f"wrote {os.path.join(args.out, 'real_logs_study.csv')}, real_logs_study.md"
          f"{', ' + figure if figure else ' (no figure: no reference)'}", file=sys.stderr)


if __name__ == "__main__":
    main()
