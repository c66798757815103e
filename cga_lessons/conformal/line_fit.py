"""The least-squares line in the conformal model: the meet of the two best planes (section 4.1).

A point lies on a line exactly when ``x . pi = 0`` for every plane pi of the pencil through it.  The plane problem
of :func:`~cga_lessons.conformal.fit_plane` (``min sum (x_i . pi)^2`` over ``pi = n + delta e`` with
``pi^2 = |n|^2 = 1``, delta eliminated in closed form) therefore has a two-dimensional near-null space for points on
a line: its two smallest eigenvectors are two orthogonal planes through the line, and their outer product is the
line.  It is the total-least-squares line: through the points' centroid along their principal direction.
:func:`fit_line` returns it as a :class:`LineFit`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector

from .blades_classify import classify
from .entities import plane, point_pair
from .fitting import VECTOR_BLADES, VECTOR_METRIC, checked_points
from .lines_circles import line_closest_point, line_direction, line_from_points
from .multivector_checks import multivector
from .points import up

__all__ = ["LineFit", "fit_line"]


def _entity(X, func: str, name: str, kind: str, dimension: int) -> Multivector:
    """``X`` if it is one real entity of that kind ("flat": a line; "round" of dimension 0: a point pair)."""
    X = multivector(X, func, name, single=True, numeric=True)
    with checks.relabel(func, name):
        got = classify(X)
    kinds = ("flat", "dual flat") if kind == "flat" else (kind,)
    if got.kind not in kinds or got.dimension != dimension or got.imaginary:
        what = "a line" if kind == "flat" else "a point pair"
        raise checks.fail(func, name, f"expected {what}, got a {got.kind} of dimension {got.dimension}")
    return X


def _line(X, func: str, name: str) -> Multivector:
    return _entity(X, func, name, "flat", 1)


def _point_pair(X, func: str, name: str) -> Multivector:
    return _entity(X, func, name, "round", 0)


def _ends(value, func: str, name: str) -> np.ndarray:
    return checks.array(value, func, name, (2, 3))


@dataclass(frozen=True, eq=False)
class LineFit:
    """A line fitted to points (:func:`fit_line`).

    Attributes
    ----------
    blade : Multivector
        The line ``e ^ a ^ b`` (2.81), dual form, through ``ends``.
    pair : Multivector
        The point pair ``a ^ b`` (2.68) of the ends: where to draw it.
    direction : ndarray (3,)
        Unit direction (2.127), its largest component positive.
    point : ndarray (3,)
        The foot of the points' centroid on the line (the centroid, to round-off).
    ends : ndarray (2, 3)
        ``a`` and ``b``: the projections of the extreme points onto the line.
    rms : float
        RMS distance (m) of the points from the line.
    """

    blade: Multivector
    pair: Multivector
    direction: np.ndarray
    point: np.ndarray
    ends: np.ndarray
    rms: float

    def __post_init__(self):
        checks.record(self, direction=checks.vector3, point=checks.vector3, ends=_ends, rms=checks.length,
                      blade=_line, pair=_point_pair)  # fmt: skip


def fit_line(X) -> LineFit:
    """Conformal least-squares line through points X (N, 3): the meet of the two best planes, ``L = pi1 ^ pi2``
    (2.77, 2.81, 2.89), the total-least-squares line.

    The points are moved to their centroid and scaled to unit RMS radius (a similarity); the two smallest
    eigenvectors of the plane problem (the Schur complement of its distance, the covariance of the points) are two
    orthogonal planes through the line (2.89).  Direction (2.127, its largest component made positive) and the point
    nearest the origin (2.129) are read from their outer product; ``point`` is the foot of the centroid, ``ends``
    the projections of the extreme points, kept as the line ``e ^ a ^ b`` (2.81) and the point pair ``a ^ b``
    (2.68) that says where to draw it.

    Returns
    -------
    LineFit
        ``blade``, ``pair``, ``direction`` (3,), ``point`` (3,), ``ends`` (2, 3), ``rms`` (m).

    Raises a :class:`~cga_lessons.algebra.DegenerateGeometryError` for fewer than 2 points or points that coincide.

    >>> f = fit_line([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [3.0, 0.0, 1.0]])
    >>> f.direction.round(12) + 0.0, f.ends.round(12) + 0.0, f.rms < 1e-12
    (array([1., 0., 0.]), array([[0., 0., 1.],
           [3., 0., 1.]]), True)
    """
    func = "fit_line"
    X = checked_points(X, func, 2)
    c = X.mean(axis=0)
    k = np.sqrt(np.mean(np.sum((X - c) ** 2, axis=1)))
    if not k > 1e-12 * max(1.0, np.abs(X).max()):
        raise checks.degenerate(func, "X", "all points coincide")
    D = up((X - c) / k).to_array(VECTOR_BLADES)  # conformal points (2.62), normalised cloud
    A = np.column_stack([(D @ VECTOR_METRIC)[:, :3], -np.ones(len(X))])  # x . (n + delta e) = x . n - delta
    M = A.T @ A
    b, m = M[:3, 3], M[3, 3]
    _, V = np.linalg.eigh(M[:3, :3] - np.outer(b, b) / m)  # Schur complement: delta = -b . n / m
    planes = [plane(V[:, j], k * (-b @ V[:, j] / m) + c @ V[:, j]) for j in (0, 1)]  # (2.89)
    L = planes[0] ^ planes[1]  # standard form of the line
    r = np.asarray(line_direction(L), float)  # (2.127)
    r = -r if r[np.argmax(np.abs(r))] < 0 else r
    p0 = np.asarray(line_closest_point(L), float)  # (2.129)
    point = p0 + ((c - p0) @ r) * r
    w = X - point
    t = w @ r
    rms = float(np.sqrt(np.mean(np.sum((w - np.outer(t, r)) ** 2, axis=1))))
    ends = point + np.outer([t.min(), t.max()], r)
    return LineFit(blade=line_from_points(ends[0], ends[1]), pair=point_pair(ends[0], ends[1]), direction=r,
                   point=point, ends=ends, rms=rms)  # fmt: skip
