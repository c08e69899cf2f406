#!/usr/bin/env bash
# Pricing's end-to-end cost as a user sees it: whole `rcbench delibot`
# processes, priced (the default) and --no-pricing alternating, each round
# every workload, on THREADS threads (default 1). Prints one line per run:
# workload, mode, wall (s), user + system CPU (s) and peak RSS (KB) from GNU
# time, then per workload the medians' ratios and the median and largest of
# the rounds' paired ratios (a round's priced run over its unpriced one,
# which ran beside it and so saw the same load), and the host's noise: the
# unpriced runs' largest CPU time over their smallest (identical work, so
# any spread is the host's; a single paired ratio strays from the median by
# about as much). The paired median comes with a distribution-free
# confidence interval, the order statistics (k-th smallest and k-th
# largest paired ratio) whose binomial coverage is at least 95% (at least
# six rounds; fewer give the widest interval and say its coverage): the
# goal is met with confidence when the interval's top is below it. CPU time is the
# load-independent measure on a shared machine; wall time is what a user
# waits. The claim audit is off in both (--no-claim-audit): it prices
# nothing, and its host time in both runs would make pricing's share look
# smaller than it is. The workloads: the demo; the demo with the beam model,
# whose first update casts 25 million rays (the costliest to price); Wean
# with every beam; CarriBot on RoWild's Intel query (its car footprint, 8
# headings, scales 1, 2 and 4, as scripts/carribot_vs_rowild.py poses it);
# MoveBot's default (RRT* on the LoCoBot obstacles). The last five need the
# shared data and are skipped without it. WORKLOADS (names as in the table,
# space-separated) runs a subset, for more rounds where an interval is wide.
# Within a round the priced run goes first in odd rounds and second in even
# ones, so that neither mode always follows the other.
# With THREADS > 1, the round trip of a cache line between the first two
# cores (benchmarks/core_to_core_latency, built beside rcbench) is measured
# before and after each pair, and the pairs are also summarised by where the
# host had put the cores: "near" when both round trips were under FAR_NS,
# "far" when both were at or over it (a pair that saw both is left out of
# that split). On a virtual machine the placement changes between runs, and
# a priced run's threads write over what the other has read: docs/pricing.md,
# "Where the host puts the two cores".
# Usage: [THREADS=n] [WORKLOADS="a b"] [FAR_NS=ns] benchmarks/pricing_end_to_end.sh [rcbench] [shared data dir] [rounds]
set -euo pipefail
RCBENCH="$(realpath "${1:-build/rcbench}")"
DATA="$(realpath "${2:-../shared/data}")"
ROUNDS="${3:-3}"
THREADS="${THREADS:-1}"
# ns, 1-10000: the round trip at and above which the cores count as far
# apart. Source: the project's 2-core EPYC measured 52-88 ns in one
# placement and 322-368 ns in the other; 200 lies between them.
FAR_NS="${FAR_NS:-200}"
[[ "$FAR_NS" =~ ^[0-9]+$ ]] && (( FAR_NS >= 1 && FAR_NS <= 10000 )) ||
  { echo "FAR_NS: '$FAR_NS' is not a whole number of ns in 1-10000" >&2; exit 2; }
PROBE="$(dirname "$RCBENCH")/benchmarks/core_to_core_latency"
probe() { if [ "$THREADS" -gt 1 ] && [ -x "$PROBE" ]; then "$PROBE" 2>/dev/null || echo -; else echo -; fi; }
# carribot and movebot take OpenMP's thread count (they have no --threads).
export OMP_THREAD_LIMIT="$THREADS"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"

declare -A ARGS=(
  [demo]="delibot --threads $THREADS --no-claim-audit"
  [beam_model]="delibot --threads $THREADS --no-claim-audit --sensor-model beam"
  [wean_180_beams]="delibot --threads $THREADS --no-claim-audit --map $DATA/wean/wean.dat --trace $DATA/wean/robotdata1.log --particles 2000 --beam-step 1 --max-records 100"
)
# RoWild's query: start, goal and the (5,2)-cell offset in scale-1 cells,
# the 4 x 10-cell car in metres at the scale's cell size.
intel_query() {
  local cell; cell=$(awk -v s="$1" 'BEGIN { print 1 / s }')
  echo "carribot --map $DATA/intel/Intel.map --map-scale $1 --start 227,33 --goal 59,217 --offset 5,2" \
    "--start-heading 0 --goal-heading 0 --footprint $(awk -v c="$cell" 'BEGIN { print 4 * c "x" 10 * c }')" \
    "--headings 8 --path path.txt"
}
ARGS[carribot_intel_1]="$(intel_query 1)"
ARGS[carribot_intel_2]="$(intel_query 2)"
ARGS[carribot_intel_4]="$(intel_query 4)"
ARGS[movebot]="movebot --obstacles $DATA/movebot/locobot_obs.txt"
workloads=(demo beam_model)
[ -f "$DATA/wean/wean.dat" ] && workloads+=(wean_180_beams) || echo "no $DATA/wean: the Wean workload is skipped"
[ -f "$DATA/intel/Intel.map" ] && workloads+=(carribot_intel_1 carribot_intel_2 carribot_intel_4) ||
  echo "no $DATA/intel: the CarriBot workloads are skipped"
