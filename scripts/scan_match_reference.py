#!/usr/bin/python3
"""Reference trajectory for a CMU robotdata log by windowed multi-scan matching.

The CMU Wean Hall logs have no ground truth, and a filter that settles in the
wrong one of Wean's look-alike corridors still scores well on scan
consistency. This script gives an independent estimate of where the robot
was, to judge `rcbench delibot` against (--ground-truth).

How: odometry is good over a few tens of metres, so the scans of a window of
consecutive laser records, drawn at their odometry poses, form one rigid
point cloud that sees far more of the building than one scan. Placing that
cloud in the map is a 3-DOF search:
  1. global: the first --global-window records are placed by exhaustive
     search over heading (--global-step-deg) and every map cell (FFT
     cross-correlation of the binned points with exp(-d^2 / 2 sigma^2) of the
     distance d to the nearest occupied cell), the best peaks are refined
     continuously, and the best and the best DISTINCT runner-up (more than
     2 m or 20 deg away) are reported, so the ambiguity is visible;
  2. chained: windows of --window records every --stride records, each
     placed by the same correlation in a local search (+-search-xy m,
     +-search-deg deg, heading step --local-step-deg) around the pose
     predicted by the previous window's placement, then refined. A weak
     odometry prior (--prior-*) keeps a window from sliding along a
     featureless corridor for a tiny score gain (without it, robotdata1's
     chain slid 2 m in 50 records, which odometry cannot explain);
  3. Wean's doors repeat about every 6 m, so the first window can fit two
     places almost equally. The chain is therefore run from each of the
     --hypotheses best mutually distinct starts, and the start whose chain has
     the best mean window objective (score - see-through fraction - prior
     penalty) over the whole log wins. The right start need not be among
     the first window's top three: robotdata2's is fourth (the lab door
     where it starts is drawn too narrow), and with 3 hypotheses its
     reference started one door, 6 m, west; hence 8 by default;
  4. the pose of record k inside a window is the window's rigid placement of
     odometry; where windows overlap, the poses are averaged with weights
     that fall linearly towards each window's ends (headings as unit vectors).
The score of a placement is the mean over endpoints of exp(-d^2 / 2 sigma^2)
(1 = every endpoint on an occupied cell centre). The CSV also gives the
"see-through" fraction: beams whose free part crosses an occupied cell more
than 1 m before their endpoint (lower is better; a wrong door-for-door
placement raises it, but people and map clutter keep it above zero).

What the reference IS: a scan-matching estimate. Its own error is roughly
the map cell size (0.1 m) plus the odometry drift inside one window, plus
any error of the map itself. What it is NOT: ground truth. A window whose
runner-up score is close to its best, or whose best sits on the edge of the
local search, is not well determined; the per-window CSV says which.

Inputs: a CMU .dat map (values are P(free); occupied if in [0, 0.35]; -1
unknown) and CMU robotdata logs, read by scripts/cmu_inputs.py, which states
the frame and the laser geometry; no-return codes and ranges beyond
--max-range are dropped.

Outputs, per log <name>.log, written only after every log succeeded:
  <out-dir>/<name>.ref.txt      `t_s x_m y_m theta_rad`, one line per laser
                                record (rcbench's ground-truth format; t is the
                                record's ts field)
  <out-dir>/<name>.windows.csv  kind "global": the first window's best and
                                distinct runner-up; "start_hypothesis": each
                                start tried, with its whole-log scores;
                                "chain": the chosen chain's windows;
                                "alternative_chain_N": the others. Columns:
                                records, points, score, runner-up score (best
                                grid score > 0.5 m or 5 deg away: how sharp the
                                peak is), see-through, objective (score -
                                see-through - prior penalty), pose of the first
                                record, correction against the odometry
                                prediction, flags
  --figure FILE                 map + scan endpoints at the reference poses,
                                one panel per log (scripts/plot_reference.py,
                                which also draws it from these outputs)

Usage: scripts/scan_match_reference.py --map wean.dat --out-dir out/reference
       [--figure docs/figures/real_logs_reference.png] LOG [LOG ...]
"""
import argparse
import csv
import math
import os
import sys
import time

import numpy as np
from scipy import fft as sfft
from scipy import ndimage, optimize

