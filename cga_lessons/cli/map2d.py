"""``cga-lessons map2d``: the line map of a CARMEN laser log (chapter 3), its files and its error.

Writes ``LOG_map.png``, ``LOG_segments.csv``, ``LOG_poses.csv`` and ``LOG_trajectory.tum`` (the corrected
trajectory as a TUM file) together through :class:`~cga_lessons.cli.outputs.StagedOutputs`, every output path
checked before the (long) run, and prints the error (ATE, RPE per metre) of the trajectories against the log's poses.
"""

from __future__ import annotations

import csv
import math
import time
from pathlib import Path
from types import SimpleNamespace

from cga_lessons.errors import InvalidInputError

from .arguments import non_negative_int, positive
from .errors import CLIError
from .inputs import read_log
from .outputs import StagedOutputs, check_output_dir, check_output_files
from .progress import Progress
from .segments_csv import write_segments_csv

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    """The ``map2d`` command's arguments."""
    p = sub.add_parser(
        "map2d",
        help="build a line map from a CARMEN laser log",
        description="Read a CARMEN log (FLASER lines, plain or .gz), build the line map of chapter 3 and write "
        "LOG_map.png, LOG_segments.csv, LOG_poses.csv and LOG_trajectory.tum (the corrected trajectory as a TUM file); "
        "print its error (ATE, RPE per metre) against the log's poses.",
    )
    p.add_argument("log", help="CARMEN log file (.log or .log.gz)")
    p.add_argument("--out-dir", default=".", help="folder for the outputs (default: current folder)")
    p.add_argument("--max-range", type=positive(float), default=8.0, help="drop readings beyond this (m; default 8)")
    p.add_argument("--limit", type=positive(int), metavar="N", help="use only the first N scans")
    p.add_argument(
        "--odometry",
        choices=("logged", "poses", "simulated"),
        default="logged",
        help="odometry for the builder: the log's odometry fields (default), its laser poses, or drift simulated "
        "from its poses (see --seed)",
    )
    p.add_argument(
        "--seed",
        type=non_negative_int,
        metavar="N",
        help="random seed of --odometry simulated (default 0). The drift model (laser.OdometryModel()): a step of "
        "d metres turning a radians, from one logged pose to the next, is reported with noise N(0, 0.02^2 d) m on "
        "each axis and a heading error of 0.005 d (a steady drift) + N(0, 0.01^2 d + 0.03^2 |a|) rad; the steps "
        "are composed from the log's first pose",
    )
    p.add_argument("--method", choices=("plain", "conformal"), default="plain", help="section 3.1 or 3.2")
    p.add_argument(
        "--progress",
        choices=("auto", "always", "never"),
        default="auto",
        help="progress bar on stderr (auto: 100+ scans)",
    )
    p.add_argument("--force", action="store_true", help="overwrite existing output files")
    p.set_defaults(func=run)


def _build_map_with_progress(scans, odometry, progress: Progress, **kwargs):
    from cga_lessons.mapping2d import build_map

    return build_map(scans, odometry, progress=lambda k, total: progress.update(k), **kwargs)


def _log_stem(path: Path) -> str:
    name = path.name
    for suffix in (".gz", ".log", ".txt"):
        name = name.removesuffix(suffix)
    return name or "map"


def run(args) -> int:
    """Run ``map2d`` with the parsed arguments ``args``; returns the exit status."""
    import numpy as np

    from cga_lessons.mapping2d import write_tum

    log_path = Path(args.log)
    stem = _log_stem(log_path)
    out = Path(args.out_dir)
    names = ("map.png", "segments.csv", "poses.csv", "trajectory.tum")
    files = [out / f"{stem}_{name}" for name in names]
    if args.seed is not None and args.odometry != "simulated":
        raise CLIError(f"--seed applies to --odometry simulated only (not --odometry {args.odometry})")
    check_output_dir(out)  # every output path before the (long) run, not after
    check_output_files(files, overwrite=args.force, force_hint="--force")
    log = read_log(log_path)
    n = len(log) if args.limit is None else min(args.limit, len(log))
    scans, truth = log.scans[:n], log.poses[:n]
    odometry = _odometry(args, log, n)
    show = args.progress == "always" or (args.progress == "auto" and n >= 100)
    bar = Progress(n, f"map2d {stem}", enabled=show)
    t0 = time.perf_counter()
    try:
        result = _build_map_with_progress(scans, odometry, bar, method=args.method, max_range=args.max_range)
    except ValueError as exc:
        raise CLIError(f"cannot build the map: {exc}") from None
    bar.close()
    elapsed = time.perf_counter() - t0
    title = f"{log_path.name}: {n} scans, {len(result.segments)} segments"
    stamps = np.asarray(log.timestamps[:n], float)
    by_index = not (np.all(np.isfinite(stamps)) and np.all(np.diff(stamps) > 0))
    # all four files are written in a hidden folder and moved into place together, once all are complete
    with StagedOutputs(out, [f.name for f in files], overwrite=args.force, force_hint="--force") as stage:
        staged = [stage.path(f.name) for f in files]
        _draw_map(staged[0], result, truth, args.odometry, title, odometry=odometry)
        try:
            write_segments_csv(staged[1], result.segments)
            write_tum(staged[3], result.poses, np.arange(n, dtype=float) if by_index else stamps)
        except InvalidInputError as exc:
            raise CLIError(str(exc)) from None
        _write_poses_csv(staged[2], result)
        stage.commit()
    print(
        f"map2d: {n} scans -> {len(result.segments)} segments, {int(np.sum(result.corrected))} poses corrected "
        f"({elapsed:.1f} s)"
    )
    _print_trajectory_errors(odometry, result.poses, truth, args.odometry)
    if by_index:
        print(f"  (the log's timestamps do not increase strictly: {files[3].name} gives the scan index as the time)")
    for p in files:
        print(f"  wrote {p}")
    return 0


