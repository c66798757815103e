"""Products of multivectors: the cached (blade, blade, result, sign) terms and the code that runs them.

Every product of :mod:`cga_lessons.algebra` (geometric (2.11), outer (2.14,
2.30), the thesis's inner product (2.21-2.29), left contraction, scalar
product) loops over the non-zero blades of its two operands only.  The terms
of one pair of blade sets, with their signs from the axioms (2.10), are found
once and cached, and then run by one of three routes (see
:meth:`ProductTerms.product`):

* the first time a pair of blade sets meets, an interpreted loop over its
  terms (:func:`run_product`);
* from the second time on, compiled straight-line code, one Python expression
  per result blade (:func:`compile_product`; the same code for floats, arrays
  and SymPy, and the same order of operations as the loop, so the two agree to
  the bit);
* two single float multivectors with many terms (a motor times a point), one
  small matrix product ``outer(a, b).ravel() @ table`` with a cached table of
  signs (agrees to round-off).

Each :class:`~cga_lessons.algebra.Algebra` holds one :class:`ProductTerms` (its cache of terms and compiled
code, reading the algebra's sign table); :func:`left_matrix` is the matrix of a left product, behind
:meth:`Algebra.left_matrix <cga_lessons.algebra.Algebra.left_matrix>`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.checks import fail, finite_result

from .coefficients import is_float_single, is_real_single
from .multivector import Multivector, mv_from_pairs
from .operands import blade_bitmaps, finite_multivector, same_algebra

PRODUCT_CHUNK = 48  # terms per Python expression in a compiled product (keeps the parser's nesting shallow)


def compile_product(groups, n_a: int, n_b: int):
    """Compile straight-line code for one product of two blade sets.

    ``groups`` lists, per result blade, its ``(i, j, sign)`` terms (positions
    in the two coefficient sequences).  Each result is summed left to right in
    the order of the terms, exactly as the interpreted loop does, so the two
    routes give identical numbers (and identical SymPy expressions).
    """
    lines = ["def _product(A, B):"]
    if n_a:
        lines.append("    " + "".join(f"a{i}, " for i in range(n_a)) + "= A")
    if n_b:
        lines.append("    " + "".join(f"b{j}, " for j in range(n_b)) + "= B")
    names = []
    for k, terms in enumerate(groups):
        name = f"r{k}"
        names.append(name)
        for start in range(0, len(terms), PRODUCT_CHUNK):
            parts = []
            for n, (i, j, sg) in enumerate(terms[start : start + PRODUCT_CHUNK]):
                if start == 0 and n == 0:
                    parts.append(f"-(a{i} * b{j})" if sg < 0 else f"a{i} * b{j}")
                else:
                    parts.append(f"{'-' if sg < 0 else '+'} a{i} * b{j}")
            head = "" if start == 0 else f"{name} "
            lines.append(f"    {name} = {head}{' '.join(parts)}")
    lines.append("    return (" + "".join(f"{nm}, " for nm in names) + ")")
    namespace: dict = {}
    exec(compile("\n".join(lines), "<cga_lessons product>", "exec"), namespace)  # noqa: S102
    return namespace["_product"]


def run_product(groups, va, vb):
    """The interpreted form of :func:`compile_product` (same order of operations)."""
    out = []
    for terms in groups:
        i, j, sg = terms[0]
        acc = va[i] * vb[j]
        if sg < 0:
            acc = -acc
        for i, j, sg in terms[1:]:
            if sg < 0:
                acc = acc - va[i] * vb[j]
            else:
                acc = acc + va[i] * vb[j]
        out.append(acc)
    return out


class ProductTerms:
    """The products of one :class:`~cga_lessons.algebra.Algebra`: its cache of terms and compiled code.

    Reads the algebra's ``grades`` and its table of signs (2.10); the algebra holds one and calls
    :meth:`product` for every product of its multivectors.
    """

    #: uses of one pair of blade sets before its product is compiled to straight-line code
    COMPILE_AFTER = 2
    #: products with at least this many terms run as one small matrix product for float coefficients
    TABLE_TERMS = 40

    def __init__(self, algebra, cache_limit: int = 1024):
        self.algebra = algebra
        self.grades = algebra.grades
        self.sign_list = algebra._sign_list
        #: entries per cache; a full cache is emptied and refilled
        self.cache_limit = cache_limit
        #: ``{(blades of A, blades of B, kind): entry}``, see :meth:`entry`
        self.cache: dict = {}

    def terms(self, keys_a: tuple, keys_b: tuple, kind: str):
        """List of (blade_a, blade_b, result_blade, sign) for a product (cached by :meth:`entry`).

        ``kind`` is one of ``"gp"`` (geometric), ``"op"`` (outer),
        ``"ip"`` (the thesis's inner product), ``"lc"`` (left contraction),
        ``"sp"`` (scalar product).
        """
        grades = self.grades
        sign = self.sign_list
        terms = []
        for a in keys_a:
            ga = grades[a]
            for b in keys_b:
                s = sign[a][b]
                if s == 0:
                    continue
                r = a ^ b
                gr = grades[r]
                gb = grades[b]
                if kind == "op" and gr != ga + gb:
                    continue
                if kind == "ip" and (ga == 0 or gb == 0 or gr != abs(ga - gb)):
                    continue
                if kind == "lc" and gr != gb - ga:
                    continue
                if kind == "sp" and gr != 0:
                    continue
                terms.append((a, b, r, s))
        return terms

    def entry(self, key):
        """Cache entry ``[compiled or None, result blades, uses, grouped terms, table or None]``."""
        keys_a, keys_b, kind = key
        terms = self.terms(keys_a, keys_b, kind)
        pos_a = {b: i for i, b in enumerate(keys_a)}
        pos_b = {b: j for j, b in enumerate(keys_b)}
        grouped: dict = {}
        for a, b, r, s in terms:
            grouped.setdefault(r, []).append((pos_a[a], pos_b[b], s))
        table = None
        if len(terms) >= self.TABLE_TERMS and len(keys_a) * len(keys_b) <= 256:  # tables stay <= 64 kB
            nb = len(keys_b)
            table = np.zeros((len(keys_a) * nb, len(grouped)))
            for col, group in enumerate(grouped.values()):
                for i, j, s in group:
                    table[i * nb + j, col] = s
        if len(self.cache) >= self.cache_limit:
            self.cache.clear()
        entry = [None, tuple(grouped), 0, list(grouped.values()), table]
        self.cache[key] = entry
        return entry

    def product(self, A: Multivector, B: Multivector, kind: str) -> Multivector:
        """Product of two multivectors over their non-zero blades only.

        The terms of one pair of blade sets are found once and cached.  From
        the second use on they run as compiled straight-line code (one Python
        expression per result blade), the same code for floats, arrays and
        SymPy coefficients.  Two single float multivectors with many terms
        (a motor times a point) instead take one small matrix product:
        ``outer(a, b).ravel() @ table`` with a cached table of signs.
        """
        ca, cb = A._c, B._c
        key = (tuple(ca), tuple(cb), kind)
        entry = self.cache.get(key)
        if entry is None:
            entry = self.entry(key)
        table = entry[4]
        if table is not None and is_float_single(A) and is_float_single(B):
            va = np.fromiter(ca.values(), dtype=float, count=len(ca))
            vb = np.fromiter(cb.values(), dtype=float, count=len(cb))
            return mv_from_pairs(self.algebra, entry[1], (np.outer(va, vb).ravel() @ table).tolist())
        fn = entry[0]
        if fn is None:
            entry[2] += 1
            if entry[2] < self.COMPILE_AFTER:
                return mv_from_pairs(
                    self.algebra, entry[1], run_product(entry[3], list(ca.values()), list(cb.values()))
                )
            fn = entry[0] = compile_product(entry[3], len(ca), len(cb))
        return mv_from_pairs(self.algebra, entry[1], fn(ca.values(), cb.values()))


def left_matrix(alg, A: Multivector, blades_in=None, blades_out=None) -> np.ndarray:
    """Matrix of ``X -> A X`` in the algebra ``alg`` restricted to the given input/output blades (A one numeric
    multivector); :meth:`Algebra.left_matrix <cga_lessons.algebra.Algebra.left_matrix>`."""
    func = "Algebra.left_matrix"
    same_algebra(A, alg, func, "A", Multivector)
    if not is_real_single(A):
        raise fail(func, "A", "expected one multivector with real number coefficients (not a batch, not SymPy)")
    finite_multivector(A, func, "A")
    blades_in = alg.blade_order if blades_in is None else blade_bitmaps(blades_in, func, "blades_in", alg.dim)
    blades_out = alg.blade_order if blades_out is None else blade_bitmaps(blades_out, func, "blades_out", alg.dim)
    pos = {b: i for i, b in enumerate(blades_out)}
    mat = np.zeros((len(blades_out), len(blades_in)))
    for j, b in enumerate(blades_in):
        for a, c in A._c.items():
            s = alg._sign_list[a][b]
            r = a ^ b
            if s and r in pos:
                mat[pos[r], j] += s * float(c)
    return finite_result(mat, func, "the matrix")
