#!/usr/bin/python3
"""MoveBot cost distribution per nearest-neighbour structure: analysis of
scripts/workflow/studies/movebot_cost.yaml (our RRTstar with each --nn
choice against stock RRTstar + GNAT, on the same fixed seeds).

RRTstar's result depends only on the seed and the neighbours it is given;
an exact nearest-neighbour structure returns the same neighbours as GNAT
(up to ties), so equal distributions are the expected outcome.

Writes into OUT_DIR
  movebot_cost_study.csv   nn, seed, exact (exit code 0), final_cost_rad
  movebot_cost_summary.csv per structure: exact runs, median / min / max final cost (rad)
  movebot_cost_study.md    the summary as a Markdown table (printed too)
Usage: scripts/movebot_cost_study.py MERGED_CSV OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "workflow"))
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    ok = ok[ok["workload"] == "movebot"]
    if ok.empty:
        sys.exit(f"{merged}: no successful MoveBot point")
    runs = pd.DataFrame({"nn": ok["nn"], "seed": ok["seed"], "exact": ok["result.exact_path"],
                         "final_cost_rad": ok["anytime.best_cost_rad"]})
    analysis_io.save_table(runs, out_dir, "movebot_cost_study.csv")
    rows = []
    for nn, sel in runs.groupby("nn", sort=False):
        costs = sel[sel["exact"] == 1]["final_cost_rad"].dropna()
        rows.append({"nn": nn, "exact_runs": f"{len(costs)}/{len(sel)}",
                     "median_cost_rad": round(float(costs.median()), 3) if len(costs) else "-",
                     "min_cost_rad": round(float(costs.min()), 3) if len(costs) else "-",
                     "max_cost_rad": round(float(costs.max()), 3) if len(costs) else "-"})
    summary = pd.DataFrame(rows)
    analysis_io.save_table(summary, out_dir, "movebot_cost_summary.csv")
    md = ["| nn | exact runs | median cost (rad) | min | max |", "|---|---|---|---|---|"]
    md += [f"| {r['nn']} | {r['exact_runs']} | {r['median_cost_rad']} | {r['min_cost_rad']} | {r['max_cost_rad']} |"
           for r in rows]
    text = "\n".join(md) + "\n"
    analysis_io.save_text(text, out_dir, "movebot_cost_study.md")
    print(text)


if __name__ == "__main__":
    main()
