"""The geometric algebra G(p, q, r) of chapter 2 (section 2.2).

A basis blade is a bitmap: bit ``i`` set means the basis vector ``e_{i+1}`` is a
factor, in increasing order.  The sign of the product of two blades comes from
the axioms (2.10): reorder the factors (each swap of two different vectors
flips the sign, ``e_i e_j = -e_j e_i``) and contract equal factors with their
square (+1, -1 or 0).

A :class:`Multivector` is a sparse map ``blade bitmap -> coefficient``.  The
coefficient may be a Python/NumPy float, a NumPy array (a *batch*: one
multivector per element, e.g. one conformal point per row of a point cloud) or
a SymPy expression.  Every product runs over the non-zero blades only, with
the (blade, blade, result, sign) terms found once per pair of blade sets and
cached, so one code path serves the numeric chapters and the symbolic proofs.

How a product runs (see :meth:`Algebra._product`; the routes agree to the bit
except the float table, which agrees to round-off):

* the first time a pair of blade sets meets, an interpreted loop over its terms;
* from the second time on, compiled straight-line code, one Python expression
  per result blade (the same code for floats, arrays and SymPy);
* two single float multivectors with many terms (a motor times a point), one
  small matrix product ``outer(a, b).ravel() @ table`` with a cached table of
  signs, which costs a few NumPy calls instead of a Python operation per term.

A versor acts linearly on each grade (2.82).  For a single numeric versor,
:meth:`Algebra.versor_matrices` builds that action as one matrix per grade in
closed form, from one cached bilinear table per blade set (no sandwich
products), and :meth:`Algebra.apply_matrices` applies it to one entity or to a
whole batch with one matrix product; ``V >> X`` and
:func:`cga_lessons.versors.apply` take this route by themselves.

Operators (the thesis's notation on the left)::

    A B         A * B           geometric product (2.11)
    A ^ B       A ^ B           outer product (2.14, 2.30)
    A . B       A | B           the thesis's inner product (2.21-2.29), with
                                scalar . M = 0 (2.28)
    A _| B      A << B          left contraction (not the thesis's; offered
                                because most modern texts use it)
    M~          ~M              reverse (2.32-2.34)
    M^          M.involute()    grade involution (2.35)
    M*          M.dual()        dual M I^-1 (2.31)
    M^-1        M.inv()         inverse (2.19; versors and general)
    A x B       commutator(A,B) commutator product (2.36)
    exp(B)      exp(B)          exponential of a bivector (2.37), closed form
    <M>_k       M.grade(k)      grade projection (2.18)
    V X V~      V >> X          sandwich product (2.98, 2.101, 2.103)
"""

from __future__ import annotations

import math
import numbers
from functools import cache
from itertools import combinations

import numpy as np

__all__ = [
    "Algebra",
    "Multivector",
    "GeometryError",
    "DegenerateGeometryError",
    "InvalidInputError",
    "commutator",
    "exp",
]


class GeometryError(ValueError):
    """Base class of the errors raised for bad input."""


class DegenerateGeometryError(GeometryError):
    """The input describes a degenerate configuration (coincident points, ...)."""


class InvalidInputError(GeometryError):
    """The input has the wrong shape, type, or contains NaN/inf."""


def _popcount(x: int) -> int:
    return bin(x).count("1")


def _reorder_sign(a: int, b: int) -> int:
    """Sign from moving the factors of blade ``b`` past those of blade ``a``.

    Counts, for every factor of ``b``, the factors of ``a`` with a higher index
    that it has to pass (each pass is one anticommutation of (2.10)).
    """
    a >>= 1
    swaps = 0
    while a:
        swaps += _popcount(a & b)
        a >>= 1
    return -1 if swaps & 1 else 1


_PLAIN_TYPES = frozenset((float, int, np.float64, np.ndarray))


def _is_sympy(x) -> bool:
    if type(x) in _PLAIN_TYPES:
        return False
    return hasattr(x, "free_symbols") and not isinstance(x, np.ndarray)


def _is_zero(c) -> bool:
    """True when a coefficient is exactly zero (float, array or SymPy)."""
    t = type(c)
    if t is float or t is int or t is np.float64:
        return c == 0
    if t is np.ndarray:
        if c.dtype.kind in "fiub":
            return not np.count_nonzero(c)  # NaN counts as non-zero, as in any()
        return not c.any()
    if isinstance(c, np.ndarray):
        return not np.any(c)
    if isinstance(c, numbers.Number):
        return c == 0
    if _is_sympy(c):
        return c == 0 or c.is_zero is True
    return c == 0


#: Coefficient types of a single numeric multivector (the versor fast paths take only these).
_REAL_TYPES = frozenset((float, np.float64, int))
#: ... and of the operands of a product sent through a float table (ints stay exact in the other routes).
_FLOAT_TYPES = frozenset((float, np.float64))


def _is_real_single(M) -> bool:
    """True when every coefficient of ``M`` is one real number (no batch, no SymPy)."""
    real = _REAL_TYPES
    for v in M._c.values():
        if type(v) not in real:
            return False
    return True