from cmu_inputs import BEAMS, LASER_FORWARD_M, beam_endpoints, input_error, read_cmu_log, read_cmu_map
from rcbench_files import InputError, write_atomic

DISTINCT_XY_M = 2.0         # global runner-up must be this far ...
DISTINCT_THETA_RAD = math.radians(20.0)  # ... or this far in heading
LOCAL_DISTINCT_XY_M = 0.5   # local runner-up: outside the best's own peak
LOCAL_DISTINCT_THETA_RAD = math.radians(5.0)
SEE_THROUGH_MARGIN_M = 1.0  # see see_through_fraction


# ------------------------------------------------------------ geometry ---

def wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def rot(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def relative_odometry(odometry, origin_index):
    """Odometry re-expressed with record origin_index at (0, 0, 0)."""
    o0 = odometry[origin_index]
    d = (odometry[:, :2] - o0[:2]) @ rot(o0[2])  # = R(-theta0) applied to each row
    return np.column_stack([d, odometry[:, 2] - o0[2]])


def compose(placement, relative):
    """Map poses of relative poses when the origin record sits at placement (x, y, theta)."""
    xy = relative[:, :2] @ rot(placement[2]).T + placement[:2]
    return np.column_stack([xy, wrap(relative[:, 2] + placement[2])])


def window_points(log, first, last, max_range_m, decimate):
    """Endpoints of records first..last-1 in the frame of record first."""
    rel = relative_odometry(log.odometry[first:last], 0)
    pts = [beam_endpoints(rel[k], log.ranges[first + k], max_range_m) for k in range(0, last - first, decimate)]
    return np.concatenate(pts) if pts else np.zeros((0, 2))


# -------------------------------------------------------------- scoring ---

def see_through_fraction(occupied, res, log, first, poses, max_range_m, record_step=5, beam_step=2):
    """Fraction of beams whose free part (laser to SEE_THROUGH_MARGIN_M short of the endpoint) crosses
    an occupied cell.

    The endpoint score cannot tell a wall the beam went through from a wall
    it stopped at; this free-space check can, so it separates look-alike
    placements (a door where the map has a wall). No-return beams count as
    free up to max_range_m."""
    angles = -np.pi / 2 + np.arange(0, BEAMS, beam_step) * np.pi / 180
    steps = np.arange(0.0, max_range_m, res / 2)
    crossed, total = 0, 0
    for k in range(0, len(poses), record_step):
        x, y, th = poses[k]
        r = log.ranges[first + k][::beam_step]
        free = np.where(np.isfinite(r), r - SEE_THROUGH_MARGIN_M, max_range_m)
        free = np.minimum(free, max_range_m)
        sx, sy = x + LASER_FORWARD_M * math.cos(th), y + LASER_FORWARD_M * math.sin(th)
        d = steps[None, :]
        px = sx + d * np.cos(th + angles)[:, None]
        py = sy + d * np.sin(th + angles)[:, None]
        ix, iy = np.floor(px / res).astype(int), np.floor(py / res).astype(int)
        inside = (ix >= 0) & (iy >= 0) & (ix < occupied.shape[0]) & (iy < occupied.shape[1])
        hit = np.zeros(px.shape, bool)
        hit[inside] = occupied[ix[inside], iy[inside]]
        hit &= d < free[:, None]
        use = free > 0
        crossed += int(hit[use].any(1).sum())
        total += int(use.sum())
    return crossed / total if total else float("nan")


class ScoreField:
    """exp(-d^2 / 2 sigma^2) of the distance to the nearest occupied cell, zero-padded."""

    def __init__(self, occupied, resolution_m, sigma_m, pad_cells):
        d = ndimage.distance_transform_edt(~occupied) * resolution_m
        self.res = resolution_m
        self.pad = pad_cells
        self.field = np.pad(np.exp(-0.5 * (d / sigma_m) ** 2), pad_cells)
        self.map_shape = occupied.shape
        self.occupied = occupied

    def score(self, pts, pose):
        """Mean field value at the points placed at pose (bilinear between cell centres)."""
        q = pts @ rot(pose[2]).T + pose[:2]
        idx = q / self.res - 0.5 + self.pad
        return float(ndimage.map_coordinates(self.field, idx.T, order=1, mode="constant", cval=0.0).mean())

    def refine(self, pts, pose, penalty=None):
        """Continuous local maximum of score - penalty(pose) near pose (Nelder-Mead on x, y, theta).

        Returns (pose, score at that pose without the penalty)."""
        scale = np.array([self.res, self.res, math.radians(1.0)])

        def cost(z):
            p = pose + z * scale
            return -self.score(pts, p) + (penalty(p) if penalty else 0.0)

        res = optimize.minimize(cost, np.zeros(3), method="Nelder-Mead",
                                options={"xatol": 0.02, "fatol": 1e-5, "initial_simplex":
                                         np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)})
        best = pose + res.x * scale
        best[2] = float(wrap(best[2]))
        return best, self.score(pts, best)


