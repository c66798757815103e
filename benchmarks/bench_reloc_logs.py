"""Chapter 5 benchmark on real logs: relocalization in maps built from the rest of each log.

Run: ``python benchmarks/bench_reloc_logs.py [log ...] [--sparse] [--before] [--max-range R]`` (default: all six
CARMEN logs; ``--before``: the method without the coverage grid and the deficit rule of ``tie_bar``, for comparison).
Prints numbers only; nothing here is asserted.

The laser's reach is each log's own (:func:`cga_lessons.mapping2d.laser_facts.returns_reach`: the distance within
which 99 % of its returns fall, 13.5-30.6 m on these logs; the maps use the same reach); ``--max-range R`` sets one
reach for all (the table stored before measured 8 m: single scans 73.4 %, runs 76.9 %, wrong 1.6 %).

For each log (``data/carmen/<name>-corrected.log.gz``, the shared copy until it is there):

* single scans: every 7th scan (from the 4th) is held out, the map (lines and coverage grid,
  :func:`cga_lessons.relocalization.eval.reference_from_log`) is built at the logged poses from all
  the other scans, and each held-out scan is relocalized alone;
* runs of three: the scans ``k-2, k-1, k`` for every held-out ``k`` are held out, the map is built
  from the rest, and each run is relocalized with :func:`cga_lessons.relocalization.sequence.relocalize_sequence`
  on odometry simulated from the logged poses (:func:`cga_lessons.mapping2d.laser.simulate_odometry`, the
  project's drift model; the corrected logs log the poses as odometry), one drift per seed.

With ``--sparse`` the map leaves out two scans either side of every held-out scan and uses every
second of the rest (the defaults of :func:`cga_lessons.relocalization.eval.evaluate_log`): maps
with holes where the held-out scans are.

The full runs write their table to ``benchmarks/bench_reloc_logs[_sparse][_before].json`` (notebook 09 shows it).

A relocalization is *located* when it is confident and within 10 cm and 2 degrees of the logged
pose, *confidently wrong* when confident and not within them.  The totals are set against the
targets: runs of three >= 90 % located, single scans >= 75 %, confidently wrong <= 2 % of all.
"""

from __future__ import annotations

import json
import sys
import time
from multiprocessing import Pool
from pathlib import Path

import numpy as np

from cga_lessons import data_path
from cga_lessons.mapping2d import laser, read_carmen_log
from cga_lessons.mapping2d.laser_facts import returns_reach
from cga_lessons.relocalization.eval import evaluate_log
from cga_lessons.relocalization.lookaround import evaluate_log_sequences

LOGS = ("intel", "aces", "csail", "freiburg-101", "seattle", "orebro")
EVERY, FIRST, RUN = 7, 3, 3


def log_path(name):
    return data_path("carmen", f"{name}-corrected.log.gz")


def protocol(sparse):
    return dict(exclude=2, map_step=2) if sparse else dict(exclude=0, map_step=1)


#: The method as it was before the coverage grid and the deficit rule (``--before``).
BEFORE = dict(coverage=False, deficit_ratio=0.0)


def task(args):
    """One log's single scans (seed None) or one seed's runs of three: counts and times."""
    name, seed, sparse, before, reach, options = args
    kw = {**protocol(sparse), **(BEFORE if before else {}), **options}
    log = read_carmen_log(log_path(name))
    reach = returns_reach(log.ranges) if reach is None else reach
    held = np.arange(max(FIRST, RUN - 1), len(log), EVERY)
    t0 = time.perf_counter()
    if seed is None:
        ev, _ = evaluate_log(log, held, max_range=reach, **kw)
    else:
        odo = laser.simulate_odometry(log.poses, np.random.default_rng(seed))
        ev, _, _ = evaluate_log_sequences(
            log, held - (RUN - 1), length=RUN, stride=1, odometry=odo, max_range=reach, **kw
        )
    s = ev.summary()
    counts = (s.n, s.success, s.ambiguous, s.confidently_wrong, s.failed)
    return (name, seed, *counts, float(np.mean(ev.seconds)), time.perf_counter() - t0, reach)


