#!/usr/bin/python3
"""Leave-one-log-out check of the hypothesis window picked on the real logs
(analysis of scripts/workflow/studies/window_cv.yaml).

The cautious recipe's --hypothesis-window was chosen with all four Wean logs
in view, and there is no fifth real log to test it on. This script asks the
next best question: had the window been picked on three logs, how would the
fourth have fared? The study runs the real-log study's points once per
window (the same seeds, the recipe's other options unchanged); this script
judges every point as scripts/real_logs_study.py does, then for each log
picks the window on the other three by a fixed rule and reports the
held-out log's claim outcomes at that window.

The rule, in order: fewest wrong claims (a wrong claim is the failure a user
cannot see), then most claims that held, then the larger window (the more
cautious filter). Outcomes are real_logs_study.py's: held (>= 95 % of the
records within 1 m of the reference from the claim on), wrong, or none.

Writes into OUT_DIR
  window_grid.csv          log, window_nats, held, held_late, wrong, none, ends_within_1m
  cross_validation.csv     held-out log, chosen window, its outcomes there
  cross_validation.md      both tables in Markdown (printed too)

Usage: scripts/window_cross_validation.py MERGED_CSV OUT_DIR
"""
import io
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402

import real_logs_study  # noqa: E402

WINDOW = "hypothesis_window_nats"


def fail(message):
    sys.exit(f"window_cross_validation: {message}")


def outcome_counts(rows):
    """Per log: counts of held, held in the second half, wrong, none, and runs ending within 1 m."""
    counts = {}
    for row in rows:
        c = counts.setdefault(row["log"], {"held": 0, "held_late": 0, "wrong": 0, "none": 0,
                                           "ends_within_1m": 0, "runs": 0})
        outcome = row["claim_outcome"]
        if outcome == "-":
            fail(f"no reference for {row['log']} (the points need --ground-truth)")
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
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    if WINDOW not in table.columns:
        fail(f"{merged}: no '{WINDOW}' column: the study must vary --hypothesis-window")
    rows, _, _ = real_logs_study.judged_rows(ok)
    window_of = dict(zip(ok["point"], ok[WINDOW].astype(float)))
    windows = sorted(set(window_of.values()))
    grid = {w: outcome_counts([r for r in rows if window_of[r["point"]] == w]) for w in windows}
    logs = sorted(grid[windows[0]])
    if len(logs) < 2 or any(sorted(grid[w]) != logs for w in windows):
        fail("every window must cover the same two or more logs (a failed point leaves a hole: see the merged table)")
    folds = [(log, choose(grid, windows, [other for other in logs if other != log])) for log in logs]

    grid_rows = [{"log": log, "window_nats": f"{w:g}", **grid[w][log]} for w in windows for log in logs]
    analysis_io.save_table(pd.DataFrame(grid_rows), out_dir, "window_grid.csv")
    fold_rows = [{"held_out_log": log, "window_nats": f"{w:g}", **grid[w][log]} for log, w in folds]
    analysis_io.save_table(pd.DataFrame(fold_rows), out_dir, "cross_validation.csv")
    md = markdown(grid, windows, logs, folds)
    analysis_io.save_text(md, out_dir, "cross_validation.md")
    print(md)


if __name__ == "__main__":
    main()