def bin_points(q, res):
    """Histogram of points q (m) on the cell grid; returns (hist, index of its [0, 0] cell)."""
    ij = np.floor(q / res).astype(int)
    lo = ij.min(0)
    ij -= lo
    h = np.zeros(ij.max(0) + 1)
    np.add.at(h, (ij[:, 0], ij[:, 1]), 1.0)
    return h, lo


def global_search(field, pts, step_deg, peaks_per_heading=8):
    """All placements of pts (record origin at pose) over the map: list of (score, x, y, theta) peaks."""
    res, pad = field.res, field.pad
    nx, ny = field.map_shape
    radius = float(np.sqrt((pts ** 2).sum(1)).max()) if len(pts) else 0.0
    ext = int(math.ceil(2 * radius / res)) + 2
    shape = (sfft.next_fast_len(nx + ext), sfft.next_fast_len(ny + ext))
    core = field.field[pad:pad + nx, pad:pad + ny]
    spectrum = sfft.rfft2(core, shape)
    suppress = int(round(1.0 / res)) * 2 + 1  # peaks at least 1 m apart
    candidates = []
    for deg in np.arange(0.0, 360.0, step_deg):
        theta = math.radians(deg)
        q = pts @ rot(theta).T
        h, lo = bin_points(q, res)
        # corr[u] = sum_v h[v] field[u + v]: origin at cell u puts point bin v on map cell u + v
        corr = sfft.irfft2(spectrum * np.conj(sfft.rfft2(h, shape)), shape)[:nx, :ny]
        peak = corr == ndimage.maximum_filter(corr, size=suppress, mode="constant")
        idx = np.flatnonzero(peak)
        top = idx[np.argsort(corr.ravel()[idx])[::-1][:peaks_per_heading]]
        for u in top:
            i, j = divmod(int(u), ny)
            # shift t moves bin lo + v to cell u + v: t = (u - lo) cells
            candidates.append((corr[i, j] / len(pts), (i - lo[0]) * res, (j - lo[1]) * res, theta))
    candidates.sort(key=lambda c: -c[0])
    return candidates


def local_search(field, pts, predicted, search_xy_m, search_deg, step_deg):
    """Scores of placements around predicted on a grid of headings x cells.

    Returns (scores [headings, cells, cells], x_m [cells], y_m [cells], theta_rad [headings]).
    """
    res, pad = field.res, field.pad
    m = int(math.ceil(search_xy_m / res))
    thetas = predicted[2] + np.radians(np.arange(-search_deg, search_deg + 1e-9, step_deg))
    scores = np.zeros((len(thetas), 2 * m + 1, 2 * m + 1))
    for t, theta in enumerate(thetas):
        q = pts @ rot(theta).T + predicted[:2]
        h, lo = bin_points(q, res)
        a0, b0 = lo[0] + pad - m, lo[1] + pad - m
        a1, b1 = a0 + h.shape[0] + 2 * m, b0 + h.shape[1] + 2 * m
        crop = np.zeros((a1 - a0, b1 - b0))
        ca0, cb0 = max(a0, 0), max(b0, 0)
        ca1, cb1 = min(a1, field.field.shape[0]), min(b1, field.field.shape[1])
        if ca1 > ca0 and cb1 > cb0:
            crop[ca0 - a0:ca1 - a0, cb0 - b0:cb1 - b0] = field.field[ca0:ca1, cb0:cb1]
        shape = (sfft.next_fast_len(crop.shape[0]), sfft.next_fast_len(crop.shape[1]))
        # corr[i] = sum_v h[v] crop[i + v]: a shift of (i - m) cells from the prediction
        corr = sfft.irfft2(sfft.rfft2(crop, shape) * np.conj(sfft.rfft2(h, shape)), shape)
        scores[t] = corr[:2 * m + 1, :2 * m + 1] / len(pts)
    offsets = (np.arange(2 * m + 1) - m) * res
    return scores, predicted[0] + offsets, predicted[1] + offsets, thetas


