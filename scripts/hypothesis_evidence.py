#!/usr/bin/python3
"""How much the scans favour one start hypothesis over a look-alike, record by record.

Runs `rcbench delibot` twice per log and sensor model, tracking from two
starts: the scan-matching reference's first pose (A) and the same pose moved
by --offset (B, e.g. the look-alike door one door west). Every sensor
update's timeline value `log_mean_likelihood_nats` is log p(scan | earlier scans,
start), the particle estimate of the update's normalizer, so its running sum
is the log marginal likelihood of the scans so far given the start, and the
difference of the two sums is the log Bayes factor of A over B (nats). Both
runs see the same scans and the same update gating (it depends on odometry
only). A filter that resamples a hypothesis away while this difference is
negative cannot get it back, however large the difference grows later.

Writes
  <out>/hypothesis_evidence.csv   log, model, record, cum_a_nats, cum_b_nats,
                                  log_bayes_factor_nats, separation_m
  --figure FILE                   the log Bayes factor against the record,
                                  one panel per log, one line per model
and prints per (log, model): the lowest log Bayes factor and its record, the
last record at which it was below 0 ("never", or "still below at the end"),
and its final value. separation_m is the
distance between the two tracks' estimates: a track that has wandered onto
the other hypothesis (separation near 0) no longer compares two hypotheses.

Usage: scripts/hypothesis_evidence.py [--rcbench build/rcbench]
       [--data-dir ../shared/data] [--reference-dir out/reference]
       [--logs robotdata1,robotdata2] [--models likelihood,beam]
       [--offset -5.9,0] [--out out/evidence] [--figure F.png]
       [-- EXTRA RCBENCH ARGS]
Every run uses --quiet --no-pricing --recovery-alpha-slow 0 (random
injection would let a track jump to the other hypothesis) plus the extra
arguments. The reference files come from scripts/scan_match_reference.py.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import subprocess
import sys
import tempfile

from rcbench_files import SHARED_DATA, InputError, atomic_output, save_figure, read_cumulative_evidence, read_poses, split_extra_args



def fail(message):
    sys.exit(f"hypothesis_evidence: {message}")


def first_reference_pose(path):
    """(x_m, y_m, theta_rad) of the first pose of a ground-truth file."""
    try:
        return tuple(read_poses(path)[0][1:])
    except InputError as e:
        fail(f"{e} (make the reference with scripts/scan_match_reference.py)")


def read_evidence(path):
    """Per record: (cumulative log_mean_likelihood_nats, est_x_m, est_y_m)."""
    try:
        return [(total, x, y) for total, _, x, y in read_cumulative_evidence(path)]
    except InputError as e:
        fail(str(e))


def run_track(rcbench, map_path, trace_path, start, model, extra, timeline):
    cmd = [rcbench, "delibot", "--map", map_path, "--trace", trace_path, "--sensor-model", model,
           "--initial-pose", ",".join(f"{v:.6f}" for v in start), "--recovery-alpha-slow", "0",
           "--quiet", "--no-pricing", "--threads", "1", "--timeline", timeline, *extra]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(cmd)} exited {done.returncode}: {done.stderr.strip()}")
    return read_evidence(timeline)


def summarize(diff):
    """Lowest value and its record, when the factor was last below 0 ('never',
    'still at the end', or the record), and the final value."""
    low = min(range(len(diff)), key=lambda i: diff[i])
    below = [i for i, d in enumerate(diff) if d < 0]
    if not below:
        last_below = "never"
    elif diff[-1] < 0:
        last_below = "still below at the end"
    else:
        last_below = f"record {below[-1]}"
    return diff[low], low, last_below, diff[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--data-dir", default=SHARED_DATA)
    ap.add_argument("--reference-dir", default="out/reference")
    ap.add_argument("--logs", default="robotdata1,robotdata2", help="comma-separated CMU log names")
    ap.add_argument("--models", default="likelihood,beam", help="comma-separated --sensor-model values")
    ap.add_argument("--offset", default="-5.9,0", help="start B = start A + (dx, dy) (m, m)")
    ap.add_argument("--out", default="out/evidence")
    ap.add_argument("--figure", default="", help="PNG of the log Bayes factor per record")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (count)")
    own, extra = split_extra_args(sys.argv[1:])
    args = ap.parse_args(own)
    try:
        dx, dy = (float(v) for v in args.offset.split(","))
    except ValueError:
        fail(f"--offset '{args.offset}': expected DX,DY in metres")
    if not os.path.exists(args.rcbench):
        fail(f"{args.rcbench}: not found (build it with scripts/setup)")
    map_path = os.path.join(args.data_dir, "wean", "wean.dat")
    logs = [l for l in args.logs.split(",") if l]
    models = [m for m in args.models.split(",") if m]
    os.makedirs(args.out, exist_ok=True)

    jobs = {}
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for log in logs:
            trace = os.path.join(args.data_dir, "wean", log + ".log")
            if not os.path.exists(trace):
                fail(f"{trace}: not found")
            a = first_reference_pose(os.path.join(args.reference_dir, log + ".ref.txt"))
            b = (a[0] + dx, a[1] + dy, a[2])
            for model in models:
                for name, start in (("a", a), ("b", b)):
                    timeline = os.path.join(tmp, f"{log}_{model}_{name}.csv")
                    jobs[(log, model, name)] = pool.submit(run_track, args.rcbench, map_path, trace, start, model,
                                                           extra, timeline)
        results = {key: job.result() for key, job in jobs.items()}

    csv_path = os.path.join(args.out, "hypothesis_evidence.csv")
    curves = {}
    with atomic_output(csv_path, newline="") as f:
        w = csv.writer(f)
        w.writerow(["log", "model", "record", "cum_a_nats", "cum_b_nats", "log_bayes_factor_nats", "separation_m"])
        for log in logs:
            for model in models:
                a, b = results[(log, model, "a")], results[(log, model, "b")]
                diff = []
                for record, ((ca, xa, ya), (cb, xb, yb)) in enumerate(zip(a, b)):
                    diff.append(ca - cb)
                    w.writerow([log, model, record, f"{ca:.3f}", f"{cb:.3f}", f"{ca - cb:.3f}",
                                f"{math.hypot(xa - xb, ya - yb):.3f}"])
                curves[(log, model)] = diff
                low, low_at, last_below, final = summarize(diff)
                min_sep = min(math.hypot(pa[1] - pb[1], pa[2] - pb[2]) for pa, pb in zip(a, b))
                print(f"{log} {model}: lowest {low:.1f} nats at record {low_at}, last below 0: "
                      f"{last_below}, final {final:.1f} nats; tracks at least {min_sep:.1f} m apart")
    print(f"wrote {csv_path}")

    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, len(logs), figsize=(6 * len(logs), 4), squeeze=False)
        for ax, log in zip(axes[0], logs):
            for model in models:
                ax.plot(curves[(log, model)], label=model)
            ax.axhline(0.0, color="black", linewidth=0.8)
            ax.set_yscale("symlog", linthresh=10.0)
            ax.set_title(f"{log}: start A (reference) vs B (A + ({dx:g}, {dy:g}) m)")
            ax.set_xlabel("laser record")
            ax.set_ylabel("log Bayes factor A over B (nats)")
            ax.legend()
            ax.grid(True, alpha=0.3)
        fig.tight_layout()
        os.makedirs(os.path.dirname(os.path.abspath(args.figure)), exist_ok=True)
        save_figure(fig, args.figure, dpi=110)
        print(f"wrote {args.figure}")


if __name__ == "__main__":
    main()
