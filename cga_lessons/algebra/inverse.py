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
        if not is_sympy(d) and all(X.algebra.grades[b] == 1 for b in X._c):
            d = vector_square(X, d)
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


_EPS = float(np.finfo(float).eps)


def vector_square(X, d):
    """``X X`` of a real vector X (single or a batch), ``d`` as the product ``X ~X`` gave it, honest about its
    round-off (2.19).  That product sums the squared coefficients with their signs, which loses ``eps |X|^2``: in
    G(4,1) a sphere |c| from the origin has e+ and e- coefficients near |c|^2/2, so the loss is ~eps |c|^4 where
    ``X X`` (its squared radius) may be 1.  Where d is below that bound, ``X X`` is summed again with each negative
    basis vector paired with a positive one, ``a^2 - b^2 = (a - b)(a + b)`` (e+ with e-: the weight times twice
    the e part), terms of the size of the geometry, and kept when above their own round-off; below it, X is null
    to working precision and has no inverse (zero is returned: the caller raises).  d itself where it was sound,
    so that those inverses keep their bits."""
    alg = X.algebra
    if type(d) is float:  # one vector: the test in floats (a few flops where it is sound)
        size = 0.0
        for v in X._c.values():
            size += v * v
        if abs(d) > (alg.n + 1) * _EPS * size or not size < np.inf:
            return d
    coef = [np.asarray(X._c.get(1 << i, 0.0), dtype=float) for i in range(alg.n)]
    with np.errstate(over="ignore", invalid="ignore"):
        size = sum(v * v for v in coef)
        if not np.all(np.isfinite(size)):
            return d
        sound = np.abs(np.asarray(d, dtype=float)) > (alg.n + 1) * _EPS * size
        if np.all(sound):
            return d
        m = alg.metric
        pos, neg = [i for i in range(alg.n) if m[i] > 0], [i for i in range(alg.n) if m[i] < 0]
        pairs = list(zip(reversed(pos), neg))
        paired = {i for pair in pairs for i in pair}
        terms = [(coef[a] - coef[b]) * (coef[a] + coef[b]) for a, b in pairs]
        terms += [m[i] * coef[i] * coef[i] for i in range(alg.n) if m[i] and i not in paired]
        dh = sum(terms)
        bound = (len(terms) + 3) * _EPS * sum(np.abs(t) for t in terms)
    out = np.where(sound, d, np.where(np.abs(dh) > bound, dh, 0.0))
    return float(out) if out.ndim == 0 else out


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
