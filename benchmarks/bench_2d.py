"""Chapter 3 benchmark: segment extraction throughput, map building time, and map quality.

Run: ``python benchmarks/bench_2d.py`` (add ``--quick`` to skip the whole Intel log).
Prints numbers only; nothing here is asserted.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from cga_lessons import data_path, laser, lines, mapping2d


def extraction_rate(scans, repeat=3):
    """Scans per second of extract_segments on 361-beam scans."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for r, a in scans:
            lines.extract_segments(r, a, max_range=5.0)
        best = min(best, time.perf_counter() - t0)
    return len(scans) / best


def run_scene(name, seed, method="plain", n=None):
    scene = laser.load_scene(name)
    rng = np.random.default_rng(seed)
    truth = scene.trajectory[:n]
    scans = laser.simulate_scans(scene, truth, rng)
    odo = laser.simulate_odometry(truth, rng)
    t0 = time.perf_counter()
    res = mapping2d.build_map(scans, odo, method=method)
    dt = time.perf_counter() - t0
    po, _ = mapping2d.pose_errors(odo, truth)
    pc, hc = mapping2d.pose_errors(res.poses, truth)
    me = np.median(mapping2d.map_errors(res.segments, scene.walls))
    return po, pc, hc, me, 1000 * dt / len(truth)


def main(quick=False):
    office = laser.load_scene("office")
    scans = laser.simulate_scans(office, office.trajectory[:300], np.random.default_rng(0))
    print(f"segment extraction: {extraction_rate(scans):.0f} scans/s (361 beams, office scene)")

    print("\nsynthetic scenes, default noise and drift (plain): odometry RMSE -> corrected RMSE (ratio), map error")
    for name, seeds in (("room", range(3)), ("corridor", range(3)), ("office", range(5))):
        for seed in seeds:
            po, pc, hc, me, ms = run_scene(name, seed)
            print(f"  {name:8} seed {seed}: {po:6.3f} m -> {pc:6.3f} m ({po / pc:5.1f}x), "
                  f"heading {np.degrees(hc):5.2f} deg, map median {100 * me:4.1f} cm, {ms:5.1f} ms/scan")

    po, pc, hc, me, ms = run_scene("office", 0, "conformal", n=60)
    _, _, _, _, ms_plain = run_scene("office", 0, "plain", n=60)
    print(f"\nmap building, office first 60 scans: plain {ms_plain:.1f} ms/scan, conformal {ms:.1f} ms/scan")

    log = laser.read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    n = 300 if quick else len(log)
    print(f"\nIntel Research Lab, {n} scans, readings up to 8 m, odometry from the true poses by OdometryModel():")
    for seed in range(4):
        odo = laser.simulate_odometry(log.poses[:n], np.random.default_rng(seed))
        t0 = time.perf_counter()
        res = mapping2d.build_map(log.scans[:n], odo, max_range=8.0)
        dt = time.perf_counter() - t0
        po, ho = mapping2d.pose_errors(odo, log.poses[:n])
        pc, hc = mapping2d.pose_errors(res.poses, log.poses[:n])
        print(f"  seed {seed}: {po:6.2f} m / {np.degrees(ho):6.1f} deg -> {pc:5.2f} m / {np.degrees(hc):5.1f} deg "
              f"({po / pc:4.1f}x), {1000 * dt / n:5.1f} ms/scan")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
