"""Chapter 3 benchmark: segment extraction throughput, map building time, and map quality.

Run: ``python benchmarks/bench_2d.py`` (add ``--quick`` for the first 300 scans of the Intel log only).
Prints numbers only; nothing here is asserted.  Ratios are within one run of this script.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from cga_lessons import data_path, mapping2d


def extraction_rate(scans, repeat=3):
    """Scans per second of extract_segments on 361-beam scans."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for r, a in scans:
            mapping2d.extract_segments(r, a, max_range=5.0)
        best = min(best, time.perf_counter() - t0)
    return len(scans) / best


def run_scene(name, seed, method="plain", n=None, **overrides):
    scene = mapping2d.load_scene(name)
    rng = np.random.default_rng(seed)
    truth = scene.trajectory[:n]
    scans = mapping2d.simulate_scans(scene, truth, rng)
    odo = mapping2d.simulate_odometry(truth, rng)
    t0 = time.perf_counter()
    res = mapping2d.build_map(scans, odo, method=method, **overrides)
    dt = time.perf_counter() - t0
    po, _ = mapping2d.pose_errors(odo, truth)
    pc, hc = mapping2d.pose_errors(res.poses, truth)
    me = np.median(mapping2d.map_errors(res.segments, scene.walls))
    return po, pc, hc, me, 1000 * dt / len(truth), len(res.loops)


def main(quick=False):
    office = mapping2d.load_scene("office")
    scans = mapping2d.simulate_scans(office, office.trajectory[:300], np.random.default_rng(0))
    print(f"segment extraction: {extraction_rate(scans):.0f} scans/s (361 beams, office scene)")

    print("\nsynthetic scenes, default noise and drift (plain): odometry RMSE -> corrected RMSE (ratio), map error")
    for name, seeds in (("room", range(3)), ("corridor", range(3)), ("office", range(5))):
        for seed in seeds:
            po, pc, hc, me, ms, nl = run_scene(name, seed)
            print(
                f"  {name:8} seed {seed}: {po:6.3f} m -> {pc:6.3f} m ({po / pc:5.1f}x), "
                f"heading {np.degrees(hc):5.2f} deg, map median {100 * me:4.1f} cm, {nl} loops, {ms:5.1f} ms/scan"
            )

    po, pc, hc, me, ms, _ = run_scene("office", 0, "conformal", n=60)
    _, _, _, _, ms_plain, _ = run_scene("office", 0, "plain", n=60)
    print(f"\nmap building, office first 60 scans: plain {ms_plain:.1f} ms/scan, conformal {ms:.1f} ms/scan")

    log = mapping2d.read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    n = 300 if quick else len(log)
    cloud = mapping2d.scans_to_world(log.scans[:n], log.poses[:n], max_range=8.0, step=3)
    print(f"\nIntel Research Lab, {n} scans, readings up to 8 m, odometry from the true poses by OdometryModel();")
    print("map error: distance of the segment ends to the log's points at the true poses")
    for seed in range(4):
        odo = mapping2d.simulate_odometry(log.poses[:n], np.random.default_rng(seed))
        po, ho = mapping2d.pose_errors(odo, log.poses[:n])
        for loops in (True, False):
            t0 = time.perf_counter()
            res = mapping2d.build_map(log.scans[:n], odo, max_range=8.0, loop_closure=loops)
            dt = time.perf_counter() - t0
            pc, hc = mapping2d.pose_errors(res.poses, log.poses[:n])
            me = mapping2d.map_point_errors(res.segments, cloud)
            what = f"{len(res.loops):2d} loops closed" if loops else "no loop closure"
            print(
                f"  seed {seed}, {what:15}: {po:6.2f} m / {np.degrees(ho):5.1f} deg -> {pc:5.2f} m / "
                f"{np.degrees(hc):4.1f} deg ({po / pc:5.1f}x), map median {100 * np.median(me):5.1f} cm, "
                f"{1000 * dt / n:5.1f} ms/scan"
            )


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
