"""Motors of G(4,1) in closed form: their rotor and translation read off the coefficients, and their matrices
built from (R, t) in the null basis (2.102, 2.141-2.144).

A motor (even, commuting with the point at infinity e, 2.102) takes a route of its own in
:meth:`~cga_lessons.algebra.versor_matrices.VersorActions.matrices`:
:meth:`MotorMatrices.rigid` (or :func:`motor_parts`) reads the rotor R and the translation t linearly off the
coefficients (2.141-2.144), and the matrices are built in closed form from (R, t) in the null basis
(e1, e2, e3, e, e0), where no entry is a difference of large terms (see :mod:`cga_lessons.algebra.versor_matrices`).
:func:`motor_tolerance` says how far a multivector may be from a motor.

Each :class:`~cga_lessons.algebra.Algebra` holds one :class:`MotorMatrices` (with the caches it shares with the
algebra's :class:`~cga_lessons.algebra.versor_matrices.VersorActions`) and delegates
:meth:`Algebra.rigid_motion <cga_lessons.algebra.Algebra.rigid_motion>` to it.
"""

from __future__ import annotations

import math
import sys

import numpy as np

from cga_lessons.checks import fail

from .coefficients import is_real_single
from .multivector import Multivector
from .operands import nonnegative, not_finite, same_algebra
from .versor_matrices import VERSOR_TOLERANCE, VersorMatrices

__all__ = ["motor_tolerance", "motor_parts", "MOTOR_TOLERANCE_CAP", "MotorMatrices"]

#: The most a motor's defects may reach, relative to its largest coefficient (see ``motor_tolerance``).
MOTOR_TOLERANCE_CAP = 1e-8
_EPS = sys.float_info.epsilon


def motor_tolerance(vmax, n_norm, r_norm):
    """How far ``M = R + e n`` may be from a motor: the bound on its defects (E parts, e+ != e- parts,
    ``<n ~R>_3``), for floats or arrays.

    ``VERSOR_TOLERANCE`` of the largest coefficient ``vmax``, plus the round-off
    a product of motors leaves in the e+/e- basis: the e+ and e- parts of the
    factors multiply into terms that cancel (e+ e+ = 1, e- e- = -1), so a
    product carries defects of about ``eps (|n|/|R|)^2`` relative to its largest
    coefficient, |n|/|R| being about |t|/2 (measured: at most 13 times that
    for products of four motors); allowed 16 times, capped at
    ``MOTOR_TOLERANCE_CAP``.  Beyond the cap (products of motors translating
    by more than ~1e3) the multivector is no longer taken for a motor.
    """
    for name, v in (("vmax", vmax), ("n_norm", n_norm), ("r_norm", r_norm)):
        nonnegative(v, "motor_tolerance", name, positive=name == "r_norm")
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            ratio = n_norm / r_norm
            rel = np.minimum(VERSOR_TOLERANCE + 16 * _EPS * ratio * ratio, MOTOR_TOLERANCE_CAP)
            return rel * vmax
    except ValueError as exc:
        raise fail(
            "motor_tolerance", "vmax, n_norm, r_norm", f"arrays of shapes that do not broadcast ({exc})"
        ) from None


