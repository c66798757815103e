"""Kinematic chains of n joints as products of motors (the thesis's future work, section 6.2.2).

The thesis closes (6.2.2) asking for "an algorithm for motors in conformal geometry that model a mechanism
with n degrees of freedom".  Here it is, built from chapter 2's own pieces:

* a revolute joint is its axis *line* L, a unit line in standard form ``L = l + e (t . l)`` (2.107, 2.108);
  turning by q about it is the motor ``M(q) = exp(-q/2 L) = cos(q/2) - sin(q/2) L`` (2.109; L^2 = -1, so
  the series 2.37 folds onto cos and sin);
* a prismatic joint is a unit direction d; sliding by q is the translator ``exp(e d q/2) = 1 + e d q/2``
  (2.100);
* a chain is its joints at the home configuration (every axis in the base frame, q = 0) and a home motor M0,
  the end effector's pose at q = 0.  Its forward kinematics is the product of the joints' motors (2.102,
  2.103: a product of motors is a motor)::

      M(q) = M_1(q_1) M_2(q_2) ... M_n(q_n) M0,

  the product of exponentials of robotics (Brockett 1984; Lynch & Park 2017, ch. 4) written in G(4,1);
* the spatial Jacobian: column i is the axis line of joint i moved by the motors before it,
  ``L_i' = P L_i ~P`` with ``P = M_1 ... M_{i-1}`` (2.103 applied to a line), read as a twist.

Numbers.  A motor is 8 numbers ``c`` on ``(1, e12, e13, e23, e1 e, e2 e, e3 e, e123 e)`` (e = e- + e+, the
point at infinity): its G(4,1) coefficients on the blades 1, e12, e13, e23, e1-, e2-, e3-, e123- (the e+
twins are equal, 2.140-2.143).  The product of two motors is bilinear in those numbers; its 8x8x8 structure
constants are read off the geometric product of :class:`~cga_lessons.algebra.Multivector` once, at import
(:mod:`~cga_lessons.kinematics.motor_numbers`).
Every joint motor is ``a(q) + b(q) B`` with ``(a, b) = (cos q/2, sin q/2)`` and ``B = -L`` (revolute) or
``(1, q)`` and ``B = e d/2`` (prismatic), so one step of the chain, ``P M_i = a P + b (P B)``, is one
(N, 8) x (8, 8) matrix product for N configurations at once: no Python loop over configurations.

A twist ``(omega, v)`` (rotation rate, velocity of the point at the origin) is the bivector
``-(omega I_E - e v)/2`` (2.108-2.110: the unit line through p along r has ``omega = r``, ``v = p x r``).

>>> import numpy as np
>>> elbow = chain([revolute([0, 0, 1]), revolute([0, 0, 1], point=[1, 0, 0])], home=[2.0, 0.0, 0.0])
>>> forward_matrix(elbow, [np.pi / 2, 0.0])[:3, 3].round(12) + 0.0
array([0., 2., 0.])
>>> forward_matrix(elbow, np.array([[0.0, np.pi / 2], [np.pi, 0.0]]))[:, :3, 3].round(12) + 0.0
array([[ 1.,  1.,  0.],
       [-2.,  0.,  0.]])
>>> spatial_jacobian(elbow, [0.0, 0.0]).T.round(12) + 0.0  # one row per joint: (omega, v), v = p x omega
array([[ 0.,  0.,  1.,  0.,  0.,  0.],
       [ 0.,  0.,  1.,  0., -1.,  0.]])
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError, Multivector
from cga_lessons.conformal import G41

from .motor_numbers import (
    REVERSE_SIGNS,
    coefficients_to_matrix_unchecked,
    coefficients_to_motor_unchecked,
    motor_coefficients,
    multiply_batches,
    read_numbers,
    right_product,
    twists_unchecked,
)

__all__ = ["Joint", "Chain", "revolute", "prismatic", "chain", "forward_coefficients", "forward_motor",
           "forward_matrix", "spatial_jacobian"]  # fmt: skip


# ----------------------------------------------------------------- input checks
def _vec3(x, func: str, name: str, *, unit: bool = False) -> np.ndarray:
    """Three finite numbers (3,); with ``unit`` a direction, returned as a unit vector (the zero vector refused)."""
    a = checks.array(x, func, name, (3,))
    if unit:
        big = float(np.max(np.abs(a)))
        if big == 0.0:
            raise checks.fail(func, name, "is the zero vector, a joint needs a direction")
        return (a / big) / np.linalg.norm(a / big)  # scaled first: neither 1e200 nor 1e-200 over- or underflows
    return a


def _point(x, func: str, name: str) -> np.ndarray:
    """A point (3,) whose coordinates a conformal line can hold (up to 1e150: their squares stay finite)."""
    return checks.magnitude(_vec3(x, func, name), func, name, why="a line's squares overflow a float")


# ----------------------------------------------------------------- joints and chains
@dataclass(frozen=True, eq=False)
class Joint:
    """One joint at the home configuration, in the base frame.

    ``kind`` is ``"revolute"`` (turn by +q about the line through ``point`` with direction ``direction``,
    right-hand rule) or ``"prismatic"`` (slide by q along ``direction``; ``point`` is unused).  ``direction``
    is a unit vector.  :attr:`line` is the axis as a conformal line (standard form, 2.108) and
    :attr:`generator` the numbers of the bivector g with ``M(q) = exp(q g)``: ``-L/2`` (2.109) or ``e d/2``
    (2.100).
    """

    kind: str
    direction: tuple
    point: tuple = (0.0, 0.0, 0.0)
    name: str = ""

    def __post_init__(self):
        f = "Joint"
        checks.choice(self.kind, f, "kind", ("revolute", "prismatic"))
        object.__setattr__(self, "direction", tuple(_vec3(self.direction, f, "direction", unit=True).tolist()))
        object.__setattr__(self, "point", tuple(_point(self.point, f, "point").tolist()))
        checks.text(self.name, f, "name", empty=True)

    @functools.cached_property
    def line(self) -> Multivector:
        """The unit axis line, standard form ``L = l + e (t . l)`` (2.107, 2.108; for a slide, its direction)."""
        p, d = np.array(self.point), np.array(self.direction)
        return cga.standard_form(cga.normalize_line(cga.line_from_points(p, p + d)))

    @functools.cached_property
    def generator(self) -> np.ndarray:
        """Numbers (8,) of the bivector g with ``M(q) = exp(q g)``."""
        if self.kind == "revolute":
            return -0.5 * read_numbers(self.line) + 0.0
        return read_numbers(cga.translator(np.array(self.direction)) - 1.0) + 0.0  # e d / 2 (2.100)


def _axis_of_line(L: Multivector, func: str, name: str):
    """Direction and closest point of a numeric conformal line (dual or standard form)."""
    if L.algebra is not G41 or L.shape:
        raise checks.fail(func, name, "expected one numeric line of G(4,1)")
    if not all(isinstance(v, (float, int, np.floating, np.integer)) for v in L.coeffs.values()):
        raise checks.fail(func, name, "one numeric line, got batched or symbolic coefficients")
    try:
        kind = cga.classify(L)
        if kind.kind not in ("flat", "dual flat") or kind.dimension != 1:  # dual (grade 3) or standard form (grade 2)
            raise checks.fail(func, name, f"not a line (a {kind.kind} of dimension {kind.dimension})")
        return np.asarray(cga.line_direction(L), float), np.asarray(cga.line_closest_point(L), float)
    except GeometryError as exc:
        if str(exc).startswith(f"{func}: {name}:"):
            raise
        raise checks.fail(func, name, f"not a line ({exc})") from None


def revolute(axis, point=(0.0, 0.0, 0.0), name: str = "") -> Joint:
    """A revolute joint: ``axis`` a direction (3,) through ``point``, or a conformal line (dual or standard form).

    >>> revolute([0, 0, 2.0], point=[1, 0, 0]).generator.tolist()  # -L/2, L = e12 - e2 e
    [0.0, -0.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0]
    """
    f = "revolute"
    checks.text(name, f, "name", empty=True)
    if isinstance(axis, Multivector):
        d, p = _axis_of_line(axis, f, "axis")
    else:
        d = _vec3(axis, f, "axis", unit=True)
        p = _vec3(point, f, "point")
        p = p - (p @ d) * d  # the point of the axis nearest the origin
    p = _point(checks.finite_result(p, f, "point: its projection on the axis"), f, "point")
    return Joint("revolute", tuple(d), tuple(p), name)


def prismatic(direction, name: str = "") -> Joint:
    """A prismatic joint sliding along the unit ``direction`` (3,): ``exp(e d q/2) = 1 + e d q/2`` (2.100)."""
    checks.text(name, "prismatic", "name", empty=True)
    return Joint("prismatic", tuple(_vec3(direction, "prismatic", "direction", unit=True).tolist()), name=name)


@dataclass(frozen=True, eq=False)
class _Tables:
    """A chain's numbers: generators g_i (n, 8), which joints turn (n,), right products by B_i, g_i and M0."""

    gen: np.ndarray
    revolute: np.ndarray
    right: np.ndarray
    gen_right: np.ndarray
    home_right: np.ndarray