def _is_float_single(M) -> bool:
    """True when every coefficient of ``M`` is one float."""
    flt = _FLOAT_TYPES
    for v in M._c.values():
        if type(v) not in flt:
            return False
    return True


def _absmax(v) -> float:
    """max |v| of a real coefficient, a number or an array, as a float (NaN stays NaN)."""
    t = type(v)
    if t is float or t is np.float64 or t is int:
        return float(abs(v))
    return float(np.max(np.abs(v)))


def _all_finite(arr: np.ndarray) -> bool:
    """``np.isfinite(arr).all()`` for a float array, screened cheaply first.

    For a large contiguous float64 array the dot product ``a . a`` is finite
    exactly when no element is NaN or inf, unless the squares overflow (only
    for |a| > 1e154), in which case the full test decides.
    """
    if arr.size <= 8:
        return all(map(math.isfinite, arr.ravel().tolist()))
    if arr.dtype == np.float64 and arr.size > 512 and arr.flags.c_contiguous:
        flat = arr.reshape(-1)
        with np.errstate(over="ignore", invalid="ignore"):
            if np.isfinite(flat @ flat):
                return True
    return bool(np.isfinite(arr).all())


def _mv(algebra, coeffs: dict):
    """A Multivector from a dict that is already pruned (no checks, no copy)."""
    m = object.__new__(Multivector)
    m.algebra = algebra
    m._c = coeffs
    return m


def _mv_pruned(algebra, keys, values):
    """A Multivector from parallel keys and values, dropping exact zeros."""
    out = {}
    for k, v in zip(keys, values):
        t = type(v)
        if t is float or t is np.float64 or t is int:
            if v != 0:
                out[k] = v
        elif not _is_zero(v):
            out[k] = v
    m = object.__new__(Multivector)
    m.algebra = algebra
    m._c = out
    return m


def _is_real_batch(M) -> bool:
    """True when ``M`` is a numeric batch: real arrays (at least one) and real numbers, no SymPy."""
    real = _REAL_TYPES
    seen = False
    for v in M._c.values():
        if type(v) is np.ndarray:
            if v.dtype.kind not in "fiu" or not v.ndim:
                return False
            seen = True
        elif type(v) not in real:
            return False
    return seen


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


_CHUNK = 48  # terms per Python expression in a compiled product (keeps the parser's nesting shallow)


def _compile_product(groups, n_a: int, n_b: int):
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
        for start in range(0, len(terms), _CHUNK):
            parts = []
            for n, (i, j, sg) in enumerate(terms[start:start + _CHUNK]):
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


def _run_product(groups, va, vb):
    """The interpreted form of :func:`_compile_product` (same order of operations)."""
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


