#!/usr/bin/python3
"""Leave-one-log-out check of the hypothesis window picked on the real logs.

The cautious recipe's --hypothesis-window was chosen with all four Wean logs
in view, and there is no fifth real log to test it on. This script asks the
next best question: had the window been picked on three logs, how would the
fourth have fared? It runs scripts/real_logs_study.py once per window in
--windows (the same seeds, the recipe's other options unchanged), then for
each log picks the window on the other three by a fixed rule and reports the
held-out log's claim outcomes at that window.

The rule, in order: fewest wrong claims (a wrong claim is the failure a user
cannot see), then most claims that held, then the larger window (the more
cautious filter). Outcomes are real_logs_study.py's: held (>= 95 % of the
records within 1 m of the reference from the claim on), wrong, or none.

Writes
  <out>/window_W/...             each window's real_logs_study output
  <out>/window_grid.csv          log, window_nats, held, held_late, wrong, none, ends_within_1m
  <out>/cross_validation.csv     held-out log, chosen window, its outcomes there
  <out>/cross_validation.md      both tables in Markdown (printed too)

Usage: scripts/window_cross_validation.py [--windows 2,4,8,16,32] [--seeds 10]
       [--reference-dir out/reference] [--out out/window_cv] [--rcbench build/rcbench]
       -- <rcbench delibot options without --hypothesis-window>
"""
import argparse
import csv
import io
import os
import subprocess
import sys

from rcbench_files import split_extra_args

HERE = os.path.dirname(os.path.abspath(__file__))


def fail(message):
    sys.exit(f"window_cross_validation: {message}")


def parse_windows(text):
    try:
        windows = [float(v) for v in text.split(",")]
    except ValueError:
        fail(f"--windows '{text}' is not a comma-separated list of numbers (nats)")
    if not windows or any(not w > 0 for w in windows) or len(set(windows)) != len(windows):
        fail(f"--windows '{text}' must list distinct windows > 0 nats")
    return sorted(windows)


def window_dir(out, window):
    return os.path.join(out, f"window_{window:g}")


def run_study(args, window, extra):
    cmd = [sys.executable, os.path.join(HERE, "real_logs_study.py"), "--rcbench", args.rcbench,
           "--reference-dir", args.reference_dir, "--seeds", str(args.seeds), "--jobs", str(args.jobs),
           "--out", window_dir(args.out, window), "--", *extra, "--hypothesis-window", f"{window:g}"]
    print(f"window {window:g} nats: {' '.join(cmd)}", file=sys.stderr)
    result = subprocess.run(cmd, stdout=subprocess.DEVNULL)
    if result.returncode != 0:
        fail(f"real_logs_study.py failed for window {window:g} (exit {result.returncode})")


def read_outcomes(path):
    """Per log: counts of held, held in the second half, wrong, none, and runs ending within 1 m."""
    counts = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            c = counts.setdefault(row["log"], {"held": 0, "held_late": 0, "wrong": 0, "none": 0,
                                               "ends_within_1m": 0, "runs": 0})
            outcome = row["claim_outcome"]
            if outcome == "-":
                fail(f"{path}: no reference for {row['log']} (pass --reference-dir)")
            c[outcome] += 1
            if outcome == "held" and int(row["own_claim_record"]) >= int(row["records"]) / 2:
                c["held_late"] += 1
            c["ends_within_1m"] += float(row["final_err_xy_m"]) < 1.0
            c["runs"] += 1
    return counts


def choose(grid, windows, logs):
    """The rule of the module docstring, on the given logs."""
    def key(window):
        wrong = sum(grid[window][log]["wrong"] for log in logs)
        held = sum(grid[window][log]["held"] for log in logs)
        return (-wrong, held, window)
    return max(windows, key=key)