def _joints(joints, func: str) -> tuple:
    joints = tuple(joints) if isinstance(joints, (list, tuple)) else joints
    if not isinstance(joints, tuple) or not joints or not all(isinstance(j, Joint) for j in joints):
        raise checks.fail(func, "joints", "expected a non-empty sequence of Joint (revolute, prismatic)")
    return joints


@dataclass(frozen=True, eq=False)
class Chain:
    """Joints at home and the home motor M0 (the end effector's pose at q = 0, unit): ``M = M_1 ... M_n M0``.

    Build it with :func:`chain`, which also reads a home given as a matrix or a translation.
    """

    joints: tuple
    home: Multivector
    name: str = ""

    def __post_init__(self):
        object.__setattr__(self, "joints", _joints(self.joints, "Chain"))
        if getattr(self.home, "shape", None):
            raise checks.fail("Chain", "home", f"one motor, got a batch of shape {self.home.shape}")
        motor_coefficients(self.home, "Chain", "home")
        checks.text(self.name, "Chain", "name", empty=True)

    @property
    def n(self) -> int:  # the number of joints (degrees of freedom)
        return len(self.joints)

    @functools.cached_property
    def _tables(self):
        gen = np.array([j.generator for j in self.joints])
        kinds = np.array([j.kind == "revolute" for j in self.joints])
        gen_right = np.array([right_product(g) for g in gen])
        right = gen_right * np.where(kinds, 2.0, 1.0)[:, None, None]  # B = 2 g = -L, or g = e d/2
        home = right_product(motor_coefficients(self.home, "Chain", "home"))
        return _Tables(gen, kinds, right, gen_right, home)