class OdometryPrior:
    """Penalty (score units) for moving a window away from its odometry-chained prediction."""

    def __init__(self, weight, sigma_xy_m, sigma_theta_rad):
        self.weight, self.sigma_xy, self.sigma_theta = weight, sigma_xy_m, sigma_theta_rad

    def __call__(self, dx, dy, dtheta):
        return 0.5 * self.weight * ((dx ** 2 + dy ** 2) / self.sigma_xy ** 2 + (dtheta / self.sigma_theta) ** 2)


def distinct(a, b, xy_m, theta_rad):
    return math.hypot(a[1] - b[1], a[2] - b[2]) > xy_m or abs(float(wrap(a[3] - b[3]))) > theta_rad


# ------------------------------------------------------------- the chain ---

def windows_of(n, length, stride):
    if n <= length:
        return [(0, n)]
    starts = list(range(0, n - length + 1, stride))
    if starts[-1] + length < n:
        starts.append(n - length)
    return [(s, s + length) for s in starts]


def build_reference(log, field, args):
    n = len(log.times)
    rows = []
    # 1. global placement of the first window
    g_end = min(args.global_window, n)
    pts = window_points(log, 0, g_end, args.max_range, args.decimate)
    if len(pts) < 50:
        raise input_error(log.path, 0, "L records", f"only {len(pts)} usable endpoints in the first {g_end} records")
    cands = global_search(field, pts, args.global_step_deg)
    # Refine the best few mutually separate peaks (neighbouring headings of
    # one peak are one candidate), so best and runner-up are compared alike.
    picked = []
    for c in cands:
        if all(distinct(c, p, LOCAL_DISTINCT_XY_M, LOCAL_DISTINCT_THETA_RAD) for p in picked):
            picked.append(c)
            if len(picked) == args.refine_top:
                break
    refined = sorted(((s, *pose) for pose, s in (field.refine(pts, np.array(c[1:])) for c in picked)),
                     key=lambda c: -c[0])
    best = refined[0]
    runner = next((c for c in refined[1:] if distinct(c, best, DISTINCT_XY_M, DISTINCT_THETA_RAD)), None)
    rel = relative_odometry(log.odometry[:g_end], 0)
    see = [see_through_fraction(field.occupied, field.res, log, 0, compose(np.asarray(c[1:]), rel), args.max_range)
           if c is not None else float("nan") for c in (best, runner)]
    rows.append(window_row("global", 0, g_end, len(pts), best, runner, None, [], see))
    # The first window alone may be ambiguous (Wean's doors repeat every ~6 m),
    # so the whole log decides: chain from each of the --hypotheses best
    # mutually distinct starts and keep the chain with the best mean window
    # objective: score - see-through fraction - odometry prior penalty. Both
    # terms matter: a chain from a wrong start stays in the map only by
    # sliding metres per window, or by seeing through walls (robotdata2 from
    # (52, 41) with --prior-sigma-xy 0.5 slides and sees through the end wall;
    # on score alone it would win).
    starts = [best]
    for c in refined[1:]:
        if len(starts) < args.hypotheses and all(distinct(c, h, DISTINCT_XY_M, DISTINCT_THETA_RAD) for h in starts):
            starts.append(c)
    chains = [chain(log, field, args, np.array(h[1:])) for h in starts]
    objectives = [chain_mean(c_rows, "objective") for _, c_rows in chains]
    chosen = int(np.nanargmax(objectives))
    for h, (poses, c_rows), objective in zip(starts, chains, objectives):
        row = window_row("start_hypothesis", 0, g_end, len(pts), h, None, None, [], [float("nan")] * 2)
        row["objective"] = objective
        row["flags"] = ("chosen; " if h is starts[chosen] else "") + \
            f"whole-log mean window objective {objective:.3f} (score {chain_mean(c_rows, 'score'):.3f}), " \
            f"see-through {chain_mean(c_rows, 'see_through'):.3f}, " \
            f"{sum(1 for r in c_rows if r['correction_xy_m'] > args.max_correction)} corrections > " \
            f"{args.max_correction:g} m"
        rows.append(row)
    for i, (poses, c_rows) in enumerate(chains):
        for r in c_rows:
            r["kind"] = "chain" if i == chosen else f"alternative_chain_{i + 1}"
        rows += c_rows
    return chains[chosen][0], rows


