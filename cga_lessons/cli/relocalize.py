"""``cga-lessons relocalize``: where is the robot of a scan (or of a sequence of scans) on a saved line map
(chapter 5)."""

from __future__ import annotations

import importlib
import math
from pathlib import Path

from cga_lessons.errors import InvalidInputError

from .arguments import positive
from .errors import CLIError
from .inputs import read_log
from .segments_csv import read_segments_csv

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    """The ``relocalize`` command's arguments."""
    p = sub.add_parser(
        "relocalize",
        help="locate one scan of a log on a saved line map (chapter 5)",
        description="Find the pose of scan K of LOG on the map MAP_CSV (a segments CSV written by map2d).",
    )
    p.add_argument("map_csv", help="segments CSV written by map2d")
    p.add_argument("log", help="CARMEN log holding the scan")
    p.add_argument(
        "--scan-index",
        type=int,
        nargs="+",
        required=True,
        metavar="K",
        help="which scan of the log (0-based); several: relocalize them as a sequence with the log's odometry",
    )
    p.add_argument("--max-range", type=positive(float), default=8.0, help="drop readings beyond this (m; default 8)")
    p.set_defaults(func=run)


def _read_map(path):
    try:
        return read_segments_csv(path)
    except InvalidInputError as exc:  # a missing or malformed map file: the message names the file
        raise CLIError(str(exc).removeprefix("read_segments_csv: path: ")) from None


def run(args) -> int:
    """Run ``relocalize`` with the parsed arguments ``args``; returns the exit status."""
    try:
        reloc = importlib.import_module("cga_lessons.relocalization")
    except ModuleNotFoundError as exc:
        if exc.name != "cga_lessons.relocalization":
            raise
        raise CLIError(
            "relocalization (chapter 5) is not in this checkout yet: cga_lessons/relocalization/relocalizer.py"
        ) from None
    segments = _read_map(args.map_csv)
    log = read_log(Path(args.log))
    indices = list(args.scan_index)
    for k in indices:
        if not -len(log) <= k < len(log):
            raise CLIError(f"--scan-index {k} is out of range: {args.log} holds {len(log)} scans")
    k = indices[-1]
    try:
        if len(indices) == 1:
            found = reloc.relocalize(segments, scan=log.scans[k], max_range=args.max_range)
        else:  # a sequence: the scans with the log's odometry between them; the pose is the last scan's
            from cga_lessons.relocalization import relocalize_sequence

            scans = [log.scans[i] for i in indices]
            found = relocalize_sequence(segments, scans, log.odometry[indices], max_range=args.max_range)
    except ValueError as exc:
        raise CLIError(f"relocalization failed: {exc}") from None
    status = getattr(found, "status", "ok" if getattr(found, "pose", None) is not None else "failed")
    which = f"scan {k}" if len(indices) == 1 else f"scans {', '.join(map(str, indices))} (pose at scan {k})"
    where = f"{which} of {Path(args.log).name} on {Path(args.map_csv).name} ({len(segments)} segments)"
    print(f"relocalize: {where}: {status}")
    if found.pose is None:
        message = getattr(found, "message", "")
        print(f"  no pose found{': ' + message if message else ''}")
        return 0
    print(f"  pose (laser in the map frame): {_pose_text(found.pose)}, score {float(found.score):.3f}")
    print(f"  ambiguous: {'yes' if found.ambiguous else 'no'}")
    print(f"  (the log's own pose for this scan: {_pose_text(log.poses[k])})")
    others = list(getattr(found, "candidates", []))[1:]
    if found.ambiguous and others:
        print("  other candidates:")
        for c in others[:5]:
            print(f"    {_pose_text(c.pose)}, score {float(c.score):.3f}")
    return 0


def _pose_text(pose) -> str:
    x, y, th = (float(v) for v in pose)
    return f"x = {x:.3f} m, y = {y:.3f} m, theta = {math.degrees(th):.2f} deg"
