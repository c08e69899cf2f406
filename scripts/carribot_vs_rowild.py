#!/usr/bin/env python3
"""CarriBot against RoWild's CarriBot on RoWild's own Intel query, end to end.

For each map scale, runs RoWild's carribot.out and `rcbench carribot` (with
pricing, and with --no-pricing) alternately, --repeats times each, under
/usr/bin/time -v, and prints the median wall time (s) and median peak
resident memory (MB) of each side, and the medians of the paired ratios
RoWild / ours of wall time and of CPU time (user + system; above 1 means ours
is faster). On a loaded machine the CPU ratio is the steadier one.

The query is RoWild's (cmu-roboarch/rowild, e2e/CarriBot/harness.cpp):
Intel.map split into s x s cells, start (227, 33) and goal (59, 217) times s,
a 10 x 4-cell car, 8 headings, heading 0 at start and goal (RoWild's goal
test compares the whole state). RoWild's (x, y) is the car's corner; ours is
the footprint's centre, hence --offset 5,2 (cells of the scaled map) at
every scale. The car is 4 x 10 cells of the scaled map: a MovingAI map has
1 m cells, so at scale s a cell is 1/s m and --footprint is (4/s)x(10/s) m.

RoWild is not part of rcbench: build it from its own sources (outside this
repository) and pass its binary with --rowild. Without --rowild only our
side runs.

  scripts/carribot_vs_rowild.py --rowild /tmp/rowild/e2e/CarriBot/carribot.out --scales 1 2 4 --repeats 5
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd):
    """(wall s, peak RSS MB, user + system CPU s) of one run of cmd under /usr/bin/time -v; raises on failure."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as log:
        proc = subprocess.run(["/usr/bin/time", "-v", "-o", log.name] + cmd, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
        text = log.read()
    if proc.returncode != 0:
        raise RuntimeError("%s exited with %d:\n%s%s" % (" ".join(cmd), proc.returncode, proc.stdout[-2000:],
                                                           proc.stderr[-2000:]))
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([\d.]+)", text)
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
    user = re.search(r"User time \(seconds\): ([\d.]+)", text)
    system = re.search(r"System time \(seconds\): ([\d.]+)", text)
    seconds = int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))
    return seconds, int(rss.group(1)) / 1024.0, float(user.group(1)) + float(system.group(1))


def rowild_cmd(binary, intel_map, scale, out):
    return [binary, "--map=" + intel_map, "--scale-map=%d" % scale, "--output=" + out]


def ours_cmd(rcbench, intel_map, scale, pricing, out):
    cell = 1.0 / scale  # m; MovingAI maps have 1 m cells
    cmd = [rcbench, "carribot", "--quiet", "--map", intel_map, "--map-scale", str(scale), "--start", "227,33",
           "--goal", "59,217", "--offset", "5,2", "--start-heading", "0", "--goal-heading", "0", "--footprint", "%.17gx%.17g" % (4 * cell, 10 * cell),
           "--headings", "8", "--path", out]
    return cmd + ([] if pricing else ["--no-pricing"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rowild", help="RoWild's carribot.out (built outside the repository); default: ours only")
    parser.add_argument("--rcbench", default=os.path.join(ROOT, "build", "rcbench"), help="the rcbench binary")
    parser.add_argument("--map", default=os.path.join(ROOT, "..", "shared", "data", "intel", "Intel.map"),
                        help="Intel.map (RoWild's, identical to ../shared/data/intel/Intel.map)")
    parser.add_argument("--scales", type=int, nargs="+", default=[1, 2, 4], help="map scales (count)")
    parser.add_argument("--repeats", type=int, default=5, help="runs of each side per scale (count)")
    parser.add_argument("--threads", type=int, default=0,
                        help="OMP_THREAD_LIMIT for both sides (count; RoWild's search asks for 2 threads in its "
                             "source, which only this limit caps); 0: each side's default")
    args = parser.parse_args()
    if args.threads > 0:
        os.environ["OMP_THREAD_LIMIT"] = str(args.threads)
    if not os.path.exists(args.map):
        sys.exit("carribot_vs_rowild.py: %s: no such map" % args.map)

    sides = ["ours_priced", "ours_no_pricing"] + (["rowild"] if args.rowild else [])
    print("scale,side,runs,median_wall_s,median_cpu_s,median_peak_rss_mb,median_wall_ratio_rowild_over_ours,"
          "median_cpu_ratio_rowild_over_ours")
    with tempfile.TemporaryDirectory() as tmp:
        for scale in args.scales:
            runs = {side: [] for side in sides}
            for r in range(args.repeats):
                # Alternate the order each round so neither side always runs first.
                order = sides if r % 2 == 0 else list(reversed(sides))
                for side in order:
                    out = os.path.join(tmp, "%s_%d_%d.txt" % (side, scale, r))
                    if side == "rowild":
                        cmd = rowild_cmd(args.rowild, args.map, scale, out)
                    else:
                        cmd = ours_cmd(args.rcbench, args.map, scale, side == "ours_priced", out)
                    runs[side].append(timed(cmd))
            for side in sides:
                walls = [w for w, _, _ in runs[side]]
                rss = [m for _, m, _ in runs[side]]
                cpu = [c for _, _, c in runs[side]]
                ratio, cpu_ratio = "", ""
                if "rowild" in runs and side != "rowild":
                    ratio = "%.2f" % statistics.median(
                        rw / w for (rw, _, _), (w, _, _) in zip(runs["rowild"], runs[side]))
                    cpu_ratio = "%.2f" % statistics.median(
                        rc / c for (_, _, rc), (_, _, c) in zip(runs["rowild"], runs[side]))
                print("%d,%s,%d,%.3f,%.3f,%.0f,%s,%s" % (scale, side, len(walls), statistics.median(walls),
                                                         statistics.median(cpu), statistics.median(rss), ratio,
                                                         cpu_ratio),
                      flush=True)


if __name__ == "__main__":
    main()