def chain_mean(rows, column):
    v = [r[column] for r in rows if math.isfinite(r[column])]
    return float(np.mean(v)) if v else float("nan")


def chain(log, field, args, placement):
    """Chained local windows from record 0 at placement: (blended poses [n, 3], window rows)."""
    n = len(log.times)
    rows = []
    wins = windows_of(n, args.window, args.stride)
    prior = OdometryPrior(args.prior_weight, args.prior_sigma_xy, math.radians(args.prior_sigma_deg))
    poses_per_window = []
    prev_start, prev_placement = 0, placement
    for w, (s, e) in enumerate(wins):
        predicted = compose(prev_placement, relative_odometry(log.odometry, prev_start)[s:s + 1])[0]
        pts = window_points(log, s, e, args.max_range, args.decimate)
        flags = []
        if len(pts) < 50:  # nothing to match: keep the prediction
            chosen, runner_c, flags = (float("nan"), *predicted), None, ["too few points; odometry only"]
            pose = predicted
        else:
            scores, xs, ys, thetas = local_search(field, pts, predicted, args.search_xy, args.search_deg,
                                                  args.local_step_deg)
            objective = scores - prior(xs[None, :, None] - predicted[0], ys[None, None, :] - predicted[1],
                                       (thetas - predicted[2])[:, None, None])
            t, i, j = np.unravel_index(np.argmax(objective), objective.shape)
            penalty = lambda p: prior(p[0] - predicted[0], p[1] - predicted[1], float(wrap(p[2] - predicted[2])))
            pose, score = field.refine(pts, np.array([xs[i], ys[j], thetas[t]]), penalty)
            chosen = (score, *pose)
            # runner-up: best pure match score outside the chosen peak
            far = (np.hypot(xs[None, :, None] - pose[0], ys[None, None, :] - pose[1]) > LOCAL_DISTINCT_XY_M) | \
                  (np.abs(wrap(thetas - pose[2]))[:, None, None] > LOCAL_DISTINCT_THETA_RAD)
            if far.any():
                rt, ri, rj = np.unravel_index(np.argmax(np.where(far, scores, -np.inf)), scores.shape)
                runner_c = (field.score(pts, np.array([xs[ri], ys[rj], thetas[rt]])), xs[ri], ys[rj], thetas[rt])
            else:
                runner_c = None
            edge = len(xs) - 1
            if i in (0, edge) or j in (0, edge) or t in (0, len(thetas) - 1):
                flags.append("best on the search edge")
            if runner_c is not None and runner_c[0] > score - args.ambiguity_margin:
                flags.append("runner-up within %.3f" % args.ambiguity_margin)
            if score < args.low_score:
                flags.append("score below %.2f" % args.low_score)
            if math.hypot(pose[0] - predicted[0], pose[1] - predicted[1]) > args.max_correction:
                flags.append("correction > %g m (more than odometry drifts)" % args.max_correction)
        rel = relative_odometry(log.odometry[s:e], 0)
        poses = compose(np.asarray(pose), rel)
        see = [see_through_fraction(field.occupied, field.res, log, s, compose(np.asarray(c[1:]), rel), args.max_range)
               if c is not None else float("nan") for c in (chosen, runner_c)]
        rows.append(window_row("chain", s, e, len(pts), chosen, runner_c, predicted, flags, see))
        # matched endpoints - contradicted beams - odometry penalty (all fractions/score units)
        rows[-1]["objective"] = chosen[0] - see[0] - prior(pose[0] - predicted[0], pose[1] - predicted[1],
                                                           float(wrap(pose[2] - predicted[2])))
        poses_per_window.append((s, e, poses))
        prev_start, prev_placement = s, np.asarray(pose)

    # 3. blend overlapping windows
    acc = np.zeros((n, 4))  # sum w*x, w*y, w*cos, w*sin
    wsum = np.zeros(n)
    for s, e, poses in poses_per_window:
        k = np.arange(e - s)
        w = np.minimum(k + 1, e - s - k).astype(float)
        acc[s:e] += w[:, None] * np.column_stack([poses[:, 0], poses[:, 1], np.cos(poses[:, 2]), np.sin(poses[:, 2])])
        wsum[s:e] += w
    ref = np.column_stack([acc[:, 0] / wsum, acc[:, 1] / wsum, np.arctan2(acc[:, 3], acc[:, 2])])
    return ref, rows