[ -f "$DATA/movebot/locobot_obs.txt" ] && workloads+=(movebot) || echo "no $DATA/movebot: the MoveBot workload is skipped"
if [ -n "${WORKLOADS:-}" ]; then
  chosen=()
  for w in $WORKLOADS; do
    [ -n "${ARGS[$w]:-}" ] || { echo "WORKLOADS: no workload '$w' (known: ${!ARGS[*]})" >&2; exit 2; }
    for have in "${workloads[@]}"; do [ "$have" = "$w" ] && chosen+=("$w"); done
  done
  [ "${#chosen[@]}" -gt 0 ] || { echo "WORKLOADS: none of '$WORKLOADS' can run here" >&2; exit 2; }
  workloads=("${chosen[@]}")
fi

# The host first: pricing's ratio moved by several percent from one 2-core
# machine to another with the code unchanged (docs/pricing.md), so a table
# means little without it.
cpu=$(awk -F': ' '
  /^model name/ && !name { name = $2 } /^cpu family/ && !family { family = $2 }
  /^model[[:space:]]*:/ && !model { model = $2 } /^flags/ && / avx512f / { avx512 = "yes" }
  END { printf "%s (family %s, model %s), AVX-512 %s", name ? name : "unknown CPU", family ? family : "?",
        model ? model : "?", avx512 ? avx512 : "no" }' /proc/cpuinfo 2>/dev/null || echo "unknown CPU")
# nproc honours OMP_THREAD_LIMIT, set above: the cores without it.
echo "host: $cpu, $(env -u OMP_THREAD_LIMIT -u OMP_NUM_THREADS nproc) cores; threads $THREADS; rounds $ROUNDS"

: > runs.txt
for round in $(seq "$ROUNDS"); do
  for w in "${workloads[@]}"; do
    modes=(priced unpriced); (( round % 2 == 0 )) && modes=(unpriced priced)
    before=$(probe)
    for mode in "${modes[@]}"; do
      flag=""; [ "$mode" = unpriced ] && flag="--no-pricing"
      # shellcheck disable=SC2086
      /usr/bin/time -f "%e %U %S %M" -o time.txt "$RCBENCH" ${ARGS[$w]} $flag >/dev/null 2>&1
      read -r wall user sys rss < time.txt
      cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')
      echo "$w $mode $wall $cpu $rss" >> pair.txt
    done
    after=$(probe)
    while read -r line; do echo "$line $before $after" | tee -a runs.txt; done < pair.txt
    rm pair.txt
  done
done

python3 - runs.txt "$FAR_NS" <<'PY'
import math, statistics, sys

def median_interval(xs):
    """The k-th smallest and k-th largest of xs, the largest k whose coverage of the
    median, 1 - 2 P(Binomial(n, 1/2) < k), is at least 95%, and that coverage."""
    xs, n = sorted(xs), len(xs)
    coverage = lambda k: 1 - 2 * sum(math.comb(n, i) for i in range(k)) / 2**n
    k = 1
    while k + 1 <= (n + 1) // 2 and coverage(k + 1) >= 0.95:
        k += 1
    return xs[k - 1], xs[n - k], coverage(k)
runs, placement = {}, {}
far_ns = float(sys.argv[2])
for line in open(sys.argv[1]):
    w, mode, wall, cpu, rss, before, after = line.split()
    runs.setdefault((w, mode), []).append((float(wall), float(cpu), int(rss)))
    if mode == "priced":
        trips = [float(t) for t in (before, after) if t != "-"]
        where = None
        if len(trips) == 2:
            where = "near" if max(trips) < far_ns else "far" if min(trips) >= far_ns else None
        placement.setdefault(w, []).append(where)
print("\n| workload | CPU priced / unpriced (s) | ratio | paired: median, largest | paired median's interval (coverage) | wall priced / unpriced (s) | ratio | paired: median, largest | peak RSS priced / unpriced (MB) | ratio | unpriced CPU spread |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for w in dict.fromkeys(k[0] for k in runs):
    p, u = runs[(w, "priced")], runs[(w, "unpriced")]
    med = lambda xs, i: statistics.median(x[i] for x in xs)
    cells = []
    for i, scale in ((1, 1), (0, 1), (2, 1024)):
        a, b = med(p, i) / scale, med(u, i) / scale
        cells += [f"{a:.2f} / {b:.2f}" if scale == 1 else f"{a:.0f} / {b:.0f}", f"{a / b:.2f}x"]
        if scale == 1:
            paired = [x[i] / y[i] for x, y in zip(p, u)]
            cells.append(f"{statistics.median(paired):.2f}x, {max(paired):.2f}x")
            if i == 1:
                lo, hi, coverage = median_interval(paired)
                cells.append(f"{lo:.2f}-{hi:.2f}x ({100 * coverage:.0f}%)")
    cells.append(f"{max(x[1] for x in u) / min(x[1] for x in u):.2f}x")
    print(f"| {w} | " + " | ".join(cells) + " |")
if any(where for ws in placement.values() for where in ws):
    print(f"\nBy where the host had put the cores (round trip under {far_ns:.0f} ns: near; CPU time):")
    print("\n| workload | near: pairs, paired median (interval) | far: pairs, paired median (interval) |")
    print("|---|---|---|")
    for w in dict.fromkeys(k[0] for k in runs):
        p, u = runs[(w, "priced")], runs[(w, "unpriced")]
        cells = []
        for side in ("near", "far"):
            paired = [x[1] / y[1] for x, y, where in zip(p, u, placement[w]) if where == side]
            if not paired:
                cells.append("0")
                continue
            lo, hi, coverage = median_interval(paired)
            cells.append(f"{len(paired)}, {statistics.median(paired):.2f}x ({lo:.2f}-{hi:.2f}x, {100 * coverage:.0f}%)")
        print(f"| {w} | " + " | ".join(cells) + " |")
PY
