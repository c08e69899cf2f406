#!/usr/bin/python3
"""Replays DeliBot's ground-truth-free convergence claim on existing
timelines under two gates, and grades each claim against the truth
(issue #25; docs/defaults.md, "A claim gate derived from the sensor model").

The claim needs SUSTAIN consecutive sensor updates with mode weight >= 0.8
and no rival hypothesis alive (hypotheses_alive <= 1), and a scan-consistency
test over them:
  old   every update's consistency >= 0.5 (DelibotSettings'
        converged_consistency; what the summary computes,
        workloads/delibot/delibot_summary.cc)
  model the window's mean consistency >= T, where T is the lower
        ALPHA-quantile (normal approximation to the binomial over SUSTAIN x
        BEAMS beams) of the fraction of beams within K sigma_hit that the beam
        model's own mixture expects at the true pose; the expectation is its
        lower bound over the expected range z* in [0, max_range]
        (ModelWithinFraction)
  fixed the window's mean consistency >= a given value (--fixed-threshold),
        for a rule fixed on tuning data.
The claim gate does not feed back into the filter (the summary computes it
from the timeline's rows), so a timeline run once grades every gate.

A claim holds when at least 95 % of the records from it on are within 1 m of
the truth (scripts/accuracy_study.py's rule). Prints one line per timeline and
a table per set: claims made / held / wrong / never, the false-claim rate
with its one-sided 95 % Clopper-Pearson upper bound, and, against the old
gate, the correct claims the other gate loses or delays.

Usage: scripts/claim_gate_offline.py [--set NAME=GLOB ...] [--fixed-threshold X]
       [beam-model options (z_max drops out): --z-hit 0.5 --z-short 0.05 --z-rand 0.5
        --sigma-hit 0.2 --lambda-short 0.1 --max-range 10 --consistency-sigmas 3
        --beams 180 --sustain 10 --alpha 0.01]
Standard library only.
"""
import argparse
import csv
import glob
import math
import statistics
import sys

CLAIM_RADIUS_M = 1.0
CLAIM_FRACTION = 0.95
MODE_WEIGHT = 0.8
OLD_CONSISTENCY = 0.5


def normal_quantile(p):
    """Inverse standard normal CDF by bisection on math.erf (p in (0, 1))."""
    lo, hi = -10.0, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if 0.5 * (1.0 + math.erf(mid / math.sqrt(2.0))) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def model_within_fraction_at(a, z_star):
    """P(|z - z*| <= k sigma_hit | z < max_range) under the beam mixture
    (Probabilistic Robotics 6.3: hit normalized on [0, max_range], short
    truncated to [0, z*], rand uniform on [0, max_range); max readings are
    left out of the consistency, so z_max drops out of the denominator."""
    tol = a.consistency_sigmas * a.sigma_hit
    lo, hi = max(0.0, z_star - tol), min(a.max_range, z_star + tol)
    cdf = lambda x: 0.5 * (1.0 + math.erf((x - z_star) / (a.sigma_hit * math.sqrt(2.0))))
    hit = (cdf(hi) - cdf(lo)) / (cdf(a.max_range) - cdf(0.0))
    lam = a.lambda_short
    short = 0.0
    if z_star > 0.0:
        short = (math.exp(-lam * lo) - math.exp(-lam * z_star)) / (1.0 - math.exp(-lam * z_star))
    rand = (hi - lo) / a.max_range
    return (a.z_hit * hit + a.z_short * short + a.z_rand * rand) / (a.z_hit + a.z_short + a.z_rand)


def model_within_fraction(a):
    """The lower bound over z* in (0, max_range] (1000 steps): whatever the
    ranges the map predicts, the model expects at least this fraction."""
    return min(model_within_fraction_at(a, a.max_range * i / 1000.0) for i in range(1, 1001))


def model_threshold(a):
    p = model_within_fraction(a)
    n = a.sustain * a.beams
    return p - normal_quantile(1.0 - a.alpha) * math.sqrt(p * (1.0 - p) / n), p


def clopper_pearson_upper(x, n, level=0.95):
    """One-sided upper bound: the p with P(X <= x | n, p) = 1 - level."""
    if n == 0:
        return float("nan")
    if x >= n:
        return 1.0
    cdf = lambda p: sum(math.comb(n, i) * p**i * (1 - p) ** (n - i) for i in range(x + 1))
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if cdf(mid) > 1.0 - level:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def read_rows(path):
    with open(path, newline="") as f:
        return [
            {
                "iteration": int(r["iteration"]),
                "updated": r["sensor_updated"] == "1",
                "mode_weight": float(r["mode_weight"]),
                "consistency": float(r["consistency"]),
                "alive": int(r["hypotheses_alive"]),
                "err": float(r["err_xy_m"]),
            }
            for r in csv.DictReader(f)
        ]


