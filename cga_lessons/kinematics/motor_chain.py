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
constants are read off the geometric product of :class:`~cga_lessons.algebra.Multivector` once, at import.
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

from cga_lessons import conformal as cga
from cga_lessons.algebra import InvalidInputError, Multivector
from cga_lessons.conformal import G41, why_not_motor

__all__ = ["Joint", "Chain", "revolute", "prismatic", "chain", "motor_coefficients", "coefficients_to_motor",
           "coefficients_to_matrix", "forward_coefficients", "forward_motor", "forward_matrix", "spatial_jacobian",
           "twist_of_bivector"]  # fmt: skip

#: The G(4,1) blades of a motor's 8 numbers: 1, e12, e13, e23, then e1-, e2-, e3-, e123- (with e+ twins).
MOTOR_BLADES = (0, 3, 5, 6, 17, 18, 20, 23)
_TWIN = 0b11000  # blade ^ _TWIN turns e- into e+
REVERSE_SIGNS = np.array([1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, 1.0])  # grades 0, 2 x6, 4 (2.33)


def _basis(k: int) -> Multivector:
    b = MOTOR_BLADES[k]
    return Multivector(G41, {b: 1.0, b ^ _TWIN: 1.0} if b & 16 else {b: 1.0})


def _read(X: Multivector) -> np.ndarray:
    return np.array([float(X.coeffs.get(b, 0.0)) for b in MOTOR_BLADES])


@functools.cache
def _structure() -> np.ndarray:
    """T[i, j, k]: the k-th number of the geometric product (basis i)(basis j), from G(4,1)'s product."""
    T = np.zeros((8, 8, 8))
    for i in range(8):
        for j in range(8):
            T[i, j] = _read(_basis(i) * _basis(j))
    return T


_T = _structure()
_T64 = np.ascontiguousarray(_T.reshape(64, 8))


def _right(X: np.ndarray) -> np.ndarray:
    """The 8x8 matrix R with ``P @ R`` the numbers of the product P X, for the fixed motor numbers X."""
    return np.einsum("ijk,j->ik", _T, X)


