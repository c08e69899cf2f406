#!/usr/bin/python3
"""Cost-model sensitivity: analysis of scripts/workflow/studies/sensitivity.yaml
(each point is one `rcbench calibrate --sensitivity` run, which writes
sensitivity.csv, calibration.csv and flips.md into the point's folder).

Writes into OUT_DIR, for every successful point (its particles and beams
in the figure's name when the study has more than one point):
  sensitivity.png        the tornado plot of scripts/plot_sensitivity.py: per
                         speedup result, the range each parameter moves it
                         over (x0.5 and x2, one at a time), widest first;
  sensitivity_ranges.csv per point, speedup result and parameter: the
                         baseline, the lowest and highest result (x faster),
                         and whether the range crosses 1x (the comparison flips);
  sensitivity_flips.md   the (result, parameter) pairs that flip, per point.
Usage: scripts/sensitivity_study.py MERGED_CSV OUT_DIR
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "workflow"))
sys.path.insert(0, HERE)
import analysis_io  # noqa: E402
import pandas as pd  # noqa: E402
import plot_sensitivity  # noqa: E402

NEUTRAL_X = 1.0  # a speedup of 1x: the two sides of the comparison are equally fast


def ranges(sensitivity_csv):
    """[(result, parameter, baseline, low, high)] of a sweep's speedup results."""
    order, baseline, spans = plot_sensitivity.read(sensitivity_csv)
    speedups = plot_sensitivity.speedup_results(os.path.join(os.path.dirname(sensitivity_csv), "calibration.csv"))
    rows = []
    for name in order:
        if name not in speedups:
            continue
        for parameter, values in spans[name].items():
            lo, hi = min(values + [baseline[name]]), max(values + [baseline[name]])
            rows.append((name, parameter, baseline[name], lo, hi))
    return rows


def main():
    merged, out_dir = analysis_io.arguments(__doc__)
    table, ok = analysis_io.load(merged)
    ok = ok[ok["workload"] == "calibrate"]
    if ok.empty:
        sys.exit(f"{merged}: no successful calibrate point")
    label_columns = [c for c in ("particles", "beams") if c in ok.columns]
    records, md = [], []
    for _, row in ok.iterrows():
        csv = os.path.join(row["folder"], "sensitivity.csv")
        if not os.path.exists(csv):
            sys.exit(f"{csv}: missing (was the point run with sensitivity: true?)")
        suffix = "" if len(ok) == 1 else "_" + ("_".join(f"{c}{row[c]}" for c in label_columns) or row["point"])
        where = ", ".join(f"{c} {row[c]}" for c in label_columns) or row["point"]
        fig = plot_sensitivity.figure(csv)
        analysis_io.save_figure(fig, out_dir, f"sensitivity{suffix}.png",
                                f"Each speedup result's range over one parameter at a time (x0.5 and x2; "
                                f"choices: every value), {where}; black: the default; dashed: 1x; red: flips.")
        flips = []
        for result, parameter, base, lo, hi in ranges(csv):
            crosses = (lo - NEUTRAL_X) * (hi - NEUTRAL_X) < 0
            records.append({"point": row["point"], **{c: row[c] for c in label_columns}, "result": result,
                            "parameter": parameter, "baseline_x": base, "low_x": lo, "high_x": hi,
                            "flips": crosses})
            if crosses:
                flips.append(f"| {result} | {parameter} | {base:.3g} | {lo:.3g} | {hi:.3g} |")
        md.append(f"### {where}\n")
        if flips:
            md += ["| result | parameter | default (x) | low (x) | high (x) |", "|---|---|---:|---:|---:|"] + flips
        else:
            md.append("No parameter moves a speedup result across 1x.")
        md.append("")
    analysis_io.save_table(pd.DataFrame(records), out_dir, "sensitivity_ranges.csv")
    text = "\n".join(md)
    analysis_io.save_text(text, out_dir, "sensitivity_flips.md")
    print(text)


if __name__ == "__main__":
    main()
