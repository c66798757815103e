"""How well do a log's "corrected" poses agree with its own scans?  An independent check of the reference.

Run: ``python benchmarks/bench_log_consistency.py`` (the six bundled logs, about a minute); ``--logs intel,aces``
to choose; ``--every 3`` to register every third scan only; ``--json PATH`` to store the table.

The chapter's benchmark (``benchmarks/bench_logs.py``) measures the maps against the logs' corrected poses as if
they were the truth.  This script asks how true they are, with nothing of the package's line method in the loop:
each scan's points are registered, point to line, on the points of all the *other* scans placed at the log's
poses (leave-one-out; the ``--exclude`` scans on either side are left out too, since neighbours share the local
errors of whatever made the poses), starting at the log's pose.  A reference point is used only where its
twelve nearest neighbours lie on a line (smallest over largest eigenvalue of their scatter below 0.2), within
0.5 m; the residuals are weighted robustly (Huber at twice their median absolute deviation) and Gauss-Newton
runs to convergence.  The pose it ends at is where the rest of the log says the scan belongs; its offset from
the log's pose is the reference's own error for that scan (plus the registration's, whose formal standard
deviation is printed beside it).

Printed per log: the scans registered, the heading offset (median of its size, RMS, 90th percentile), the
position offset (median, 90th percentile), the median formal standard deviation of the heading, the first
scan's heading offset (a map built from the scans, anchored at the first pose, turns with it), and the lag-one
autocorrelation of the heading offsets (are the errors independent from scan to scan?).  Numbers only; nothing
is asserted.
"""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np
from scipy.spatial import cKDTree

from cga_lessons import data_path, mapping2d

LOGS = ("intel", "aces", "csail", "freiburg-101", "seattle", "orebro")
MAX_RANGE = 8.0  # the reach bench_logs.py builds its maps with
NEIGHBOURS, FLATNESS, REACH = 12, 0.2, 0.5


def reference(scans, poses):
    """Every scan's points in the world at ``poses``, their scan, and the normals of those that lie on a line."""
    world = [mapping2d.scans_to_world([s], poses[k : k + 1], max_range=MAX_RANGE) for k, s in enumerate(scans)]
    owner = np.concatenate([np.full(len(p), k) for k, p in enumerate(world)])
    points = np.concatenate(world)
    tree = cKDTree(points)
    _, nb = tree.query(points, k=NEIGHBOURS)
    spread = points[nb] - points[nb].mean(axis=1, keepdims=True)
    w, v = np.linalg.eigh(np.einsum("nki,nkj->nij", spread, spread))
    flat = w[:, 0] < FLATNESS * np.maximum(w[:, 1], 1e-12)
    return tree, points, owner, v[:, :, 0], flat


def register(k, local, start, ref, exclude, iterations=30):
    """Scan ``k``'s points (laser frame) registered on the other scans' points: (pose, pairs, heading sd) or None."""
    tree, points, owner, normal, flat = ref
    x = np.array(start, float)
    if len(local) < 20:
        return None
    for _ in range(iterations):
        c, s = np.cos(x[2]), np.sin(x[2])
        q = local @ np.array([[c, s], [-s, c]]) + x[:2]
        d, j = tree.query(q, k=8, distance_upper_bound=REACH)
        found = np.isfinite(d)
        j = np.where(found, j, 0)
        d = np.where(found & (np.abs(owner[j] - k) > exclude) & flat[j], d, np.inf)
        pick = np.argmin(d, axis=1)
        rows = np.arange(len(d))
        ok = np.isfinite(d[rows, pick])
        if ok.sum() < 20:
            return None
        partner = j[rows, pick][ok]
        n, qo = normal[partner], q[ok]
        r = np.einsum("ij,ij->i", n, qo - points[partner])
        lever = qo - x[:2]
        J = np.column_stack([n, n[:, 1] * lever[:, 0] - n[:, 0] * lever[:, 1]])
        sigma = 1.4826 * np.median(np.abs(r)) + 1e-4
        w = np.minimum(1.0, 2 * sigma / np.maximum(np.abs(r), 1e-12))
        A = J.T @ (w[:, None] * J)
        dx = np.linalg.solve(A + 1e-12 * np.eye(3), -J.T @ (w * r))
        x += dx
        if np.abs(dx[:2]).max() < 1e-6 and abs(dx[2]) < 1e-7:
            break
    return x, int(ok.sum()), float(sigma * np.sqrt(np.linalg.inv(A)[2, 2]))


def check_log(name, every, exclude):
    log = mapping2d.read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
    scans, poses = log.scans, log.poses
    ref = reference(scans, poses)
    zero = np.zeros((1, 3))
    out = []
    for k in range(0, len(scans), every):
        got = register(k, mapping2d.scans_to_world([scans[k]], zero, max_range=MAX_RANGE), poses[k], ref, exclude)
        if got is not None:
            x, pairs, sd = got
            dth = np.degrees(np.angle(np.exp(1j * (x[2] - poses[k, 2]))))
            out.append((k, dth, 100 * np.hypot(*(x[:2] - poses[k, :2])), pairs, np.degrees(sd)))
    a = np.array(out)
    h = a[:, 1]
    first = a[a[:, 0] == 0]
    return dict(
        name=name,
        scans=len(scans),
        registered=len(a),
        heading_median_abs_deg=float(np.median(np.abs(h))),
        heading_rms_deg=float(np.sqrt(np.mean(h**2))),
        heading_p90_deg=float(np.percentile(np.abs(h), 90)),
        position_median_cm=float(np.median(a[:, 2])),
        position_p90_cm=float(np.percentile(a[:, 2], 90)),
        heading_sd_median_deg=float(np.median(a[:, 4])),
        first_scan_heading_deg=float(first[0, 1]) if len(first) else None,
        lag1_autocorrelation=float(np.corrcoef(h[:-1], h[1:])[0, 1]) if len(h) > 2 else None,
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--logs", default=",".join(LOGS), help="comma-separated logs (default: the six bundled)")
    ap.add_argument("--every", type=int, default=1, help="register every n-th scan (default 1: all)")
    ap.add_argument("--exclude", type=int, default=2, help="neighbouring scans left out on either side (default 2)")
    ap.add_argument("--json", help="write the table to this file (refused if it exists)")
    args = ap.parse_args(argv)
    if args.json and __import__("pathlib").Path(args.json).exists():
        ap.error(f"--json: {args.json} exists; choose another name")
    rows = [check_log(name.strip(), args.every, args.exclude) for name in args.logs.split(",")]
    print(f"{'log':14s} {'scans':>5s}  heading offset: median |.|   RMS   90th pct  (formal sd)   "
          f"position: median  90th pct   first scan   lag-1 corr")
    for r in rows:
        print(f"{r['name']:14s} {r['registered']:5d}  {r['heading_median_abs_deg']:13.3f}° "
              f"{r['heading_rms_deg']:7.3f}° {r['heading_p90_deg']:8.3f}°  ({r['heading_sd_median_deg']:.3f}°)   "
              f"{r['position_median_cm']:12.2f} cm {r['position_p90_cm']:6.2f} cm  "
              f"{r['first_scan_heading_deg']:+9.3f}°   {r['lag1_autocorrelation']:+8.2f}")
    if args.json:
        meta = dict(every=args.every, exclude=args.exclude, max_range=MAX_RANGE)
        with open(args.json, "x") as f:
            json.dump(dict(options=meta, logs=rows), f, indent=1)
        print("wrote", args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
