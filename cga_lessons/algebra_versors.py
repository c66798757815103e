"""A versor's action as one matrix per grade, built in closed form (2.82).

A versor V acts linearly on each grade: ``X -> V X^ V^-1`` (2.82) maps grade-k
blades to grade-k blades.  For a single numeric versor,
:meth:`_VersorMatrices.versor_matrices` builds that action as one matrix per
grade, from one cached bilinear table per blade set (no sandwich products):
with ``v`` the coefficients of V, ``outer(v, v).ravel() @ T`` gives ``V ~V``
and every matrix at once.  :meth:`_VersorMatrices.apply_matrices` then applies
the matrices to one entity or to a whole batch with one matrix product per
grade, so moving a million points by a motor costs one 5x5 matrix product.
``V >> X`` (:meth:`~cga_lessons.multivector.Multivector.__rshift__`, the
sandwich of (2.98, 2.101, 2.103)) and :func:`cga_lessons.versors.apply` take
this route by themselves.

:class:`_VersorMatrices` is mixed into :class:`~cga_lessons.algebra.Algebra`,
which owns the sign table and the caches it reads; it is not used alone.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .algebra_coefficients import _is_real_single
from .multivector import _mv, _mv_pruned

if TYPE_CHECKING:
    from .multivector import Multivector


def _stack_rows(vals, shape: tuple) -> np.ndarray:
    """Stack batch coefficients into a ``(k,) + shape`` array.

    No copy when they already are the consecutive rows of one C-contiguous
    float block (the layout :func:`~cga_lessons.model.up` and
    :meth:`Algebra.apply_matrices` produce).
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
    rows = [v if type(v) is np.ndarray and v.shape == shape else np.broadcast_to(np.asarray(v, float), shape)
            for v in vals]
    return np.stack(rows)


class _VersorMatrices:
    """Versor matrices of :class:`~cga_lessons.algebra.Algebra` (mixed into it).

    Reads the algebra's ``_sign_list`` (the signs of (2.10)), ``_rev_flip``,
    ``grade_blades``, ``grades`` and the caches ``_table_cache`` and
    ``_versor_cache``, all set by ``Algebra.__init__``.
    """

    def _sandwich_table(self, keys: tuple, grades: tuple):
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
        hit = self._table_cache.get(ck)
        if hit is not None:
            return hit
        sign, flip, dim, m = self._sign_list, self._rev_flip, self.dim, len(keys)
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
        if len(self._table_cache) >= 128:  # up to ~270 kB each (16 blades, grade 2)
            self._table_cache.clear()
        self._table_cache[ck] = hit
        return hit

    def _versor_info(self, V: Multivector, grades: tuple):
        """``(d, parity, raw, unit)`` for a single numeric versor V, else None (cached by value).

        ``d = <V ~V>_0``; ``raw[g]`` is the matrix of ``X -> V X ~V`` and
        ``unit[g]`` that of ``X -> V X^ V^-1`` (2.82) on grade g.  V is a
        versor here when its blades have one parity and ``V ~V`` is a non-zero
        scalar up to round-off (1e-12 relative); in G(p, q) with p + q <= 5
        that makes V an element of the Clifford group, so it keeps grades.
        """
        c = V._c
        if not c or not _is_real_single(V) or self.n > 5:
            return None
        ck = (tuple(c), tuple(c.values()), grades)
        hit = self._versor_cache.get(ck)
        if hit is not None:
            return hit
        parity, T, slices = self._sandwich_table(ck[0], grades)
        if parity is None:
            return None
        v = np.array(ck[1])
        w = (v[:, None] * v).ravel() @ T
        dim = self.dim
        head = w[:dim].tolist()
        d = head[0]
        if not (math.isfinite(d) and d != 0 and max(map(abs, head[1:]), default=0.0) <= 1e-12 * abs(d)):
            return None
        raw, unit = {}, {}
        for g, sl in slices.items():
            k = len(self.grade_blades[g])
            raw[g] = mat = w[sl].reshape(k, k)
            unit[g] = u = mat * ((-1.0 if parity and g & 1 else 1.0) / d)
            u.flags.writeable = False  # shared through the cache
        w.flags.writeable = False
        hit = (d, parity, raw, unit)
        if len(self._versor_cache) >= 256:
            self._versor_cache.clear()
        self._versor_cache[ck] = hit
        return hit

    def versor_matrices(self, V: Multivector, grades) -> dict | None:
        """Matrices of ``X -> V X^ V^-1`` (2.82) on the given grades, or None.

        For a single numeric versor V (real coefficients, ``V ~V`` a non-zero
        scalar up to round-off) returns ``{grade: k x k matrix}`` over the
        blades of that grade in the order of (2.9) (``self.grade_blades``):
        the outermorphism of the versor, built in closed form from one cached
        bilinear table per blade set (:meth:`_sandwich_table`), with no
        multivector products.  X^ is the grade involution, applied when V is
        odd.  Returns None for anything else (SymPy or batched coefficients,
        mixed parity, not a versor); the caller then uses the plain sandwich.
        """
        info = self._versor_info(V, tuple(grades))
        return None if info is None else info[3]

    def apply_matrices(self, mats: dict, X: Multivector) -> Multivector:
        """Apply per-grade matrices (from :meth:`versor_matrices`) to X, single or batched.

        A batch costs, per grade, one ``(k, k) x (k, N)`` matrix product; when
        X's coefficient arrays of that grade are consecutive rows of one
        C-contiguous block (as :func:`~cga_lessons.model.up` and this method
        return them) no copy is made.  Results come back as the rows of one
        block.  Output blades whose matrix row is zero on X's blades are left
        out; the others are kept even if their values happen to vanish.
        """
        c = X._c
        batch = X.shape
        if not batch:
            keys, vals = [], []
            for g, mat in mats.items():
                blades = self.grade_blades[g]
                x = np.array([c.get(b, 0.0) for b in blades], dtype=float)
                keys += blades
                vals += (mat @ x).tolist()
            return _mv_pruned(self, keys, vals)
        out = {}
        for g, mat in mats.items():
            blades = self.grade_blades[g]
            idx = [j for j, b in enumerate(blades) if b in c]
            if not idx:
                continue
            sub = mat if len(idx) == len(blades) else mat[:, idx]
            block = _stack_rows([c[blades[j]] for j in idx], batch)
            if len(batch) == 1:
                res = sub @ block
            else:  # a batch of any shape: one (k, k) x (k, prod(shape)) product
                res = (sub @ block.reshape(len(idx), -1)).reshape((len(blades),) + batch)
            nz = np.any(sub != 0, axis=1)
            for i, b in enumerate(blades):
                if nz[i]:
                    out[b] = res[i]
        return _mv(self, out)
