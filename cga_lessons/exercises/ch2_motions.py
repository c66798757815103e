"""Exercises of chapter 2, notebooks 03 and 04: versors (motors, rotors about lines, screws) and entity properties.

Every truth here is a closed form written out with plain NumPy/SymPy (Rodrigues' matrix, 4x4 homogeneous
matrices, coefficients worked out by hand from the rules (2.4) and (2.10)), not the library function a
student would call.  Those of notebooks 01 and 02 are in :mod:`cga_lessons.exercises.ch2`.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons.algebra import Multivector
from cga_lessons.stereo import rotation_matrix  # Rodrigues in plain NumPy: independent of the algebra

from .answers import Malformed, Wrong, as_array, as_expression, as_float
from .ch2 import real_symbols
from .checking import exercise
from .compare import compare_expression, compare_vector


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


# --------------------------------------------------------------------------- notebook 03


def _motion_of(M: Multivector, points: np.ndarray) -> np.ndarray:
    """Where the sandwich M X ~M sends each point (M need not be normalised)."""
    from cga_lessons.conformal import G41

    e_inf = G41.blade("e+") + G41.blade("e-")
    e_o = (G41.blade("e-") - G41.blade("e+")) * 0.5
    out = []
    for p in points:
        X = G41.blade("e1", p[0]) + G41.blade("e2", p[1]) + G41.blade("e3", p[2]) + e_inf * (p @ p / 2) + e_o
        Y = M * X * ~M
        w = -float((Y | e_inf).scalar())
        if abs(w) < 1e-12:
            raise Wrong("your versor sends a point to infinity; a motor keeps points finite.")
        out.append([float(Y["e1"]) / w, float(Y["e2"]) / w, float(Y["e3"]) / w])
    return np.array(out)


_PROBES = np.array([[0.3, -0.7, 0.2], [1.5, 0.4, -1.0], [-1.2, 2.0, 0.8], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0]])


@exercise(
    "ch2.7",
    title="the motor turning +90 degrees about the vertical line through c = (1, 1, 0), Eq. (2.104)",
    notebook="03_conformal_transformations",
    kind="compute",
    expects="a Multivector of G(4,1) (a motor; M and -M count as the same)",
    equations=("2.102", "2.104", "2.105"),
)
def _ch2_7(answer):
    from cga_lessons.conformal import G41

    if not isinstance(answer, Multivector):
        raise Malformed(f"a motor is a Multivector, not a {type(answer).__name__}")
    if answer.algebra is not G41 and answer.algebra.signature != G41.signature:
        raise Wrong(f"the motor lives in G(4,1); yours is in G{answer.algebra.signature}.")
    odd = [g for g in answer.grades_present() if g % 2]
    if odd or not answer.blades():
        raise Wrong(
            f"the grade is wrong: a motor is even (grades 0, 2, 4); yours has grades {answer.grades_present()}."
        )
    norm = answer * ~answer
    k = float(norm.scalar())
    if not norm.grade(2, 4).iszero(atol=1e-9 * max(abs(k), 1.0)) or k <= 0:
        raise Wrong("M ~M is not a positive scalar, so this is not a motor (a product of a translator and a rotor).")
    c = np.array([1.0, 1.0, 0.0])
    truth = (_PROBES - c) @ rotation_matrix([0, 0, 1], math.pi / 2).T + c
    moved = _motion_of(answer, _PROBES)
    if not np.allclose(moved, truth, atol=1e-7):
        if np.allclose(moved, (_PROBES - c) @ rotation_matrix([0, 0, 1], -math.pi / 2).T + c, atol=1e-7):
            raise Wrong("the axis is right but it turns the wrong way: +90 degrees is counter-clockwise seen from +z.")
        if np.allclose(moved, _PROBES @ rotation_matrix([0, 0, 1], math.pi / 2).T, atol=1e-7):
            raise Wrong("that turns about the z axis through the origin; the axis must pass through c.")
        if np.allclose(moved, (_PROBES + c) @ rotation_matrix([0, 0, 1], math.pi / 2).T - c, atol=1e-7):
            raise Wrong("the axis passes through -c: the two translators are swapped (T R ~T with T moving by +c).")
        if not np.allclose(moved[3], c, atol=1e-7):
            raise Wrong("the point c should stay where it is (it is on the axis), and your motor moves it.")
        raise Wrong("c stays fixed, but the other points do not turn by +90 degrees about the vertical through c.")
    if abs(k - 1) > 1e-9:
        raise Wrong("the motion is right, but M ~M is not 1: normalise the motor (divide by the square root of M ~M).")
    return "A rotation about any line is T R ~T, the rotor conjugated by the translator to the line."


@exercise(
    "ch2.8",
    title="the angle of the rotation a b made by reflecting in the plane with normal b, then in the one with normal a",
    notebook="03_conformal_transformations",
    kind="derive",
    expects="a SymPy expression in phi: the angle (radians, about +z, right-hand rule)",
    equations=("2.84", "2.93"),
)
def _ch2_8(answer):
    import sympy

    s = real_symbols("phi")
    phi = s["phi"]
    expr = as_expression(answer, s, "the answer")
    f = sympy.lambdify([phi], expr, modules="numpy")
    samples = np.linspace(0.1, 1.3, 7)
    try:
        got = np.array([float(f(p)) for p in samples])
    except (TypeError, ValueError, ZeroDivisionError) as exc:
        raise Wrong(f"the answer cannot be evaluated for phi in (0.1, 1.3) ({type(exc).__name__}).") from None
    truth = []
    for p in samples:  # Householder reflections: the plane with normal b first, then the plane with normal a
        a, b = np.array([1.0, 0.0, 0.0]), np.array([math.cos(p), math.sin(p), 0.0])
        R = (np.eye(3) - 2 * np.outer(a, a)) @ (np.eye(3) - 2 * np.outer(b, b))
        truth.append(math.atan2(R[1, 0], R[0, 0]))
    truth = np.array(truth)
    if np.allclose(_wrap(got - truth), 0, atol=1e-9):
        return (
            "Two reflections in planes at angle phi rotate by twice that angle, "
            "from the first normal toward the second."
        )
    if np.allclose(_wrap(got + truth), 0, atol=1e-9):
        raise Wrong("the sign is wrong: check the order. Reflecting in b first turns from b toward a.")
    if np.allclose(_wrap(2 * got - truth), 0, atol=1e-9) or np.allclose(_wrap(2 * got + truth), 0, atol=1e-9):
        raise Wrong("half the angle: two reflections turn by twice the angle between the planes.")
    raise Wrong("it is a different function of phi.")


@exercise(
    "ch2.9",
    title="where the motor M = R T (R: +90 degrees about z, T: by (1, 0, 0)) sends the origin",
    notebook="03_conformal_transformations",
    kind="break",
    expects="a NumPy array of shape (3,)",
    equations=("2.99", "2.102"),
)
def _ch2_9(answer):
    Rz = rotation_matrix([0, 0, 1], math.pi / 2)
    t = np.array([1.0, 0.0, 0.0])
    truth = Rz @ (np.zeros(3) + t)  # in M X ~M with M = R T, T acts first
    compare_vector(
        answer,
        truth,
        hints=[
            (
                Rz @ np.zeros(3) + t,
                "that is where T R sends the origin (turn, then move). In R T the translator acts first.",
            ),
            (Rz.T @ t, "the turn goes the wrong way: the rotor turns counter-clockwise about +z for a positive angle."),
        ],
    )
    return (
        "The rightmost factor of a versor product acts first: R T moves, then turns "
        "(the text's R = R1 R2 has it backwards)."
    )


# --------------------------------------------------------------------------- notebook 04


def _read_angle_axis(answer):
    if isinstance(answer, dict) or not hasattr(answer, "__len__") or isinstance(answer, (str, np.ndarray)):
        if isinstance(answer, np.ndarray) and answer.dtype == object and answer.shape == (2,):
            answer = tuple(answer)
        else:
            raise Malformed("give a pair (theta, axis): theta a float, axis an array of shape (3,)")
    if len(answer) != 2:
        raise Wrong(f"the shape is wrong: give a pair (theta, axis); yours has {len(answer)} items.")
    theta = as_float(answer[0], "theta")
    axis = as_array(answer[1], (3,), "the axis")
    return theta, axis


@exercise(
    "ch2.10",
    title="the angle and axis of the rotor R = 0.6 - 0.8 e12, Eqs. (2.135)-(2.137)",
    notebook="04_entity_properties",
    kind="compute",
    expects="a pair (theta, axis): theta in radians, axis a unit NumPy array of shape (3,)",
    equations=("2.135", "2.136", "2.137"),
)
def _ch2_10(answer):
    theta, axis = _read_angle_axis(answer)
    n = np.linalg.norm(axis)
    if n == 0:
        raise Wrong("the axis is the zero vector.")
    # R = cos(t/2) - sin(t/2) n I_E with e3 I_E = e12: cos(t/2) = 0.6, sin(t/2) = 0.8, n = e3
    true_theta, true_axis = 2 * math.acos(0.6), np.array([0.0, 0.0, 1.0])
    truth = rotation_matrix(true_axis, true_theta)
    if abs(n - 1) > 1e-6:
        if np.allclose(rotation_matrix(axis, theta), truth, atol=1e-6):
            raise Wrong("the rotation is right, but the axis must be a unit vector.")
        raise Wrong("the axis must be a unit vector (and the rotation is off too).")
    mine = rotation_matrix(axis, theta)
    if np.allclose(mine, truth, atol=1e-6):
        return "c = cos(theta/2) gives the angle; the bivector part, read as a line (2.126), gives the axis."
    if np.allclose(rotation_matrix(axis, math.radians(theta)), truth, atol=1e-6):
        raise Wrong("it looks like degrees; give theta in radians.")
    if np.allclose(mine, truth.T, atol=1e-6):
        raise Wrong("the axis line is right but the rotation goes the other way: flip the sign of the axis or angle.")
    if np.allclose(rotation_matrix(axis, 2 * theta), truth, atol=1e-6):
        raise Wrong("that is half the angle: the rotor holds theta/2.")
    if np.allclose(rotation_matrix(axis, theta / 2), truth, atol=1e-6):
        raise Wrong("that is twice the angle: theta = 2 arccos(c), not 4 arccos(c).")
    if abs(abs(axis @ true_axis) / n - 1) < 1e-6:
        raise Wrong("the axis is right (up to its sign); the angle is off.")
    raise Wrong(f"the axis is off by {math.degrees(math.acos(min(1.0, abs(axis @ true_axis) / n))):.0f} degrees.")


def _ch2_11_given():
    """The motor of exercise ch2.11 (its rotation and translation are what the student recovers)."""
    from cga_lessons.conformal import rotor, translator

    return translator([0.7, -1.3, 0.4]) * rotor(np.array([1.0, 2.0, 2.0]) / 3, 1.2)


@exercise(
    "ch2.11",
    title="the translation t of the motor M = exercises.given('ch2.11'), Eqs. (2.140)-(2.144)",
    notebook="04_entity_properties",
    kind="compute",
    expects="a NumPy array of shape (3,)",
    equations=("2.140", "2.141", "2.142", "2.143", "2.144"),
    given=_ch2_11_given,
)
def _ch2_11(answer):
    t = np.array([0.7, -1.3, 0.4])  # the 4x4 matrix of T R is [[Rot, t], [0, 1]]: t is its last column
    Rot = rotation_matrix(np.array([1.0, 2.0, 2.0]) / 3, 1.2)
    compare_vector(
        answer,
        t,
        hints=[
            (t / 2, "half of it: (2.144) has the factor 2, t = 2 R' I_E ~R."),
            (Rot.T @ t, "that is the translation turned back by the rotation: the reverse ~R goes on the right."),
            (Rot @ t, "that is the translation turned once more by the rotation: check the order of the factors."),
        ],
    )
    return "The part of M without e is the rotor; the part with e, times 2 ~R, is the translation."


@exercise(
    "ch2.12",
    title="-2 X.Y for weighted points X = alpha up(a), Y = beta up(b) at distance d, Eq. (2.66)",
    notebook="04_entity_properties",
    kind="break",
    expects="a SymPy expression in alpha, beta, d",
    equations=("2.61", "2.66", "2.111"),
)
def _ch2_12(answer):
    s = real_symbols("alpha", "beta", "d")
    a, b, d = s.values()
    compare_expression(
        answer,
        a * b * d**2,
        s,
        hints=[(d**2, "that holds for normalised points only (X.e = Y.e = -1); here the points carry weights.")],
    )
    return "The weights multiply in: divide by (X.e)(Y.e) before reading a distance from X.Y."
