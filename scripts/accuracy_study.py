#!/usr/bin/python3
"""Analysis of the DeliBot accuracy study (scripts/workflow/studies/accuracy.yaml;
the CI runs a reduced version: tests/delibot/accuracy_regression_test.cc).

The study runs, per map and seed, a simulated trace with ground truth, then
global localization from uniform particles (mode=global) and tracking from
the true first pose (mode=tracking). This script reports, per map:
  - the fraction of seeds whose global localization converged (error below
    0.2 m and 5 deg for 10 consecutive records, and still so at the end);
  - the median tracking error, the runs still within 0.2 m at the end, and
    the jumps (estimate moved > 1 m between records) after convergence;
  - global localization's own (ground-truth-free) claims of convergence:
    made, held, wrong and never made, and the median claim record (a claim
    held if at least 95 % of the records from it on are within 1 m of the
    truth: what a user without ground truth would have relied on), and
    whether the claim standing at the end held (a claim the filter
    contradicted later, by a jump or injected particles, is withdrawn).
Why these settings (1000 records, 500 tracking particles): docs/studies.md.

Writes into OUT_DIR
  accuracy_study.csv   one row per (map, seed): global_* and tracking_* columns
  accuracy_summary.csv the per-map summary
  accuracy_study.md    the same summary as a Markdown table
Usage: scripts/accuracy_study.py MERGED_CSV OUT_DIR
"""
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402

from rcbench_files import InputError, read_timeline_rows  # noqa: E402

CLAIM_RADIUS_M = 1.0
CLAIM_FRACTION = 0.95


def claim_held(timeline, claim):
    """At least 95 % of the records from the claim on within 1 m of the truth."""
    if claim < 0:
        return False
    try:
        rows = read_timeline_rows(timeline, ("iteration", "err_xy_m"))
    except InputError as e:
        sys.exit(f"accuracy_study: {e}")
    after = [float(r["err_xy_m"]) for r in rows if int(r["iteration"]) >= claim]
    return bool(after) and sum(e < CLAIM_RADIUS_M for e in after) >= CLAIM_FRACTION * len(after)


def per_seed(ok):
    rows = []
    for (map_name, seed), pair in ok.groupby(["map_label", "seed"], sort=False):
        by_mode = {r["mode"]: r for _, r in pair.iterrows()}
        if set(by_mode) != {"global", "tracking"}:
            continue  # one of the two runs failed: the merged table names it
        row = {"map": map_name, "seed": int(seed)}
        for mode, r in by_mode.items():
            row[f"{mode}_converged"] = int(r["accuracy.convergence_iteration"] >= 0 and r["accuracy.converged_at_end"])
            row[f"{mode}_convergence_iteration"] = int(r["accuracy.convergence_iteration"])
            row[f"{mode}_median_err_xy_m"] = r["accuracy.median_err_xy_m"]
            row[f"{mode}_final_err_xy_m"] = r["accuracy.final_err_xy_m"]
            row[f"{mode}_jumps"] = int(r["accuracy.jumps_after_convergence"])
            row[f"{mode}_time_per_update_s"] = r["totals.wall_per_update_s"]
        g = by_mode["global"]
        timeline = os.path.join(g["folder"], "timeline.csv")
        claim = int(g["accuracy.convergence_iteration_without_ground_truth"])
        standing = int(g.get("accuracy.standing_claim_iteration", -1))
        row["global_own_claim_record"] = claim
        row["global_own_claim_held"] = int(claim_held(timeline, claim))
        row["global_standing_claim_record"] = standing
        row["global_standing_claim_held"] = int(claim_held(timeline, standing))
        rows.append(row)
    return pd.DataFrame(rows)


def summary(seeds):
    out = []
    for name, sel in seeds.groupby("map", sort=False):
        conv = sel[sel["global_converged"] == 1]
        trk = sel["tracking_median_err_xy_m"]
        its = list(conv["global_convergence_iteration"])
        n = len(sel)
        made = sel[sel["global_own_claim_record"] >= 0]
        held = int(made["global_own_claim_held"].sum())
        out.append({
            "map": name, "seeds": n,
            "global_converged": f"{len(conv)}/{n} ({100 * len(conv) / n:.0f}%)",
            "median_convergence_record": statistics.median(its) if its else "-",
            "jumps_after_global_convergence": int(conv["global_jumps"].sum()),
            "tracking_median_err_xy_m": f"{trk.median():.3f}",
            "worst_tracking_median_err_xy_m": f"{trk.max():.3f}",
            "tracking_localized_at_end": f"{int(sel['tracking_converged'].sum())}/{n}",
            "tracking_jumps": int(sel["tracking_jumps"].sum()),
            "global_own_claims_made_held_wrong_never": f"{len(made)} / {held} / {len(made) - held} / {n - len(made)}",
            "global_median_own_claim_record": statistics.median(made["global_own_claim_record"]) if len(made) else "-",
            "global_standing_claim_held": f"{int(sel['global_standing_claim_held'].sum())}/{n}",
        })
    return pd.DataFrame(out)


def markdown(table):
    head = ["map", "seeds", "global localization converged", "median convergence record",
            "jumps after global convergence", "tracking median error (m)", "worst tracking median (m)",
            "tracking still localized at the end", "tracking jumps",
            "global: own claims made / held / wrong / never", "global: median own claim record",
            "global: claim standing at the end held"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for _, r in table.iterrows():
        lines.append("| " + " | ".join(str(v) for v in r.values) + " |")
    return "\n".join(lines) + "\n"


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    analysis_io.require_columns(table, merged, ("map_label", "mode", "seed"), "the accuracy study")
    seeds = per_seed(ok)
    if seeds.empty:
        sys.exit(f"{merged}: no (map, seed) with both runs ok")
    analysis_io.save_table(seeds, out_dir, "accuracy_study.csv")
    per_map = summary(seeds)
    analysis_io.save_table(per_map, out_dir, "accuracy_summary.csv")
    md = markdown(per_map)
    analysis_io.save_text(md, out_dir, "accuracy_study.md")
    print(md)


if __name__ == "__main__":
    main()