def first_claim(rows, sustain, mean_threshold=None):
    """The first record of `sustain` consecutive sensor updates that pass
    (old gate: each update's consistency >= 0.5; else the window's mean
    consistency >= mean_threshold), or -1."""
    updates = [r for r in rows if r["updated"]]
    run = []
    for r in updates:
        ok = r["mode_weight"] >= MODE_WEIGHT and r["alive"] <= 1
        if mean_threshold is None:
            ok = ok and r["consistency"] >= OLD_CONSISTENCY
        if not ok:
            run = []
            continue
        run.append(r)
        if len(run) >= sustain:
            window = run[-sustain:]
            if mean_threshold is None or statistics.fmean(w["consistency"] for w in window) >= mean_threshold:
                return window[0]["iteration"]
    return -1


def held(rows, claim):
    after = [r["err"] for r in rows if r["iteration"] >= claim]
    return bool(after) and sum(e < CLAIM_RADIUS_M for e in after) >= CLAIM_FRACTION * len(after)


def grade(claims):
    made = [c for c in claims if c[0] >= 0]
    wrong = sum(1 for c in made if not c[1])
    return len(made), len(made) - wrong, wrong, len(claims) - len(made)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--set", action="append", required=True, help="NAME=GLOB of timelines with ground truth")
    ap.add_argument("--fixed-threshold", type=float, help="also grade a window-mean gate at this value")
    for name, default in (("z-hit", 0.5), ("z-short", 0.05), ("z-rand", 0.5), ("sigma-hit", 0.2),
                          ("lambda-short", 0.1), ("max-range", 10.0), ("consistency-sigmas", 3.0), ("alpha", 0.01)):
        ap.add_argument("--" + name, type=float, default=default)
    ap.add_argument("--beams", type=int, default=180, help="beams per scan (the CMU SICK: 180)")
    ap.add_argument("--sustain", type=int, default=10, help="kSustainRecords")
    a = ap.parse_args()
    threshold, p = model_threshold(a)
    print(f"model gate: expected within-fraction at the true pose >= {p:.4f}; threshold (alpha {a.alpha}, "
          f"{a.sustain} x {a.beams} beams) {threshold:.4f}")
    gates = [("old", None), ("model", threshold)]
    if a.fixed_threshold is not None:
        gates.append(("fixed", a.fixed_threshold))
    for spec in a.set:
        name, pattern = spec.split("=", 1)
        paths = sorted(glob.glob(pattern))
        if not paths:
            sys.exit(f"claim_gate_offline: no timeline matches {pattern}")
        per_gate = {g: [] for g, _ in gates}
        print(f"\n{name}: {len(paths)} timelines")
        for path in paths:
            rows = read_rows(path)
            line = [path.rsplit("/", 1)[-1]]
            for g, t in gates:
                c = first_claim(rows, a.sustain, t)
                h = c >= 0 and held(rows, c)
                per_gate[g].append((c, h))
                line.append(f"{g}={c}{'' if c < 0 else (' held' if h else ' WRONG')}")
            print("  " + ", ".join(line))
        print("| gate | claims made / held / wrong / never | false-claim rate (95 % upper) | correct claims lost / delayed (median delay, records) |")
        print("|---|---|---|---|")
        for g, _ in gates:
            made, ok, wrong, never = grade(per_gate[g])
            rate = f"{wrong}/{made} = {100.0 * wrong / made:.1f} %" if made else "0/0"
            upper = clopper_pearson_upper(wrong, made)
            lost = delayed = 0
            delays = []
            for (c0, h0), (c1, _) in zip(per_gate["old"], per_gate[g]):
                if c0 >= 0 and h0:
                    if c1 < 0:
                        lost += 1
                    elif c1 > c0:
                        delayed += 1
                        delays.append(c1 - c0)
            med = statistics.median(delays) if delays else 0
            print(f"| {g} | {made} / {ok} / {wrong} / {never} | {rate} ({100.0 * upper:.0f} %) | {lost} / {delayed} ({med}) |")


if __name__ == "__main__":
    main()
