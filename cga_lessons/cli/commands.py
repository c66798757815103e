"""The ``cga-lessons`` command line.

Subcommands::

    cga-lessons lab                       open the course in JupyterLab (root-safe, on 127.0.0.1)
    cga-lessons map2d LOG                 line map of a CARMEN laser log: a PNG, the segments as CSV, the
                                          trajectory as a TUM file, and its error against the log's poses
    cga-lessons relocalize MAP_CSV LOG --scan-index K [K ...]
                                          where is the robot of scan K on a saved map (chapter 5)
    cga-lessons equations                 the equation registry as a table (--todo, --write-readme)
    cga-lessons export-html               the stored, executed notebooks as a static site, offline

Every subcommand that writes files checks every output path before any work
and refuses to overwrite a file, or to write through a symbolic link, unless
``--force`` is given (which replaces the link itself, never its target; a
folder where a file goes is refused even then); it writes its files in a
hidden temporary folder and moves them into place only when all of them are
complete (:mod:`cga_lessons.cli.io`).  Missing or malformed inputs give a
one-line error and exit status 1 (2 for a wrong command line).
``python -m cga_lessons`` runs the same program.
"""

from __future__ import annotations

import argparse
import csv
import importlib
import importlib.util
import math
import os
import shlex
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

from cga_lessons.errors import InvalidInputError
from cga_lessons.paths import PROJECT_ROOT

from .io import CLIError, StagedOutputs, check_output_dir, check_output_files  # CLIError lives beside the checks
from .segments_csv import read_segments_csv, write_segments_csv

__all__ = [
    "main",
    "build_parser",
]


def _non_negative_int(text):
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 0")
    return value


def _positive(kind):
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
        if not (value > 0 and math.isfinite(value)):
            raise argparse.ArgumentTypeError(f"{text!r} must be positive")
        return value

    return parse


# --------------------------------------------------------------------------- progress


class Progress:
    """A plain progress bar on a stream: redrawn in place on a terminal, a line every 10 % otherwise."""

    def __init__(self, total: int, label: str, stream=None, enabled: bool = True):
        self.total, self.label, self.enabled = max(int(total), 1), label, enabled
        self.stream = stream or sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.done, self._shown, self._last_draw, self._start = 0, -1, 0.0, time.monotonic()

    def update(self, done: int):
        self.done = min(max(int(done), self.done), self.total)
        if not self.enabled:
            return
        if self.tty:
            now = time.monotonic()
            if now - self._last_draw > 0.1 or self.done == self.total:
                self._last_draw = now
                self.stream.write("\r" + self._line())
                self.stream.flush()
        else:
            step = 10 * self.done // self.total
            if step > self._shown:
                self._shown = step
                self.stream.write(self._line() + "\n")
                self.stream.flush()

    def _line(self) -> str:
        frac = self.done / self.total
        bar = "#" * int(30 * frac)
        return f"{self.label} [{bar:<30}] {self.done}/{self.total} {time.monotonic() - self._start:5.1f} s"

    def close(self):
        self.update(self.total)
        if self.enabled and self.tty:
            self.stream.write("\n")
            self.stream.flush()


def _build_map_with_progress(scans, odometry, progress: Progress, **kwargs):
    from cga_lessons.mapping2d import build_map

    return build_map(scans, odometry, progress=lambda k, total: progress.update(k), **kwargs)


def _log_stem(path: Path) -> str:
    name = path.name
    for suffix in (".gz", ".log", ".txt"):
        name = name.removesuffix(suffix)
    return name or "map"


def _read_log(path):
    from cga_lessons.mapping2d import read_carmen_log

    try:
        return read_carmen_log(path)
    except InvalidInputError as exc:  # a missing, unreadable or malformed log: the message names the file
        raise CLIError(str(exc).removeprefix("read_carmen_log: path: ")) from None


def _read_map(path):
    try:
        return read_segments_csv(path)
    except InvalidInputError as exc:  # a missing or malformed map file: the message names the file
        raise CLIError(str(exc).removeprefix("read_segments_csv: path: ")) from None


# --------------------------------------------------------------------------- subcommands


