"""A versor's action as one matrix per grade, built in closed form (2.82).

A versor V acts linearly on each grade: ``X -> V X^ V^-1`` (2.82) maps grade-k
blades to grade-k blades.  For a single numeric versor,
:meth:`VersorActions.matrices` builds that action as one matrix per
grade, from one cached bilinear table per blade set (no sandwich products):
with ``v`` the coefficients of V, ``outer(v, v).ravel() @ T`` gives ``V ~V``
and every matrix at once.  :meth:`VersorActions.apply` then applies
the matrices to one entity or to a whole batch with one matrix product per
grade, so moving a million points by a motor costs one 5x5 matrix product.
``V >> X`` (:meth:`~cga_lessons.algebra.multivector.Multivector.__rshift__`, the
sandwich of (2.98, 2.101, 2.103)) and :func:`cga_lessons.conformal.versors.apply` take
this route by themselves.

Motors of G(4,1) (even, commuting with the point at infinity e, 2.102) take a
route of their own, :meth:`~cga_lessons.algebra.motor_matrices.MotorMatrices.rigid`: the rotor R and the
translation t are read linearly off the coefficients (2.141-2.144), and the
matrices are built in closed form from (R, t) in the null basis
(e1, e2, e3, e, e0), where no entry is a difference of large terms, and applied
there (:class:`VersorMatrices`).  In the e+/e- basis a motor translating by t
has entries such as 1 - t^2/2 and a point at x has e+/e- coefficients of size
x^2/2, so the plain product loses ~eps |t|^2 |x|^2 to cancellation.

Each :class:`~cga_lessons.algebra.Algebra` holds one :class:`VersorActions` (with the caches of its tables and
versors) and delegates :meth:`Algebra.versor_matrices <cga_lessons.algebra.Algebra.versor_matrices>` and
:meth:`Algebra.apply_matrices <cga_lessons.algebra.Algebra.apply_matrices>` to it.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons.checks import fail, integer
from cga_lessons.scratch import scratch

from .coefficients import is_real_single
from .multivector import Multivector, mv_from_dict, mv_from_pairs
from .operands import finite_out, matrices_per_grade, not_finite, same_algebra


def stack_rows(vals, shape: tuple) -> np.ndarray:
    """Stack batch coefficients into a ``(k,) + shape`` array.

    No copy when they already are the consecutive rows of one C-contiguous
    float block (the layout :func:`~cga_lessons.conformal.points.up` and
    :meth:`VersorActions.apply` produce).
    """
    base = getattr(vals[0], "base", None)
    if (
        type(base) is np.ndarray
        and base.dtype == np.float64
        and base.shape == (len(vals),) + shape
        and base.flags.c_contiguous
    ):
        step = base.strides[0]
        p0 = base.__array_interface__["data"][0]
        rest = base.strides[1:]
        for i, v in enumerate(vals):
            if (
                type(v) is not np.ndarray
                or v.base is not base
                or v.shape != shape
                or v.strides != rest
                or v.__array_interface__["data"][0] != p0 + i * step
            ):
                break
        else:
            return base
    rows = [
        v if type(v) is np.ndarray and v.shape == shape else np.broadcast_to(np.asarray(v, float), shape) for v in vals
    ]
    return np.stack(rows)


#: Relative tolerance of the versor tests (of ``V ~V`` against ``|v|^2``, of a motor's parts against its
#: largest coefficient).
VERSOR_TOLERANCE = 1e-12
#: The rotor blades 1 e12 e13 e23 of a motor M = R + e n of G(4,1) (bitmaps e1=1 e2=2 e3=4 e+=8 e-=16): R = (M ^ E) E
#: (2.141).  n sits on e1- e2- e3- e123- (negated: e n = (e+ + e-) n, 2.53) and, equal, on e1+ e2+ e3+ e123+.
ROTOR_BLADES = (0, 3, 5, 6)
_EPS = float(np.finfo(float).eps)


class VersorMatrices(dict):
    """``{grade: k x k matrix}`` of a versor's action in the blade order of (2.9), e+/e- basis.

    Returned by :meth:`Algebra.versor_matrices <cga_lessons.algebra.Algebra.versor_matrices>`.  For a motor of G(4,1)
    two more attributes are set (None otherwise): ``rigid``, the ``(R, t)`` of ``rigid_motion``, and
    ``null``, the same action on the coordinates in which :meth:`VersorActions.apply` applies it (each pair of
    e+/e- coefficients ``(a, b)`` taken as ``(a, b - a)``; see ``MotorMatrices.info``).  All arrays are read-only
    (they are shared by a cache).
    """

    __slots__ = ("rigid", "null")

    def __init__(self, mats, rigid=None, null=None):
        super().__init__(mats)
        self.rigid = rigid
        self.null = null


class VersorActions:
    """The versor matrices of one :class:`~cga_lessons.algebra.Algebra` (2.82): tables, versors and their action.

    Reads the algebra's signs (2.10), reverse signs, ``grades`` and ``grade_blades``; ``motors`` is the algebra's
    :class:`~cga_lessons.algebra.motor_matrices.MotorMatrices` (the closed form of a motor of G(4,1)) and
    ``table_cache``/``versor_cache`` the caches both share (bilinear and null-basis tables; versors by value).
    """

    def __init__(self, algebra, motors, table_cache: dict, versor_cache: dict):
        self.algebra = algebra
        self.motors = motors
        self.n, self.dim = algebra.n, algebra.dim
        self.grades, self.grade_blades = algebra.grades, algebra.grade_blades
        self.sign_list, self.rev_flip = algebra._sign_list, algebra._rev_flip
        self.table_cache, self.versor_cache = table_cache, versor_cache

    def sandwich_table(self, keys: tuple, grades: tuple):
        """Bilinear table of the sandwich ``V X ~V`` for versors with blades ``keys``.

        Returns ``(parity, T, slices)``: ``parity`` is 0 (all blades even), 1
        (all odd) or None (mixed).  ``T`` has shape ``(m*m, dim + sum k_g^2)``
        for the m blades in ``keys`` and the k_g blades of each grade g in
        ``grades``, such that with ``v`` the coefficients of V in the order of
        ``keys``, ``w = outer(v, v).ravel() @ T`` holds the coefficients of
        ``V ~V`` (all ``dim`` blades) and then, for each grade, the k_g x k_g
        matrix of ``X -> V X ~V`` (row-major) at ``w[slices[g]]``.
        """
        ck = (keys, grades)
        hit = self.table_cache.get(ck)
        if hit is not None:
            return hit
        sign, flip, dim, m = self.sign_list, self.rev_flip, self.dim, len(keys)
        slices, width = {}, dim
        for g in grades:
            k = len(self.grade_blades[g])
            slices[g] = slice(width, width + k * k)
            width += k * k
        T = np.zeros((m, m, width))
        for ia, a in enumerate(keys):
            for ib, b in enumerate(keys):
                s = sign[a][b] * (-1 if flip[b] else 1)
                if s:
                    T[ia, ib, a ^ b] += s
            for g in grades:
                blades = self.grade_blades[g]
                k, off = len(blades), slices[g].start
                pos = {bl: i for i, bl in enumerate(blades)}
                for j, x in enumerate(blades):
                    s1 = sign[a][x]
                    if not s1:
                        continue
                    r1 = a ^ x
                    for ib, b in enumerate(keys):
                        s2 = sign[r1][b]
                        r = r1 ^ b
                        if s2 and r in pos:
                            T[ia, ib, off + pos[r] * k + j] += s1 * s2 * (-1 if flip[b] else 1)
        parities = {self.grades[b] & 1 for b in keys}
        parity = parities.pop() if len(parities) == 1 else None
        hit = (parity, T.reshape(m * m, width), slices)
        if len(self.table_cache) >= 128:  # up to ~270 kB each (16 blades, grade 2)
            self.table_cache.clear()
        self.table_cache[ck] = hit
        return hit

    def info(self, V: Multivector, grades: tuple):
        """``(d, parity, raw, unit)`` for a single numeric versor V, else None (cached by value).

        ``d = <V ~V>_0``; ``raw[g]`` is the matrix of ``X -> V X ~V`` and
        ``unit[g]`` that of ``X -> V X^ V^-1`` (2.82) on grade g, both
        :class:`VersorMatrices` (``unit`` None when ``V ~V`` is not resolved,
        below).  A motor of G(4,1) (:meth:`MotorMatrices.rigid`) gets them in
        closed form from its rotation and translation.  Any other V is
        a versor here when its blades have one parity and ``V ~V`` is a
        non-zero scalar up to round-off: its other blades within
        ``VERSOR_TOLERANCE |v|^2`` (|v|^2 the sum of the squared coefficients,
        which bounds the sum of the |products| making up each entry of V ~V,
        hence their round-off); in G(p, q) with p + q <= 5 that makes V an
        element of the Clifford group, so it keeps grades.  And ``V ~V`` itself
        must be resolved for ``unit``: its round-off, eps times the sum of the
        squared coefficients of the non-null blades, within ``VERSOR_TOLERANCE``
        of it.  Otherwise (in G(4,1) a sphere far from the origin: its e+ and e-
        coefficients near |c|^2/2 square to ~|c|^4 where ``V ~V`` is its squared
        radius) the matrices divided by it would be garbage: ``unit`` is None
        (:meth:`matrices` returns None, and :func:`cga_lessons.conformal.apply`
        takes such a versor by its factors), while ``raw``, which never divides
        by it, stays the sandwich ``V X ~V`` to the round-off of its terms.
        """
        c = V._c
        if not c or not is_real_single(V) or self.n > 5:
            return None
        ck = (tuple(c), tuple(c.values()), grades)
        hit = self.versor_cache.get(ck)
        if hit is not None:
            return hit
        rigid = self.motors.rigid(V)
        if rigid is not None:
            hit = self.motors.info(rigid, sum(float(c.get(b, 0.0)) ** 2 for b in ROTOR_BLADES), grades)
        else:
            hit = self.table_info(ck, grades)
        if hit is None:
            return None
        if len(self.versor_cache) >= 256:
            self.versor_cache.clear()
        self.versor_cache[ck] = hit
        return hit

    def table_info(self, ck: tuple, grades: tuple):
        """:meth:`info` of a general versor, from the bilinear table of (2.82)."""
        parity, T, slices = self.sandwich_table(ck[0], grades)
        if parity is None:
            return None
        v = np.array(ck[1], dtype=float)
        m = len(v)
        with np.errstate(over="ignore", invalid="ignore"):
            size = float(v @ v)
            w = (v[:, None] * v).ravel() @ T
            # the terms summed into <V ~V>_0: b ~b of each blade, +-1 (0 for a null blade of a degenerate metric)
            dsize = float(np.abs(T[:: m + 1, 0]) @ (v * v))
        head = w[: self.dim].tolist()
        d = head[0]
        if not (math.isfinite(d) and d != 0 and math.isfinite(size)):
            return None
        resolved = _EPS * dsize <= VERSOR_TOLERANCE * abs(d)  # else V ~V is lost to round-off: no unit matrices
        if max(map(abs, head[1:]), default=0.0) > VERSOR_TOLERANCE * size:
            return None
        raw, unit = {}, {}
        for g, sl in slices.items():
            k = len(self.grade_blades[g])
            raw[g] = mat = w[sl].reshape(k, k)
            if resolved:
                unit[g] = u = mat * ((-1.0 if parity and g & 1 else 1.0) / d)
                u.flags.writeable = False  # shared through the cache
        w.flags.writeable = False
        return d, parity, VersorMatrices(raw), (VersorMatrices(unit) if resolved else None)

    def matrices(self, V: Multivector, grades) -> dict | None:
        """:meth:`Algebra.versor_matrices <cga_lessons.algebra.Algebra.versor_matrices>`: :meth:`info` with V and
        grades checked."""
        func = "Algebra.versor_matrices"
        if type(V) is not Multivector or V.algebra is not self.algebra:
            same_algebra(V, self.algebra, func, "V", Multivector)
        if type(grades) is not tuple:
            if isinstance(grades, (str, bytes)) or not hasattr(grades, "__iter__"):
                raise fail(func, "grades", f"expected a sequence of grades 0..{self.n}, got {grades!r:.40}")
            grades = tuple(grades)
        n = self.n
        for g in grades:
            if type(g) is not int or g < 0 or g > n:
                grades = tuple(integer(g, func, "grades", low=0, high=n) for g in grades)
                break
        info = self.info(V, grades)
        if info is None and not_finite(V) is not None:
            raise fail(func, "V", f"coefficient of {not_finite(V)} is NaN or inf")
        return None if info is None else info[3]

    def apply(self, mats: dict, X: Multivector) -> Multivector:
        """:meth:`Algebra.apply_matrices <cga_lessons.algebra.Algebra.apply_matrices>`: :meth:`apply_unchecked` with
        the matrices and X checked."""
        func = "Algebra.apply_matrices"
        if type(X) is not Multivector or X.algebra is not self.algebra:
            same_algebra(X, self.algebra, func, "X", Multivector)
        if type(mats) is not VersorMatrices:  # those of versor_matrices are finite and of the right shapes
            matrices_per_grade(mats, self.grade_blades, func)
        try:
            out = self.apply_unchecked(mats, X)
        except (TypeError, ValueError) as exc:
            raise fail(func, "X", f"expected real number or array coefficients ({exc})") from None
        return finite_out(out, func, "X")

    def apply_unchecked(self, mats: dict, X: Multivector) -> Multivector:
        """:meth:`apply` unchecked (the fast path of ``V >> X``).

        A batch costs, per grade, one ``(k, k) x (k, N)`` matrix product; when
        X's coefficient arrays of that grade are consecutive rows of one
        C-contiguous block (as :func:`~cga_lessons.conformal.points.up` and this method
        return them) no copy is made.  Results come back as the rows of one
        block.  Output blades whose matrix row is zero on X's blades are left
        out; the others are kept even if their values happen to vanish.

        The matrices of a motor (``mats.null`` set) are applied in the null
        basis: each pair of e+/e- coefficients ``(a, b)`` becomes
        ``((a + b)/2, b - a)`` (for a point, ``x^2/2`` and its weight, 2.111),
        then the null-basis matrix, then ``(c, w) -> (c - w/2, c + w/2)`` back
        (folded into the matrix, see ``MotorMatrices.info``), so that no large e+/e-
        terms cancel and a point keeps its weight to one rounding.
        """
        c = X._c
        batch = X.shape
        null = getattr(mats, "null", None)
        if not batch:
            keys, vals = [], []
            for g, mat in mats.items():
                blades = self.grade_blades[g]
                if null is None:
                    vals += (mat @ np.array([c.get(b, 0.0) for b in blades], dtype=float)).tolist()
                else:
                    vals += self.apply_null_one(g, null[g], [float(c.get(b, 0.0)) for b in blades])
                keys += blades
            return mv_from_pairs(self.algebra, keys, vals)
        out = {}
        for g, mat in mats.items():
            blades = self.grade_blades[g]
            idx = [j for j, b in enumerate(blades) if b in c]
            if not idx:
                continue
            sub = mat if len(idx) == len(blades) else mat[:, idx]
            if null is not None:
                res = self.apply_null(g, null[g], [c.get(b) for b in blades], batch)
            else:
                block = stack_rows([c[blades[j]] for j in idx], batch)
                res = sub @ (block if len(batch) == 1 else block.reshape(len(idx), -1))
            if len(batch) != 1:  # a batch of any shape: one (k, k) x (k, prod(shape)) product
                res = res.reshape((len(blades),) + batch)
            nz = np.any(sub != 0, axis=1)
            for i, b in enumerate(blades):
                if nz[i]:
                    out[b] = res[i]
        return mv_from_dict(self.algebra, out)

    def apply_null_one(self, g: int, K: np.ndarray, x: list) -> list:
        """The motor's ``K`` (``MotorMatrices.info``) on the grade-g e+/e- coefficients of one entity (floats)."""
        pairs = self.motors.null_tables(g)[1]
        for i, j in pairs:  # (a, b) -> (a, b - a)
            x[j] -= x[i]
        y = (K @ np.array(x)).tolist()
        for i, j in pairs:  # (a', w') -> (a', a' + w')
            y[j] += y[i]
        return y

    def apply_null(self, g: int, K: np.ndarray, rows: list, shape: tuple) -> np.ndarray:
        """The motor's ``K`` (``MotorMatrices.info``) on a batch: ``rows`` holds the coefficient of each
        grade-g blade (an array of ``shape``, a number, or None when absent).  Returns the (k, prod(shape))
        block of the e+/e- coefficients of the result.

        The input goes into a scratch block reused by the thread (:func:`cga_lessons.scratch.scratch`),
        the e- rows as ``b - a``; after the product the e- rows get ``a' + w'``.
        """
        pairs = self.motors.null_tables(g)[1]
        k = len(rows)
        size = math.prod(shape)
        z = scratch(k * size, "versor apply").reshape((k,) + shape)
        minus = {j: i for i, j in pairs}
        for p, v in enumerate(rows):
            i = minus.get(p)
            if i is None or rows[i] is None:
                if v is None:
                    z[p] = 0.0
                else:
                    np.copyto(z[p], v)
            elif v is None:
                np.negative(rows[i], out=z[p])
            else:
                np.subtract(v, rows[i], out=z[p])
        zf = z.reshape(k, size)
        if g == 1:  # K = d N: its e- row is (0, 0, 0, 0, d), so the product needs only the first four rows
            y = np.empty((5, size))
            np.matmul(K[:4], zf, out=y[:4])
            d = K[4, 4]
            if d == 1.0:
                np.add(y[3], zf[4], out=y[4])
            else:
                np.multiply(zf[4], d, out=y[4])
                y[4] += y[3]
            return y
        y = K @ zf
        for i, j in pairs:
            y[j] += y[i]
        return y
