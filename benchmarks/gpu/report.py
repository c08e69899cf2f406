#!/usr/bin/python3
"""The GPU check's report (docs/gpu_check.md): the SIMT model beside a real GPU.

  report.py --model model.csv --measured measured.csv [--profile profile.csv]
            [--sact-model sact_model.csv --sact-measured sact_measured.csv
             [--sact-profile sact_profile.csv]]

model.csv comes from gpu_ray_cast_export (the model's predictions),
measured.csv from ray_cast_on_gpu and profile.csv from Nsight Compute
(benchmarks/gpu/run_on_gpu.sh). Prints Markdown tables to standard output:

  answers   FP64 and FP32 answers against the host's
  time      measured kernel time beside each model column, and the ratio
  ranking   which method is cheapest, by the GPU and by each model column
  counters  SIMT efficiency, node-fetch sectors, warp instructions and the
            SM clock, measured (ncu) beside the model (needs --profile)
  leaf      the ray kernels with the max-log and the exact beam leaf:
            what each adds to the traversal, measured and modelled, and
            the exact leaf's log densities against the host's
  SACT      the collision kernel's outcomes, time and counters the same way
            (gpu_sact_export, sact_on_gpu)

Every number is read from the files; nothing is fitted.
"""
import argparse
import csv
import sys
from collections import defaultdict

METHODS = ["march", "dda", "rm"]
ORDERS = ["random", "grid"]
PRECISIONS = ["fp64", "fp32"]
# Model columns: (preset, isa, heading).
MODEL_COLUMNS = [
    ("h100", "sass", "model, H100 preset, SASS counts"),
    ("h100", "ptx", "model, H100 preset, PTX counts"),
    ("default", "ptx", "model, default GPU (8 SMs, 1.365 GHz), PTX"),
]
KERNEL_NAME = {"rc_march": "march", "rc_dda": "dda", "rc_rm": "rm"}


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def key(row):
    return (row["method"], row["order"], row["precision"])


def leaf_of(row):
    return row.get("leaf", "none")


def read_launches(path):
    """{launch id: {"kernel": name, metric: float}} from ncu --csv."""
    with open(path, newline="") as f:
        lines = [line for line in f if line.startswith('"')]
    launches = defaultdict(dict)
    for row in csv.DictReader(lines):
        launches[int(row["ID"])]["kernel"] = row["Kernel Name"]
        launches[int(row["ID"])][row["Metric Name"]] = float(row["Metric Value"].replace(",", ""))
    return launches


def read_profile(path):
    """{(method, order, precision): {metric: float}} from ncu --csv; the
    second launch of each configuration (run_on_gpu.sh launches each twice:
    one warm-up, one timed)."""
    launches = read_launches(path)
    # Launch order is the harness's: method, order, precision, each launched
    # twice; then, with a leaf file, the launches with a leaf (not read here).
    configs = [(m, o, p) for m in METHODS for o in ORDERS for p in PRECISIONS]
    ids = sorted(launches)
    if len(ids) not in (2 * len(configs), 4 * len(configs)):
        sys.exit(f"report.py: {path}: {len(ids)} profiled launches, expected {2 * len(configs)} "
                 f"or, with the leaf, {4 * len(configs)}")
    profile = {}
    for i, config in enumerate(configs):
        launch = launches[ids[2 * i + 1]]
        name = launch["kernel"]
        if KERNEL_NAME.get(name.rsplit("_", 1)[0]) != config[0] or not name.endswith(config[2]):
            sys.exit(f"report.py: {path}: launch {ids[2 * i + 1]} is {name}, expected {config[0]} {config[2]}")
        profile[config] = launch
    return profile


def read_sact_profile(path, configs):
    """{(scene, repeat, precision): {metric: float}}: the second launch of
    each configuration, in sact_on_gpu's order (`configs`)."""
    launches = read_launches(path)
    ids = sorted(launches)
    if len(ids) != 2 * len(configs):
        sys.exit(f"report.py: {path}: {len(ids)} profiled launches, expected {2 * len(configs)}")
    profile = {}
    for i, config in enumerate(configs):
        launch = launches[ids[2 * i + 1]]
        if launch["kernel"] != "rc_sact_" + config[2]:
            sys.exit(f"report.py: {path}: launch {ids[2 * i + 1]} is {launch['kernel']}, expected rc_sact_{config[2]}")
        profile[config] = launch
    return profile


