"""Exercises of the exploration document (notebook 10): tangent bearings, crossings of a path, and (3.1).

Truths are plane geometry written out here: bearings by atan2 and arcsin, the crossings of a line and a
circle by the quadratic formula, the owner of a cell by flooring coordinates.
"""

from __future__ import annotations

import math

import numpy as np

from .answers import Wrong, as_array
from .checking import exercise


def _wrap(a):
    return (np.asarray(a, float) + np.pi) % (2 * np.pi) - np.pi


_ROBOT, _OBSTACLE, _RADIUS = np.array([0.0, 0.0]), np.array([-63.0, 6.0]), 7.5


@exercise(
    "expl.1",
    title="the bearings of the two tangents from the robot at (0, 0) to the circle of radius 7.5 cm at (-63, 6)",
    notebook="10_exploration",
    kind="compute",
    expects="a NumPy array of shape (2,): two angles in radians, in any order",
    equations=("exploration 3.1.2",),
)
def _expl_1(answer):
    got = as_array(answer, (2,))
    rel = _OBSTACLE - _ROBOT
    d = float(np.hypot(*rel))
    beta = math.atan2(rel[1], rel[0])
    half = math.asin(_RADIUS / d)  # the tangent touches the circle at a right angle to the radius
    truth = np.array([beta - half, beta + half])

    def same(a, b, tol=1e-6):  # the same two angles modulo 2 pi, in either order
        a, b = np.asarray(a, float), np.asarray(b, float)
        return any(bool(np.all(np.abs(_wrap(a - c)) < tol)) for c in (b, b[::-1]))

    if same(got, truth):
        return "beta_c -/+ arcsin(r/d): the tangent is at a right angle to the radius at the point where it touches."
    if same(np.radians(got), truth):
        raise Wrong("it looks like degrees; give radians.")
    if same(got, np.array([beta - math.atan(_RADIUS / d), beta + math.atan(_RADIUS / d)])):
        raise Wrong(
            "that uses arctan(r/d). The radius to the point of contact is perpendicular to the tangent, "
            "so r/d is a sine."
        )
    if np.all(np.abs(_wrap(got - beta)) < 1e-6):
        raise Wrong("both angles are the bearing of the centre; the tangents lie on either side of it.")
    if same(got, np.array([-beta - half, -beta + half])) or same(
        got, np.array([beta + math.pi - half, beta + math.pi + half])
    ):
        raise Wrong("the bearing of the centre is off: use atan2(y, x) of the centre seen from the robot.")
    mid = _wrap(np.angle(np.exp(1j * got).sum()))
    if abs(_wrap(mid - beta)) < 1e-6:
        raise Wrong("the two angles are centred on the right bearing, but their spread is off.")
    raise Wrong("the bearings are off.")


_START, _GOAL, _CENTRE, _R = np.array([0.0, 0.0]), np.array([100.0, 20.0]), np.array([50.0, 5.0]), 12.0


@exercise(
    "expl.2",
    title="where the path from (0, 0) to (100, 20) crosses the circle of radius 12 at (50, 5): exploration (3.2)-(3.3)",
    notebook="10_exploration",
    kind="compute",
    expects="a NumPy array of shape (2, 2): the two crossing points, in any order",
    equations=("exploration 3.2", "exploration 3.3"),
)
def _expl_2(answer):
    got = as_array(answer, (2, 2))
    u = _GOAL - _START
    w = _START - _CENTRE
    a, b, c = u @ u, 2 * u @ w, w @ w - _R**2  # |S + s u - C|^2 = r^2
    root = math.sqrt(b * b - 4 * a * c)
    truth = np.array([_START + (-b - root) / (2 * a) * u, _START + (-b + root) / (2 * a) * u])
    if np.allclose(got, truth, atol=1e-6) or np.allclose(got, truth[::-1], atol=1e-6):
        return "Substituting the line into the circle leaves a quadratic; its two roots are the crossings."
    if np.allclose(got, got[0], atol=1e-9):
        raise Wrong("both rows are the same point; there are two crossings.")
    on_circle = np.abs(np.hypot(*(got - _CENTRE).T) - _R) < 1e-6
    rel = got - _START
    on_line = np.abs(u[0] * rel[:, 1] - u[1] * rel[:, 0]) / math.hypot(*u) < 1e-6
    if np.allclose(got[:, ::-1], truth, atol=1e-6) or np.allclose(got[::-1, ::-1], truth, atol=1e-6):
        raise Wrong("x and y are swapped in each row.")
    bad = [
        f"point {i + 1} is {'on' if on_circle[i] else 'not on'} the circle and {'on' if on_line[i] else 'not on'} "
        f"the line"
        for i in range(2)
        if not (on_circle[i] and on_line[i])
    ]
    raise Wrong("; ".join(bad) + ".")


_X0, _DELTA, _SHAPE = np.array([-120.0, -120.0, 0.0]), 30.0, np.array([9, 9, 2])


@exercise(
    "expl.3",
    title="a point where the L1-nearest node of (3.1) is not the node whose cell holds the point",
    notebook="10_exploration",
    kind="break",
    expects="a NumPy array of shape (3,): a point (cm) inside the workspace of make_grid()",
    equations=("exploration 3.1",),
)
def _expl_3(answer):
    p = as_array(answer, (3,))
    ijk = np.floor((p - _X0) / _DELTA).astype(int)
    if np.any(ijk < 0) or np.any(ijk >= _SHAPE):
        raise Wrong("the point is outside the cells of the workspace (x, y in [-120, 150), z in [0, 60)).")
    axes = [_X0[k] + _DELTA * np.arange(_SHAPE[k]) for k in range(3)]
    nodes = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    B = np.abs(nodes - p).sum(axis=1)  # exploration (3.1)
    best = np.flatnonzero(B <= B.min() + 1e-9)
    owner = _X0 + _DELTA * ijk
    if len(best) > 1:
        raise Wrong(f"{len(best)} nodes are equally near in L1 distance; pick a point where the nearest is unique.")
    if np.allclose(nodes[best[0]], owner):
        raise Wrong("here the L1-nearest node is the cell's own node; try points farther from the node's corner.")
    return "The node owns the cell on its upper side, so a point past the middle of a cell is nearer to the next node."