def _cmd_lab(args) -> int:
    nbdir = Path(args.notebook_dir) if args.notebook_dir else PROJECT_ROOT / "notebooks"
    if not nbdir.is_dir():
        raise CLIError(f"no notebooks folder at {nbdir} (run from a checkout of the course, or pass --notebook-dir)")
    # The lab's root is the checkout (README.md, data/ and notebooks/ side by side), the notebooks' folder opened.
    root = nbdir.parent if nbdir.name == "notebooks" else nbdir
    cmd = [sys.executable, "-m", "jupyterlab", f"--ServerApp.root_dir={root}", "--ServerApp.ip=127.0.0.1"]
    if args.port:
        cmd.append(f"--ServerApp.port={args.port}")
    if args.no_browser:
        cmd.append("--no-browser")
    if (nbdir / "00_start_here.ipynb").is_file():
        cmd.append(f"--LabApp.default_url=/lab/tree/{(nbdir / '00_start_here.ipynb').relative_to(root).as_posix()}")
    if getattr(os, "geteuid", lambda: 1)() == 0:
        cmd.append("--allow-root")  # JupyterLab refuses to start as root without it
    if args.dry_run:
        print(shlex.join(cmd))
        return 0
    if importlib.util.find_spec("jupyterlab") is None:
        raise CLIError("JupyterLab is not installed: pip install -e . installs it with the course")
    if os.name == "posix":  # become JupyterLab: signals (Ctrl-C, a kill) reach the server, no orphan is left
        os.execv(cmd[0], cmd)
    try:
        return subprocess.call(cmd)
    except KeyboardInterrupt:
        return 130


def _cmd_map2d(args) -> int:
    import numpy as np

    from cga_lessons.mapping2d import odometry_repeats_poses, simulate_odometry, write_tum

    log_path = Path(args.log)
    stem = _log_stem(log_path)
    out = Path(args.out_dir)
    names = ("map.png", "segments.csv", "poses.csv", "trajectory.tum")
    files = [out / f"{stem}_{name}" for name in names]
    if args.seed is not None and args.odometry != "simulated":
        raise CLIError(f"--seed applies to --odometry simulated only (not --odometry {args.odometry})")
    check_output_dir(out)  # every output path before the (long) run, not after
    check_output_files(files, overwrite=args.force, force_hint="--force")
    log = _read_log(log_path)
    n = len(log) if args.limit is None else min(args.limit, len(log))
    scans, truth = log.scans[:n], log.poses[:n]
    if args.odometry == "simulated":
        seed = 0 if args.seed is None else args.seed
        odometry = simulate_odometry(truth, np.random.default_rng(seed))
        print(f"map2d: odometry simulated from the log's poses (laser.OdometryModel() drift, seed {seed})")
    elif args.odometry == "poses":
        odometry = truth
    else:
        odometry = log.odometry[:n]
        if odometry_repeats_poses(SimpleNamespace(poses=truth, odometry=odometry)):
            print(
                "map2d: note: the log's odometry equals its corrected poses (the odometry fields repeat the pose a "
                "SLAM back end settled on), so there is no drift to correct and the map shows no correction at work; "
                "try --odometry simulated --seed N (N = 0, 1, ...) to drive the builder with odometry that drifts"
            )
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
        with open(staged[2], "w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(["scan", "x", "y", "theta", "corrected", "n_matches"])
            for k, (p, c, m) in enumerate(zip(result.poses, result.corrected, result.n_matches)):
                w.writerow([k, f"{p[0]:.6f}", f"{p[1]:.6f}", f"{p[2]:.6f}", int(c), int(m)])
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


def _cmd_relocalize(args) -> int:
    try:
        reloc = importlib.import_module("cga_lessons.relocalization")
    except ModuleNotFoundError as exc:
        if exc.name != "cga_lessons.relocalization":
            raise
        raise CLIError(
            "relocalization (chapter 5) is not in this checkout yet: cga_lessons/relocalization/relocalizer.py"
        ) from None
    segments = _read_map(args.map_csv)
    log = _read_log(Path(args.log))
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


def _cmd_equations(args) -> int:
    from cga_lessons.equations import main as equations_main

    argv = ["--format", args.format] + (["--todo"] if args.todo else [])
    if args.write_readme:
        argv.append("--write-readme")
    if args.check_readme:
        argv.append("--check-readme")
    if args.readme:
        if not Path(args.readme).is_file():
            raise CLIError(f"no such README {args.readme!r}")
        argv += ["--readme", args.readme]
    return equations_main(argv)


def _cmd_export_html(args) -> int:
    from .export import export_html  # nbconvert and its template, loaded for this command only

    return export_html(args)


# --------------------------------------------------------------------------- the parser


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="cga-lessons",
        description="Conformal geometric algebra for robot mapping: the course's command line.",
    )
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    _add_lab_parser(sub)
    _add_map2d_parser(sub)
    _add_relocalize_parser(sub)
    _add_equations_parser(sub)
    _add_export_html_parser(sub)
    return ap


