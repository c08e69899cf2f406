#!/usr/bin/python3
"""How much evidence a hypothesis loses to sampling when it holds few particles.

The hypothesis floor (`rcbench delibot --hypothesis-floor N`) keeps a rival
hypothesis alive with at least N particles and compares hypotheses by their
posterior mass, i.e. by the running sum of each one's log scan likelihoods.
A hypothesis held by few particles tracks the robot less finely than one
held by many, so its per-update scan likelihood, and with it its mass, is
biased low: a true hypothesis held at the floor trails a well-sampled wrong
one by this sampling loss on top of whatever the scans really say. This
script measures the loss, without any reference or real log: it simulates
traces (`rcbench simulate`, default noise) on the generated office map and,
when ../shared/data is present, on Wean Hall, then tracks each one from its
true first pose (recovery off, so no particle leaves the hypothesis) with
each particle count, and sums the timeline's `log_mean_likelihood_nats`
(the log marginal likelihood of the scans given the start; see
scripts/hypothesis_evidence.py). The loss of a count is its shortfall
against the largest count, per sensor update, averaged over the seeds.

Read the loss against the hypothesis window: a true hypothesis held at the
floor for U updates falls U x loss nats behind a well-sampled look-alike
that the scans do not favour at all; at 20 particles on simulated Wean that
is 0.5 nats per update, about the real lead of robotdata2's look-alike
track (README, "How many particles a hypothesis needs").

Writes <out>/evidence_vs_particles.csv (map, seed, particles,
log_evidence_nats, sensor_updates) and <out>/evidence_vs_particles.md (per
map and count: mean log evidence and the loss per update), and prints the
table.

Usage: scripts/evidence_vs_particles.py [--rcbench build/rcbench]
       [--data-dir ../shared/data] [--maps office,wean] [--seeds 3]
       [--records 1000] [--counts 20,50,100,200,300,500,1000,2000,5000]
       [--out out/evidence_vs_particles] [-- EXTRA RCBENCH ARGS]
Every run uses --quiet --no-pricing --threads 1 --recovery-alpha-slow 0
--sensor-model likelihood (the real-log recipe's model) plus the extra
arguments; two runs at a time (--jobs).
"""
import argparse
import concurrent.futures
import csv
import os
import statistics
import subprocess
import sys

from rcbench_files import SHARED_DATA, InputError, atomic_output, read_cumulative_evidence, read_poses, split_extra_args


def fail(message):
    sys.exit(f"evidence_vs_particles: {message}")


def run(cmd):
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        fail(f"exit {result.returncode}: {' '.join(cmd)}\n{result.stderr.strip()}")


def log_evidence(timeline_path):
    """(log marginal likelihood of the run's scans (nats), number of sensor updates)."""
    try:
        records = read_cumulative_evidence(timeline_path)
    except InputError as e:
        fail(str(e))
    updates = sum(updated for _, updated, _, _ in records)
    if updates == 0:
        fail(f"{timeline_path}: no sensor update")
    return records[-1][0], updates


