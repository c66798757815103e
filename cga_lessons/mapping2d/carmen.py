"""Laser logs in the CARMEN text format (chapter 3, section 3.1): their FLASER lines as scans and poses.

A log holds, per scan, ``n`` ranges over a fan of beams and two poses: the laser pose the log gives (the SLAM
solution in the "corrected" logs) and the odometry.  :func:`read_carmen_log` reads a plain or gzipped log;
every problem with the file (missing, binary, a truncated gzip stream, a malformed line) is one
:class:`~cga_lessons.algebra.InvalidInputError` naming the function, the ``path`` argument and, for a bad line,
its number; nothing is returned from a file that cannot be read whole.  :mod:`cga_lessons.mapping2d.laser`
re-exports both names.
"""

from __future__ import annotations

import gzip
import zlib
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError

from .inputs import reach
from .laser_facts import no_return_codes
from .poses import wrap_unchecked

__all__ = ["CarmenLog", "read_carmen_log"]


@dataclass
class CarmenLog:
    """The laser scans and poses of a CARMEN log.

    Attributes
    ----------
    ranges : ndarray, shape (T, n)
        Metres; ``inf`` where the beam returned nothing.
    angles : ndarray, shape (n,)
        Beam angles in the laser frame, radians.
    poses : ndarray, shape (T, 3)
        The logged laser pose of each scan (in the "corrected" logs: the SLAM
        solution, used as ground truth).
    odometry : ndarray, shape (T, 3)
        The logged odometry pose of each scan.
    timestamps : ndarray, shape (T,)
    laser_offset : float
        ``robot_frontlaser_offset`` from the log's PARAM lines (m), 0 if absent.
    no_return_codes : tuple of float
        The values the log uses to say "no return" that :func:`no_return_codes` found (their readings, and all
        readings above the smallest, are ``inf`` in ``ranges``).
    """

    ranges: np.ndarray
    angles: np.ndarray
    poses: np.ndarray
    odometry: np.ndarray
    timestamps: np.ndarray
    laser_offset: float = 0.0
    no_return_codes: tuple = ()

    def __post_init__(self):
        f = "CarmenLog"
        self.ranges = checks.array(self.ranges, f, "ranges", (None, None), finite=False)
        if np.isnan(self.ranges).any() or (self.ranges == -np.inf).any():
            raise checks.fail(f, "ranges", "holds NaN or -inf (a beam without return is +inf)")
        self.angles = checks.array(self.angles, f, "angles", (None,))
        if len(self.angles) != self.ranges.shape[1]:
            raise checks.fail(
                f, "ranges, angles", f"{self.ranges.shape[1]} ranges a scan but {len(self.angles)} angles"
            )
        self.poses = checks.array(self.poses, f, "poses", (None, 3))
        self.odometry = checks.array(self.odometry, f, "odometry", (None, 3))
        self.timestamps = checks.array(self.timestamps, f, "timestamps", (None,))
        checks.same_length(f, ranges=self.ranges, poses=self.poses, odometry=self.odometry, timestamps=self.timestamps)
        self.laser_offset = checks.real(self.laser_offset, f, "laser_offset")
        if not isinstance(self.no_return_codes, (tuple, list)):
            raise checks.fail(f, "no_return_codes", f"expected a tuple of numbers, got {self.no_return_codes!r}")
        self.no_return_codes = tuple(checks.real(v, f, "no_return_codes") for v in self.no_return_codes)

    @property
    def scans(self) -> list:
        """The scans as a list of ``(ranges, angles)`` pairs."""
        return [(r, self.angles) for r in self.ranges]

    def __len__(self):
        return len(self.ranges)


