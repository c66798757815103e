"""Norms and the inverse of a multivector (2.19).

A versor or a blade M has ``M ~M`` a scalar, so its inverse is
``M^-1 = ~M / (M ~M)`` (2.19; for a vector ``a^-1 = a / a^2``).  Any other
invertible multivector is inverted by solving the linear system of
``X -> M X`` over all blades (NumPy for numbers and batches, SymPy for
symbols).  Zero, null and singular multivectors raise
:class:`~cga_lessons.algebra.DegenerateGeometryError`.

Plain functions of a multivector X, each one of the methods of
:class:`~cga_lessons.algebra.multivector.Multivector` (``X.inv()`` is :func:`inv`, ...).
"""

from __future__ import annotations

import numpy as np

from cga_lessons.checks import degenerate, fail

from .coefficients import REAL_TYPES, is_real_single, is_sympy
from .operands import finite_out, not_finite

_INV = "Multivector.inv"


def norm2(X):
    """Squared norm <M ~M>_0 (for a point pair or blade, the square; may be negative)."""
    return X.scalar_product(~X)


def norm(X):
    """sqrt(|<M ~M>_0|)."""
    v = X.norm2()
    if is_sympy(v):
        import sympy

        return sympy.sqrt(v)
    return np.sqrt(np.abs(v))


def normalized(X):
    """M / norm(M); raises when the norm is zero."""
    func = "Multivector.normalized"
    bad = not_finite(X)
    if bad is not None:
        raise fail(func, "self", f"coefficient of {bad} is NaN or inf")
    n = X.norm()
    if not is_sympy(n) and np.any(np.asarray(n) == 0):
        raise degenerate(func, "self", "the multivector has zero norm")
    return finite_out(type(X)(X.algebra, {b: v / n for b, v in X._c.items()}), func, "self")


def inv(X):
    """Inverse (2.19).  Versors and blades use M~ / (M M~); otherwise a linear solve."""
    if not X._c:
        raise degenerate(_INV, "self", "the zero multivector has no inverse")
    bad = not_finite(X)
    if bad is not None:
        raise fail(_INV, "self", f"coefficient of {bad} is NaN or inf")
    rev = ~X
    mm = X * rev
    if any(is_sympy(v) for v in mm._c.values()):
        mm = mm.expand()  # cancel before testing for a scalar, or a blade falls into the 32x32 solve
    elif 0 in mm._c and len(mm._c) > 1:
        # a versor's M ~M is a scalar up to round-off in the other blades
        if is_real_single(mm):
            rest = max(abs(v) for b, v in mm._c.items() if b != 0) / max(abs(mm._c[0]), 1e-300)
        else:
            s0 = np.abs(np.asarray(mm._c[0], dtype=float))
            rest = max(float(np.max(np.abs(v) / np.maximum(s0, 1e-300))) for b, v in mm._c.items() if b != 0)
        if rest <= 1e-12:
            mm = type(X)(X.algebra, {0: mm._c[0]})
    if set(mm._c) <= {0}:
        d = mm._c.get(0, 0)
        if is_sympy(d):
            if d == 0:
                raise degenerate(_INV, "self", "M ~M = 0, the multivector is null and has no inverse")
        elif type(d) in REAL_TYPES:
            if d == 0:
                raise degenerate(_INV, "self", "M ~M = 0, the multivector is null and has no inverse")
        elif np.any(np.asarray(d) == 0):
            raise degenerate(_INV, "self", "M ~M = 0, the multivector is null and has no inverse")
        return finite_out(type(X)(X.algebra, {b: v / d for b, v in rev._c.items()}), _INV, "self")
    # also try M^ ~M (covers M with mixed parity such as 1 + e when scalar)
    return _general_inverse(X)


def _general_inverse(X):
    alg = X.algebra
    vals = list(X._c.values())
    if any(is_sympy(v) for v in vals):
        import sympy

        mat = sympy.zeros(alg.dim, alg.dim)
        pos = {b: i for i, b in enumerate(alg.blade_order)}
        for j, b in enumerate(alg.blade_order):
            for a, c in X._c.items():
                s = alg._sign_list[a][b]
                if s:
                    mat[pos[a ^ b], j] += s * c
        rhs = sympy.zeros(alg.dim, 1)
        rhs[pos[0], 0] = 1
        if mat.det() == 0:
            raise degenerate(_INV, "self", "the multivector is not invertible")
        sol = mat.LUsolve(rhs)
        return type(X)(alg, {b: sympy.simplify(sol[pos[b], 0]) for b in alg.blade_order}, _prune=True)
    shape = X.shape
    blades = alg.blade_order
    pos = {b: i for i, b in enumerate(blades)}
    mats = np.zeros(shape + (alg.dim, alg.dim))
    for j, b in enumerate(blades):
        for a, c in X._c.items():
            s = alg._sign_list[a][b]
            if s:
                mats[..., pos[a ^ b], j] += s * np.asarray(c, dtype=float)
    rhs = np.zeros(shape + (alg.dim,))
    rhs[..., pos[0]] = 1.0
    try:
        sol = np.linalg.solve(mats, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError as exc:
        raise degenerate(_INV, "self", "the multivector is not invertible") from exc
    if not np.all(np.isfinite(sol)):
        raise degenerate(_INV, "self", "the multivector is not invertible (singular to working precision)")
    if sol.ndim == 1:
        return type(X)(alg, {b: float(sol[i]) for i, b in enumerate(blades) if sol[i] != 0})
    return type(X)(alg, {b: sol[..., i] for i, b in enumerate(blades)})