def window_row(kind, s, e, npts, best, runner, predicted, flags, see_through):
    row = {"kind": kind, "first_record": s, "last_record": e - 1, "points": npts,
           "score": best[0], "runner_up_score": runner[0] if runner else float("nan"),
           "see_through": see_through[0], "runner_up_see_through": see_through[1],
           "x_m": best[1], "y_m": best[2], "theta_rad": best[3],
           "runner_up_x_m": runner[1] if runner else float("nan"),
           "runner_up_y_m": runner[2] if runner else float("nan"),
           "runner_up_theta_rad": runner[3] if runner else float("nan"),
           "objective": float("nan"),
           "correction_xy_m": float("nan"), "correction_theta_rad": float("nan"), "flags": "; ".join(flags)}
    if predicted is not None:
        row["correction_xy_m"] = math.hypot(best[1] - predicted[0], best[2] - predicted[1])
        row["correction_theta_rad"] = float(wrap(best[3] - predicted[2]))
    return row


# --------------------------------------------------------------- output ---

def reference_text(times, ref):
    lines = ["# t_s x_m y_m theta_rad  (scan-matching reference from scripts/scan_match_reference.py, not ground truth)"]
    lines += ["%.17g %.17g %.17g %.17g" % (t, x, y, th) for t, (x, y, th) in zip(times, ref)]
    return "\n".join(lines) + "\n"


def windows_text(rows):
    import io
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    return out.getvalue()


