#!/usr/bin/python3
"""Merges a study's point records into one tidy CSV: one row per point, in
the configuration's order, with every parameter and every metric.

Columns, left to right:
  point, group, workload, status (ok | failed), error, exit_code, wall_s,
  host, slurm_job_id (empty outside Slurm), started_utc, rcbench_sha256,
  folder (the point's own folder);
  the label columns of named axes (AXIS, or AXIS_label for labelled values);
  every option the point passed to rcbench, named like the option with its
  unit from `rcbench <workload> --help` (--initial-sigma-xy -> initial_sigma_xy_m);
  every metric of the run (point_metrics.py), units in the names.
A failed point has its row, its error, and empty metrics.

Each name in the study's `tables` (a CSV every point writes, e.g.
sensitivity.csv) is concatenated over the points into <study>_<name>.csv,
each row prefixed with its point's id and parameters.

Run by the Snakefile as: merge.py OUT/study_config.json
"""
import json
import os
import sys

import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import option_units  # noqa: E402
import point_metrics  # noqa: E402
from study_config import load_snapshot  # noqa: E402

RECORD_COLUMNS = ["point", "group", "workload", "status", "error", "exit_code", "wall_s", "host", "slurm_job_id",
                  "started_utc", "rcbench_sha256", "folder"]


def option_value(v):
    if isinstance(v, dict):  # an unresolved function (the point never ran): show it as written
        (fn, arg), = v.items()
        return f"{fn}({arg})"
    if isinstance(v, bool):
        return int(v)
    return v


def point_row(study, pid, units):
    spec = study.points[pid]
    path = study.point_record(pid)
    with open(path) as f:
        record = json.load(f)
    row = {"point": pid, "group": spec["group"], "workload": spec["workload"], "status": record["status"],
           "error": record.get("error", ""), "exit_code": record.get("exit_code"),
           "wall_s": record.get("wall_s"), "host": record.get("host", ""),
           "slurm_job_id": record.get("slurm_job_id", ""),
           "started_utc": record.get("started_utc", ""), "rcbench_sha256": record.get("rcbench_sha256", ""),
           "folder": spec["folder"]}
    row.update(spec["labels"])
    options = record.get("resolved_options") or spec["options"]
    for name, value in options.items():
        row[units.column(spec["workload"], name)] = option_value(value)
    parameters = ["point", "group", "workload"] + list(row)[len(RECORD_COLUMNS):]
    if record["status"] == "ok":
        try:
            metrics = point_metrics.metrics(spec, record)
        except point_metrics.MetricsError as e:
            row["status"] = "failed"
            row["error"] = f"outputs unreadable: {e}"
            metrics = {}
        for k, v in metrics.items():
            if k in row:
                raise ValueError(f"{pid}: metric '{k}' collides with a parameter column")
            row[k] = v
    return row, parameters


def write_csv_atomic(frame, path):
    tmp = f"{path}.tmp-{os.getpid()}"
    frame.to_csv(tmp, index=False)
    os.replace(tmp, path)


def merge_study(study, out_csv):
    units = option_units.OptionUnits(study.rcbench)
    rows, parameters = zip(*[point_row(study, pid, units) for pid in study.order]) if study.order else ((), ())
    frame = pd.DataFrame(list(rows))
    ordered = [c for c in RECORD_COLUMNS if c in frame.columns]
    frame = frame[ordered + [c for c in frame.columns if c not in ordered]]
    write_csv_atomic(frame, out_csv)
    for table in study.tables:
        parts = []
        for row, params in zip(rows, parameters):
            path = os.path.join(row["folder"], table)
            if row["status"] != "ok" or not os.path.exists(path):
                continue
            part = pd.read_csv(path)
            for k in reversed(params):
                part.insert(0, k if k not in part.columns else f"point_{k}", row[k])
            parts.append(part)
        stem = os.path.splitext(os.path.basename(table))[0]
        if parts:
            write_csv_atomic(pd.concat(parts, ignore_index=True), os.path.join(study.out, f"{study.name}_{stem}.csv"))
    print(f"merged {len(rows)} points ({sum(r['status'] == 'ok' for r in rows)} ok) into {out_csv}", file=sys.stderr)
    return frame


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: merge.py OUT/study_config.json   (the Snakefile writes it)")
    study, _ = load_snapshot(sys.argv[1])
    merge_study(study, study.merged_csv())


if __name__ == "__main__":
    main()
