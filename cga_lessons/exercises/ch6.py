"""Exercises of chapter 6, the future work (notebook 11): a two-joint arm, its singular elbow, KLD sampling.

The truths are closed forms written out with cosines and sines (the planar arm's tool position and the
determinant of its Jacobian) and the Wilson-Hilferty form of the chi-square quantile that KLD sampling
uses (Fox, 2003), none of them computed with the library a student would call.
"""

from __future__ import annotations

import math

import numpy as np

from .answers import Wrong, as_float
from .checking import exercise
from .compare import compare_number, compare_vector

# --------------------------------------------------------------------------- ch6.1: a two-joint arm

_L1, _L2 = 0.5, 0.3  # link lengths (m): joint 1 at the origin, joint 2 at (0.5, 0, 0), tool at (0.8, 0, 0)
_Q = (math.pi / 3, -math.pi / 2)


def _planar_tool(q1, q2, l1=_L1, l2=_L2):
    return np.array([l1 * math.cos(q1) + l2 * math.cos(q1 + q2), l1 * math.sin(q1) + l2 * math.sin(q1 + q2), 0.0])


def _turn_about(point, angle, x):
    c, s = math.cos(angle), math.sin(angle)
    d = np.asarray(x, float) - point
    return np.array([point[0] + c * d[0] - s * d[1], point[1] + s * d[0] + c * d[1], x[2]])


@exercise(
    "ch6.1",
    title="the tool position of a two-joint planar arm (links 0.5 m and 0.3 m, axes along z) at q = (pi/3, -pi/2)",
    notebook="11_future_work",
    kind="compute",
    expects="a NumPy array of shape (3,), metres",
    equations=("2.107", "2.108", "2.109"),
)
def _ch6_1(answer):
    truth = _planar_tool(*_Q)
    tool0 = np.array([_L1 + _L2, 0.0, 0.0])
    # the joints' motors multiplied the other way round: turn about the origin first, then about the fixed
    # home axis of joint 2 at (0.5, 0, 0)
    swapped = _turn_about(np.array([_L1, 0.0, 0.0]), _Q[1], _turn_about(np.zeros(3), _Q[0], tool0))
    compare_vector(
        answer,
        truth,
        hints=[
            (
                _planar_tool(_Q[0], _Q[1] - _Q[0]),
                "the second angle is measured from the first link, not from the x axis: the second link turns "
                "by q1 + q2 in the base frame.",
            ),
            (
                _planar_tool(*np.degrees(_Q)),
                "the angles look like degrees: give the joint values in radians.",
            ),
            (
                swapped,
                "the joints' motors are multiplied in the wrong order: M = M1(q1) M2(q2) M0, so that joint 2 "
                "turns about its home axis before joint 1 carries it along.",
            ),
            (
                _planar_tool(-_Q[0], -_Q[1]),
                "both joints turn the wrong way: a revolute joint turns by +q about its axis (right-hand rule).",
            ),
            (tool0, "that is the home position: the joints have not moved the tool."),
        ],
    )
    return (
        "The product of the joints' motors M1(q1) M2(q2) with the home motor M0 moves the tool as the closed form "
        "(l1 cos q1 + l2 cos(q1 + q2), l1 sin q1 + l2 sin(q1 + q2), 0) says; the same product serves any chain."
    )


# --------------------------------------------------------------------------- ch6.2: the singular elbow


@exercise(
    "ch6.2",
    title="the elbow angle q2 in (0, 2 pi) at which the tool of ch6.1 can no longer move in every direction of the "
    "plane (the 2x2 Jacobian of its position (x, y) in (q1, q2) loses rank)",
    notebook="11_future_work",
    kind="break",
    expects="a float: q2 in radians",
    equations=("2.103",),
)
def _ch6_2(answer):
    v = as_float(answer, "q2")
    # the tool position's Jacobian d(x, y)/d(q1, q2) has the determinant l1 l2 sin q2: zero at q2 = 0 and pi only
    if abs(math.remainder(v - math.pi, 2 * math.pi)) < 1e-6:
        return (
            "Folded back (q2 = pi) the two links lie on one line, as stretched out (q2 = 0): det J = l1 l2 sin q2 "
            "vanishes and the tool cannot move along the arm. (The spatial Jacobian keeps its rank: the joints "
            "still turn the arm; it is the tool point that loses a direction.) Damped least squares keeps the "
            "step finite there."
        )
    if abs(math.remainder(v, 2 * math.pi)) < 1e-6:
        raise Wrong("that is the stretched arm (q2 = 0): the exercise asks for the other singular elbow in (0, 2 pi).")
    if abs(math.remainder(math.radians(v) - math.pi, 2 * math.pi)) < 1e-6:
        raise Wrong("that looks like degrees: give q2 in radians.")
    if abs(math.remainder(v - math.pi / 2, math.pi)) < 1e-6:
        raise Wrong(
            "with the links at right angles |det J| = l1 l2 |sin q2| is at its largest: the arm is as far from "
            "singular as it gets."
        )
    raise Wrong(
        "at that elbow angle the two joints still move the tool point in two different directions (the columns "
        "of its position's Jacobian are independent)."
    )


# --------------------------------------------------------------------------- ch6.3: KLD sampling

_BINS, _EPS, _Z = 50, 0.05, 2.326  # occupied bins, KL bound, upper 0.99 quantile of N(0, 1)


def _kld_count(k, eps=_EPS, z=_Z):
    a = 2.0 / (9.0 * (k - 1))
    return (k - 1) / (2 * eps) * (1 - a + math.sqrt(a) * z) ** 3


@exercise(
    "ch6.3",
    title="how many particles KLD sampling asks for when they occupy k = 50 bins (epsilon = 0.05, z = 2.326)",
    notebook="11_future_work",
    kind="compute",
    expects="a number of particles (an int, or the float before rounding up)",
)
def _ch6_3(answer):
    v = as_float(answer, "the number of particles")
    truth = _kld_count(_BINS)
    if abs(v - math.ceil(truth)) >= 0.5:  # not the count rounded up: the bound itself, to about 4 digits
        compare_number(
            v,
            truth,
            hints=[
                (_kld_count(_BINS + 1), "the chi-square law has k - 1 degrees of freedom, not k."),
                (
                    (_BINS - 1) / (2 * _EPS) * (1 - 2 / (9 * (_BINS - 1)) + math.sqrt(2 / (9 * (_BINS - 1))) * _Z),
                    "the bracket of the Wilson-Hilferty approximation is cubed.",
                ),
                (_kld_count(_BINS, z=1.645), "z = 2.326 is the upper 0.99 quantile; 1.645 is the 0.95 one."),
                (_kld_count(_BINS, eps=_EPS / 2), "the count is (k - 1) / (2 epsilon) times the bracket cubed."),
                (math.floor(truth), "round up: the bound is the least number of particles that meets it."),
            ],
            rtol=1e-4,
        )
    return (
        "The count grows about linearly with the occupied bins: a filter whose particles gather in a few "
        "places keeps few of them, one spread over the whole map keeps many."
    )