class MotorMatrices:
    """The motors of one :class:`~cga_lessons.algebra.Algebra` of signature (4, 1, 0): their ``(R, t)`` read off
    the coefficients (cached by value), the null-basis tables and their matrices in closed form.

    ``table_cache`` and ``versor_cache`` are the caches it shares with the algebra's
    :class:`~cga_lessons.algebra.versor_matrices.VersorActions`.
    """

    def __init__(self, algebra, table_cache: dict, versor_cache: dict):
        self.algebra = algebra
        self.motor_algebra = algebra.signature == (4, 1, 0)
        self.n, self.dim = algebra.n, algebra.dim
        self.grades, self.grade_blades = algebra.grades, algebra.grade_blades
        self.table_cache, self.versor_cache = table_cache, versor_cache

    def rigid_motion(self, V: Multivector):
        """:meth:`Algebra.rigid_motion <cga_lessons.algebra.Algebra.rigid_motion>`: :meth:`rigid` with V checked."""
        if type(V) is not Multivector or V.algebra is not self.algebra:
            same_algebra(V, self.algebra, "Algebra.rigid_motion", "V", Multivector)
        hit = self.rigid(V)
        if hit is None and not_finite(V) is not None:
            raise fail("Algebra.rigid_motion", "V", f"coefficient of {not_finite(V)} is NaN or inf")
        return hit

    def rigid(self, V: Multivector):
        """:meth:`rigid_motion` of a multivector of this algebra (unchecked: the fast paths' call)."""
        c = V._c
        if not c or not is_real_single(V):
            return None
        key = ("rigid", tuple(c), tuple(c.values()))
        hit = self.versor_cache.get(key, False)
        if hit is not False:
            return hit
        hit = motor_parts(c, self.grades) if self.motor_algebra and not_finite(V) is None else None
        if len(self.versor_cache) >= 256:
            self.versor_cache.clear()
        self.versor_cache[key] = hit
        return hit

    def null_tables(self, g: int):
        """Index tables of grade g for the null basis (e1, e2, e3, e, e0) of G(4,1).

        Returns ``(keep, pairs, P, Pinv, comp, sign)``: ``pairs`` the
        positions ``(i, j)`` of the blades ``B e+`` and ``B e-``, ``keep`` the
        others; ``P`` maps e+/e- coefficients to null-basis ones,
        ``(a, b) -> ((a + b)/2, b - a)`` on each pair (``B e`` and ``B e0``,
        since ``e = e+ + e-`` and ``e0 = (e- - e+)/2``, 2.53; ``B e+ e- = B e e0``
        is unchanged), ``Pinv`` back.  ``comp``/``sign`` index the compound
        matrices (below).
        """
        key = ("null-basis", g)
        hit = self.table_cache.get(key)
        if hit is not None:
            return hit
        blades = self.grade_blades[g]
        k = len(blades)
        pos = {b: i for i, b in enumerate(blades)}
        ip = [i for i, b in enumerate(blades) if b & 8 and not b & 16]
        im = [pos[blades[i] ^ 24] for i in ip]
        keep = [i for i in range(k) if i not in ip and i not in im]
        P, Pinv = np.eye(k), np.eye(k)
        P[ip, ip], P[ip, im], P[im, ip], P[im, im] = 0.5, 0.5, -1.0, 1.0
        Pinv[ip, ip], Pinv[ip, im], Pinv[im, ip], Pinv[im, im] = 1.0, -0.5, 1.0, 0.5

        def bits(b):
            return [i for i in range(self.n) if b >> i & 1]

        comp = sign = None
        if g == 2:
            comp = np.array([bits(b) for b in blades], dtype=np.intp).T  # (2, 10): the index pairs
        elif g in (3, 4):  # Jacobi: minors of N from the complementary minors of N^-1
            other = {b: i for i, b in enumerate(self.grade_blades[self.n - g])}
            comp = np.array([other[(self.dim - 1) ^ b] for b in blades], dtype=np.intp)
            s = np.array([-1.0 if sum(bits(b)) & 1 else 1.0 for b in blades])
            sign = s[:, None] * s[None, :]
        hit = (keep, list(zip(ip, im)), P, Pinv, comp, sign)
        self.table_cache[key] = hit
        return hit

    def info(self, rigid: tuple, d: float, grades: tuple):
        """:meth:`~cga_lessons.algebra.versor_matrices.VersorActions.info` of a motor, in closed form from ``(R, t)``.

        In the null basis (e1, e2, e3, e, e0) the motor maps ``x -> R x + (R x . t) e``,
        ``e -> e`` and ``e0 -> e0 + t + t^2/2 e`` (T up(x) ~T = up(x + t), 2.101, 2.62), so on grade 1::

            N = [[R, 0, t], [(R^T t)^T, 1, t^2/2], [0, 0, 1]]

        and on grade k its k-th compound (the outermorphism, 2.82): the 2x2
        minors of N for k = 2, and for k = 3, 4 the complementary minors of
        ``N^-1 = [[R^T, 0, -R^T t], [-t^T, 1, t^2/2], [0, 0, 1]]`` (Jacobi;
        det N = 1).  No entry is a difference of large terms.  The e+/e-
        matrices are ``Pinv C P`` (:meth:`null_tables`), on grade 1 written
        out: ``[[R, -t, t], [u^T, 1 - h, h], [u^T, -h, 1 + h]]`` with
        ``u = R^T t``, ``h = t^2/2``.  A motor is even, so ``V X^ V^-1 = V X V^-1``
        and ``V X ~V = d V X V^-1`` with ``d = R ~R``.

        ``null[g]`` (what :meth:`~cga_lessons.algebra.versor_matrices.VersorActions.apply` uses) is
        ``K = T_row C T_col``: it takes each e+/e- pair of coefficients as ``(a, w) = (a, b - a)``
        (the e coefficient is ``a + w/2``: T_col) and returns ``(a', w')``
        with ``a' = c' - w'/2`` the e+ coefficient (T_row); then ``b' = a' + w'``.
        So only ``b - a`` and ``a' + w'`` are computed outside the matrix
        product: a point keeps its weight up to the one rounding of ``a' + w'``
        (none at all when a' is a multiple of the spacing at ``a' + w'``, as for
        a point far away unless ``a'`` lies within w' below a power of two).  The
        large e+/e- coefficients of a point far away multiply only the entries
        mapping e to e; on grade 1, K = N.
        """
        if not (math.isfinite(d) and d > 0):
            return None
        N, unit1, Ni = _motor_grade1(*rigid, inverse=3 in grades or 4 in grades)
        null, unit = {}, {}
        for g in grades:
            _, pairs, P, Pinv, comp, sign = self.null_tables(g)
            if g == 1:  # its K (below) is N itself
                null[1], unit[1] = N, unit1
                continue
            if g in (0, self.n):
                C = np.ones((1, 1))
            elif g == 2:
                C = _minors2(N, comp)
            elif g == 3:
                C = sign * _minors2(Ni, self.null_tables(2)[4])[np.ix_(comp, comp)].T
            else:
                C = sign * Ni[np.ix_(comp, comp)].T
            C = np.array(C)
            unit[g] = Pinv @ C @ P
            for i, j in pairs:  # K: (a, b - a) -> (c - w/2, w), see the docstring
                C[i] -= 0.5 * C[j]
            for i, j in pairs:
                C[:, j] += 0.5 * C[:, i]
            null[g] = C
        raw, raw_null = unit, null
        if d != 1.0:
            raw = {g: d * mat for g, mat in unit.items()}
            raw_null = {g: d * mat for g, mat in null.items()}
        for mat in (*null.values(), *unit.values(), *raw.values(), *raw_null.values()):
            mat.flags.writeable = False  # shared through the cache
        return d, 0, VersorMatrices(raw, rigid, raw_null), VersorMatrices(unit, rigid, null)


