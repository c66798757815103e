"""Exercises of chapter 3 (notebooks 05 and 06): diffTheta, rho seen from where, a corridor, point pairs, spheres.

Every truth is plane geometry written out here with NumPy and SymPy (the short angle by atan2, a projection
onto a line, the eigenvectors of a 2x2 matrix, distances of centres), not the library function a student
would call.
"""

from __future__ import annotations

import math

import numpy as np

from .answers import Malformed, Wrong, as_array
from .checking import exercise
from .compare import compare_expression, compare_number, compare_vector


def _symbols(*names):
    import sympy

    return {n: sympy.Symbol(n, real=True) for n in names}


def _short_angle(a: float) -> float:
    """The signed angle in (-pi, pi] equivalent to ``a``."""
    return math.atan2(math.sin(a), math.cos(a))


# --------------------------------------------------------------------------- notebook 05

_TA, _TB = 0.02, 6.25  # two Hough angles on either side of the cut at 0


@exercise(
    "ch3.1",
    title="diffTheta(0.02, 6.25) with theta_xi = 2 pi/100: two angles across the cut at 0, Eq. (3.5)",
    notebook="05_laser_line_maps",
    kind="compute",
    expects="a float (radians)",
    equations=("3.5",),
)
def _ch3_1(answer):
    truth = _short_angle(_TA - _TB)  # both within theta_xi of the cut: the short way round
    compare_number(
        answer,
        truth,
        hints=[
            (
                _TA - _TB,
                "that is the plain difference theta_a - theta_b, the long way round the circle (and what (3.5) "
                "as printed returns: its condition theta_a + theta_xi <= 0 never holds). Both angles are within "
                "theta_xi of the cut; go across it.",
            ),
            (_TB - _TA, "that is theta_b - theta_a the long way round: check both the order and the way round."),
            (2 * math.pi - truth, "that is 2 pi minus the answer: the long way round, and the sign is wrong too."),
        ],
    )
    return "Across the cut diffTheta adds 2 pi, so two lines with almost the same normal compare as close."


@exercise(
    "ch3.2",
    title="derive how rho measured from the world origin changes when a heading error delta turns the scan "
    "about the robot at (px, py)",
    notebook="05_laser_line_maps",
    kind="derive",
    expects="a SymPy expression in delta, theta, px, py",
    equations=("3.3", "3.4"),
)
def _ch3_2(answer):
    import sympy

    s = _symbols("delta", "theta", "px", "py")
    d, th, px, py = s.values()
    # n' . (p + R (q - p)) - n . q = (n' - n) . p, with n' = R n: q cancels
    truth = px * (sympy.cos(th + d) - sympy.cos(th)) + py * (sympy.sin(th + d) - sympy.sin(th))
    first_order = d * (-px * sympy.sin(th) + py * sympy.cos(th))
    compare_expression(
        answer,
        truth,
        s,
        hints=[
            (first_order, "that is the first-order approximation for a small delta; give the exact change."),
            (
                sympy.Integer(0),
                "zero is the change of rho measured from the robot: a turn about the robot keeps every distance "
                "from it. Measured from the world origin it is not zero.",
            ),
            (truth.subs(d, -d), "the turn goes the wrong way: the scan turns by +delta (counter-clockwise)."),
        ],
    )
    return (
        "The point q on the line cancels: the change is (n' - n) . p, about delta times the robot's distance "
        "along the line. Far from the origin a small heading error moves rho a lot; seen from the robot it does not."
    )


_ALPHA = math.radians(25.0)  # the corridor's direction
_U = np.array([math.cos(_ALPHA), math.sin(_ALPHA)])
_N = np.array([-math.sin(_ALPHA), math.cos(_ALPHA)])
_ERROR = np.array([0.30, -0.10])  # true position minus predicted position


def _ch3_3_given():
    """Hough coordinates of the corridor of exercise ch3.3, seen from the predicted position.

    Returns
    -------
    rho_g, rho_l, theta_l : ndarray, shape (2,) each
        The two walls of the global map, and the local lines (after the heading correction) that match them.
    """
    normals = np.array([_N, -_N])  # each wall's normal, pointing away from the robot
    theta = np.mod(np.arctan2(normals[:, 1], normals[:, 0]), 2 * np.pi)
    rho_g = np.array([1.0, 1.0])  # walls 1 m on either side of the predicted position
    rho_l = rho_g - normals @ _ERROR  # the local map was placed with the predicted pose: shifted by -error
    return rho_g, rho_l, theta


@exercise(
    "ch3.3",
    title="the position error left after the translation correction (3.9)-(3.12) in a corridor: "
    "exercises.given('ch3.3')",
    notebook="05_laser_line_maps",
    kind="break",
    expects="a NumPy array of shape (2,): true position minus corrected position, metres",
    equations=("3.9", "3.10", "3.11", "3.12"),
    given=_ch3_3_given,
)
def _ch3_3(answer):
    # A = sum n n^T has rank one: (3.12) fixes the component along the normal and nothing along the walls
    # (a minimum-norm solution, or the builder's "keep the odometry there", leaves that part as it was).
    truth = (_ERROR @ _U) * _U
    fixed = (_ERROR @ _N) * _N
    compare_vector(
        answer,
        truth,
        atol=1e-9,
        hints=[
            (fixed, "that is the correction itself, the part of the error the walls do fix; what is left?"),
            (_ERROR, "that is the whole error before the correction; the walls do fix part of it."),
            (
                np.zeros(2),
                "zero would mean (3.12) removed the whole error. Look at the rank of the matrix sum n n^T of (3.12) "
                "when every line is parallel.",
            ),
        ],
    )
    return (
        "Parallel walls constrain only the offset across them: sum n n^T has rank one, and the error along "
        "the corridor goes straight into the map unless something else (a door jamb, a real edge) pins it."
    )


