"""Two laser scans registered by the motor that fits their corresponding points (iterative closest points).

Chapter 3 of the thesis registers scans through their *lines* (3.4-3.12).
This module does it with the scans' raw points and one closed-form step from
:func:`cga_lessons.conformal.motor_estimation.motor_from_points`: pair every point of
the second scan with the closest point of the first scan's *outline* (its
consecutive points joined where they lie on one surface), fit the motor of
those pairs, move the scan, pair again (Besl & McKay 1992, "A method for
registration of 3-D shapes", closest points on the shape rather than on its
samples, which a laser's beams space centimetres to decimetres apart; the fit
is Horn's / Valkenburg & Dorst's, here in the plane).  Each round re-fits the whole motor from the original points,
so round-off does not pile up over the rounds.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> rng = np.random.default_rng(0)
    >>> wall = np.column_stack([np.linspace(0, 4, 200), np.zeros(200)])
    >>> room = np.vstack([wall, wall[:, ::-1], wall + [0, 4], wall[:, ::-1] + [4, 0]])
    >>> c, s = np.cos(0.1), np.sin(0.1)
    >>> seen = (room - [0.2, 0.1]) @ np.array([[c, -s], [s, c]])  # the room seen from (0.2, 0.1, 0.1 rad)
    >>> reg = register_scans(seen, room)
    >>> reg.pose.round(4), bool(reg.converged)
    (array([0.2, 0.1, 0.1]), True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, Multivector
from cga_lessons.conformal import apply_to_points, motor, motor_from_points, motor_to_matrix

from .poses import wrap_unchecked

__all__ = ["IcpParams", "ScanRegistration", "register_scans"]


@dataclass(frozen=True)
class IcpParams:
    """Settings of :func:`register_scans`.

    Attributes
    ----------
    max_iterations : int
        Rounds of pairing and fitting (100).  Closest-point iterations converge
        linearly, slowly along walls: from a start 10 cm and 3 degrees off, the
        simulated scans of the bundled scenes (1 cm noise) took 16 to 64 rounds.
    max_distance : float
        Pairs farther apart than this (m) are dropped in the first round: the
        largest error of the starting pose the method is asked to undo.  0.5 m
        is the position error that wheel odometry reaches over a few metres of
        travel (the drift model of :class:`cga_lessons.mapping2d.laser.OdometryModel`:
        2 cm per metre plus what a heading error of a few degrees does at a
        few metres' range).
    trim : float
        After the first round a pair is kept when its distance is within
        ``trim`` times the median pair distance (a robust 3-sigma-like cut: a
        point whose partner is a different wall, or a part of the room only
        one scan sees, is not pulled on).
    link : float
        Two consecutive target points are joined into the scan's outline when
        they are at most ``link`` times the median spacing of consecutive
        points apart (3: a wall seen at a grazing angle spreads its points a
        few times wider; a jump of more is an occlusion edge, not a surface).
    tolerance : (float, float)
        Stop when a round moves the scan by less than this (m, rad): 0.1 mm
        and 10 microradians, far below a laser's centimetre noise.
    """

    max_iterations: int = 100
    max_distance: float = 0.5
    trim: float = 3.0
    link: float = 3.0
    tolerance: tuple = (1e-4, 1e-5)

    def __post_init__(self):
        f = "IcpParams"
        checks.integer(self.max_iterations, f, "max_iterations", low=1)
        for name in ("max_distance", "trim", "link"):
            checks.real(getattr(self, name), f, name, low=0.0, strict_low=True)
        if min(checks.array(self.tolerance, f, "tolerance", (2,))) < 0:
            raise checks.fail(f, "tolerance", f"must be two numbers >= 0 (m, rad), got {self.tolerance!r}")


@dataclass(frozen=True)
class ScanRegistration:
    """The result of :func:`register_scans`.

    Attributes
    ----------
    motor : Multivector
        The motor M with ``target ~ M source ~M`` (points lifted to z = 0).
    pose : ndarray, shape (3,)
        The same motion as ``(x, y, theta)``: the pose of the source scan's
        frame in the target scan's frame.
    rms : float
        Root-mean-square distance (m) of the kept pairs at the end.
    pairs : int
        Number of kept pairs at the end.
    iterations : int
    converged : bool
        The last round moved the scan by less than the tolerance.
    """

    motor: Multivector
    pose: np.ndarray
    rms: float
    pairs: int
    iterations: int
    converged: bool


def _planar(points, func: str, name: str) -> np.ndarray:
    arr = checks.magnitude(checks.array(points, func, name, (None, 2)), func, name)
    if len(arr) < 3:
        raise checks.degenerate(func, name, f"needs at least 3 points, got {len(arr)}")
    if np.all(arr == arr[0]):
        raise checks.degenerate(func, name, "all its points coincide")
    return arr


def _closest_on_polyline(tree, tgt, link, q):
    """The closest point to each of ``q`` on the target's polyline, and its distance.

    The polyline joins consecutive target points where ``link[i]`` (points
    ``i`` and ``i + 1`` lie on one surface); the closest vertex (k-d tree)
    is refined onto the two segments that meet there.
    """
    _, j = tree.query(q)
    best = tgt[j]
    dist = np.hypot(*(q - best).T)
    n = len(tgt)
    for lo in (j - 1, j):  # the segment before and the one after the vertex
        ok = (lo >= 0) & (lo < n - 1)
        ok[ok] &= link[lo[ok]]
        a, b = tgt[np.clip(lo, 0, n - 2)], tgt[np.clip(lo + 1, 0, n - 1)]
        ab = b - a
        t = np.einsum("ij,ij->i", q - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
        c = a + np.clip(t, 0.0, 1.0)[:, None] * ab
        d = np.hypot(*(q - c).T)
        better = ok & (d < dist)
        best = np.where(better[:, None], c, best)
        dist = np.where(better, d, dist)
    return best, dist


def _pose_of(M: Multivector) -> np.ndarray:
    H = motor_to_matrix(M)
    return np.array([H[0, 3], H[1, 3], np.arctan2(H[1, 0], H[0, 0])])


def register_scans(source, target, initial=(0.0, 0.0, 0.0), params: IcpParams | None = None) -> ScanRegistration:
    """Register scan ``source`` (N, 2) on scan ``target`` (K, 2) by iterative closest points and motors.

    Each round pairs every moved source point with its nearest target point
    (a k-d tree), keeps the pairs within the round's distance (``max_distance``
    at first, then ``trim`` times the median), and fits the planar motor of
    the kept pairs in closed form (:func:`~cga_lessons.conformal.motor_estimation.motor_from_points`,
    the motor of (2.102) that minimises the summed squared distances).

    Parameters
    ----------
    source, target : array_like, shape (N, 2) and (K, 2)
        The scans' points in their own frames (metres, finite).
    initial : array_like, shape (3,)
        Starting guess ``(x, y, theta)`` of the source frame in the target
        frame, e.g. from odometry.
    params : IcpParams, optional

    Returns
    -------
    ScanRegistration

    Raises
    ------
    InvalidInputError
        Wrong shapes, NaN/inf.
    DegenerateGeometryError
        Fewer than 3 points, or fewer than 3 pairs within the pairing
        distance (the start is too far off, or the scans do not overlap).
    """
    func = "register_scans"
    p = IcpParams() if params is None else checks.instance(params, func, "params", IcpParams, "an IcpParams or None")
    src, tgt = _planar(source, func, "source"), _planar(target, func, "target")
    x0 = checks.magnitude(checks.array(initial, func, "initial", (3,)), func, "initial")
    tree = cKDTree(tgt)
    gaps = np.hypot(*np.diff(tgt, axis=0).T)
    link = gaps <= p.link * np.median(gaps)
    src3 = np.column_stack([src, np.zeros(len(src))])
    M = motor([0.0, 0.0, 1.0], float(x0[2]), [float(x0[0]), float(x0[1]), 0.0])
    pose, limit, kept, rms, converged = x0.copy(), p.max_distance, 0, np.inf, False
    rounds = 0
    for _ in range(p.max_iterations):
        rounds += 1
        moved = apply_to_points(M, src3)[:, :2]
        near, d = _closest_on_polyline(tree, tgt, link, moved)
        keep = d <= limit
        kept = int(keep.sum())
        if kept < 3:
            raise DegenerateGeometryError(
                f"{func}: source: only {kept} points lie within {limit:.3g} m of the target scan; "
                "the starting pose is too far off or the scans do not overlap"
            )
        with checks.relabel(func, "source, target"):
            M = motor_from_points(src[keep], near[keep])
        new = _pose_of(M)
        step = new - pose
        step[2] = wrap_unchecked(step[2])
        pose = new
        rms = float(np.sqrt(np.mean(d[keep] ** 2)))
        limit = min(p.max_distance, p.trim * float(np.median(d[keep])))
        if np.hypot(step[0], step[1]) < p.tolerance[0] and abs(step[2]) < p.tolerance[1]:
            converged = True
            break
    return ScanRegistration(M, pose, rms, kept, rounds, converged)
