"""Exercises of chapter 5 (notebook 09): a symmetric room, a translation from two lines, the printed shift (5.4).

The truths are the symmetry of a rectangle (a half turn about its centre), the Hough coordinates (3.3) of
lines moved by a known pose, written out with cosines and sines, and the pose the data were built from.
"""

from __future__ import annotations

import math

import numpy as np

from .answers import Wrong, as_array
from .checking import exercise
from .compare import compare_number, compare_vector

_TWO_PI = 2 * math.pi


def _wrap(a):
    return (np.asarray(a, float) + math.pi) % _TWO_PI - math.pi


# --------------------------------------------------------------------------- ch5.1: the symmetric room

_ROOM = (6.0, 4.0)  # the room of chapter 3: inner faces x in [0, 6], y in [0, 4]
_POSE = np.array([1.0, 2.5, -0.7])


#: An answer rounded to two decimals (metres, radians) is accepted as the exact one, and said to be rounded.
_ROUNDED = 0.006


def _same_pose(p, q, tol=1e-6) -> bool:
    return bool(np.all(np.abs(p[:2] - q[:2]) < tol) and abs(float(_wrap(p[2] - q[2]))) < tol)


@exercise(
    "ch5.1",
    title="the other pose from which the 6 m x 4 m room looks exactly as from (1.0, 2.5, -0.7)",
    notebook="09_relocalization",
    kind="break",
    expects="a NumPy array of shape (3,): (x, y, theta) in metres and radians",
    equations=("5.6",),
)
def _ch5_1(answer):
    p = as_array(answer, (3,))
    w, h = _ROOM
    c = np.array([w / 2, h / 2])
    truth = np.array([*(2 * c - _POSE[:2]), _POSE[2] + math.pi])  # the half turn about the centre
    exact = _same_pose(p, truth)
    if exact or _same_pose(p, truth, tol=_ROUNDED):
        rounded = (
            ""
            if exact
            else (
                f"To the rounding you gave: exactly ({truth[0]:g}, {truth[1]:g}, {truth[2]:.6f}), the heading plus pi. "
            )
        )
        return (
            f"{rounded}A rectangle maps onto itself by a half turn about its centre: every beam from there "
            "sees the same wall at the same range. No scan can tell the two poses apart; relocalize reports both."
        )
    if _same_pose(p, _POSE):
        raise Wrong("that is the pose itself; the exercise asks for the other one.")
    if np.allclose(p[:2], truth[:2], atol=_ROUNDED):
        if abs(float(_wrap(np.radians(p[2]) - truth[2]))) < _ROUNDED:
            raise Wrong("the position is right; the heading looks like degrees: give radians.")
        raise Wrong("the position is right but the heading is not: the robot must turn with the room.")
    if np.allclose(p[:2], _POSE[:2], atol=_ROUNDED):
        raise Wrong("turning on the spot changes what the laser sees: the position must move too.")
    mirrors = [
        np.array([w - _POSE[0], _POSE[1], math.pi - _POSE[2]]),
        np.array([_POSE[0], h - _POSE[1], -_POSE[2]]),
    ]
    if any(_same_pose(p, m) for m in mirrors):
        raise Wrong(
            "that is the mirror image of the pose: from there the scan is mirrored (the beams in the opposite "
            "order). A mirror is not a motion of the robot."
        )
    if not (0 < p[0] < w and 0 < p[1] < h):
        raise Wrong("that pose is outside the room.")
    raise Wrong("from that pose the room looks different (the distances to the walls along the beams change).")


# --------------------------------------------------------------------------- ch5.2 and ch5.3: two line pairs

_ROTATION, _T = 0.7, np.array([3.2, 1.4])
_SCAN = np.array([[1.1, 0.2], [2.4, 1.6]])  # (rho, theta) of two scan lines in the laser frame


def _moved(lines, rotation, t) -> np.ndarray:
    """(rho, theta) of lines x cos(theta) + y sin(theta) = rho after x -> R x + t, with rho >= 0 kept."""
    out = []
    for rho, th in lines:
        a = th + rotation
        r = rho + t[0] * math.cos(a) + t[1] * math.sin(a)
        if r < 0:
            r, a = -r, a + math.pi
        out.append([r, a % _TWO_PI])
    return np.array(out)


_MAP = _moved(_SCAN, _ROTATION, _T)


def _ch5_2_given():
    """The input of exercises ch5.2 and ch5.3.

    Returns
    -------
    rotation : float
        The rotation Theta (radians) the angle votes found.
    scan_lines : ndarray, shape (2, 2)
        ``(rho, theta)`` of two non-parallel scan lines, laser frame.
    map_lines : ndarray, shape (2, 2)
        ``(rho, theta)`` of the map lines they correspond to, map frame (row i matches row i).
    """
    return _ROTATION, _SCAN.copy(), _MAP.copy()


@exercise(
    "ch5.2",
    title="the translation t of the laser from two non-parallel line pairs and the rotation: exercises.given('ch5.2')",
    notebook="09_relocalization",
    kind="compute",
    expects="a NumPy array of shape (2,), metres",
    equations=("3.11", "3.12", "5.4"),
    given=_ch5_2_given,
)
def _ch5_2(answer):
    a = _SCAN[:, 1]
    unturned = np.linalg.solve(np.column_stack([np.cos(a), np.sin(a)]), _MAP[:, 0] - _SCAN[:, 0])
    compare_vector(
        answer,
        _T,
        hints=[
            (
                unturned,
                "the normals are those of the laser frame: turn them by the rotation first (the map's lines have "
                "angles theta + Theta).",
            ),
        ],
    )
    return (
        "Each pair gives one equation n(theta + Theta) . t = rho_map - rho_scan; two non-parallel lines fix both "
        "components of t exactly, which is what relocalize does for every rotation the votes propose."
    )


@exercise(
    "ch5.3",
    title="how far from m2 the printed shift (5.4) by m1 - l1 puts l2 (rho error, m), with the data of ch5.2",
    notebook="09_relocalization",
    kind="break",
    expects="a float: rho of the shifted l2 minus rho of m2, metres",
    equations=("5.1", "5.2", "5.3", "5.4"),
)
def _ch5_3(answer):
    n1 = np.array([math.cos(_SCAN[0, 1] + _ROTATION), math.sin(_SCAN[0, 1] + _ROTATION)])
    n2 = np.array([math.cos(_SCAN[1, 1] + _ROTATION), math.sin(_SCAN[1, 1] + _ROTATION)])
    truth = float(_T @ n1 - _T @ n2)  # the printed shift adds t . n1 to every rho; line 2 needed t . n2
    compare_number(
        answer,
        truth,
        hints=[
            (
                0.0,
                "zero would mean the printed shift is exact. It moves every rho by the same amount; "
                "a translation moves each line's rho by t . n, a different amount for each direction.",
            ),
        ],
    )
    return (
        "One delta rho for the whole set is right only for a pure rotation about the laser (or a translation "
        "with the same t . n for every line): here the second line lands metres from its map line."
    )