# --------------------------------------------------------------------------- notebook 06

_PP_A, _PP_B = np.array([2.0, 1.0]), np.array([0.0, 3.0])


def _plane_point(answer, what="the answer"):
    """A point of the z = 0 plane: shape (2,), or (3,) with z = 0."""
    arr = np.asarray(answer, dtype=float) if isinstance(answer, (list, tuple, np.ndarray)) else None
    if arr is not None and arr.shape == (3,):
        if abs(arr[2]) > 1e-9:
            raise Wrong(f"{what} has z = {arr[2]:.3g}; the laser's points and lines lie in the z = 0 plane.")
        return arr[:2]
    return answer


@exercise(
    "ch3.4",
    title="the closest point to the origin of the line through the point pair of (2, 1) and (0, 3), Eq. (3.15)",
    notebook="06_conformal_line_maps",
    kind="compute",
    expects="a NumPy array of shape (2,) (or (3,) with z = 0)",
    equations=("3.14", "3.15", "2.129"),
)
def _ch3_4(answer):
    d = (_PP_B - _PP_A) / np.linalg.norm(_PP_B - _PP_A)
    truth = _PP_A - (_PP_A @ d) * d  # the foot of the perpendicular from the origin
    compare_vector(
        _plane_point(answer),
        truth,
        hints=[
            (
                -truth,
                "that is the antipode: (3.15) as printed has the sign of the moment (2.128) flipped. "
                "Check the sign before you trust the formula.",
            ),
            (
                (_PP_A + _PP_B) / 2,
                "that is the middle of the segment (the centre of the point pair's sphere, 2.134), not the "
                "line's closest point to the origin.",
            ),
        ],
    )
    return "The closest point is rho (cos theta, sin theta): the Hough coordinates (3.3) read off the point pair."


@exercise(
    "ch3.5",
    title="derive (s1 ^ s2)^2 for two unit-weight spheres with radii r1, r2 whose centres are d apart (3.19)",
    notebook="06_conformal_line_maps",
    kind="derive",
    expects="a SymPy expression in d, r1, r2",
    equations=("3.19", "2.72"),
)
def _ch3_5(answer):
    s = _symbols("d", "r1", "r2")
    d, r1, r2 = s.values()
    # s_i = c_i - r_i^2 e / 2 with c_i = up(centre): s_i^2 = r_i^2, s1 . s2 = (r1^2 + r2^2 - d^2) / 2,
    # and for vectors (s1 ^ s2)^2 = (s1 . s2)^2 - s1^2 s2^2
    dot = (r1**2 + r2**2 - d**2) / 2
    truth = dot**2 - r1**2 * r2**2
    compare_expression(
        answer,
        truth,
        s,
        hints=[
            (dot**2, "that is (s1 . s2)^2 alone: the square of a wedge of two vectors has one more term."),
            (dot**2 + r1**2 * r2**2, "the sign of the s1^2 s2^2 term is wrong."),
            (
                (r1**2 + r2**2 + d**2) ** 2 / 4 - r1**2 * r2**2,
                "check the sign of d^2 in s1 . s2: two points at distance d have X . Y = -d^2 / 2.",
            ),
        ],
    )
    return (
        "(s1 ^ s2)^2 = ((r1 - r2)^2 - d^2)((r1 + r2)^2 - d^2) / 4: negative exactly when |r1 - r2| < d < r1 + r2, "
        "when the spheres meet in a circle (theorem 2.4.1)."
    )


_G_START, _G_END = np.array([0.0, 1.0]), np.array([2.0, 1.0])


def _hough(a, b):
    """(rho, theta) of (3.3) of the line through a and b: the polar coordinates of its closest point."""
    d = (b - a) / np.linalg.norm(b - a)
    foot = a - (a @ d) * d
    rho = float(np.hypot(*foot))
    theta = math.atan2(foot[1], foot[0]) if rho > 1e-12 else math.atan2(-d[0], d[1])
    return rho, theta % (2 * math.pi)


@exercise(
    "ch3.6",
    title="a local segment that the Hough proximity m < 0.05 matches with the global (0, 1)-(2, 1) "
    "but the spheres of (3.19) reject",
    notebook="06_conformal_line_maps",
    kind="break",
    expects="a NumPy array of shape (2, 2): the local segment's start and end points",
    equations=("3.19", "2.134", "3.5"),
)
def _ch3_6(answer):
    seg = as_array(answer, (2, 2))
    a, b = seg
    length = float(np.hypot(*(b - a)))
    if length < 1e-6:
        raise Malformed("the two end points coincide: a segment needs two different points")
    rho_g, th_g = _hough(_G_START, _G_END)
    rho_l, th_l = _hough(a, b)
    m = math.hypot(_short_angle(th_g - th_l), rho_g - rho_l)
    if m >= 0.05:
        raise Wrong(
            f"its line is m = {m:.2f} away in Hough space, so the proximity matrix would not match it either; "
            "put it on (or very near) the global segment's line."
        )
    c_g, r_g = (_G_START + _G_END) / 2, 1.0
    c_l, r_l = (a + b) / 2, length / 2
    gap = float(np.hypot(*(c_g - c_l)))
    if gap <= abs(r_g - r_l) + 1e-9:
        raise Wrong(
            "one sphere lies inside the other: (3.19) counts that as the same segment (case 2), so it would "
            "match. The spheres must be apart."
        )
    if gap <= r_g + r_l + 1e-9:
        raise Wrong("the two spheres intersect: (3.19) would match these segments too (case 1). Move it further off.")
    return (
        "A Hough point is an infinite line: every segment on it, anywhere in the room, has the same (rho, theta). "
        "The spheres through the point pairs see where the segments are, and keep them apart."
    )
