#!/usr/bin/env bash
# Pricing's end-to-end cost as a user sees it: whole `rcbench delibot`
# processes, priced (the default) and --no-pricing alternating, each round
# both workloads, one thread. Prints one line per run: workload, mode, wall
# (s), user + system CPU (s) and peak RSS (KB) from GNU time, then the
# medians' ratios. CPU time is the load-independent measure on a shared
# machine; wall time is what a user waits. The claim audit is off in both
# (--no-claim-audit): it prices nothing, and its host time in both runs
# would make pricing's share look smaller than it is.
# Usage: benchmarks/pricing_end_to_end.sh [rcbench] [shared data dir] [rounds]
set -euo pipefail
RCBENCH="$(realpath "${1:-build/rcbench}")"
DATA="$(realpath "${2:-../shared/data}")"
ROUNDS="${3:-3}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"

declare -A ARGS=(
  [demo]="delibot --threads 1 --no-claim-audit"
  [wean_180_beams]="delibot --threads 1 --no-claim-audit --map $DATA/wean/wean.dat --trace $DATA/wean/robotdata1.log --particles 2000 --beam-step 1 --max-records 100"
)
workloads=(demo)
[ -f "$DATA/wean/wean.dat" ] && workloads+=(wean_180_beams) || echo "no $DATA/wean: the Wean workload is skipped"

: > runs.txt
for round in $(seq "$ROUNDS"); do
  for w in "${workloads[@]}"; do
    for mode in priced unpriced; do
      flag=""; [ "$mode" = unpriced ] && flag="--no-pricing"
      # shellcheck disable=SC2086
      /usr/bin/time -f "%e %U %S %M" -o time.txt "$RCBENCH" ${ARGS[$w]} $flag >/dev/null 2>&1
      read -r wall user sys rss < time.txt
      cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')
      echo "$w $mode $wall $cpu $rss" | tee -a runs.txt
    done
  done
done

python3 - runs.txt <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    w, mode, wall, cpu, rss = line.split()
    runs.setdefault((w, mode), []).append((float(wall), float(cpu), int(rss)))
print("\n| workload | CPU priced / unpriced (s) | ratio | wall priced / unpriced (s) | ratio | peak RSS priced / unpriced (MB) | ratio |")
print("|---|---|---|---|---|---|---|")
for w in dict.fromkeys(k[0] for k in runs):
    p, u = runs[(w, "priced")], runs[(w, "unpriced")]
    med = lambda xs, i: statistics.median(x[i] for x in xs)
    cells = []
    for i, scale in ((1, 1), (0, 1), (2, 1024)):
        a, b = med(p, i) / scale, med(u, i) / scale
        cells += [f"{a:.2f} / {b:.2f}" if scale == 1 else f"{a:.0f} / {b:.0f}", f"{a / b:.2f}x"]
    print(f"| {w} | " + " | ".join(cells) + " |")
PY
