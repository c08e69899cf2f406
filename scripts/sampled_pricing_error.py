#!/usr/bin/python3
"""How far sampled pricing is from exact replay, update by update.

Runs `rcbench delibot` (the demo unless extra arguments say otherwise) with
every SM replayed (--replay-sms 0), then with each sample asked for, and
compares each priced update's cycles on TTA+ and RoboCore against the exact
run's: the median signed error, the 95th percentile and the worst absolute
error, the updates whose cheapest backend differs, and RoboCore's total.
Prints a Markdown table (docs/pricing.md, "Sampled SMs and blocks").

Usage: scripts/sampled_pricing_error.py [--rcbench build/rcbench] [--strides 1 2] [-- delibot args...]
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile

BACKENDS = ["cycles_simt", "cycles_ttaplus", "cycles_ttaplus_p", "cycles_ttaplus_cr", "cycles_robocore"]
COMPARED = ["cycles_ttaplus", "cycles_robocore"]


def run(rcbench, workdir, name, replay_args, extra):
    timeline = os.path.join(workdir, name + ".csv")
    subprocess.run([rcbench, "delibot", "--quiet", "--timeline", timeline] + replay_args + extra,
                   cwd=workdir, check=True, stdout=subprocess.DEVNULL)
    with open(timeline) as f:
        return [r for r in csv.DictReader(f) if float(r["cycles_ttaplus"] or 0) > 0]


def compare(exact, sampled):
    """The row of the table for one sample's priced updates against exact's."""
    if len(exact) != len(sampled):
        sys.exit("the runs priced different updates: %d against %d" % (len(exact), len(sampled)))
    errors, differs, total_exact, total_sampled = [], 0, 0.0, 0.0
    for a, b in zip(exact, sampled):
        ca = [float(a[c]) for c in BACKENDS]
        cb = [float(b[c]) for c in BACKENDS]
        errors += [(float(b[c]) - float(a[c])) / float(a[c]) for c in COMPARED]
        differs += ca.index(min(ca)) != cb.index(min(cb))
        total_exact += float(a["cycles_robocore"])
        total_sampled += float(b["cycles_robocore"])
    magnitudes = sorted(abs(e) for e in errors)
    return [f"{100 * statistics.median(errors):+.2f}%", f"{100 * magnitudes[int(0.95 * len(magnitudes))]:.2f}%",
            f"{100 * magnitudes[-1]:.2f}%", f"{differs} of {len(exact)}",
            f"{100 * (total_sampled - total_exact) / total_exact:+.2f}%"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rcbench", default="build/rcbench")
    parser.add_argument("--strides", type=int, nargs="+", default=[1, 2], help="--replay-block-stride values")
    parser.add_argument("extra", nargs="*", help="further rcbench delibot arguments (after --)")
    args = parser.parse_args()
    rcbench = os.path.abspath(args.rcbench)
    with tempfile.TemporaryDirectory() as workdir:
        exact = run(rcbench, workdir, "exact", ["--replay-sms", "0"], args.extra)
        print("| sample | median error per update | 95th percentile | worst | updates whose cheapest backend "
              "differs | RoboCore's total |")
        print("|---|---|---|---|---|---|")
        for stride in args.strides:
            sampled = run(rcbench, workdir, f"stride{stride}",
                          ["--replay-sms", "1", "--replay-block-stride", str(stride)], args.extra)
            label = "1 SM, every block" if stride == 1 else f"1 SM, 1 block in {stride}"
            print(f"| {label} | " + " | ".join(compare(exact, sampled)) + " |")


if __name__ == "__main__":
    main()
