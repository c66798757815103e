"""Does map building slow down as the map grows?  Milliseconds per scan per block of scans, and where they go.

Run: ``python benchmarks/bench_growth.py`` (the Intel log three times over, 2,730 scans, then each of the six
logs once: a few minutes on one core); ``--quick`` for the Intel log twice over, 600 scans of each lap;
``--laps 6`` for a Freiburg-sized run (5,460 scans); ``--logs intel,csail`` to choose the single-lap logs
(``--logs none`` for none); ``--profile`` to add cProfile's top functions.

The laps are the log's scans and poses repeated (the robot drives the same building again, so every later lap
revisits the first; the Intel log ends 1.2 m from where it starts, so each new lap begins with that jump in the
truth, which the odometry repeats with its drift).  Odometry is simulated from the repeated poses as in
``benchmarks/bench_logs.py`` (``laser.simulate_odometry(poses, np.random.default_rng(seed))``, whose drift
keeps growing over the laps), and the map is built by ``mapping2d.build_map(scans, odometry, max_range=8.0)``
in this process.

Per block (``--block``, default 250 scans) it prints the milliseconds per scan, the map's size and the
exclusive time per scan of each stage (a stage's own time, its timed sub-stages taken out), measured by
wrapping the stages' functions with a timer (about 1 microsecond a call).  It prints numbers only; nothing is
asserted.  The machine's other jobs make single timings noisy: compare blocks within one run.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import sys
import time
from collections import defaultdict

import numpy as np

from cga_lessons import data_path, mapping2d
from cga_lessons.mapping2d import builder as builder_mod
from cga_lessons.mapping2d import correction as correction_mod
from cga_lessons.mapping2d import graph as graph_mod
from cga_lessons.mapping2d import loops as loops_mod

LOGS = ("intel", "aces", "csail", "freiburg-101", "seattle", "orebro")
MAX_RANGE = 8.0

# (label, owner, attribute): the stages timed, wrapped in place while a build runs
STAGES = (
    ("extract", mapping2d, "extract_segments"),
    ("learn odometry", correction_mod.ScanCorrector, "learn_odometry"),
    ("correct", builder_mod.MapBuilder, "correct"),
    ("support", builder_mod.MapBuilder, "support"),
    ("near", builder_mod.MapBuilder, "near"),
    ("fuse", builder_mod.MapBuilder, "fuse"),
    ("loop search", loops_mod.LoopCloser, "search"),
    ("find loop", loops_mod, "find_loop"),
    ("hypotheses", loops_mod, "loop_hypotheses"),
    ("visible", loops_mod, "visible_lines"),
    ("anchor", loops_mod, "anchor_scan"),
    ("graph optimize", graph_mod.PoseGraph, "optimize"),
    ("refit", builder_mod.MapBuilder, "refit"),
    ("remove duplicates", builder_mod.MapBuilder, "remove_duplicates"),
)


LOOP_PREFIX = "l."  # a stage called by the revisit search (find_loop) is counted apart, under this prefix
COLUMNS = (
    ("extract", "extract"), ("learn", "learn odometry"), ("correct", "correct"), ("support", "support"),
    ("near", "near"), ("fuse", "fuse"), ("search", "loop search"), ("find", "find loop"),
    ("hyp", "l.hypotheses"), ("visible", "l.visible"), ("anchor", "l.anchor"), ("l.corr", "l.correct"),
    ("l.supp", "l.support"), ("l.near", "l.near"), ("graph", "graph optimize"), ("refit", "refit"),
    ("dups", "remove duplicates"),
)  # fmt: skip


class StageTimer:
    """Wraps the stages' functions; accumulates each one's exclusive time (its timed callees taken out)."""

    def __init__(self):
        self.total = defaultdict(float)
        self.calls = defaultdict(int)
        self._stack = []  # [label, start, time spent in timed callees]
        self._saved = []

    def wrap(self, label, fn):
        timer = self

        def timed(*args, **kwargs):
            inside = any(frame[0] == "find loop" for frame in timer._stack)
            timer._stack.append([LOOP_PREFIX + label if inside else label, time.perf_counter(), 0.0])
            try:
                return fn(*args, **kwargs)
            finally:
                lab, t0, inner = timer._stack.pop()
                dt = time.perf_counter() - t0
                timer.total[lab] += dt - inner
                timer.calls[lab] += 1
                if timer._stack:
                    timer._stack[-1][2] += dt

        return timed

    def __enter__(self):
        for label, owner, name in STAGES:
            fn = owner.__dict__[name] if isinstance(owner, type) else getattr(owner, name)
            self._saved.append((owner, name, fn))
            setattr(owner, name, self.wrap(label, fn))
        return self

    def __exit__(self, *exc):
        for owner, name, fn in reversed(self._saved):
            setattr(owner, name, fn)
        self._saved.clear()

    def snapshot(self):
        return dict(self.total)


def load(name, laps=1, seed=0, limit=None):
    """Scans, true poses and simulated odometry of a log, its first ``limit`` scans repeated ``laps`` times."""
    log = mapping2d.read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
    n = len(log) if limit is None else min(limit, len(log))
    scans, truth = log.scans[:n] * laps, np.tile(log.poses[:n], (laps, 1))
    odometry = mapping2d.simulate_odometry(truth, np.random.default_rng(seed))
    return scans, truth, odometry


def run(name, laps, seed, block, limit=None, profile=False):
    """Build one map; print its blocks; return (ms per scan, result, truth, odometry)."""
    scans, truth, odometry = load(name, laps, seed, limit)
    T = len(scans)
    marks = [(0, time.perf_counter(), {})]
    timer = StageTimer()

    def progress(k, total):
        if k % block == 0 or k == total:
            marks.append((k, time.perf_counter(), timer.snapshot()))

    prof = cProfile.Profile() if profile else None
    with timer:
        t0 = time.perf_counter()
        if prof:
            prof.enable()
        result = mapping2d.build_map(scans, odometry, max_range=MAX_RANGE, progress=progress, record_history=True)
        if prof:
            prof.disable()
        ms = 1000 * (time.perf_counter() - t0) / T
    sizes = result.history
    short, labels = zip(*COLUMNS)
    print(f"\n{name} x{laps} ({T} scans, seed {seed}): {ms:.1f} ms/scan overall, {len(result.segments)} segments, "
          f"{len(result.loops)} loops; per block, ms per scan (exclusive, per stage):")  # fmt: skip
    print(f"{'scans':>11} {'ms/scan':>7} {'lines':>5} " + " ".join(f"{s:>6}" for s in short) + f" {'other':>6}")
    for (k0, t0_, s0), (k1, t1, s1) in zip(marks[:-1], marks[1:]):
        n = k1 - k0
        per = [1000 * (s1.get(lab, 0.0) - s0.get(lab, 0.0)) / n for lab in labels]
        total = 1000 * (t1 - t0_) / n
        print(f"{k0 + 1:5d}-{k1:5d} {total:7.1f} {sizes[k1 - 1]:5d} " + " ".join(f"{v:6.2f}" for v in per)
              + f" {total - sum(per):6.2f}")  # fmt: skip
    if prof:
        out = io.StringIO()
        pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(15)
        lines = [ln for ln in out.getvalue().splitlines() if ln.strip()]
        start = next(i for i, ln in enumerate(lines) if "ncalls" in ln)
        print("cProfile, top 15 by own time (s; the stage timer's wrappers included):")
        print("\n".join(lines[start : start + 16]))
    return ms, result, truth, odometry


def quality(result, truth, odometry, name, limit=None, laps=1):
    odo, _ = mapping2d.pose_errors(odometry, truth)
    rmse, _ = mapping2d.pose_errors(result.poses, truth)
    log = mapping2d.read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
    n = len(log) if limit is None else min(limit, len(log))
    cloud = mapping2d.scans_to_world(log.scans[:n], log.poses[:n], max_range=MAX_RANGE, step=3)
    errors = mapping2d.map_point_errors(result.segments, cloud)
    return odo / max(rmse, 1e-12), rmse, 100 * float(np.median(errors)) if len(errors) else np.inf


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="Intel, 600 scans a lap, two laps; no single-lap logs")
    ap.add_argument("--laps", type=int, default=3, help="laps of the Intel log (default 3: 2,730 scans)")
    ap.add_argument("--log", default="intel", help="the log repeated (default intel, the longest: 910 scans)")
    ap.add_argument("--logs", help="single-lap logs to time afterwards (default all six; 'none' for none)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--block", type=int, default=250, help="scans per block (default 250)")
    ap.add_argument("--profile", action="store_true", help="also run cProfile on the repeated log")
    args = ap.parse_args(argv)
    if args.laps < 1 or args.block < 1 or args.seed < 0:
        ap.error("--laps and --block must be >= 1, --seed >= 0")
    if args.log not in LOGS:
        ap.error(f"--log: unknown log {args.log!r} (choose from {', '.join(LOGS)})")
    logs = list(LOGS) if args.logs is None else [s.strip() for s in args.logs.split(",") if s.strip()]
    if logs == ["none"] or args.quick and args.logs is None:
        logs = []
    unknown = [s for s in logs if s not in LOGS]
    if unknown:
        ap.error(f"--logs: unknown log(s) {unknown} (choose from {', '.join(LOGS)})")
    return args, logs


def main(argv=None) -> int:
    args, logs = parse_args(argv)
    limit, laps = (600, 2) if args.quick else (None, args.laps)
    print(f"growth benchmark: build_map(max_range={MAX_RANGE:g}) in one process, odometry seed {args.seed}")
    ms, result, truth, odometry = run(args.log, laps, args.seed, args.block, limit, args.profile)
    ratio, rmse, map_cm = quality(result, truth, odometry, args.log, limit, laps)
    print(f"quality: ratio odometry/corrected {ratio:.1f}x, corrected RMSE {rmse:.3f} m, map median {map_cm:.1f} cm")
    if logs:
        print(f"\nsingle laps, seed {args.seed}, one process:")
        print(f"{'log':12} {'scans':>5} {'ms/scan':>7} {'ratio':>7} {'map cm':>6} {'loops':>5} {'lines':>5}")
    for name in logs:
        scans, truth, odometry = load(name, 1, args.seed)
        t0 = time.perf_counter()
        result = mapping2d.build_map(scans, odometry, max_range=MAX_RANGE)
        ms = 1000 * (time.perf_counter() - t0) / len(scans)
        ratio, _, map_cm = quality(result, truth, odometry, name)
        print(f"{name:12} {len(scans):5d} {ms:7.1f} {ratio:6.1f}x {map_cm:6.1f} {len(result.loops):5d} "
              f"{len(result.segments):5d}", flush=True)  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
