"""A motor as 8 numbers: reading them off a multivector, back to a multivector, to a 4x4 matrix, to a twist.

A motor is 8 numbers ``c`` on ``(1, e12, e13, e23, e1 e, e2 e, e3 e, e123 e)`` (e = e- + e+, the point at
infinity): its G(4,1) coefficients on the blades 1, e12, e13, e23, e1-, e2-, e3-, e123- (the e+ twins are equal,
2.140-2.143).  The product of two motors is bilinear in those numbers; its 8x8x8 structure constants are read off
the geometric product of :class:`~cga_lessons.algebra.Multivector` once, at import
(:mod:`cga_lessons.kinematics.motor_chain` builds chains from them).

The public functions check their input (:mod:`cga_lessons.checks`); the ``*_unchecked`` ones are for numbers
this package made itself (the inner loops of the chains and of inverse kinematics).
"""

from __future__ import annotations

import functools

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector
from cga_lessons.conformal import G41, why_not_motor

__all__ = ["motor_coefficients", "coefficients_to_motor", "coefficients_to_matrix", "twist_of_bivector"]

#: The G(4,1) blades of a motor's 8 numbers: 1, e12, e13, e23, then e1-, e2-, e3-, e123- (with e+ twins).
MOTOR_BLADES = (0, 3, 5, 6, 17, 18, 20, 23)
_TWIN = 0b11000  # blade ^ _TWIN turns e- into e+
REVERSE_SIGNS = np.array([1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, 1.0])  # grades 0, 2 x6, 4 (2.33)


def _basis(k: int) -> Multivector:
    b = MOTOR_BLADES[k]
    return Multivector(G41, {b: 1.0, b ^ _TWIN: 1.0} if b & 16 else {b: 1.0})


def read_numbers(X: Multivector) -> np.ndarray:
    """The 8 numbers (8,) of one numeric element of the motor algebra, as they are (no checks, no scaling)."""
    return np.array([float(X.coeffs.get(b, 0.0)) for b in MOTOR_BLADES])


@functools.cache
def _structure() -> np.ndarray:
    """T[i, j, k]: the k-th number of the geometric product (basis i)(basis j), from G(4,1)'s product."""
    T = np.zeros((8, 8, 8))
    for i in range(8):
        for j in range(8):
            T[i, j] = read_numbers(_basis(i) * _basis(j))
    return T


_T = _structure()
_T64 = np.ascontiguousarray(_T.reshape(64, 8))


def right_product(X: np.ndarray) -> np.ndarray:
    """The 8x8 matrix R with ``P @ R`` the numbers of the product P X, for the fixed motor numbers X."""
    return np.einsum("ijk,j->ik", _T, X)