def motor_parts(c: dict, grades) -> tuple | None:
    """``(R, t)`` of a motor of G(4,1) from its coefficient map ``c`` (blade bitmap -> float), or None when it is
    not one (:meth:`Algebra.rigid_motion <cga_lessons.algebra.Algebra.rigid_motion>`); ``grades[b]`` is the grade
    of blade b."""
    for b in c:
        if grades[b] & 1:
            return None
    vmax = max([abs(float(v)) for v in c.values()])
    if not (0.0 < vmax < math.inf):
        return None
    get = c.get
    r0, r12, r13, r23 = float(get(0, 0.0)), float(get(3, 0.0)), float(get(5, 0.0)), float(get(6, 0.0))
    rn = math.hypot(r0, r12, r13, r23)  # |R| = sqrt(R ~R) (2.141), no overflow
    if rn == 0.0:
        return None
    q0, q12, q13, q23 = r0 / rn, r12 / rn, r13 / rn, r23 / rn
    # e n = (e+ + e-) n puts -n on the e- blades e1- e2- e3- e123- (and on the e+ ones, for a motor)
    m1, m2, m3, m123 = float(get(17, 0.0)), float(get(18, 0.0)), float(get(20, 0.0)), float(get(23, 0.0))
    n1, n2, n3, n123 = -m1, -m2, -m3, -m123
    nn = math.hypot(n1, n2, n3, n123)
    tri = n123 * q0 - n1 * q23 + n2 * q13 - n3 * q12  # <n ~R>_3 / |R|, zero when n = t R / 2
    # The parts that move e (e+ != e-: an e0 part) or scale it (E = e+e-: a dilation, D_s = a - b E) are weighed
    # against the rotor |R| (a similarity's E part is rho |R|, rho = b / a), not against the largest coefficient,
    # which grows with |t|: measured against that, T_t D_s 1e6 out passed for a motor up to s = 1.02.
    moving = max(
        abs(float(get(9, 0.0)) - m1),
        abs(float(get(10, 0.0)) - m2),
        abs(float(get(12, 0.0)) - m3),
        abs(float(get(15, 0.0)) - m123),
        abs(float(get(24, 0.0))),
        abs(float(get(27, 0.0))),
        abs(float(get(29, 0.0))),
        abs(float(get(30, 0.0))),
    )
    ratio = nn / rn
    rel = min(VERSOR_TOLERANCE + 16 * _EPS * ratio * ratio, MOTOR_TOLERANCE_CAP)  # motor_tolerance, floats
    if not (abs(tri) <= rel * vmax and moving <= rel * rn):  # also refuses NaN
        return None
    s = 2.0 / rn  # t = 2 <n ~R>_1 / (R ~R)  (2.144)
    t0 = s * (n1 * q0 + n2 * q12 + n3 * q13 + n123 * q23)
    t1 = s * (n2 * q0 - n1 * q12 + n3 * q23 - n123 * q13)
    t2 = s * (n3 * q0 - n1 * q13 - n2 * q23 + n123 * q12)
    if not (math.isfinite(t0) and math.isfinite(t1) and math.isfinite(t2)):
        return None
    # The unit quaternion (w, x, y, z) of R = w - x e23 - y e31 - z e12 (2.96; e31 = -e13) and its matrix.
    w, x, y, z = q0, -q23, q13, -q12
    Rm = np.array(
        [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)],
            [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)],
            [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
        ]
    )
    t = np.array([t0, t1, t2])
    Rm.flags.writeable = t.flags.writeable = False
    return Rm, t


