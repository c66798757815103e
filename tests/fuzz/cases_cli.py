"""Fuzz cases of the command line's Python face (cga_lessons.cli): ``main``, its parser and the segments CSV.

``main`` is called with ``lab --dry-run`` (it prints the command that would start JupyterLab and starts nothing);
its spoiled command lines are the wrong kinds of ``argv`` (a string, a number; None reads the process's own
command line, which is no command of this program: status 2).  The map files are written into fresh folders.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from cga_lessons import cli
from cga_lessons.mapping2d import Segment, SegmentSet
from fuzz.harness import Case, temporary_folder

_DIR = temporary_folder("cga-fuzz-cli-")

SEGS = [Segment([0.0, 0.0], [2.0, 0.0], 10, None, True, False), Segment([2.0, 0.0], [2.0, 1.5], 8)]
MAP = _DIR / "map.csv"
cli.write_segments_csv(MAP, SEGS)


def _fresh_path(stem: str):
    """A path that does not exist yet (a new one for every call)."""
    return Path(tempfile.mkdtemp(dir=_DIR)) / stem


CASES = [
    Case(cli.main, {"argv": ["lab", "--dry-run", "--no-browser"]}, extra={"argv": [["lab", 3], [None]]}),
    Case(cli.build_parser, {}),
    Case(cli.read_segments_csv, {"path": MAP}),
    Case(
        cli.write_segments_csv,
        lambda: {"path": _fresh_path("map.csv"), "segments": SEGS, "overwrite": False},
        kinds={"segments": [SegmentSet.from_segments(SEGS), SEGS[0], [SEGS[0], "text"]]},
        strict=True,
    ),
]

EXEMPT: dict[str, str] = {}