def make_traces(args):
    """[(map name, seed, map path, trace path, ground-truth path)], simulated here."""
    traces = []
    maps = [m for m in args.maps.split(",") if m]
    office_map = os.path.join(args.out, "office.yaml")
    if "office" in maps:
        run([args.rcbench, "make-map", "--output", office_map])
    for name in maps:
        if name == "office":
            map_path = office_map
        elif name == "wean":
            map_path = os.path.join(args.data_dir, "wean", "wean.dat")
            if not os.path.exists(map_path):
                print(f"evidence_vs_particles: skipping Wean: {map_path} is absent", file=sys.stderr)
                continue
        else:
            fail(f"--maps: unknown map '{name}' (office or wean)")
        for seed in range(1, args.seeds + 1):
            trace = os.path.join(args.out, f"{name}_seed{seed}.log")
            run([args.rcbench, "simulate", "--map", map_path, "--seed", str(seed), "--records",
                 str(args.records), "--output", trace])
            traces.append((name, seed, map_path, trace, trace[:-len(".log")] + ".gt"))
    if not traces:
        fail("no trace to study")
    return traces


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rcbench", default="build/rcbench")
    ap.add_argument("--data-dir", default=SHARED_DATA)
    ap.add_argument("--maps", default="office,wean", help="comma-separated: office, wean")
    ap.add_argument("--seeds", type=int, default=3, help="simulated traces per map, seeds 1..S (count)")
    ap.add_argument("--records", type=int, default=1000, help="laser records per trace (count)")
    ap.add_argument("--counts", default="20,50,100,200,300,500,1000,2000,5000", help="particle counts")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (count)")
    ap.add_argument("--out", default="out/evidence_vs_particles")
    own, extra = split_extra_args(sys.argv[1:])
    args = ap.parse_args(own)
    try:
        counts = sorted({int(c) for c in args.counts.split(",") if c})
    except ValueError:
        fail(f"--counts: not a list of integers: {args.counts}")
    if len(counts) < 2 or counts[0] < 1:
        fail("--counts: need at least two positive counts")
    if args.seeds < 1 or args.records < 1:
        fail("--seeds and --records must be positive")
    os.makedirs(os.path.join(args.out, "runs"), exist_ok=True)
    traces = make_traces(args)

    jobs = []
    for name, seed, map_path, trace, truth in traces:
        try:
            x, y, theta = read_poses(truth)[0][1:]
        except InputError as e:
            fail(str(e))
        for n in counts:
            # The filter's seed is the trace's, so the seeds average over
            # both the scans and the filter's own noise.
            timeline = os.path.join(args.out, "runs", f"{name}_seed{seed}_n{n}.csv")
            cmd = [args.rcbench, "delibot", "--map", map_path, "--trace", trace, "--particles", str(n),
                   "--seed", str(seed), "--initial-pose", repr(x), repr(y), repr(theta),
                   "--sensor-model", "likelihood", "--recovery-alpha-slow", "0",
                   "--quiet", "--no-pricing", "--threads", "1", "--timeline", timeline] + extra
            jobs.append((name, seed, n, cmd, timeline))
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        list(pool.map(lambda job: run(job[3]), jobs))

    evidence = {}  # (map, seed, particles) -> (log evidence (nats), sensor updates)
    for name, seed, n, _, timeline in jobs:
        evidence[(name, seed, n)] = log_evidence(timeline)
    with atomic_output(os.path.join(args.out, "evidence_vs_particles.csv"), newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["map", "seed", "particles", "log_evidence_nats", "sensor_updates"])
        for (name, seed, n), (total, updates) in evidence.items():
            writer.writerow([name, seed, n, f"{total:.3f}", updates])

    # Loss per update of each count against the largest, per map (mean over seeds).
    maps = sorted({name for name, _, _, _, _ in traces}, key=[t[0] for t in traces].index)
    seeds_of = {m: [seed for name, seed, _, _, _ in traces if name == m] for m in maps}
    largest = counts[-1]
    lines = [f"Log evidence lost to sampling, per sensor update, against {largest} particles "
             f"(tracking from the true start, {args.seeds} simulated traces per map, {args.records} records)",
             "", "| particles | " + " | ".join(f"{m}: mean log evidence (nats) | {m}: loss (nats/update)"
                                             for m in maps) + " |",
             "|---:|" + "---:|---:|" * len(maps)]
    for n in counts:
        cells = []
        for m in maps:
            runs = [evidence[(m, seed, n)] for seed in seeds_of[m]]
            loss = statistics.mean((evidence[(m, seed, largest)][0] - total) / updates
                                   for seed, (total, updates) in zip(seeds_of[m], runs))
            cells.append(f"{statistics.mean(total for total, _ in runs):.0f} | {loss:.3f}")
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    with atomic_output(os.path.join(args.out, "evidence_vs_particles.md")) as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"wrote {args.out}/evidence_vs_particles.csv, evidence_vs_particles.md")


if __name__ == "__main__":
    main()
