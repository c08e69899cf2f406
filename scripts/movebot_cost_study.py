#!/usr/bin/python3
"""MoveBot cost distribution per nearest-neighbour structure: analysis of
scripts/workflow/studies/movebot_cost.yaml (our RRTstar with each --nn
choice against stock RRTstar + GNAT, on the same fixed seeds, at one or
more iteration budgets).

RRTstar's result depends only on the seed and the neighbours it is given;
an exact nearest-neighbour structure returns the same neighbours as GNAT
(up to ties), so equal distributions are the expected outcome, and more:
the same result seed by seed. The script counts the seeds where the
structures disagree (a different outcome, or exact costs more than 1e-9
rad apart).

Writes into OUT_DIR
  movebot_cost_study.csv   iterations, nn, seed, exact (exit code 0), final_cost_rad
  movebot_cost_summary.csv per budget and structure: exact runs, median /
                           quartiles / min / max final cost of the exact runs (rad)
  movebot_cost_study.md    the summary as a Markdown table, and per budget
                           the seeds where the structures disagree (printed too)
Usage: scripts/movebot_cost_study.py MERGED_CSV OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402

COST_TOLERANCE_RAD = 1e-9  # two exact costs closer than this are the same path's


def rounded(value):
    return round(float(value), 3)


def summary_rows(runs):
    rows = []
    for (iterations, nn), sel in runs.groupby(["iterations", "nn"], sort=False):
        costs = sel[sel["exact"] == 1]["final_cost_rad"].dropna()
        row = {"iterations": int(iterations), "nn": nn, "exact_runs": f"{len(costs)}/{len(sel)}"}
        for key, q in (("min", 0.0), ("q1", 0.25), ("median", 0.5), ("q3", 0.75), ("max", 1.0)):
            row[f"{key}_cost_rad"] = rounded(costs.quantile(q)) if len(costs) else "-"
        rows.append(row)
    return rows


def disagreements(runs):
    """Per budget: the seeds whose structures gave different outcomes or
    costs, and how many seeds every structure ran."""
    out = {}
    for iterations, budget in runs.groupby("iterations", sort=False):
        differ, compared = [], 0
        structures = budget["nn"].nunique()
        for seed, sel in budget.groupby("seed"):
            if len(sel) != structures:
                continue  # a structure's point failed: nothing to compare
            compared += 1
            exact = set(sel["exact"])
            costs = sel[sel["exact"] == 1]["final_cost_rad"]
            if len(exact) > 1 or (len(costs) and costs.max() - costs.min() > COST_TOLERANCE_RAD):
                differ.append(int(seed))
        out[int(iterations)] = (compared, differ)
    return out


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    ok = ok[ok["workload"] == "movebot"]
    if ok.empty:
        sys.exit(f"{merged}: no successful MoveBot point")
    analysis_io.require_columns(ok, merged, ["nn", "seed", "iterations", "result.exact_path",
                                             "anytime.best_cost_rad"], "movebot_cost")
    runs = pd.DataFrame({"iterations": ok["iterations"].astype(int), "nn": ok["nn"], "seed": ok["seed"],
                         "exact": ok["result.exact_path"], "final_cost_rad": ok["anytime.best_cost_rad"]})
    runs = runs.sort_values(["iterations", "nn", "seed"], kind="stable")
    analysis_io.save_table(runs, out_dir, "movebot_cost_study.csv")
    rows = summary_rows(runs)
    analysis_io.save_table(pd.DataFrame(rows), out_dir, "movebot_cost_summary.csv")
    md = ["| iterations | nn | exact runs | min | q1 | median cost (rad) | q3 | max |",
          "|---|---|---|---|---|---|---|---|"]
    md += [f"| {r['iterations']} | {r['nn']} | {r['exact_runs']} | {r['min_cost_rad']} | {r['q1_cost_rad']} | "
           f"{r['median_cost_rad']} | {r['q3_cost_rad']} | {r['max_cost_rad']} |" for r in rows]
    md.append("")
    for iterations, (compared, differ) in disagreements(runs).items():
        listed = ", ".join(str(s) for s in differ) if differ else "none"
        md.append(f"- {iterations} iterations: structures disagree on {len(differ)} of {compared} seeds ({listed})")
    text = "\n".join(md) + "\n"
    analysis_io.save_text(text, out_dir, "movebot_cost_study.md")
    print(text)


if __name__ == "__main__":
    main()