def multiply_batches(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Numbers of the products X Y of two batches (N, 8) of motors (or even elements of the motor algebra)."""
    return (X[:, :, None] * Y[:, None, :]).reshape(len(X), 64) @ _T64


# ----------------------------------------------------------------- input checks
def _vec3(x, func: str, name: str, *, unit: bool = False) -> np.ndarray:
    try:
        a = np.asarray(x)
    except (TypeError, ValueError):  # pragma: no cover (ragged input)
        raise InvalidInputError(f"{func}: {name}: expected 3 real numbers, got {x!r:.60}") from None
    if a.dtype.kind not in "iuf" or a.shape != (3,):
        raise InvalidInputError(f"{func}: {name}: expected 3 real numbers (shape (3,)), got {x!r:.60}")
    a = a.astype(float)
    if not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{func}: {name}: contains NaN or inf")
    if unit:
        big = float(np.max(np.abs(a)))
        if big == 0.0:
            raise InvalidInputError(f"{func}: {name}: is the zero vector, a joint needs a direction")
        return (a / big) / np.linalg.norm(a / big)  # scaled first: neither 1e200 nor 1e-200 over- or underflows
    return a


def motor_coefficients(M: Multivector, func: str = "motor_coefficients", name: str = "M") -> np.ndarray:
    """The 8 numbers (shape (8,), or (..., 8) for a batch) of a numeric motor, scaled to a unit motor.

    Raises :class:`InvalidInputError` naming ``func`` and ``name`` for what is not a numeric motor of G(4,1)
    (odd blades, not commuting with e, NaN/inf); ``s M`` and M give the same numbers (the same motion).

    >>> motor_coefficients(cga.translator([2.0, 0.0, 0.0])).tolist()
    [1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0]
    """
    if not isinstance(M, Multivector) or M.algebra is not G41:
        raise InvalidInputError(f"{func}: {name}: expected a motor (a Multivector of G41), got {type(M).__name__}")
    for v in M.coeffs.values():
        if not isinstance(v, (float, int, np.floating, np.integer, np.ndarray)) or isinstance(v, bool):
            raise InvalidInputError(f"{func}: {name}: numeric coefficients only, got {type(v).__name__}")
    why = why_not_motor(M) if M.coeffs else "the zero multivector is not a motor"
    if why:
        raise InvalidInputError(f"{func}: {name}: {why}")
    c = np.stack(np.broadcast_arrays(*(np.asarray(M.coeffs.get(b, 0.0), float) for b in MOTOR_BLADES)), axis=-1)
    return c / np.linalg.norm(c[..., :4], axis=-1, keepdims=True)


def coefficients_to_motor(c) -> Multivector:
    """The G(4,1) motor of 8 numbers (shape (8,), or (N, 8): a batch with (N,) coefficients).

    >>> coefficients_to_motor([1.0, 0, 0, 0, -1.0, 0, 0, 0])
    1 - 1 e1+ - 1 e1-
    """
    c = np.asarray(c, dtype=float)
    if c.shape[-1:] != (8,) or c.ndim > 2:
        raise InvalidInputError(f"coefficients_to_motor: c: expected shape (8,) or (N, 8), got {c.shape}")
    out = {}
    for k, b in enumerate(MOTOR_BLADES):
        v = c[..., k] if c.ndim == 2 else float(c[k])
        if c.ndim == 2 or v != 0.0:
            out[b] = v
            if b & 16:
                out[b ^ _TWIN] = v.copy() if c.ndim == 2 else v
    return Multivector(G41, out)


def coefficients_to_matrix(c) -> np.ndarray:
    """4x4 homogeneous matrices ``[[R, t], [0, 0, 0, 1]]`` of motors given by their numbers (..., 8).

    R is the rotation of the rotor part (2.96: ``R = w - x e23 - y e31 - z e12`` for the quaternion (w, x, y, z))
    and t the translation ``2 <n ~R>_1`` of (2.144), written out and divided by ``R ~R`` (linear in the numbers:
    exact to round-off at any distance), as :func:`cga_lessons.conformal.motor_to_matrix` does for one motor.
    """
    c = np.asarray(c, dtype=float)
    r0, r12, r13, r23, c1, c2, c3, c7 = np.moveaxis(c, -1, 0)
    n2 = r0 * r0 + r12 * r12 + r13 * r13 + r23 * r23
    w, x, y, z = r0, -r23, r13, -r12
    s = 2.0 / n2
    H = np.zeros(c.shape[:-1] + (4, 4))
    H[..., 0, :3] = np.stack([1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)], -1)
    H[..., 1, :3] = np.stack([s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)], -1)
    H[..., 2, :3] = np.stack([s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)], -1)
    H[..., 0, 3] = -s * (r0 * c1 + r12 * c2 + r13 * c3 + r23 * c7)
    H[..., 1, 3] = -s * (-r12 * c1 + r0 * c2 + r23 * c3 - r13 * c7)
    H[..., 2, 3] = -s * (-r13 * c1 - r23 * c2 + r0 * c3 + r12 * c7)
    H[..., 3, 3] = 1.0
    return H


def twist_of_bivector(c) -> np.ndarray:
    """The twist ``(omega, v)`` (..., 6) of a bivector of the motor algebra given by its numbers (..., 8).

    ``B = -(omega I_E - e v)/2``: with ``omega I_E = omega1 e23 - omega2 e13 + omega3 e12`` and ``e v = -v_i e_i e``
    this reads ``omega = (-2 c_e23, 2 c_e13, -2 c_e12)``, ``v = -2 (c_e1e, c_e2e, c_e3e)``.

    >>> L = cga.standard_form(cga.normalize_line(cga.line_from_points([1, 0, 0], [1, 0, 1])))
    >>> c = [L[b] for b in ("1", "e12", "e13", "e23", "e1-", "e2-", "e3-", "e123-")]
    >>> twist_of_bivector(-0.5 * np.array(c)) + 0.0  # about z through (1, 0, 0): omega = z, v = p x omega
    array([ 0.,  0.,  1.,  0., -1.,  0.])
    """
    c = np.asarray(c, dtype=float)
    return np.stack([-2 * c[..., 3], 2 * c[..., 2], -2 * c[..., 1], -2 * c[..., 4], -2 * c[..., 5], -2 * c[..., 6]], -1)


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
        if self.kind not in ("revolute", "prismatic"):
            raise InvalidInputError(f"Joint: kind: 'revolute' or 'prismatic', got {self.kind!r}")
        object.__setattr__(self, "direction", tuple(_vec3(self.direction, "Joint", "direction", unit=True).tolist()))
        object.__setattr__(self, "point", tuple(_vec3(self.point, "Joint", "point").tolist()))

    @functools.cached_property
    def line(self) -> Multivector:
        """The unit axis line, standard form ``L = l + e (t . l)`` (2.107, 2.108; for a slide, its direction)."""
        p, d = np.array(self.point), np.array(self.direction)
        return cga.standard_form(cga.normalize_line(cga.line_from_points(p, p + d)))

    @functools.cached_property
    def generator(self) -> np.ndarray:
        """Numbers (8,) of the bivector g with ``M(q) = exp(q g)``."""
        if self.kind == "revolute":
            return -0.5 * _read(self.line) + 0.0
        return _read(cga.translator(np.array(self.direction)) - 1.0) + 0.0  # e d / 2 (2.100)


def revolute(axis, point=(0.0, 0.0, 0.0), name: str = "") -> Joint:
    """A revolute joint: ``axis`` a direction (3,) through ``point``, or a conformal line (dual or standard form).

    >>> revolute([0, 0, 2.0], point=[1, 0, 0]).generator.tolist()  # -L/2, L = e12 - e2 e
    [0.0, -0.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0]
    """
    func = "revolute"
    if isinstance(axis, Multivector):
        if not all(isinstance(v, (float, int, np.floating, np.integer)) for v in axis.coeffs.values()):
            raise InvalidInputError(f"{func}: axis: one numeric line, got batched or symbolic coefficients")
        try:
            d = np.asarray(cga.line_direction(axis), float)
            p = np.asarray(cga.line_closest_point(axis), float)
        except ValueError as exc:
            raise InvalidInputError(f"{func}: axis: not a line ({exc})") from None
        return Joint("revolute", tuple(d), tuple(p), str(name))
    d = _vec3(axis, func, "axis", unit=True)
    p = _vec3(point, func, "point")
    p = p - (p @ d) * d  # the point of the axis nearest the origin
    return Joint("revolute", tuple(d), tuple(p), str(name))


def prismatic(direction, name: str = "") -> Joint:
    """A prismatic joint sliding along the unit ``direction`` (3,): ``exp(e d q/2) = 1 + e d q/2`` (2.100)."""
    return Joint("prismatic", tuple(_vec3(direction, "prismatic", "direction", unit=True).tolist()), name=str(name))


@dataclass(frozen=True, eq=False)
class _Tables:
    """A chain's numbers: generators g_i (n, 8), which joints turn (n,), right products by B_i, g_i and M0."""

    gen: np.ndarray
    revolute: np.ndarray
    right: np.ndarray
    gen_right: np.ndarray
    home_right: np.ndarray


@dataclass(frozen=True, eq=False)
class Chain:
    """Joints at home and the home motor M0 (the end effector's pose at q = 0, unit): ``M = M_1 ... M_n M0``.

    Build it with :func:`chain`, which checks its inputs.
    """

    joints: tuple
    home: Multivector
    name: str = ""

    @property
    def n(self) -> int:  # the number of joints (degrees of freedom)
        return len(self.joints)

    @functools.cached_property
    def _tables(self):
        gen = np.array([j.generator for j in self.joints])
        kinds = np.array([j.kind == "revolute" for j in self.joints])
        gen_right = np.array([_right(g) for g in gen])
        right = gen_right * np.where(kinds, 2.0, 1.0)[:, None, None]  # B = 2 g = -L, or g = e d/2
        return _Tables(gen, kinds, right, gen_right, _right(motor_coefficients(self.home, "Chain", "home")))


def chain(joints, home=None, name: str = "") -> Chain:
    """A :class:`Chain` of ``joints`` (a sequence of :class:`Joint`) with the home pose ``home``.

    ``home`` is a motor (Multivector), a 4x4 rigid matrix, a translation (3,), or None (the identity).
    Raises :class:`InvalidInputError` for an empty or non-Joint sequence and for a home that is not a motor.
    """
    func = "chain"
    joints = tuple(joints) if isinstance(joints, (list, tuple)) else joints
    if not isinstance(joints, tuple) or not joints or not all(isinstance(j, Joint) for j in joints):
        raise InvalidInputError(f"{func}: joints: expected a non-empty sequence of Joint (revolute, prismatic)")
    if home is None:
        M0 = G41.scalar(1.0)
    elif isinstance(home, Multivector):
        M0 = home
    else:
        arr = np.asarray(home)
        if arr.shape == (3,):
            M0 = cga.translator(_vec3(arr, func, "home"))
        elif arr.shape == (4, 4):
            try:
                M0 = cga.matrix_to_motor(arr)
            except ValueError as exc:
                raise InvalidInputError(f"{func}: home: {exc}") from None
        else:
            raise InvalidInputError(f"{func}: home: expected a motor, a 4x4 matrix or a translation (3,)")
    if M0.shape:
        raise InvalidInputError(f"{func}: home: one motor, got a batch of shape {M0.shape}")
    M0 = coefficients_to_motor(motor_coefficients(M0, func, "home"))
    return Chain(joints, M0, str(name))


# ----------------------------------------------------------------- forward kinematics and Jacobian
def check_configuration(ch: Chain, q, func: str, name: str = "q"):
    if not isinstance(ch, Chain):
        raise InvalidInputError(f"{func}: chain: expected a Chain (see kinematics.chain), got {type(ch).__name__}")
    try:
        a = np.asarray(q)
    except (TypeError, ValueError):  # pragma: no cover (ragged input)
        raise InvalidInputError(f"{func}: {name}: expected an array of joint values") from None
    if a.dtype.kind not in "iuf":
        raise InvalidInputError(f"{func}: {name}: expected real joint values, got dtype {a.dtype}")
    if a.ndim not in (1, 2) or a.shape[-1] != ch.n:
        raise InvalidInputError(f"{func}: {name}: expected shape ({ch.n},) or (N, {ch.n}), got {a.shape}")
    a = a.astype(float)
    if not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{func}: {name}: contains NaN or inf")
    return a.reshape(-1, ch.n), a.ndim == 1


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
    q2, single = check_configuration(ch, q, "forward_coefficients")
    M = _prefixes(ch, q2, False) @ ch._tables.home_right
    return M[0] if single else M


def forward_motor(ch: Chain, q) -> Multivector:
    """The end effector's pose ``M(q) = M_1(q_1) ... M_n(q_n) M0`` as a motor (batched for q of shape (N, n)).

    >>> arm = chain([revolute([0, 0, 1])], home=[1.0, 0.0, 0.0])
    >>> cga.apply_to_points(forward_motor(arm, [np.pi / 2]), [0.0, 0.0, 0.0]).round(12) + 0.0
    array([0., 1., 0.])
    """
    q2, single = check_configuration(ch, q, "forward_motor")
    M = _prefixes(ch, q2, False) @ ch._tables.home_right
    return coefficients_to_motor(M[0] if single else M)


def forward_matrix(ch: Chain, q) -> np.ndarray:
    """The end effector's pose as 4x4 homogeneous matrices, (4, 4) or (N, 4, 4)."""
    q2, single = check_configuration(ch, q, "forward_matrix")
    H = coefficients_to_matrix(_prefixes(ch, q2, False) @ ch._tables.home_right)
    return H[0] if single else H


def jacobian_and_pose(ch: Chain, q2: np.ndarray):
    """(spatial Jacobian (N, 6, n), pose numbers (N, 8)) for q2 of shape (N, n)."""
    gen, gen_right = ch._tables.gen, ch._tables.gen_right
    Ps = _prefixes(ch, q2, True)
    N = len(q2)
    cols = [np.broadcast_to(twist_of_bivector(gen[0]), (N, 6))]
    for i in range(1, ch.n):
        P = Ps[i - 1]
        moved = multiply_batches(
            P @ gen_right[i], P * REVERSE_SIGNS
        )  # P g_i ~P (2.103): the axis moved by the joints before
        cols.append(twist_of_bivector(moved))
    return np.stack(cols, axis=-1), Ps[-1] @ ch._tables.home_right


def spatial_jacobian(ch: Chain, q) -> np.ndarray:
    """The spatial Jacobian (6, n) or (N, 6, n): column i is the twist ``(omega, v)`` of joint i's axis moved.

    Column i is the generator of joint i (``-L_i/2`` for a revolute axis line L_i, 2.109; ``e d_i/2`` for a
    slide, 2.100) moved by the joints before it, ``P g_i ~P`` with ``P = M_1(q_1) ... M_{i-1}(q_{i-1})``
    (2.103), read as a twist by :func:`twist_of_bivector`.  For a revolute joint that is ``(r, p x r)``, the
    direction and the moment of the moved axis; for a slide ``(0, d)``.  The spatial twist of the end
    effector is ``J q_dot``: ``dH/dt H^-1 = [[omega^], [v]]`` for its 4x4 pose H.
    """
    q2, single = check_configuration(ch, q, "spatial_jacobian")
    J, _ = jacobian_and_pose(ch, q2)
    return J[0] if single else J