def multiply_batches(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Numbers of the products X Y of two batches (N, 8) of motors (or even elements of the motor algebra)."""
    return (X[:, :, None] * Y[:, None, :]).reshape(len(X), 64) @ _T64


# ----------------------------------------------------------------- input checks
def check_numbers(c, func: str, name: str = "c") -> np.ndarray:
    """Finite numbers of shape (..., 8).

    The number of axes is read along the first items (ragged rows are then refused by :func:`checks.array`).
    """
    axes, first = 0, c
    while isinstance(first, (list, tuple)) and len(first):
        axes, first = axes + 1, first[0]
    axes += first.ndim if isinstance(first, np.ndarray) else 0
    return checks.array(c, func, name, (None,) * max(axes - 1, 0) + (8,))


def _unit_rotor_scale(c: np.ndarray, func: str, name: str) -> np.ndarray:
    """``c`` (..., 8), rows rescaled where the rotor part's squares would over- or underflow; a zero rotor refused."""
    big = np.max(np.abs(c[..., :4]), axis=-1, keepdims=True)
    if np.any(big == 0):
        raise checks.degenerate(func, name, "the rotor part (the first 4 numbers) is zero: not a motor")
    odd = (big > 1e150) | (big < 1e-150)
    return np.where(odd, c / big, c) if np.any(odd) else c


def _prepared(M: Multivector) -> Multivector:
    """``M`` for :func:`why_not_motor`: a batch's coefficients at the batch's shape (a batched translator's scalar
    is one number), each entry divided by its largest coefficient where that is far from 1 (the test squares them;
    ``s M`` is the same motion)."""
    c = {b: np.asarray(v, float) for b, v in M.coeffs.items()}
    if M.shape:
        c = {b: np.broadcast_to(v, M.shape) for b, v in c.items()}
    big = np.maximum.reduce([np.abs(v) for v in c.values()])
    odd = (big > 1e150) | ((big < 1e-150) & (big > 0))
    if np.any(odd):
        scale = np.where(odd, big, 1.0)
        c = {b: v / scale for b, v in c.items()}
    elif not M.shape:
        return M
    return Multivector(M.algebra, c)


def motor_coefficients(M: Multivector, func: str = "motor_coefficients", name: str = "M") -> np.ndarray:
    """The 8 numbers (shape (8,), or (..., 8) for a batch) of a numeric motor, scaled to a unit motor.

    Raises :class:`InvalidInputError` naming ``func`` and ``name`` for what is not a numeric motor of G(4,1)
    (odd blades, not commuting with e, NaN/inf); ``s M`` and M give the same numbers (the same motion).

    >>> from cga_lessons import conformal as cga
    >>> motor_coefficients(cga.translator([2.0, 0.0, 0.0])).tolist()
    [1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0]
    """
    checks.instance(M, func, name, Multivector, "a motor (a Multivector of G(4,1))")
    if M.algebra is not G41:
        raise checks.fail(func, name, f"expected a motor of G(4,1), got a multivector of {M.algebra!r}")
    for v in M.coeffs.values():
        if not isinstance(v, (float, int, np.floating, np.integer, np.ndarray)) or isinstance(v, bool):
            raise checks.fail(func, name, f"numeric coefficients only, got {type(v).__name__}")
        if np.iscomplexobj(v):
            raise checks.fail(func, name, "real coefficients only, got complex ones")
    why = why_not_motor(_prepared(M)) if M.coeffs else "the zero multivector is not a motor"
    if why:
        raise checks.fail(func, name, why)
    c = np.stack(np.broadcast_arrays(*(np.asarray(M.coeffs.get(b, 0.0), float) for b in MOTOR_BLADES)), axis=-1)
    c = _unit_rotor_scale(c, func, name)
    return checks.finite_result(c / np.linalg.norm(c[..., :4], axis=-1, keepdims=True), func, f"{name}: the numbers")


def coefficients_to_motor(c) -> Multivector:
    """The G(4,1) motor of 8 numbers (shape (8,), or (N, 8): a batch with (N,) coefficients).

    >>> coefficients_to_motor([1.0, 0, 0, 0, -1.0, 0, 0, 0])
    1 - 1 e1+ - 1 e1-
    """
    f = "coefficients_to_motor"
    c, single = checks.batch(c, f, "c", (8,))
    _unit_rotor_scale(c, f, "c")
    return coefficients_to_motor_unchecked(c[0] if single else c)


def coefficients_to_motor_unchecked(c: np.ndarray) -> Multivector:
    """:func:`coefficients_to_motor` of numbers (8,) or (N, 8) this package made (no checks)."""
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
    A zero rotor part (the first 4 numbers) is refused; the numbers' scale does not matter.
    """
    f = "coefficients_to_matrix"
    c = _unit_rotor_scale(check_numbers(c, f), f, "c")
    return checks.finite_result(coefficients_to_matrix_unchecked(c), f, "c: the matrices")


def coefficients_to_matrix_unchecked(c: np.ndarray) -> np.ndarray:
    """:func:`coefficients_to_matrix` of numbers this package made (no checks)."""
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

    >>> from cga_lessons import conformal as cga
    >>> L = cga.standard_form(cga.normalize_line(cga.line_from_points([1, 0, 0], [1, 0, 1])))
    >>> c = [L[b] for b in ("1", "e12", "e13", "e23", "e1-", "e2-", "e3-", "e123-")]
    >>> twist_of_bivector(-0.5 * np.array(c)) + 0.0  # about z through (1, 0, 0): omega = z, v = p x omega
    array([ 0.,  0.,  1.,  0., -1.,  0.])
    """
    f = "twist_of_bivector"
    return checks.finite_result(twists_unchecked(check_numbers(c, f)), f, "c: the twist")


def twists_unchecked(c: np.ndarray) -> np.ndarray:
    """:func:`twist_of_bivector` of numbers this package made (no checks)."""
    return np.stack([-2 * c[..., 3], 2 * c[..., 2], -2 * c[..., 1], -2 * c[..., 4], -2 * c[..., 5], -2 * c[..., 6]], -1)