def _odometry(args, log, n: int):
    """The odometry driving the builder, as ``--odometry`` asks: the log's own fields (with a note when they only
    repeat its poses), its poses, or drift simulated from its poses with ``--seed``."""
    import numpy as np

    from cga_lessons.mapping2d import odometry_repeats_poses, simulate_odometry

    truth = log.poses[:n]
    if args.odometry == "simulated":
        seed = 0 if args.seed is None else args.seed
        odometry = simulate_odometry(truth, np.random.default_rng(seed))
        print(f"map2d: odometry simulated from the log's poses (laser.OdometryModel() drift, seed {seed})")
        return odometry
    if args.odometry == "poses":
        return truth
    odometry = log.odometry[:n]
    if odometry_repeats_poses(SimpleNamespace(poses=truth, odometry=odometry)):
        print(
            "map2d: note: the log's odometry equals its corrected poses (the odometry fields repeat the pose a "
            "SLAM back end settled on), so there is no drift to correct and the map shows no correction at work; "
            "try --odometry simulated --seed N (N = 0, 1, ...) to drive the builder with odometry that drifts"
        )
    return odometry


def _write_poses_csv(path, result) -> None:
    """The corrected poses, one a scan, with whether each was corrected and how many matches it had."""
    with open(path, "w", newline="", encoding="utf-8") as f:  # in the staged folder: moved in once complete
        w = csv.writer(f)
        w.writerow(["scan", "x", "y", "theta", "corrected", "n_matches"])
        for k, (p, c, m) in enumerate(zip(result.poses, result.corrected, result.n_matches)):
            w.writerow([k, f"{p[0]:.6f}", f"{p[1]:.6f}", f"{p[2]:.6f}", int(c), int(m)])


def _print_trajectory_errors(odometry, corrected, truth, source: str):
    """The ATE and the RPE per metre of the odometry and of the corrected poses against the log's poses."""
    import numpy as np

    from cga_lessons.mapping2d import absolute_trajectory_error, relative_pose_error

    travelled = float(np.sum(np.hypot(*np.diff(truth[:, :2], axis=0).T))) if len(truth) > 1 else 0.0
    print(
        f"  error against the log's poses ({len(truth)} poses, {travelled:.1f} m travelled; ATE without alignment, "
        "both start at the log's first pose; RPE over 1 m segments of the log's path):"
    )
    rows = [("corrected", corrected)]
    if source != "poses":
        rows.insert(0, (f"{source} odometry", odometry))
    for label, poses in rows:
        ate = absolute_trajectory_error(poses, truth)
        text = f"    {label + ':':20} ATE {ate.position_rmse:.3f} m RMS"
        text += f", heading {math.degrees(ate.heading_rmse):.2f} deg RMS"
        if travelled >= 1.0:
            rpe = relative_pose_error(poses, truth, delta=1.0)
            text += f"; RPE {100 * rpe.translation_per_metre:.2f} cm/m, {math.degrees(rpe.heading_per_metre):.3f} deg/m"
        else:
            text += "; RPE: the log's poses travel less than 1 m"
        print(text)


def _draw_map(path, result, log_poses, odometry_source, title, odometry=None):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from cga_lessons.viz.laser import draw_segments, draw_trajectory

    fig = Figure(figsize=(8, 8), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    draw_segments(result.segments, ax=ax, lw=1.0, ends=False, label="line map")
    if odometry_source == "simulated" and odometry is not None:
        draw_trajectory(odometry, ax=ax, color="tab:purple", lw=0.6, ls="--", label="simulated odometry")
    if odometry_source != "poses":
        draw_trajectory(log_poses, ax=ax, color="0.6", lw=0.8, ls=":", label="the log's poses")
    draw_trajectory(result.poses, ax=ax, color="tab:green", lw=0.8, label="corrected")
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
