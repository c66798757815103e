"""Chapter 5 benchmark: time per relocalization against map size, and success rates at scale.

Run: ``python benchmarks/bench_reloc.py`` (add ``--quick`` for fewer poses).
Prints numbers only; nothing here is asserted.

1. Map size: the office's 120 wall faces tiled k x k times (|M| = 120 k^2); the same scans from
   the original office are relocalized in each map.  Reported: the median time of ``relocalize``,
   of the thesis's vote step as written (``vote_matrix``, every shifted line against the whole map)
   and as kept (``vote_matrix_indexed``, a binary search per shifted line), with ratios to the
   smallest map and the growth exponent fitted on a log-log scale.
2. Success at scale: random poses in the office, the twin-room office, the corridor and an irregular
   hall (1 cm noise), from one scan and from a look around (four scans turning on the spot, with the
   turn's odometry drift; all four, or stopping at the first confident answer); the office against
   range noise; held-out scans of the Intel log, one by one and as short runs with the log's odometry.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from cga_lessons import data_path
from cga_lessons.mapping2d import laser, read_carmen_log
from cga_lessons.mapping2d.laser import Scene
from cga_lessons.relocalization import pose_error, prepare_map, relocalize
from cga_lessons.relocalization.eval import evaluate_log, evaluate_poses, random_free_poses
from cga_lessons.relocalization.hough import hough_set, vote_matrix, vote_matrix_indexed
from cga_lessons.relocalization.lookaround import evaluate_log_sequences, evaluate_look_around


def tiled(walls, k, period=(24.2, 14.2)):
    """The walls repeated on a k x k grid."""
    return np.concatenate([walls + np.array([i * period[0], j * period[1]]) for i in range(k) for j in range(k)])


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def map_size(quick):
    office = laser.load_scene("office")
    rng = np.random.default_rng(1)
    poses = random_free_poses(office, 6 if quick else 12, rng)
    scans = [laser.simulate_scan(office, p, rng) for p in poses]
    segs = [relocalize(office.walls, scan=s).scan_segments for s in scans]
    rows = []
    for k in (1, 2, 3, 4) if quick else (1, 2, 3, 4, 6):
        walls = tiled(office.walls, k)
        ref = prepare_map(walls)
        relocalize(ref, scan=scans[0])  # warm-up (prepares the map's pair distances)
        t_rel = np.median([median_time(lambda s=s, ref=ref: relocalize(ref, scan=s), 1) for s in scans])
        M_h = hough_set(walls)
        L_h = [hough_set(s) for s in segs]
        t_idx = np.median(
            [median_time(lambda L=L, M=M_h: vote_matrix_indexed(M, L, np.radians(3), 0.2), 1) for L in L_h]
        )
        t_lit = (
            np.median([median_time(lambda L=L, M=M_h: vote_matrix(M, L, np.radians(3), 0.2), 1) for L in L_h[:3]])
            if len(walls) <= 2000
            else np.nan
        )
        rows.append((len(walls), t_rel, t_idx, t_lit))
    n_lines = np.mean([len(s) for s in segs])
    print(f"\ntime against map size (median over {len(scans)} office scans, {n_lines:.1f} lines each)")
    print("   |M|   relocalize  ratio   votes as kept  ratio   votes as written  ratio")
    base = rows[0]
    for m, a, b, c in rows:
        lit = f"{1000 * c:12.1f} ms {c / base[3]:6.1f}x" if np.isfinite(c) else "           -        -"
        print(f"{m:6d} {1000 * a:9.1f} ms {a / base[1]:5.1f}x {1000 * b:10.1f} ms {b / base[2]:6.1f}x   {lit}")
    m = np.log([r[0] for r in rows])
    for name, col in (("relocalize", 1), ("votes as kept", 2), ("votes as written", 3)):
        y = np.array([r[col] for r in rows])
        ok = np.isfinite(y)
        slope = np.polyfit(m[ok], np.log(y[ok]), 1)[0]
        print(f"  growth of {name}: time ~ |M|^{slope:.2f}")


def hall_scene():
    outline = np.array(
        [[0, 0], [7, 0], [7, 2], [9.5, 2], [9.5, 6], [6, 6], [6, 8.5], [2.5, 8.5], [2.5, 5], [0, 5]], float
    )
    polys = []
    for a, b in zip(outline, np.roll(outline, -1, axis=0)):
        d = (b - a) / np.hypot(*(b - a))
        n = np.array([-d[1], d[0]]) * 0.05
        a2, b2 = a - d * 0.05, b + d * 0.05
        polys.append(np.array([a2 - n, b2 - n, b2 + n, a2 + n]))
    boxes = [
        np.array([[1.5, 1.2], [2.7, 1.2], [2.7, 1.8], [1.5, 1.8]]),
        np.array([[7.5, 4.0], [8.2, 4.0], [8.2, 5.2], [7.5, 5.2]]),
        np.array([[3.6, 6.8], [4.4, 6.8], [4.4, 7.3], [3.6, 7.3]]),
    ]
    return Scene("irregular hall", polys + boxes, np.zeros((1, 3)))


def line(name, s):
    print(
        f"  {name:<24} n={s.n:4d}  success {s.success:4d} ({100 * s.success_rate:5.1f} %)  "
        f"confidently wrong {s.confidently_wrong:2d}  ambiguous {s.ambiguous:4d} "
        f"(witness {s.indistinguishable:4d})  failed {s.failed:3d}  "
        f"success w/o witness {100 * s.success_rate_distinguishable:5.1f} %  {s.median_ms:5.1f} ms"
    )


def success(quick):
    n = 60 if quick else 240
    scenes = [laser.load_scene(name) for name in ("office", "office_twins", "corridor")] + [hall_scene()]
    print("\nrandom poses, 1 cm range noise, 361 beams over 180 deg, 5 m (map: the scene's walls)")
    print("one scan:")
    for scene in scenes:
        rng = np.random.default_rng(2024)
        ev = evaluate_poses(scene, scene.walls, random_free_poses(scene, n, rng), rng)
        line(scene.name, ev.summary())
    print("a look around (4 scans, turning 90 deg on the spot between them, odometry drift of the turn):")
    for scene in scenes:
        rng = np.random.default_rng(2024)
        poses = random_free_poses(scene, n, rng)
        ev, _ = evaluate_look_around(scene, scene.walls, poses, rng)
        line(scene.name, ev.summary())
        if scene.name == "office":
            ev, used = evaluate_look_around(
                scene, scene.walls, poses, np.random.default_rng(2025), stop_when_confident=True
            )
            line("office, turn when unsure", ev.summary())
            print(f"  {'':24} scans used: " + ", ".join(f"{k}: {c}" for k, c in enumerate(np.bincount(used)) if c))

    office = laser.load_scene("office")
    ref = prepare_map(office.walls)
    poses = random_free_poses(office, n // 2, np.random.default_rng(7))
    print("\noffice against range noise (one scan; a look around, turning when unsure)")
    for sigma in (0.0, 0.01, 0.02, 0.03, 0.05):
        ev = evaluate_poses(office, ref, poses, np.random.default_rng(8), range_noise=sigma)
        line(f"noise {100 * sigma:.0f} cm, one scan", ev.summary())
        ev, _ = evaluate_look_around(
            office, ref, poses, np.random.default_rng(8), range_noise=sigma, stop_when_confident=True
        )
        line(f"noise {100 * sigma:.0f} cm, look around", ev.summary())
    print("\noffice, one 360 deg scan and 10 m range")
    for kw in (
        dict(fov=2 * np.pi * 719 / 720, n_beams=720),
        dict(fov=2 * np.pi * 719 / 720, n_beams=720, max_range=10.0),
    ):
        ev = evaluate_poses(office, ref, poses, np.random.default_rng(8), **kw)
        line(f"{kw.get('max_range', 5.0):.0f} m, 360 deg", ev.summary())

    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    test = np.arange(7, len(log), 30 if quick else 15)
    ev, segs = evaluate_log(log, test, exclude=2, map_step=2)
    print(f"\nIntel log: {len(test)} held-out scans, map of {len(segs)} segments from every 2nd other scan (8 m)")
    line("Intel", ev.summary())
    ok = ev.status == "ok"
    print(
        f"  confident answers: median error {100 * np.median(ev.position_error[ok]):.1f} cm, "
        f"{np.degrees(np.median(ev.heading_error[ok])):.2f} deg"
    )
    wrong = np.flatnonzero(ev.confidently_wrong)
    for i in wrong:
        print(
            f"  confidently wrong: scan {test[i]}, {ev.position_error[i]:.2f} m, "
            f"{np.degrees(ev.heading_error[i]):.1f} deg"
        )
    starts = np.arange(7, len(log) - 10, 60 if quick else 30)
    ev, _, segs = evaluate_log_sequences(log, starts, length=3, stride=3)
    print(
        f"Intel log: {len(starts)} runs of 3 scans (3 apart) with the logged odometry, "
        f"map of {len(segs)} segments from the other scans"
    )
    line("Intel, runs of 3 scans", ev.summary())
    ref = prepare_map(segs)
    single = [relocalize(ref, scan=log.scans[k + 6], max_range=8.0) for k in starts]
    right = [
        r.status == "ok"
        and pose_error(r.pose, log.poses[k + 6])[0] < 0.1
        and pose_error(r.pose, log.poses[k + 6])[1] < np.radians(2)
        for r, k in zip(single, starts)
    ]
    wrong = sum(r.status == "ok" for r in single) - sum(right)
    print(f"  {'the last scans alone':<24} success {sum(right)} of {len(starts)}, confidently wrong {wrong}")


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    map_size(quick)
    success(quick)