def sact_report(model_path, measured_path, profile_path):
    model = {(r["scene"], r["repeat"], r["preset"], r["precision"], r["isa"]): r for r in read_csv(model_path)}
    rows = read_csv(measured_path)
    configs = [(r["scene"], r["repeat"], r["precision"]) for r in rows]
    measured = dict(zip(configs, rows))
    for c in configs:
        for preset, isa, _ in MODEL_COLUMNS:
            if (c[0], c[1], preset, c[2], isa) not in model:
                sys.exit(f"report.py: {model_path}: no row for {c} under {preset}, {isa}")
    print(f"\n### SACT: outcomes and kernel time ({rows[0]['device']}; us, measured: median of "
          f"{rows[0]['timed_launches']} launches; model: without the launch)\n")
    print("| scene | OBBs | precision | outcomes / node counts differing from the host's, stack overflows | measured | " +
          " | ".join(f"{heading} (x measured)" for _, _, heading in MODEL_COLUMNS) + " |")
    print("|---|---|---|---|---|" + "---|" * len(MODEL_COLUMNS))
    ratios = defaultdict(list)
    for c in configs:
        r = measured[c]
        seconds = float(r["median_s"])
        cells = []
        for preset, isa, _ in MODEL_COLUMNS:
            predicted = float(model[(c[0], c[1], preset, c[2], isa)]["kernel_s"])
            ratios[(preset, isa)].append(predicted / seconds)
            cells.append(f"{us(predicted)} ({predicted / seconds:.2f}x)")
        print(f"| {c[0]} | {r['queries']} | {c[2]} | {r['outcome_mismatches']} / {r['node_mismatches']}, "
              f"{r['stack_overflows']} | {us(seconds)} | " + " | ".join(cells) + " |")
    print("| **range of model / measured** | | | | | " + " | ".join(
        f"{min(ratios[(p, i)]):.2f}-{max(ratios[(p, i)]):.2f}x" for p, i, _ in MODEL_COLUMNS) + " |")
    if not profile_path:
        return
    profile = read_sact_profile(profile_path, configs)
    print("\n### SACT: counters (Nsight Compute; model: H100 preset)\n")
    print("| scene | OBBs | precision | SIMT efficiency, measured / model | "
          "warp instructions, measured sm_90 SASS / model sm_75 SASS / model PTX (M) | registers per thread, sm_90 | "
          "warps active (% of the SM's 64) |")
    print("|---|---|---|---|---|---|---|")
    for c in configs:
        counters = profile[c]
        sass, ptx = model[(c[0], c[1], "h100", c[2], "sass")], model[(c[0], c[1], "h100", c[2], "ptx")]
        print(f"| {c[0]} | {measured[c]['queries']} | {c[2]} | "
              f"{counters['smsp__thread_inst_executed_per_inst_executed.ratio'] / 32:.3f} / "
              f"{float(sass['simt_efficiency']):.3f} | {counters['smsp__inst_executed.sum'] / 1e6:.2f} / "
              f"{int(sass['warp_instructions']) / 1e6:.2f} / {int(ptx['warp_instructions']) / 1e6:.2f} | "
              f"{counters['launch__registers_per_thread']:.0f} | "
              f"{counters['sm__warps_active.avg.pct_of_peak_sustained_active']:.1f} |")