def hypotheses_text(rows):
    return "; ".join(f"({r['x_m']:.2f}, {r['y_m']:.2f}) m {math.degrees(r['theta_rad']) % 360:.0f} deg: "
                     f"{r['flags']}" for r in rows if r["kind"] == "start_hypothesis")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("logs", nargs="+", help="CMU robotdata .log files")
    ap.add_argument("--map", required=True, help="CMU .dat map (values are P(free))")
    ap.add_argument("--out-dir", default="out/reference")
    ap.add_argument("--figure", default="", help="PNG: map + endpoints at the reference poses, one panel per log")
    ap.add_argument("--global-window", type=int, default=250, help="records placed by the global search (count)")
    ap.add_argument("--window", type=int, default=100, help="records per chained window (count)")
    ap.add_argument("--stride", type=int, default=50, help="records between chained window starts (count)")
    ap.add_argument("--search-xy", type=float, default=2.0, help="local search half-width (m)")
    ap.add_argument("--search-deg", type=float, default=10.0, help="local search half-width in heading (deg)")
    ap.add_argument("--global-step-deg", type=float, default=1.0, help="global heading step (deg)")
    ap.add_argument("--local-step-deg", type=float, default=0.5, help="local heading step (deg)")
    ap.add_argument("--sigma", type=float, default=0.15, help="score kernel width (m)")
    ap.add_argument("--max-range", type=float, default=8.0, help="ignore ranges beyond this (m)")
    ap.add_argument("--decimate", type=int, default=1, help="use every K-th record's scan in a window (count)")
    ap.add_argument("--hypotheses", type=int, default=8,
                    help="distinct starts chained through the whole log; the best whole-log mean objective wins (count)")
    ap.add_argument("--refine-top", type=int, default=20, help="global peaks refined continuously (count)")
    ap.add_argument("--prior-weight", type=float, default=0.01,
                    help="odometry prior: score units lost per squared sigma of deviation from the prediction "
                         "(0 = pure scan matching)")
    ap.add_argument("--prior-sigma-xy", type=float, default=0.3, help="odometry prior position sigma (m)")
    ap.add_argument("--prior-sigma-deg", type=float, default=3.0, help="odometry prior heading sigma (deg)")
    ap.add_argument("--ambiguity-margin", type=float, default=0.01,
                    help="flag a window whose runner-up scores within this of its best (score units)")
    ap.add_argument("--max-correction", type=float, default=1.0,
                    help="flag a window moved this far from its odometry prediction (m)")
    ap.add_argument("--low-score", type=float, default=0.5, help="flag a window scoring below this (score units)")
    args = ap.parse_args()
    if min(args.window, args.stride, args.global_window, args.decimate, args.refine_top, args.hypotheses) < 1 or args.stride > args.window:
        sys.exit("scan_match_reference: --window, --stride, --global-window, --decimate, --refine-top, --hypotheses must be >= 1 "
                 "and --stride <= --window")
    if min(args.search_xy, args.search_deg, args.global_step_deg, args.local_step_deg, args.sigma, args.max_range) <= 0:
        sys.exit("scan_match_reference: --search-xy, --search-deg, the steps, --sigma and --max-range must be > 0")
    if args.prior_weight < 0 or min(args.prior_sigma_xy, args.prior_sigma_deg) <= 0:
        sys.exit("scan_match_reference: --prior-weight must be >= 0 and the prior sigmas > 0")

    try:
        t0 = time.time()
        occupied, res = read_cmu_map(args.map)
        field = ScoreField(occupied, res, args.sigma, pad_cells=int(math.ceil((args.max_range + args.search_xy + 2) / res)))
        print(f"map: {args.map} ({occupied.shape[0]} x {occupied.shape[1]} cells of {res} m, "
              f"{int(occupied.sum())} occupied), {time.time() - t0:.1f} s", file=sys.stderr)
        results = []
        for path in args.logs:
            t1 = time.time()
            log = read_cmu_log(path)
            ref, rows = build_reference(log, field, args)
            name = os.path.splitext(os.path.basename(path))[0]
            results.append((name, log, ref, rows))
            g = rows[0]
            local = [r for r in rows if r["kind"] == "chain"]
            scores = np.array([r["score"] for r in local])
            print(f"{name}: {len(log.times)} records; first window: best {g['score']:.3f} at ({g['x_m']:.2f}, "
                  f"{g['y_m']:.2f}) m {math.degrees(g['theta_rad']) % 360:.1f} deg, distinct runner-up "
                  f"{g['runner_up_score']:.3f} at ({g['runner_up_x_m']:.2f}, {g['runner_up_y_m']:.2f}) m "
                  f"{math.degrees(g['runner_up_theta_rad']) % 360:.0f} deg; {time.time() - t1:.1f} s", file=sys.stderr)
            print(f"  start hypotheses: {hypotheses_text(rows)}", file=sys.stderr)
            print(f"  reference starts at ({ref[0, 0]:.2f}, {ref[0, 1]:.2f}) m {math.degrees(ref[0, 2]) % 360:.1f} "
                  f"deg; {len(local)} windows, score min {np.nanmin(scores):.3f} median {np.nanmedian(scores):.3f}, "
                  f"{sum(1 for r in local if r['flags'])} flagged", file=sys.stderr)
            for r in local:
                if r["flags"]:
                    print(f"  records {r['first_record']}-{r['last_record']}: score {r['score']:.3f}, runner-up "
                          f"{r['runner_up_score']:.3f}: {r['flags']}", file=sys.stderr)
    except InputError as e:
        sys.exit(f"scan_match_reference: {e}")
    for name, log, ref, rows in results:
        if not np.isfinite(ref).all():
            sys.exit(f"scan_match_reference: {name}: non-finite reference pose (bug)")
    for name, log, ref, rows in results:
        write_atomic(os.path.join(args.out_dir, name + ".ref.txt"), reference_text(log.times, ref))
        write_atomic(os.path.join(args.out_dir, name + ".windows.csv"), windows_text(rows))
        print(f"wrote {os.path.join(args.out_dir, name + '.ref.txt')} and {name}.windows.csv", file=sys.stderr)
    if args.figure:
        from plot_reference import draw_figure
        draw_figure(args.figure, occupied, res, results, args.max_range)
        print(f"wrote {args.figure}", file=sys.stderr)


if __name__ == "__main__":
    main()