def _motor_grade1(Rm: np.ndarray, t: np.ndarray, inverse: bool):
    """The grade-1 matrices of the motor ``(R, t)``: N in the null basis (e1, e2, e3, e, e0), the e+/e- matrix
    ``Pinv N P`` written out (the e+ column -t, 1 - h, -h; the e- column t, h, 1 + h) and, if ``inverse``,
    ``N^-1`` (else None); see :meth:`MotorMatrices.info`."""
    (a, b, c), (e, f, g_), (k, l, m) = Rm.tolist()
    tx, ty, tz = t.tolist()
    ux, uy, uz = a * tx + e * ty + k * tz, b * tx + f * ty + l * tz, c * tx + g_ * ty + m * tz  # R^T t
    h = 0.5 * (tx * tx + ty * ty + tz * tz)
    N = np.array(
        [
            [a, b, c, 0.0, tx],
            [e, f, g_, 0.0, ty],
            [k, l, m, 0.0, tz],
            [ux, uy, uz, 1.0, h],
            [0.0, 0.0, 0.0, 0.0, 1.0],
        ]
    )
    unit = np.array(
        [
            [a, b, c, -tx, tx],
            [e, f, g_, -ty, ty],
            [k, l, m, -tz, tz],
            [ux, uy, uz, 1.0 - h, h],
            [ux, uy, uz, -h, 1.0 + h],
        ]
    )
    if not inverse:
        return N, unit, None
    Ni = np.array(
        [
            [a, e, k, 0.0, -ux],
            [b, f, l, 0.0, -uy],
            [c, g_, m, 0.0, -uz],
            [-tx, -ty, -tz, 1.0, h],
            [0.0, 0.0, 0.0, 0.0, 1.0],
        ]
    )
    return N, unit, Ni


def _minors2(A: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """The 2x2 minors ``det A[(i0, i1), (j0, j1)]`` over the index pairs ``pairs`` (2, m), as an (m, m) array."""
    i0, i1 = pairs
    return A[np.ix_(i0, i0)] * A[np.ix_(i1, i1)] - A[np.ix_(i0, i1)] * A[np.ix_(i1, i0)]