def us(seconds):
    return f"{seconds * 1e6:.1f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--model", required=True, help="model.csv from gpu_ray_cast_export")
    parser.add_argument("--measured", required=True, help="measured.csv from ray_cast_on_gpu")
    parser.add_argument("--profile", help="profile.csv from ncu (run_on_gpu.sh)")
    parser.add_argument("--sact-model", help="sact_model.csv from gpu_sact_export")
    parser.add_argument("--sact-measured", help="sact_measured.csv from sact_on_gpu")
    parser.add_argument("--sact-profile", help="sact_profile.csv from ncu (run_on_gpu.sh)")
    args = parser.parse_args()
    if bool(args.sact_model) != bool(args.sact_measured):
        parser.error("--sact-model and --sact-measured go together")

    model_rows, measured_rows = read_csv(args.model), read_csv(args.measured)
    model = {(r["preset"], r["isa"]) + key(r): r for r in model_rows if leaf_of(r) == "none"}
    measured = {key(r): r for r in measured_rows if leaf_of(r) == "none"}
    configs = [(m, o, p) for m in METHODS for o in ORDERS for p in PRECISIONS]
    missing = [c for c in configs if c not in measured] + [
        (preset, isa) + c for preset, isa, _ in MODEL_COLUMNS for c in configs if (preset, isa) + c not in model]
    if missing:
        sys.exit(f"report.py: no row for {missing[0]}")
    device = measured[configs[0]]["device"]
    queries = int(measured[configs[0]]["queries"])
    map_name = model[("default", "ptx") + configs[0]]["map"]

    print(f"### Answers ({device}, {queries} rays, {map_name} map)\n")
    print("| method | order | precision | range differs from the host's | node count differs | largest range difference (m) |")
    print("|---|---|---|---|---|---|")
    for c in configs:
        r = measured[c]
        print(f"| {c[0]} | {c[1]} | {c[2]} | {r['range_mismatches']} | {r['node_mismatches']} | "
              f"{float(r['max_range_diff_m']):.3g} |")

    print(f"\n### Kernel time (us; measured: median of {measured[configs[0]]['timed_launches']} launches, "
          "CUDA events; model: without the launch)\n")
    print("| method | order | precision | measured | " +
          " | ".join(f"{heading} (x measured)" for _, _, heading in MODEL_COLUMNS) + " |")
    print("|---|---|---|---|" + "---|" * len(MODEL_COLUMNS))
    ratios = defaultdict(list)
    for c in configs:
        seconds = float(measured[c]["median_s"])
        cells = []
        for preset, isa, _ in MODEL_COLUMNS:
            predicted = float(model[(preset, isa) + c]["kernel_s"])
            ratios[(preset, isa)].append(predicted / seconds)
            cells.append(f"{us(predicted)} ({predicted / seconds:.2f}x)")
        print(f"| {c[0]} | {c[1]} | {c[2]} | {us(seconds)} | " + " | ".join(cells) + " |")
    print("| **range of model / measured** | | | | " + " | ".join(
        f"{min(ratios[(p, i)]):.2f}-{max(ratios[(p, i)]):.2f}x" for p, i, _ in MODEL_COLUMNS) + " |")

    print("\n### Which method is cheapest, and which dearest\n")
    print("| order | precision | measured | " + " | ".join(h for _, _, h in MODEL_COLUMNS) + " |")
    print("|---|---|---|" + "---|" * len(MODEL_COLUMNS))
    for o in ORDERS:
        for p in PRECISIONS:
            truth = sorted(METHODS, key=lambda m: float(measured[(m, o, p)]["median_s"]))
            cells = []
            for preset, isa, _ in MODEL_COLUMNS:
                ranked = sorted(METHODS, key=lambda m: float(model[(preset, isa, m, o, p)]["kernel_s"]))
                agrees = "same order" if ranked == truth else (
                    "same cheapest" if ranked[0] == truth[0] else "cheapest differs")
                cells.append(f"{' < '.join(ranked)} ({agrees})")
            print(f"| {o} | {p} | {' < '.join(truth)} | " + " | ".join(cells) + " |")

    if args.profile:
        ray_counters(read_profile(args.profile), model, configs, queries)
    if any(leaf_of(r) != "none" for r in measured_rows):
        leaf_report(model_rows, measured_rows)
    if args.sact_model:
        sact_report(args.sact_model, args.sact_measured, args.sact_profile)