def main(logs=None, seeds=(0, 1, 2, 3), sparse=False, before=False, processes=2, out=None, max_range=None, **options):
    """Run the benchmark on ``logs`` (names, default all six) and print the table and the totals.

    ``before``: the method without the coverage grid and the deficit rule, for comparison.
    ``out``: a JSON file to write the table to (notebook 09 shows it).
    ``max_range``: one reach (m) for every log; None: each log's own (``returns_reach``).
    ``options``: parameters of the relocalization (fields of a stage of
    :class:`cga_lessons.relocalization.RelocParams`) to try.
    """
    logs = list(logs or LOGS)
    jobs = [(n, None, sparse, before, max_range, options) for n in logs]
    jobs += [(n, s, sparse, before, max_range, options) for n in logs for s in seeds]
    jobs.sort(key=lambda j: -log_path(j[0]).stat().st_size)  # the big logs first: the two workers end together
    with Pool(processes) as pool:
        done = pool.map(task, jobs, chunksize=1)
    res = {(o[0], o[1]): o for o in done}
    which = "sparse maps (2 scans either side left out, every 2nd of the rest)" if sparse else "maps from the rest"
    method = "before (no coverage grid, no deficit rule)" if before else "with coverage grid"
    reach = "each log's reach" if max_range is None else f"reach {max_range:g} m"
    print(f"\nrelocalization on CARMEN logs, every {EVERY}th scan held out, {which}, {reach}, seeds {list(seeds)}")
    print(f"method: {method}")
    print(
        f"{'log':<13} {'reach m':>7} {'single n':>8} {'located':>8} {'ambig.':>7} {'wrong':>6} {'ms':>6}   "
        f"{'runs n':>7} {'located':>8} {'wrong':>6} {'ms/run':>7}"
    )
    tot = dict(sn=0, sl=0, sw=0, rn=0, rl=0, rw=0)
    table = {}
    for name in logs:
        _, _, n, ok, amb, wrong, _, sec, _, reach_m = res[(name, None)]
        runs = [res[(name, s)] for s in seeds]
        rn, rl, rw = (sum(r[i] for r in runs) for i in (2, 3, 5))
        rms = 1000 * np.mean([r[7] for r in runs]) if runs else float("nan")
        print(
            f"{name:<13} {reach_m:7.1f} {n:8d} {100 * ok / n:7.1f}% {100 * amb / n:6.1f}% {wrong:6d} "
            f"{1000 * sec:6.0f}   "
            f"{rn:7d} {100 * rl / max(rn, 1):7.1f}% {rw:6d} {rms:7.0f}"
        )
        table[name] = dict(
            reach=reach_m,
            single_n=n,
            single_located=ok,
            single_ambiguous=amb,
            single_wrong=wrong,
            single_ms=1000 * sec,
            runs_n=rn,
            runs_located=rl,
            runs_wrong=rw,
            runs_ms=rms,
        )
        tot["sn"] += n
        tot["sl"] += ok
        tot["sw"] += wrong
        tot["rn"] += rn
        tot["rl"] += rl
        tot["rw"] += rw
    single = tot["sl"] / tot["sn"]
    runs = tot["rl"] / max(tot["rn"], 1)
    wrong = (tot["sw"] + tot["rw"]) / (tot["sn"] + tot["rn"])
    print("totals against the targets:")
    print(
        f"  single scans located   {100 * single:5.1f} % of {tot['sn']} (target >= 75 %)  "
        f"{'PASS' if single >= 0.75 else 'FAIL'}"
    )
    print(
        f"  runs of three located  {100 * runs:5.1f} % of {tot['rn']} (target >= 90 %)  "
        f"{'PASS' if runs >= 0.90 else 'FAIL'}"
    )
    print(
        f"  confidently wrong      {100 * wrong:5.1f} % ({tot['sw']} single, {tot['rw']} runs) (target <= 2 %)  "
        f"{'PASS' if wrong <= 0.02 else 'FAIL'}"
    )
    if out is not None:
        doc = dict(protocol=which, method=method, every=EVERY, run=RUN, seeds=list(seeds), max_range=max_range)
        Path(out).write_text(json.dumps({**doc, "logs": table, "totals": tot}, indent=1) + "\n")
    return res


if __name__ == "__main__":
    argv = sys.argv[1:]
    max_range = None
    if "--max-range" in argv:
        i = argv.index("--max-range")
        try:
            max_range = float(argv[i + 1])
        except (IndexError, ValueError):
            sys.exit("--max-range needs a positive number of metres")
        if not max_range > 0:
            sys.exit("--max-range needs a positive number of metres")
        del argv[i : i + 2]
    args = [a for a in argv if not a.startswith("--")]
    before, sparse = "--before" in argv, "--sparse" in argv
    name = "bench_reloc_logs" + ("_sparse" if sparse else "") + ("_before" if before else "") + ".json"
    out = None if args or max_range is not None else Path(__file__).with_name(name)
    main(args or None, sparse=sparse, before=before, out=out, max_range=max_range)