class Algebra:
    """The geometric algebra G(p, q, r), equations (2.9)-(2.10).

    Parameters
    ----------
    p, q, r : int
        Number of basis vectors squaring to +1, -1 and 0 (2.10).
    labels : sequence of str, optional
        One short label per basis vector, used in blade names: the vector
        ``i`` is called ``"e" + labels[i]`` and a blade concatenates labels
        (``"e12"``, ``"e1+"``, ``"e123+-"``).  Default ``"1", "2", ...``.

    Examples
    --------
    >>> G2 = Algebra(2)
    >>> e1, e2 = G2.basis_vectors()
    >>> e1 * e2 == -(e2 * e1)
    True
    >>> float((e1 * e2) ** 2)
    -1.0
    """

    def __init__(self, p: int, q: int = 0, r: int = 0, labels=None):
        for name, v in (("p", p), ("q", q), ("r", r)):
            if not isinstance(v, numbers.Integral) or v < 0:
                raise InvalidInputError(f"Algebra: {name} must be a non-negative integer, got {v!r}")
        self.p, self.q, self.r = int(p), int(q), int(r)
        self.n = n = self.p + self.q + self.r
        if n > 10:
            raise InvalidInputError(f"Algebra: dimension p+q+r = {n} is too large for this dense sign table (max 10)")
        if labels is None:
            labels = [str(i + 1) for i in range(n)] if n < 10 else [f"({i + 1})" for i in range(n)]
        labels = list(labels)
        if len(labels) != n or len(set(labels)) != n:
            raise InvalidInputError(f"Algebra: need {n} distinct labels, got {labels!r}")
        self.labels = labels
        self.metric = tuple([1] * self.p + [-1] * self.q + [0] * self.r)
        self.dim = 1 << n
        # Product sign table (2.10): sign[a, b] in {-1, 0, 1}; result blade a ^ b.
        sign = np.zeros((self.dim, self.dim), dtype=np.int8)
        for a in range(self.dim):
            for b in range(self.dim):
                s = _reorder_sign(a, b)
                common = a & b
                i = 0
                while common:
                    if common & 1:
                        s *= self.metric[i]
                    common >>= 1
                    i += 1
                sign[a, b] = s
        self._sign = sign
        self._sign_list = sign.tolist()
        self.grades = [_popcount(b) for b in range(self.dim)]
        # Blades in the order of grade, then index (the order of (2.9)).
        order = []
        for k in range(n + 1):
            for combo in combinations(range(n), k):
                order.append(sum(1 << i for i in combo))
        self.blade_order = order
        self.blade_names = {b: self._make_name(b) for b in range(self.dim)}
        self._name_to_blade = {}
        for b, nm in self.blade_names.items():
            self._name_to_blade[nm] = (b, 1)
        self.pseudoscalar_blade = self.dim - 1
        self._product_cache: dict = {}
        self._table_cache: dict = {}
        self._versor_cache: dict = {}
        #: True where the reverse (2.32) flips the sign of a blade
        self._rev_flip = [bool((g * (g - 1) // 2) & 1) for g in self.grades]
        #: blades of each grade in the order of (2.9)
        self.grade_blades = [[b for b in order if self.grades[b] == k] for k in range(n + 1)]

    # ------------------------------------------------------------------ names
    def _make_name(self, blade: int) -> str:
        if blade == 0:
            return "1"
        return "e" + "".join(self.labels[i] for i in range(self.n) if blade >> i & 1)

    def parse_blade(self, name: str) -> tuple[int, int]:
        """Return ``(bitmap, sign)`` for a blade name, in any factor order.

        ``"e31"`` gives the bitmap of ``e13`` and sign -1 (``e31 = -e13``).
        A repeated factor is contracted with its square, so ``"e11"`` is the
        scalar 1 in G(3).
        """
        if name in self._name_to_blade:
            return self._name_to_blade[name]
        if name in ("1", "", "scalar"):
            return 0, 1
        if not name.startswith("e"):
            raise KeyError(f"{name!r} is not a blade name of G{self.signature}")
        rest = name[1:]
        factors = []
        labels = sorted(self.labels, key=len, reverse=True)
        while rest:
            for lab in labels:
                if rest.startswith(lab):
                    factors.append(self.labels.index(lab))
                    rest = rest[len(lab):]
                    break
            else:
                raise KeyError(f"{name!r} is not a blade name of G{self.signature} (labels {self.labels})")
        blade, sign = 0, 1
        for i in factors:
            sign *= self._sign_list[blade][1 << i]
            blade ^= 1 << i
        if sign == 0:
            raise KeyError(f"{name!r} is zero in G{self.signature} (a null vector squared)")
        self._name_to_blade[name] = (blade, sign)
        return blade, sign

    @property
    def signature(self) -> tuple[int, int, int]:
        return (self.p, self.q, self.r)

    def __repr__(self) -> str:
        return f"Algebra({self.p}, {self.q}, {self.r})"

    # ----------------------------------------------------------- constructors
    def blade(self, name: str, coeff=1.0) -> Multivector:
        """The basis blade called ``name`` (any factor order) times ``coeff``."""
        b, s = self.parse_blade(name)
        return Multivector(self, {b: coeff if s == 1 else -coeff})

    def scalar(self, value) -> Multivector:
        return Multivector(self, {0: value})

    def basis_vectors(self) -> list[Multivector]:
        """The n basis vectors e_1 ... e_n (2.9)."""
        return [Multivector(self, {1 << i: 1.0}) for i in range(self.n)]

    def vector(self, coeffs) -> Multivector:
        """A grade-1 multivector from ``coeffs`` of shape (n,) or (N, n) (a batch)."""
        arr = coeffs
        if isinstance(arr, (list, tuple)) and arr and all(_is_sympy(c) for c in arr):
            return Multivector(self, {1 << i: c for i, c in enumerate(arr) if not _is_zero(c)})
        arr = np.asarray(coeffs)
        if arr.shape[-1] != self.n:
            raise InvalidInputError(f"vector: last axis must have length {self.n}, got shape {arr.shape}")
        if arr.dtype == object:
            return Multivector(self, {1 << i: arr[..., i] if arr.ndim > 1 else arr[i] for i in range(self.n)})
        arr = arr.astype(float)
        if arr.ndim == 1:
            return Multivector(self, {1 << i: float(arr[i]) for i in range(self.n) if arr[i] != 0})
        return Multivector(self, {1 << i: arr[..., i] for i in range(self.n)})

    def pseudoscalar(self) -> Multivector:
        """The unit pseudoscalar I = e_1 ^ ... ^ e_n (2.9)."""
        return Multivector(self, {self.pseudoscalar_blade: 1.0})

    def from_array(self, arr, blades=None) -> Multivector:
        """Multivector from an array whose last axis runs over ``blades``.

        ``blades`` defaults to all blades in the order of (2.9)
        (``self.blade_order``).
        """
        blades = self.blade_order if blades is None else blades
        arr = np.asarray(arr, dtype=float)
        if arr.shape[-1] != len(blades):
            raise InvalidInputError(f"from_array: last axis must have length {len(blades)}, got shape {arr.shape}")
        if arr.ndim == 1:
            return Multivector(self, {b: float(arr[i]) for i, b in enumerate(blades) if arr[i] != 0})
        return Multivector(self, {b: arr[..., i] for i, b in enumerate(blades)})

    # ---------------------------------------------------------- product terms
    def _terms(self, keys_a: tuple, keys_b: tuple, kind: str):
        """List of (blade_a, blade_b, result_blade, sign) for a product (cached by :meth:`_product_entry`).

        ``kind`` is one of ``"gp"`` (geometric), ``"op"`` (outer),
        ``"ip"`` (the thesis's inner product), ``"lc"`` (left contraction),
        ``"sp"`` (scalar product).
        """
        grades = self.grades
        sign = self._sign_list
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

    #: uses of one pair of blade sets before its product is compiled to straight-line code
    _COMPILE_AFTER = 2
    _CACHE_LIMIT = 1024  # entries per cache; a full cache is emptied and refilled

    #: products with at least this many terms run as one small matrix product for float coefficients
    _TABLE_TERMS = 40

    def _product_entry(self, key):
        """Cache entry ``[compiled or None, result blades, uses, grouped terms, table or None]``."""
        keys_a, keys_b, kind = key
        terms = self._terms(keys_a, keys_b, kind)
        pos_a = {b: i for i, b in enumerate(keys_a)}
        pos_b = {b: j for j, b in enumerate(keys_b)}
        grouped: dict = {}
        for a, b, r, s in terms:
            grouped.setdefault(r, []).append((pos_a[a], pos_b[b], s))
        table = None
        if len(terms) >= self._TABLE_TERMS and len(keys_a) * len(keys_b) <= 256:  # tables stay <= 64 kB
            nb = len(keys_b)
            table = np.zeros((len(keys_a) * nb, len(grouped)))
            for col, group in enumerate(grouped.values()):
                for i, j, s in group:
                    table[i * nb + j, col] = s
        if len(self._product_cache) >= self._CACHE_LIMIT:
            self._product_cache.clear()
        entry = [None, tuple(grouped), 0, list(grouped.values()), table]
        self._product_cache[key] = entry
        return entry

    def _product(self, A: Multivector, B: Multivector, kind: str) -> Multivector:
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
        entry = self._product_cache.get(key)
        if entry is None:
            entry = self._product_entry(key)
        table = entry[4]
        if table is not None and _is_float_single(A) and _is_float_single(B):
            va = np.fromiter(ca.values(), dtype=float, count=len(ca))
            vb = np.fromiter(cb.values(), dtype=float, count=len(cb))
            return _mv_pruned(self, entry[1], (np.outer(va, vb).ravel() @ table).tolist())
        fn = entry[0]
        if fn is None:
            entry[2] += 1
            if entry[2] < self._COMPILE_AFTER:
                return _mv_pruned(self, entry[1], _run_product(entry[3], list(ca.values()), list(cb.values())))
            fn = entry[0] = _compile_product(entry[3], len(ca), len(cb))
        return _mv_pruned(self, entry[1], fn(ca.values(), cb.values()))

    # ------------------------------------------------------ versor matrices
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

    # ------------------------------------------------ linear maps as matrices
    def left_matrix(self, A: Multivector, blades_in=None, blades_out=None) -> np.ndarray:
        """Matrix of ``X -> A X`` restricted to the given input/output blades (numeric A)."""
        blades_in = self.blade_order if blades_in is None else blades_in
        blades_out = self.blade_order if blades_out is None else blades_out
        pos = {b: i for i, b in enumerate(blades_out)}
        mat = np.zeros((len(blades_out), len(blades_in)))
        for j, b in enumerate(blades_in):
            for a, c in A._c.items():
                s = self._sign_list[a][b]
                r = a ^ b
                if s and r in pos:
                    mat[pos[r], j] += s * float(c)
        return mat


class Multivector:
    """A multivector of an :class:`Algebra`: a sparse map blade -> coefficient.

    Coefficients are floats, NumPy arrays (a batch, all of one shape) or SymPy
    expressions.  Read a coefficient by blade name, ``X["e12"]`` (zero where
    absent; ``X["e21"]`` is ``-X["e12"]``); :meth:`blades` lists the non-zero
    ones.
    """

    __slots__ = ("algebra", "_c")
    __array_priority__ = 1000  # so that ndarray * Multivector defers to us
    __array_ufunc__ = None

    def __init__(self, algebra: Algebra, coeffs: dict | None = None, _prune: bool = False):
        self.algebra = algebra
        c = coeffs or {}
        if _prune:
            c = {k: v for k, v in c.items() if not _is_zero(v)}
        self._c = c

    def _sympy_(self):
        # Tell SymPy a multivector is not one of its expressions, so that
        # ``sympy_expr * X`` falls back to Multivector.__rmul__.
        import sympy

        raise sympy.SympifyError(self)

    # -------------------------------------------------------------- access
    def __getitem__(self, name):
        if isinstance(name, str):
            b, s = self.algebra.parse_blade(name)
        else:
            b, s = int(name), 1
        v = self._c.get(b, 0.0)
        return v if s == 1 else -v

    def blades(self) -> list[str]:
        """Names of the blades with a non-zero coefficient, in the order of (2.9)."""
        order = self.algebra.blade_order
        return [self.algebra.blade_names[b] for b in order if b in self._c]

    def items(self):
        """(blade name, coefficient) pairs in the order of (2.9)."""
        return [(self.algebra.blade_names[b], self._c[b]) for b in self.algebra.blade_order if b in self._c]

    @property
    def coeffs(self) -> dict:
        """The raw sparse map ``{bitmap: coefficient}`` (read only by convention)."""
        return self._c

    @property
    def shape(self) -> tuple:
        """Batch shape: () for a single multivector, (N,) for N of them."""
        for v in self._c.values():
            if isinstance(v, np.ndarray):
                return v.shape
        return ()

    def __len__(self):
        shape = self.shape
        if not shape:
            raise TypeError("a single multivector has no len(); use .shape for batches")
        return shape[0]

    def __getattr__(self, name):
        # blade access as attributes is deliberately not offered: X["e12"] is explicit.
        raise AttributeError(name)

    def batch_item(self, index) -> Multivector:
        """One multivector (or a sub-batch) of a batch: ``X.batch_item(3)``."""
        out = {}
        for b, v in self._c.items():
            out[b] = v[index] if isinstance(v, np.ndarray) else v
        return Multivector(self.algebra, out, _prune=True)

    def to_array(self, blades=None) -> np.ndarray:
        """Coefficients as an array, last axis over ``blades`` (default all, order of (2.9))."""
        alg = self.algebra
        blades = alg.blade_order if blades is None else blades
        shape = self.shape
        out = np.zeros(shape + (len(blades),))
        for i, b in enumerate(blades):
            if b in self._c:
                out[..., i] = self._c[b]
        return out

    def grades_present(self) -> list[int]:
        return sorted({self.algebra.grades[b] for b in self._c})

    # ---------------------------------------------------------- arithmetic
    def _coerce(self, other) -> Multivector:
        if isinstance(other, Multivector):
            if other.algebra is not self.algebra:
                raise InvalidInputError(f"cannot combine multivectors of {self.algebra} and {other.algebra}")
            return other
        if isinstance(other, np.ndarray) or isinstance(other, numbers.Number) or _is_sympy(other):
            return Multivector(self.algebra, {0: other}, _prune=True)
        return NotImplemented

    def __add__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        out = dict(self._c)
        for b, v in other._c.items():
            out[b] = out[b] + v if b in out else v
        return Multivector(self.algebra, out, _prune=True)

    __radd__ = __add__

    def __neg__(self):
        return Multivector(self.algebra, {b: -v for b, v in self._c.items()})

    def __pos__(self):
        return self

    def __sub__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self + (-other)

    def __rsub__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return other + (-self)

    def _scale(self, k):
        return Multivector(self.algebra, {b: v * k for b, v in self._c.items()}, _prune=True)

    def __mul__(self, other):
        """Geometric product (2.11)."""
        if isinstance(other, Multivector):
            return self.algebra._product(self, self._coerce(other), "gp")
        if isinstance(other, (numbers.Number, np.ndarray)) or _is_sympy(other):
            return self._scale(other)
        return NotImplemented

    def __rmul__(self, other):
        if isinstance(other, (numbers.Number, np.ndarray)) or _is_sympy(other):
            return Multivector(self.algebra, {b: other * v for b, v in self._c.items()}, _prune=True)
        return NotImplemented

    def __truediv__(self, other):
        """Division: by a scalar, or right multiplication by the inverse (2.19)."""
        if isinstance(other, Multivector):
            return self * other.inv()
        if isinstance(other, (numbers.Number, np.ndarray)) or _is_sympy(other):
            return Multivector(self.algebra, {b: v / other for b, v in self._c.items()})
        return NotImplemented

    def __rtruediv__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return other * self.inv()

    def __xor__(self, other):
        """Outer product (2.14, 2.30); a scalar factor just scales (2.20)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "op")

    def __rxor__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(other, self, "op")

    def __or__(self, other):
        """The thesis's inner product (2.21-2.29): <A_r B_s>_|r-s|, zero with a scalar (2.28)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "ip")

    def __ror__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(other, self, "ip")

    def __lshift__(self, other):
        """Left contraction A _| B: <A_r B_s>_{s-r} (zero when r > s)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "lc")

    def __rshift__(self, other):
        """Sandwich ``V >> X = V X ~V`` (2.98, 2.101, 2.103).

        A single numeric versor V (``V ~V`` a non-zero scalar, one parity, in
        an algebra of dimension at most 5) on a numeric X, one entity or a
        batch, takes the fast path: the matrix of ``X -> V X ~V`` on each grade
        of X, built once in closed form (:meth:`Algebra.versor_matrices`),
        times X's coefficients.  A versor keeps grades (2.82), so the result
        has X's grades only, where the plain product adds round-off in the
        others.  Anything else is the plain product ``V * X * ~V``.
        """
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        if other.algebra is self.algebra and other._c and (_is_real_single(other) or _is_real_batch(other)):
            info = self.algebra._versor_info(self, tuple(other.grades_present()))
            if info is not None:
                return self.algebra.apply_matrices(info[2], other)
        return self * other * ~self

    def inner(self, other):
        """The thesis's inner product (2.21-2.29), same as ``self | other``."""
        return self | other

    def left_contraction(self, other):
        """Left contraction, same as ``self << other``."""
        return self << other

    def scalar_product(self, other):
        """<A B>_0 as a coefficient (float, array or SymPy)."""
        return self.algebra._product(self, self._coerce(other), "sp")._c.get(0, 0.0)

    def __pow__(self, k):
        if not isinstance(k, numbers.Integral):
            raise InvalidInputError(f"power: exponent must be an integer, got {k!r}")
        if k < 0:
            return self.inv() ** (-k)
        out = Multivector(self.algebra, {0: 1.0})
        base = self
        while k:
            if k & 1:
                out = out * base
            base = base * base
            k >>= 1
        return out

    # ----------------------------------------------------------- involutions
    def __invert__(self):
        """Reverse (2.32-2.33): grade k gets the sign (-1)^(k(k-1)/2)."""
        flip = self.algebra._rev_flip
        return _mv(self.algebra, {b: (-v if flip[b] else v) for b, v in self._c.items()})

    def reverse(self):
        return ~self

    def involute(self):
        """Grade involution (2.35): grade k gets the sign (-1)^k."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: (-v if g[b] & 1 else v) for b, v in self._c.items()})

    def conjugate(self):
        """Clifford conjugate: reverse of the grade involution."""
        return (~self).involute()

    def grade(self, *ks):
        """Grade projection <M>_k (2.18); several grades give their sum."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] in ks})

    def even(self):
        """Even part (2.16)."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] % 2 == 0})

    def odd(self):
        """Odd part (2.17)."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] % 2 == 1})

    def dual(self):
        """Dual M* = M I^-1 (2.31)."""
        alg = self.algebra
        I = alg.pseudoscalar()
        return self * I.inv()

    def undual(self):
        """Inverse of :meth:`dual`: M I."""
        return self * self.algebra.pseudoscalar()

    def scalar(self):
        """The scalar part <M>_0 as a coefficient (an array of zeros for a batch without one)."""
        if 0 in self._c:
            return self._c[0]
        shape = self.shape
        return np.zeros(shape) if shape else 0.0

    def __float__(self):
        scale = max((_absmax(v) for v in self._c.values() if not _is_sympy(v)), default=0.0)
        extra = [
            self.algebra.blade_names[b]
            for b, v in self._c.items()
            if b != 0 and (_is_sympy(v) or _absmax(v) > 1e-10 * max(scale, 1e-300))
        ]
        if extra:
            raise InvalidInputError(f"float(): multivector is not a scalar (has blades {extra})")
        v = self._c.get(0, 0.0)
        if isinstance(v, np.ndarray):
            if v.size != 1:
                raise InvalidInputError(f"float(): a batch of {v.size} scalars is not one float")
            return float(v.reshape(-1)[0])
        return float(v)

    # ---------------------------------------------------------- norms, inverse
    def norm2(self):
        """Squared norm <M ~M>_0 (for a point pair or blade, the square; may be negative)."""
        return self.scalar_product(~self)

    def norm(self):
        """sqrt(|<M ~M>_0|)."""
        v = self.norm2()
        if _is_sympy(v):
            import sympy

            return sympy.sqrt(v)
        return np.sqrt(np.abs(v))

    def normalized(self):
        """M / norm(M); raises when the norm is zero."""
        n = self.norm()
        if not _is_sympy(n) and np.any(np.asarray(n) == 0):
            raise DegenerateGeometryError("normalized: the multivector has zero norm")
        return self / n

    def inv(self):
        """Inverse (2.19).  Versors and blades use M~ / (M M~); otherwise a linear solve."""
        if not self._c:
            raise DegenerateGeometryError("inv: the zero multivector has no inverse")
        rev = ~self
        mm = self * rev
        if any(_is_sympy(v) for v in mm._c.values()):
            mm = mm.expand()  # cancel before testing for a scalar, or a blade falls into the 32x32 solve
        elif 0 in mm._c and len(mm._c) > 1:
            # a versor's M ~M is a scalar up to round-off in the other blades
            if _is_real_single(mm):
                rest = max(abs(v) for b, v in mm._c.items() if b != 0) / max(abs(mm._c[0]), 1e-300)
            else:
                s0 = np.abs(np.asarray(mm._c[0], dtype=float))
                rest = max(float(np.max(np.abs(v) / np.maximum(s0, 1e-300))) for b, v in mm._c.items() if b != 0)
            if rest <= 1e-12:
                mm = Multivector(self.algebra, {0: mm._c[0]})
        if set(mm._c) <= {0}:
            d = mm._c.get(0, 0)
            if _is_sympy(d):
                if d == 0:
                    raise DegenerateGeometryError("inv: M ~M = 0, the multivector is null and has no inverse")
            elif type(d) in _REAL_TYPES:
                if d == 0:
                    raise DegenerateGeometryError("inv: M ~M = 0, the multivector is null and has no inverse")
            elif np.any(np.asarray(d) == 0):
                raise DegenerateGeometryError("inv: M ~M = 0, the multivector is null and has no inverse")
            return rev / d
        # also try M^ ~M (covers M with mixed parity such as 1 + e when scalar)
        return self._general_inverse()

    def _general_inverse(self):
        alg = self.algebra
        vals = list(self._c.values())
        if any(_is_sympy(v) for v in vals):
            import sympy

            mat = sympy.zeros(alg.dim, alg.dim)
            pos = {b: i for i, b in enumerate(alg.blade_order)}
            for j, b in enumerate(alg.blade_order):
                for a, c in self._c.items():
                    s = alg._sign_list[a][b]
                    if s:
                        mat[pos[a ^ b], j] += s * c
            rhs = sympy.zeros(alg.dim, 1)
            rhs[pos[0], 0] = 1
            if mat.det() == 0:
                raise DegenerateGeometryError("inv: the multivector is not invertible")
            sol = mat.LUsolve(rhs)
            return Multivector(alg, {b: sympy.simplify(sol[pos[b], 0]) for b in alg.blade_order}, _prune=True)
        shape = self.shape
        blades = alg.blade_order
        pos = {b: i for i, b in enumerate(blades)}
        mats = np.zeros(shape + (alg.dim, alg.dim))
        for j, b in enumerate(blades):
            for a, c in self._c.items():
                s = alg._sign_list[a][b]
                if s:
                    mats[..., pos[a ^ b], j] += s * np.asarray(c, dtype=float)
        rhs = np.zeros(shape + (alg.dim,))
        rhs[..., pos[0]] = 1.0
        try:
            sol = np.linalg.solve(mats, rhs[..., None])[..., 0]
        except np.linalg.LinAlgError as exc:
            raise DegenerateGeometryError("inv: the multivector is not invertible") from exc
        return alg.from_array(sol)

    # -------------------------------------------------------- comparisons
    def isclose(self, other, rtol: float = 1e-9, atol: float = 1e-12) -> bool:
        """True when every coefficient agrees within ``atol + rtol*|other|`` (numeric)."""
        other = self._coerce(other)
        for b in set(self._c) | set(other._c):
            a = np.asarray(self._c.get(b, 0.0), dtype=float)
            c = np.asarray(other._c.get(b, 0.0), dtype=float)
            if not np.allclose(a, c, rtol=rtol, atol=atol):
                return False
        return True

    def __eq__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        diff = self - other
        for v in diff._c.values():
            if _is_sympy(v):
                import sympy

                if sympy.simplify(v) != 0:
                    return False
            elif np.any(np.asarray(v) != 0):
                return False
        return True

    def __ne__(self, other):
        eq = self.__eq__(other)
        return eq if eq is NotImplemented else not eq

    __hash__ = None

    def iszero(self, atol: float = 1e-12) -> bool:
        return self.isclose(0.0, rtol=0.0, atol=atol)

    # ------------------------------------------------------------ SymPy help
    def simplify(self, fn=None):
        """Apply ``sympy.simplify`` (or ``fn``) to every coefficient and drop zeros."""
        import sympy

        fn = fn or sympy.simplify
        return Multivector(self.algebra, {b: fn(v) if _is_sympy(v) else v for b, v in self._c.items()}, _prune=True)

    def expand(self):
        import sympy

        return self.simplify(sympy.expand)

    def subs(self, *args, **kwargs):
        """SymPy substitution in every coefficient."""
        return Multivector(
            self.algebra,
            {b: v.subs(*args, **kwargs) if _is_sympy(v) else v for b, v in self._c.items()},
            _prune=True,
        )

    def map(self, fn):
        """Apply ``fn`` to every coefficient."""
        return Multivector(self.algebra, {b: fn(v) for b, v in self._c.items()}, _prune=True)

    # ------------------------------------------------------------- display
    def _fmt_coeff(self, v) -> str:
        if isinstance(v, np.ndarray):
            return f"array{v.shape}"
        if isinstance(v, (float, np.floating)):
            return f"{float(v):.6g}"
        return str(v)

    def __repr__(self) -> str:
        if not self._c:
            return "0"
        parts = []
        for name, v in self.items():
            s = self._fmt_coeff(v)
            if _is_sympy(v) and (len(getattr(v, "args", ())) > 1 and v.is_Add):
                s = f"({s})"
            term = s if name == "1" else f"{s} {name}"
            parts.append(term)
        out = parts[0]
        for t in parts[1:]:
            out += " - " + t[1:] if t.startswith("-") else " + " + t
        return out

    def _repr_latex_(self) -> str:
        if not self._c:
            return "$0$"
        alg = self.algebra
        parts = []
        for b in alg.blade_order:
            if b not in self._c:
                continue
            v = self._c[b]
            if _is_sympy(v):
                import sympy

                s = sympy.latex(v)
                if v.is_Add:
                    s = f"\\left({s}\\right)"
            else:
                s = self._fmt_coeff(v)
            if b == 0:
                parts.append(s)
            else:
                sub = "".join(alg.labels[i] for i in range(alg.n) if b >> i & 1)
                parts.append(f"{s}\\,\\mathbf{{e}}_{{{sub}}}")
        out = parts[0]
        for t in parts[1:]:
            out += " - " + t[1:] if t.startswith("-") else " + " + t
        return f"${out}$"


def commutator(A: Multivector, B: Multivector) -> Multivector:
    """Commutator product A x B = (AB - BA)/2 (2.36)."""
    return (A * B - B * A) / 2


def _any_sympy(*mvs) -> bool:
    return any(_is_sympy(v) for m in mvs for v in m._c.values())


@cache
def _sympy():
    import sympy

    return sympy


def _cosh_sinhc(lam):
    """cosh(sqrt(lam)) and sinh(sqrt(lam))/sqrt(lam), real for real lam of any sign."""
    if _is_sympy(lam):
        sp = _sympy()
        if lam == 0:
            return sp.Integer(1), sp.Integer(1)
        if lam.is_negative or (-lam).is_positive:
            a = sp.sqrt(-lam)
            return sp.cos(a), sp.sin(a) / a
        if lam.is_positive:
            a = sp.sqrt(lam)
            return sp.cosh(a), sp.sinh(a) / a
        # sign unknown: give the form for a negative square (rotations), the common case
        a = sp.sqrt(-lam)
        return sp.cos(a), sp.sin(a) / a
    lam = np.asarray(lam, dtype=float)
    a = np.sqrt(np.abs(lam))
    pos = lam > 0
    c = np.where(pos, np.cosh(a), np.cos(a))
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(pos, np.sinh(a) / np.where(a == 0, 1, a), np.sin(a) / np.where(a == 0, 1, a))
    s = np.where(a < 1e-8, 1.0 + lam / 6.0, s)
    if c.ndim == 0:
        return float(c), float(s)
    return c, s


def _exp_simple(B: Multivector, lam):
    """exp of a bivector with a scalar square ``lam`` (2.37 summed in closed form)."""
    c, s = _cosh_sinhc(lam)
    return B * s + c


def exp(B: Multivector) -> Multivector:
    """Exponential of a bivector (2.37), summed in closed form.

    A bivector whose square is a scalar ``lam`` is simple and
    ``exp(B) = cosh(sqrt(lam)) + B sinh(sqrt(lam))/sqrt(lam)`` (cos/sin for a
    rotation plane, ``1 + B`` for a null bivector such as ``e t/2`` of a
    translator, 2.100).  A general bivector of G(4,1) (a screw, 2.110) splits
    into two commuting simple bivectors B = B1 + B2, with squares the roots of
    ``l^2 - <B^2>_0 l + (<B^2>_4)^2/4 = 0``; then exp(B) = exp(B1) exp(B2).
    A scalar part, if present, multiplies by its ordinary exponential.
    """
    alg = B.algebra
    grades = set(B.grades_present())
    if not grades <= {0, 2}:
        raise InvalidInputError(f"exp: closed form needs a bivector (plus scalar), got grades {sorted(grades)}")
    scal = B.scalar()
    B = B.grade(2)
    factor = None
    if not _is_zero(scal):
        factor = _sympy().exp(scal) if _is_sympy(scal) else np.exp(scal)
    if not B._c:
        out = Multivector(alg, {0: 1.0})
        return out * factor if factor is not None else out
    sq = B * B
    lam0 = sq.scalar()
    four = sq.grade(4)
    symbolic = _any_sympy(B)
    if symbolic:
        four = four.simplify()
    numeric_small = (not symbolic) and four.iszero(atol=1e-14 * max(1.0, float(np.max(np.abs(lam0)))))
    if (symbolic and not four._c) or numeric_small:
        out = _exp_simple(B, lam0)
    else:
        q = (four * four).scalar()
        if symbolic:
            sp = _sympy()
            disc = sp.sqrt(lam0**2 - q)
            l1, l2 = (lam0 + disc) / 2, (lam0 - disc) / 2
        else:
            disc = np.sqrt(np.maximum(np.asarray(lam0) ** 2 - q, 0.0))
            l1, l2 = (lam0 + disc) / 2, (lam0 - disc) / 2
            if np.any(disc < 1e-10 * np.maximum(1.0, np.abs(lam0))):
                return _exp_series(B) * (factor if factor is not None else 1.0)
        half = four * 0.5 if not symbolic else four / 2
        Binv = B.inv()
        B1 = (Binv * (half + l1)).grade(2)
        B2 = B - B1
        out = _exp_simple(B1, l1) * _exp_simple(B2, l2)
        if symbolic:
            out = out.simplify()
    return out * factor if factor is not None else out


def _exp_series(B: Multivector, terms: int = 30) -> Multivector:
    """exp by scaling and squaring of the series (2.37), for the rare repeated-root case."""
    norm = np.max(np.abs(B.to_array()))
    k = int(max(0, np.ceil(np.log2(max(norm, 1e-300))) + 1)) if norm > 0.5 else 0
    X = B * (0.5**k)
    out = Multivector(B.algebra, {0: 1.0})
    term = Multivector(B.algebra, {0: 1.0})
    for i in range(1, terms):
        term = term * X * (1.0 / i)
        out = out + term
    for _ in range(k):
        out = out * out
    return out