def _add_lab_parser(sub) -> None:
    """The ``lab`` command's arguments."""
    p = sub.add_parser("lab", help="open the course in JupyterLab", description="Open the notebooks in JupyterLab.")
    p.add_argument("--notebook-dir", help="the notebooks folder (default: the checkout's notebooks/)")
    p.add_argument("--port", type=int, help="port to listen on (default: JupyterLab's choice)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.add_argument("--dry-run", action="store_true", help="print the command instead of running it")
    p.set_defaults(func=_cmd_lab)


def _add_map2d_parser(sub) -> None:
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
    p.add_argument("--max-range", type=_positive(float), default=8.0, help="drop readings beyond this (m; default 8)")
    p.add_argument("--limit", type=_positive(int), metavar="N", help="use only the first N scans")
    p.add_argument(
        "--odometry",
        choices=("logged", "poses", "simulated"),
        default="logged",
        help="odometry for the builder: the log's odometry fields (default), its laser poses, or drift simulated "
        "from its poses (see --seed)",
    )
    p.add_argument(
        "--seed",
        type=_non_negative_int,
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
    p.set_defaults(func=_cmd_map2d)


def _add_relocalize_parser(sub) -> None:
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
    p.add_argument("--max-range", type=_positive(float), default=8.0, help="drop readings beyond this (m; default 8)")
    p.set_defaults(func=_cmd_relocalize)


def _add_equations_parser(sub) -> None:
    """The ``equations`` command's arguments."""
    p = sub.add_parser("equations", help="the equation registry as a table", description="The coverage table.")
    p.add_argument("--format", choices=("markdown", "text"), default="text", help="output format (default text)")
    p.add_argument("--todo", action="store_true", help="list only the equations still todo")
    p.add_argument("--write-readme", action="store_true", help="regenerate the table between the README's markers")
    p.add_argument("--check-readme", action="store_true", help="exit with status 1 when the README's table is stale")
    p.add_argument("--readme", help="README to write or check (default: the checkout's README.md)")
    p.set_defaults(func=_cmd_equations)


def _add_export_html_parser(sub) -> None:
    """The ``export-html`` command's arguments."""
    p = sub.add_parser(
        "export-html",
        help="the executed notebooks as a static site",
        description="Convert the stored, executed notebooks to HTML pages with an index, without executing them and "
        "without any script or style loaded from the network.",
    )
    p.add_argument("--out-dir", default="site", help="folder for the pages (default: site)")
    p.add_argument("--notebook-dir", help="the notebooks folder (default: the checkout's notebooks/)")
    p.add_argument("--include-solutions", action="store_true", help="also export teacher_solutions.ipynb")
    p.add_argument(
        "--mathjax-url",
        default="",
        help="MathJax 2.7 script to typeset formulas (default: the copy bundled into the site's mathjax/)",
    )
    p.add_argument("--force", action="store_true", help="overwrite existing pages")
    p.set_defaults(func=_cmd_export_html)


def main(argv=None) -> int:
    """Run the command line with the arguments ``argv`` (a list of strings; None: the process's own, ``sys.argv``);
    returns the exit status: 0 done, 1 an error the user can fix (printed on one line), 2 a wrong command line
    (argparse's usage message), 130 interrupted.

    Raises
    ------
    InvalidInputError
        ``argv`` is not a list (or tuple) of strings (or paths).
    """
    parser = build_parser()
    try:
        args = parser.parse_args(_argv(argv))
    except SystemExit as exc:  # argparse has printed the usage and the error (status 2), or the help (status 0)
        return exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except CLIError as exc:
        message = " ".join(str(exc).split("\n"))  # one line, whatever the message holds
        print(f"cga-lessons {args.command}: error: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"cga-lessons {args.command}: interrupted", file=sys.stderr)
        return 130


def _argv(argv):
    """The command-line arguments as a list of strings (None: the process's own)."""
    if argv is None:
        return None
    if not isinstance(argv, (list, tuple)):
        raise InvalidInputError(f"main: argv: expected a list of strings, got {type(argv).__name__} {argv!r:.40}")
    bad = [a for a in argv if not isinstance(a, (str, os.PathLike))]
    if bad:
        raise InvalidInputError(f"main: argv: expected strings, got {bad[0]!r:.40} ({type(bad[0]).__name__})")
    return [os.fspath(a) for a in argv]


if __name__ == "__main__":
    sys.exit(main())