def leaf_report(model_rows, measured_rows):
    """What the beam leaf adds to each ray kernel (random order), measured
    and modelled, and how the GPU's exact leaf compares with the host's."""
    model = {(r["preset"], r["isa"], r["method"], r["precision"], leaf_of(r)): r
             for r in model_rows if r["order"] == "random"}
    measured = {(r["method"], r["precision"], leaf_of(r)): r for r in measured_rows if r["order"] == "random"}
    columns = [(p, i, h) for p, i, h in MODEL_COLUMNS if p == "h100"]
    print("\n### The beam leaf (random order): kernel time with each leaf, and what it adds to the traversal\n")
    print("| method | precision | measured: none / max-log / exact (us) | measured: max-log, exact adds | " +
          " | ".join(f"{h}: max-log, exact adds" for _, _, h in columns) +
          " | exact leaf's log densities differing from the host's (largest difference) |")
    print("|---|---|---|---|" + "---|" * len(columns) + "---|")
    for m in METHODS:
        for p in PRECISIONS:
            if any((m, p, leaf) not in measured for leaf in ("none", "maxlog", "exact")):
                sys.exit(f"report.py: no measured leaf rows for {m} {p}")
            t = {leaf: float(measured[(m, p, leaf)]["median_s"]) for leaf in ("none", "maxlog", "exact")}
            cells = []
            for preset, isa, _ in columns:
                k = {leaf: float(model[(preset, isa, m, p, leaf)]["kernel_s"]) for leaf in ("none", "maxlog", "exact")}
                cells.append(f"{k['maxlog'] / k['none'] - 1:+.1%}, {k['exact'] / k['none'] - 1:+.1%}")
            exact = measured[(m, p, "exact")]
            print(f"| {m} | {p} | {us(t['none'])} / {us(t['maxlog'])} / {us(t['exact'])} | "
                  f"{t['maxlog'] / t['none'] - 1:+.1%}, {t['exact'] / t['none'] - 1:+.1%} | " + " | ".join(cells) +
                  f" | {exact['log_density_differs']} of {exact['queries']} "
                  f"({float(exact['max_log_density_diff']):.3g}) |")


def ray_counters(profile, model, configs, queries):
    print("\n### Counters (Nsight Compute, one launch each, caches flushed before it; "
          "model: H100 preset)\n")
    print("| method | order | precision | SIMT efficiency, measured / model | "
          "global load sectors, measured / model (node fetches + ray inputs) | "
          "warp instructions, measured sm_90 SASS / model sm_75 SASS / model PTX (M) | SM clock (GHz) |")
    print("|---|---|---|---|---|---|---|")
    for c in configs:
        counters = profile[c]
        sass, ptx = model[("h100", "sass") + c], model[("h100", "ptx") + c]
        efficiency = counters["smsp__thread_inst_executed_per_inst_executed.ratio"] / 32
        # Each warp loads its 32 rays' four inputs (origin, direction), one
        # scalar each, coalesced into 32-byte sectors; the model replays the
        # node fetches alone.
        scalar_bytes = 8 if c[2] == "fp64" else 4
        input_sectors = 4 * queries * scalar_bytes // 32
        modelled_sectors = int(sass["sector_requests"]) + input_sectors
        measured_sectors = counters["l1tex__t_sectors_pipe_lsu_mem_global_op_ld.sum"]
        print(f"| {c[0]} | {c[1]} | {c[2]} | {efficiency:.3f} / {float(sass['simt_efficiency']):.3f} | "
              f"{measured_sectors / 1e6:.3f}M / {modelled_sectors / 1e6:.3f}M "
              f"({modelled_sectors / measured_sectors:.3f}x) | "
              f"{counters['smsp__inst_executed.sum'] / 1e6:.1f} / {int(sass['warp_instructions']) / 1e6:.1f} / "
              f"{int(ptx['warp_instructions']) / 1e6:.1f} | "
              f"{counters['sm__cycles_elapsed.avg.per_second'] / 1e9:.3f} |")


if __name__ == "__main__":
    main()