def _home(home, func: str) -> Multivector:
    """The home motor of a motor, a 4x4 rigid matrix, a translation (3,) or None (the identity)."""
    if home is None:
        return G41.scalar(1.0)
    if isinstance(home, Multivector):
        return home
    scalar = isinstance(home, np.ndarray) and home.ndim == 0
    if scalar or not isinstance(home, (list, tuple, np.ndarray)) or len(home) not in (3, 4):
        raise checks.fail(func, "home", "expected a motor, a 4x4 matrix or a translation (3,)")
    if len(home) == 3:
        return cga.translator(_point(home, func, "home"))
    H = checks.array(home, func, "home", (4, 4))
    with checks.relabel(func, "home"):
        return cga.matrix_to_motor(H)


def chain(joints, home=None, name: str = "") -> Chain:
    """A :class:`Chain` of ``joints`` (a sequence of :class:`Joint`) with the home pose ``home``.

    ``home`` is a motor (Multivector), a 4x4 rigid matrix, a translation (3,), or None (the identity).
    Raises :class:`InvalidInputError` for an empty or non-Joint sequence and for a home that is not a motor.
    """
    f = "chain"
    joints = _joints(joints, f)
    checks.text(name, f, "name", empty=True)
    M0 = _home(home, f)
    if M0.shape:
        raise checks.fail(f, "home", f"one motor, got a batch of shape {M0.shape}")
    M0 = coefficients_to_motor_unchecked(motor_coefficients(M0, f, "home"))
    return Chain(joints, M0, name)


# ----------------------------------------------------------------- forward kinematics and Jacobian
def check_configuration(ch: Chain, q, func: str, name: str = "q"):
    """``(q as (N, n), single)`` for joint values of shape (n,) or (N, n) of the chain ``ch``."""
    checks.instance(ch, func, "chain", Chain, "a Chain (see kinematics.chain)")
    return checks.batch(q, func, name, (ch.n,))