def read_carmen_log(path, *, no_return_range: float = 80.0, fov: float = np.pi, detect_codes: bool = True) -> CarmenLog:
    """Read the FLASER lines of a CARMEN log (plain text or gzip).

    Each line ``FLASER n r_1 ... r_n x y theta odom_x odom_y odom_theta
    timestamp host logger_timestamp`` is one scan of ``n`` beams from -90
    degrees (right) counter-clockwise: 1 degree apart for 180 or 181 beams,
    0.5 degree for 360 or 361 (as CARMEN's own reader assumes), otherwise
    spread evenly over ``fov``.  Other messages (ODOM, PARAM, NEFF, comments)
    are skipped.

    Parameters
    ----------
    path : str or Path
    no_return_range : float
        Ranges at or beyond this (m) mean "no return" and become ``inf``
        (SICK scanners in these logs report about 81.9 m).
    fov : float
        Field of view (radians, at most 2 pi) assumed for beam counts other than 180, 181, 360, 361.
    detect_codes : bool
        Also find the log's own "no return" values (:func:`no_return_codes`): their readings and any above the
        smallest become ``inf`` (recorded in ``CarmenLog.no_return_codes``).

    Returns
    -------
    CarmenLog

    Raises
    ------
    InvalidInputError
        Naming ``path``: a missing file or a folder, a file that cannot be read (binary, not text, a corrupt or
        truncated gzip stream), a malformed FLASER line (naming the line number), scans of different lengths,
        or a file with no FLASER line.
    """
    f = "read_carmen_log"
    path = checks.existing_path(path, f, "path")
    no_return_range = reach(no_return_range, f, "no_return_range")
    fov = checks.real(fov, f, "fov", low=0.0, strict_low=True, high=2 * np.pi)
    detect_codes = checks.flag(detect_codes, f, "detect_codes")
    opener = gzip.open if path.suffix == ".gz" else open
    try:
        with opener(path, "rt") as fh:
            ranges, poses, odom, stamps, offset = _read_lines(fh, path)
    except InvalidInputError:
        raise
    except (OSError, EOFError, UnicodeDecodeError, zlib.error) as exc:  # binary, a corrupt or truncated gzip stream
        raise checks.fail(f, "path", f"cannot read the log {str(path)!r}: {exc}") from None
    n_beams = ranges.shape[1]
    ranges[(ranges >= no_return_range) | (ranges <= 0)] = np.inf
    poses[:, 2] = wrap_unchecked(poses[:, 2])
    odom[:, 2] = wrap_unchecked(odom[:, 2])
    codes = no_return_codes(ranges) if detect_codes else ()
    if codes:
        ranges[ranges >= codes[0]] = np.inf
    return CarmenLog(ranges, _carmen_angles(n_beams, fov), poses, odom, stamps, offset, codes)


def _read_lines(lines, path):
    """The FLASER fields of a log's lines: ranges (T, n), poses (T, 3), odometry (T, 3), timestamps (T,), offset."""
    ranges, poses, odom, stamps, offset = [], [], [], [], 0.0
    n_beams = None
    for lineno, line in enumerate(lines, start=1):
        tok = line.split()
        if not tok or tok[0].startswith("#"):
            continue
        where = f"{path.name}, line {lineno}"
        if tok[0] == "PARAM" and len(tok) >= 3 and tok[1] == "robot_frontlaser_offset":
            try:
                offset = checks.real(float(tok[2]), "read_carmen_log", "path")
            except (ValueError, InvalidInputError):
                raise _bad(where, f"bad robot_frontlaser_offset {tok[2]!r}") from None
        if tok[0] != "FLASER":
            continue
        try:
            n = int(tok[1])
        except (IndexError, ValueError):
            raise _bad(where, "FLASER without a beam count") from None
        if n < 2 or len(tok) < n + 9:
            raise _bad(
                where, f"FLASER line truncated or malformed ({len(tok)} fields, expected {n + 11} for {n} beams)"
            )
        try:
            vals = np.array(tok[2 : n + 9], float)
        except ValueError as exc:
            raise _bad(where, f"non-numeric value in the FLASER fields ({exc})") from None
        if not np.all(np.isfinite(vals)):
            raise _bad(where, "non-finite value in the FLASER fields")
        if n_beams is None:
            n_beams = n
        elif n != n_beams:
            raise _bad(where, f"{n} beams, but earlier scans had {n_beams}")
        ranges.append(vals[:n].copy())
        poses.append(vals[n : n + 3])
        odom.append(vals[n + 3 : n + 6])
        stamps.append(vals[n + 6])
    if not ranges:
        raise checks.fail("read_carmen_log", "path", f"{path.name} holds no FLASER line")
    return np.array(ranges), np.array(poses), np.array(odom), np.array(stamps), offset


def _bad(where: str, problem: str) -> InvalidInputError:
    return checks.fail("read_carmen_log", "path", f"{where}: {problem}")


def _carmen_angles(n: int, fov: float) -> np.ndarray:
    """Beam angles as CARMEN's own log reader guesses them for old FLASER lines.

    180/181 beams are 1 degree apart and 360/361 beams 0.5 degree apart, from
    -90 degrees (CARMEN's ``carmen_laser_guess_angle_increment``); other counts
    are spread evenly over ``fov``.
    """
    step = {180: np.pi / 180, 181: np.pi / 180, 360: np.pi / 360, 361: np.pi / 360}.get(n)
    if step is None:
        return np.linspace(-fov / 2, fov / 2, n)
    return -np.pi / 2 + step * np.arange(n)
