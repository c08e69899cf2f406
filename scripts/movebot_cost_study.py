#!/usr/bin/python3
"""MoveBot cost distribution: our RRTstar with each nearest-neighbour
structure against stock RRTstar + GNAT, on the same fixed seeds.

For every seed and every --nn choice, runs
  rcbench movebot --seed S --iterations N --nn NN --no-pricing --anytime ...
and reports, per structure, how many runs found an exact path and the
median / min / max final cost (rad, joint-space length). RRTstar's result
depends only on the seed and the neighbours it is given; an exact
nearest-neighbour structure returns the same neighbours as GNAT (up to ties),
so equal distributions are the expected outcome.
Writes <out>/movebot_cost_study.csv and prints a Markdown table.

Usage: scripts/movebot_cost_study.py [--rcbench build/rcbench] [--out out/movebot]
       [--seeds 10] [--iterations 2000] [--nn gnat,p-ray,p-sphere]
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys

from rcbench_files import atomic_output


def final_cost(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return float(rows[-1]["best_cost_rad"]) if rows and rows[-1]["best_cost_rad"] else None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rcbench", default="build/rcbench")
    parser.add_argument("--out", default="out/movebot")
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--iterations", type=int, default=2000)
    parser.add_argument("--nn", default="gnat,p-ray,p-sphere")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    results = []
    for nn in args.nn.split(","):
        for seed in range(1, args.seeds + 1):
            anytime = os.path.join(args.out, f"anytime_{nn}_{seed}.csv")
            run = subprocess.run([args.rcbench, "movebot", "--seed", str(seed), "--iterations", str(args.iterations),
                                  "--nn", nn, "--no-pricing", "--anytime", anytime],
                                 capture_output=True, text=True)
            if run.returncode not in (0, 3):
                sys.exit(f"rcbench movebot --nn {nn} --seed {seed} failed ({run.returncode}):\n{run.stderr}")
            cost = final_cost(anytime)
            results.append((nn, seed, run.returncode == 0, cost))
            print(f"{nn} seed {seed}: {'exact' if run.returncode == 0 else 'no exact path'}, cost {cost}", flush=True)
    with atomic_output(os.path.join(args.out, "movebot_cost_study.csv"), newline="") as f:
        w = csv.writer(f)
        w.writerow(["nn", "seed", "exact", "final_cost_rad"])
        for nn, seed, exact, cost in results:
            w.writerow([nn, seed, int(exact), "" if cost is None else cost])
    print("\n| nn | exact runs | median cost (rad) | min | max |\n|---|---|---|---|---|")
    for nn in args.nn.split(","):
        costs = [c for n, _, e, c in results if n == nn and e]
        runs = sum(1 for n, *_ in results if n == nn)
        if costs:
            print(f"| {nn} | {len(costs)}/{runs} | {statistics.median(costs):.3f} | {min(costs):.3f} | {max(costs):.3f} |")
        else:
            print(f"| {nn} | 0/{runs} | - | - | - |")


if __name__ == "__main__":
    main()
