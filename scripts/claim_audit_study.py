#!/usr/bin/python3
"""Analysis of a DeliBot claim study: the same traces run with the claim
audit (run "audit") and without it (run "unaudited", `--no-claim-audit`;
scripts/workflow/studies/claim_audit_held_out.yaml), each run's claim
graded against the ground truth.

A run's claim is the filter's own, ground-truth-free claim of being
localized (the summary's convergence_iteration_without_ground_truth: with
audits, the first claim an audit passed). It held when at least 95 % of the
records from it on are within 1 m of the truth (accuracy_study.claim_held,
the grade of every claim table in docs/defaults.md); otherwise it is wrong.
Per (map, run) the script reports claims made / held / wrong / never, the
claim records, the due claims that audits refused, and the median host time
(the run's own `totals.wall_s`), and per map every claim a run without
audits made that held and the audited run of the same trace did not make
(a lost claim).

Writes into OUT_DIR
  claim_audit_study.csv  one row per point: map, seed, run, claim record,
                         held (1/0; empty when no claim), refused audits,
                         host time (s)
  claim_audit_study.md   the per-(map, run) table, and the lost claims
Usage: scripts/claim_audit_study.py MERGED_CSV OUT_DIR
"""
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402
from accuracy_study import claim_held  # noqa: E402

CLAIM = "accuracy.convergence_iteration_without_ground_truth"
REFUSED = "accuracy.claims_refused_by_audit"
HOST_S = "totals.wall_s"


def per_point(ok):
    rows = []
    for _, r in ok.iterrows():
        claim = int(r[CLAIM])
        held = claim_held(os.path.join(r["folder"], "timeline.csv"), claim) if claim >= 0 else None
        rows.append({"map": r["map_label"], "seed": int(r["seed"]), "run": r["run"], "claim_record": claim,
                     "held": "" if held is None else int(held),
                     "refused_audits": int(r[REFUSED]) if pd.notna(r.get(REFUSED)) else 0,
                     "host_time_s": round(float(r[HOST_S]), 1)})
    return pd.DataFrame(rows)


def summary(points):
    lines = ["| map | run | runs | claims made / held / wrong / never | claim records | refused audits |"
             " median host time (s) |", "|---|---|---|---|---|---|---|"]
    for (map_name, run), sel in points.groupby(["map", "run"], sort=False):
        made = sel[sel["claim_record"] >= 0]
        held = int((made["held"] == 1).sum())
        records = ", ".join(str(c) for c in sorted(made["claim_record"])) or "-"
        lines.append(f"| {map_name} | {run} | {len(sel)} | {len(made)} / {held} / {len(made) - held} / "
                     f"{len(sel) - len(made)} | {records} | {int(sel['refused_audits'].sum())} | "
                     f"{statistics.median(sel['host_time_s']):.1f} |")
    lost = []
    for (map_name, seed), sel in points.groupby(["map", "seed"], sort=False):
        by_run = {r["run"]: r for _, r in sel.iterrows()}
        plain, audited = by_run.get("unaudited"), by_run.get("audit")
        if plain is None or audited is None:
            continue
        if plain["claim_record"] >= 0 and plain["held"] == 1 and not (
                audited["claim_record"] >= 0 and audited["held"] == 1):
            lost.append(f"{map_name} seed {seed} (claim at record {plain['claim_record']} without audits)")
    return "\n".join(lines) + "\n\nHeld claims lost with audits: " + ("; ".join(lost) or "none") + ".\n"


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    analysis_io.require_columns(table, merged, ("map_label", "seed", "run", CLAIM, HOST_S), "a claim study")
    points = per_point(ok)
    if points.empty:
        sys.exit(f"{merged}: no point ran")
    analysis_io.save_table(points, out_dir, "claim_audit_study.csv")
    md = summary(points)
    analysis_io.save_text(md, out_dir, "claim_audit_study.md")
    print(md)


if __name__ == "__main__":
    main()
