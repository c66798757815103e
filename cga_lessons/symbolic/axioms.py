"""Symbolic derivations of sections 2.1-2.2: the Clifford product of vectors in the plane and the basis blades and
product axioms of G(p, q, r), Eqs. (2.1)-(2.10).

Each function returns a :class:`~cga_lessons.symbolic.core.Derivation`;
``d.holds`` is asserted by ``tests/test_symbolic.py``.
"""

from __future__ import annotations

from math import comb

import sympy as sp

from cga_lessons.algebra import Algebra, Multivector

from .core import signature_list
from .records import Derivation, derivation

__all__ = [
    "clifford_product_plane",
    "basis_and_product_axioms",
]

ONE = sp.Integer(1)


def exact_basis(alg: Algebra) -> list:
    """Basis vectors of ``alg`` with exact coefficient 1."""
    return [Multivector(alg, {1 << i: ONE}) for i in range(alg.n)]


# --------------------------------------------------------------- 2.1 - 2.10
@derivation
def clifford_product_plane() -> Derivation:
    """The Clifford product of vectors in R^2, Eqs. (2.1)-(2.8).

    The multiplication rules (2.4) are *solved*, not assumed: writing the
    unknown squares ``e1^2 = q1``, ``e2^2 = q2`` and the unknown symmetric
    product ``e1 e2 + e2 e1 = k`` in the distributive expansion (2.3) and
    asking that (2.2) hold for every x and y gives ``q1 = q2 = 1``, ``k = 0``.
    The algebra's products are then compared with that solution and with the
    coordinate forms of the dot (2.5) and outer (2.6) products.

    Returns
    -------
    Derivation
        values: ``rules`` (the solved q1, q2, k).
    """
    d = Derivation("Clifford product in the plane", ("2.1", "2.2", "2.3", "2.4", "2.5", "2.6", "2.7", "2.8"))
    G2 = Algebra(2)
    e1, e2 = exact_basis(G2)
    x, y, a1, a2, b1, b2 = sp.symbols("x y a1 a2 b1 b2", real=True)
    r = e1 * x + e2 * y
    d.add("2.1 r r = |r|^2", "2.1", r * r, sp.sqrt(x**2 + y**2) ** 2)
    d.add("2.2 (x e1 + y e2)^2 = x^2 + y^2", "2.2", (e1 * x + e2 * y) * (e1 * x + e2 * y), x**2 + y**2)
    expansion = (e1 * e1) * x**2 + (e2 * e2) * y**2 + (e1 * e2 + e2 * e1) * (x * y)
    d.add("2.3 distributive expansion", "2.3", expansion, r * r)
    q1, q2, k = sp.symbols("q1 q2 k")
    unknown = sp.Poly(x**2 * q1 + y**2 * q2 + x * y * k - (x**2 + y**2), x, y)
    rules = sp.solve(unknown.coeffs(), [q1, q2, k], dict=True)
    d.values["rules"] = rules
    d.add_bool("2.4 rules solved uniquely", "2.4", len(rules) == 1, lhs=rules, rhs=[{q1: 1, q2: 1, k: 0}])
    sol = rules[0] if rules else {q1: None, q2: None, k: None}
    d.add("2.4 e1^2 = solved q1", "2.4", e1 * e1, sol[q1])
    d.add("2.4 e2^2 = solved q2", "2.4", e2 * e2, sol[q2])
    d.add("2.4 e1 e2 + e2 e1 = solved k", "2.4", e1 * e2 + e2 * e1, sol[k])
    d.add("2.4 (e1 e2)^2 = -1", "2.4", (e1 * e2) * (e1 * e2), -ONE)
    a = e1 * a1 + e2 * a2
    b = e1 * b1 + e2 * b2
    e12 = e1 * e2
    d.add("2.5 a . b = a1 b1 + a2 b2", "2.5", a | b, a1 * b1 + a2 * b2)
    d.add("2.5 a . b = <ab>_0", "2.5", (a * b).grade(0), a1 * b1 + a2 * b2)
    d.add("2.6 a ^ b = (a1 b2 - a2 b1) e12", "2.6", a ^ b, e12 * (a1 * b2 - a2 * b1))
    d.add("2.7 a ^ b = -b ^ a", "2.7", a ^ b, -(b ^ a))
    d.add("2.8 ab = a.b + (a1 b2 - a2 b1) e12", "2.8", a * b, e12 * (a1 * b2 - a2 * b1) + (a1 * b1 + a2 * b2))
    return d


def basis_and_product_axioms(signatures=((2, 0, 0), (3, 0, 0), (4, 1, 0), (2, 1, 1))) -> Derivation:
    """The basis of G(p,q,r) and the product axioms, Eqs. (2.9)-(2.10).

    For each signature: the blades of grade k number C(n, k) (2.9), the
    pseudoscalar is ``e1 ^ ... ^ en`` (2.9), ``e_i e_i`` is +1, -1, 0 for the
    first p, next q and last r vectors, and ``e_i e_j = e_i ^ e_j = -e_j ^ e_i``
    for i != j (2.10).  ``signatures``: distinct ``(p, q, r)``, each of dimension 1 to 10.
    """
    return _axioms(signature_list(signatures, "basis_and_product_axioms"))


@derivation
def _axioms(signatures: tuple) -> Derivation:
    """:func:`basis_and_product_axioms` of checked signatures (computed once each)."""
    d = Derivation("Basis blades and product axioms of G(p,q,r)", ("2.9", "2.10"))
    for p, q, r in signatures:
        alg = Algebra(p, q, r)
        n = alg.n
        vs = exact_basis(alg)
        tag = f"G({p},{q},{r})"
        counts = [sum(1 for b in range(alg.dim) if alg.grades[b] == k) for k in range(n + 1)]
        d.add(f"2.9 {tag} blades per grade = C(n,k)", "2.9", counts, [comb(n, k) for k in range(n + 1)])
        wedge = vs[0]
        for v in vs[1:]:
            wedge = wedge ^ v
        d.add(f"2.9 {tag} I = e1 ^ ... ^ en", "2.9", wedge, Multivector(alg, {alg.dim - 1: ONE}))
        squares = [(vs[i] * vs[i]).scalar() for i in range(n)]
        metric = [1] * p + [-1] * q + [0] * r
        d.add(f"2.10 {tag} e_i e_i = +1, -1, 0", "2.10", squares, metric)
        pairs = [(i, j) for i in range(n) for j in range(n) if i != j]
        d.add(
            f"2.10 {tag} e_i e_j = e_i ^ e_j",
            "2.10",
            [vs[i] * vs[j] for i, j in pairs],
            [vs[i] ^ vs[j] for i, j in pairs],
        )
        d.add(
            f"2.10 {tag} e_i ^ e_j = -e_j ^ e_i",
            "2.10",
            [vs[i] ^ vs[j] for i, j in pairs],
            [-(vs[j] ^ vs[i]) for i, j in pairs],
        )
    return d
