"""The metrics of one finished point, read from the files its run wrote;
one flat dict per point, units in the names (the merged CSV's columns).

  delibot   its --summary JSON, flattened: section.key (totals.wall_per_update_s,
            accuracy.median_err_xy_m, config.particles: the effective settings,
            defaults included, ...); top-level scalars as summary.KEY;
  movebot   result.exact_path (exit code 0), the last anytime row
            (anytime.best_cost_rad, anytime.time_s, anytime.iterations), the
            first solution's time, and the timeline's sums of queries,
            self-collision tests and refusals, and cycles (timeline.*);
  carribot  per-query timeline aggregated: timeline.queries, timeline.found,
            sums over the queries of lengths, expansions and cycles, and the
            final cum_cycles_policy / _oracle;
  collide   its timeline (section,key,value) as section.key.
Only `rcbench delibot` writes a summary JSON; for the others the numbers are
aggregated here from their CSVs, each with the rule stated above.
"""
import csv
import json
import math
import os

# Metrics the report's overview table shows when present.
KEY_METRICS = [
    "totals.wall_per_update_s", "accuracy.median_err_xy_m", "accuracy.p95_err_xy_m",
    "accuracy.convergence_iteration", "accuracy.converged_at_end", "pricing.policy_total_cycles",
    "pricing.oracle_total_cycles", "result.exact_path", "anytime.best_cost_rad", "anytime.first_solution_s",
    "timeline.queries", "timeline.found", "timeline.path_length_m", "timeline.expanded", "summary.queries",
    "summary.collisions",
    "summary.nodes_per_query_mean",
]


class MetricsError(Exception):
    """An output of a finished run is missing or malformed; names the file."""


def flatten(obj, prefix=""):
    out = {}
    for k, v in obj.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten(v, name + "."))
        elif isinstance(v, list):
            if all(not isinstance(x, (dict, list)) for x in v):
                out[name] = ";".join(str(x) for x in v)
            else:
                out[name] = json.dumps(v, sort_keys=True)
        elif isinstance(v, bool):
            out[name] = int(v)
        else:
            out[name] = v
    return out


def read_csv_rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise MetricsError(f"{path}: {e.strerror}") from None


def number(path, row_no, column, text):
    if text is None or text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise MetricsError(f"{path}: row {row_no}: column '{column}': '{text}' is not a number") from None


def delibot(spec, record):
    path = spec["outputs"]["summary"]
    try:
        with open(path) as f:
            summary = json.load(f)
    except OSError as e:
        raise MetricsError(f"{path}: {e.strerror}") from None
    except ValueError as e:
        raise MetricsError(f"{path}: not JSON ({e})") from None
    # Sections keep their names (totals.wall_per_update_s); top-level scalars
    # (workload, engine) would collide with the parameter columns: summary.engine.
    return {(k if "." in k else f"summary.{k}"): v for k, v in flatten(summary).items()}


def movebot(spec, record):
    out = {"result.exact_path": int(record.get("exit_code") == 0)}
    path = spec["outputs"]["anytime"]
    rows = read_csv_rows(path)
    if rows:
        last = rows[-1]
        out["anytime.time_s"] = number(path, len(rows), "time_s", last["time_s"])
        out["anytime.iterations"] = number(path, len(rows), "iterations", last["iterations"])
        out["anytime.best_cost_rad"] = number(path, len(rows), "best_cost_rad", last["best_cost_rad"])
        first = next((r for r in rows if r["best_cost_rad"] != ""), None)
        out["anytime.first_solution_s"] = number(path, 0, "time_s", first["time_s"]) if first else math.nan
    timeline = spec["outputs"]["timeline"]
    rows = read_csv_rows(timeline)
    if rows:
        for column in rows[0]:
            if column in ("collision_queries", "nn_queries", "collision_configurations", "self_collision_tests",
                          "self_collisions") or \
                    column.startswith("cycles_") or column == "energy_j":
                out[f"timeline.{column}"] = sum(number(timeline, i + 1, column, r[column])
                                                for i, r in enumerate(rows) if r[column] != "")
        out["timeline.rows"] = len(rows)
    return out


def carribot(spec, record):
    path = spec["outputs"]["timeline"]
    rows = read_csv_rows(path)
    queries = [r for r in rows if r["status"] != "setup"]
    out = {"timeline.queries": len(queries), "timeline.found": sum(r["status"] == "found" for r in queries)}
    sums = ["path_length_cells", "path_length_m", "optimal_length_cells", "turns", "expanded", "collision_queries",
            "kernel_launches", "kernel_queries", "wall_s", "energy_j"]
    for column in sums + [c for c in (rows[0] if rows else {}) if c.startswith("cycles_")]:
        if rows and column in rows[0]:
            values = [number(path, i + 1, column, r[column]) for i, r in enumerate(rows)]
            out[f"timeline.{column}"] = sum(v for v in values if not math.isnan(v))
    for column in ("cum_cycles_policy", "cum_cycles_oracle"):
        if rows and column in rows[0]:
            out[f"timeline.{column}"] = number(path, len(rows), column, rows[-1][column])
    return out


def collide(spec, record):
    path = spec["outputs"]["timeline"]
    out = {}
    for i, r in enumerate(read_csv_rows(path)):
        name = f"{r['section']}.{r['key']}"
        try:
            out[name] = float(r["value"])
        except ValueError:
            out[name] = r["value"]
    return out


READERS = {"delibot": delibot, "movebot": movebot, "carribot": carribot, "collide": collide}


def metrics(spec, record):
    """The metrics of a point whose run succeeded; {} for a workload without a reader."""
    reader = READERS.get(spec["workload"])
    if reader is None:
        return {}
    for option, path in spec["outputs"].items():
        if option in ("summary", "timeline", "anytime") and not os.path.exists(path):
            raise MetricsError(f"{path}: not written by the run (--{option})")
    return reader(spec, record)