def _prefixes(ch: Chain, q2: np.ndarray, keep: bool):
    """Numbers of ``M_1 ... M_i`` for i = 1..n (each joint in closed form, 2.100, 2.109): the last, or all."""
    t = ch._tables
    kinds, right = t.revolute, t.right
    half = 0.5 * q2
    a, b = np.cos(half), np.sin(half)
    if not kinds.all():
        a[:, ~kinds], b[:, ~kinds] = 1.0, q2[:, ~kinds]
    P = b[:, :1] * (right[0][0])  # M_1 = a + b B_1: the first row of R(B_1) is B_1 itself
    P[:, 0] += a[:, 0]
    out = [P] if keep else None
    for i in range(1, ch.n):
        Y = P @ right[i]
        P = a[:, i : i + 1] * P
        P += b[:, i : i + 1] * Y
        if keep:
            out.append(P)
    return out if keep else P


def forward_coefficients(ch: Chain, q) -> np.ndarray:
    """Numbers (8,) or (N, 8) of ``M(q) = M_1(q_1) ... M_n(q_n) M0`` for q of shape (n,) or (N, n)."""
    f = "forward_coefficients"
    q2, single = check_configuration(ch, q, f)
    M = checks.finite_result(_prefixes(ch, q2, False) @ ch._tables.home_right, f, "q: the pose")
    return M[0] if single else M


def forward_motor(ch: Chain, q) -> Multivector:
    """The end effector's pose ``M(q) = M_1(q_1) ... M_n(q_n) M0`` as a motor (batched for q of shape (N, n)).

    >>> arm = chain([revolute([0, 0, 1])], home=[1.0, 0.0, 0.0])
    >>> cga.apply_to_points(forward_motor(arm, [np.pi / 2]), [0.0, 0.0, 0.0]).round(12) + 0.0
    array([0., 1., 0.])
    """
    f = "forward_motor"
    q2, single = check_configuration(ch, q, f)
    M = checks.finite_result(_prefixes(ch, q2, False) @ ch._tables.home_right, f, "q: the pose")
    return coefficients_to_motor_unchecked(M[0] if single else M)


def forward_matrix(ch: Chain, q) -> np.ndarray:
    """The end effector's pose as 4x4 homogeneous matrices, (4, 4) or (N, 4, 4)."""
    f = "forward_matrix"
    q2, single = check_configuration(ch, q, f)
    H = coefficients_to_matrix_unchecked(_prefixes(ch, q2, False) @ ch._tables.home_right)
    H = checks.finite_result(H, f, "q: the pose")
    return H[0] if single else H


def jacobian_and_pose(ch: Chain, q2: np.ndarray):
    """(spatial Jacobian (N, 6, n), pose numbers (N, 8)) for q2 of shape (N, n)."""
    gen, gen_right = ch._tables.gen, ch._tables.gen_right
    Ps = _prefixes(ch, q2, True)
    N = len(q2)
    cols = [np.broadcast_to(twists_unchecked(gen[0]), (N, 6))]
    for i in range(1, ch.n):
        P = Ps[i - 1]
        moved = multiply_batches(
            P @ gen_right[i], P * REVERSE_SIGNS
        )  # P g_i ~P (2.103): the axis moved by the joints before
        cols.append(twists_unchecked(moved))
    return np.stack(cols, axis=-1), Ps[-1] @ ch._tables.home_right


def spatial_jacobian(ch: Chain, q) -> np.ndarray:
    """The spatial Jacobian (6, n) or (N, 6, n): column i is the twist ``(omega, v)`` of joint i's axis moved.

    Column i is the generator of joint i (``-L_i/2`` for a revolute axis line L_i, 2.109; ``e d_i/2`` for a
    slide, 2.100) moved by the joints before it, ``P g_i ~P`` with ``P = M_1(q_1) ... M_{i-1}(q_{i-1})``
    (2.103), read as a twist by :func:`~cga_lessons.kinematics.motor_numbers.twist_of_bivector`.  For a revolute
    joint that is ``(r, p x r)``, the direction and the moment of the moved axis; for a slide ``(0, d)``.  The
    spatial twist of the end effector is ``J q_dot``: ``dH/dt H^-1 = [[omega^], [v]]`` for its 4x4 pose H.
    """
    f = "spatial_jacobian"
    q2, single = check_configuration(ch, q, f)
    J = checks.finite_result(jacobian_and_pose(ch, q2)[0], f, "q: the Jacobian")
    return J[0] if single else J