def markdown(grid, windows, logs, folds):
    out = io.StringIO()
    out.write(f"On all {len(logs)} logs the rule picks {choose(grid, windows, logs):g} nats.\n\n")
    out.write("| window (nats) | " + " | ".join(logs) + " | all: held / wrong / none |\n")
    out.write("|---:|" + "---|" * (len(logs) + 1) + "\n")
    for w in windows:
        cells = [f"{grid[w][log]['held']} / {grid[w][log]['wrong']} / {grid[w][log]['none']}" for log in logs]
        total = [sum(grid[w][log][k] for log in logs) for k in ("held", "wrong", "none")]
        out.write(f"| {w:g} | " + " | ".join(cells) + f" | {total[0]} / {total[1]} / {total[2]} |\n")
    out.write("\n| held-out log | window chosen on the other three (nats) | held-out: held (late) / wrong / none"
              " | ends within 1 m |\n|---|---:|---|---:|\n")
    for log, window in folds:
        c = grid[window][log]
        out.write(f"| {log} | {window:g} | {c['held']} ({c['held_late']}) / {c['wrong']} / {c['none']} | "
                  f"{c['ends_within_1m']} of {c['runs']} |\n")
    totals = {k: sum(grid[w][log][k] for log, w in folds) for k in ("held", "held_late", "wrong", "none",
                                                                      "ends_within_1m", "runs")}
    out.write(f"| all four, held out | | {totals['held']} ({totals['held_late']}) / {totals['wrong']} / "
              f"{totals['none']} | {totals['ends_within_1m']} of {totals['runs']} |\n")
    return out.getvalue()


def main():
    argv, extra = split_extra_args(sys.argv[1:])
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--windows", default="2,4,8,16,32", help="hypothesis windows to try (nats, comma-separated)")
    ap.add_argument("--seeds", type=int, default=10, help="seeds 1..S per log (count)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (count)")
    ap.add_argument("--reference-dir", default="out/reference", help="holds robotdataN.ref.txt")
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--out", default="out/window_cv")
    ap.add_argument("--reuse", action="store_true",
                    help="read an existing <out>/window_W/real_logs_study.csv instead of running it again")
    args = ap.parse_args(argv)
    windows = parse_windows(args.windows)
    if any(a == "--hypothesis-window" or a.startswith("--hypothesis-window=") for a in extra):
        fail("leave --hypothesis-window out of the rcbench options: this script sets it")
    if args.seeds < 1 or args.jobs < 1:
        fail("--seeds and --jobs must be >= 1")
    refs = [os.path.join(args.reference_dir, f"robotdata{n}.ref.txt") for n in range(1, 5)]
    missing = [p for p in refs if not os.path.isfile(p)]
    if missing:
        fail(f"reference missing: {', '.join(missing)} (scripts/scan_match_reference.py writes it)")

    grid = {}
    for w in windows:
        path = os.path.join(window_dir(args.out, w), "real_logs_study.csv")
        if not (args.reuse and os.path.isfile(path)):
            run_study(args, w, extra)
        grid[w] = read_outcomes(path)
    logs = sorted(grid[windows[0]])
    if len(logs) < 2 or any(sorted(grid[w]) != logs for w in windows):
        fail("every window's study must cover the same two or more logs")
    folds = [(log, choose(grid, windows, [other for other in logs if other != log])) for log in logs]

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "window_grid.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["log", "window_nats", "held", "held_late", "wrong", "none", "ends_within_1m", "runs"])
        for window in windows:
            for log in logs:
                c = grid[window][log]
                w.writerow([log, f"{window:g}", c["held"], c["held_late"], c["wrong"], c["none"],
                            c["ends_within_1m"], c["runs"]])
    with open(os.path.join(args.out, "cross_validation.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["held_out_log", "window_nats", "held", "held_late", "wrong", "none", "ends_within_1m", "runs"])
        for log, window in folds:
            c = grid[window][log]
            w.writerow([log, f"{window:g}", c["held"], c["held_late"], c["wrong"], c["none"], c["ends_within_1m"],
                        c["runs"]])
    md = markdown(grid, windows, logs, folds)
    with open(os.path.join(args.out, "cross_validation.md"), "w") as f:
        f.write(md)
    print(md)


if __name__ == "__main__":
    main()
