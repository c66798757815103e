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

How a product runs (see :meth:`ProductTerms.product <cga_lessons.algebra.products.ProductTerms.product>`; the
routes agree to the bit
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
:func:`cga_lessons.conformal.versors.apply` take this route by themselves.

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

The package's facade (:mod:`cga_lessons.algebra`) is the public home of all of these names: import them
from there.  The code lives in one module per idea::

    core.py                     Algebra: blades as bitmaps, signs (2.10), names, constructors
    multivector.py              Multivector and its operators; commutator (2.36)
    access.py                   reading coefficients (X["e12"]), batches, arrays; isclose and ==
    involutions.py              grade projection, reverse, grade involution, dual (2.16-2.18, 2.31-2.35)
    operands.py                 the checks of operands: what the operators and methods refuse
    products.py                 ProductTerms: cached product terms, compiled straight-line code, float tables
    versor_matrices.py          VersorActions: versor matrices per grade in closed form (2.82), apply_matrices
    motor_matrices.py           MotorMatrices: motors' matrices from (R, t) in the null basis (2.141-2.144)
    inverse.py                  norms and the inverse (2.19)
    display.py                  text and LaTeX display, SymPy helpers (simplify, expand, subs)
    exponential.py              exp of a bivector (2.37)
    coefficients.py             the three kinds of coefficient: float, array batch, SymPy

and the errors (GeometryError, DegenerateGeometryError, InvalidInputError) in :mod:`cga_lessons.errors`.
Every operator and method refuses bad operands with one of them, naming what the user wrote
(``"Multivector /: other: division by zero"``, ``"Algebra.vector: coeffs: contains NaN or inf"``).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from cga_lessons.checks import fail, integer, text

from .coefficients import (
    is_sympy,
    is_zero,
)
from .motor_matrices import MotorMatrices
from .multivector import Multivector
from .operands import AlgebraKind, BladeNameError, blade_bitmaps, coefficient, coefficient_array
from .products import ProductTerms, left_matrix
from .versor_matrices import VersorActions

__all__ = [
    "Algebra",
]


def _labels(labels, n: int) -> list:
    """The labels of the basis vectors: ``n`` distinct non-empty strings (default ``"1", "2", ...``)."""
    if labels is None:
        return [str(i + 1) for i in range(n)] if n < 10 else [f"({i + 1})" for i in range(n)]
    if isinstance(labels, (str, bytes)) or not hasattr(labels, "__iter__"):
        raise fail("Algebra", "labels", f"expected a sequence of {n} strings, got {labels!r:.40}")
    labels = [text(v, "Algebra", "labels") for v in labels]
    if len(labels) != n or len(set(labels)) != n:
        raise fail("Algebra", "labels", f"need {n} distinct labels, got {labels!r}")
    return labels


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


class Algebra(AlgebraKind):
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

    This class holds the sign table (2.10) and the blade names, and three helpers that read them: its products
    (:class:`~cga_lessons.algebra.products.ProductTerms`), the versor matrices
    (:class:`~cga_lessons.algebra.versor_matrices.VersorActions`) and the motors' closed form
    (:class:`~cga_lessons.algebra.motor_matrices.MotorMatrices`), with the caches they share.
    """

    def __init__(self, p: int, q: int = 0, r: int = 0, labels=None):
        p, q, r = (integer(v, "Algebra", name, low=0) for name, v in (("p", p), ("q", q), ("r", r)))
        self.p, self.q, self.r = p, q, r
        self.n = n = p + q + r
        if n > 10:
            raise fail("Algebra", "p, q, r", f"dimension p+q+r = {n} is too large for this dense sign table (max 10)")
        labels = _labels(labels, n)
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
        #: True where the reverse (2.32) flips the sign of a blade
        self._rev_flip = [bool((g * (g - 1) // 2) & 1) for g in self.grades]
        #: blades of each grade in the order of (2.9)
        self.grade_blades = [[b for b in order if self.grades[b] == k] for k in range(n + 1)]
        # The helpers that read the tables above (composed, not inherited), and the caches two of them share.
        tables, versors = {}, {}
        self._products = ProductTerms(self)
        self._motors = MotorMatrices(self, tables, versors)
        self._versors = VersorActions(self, self._motors, tables, versors)
        #: What a layer above adds to the operators' results (:meth:`set_operation_hook`); None: nothing.
        self.operation_hook = None

    def set_operation_hook(self, hook) -> None:
        """Let a layer above this one add to the results of the operators that combine entities: ``A ^ B``,
        ``A + B`` and ``A - B`` of this algebra's multivectors.

        ``hook(result, op, left, right)`` is called when both operands are multivectors: ``result`` is the plain
        result, ``op`` the operator's symbol (``"^"``, ``"+"``, ``"-"``), ``left`` and ``right`` the operands as
        written.  It must return ``result`` or a multivector with exactly its coefficients (a subclass that carries
        more: the conformal layer registers :func:`cga_lessons.conformal.point_wedges.framed_points` on G(4,1), so
        that the outer product and the sums of plain conformal points carry their local frame).  The operators
        without the hook are :meth:`Multivector.plain_operation <cga_lessons.algebra.Multivector.plain_operation>`.
        ``None`` removes it.  The algebra never
        imports the layer that registers it; an algebra without a hook pays one attribute read per operator.  The
        geometric product, the hot path of every versor, and the inner products are not hooked.
        """
        if hook is not None and not callable(hook):
            raise fail("Algebra.set_operation_hook", "hook", f"expected a function or None, got {type(hook).__name__}")
        self.operation_hook = hook

    # ------------------------------------------------------------------ names
    def _make_name(self, blade: int) -> str:
        if blade == 0:
            return "1"
        return "e" + "".join(self.labels[i] for i in range(self.n) if blade >> i & 1)

    def parse_blade(self, name: str) -> tuple[int, int]:
        """Return ``(bitmap, sign)`` for a blade name, in any factor order.

        ``"e31"`` gives the bitmap of ``e13`` and sign -1 (``e31 = -e13``).
        A repeated factor is contracted with its square, so ``"e11"`` is the
        scalar 1 in G(3).  A name that is not a blade's raises an
        :class:`~cga_lessons.algebra.InvalidInputError` that is also a ``KeyError``.
        """
        hit = self._name_to_blade.get(name) if type(name) is str else None
        return hit if hit is not None else self._parse(name, "Algebra.parse_blade", "name")

    def _parse(self, name, func: str, arg: str) -> tuple[int, int]:
        """:meth:`parse_blade` with the errors naming ``func`` and its argument ``arg``."""
        text(name, func, arg, empty=True)
        if name in self._name_to_blade:
            return self._name_to_blade[name]
        if name in ("1", "", "scalar"):
            return 0, 1
        if not name.startswith("e"):
            raise BladeNameError(f"{func}: {arg}: {name!r} is not a blade name of G{self.signature}")
        rest = name[1:]
        factors = []
        labels = sorted(self.labels, key=len, reverse=True)
        while rest:
            for lab in labels:
                if rest.startswith(lab):
                    factors.append(self.labels.index(lab))
                    rest = rest[len(lab) :]
                    break
            else:
                raise BladeNameError(
                    f"{func}: {arg}: {name!r} is not a blade name of G{self.signature} (labels {self.labels})"
                )
        blade, sign = 0, 1
        for i in factors:
            sign *= self._sign_list[blade][1 << i]
            blade ^= 1 << i
        if sign == 0:
            raise BladeNameError(f"{func}: {arg}: {name!r} is zero in G{self.signature} (a null vector squared)")
        self._name_to_blade[name] = (blade, sign)
        return blade, sign

    def __copy__(self):
        return self  # one algebra: copies of its multivectors combine with the originals

    def __deepcopy__(self, memo):
        return self

    @property
    def signature(self) -> tuple[int, int, int]:
        return (self.p, self.q, self.r)

    def __repr__(self) -> str:
        return f"Algebra({self.p}, {self.q}, {self.r})"

    # ----------------------------------------------------------- constructors
    def blade(self, name: str, coeff=1.0) -> Multivector:
        """The basis blade called ``name`` (any factor order) times ``coeff``."""
        b, s = self._parse(name, "Algebra.blade", "name")
        coeff = coefficient(coeff, "Algebra.blade", "coeff")
        return Multivector(self, {b: coeff if s == 1 else -coeff})

    def scalar(self, value) -> Multivector:
        """The scalar ``value`` (a number, an array for a batch, or a SymPy expression) as a multivector."""
        return Multivector(self, {0: coefficient(value, "Algebra.scalar", "value")})

    def basis_vectors(self) -> list[Multivector]:
        """The n basis vectors e_1 ... e_n (2.9)."""
        return [Multivector(self, {1 << i: 1.0}) for i in range(self.n)]

    def vector(self, coeffs) -> Multivector:
        """A grade-1 multivector from ``coeffs`` of shape (n,) or (N, n) (a batch); SymPy entries stay exact."""
        func = "Algebra.vector"
        arr = coeffs
        if isinstance(arr, (list, tuple)) and arr and all(is_sympy(c) for c in arr):
            if len(arr) != self.n:
                raise fail(func, "coeffs", f"expected {self.n} coefficients, got {len(arr)}")
            return Multivector(self, {1 << i: c for i, c in enumerate(arr) if not is_zero(c)})
        obj = coeffs if isinstance(coeffs, np.ndarray) else np.asarray(coeffs, dtype=object)  # ragged rows: lists
        if obj.dtype == object and obj.ndim and any(is_sympy(v) for v in obj.flat):
            if obj.shape[-1] != self.n:
                raise fail(func, "coeffs", f"the last axis must have length {self.n}, got shape {obj.shape}")
            return Multivector(self, {1 << i: obj[..., i] if obj.ndim > 1 else obj[i] for i in range(self.n)})
        arr = coefficient_array(coeffs, func, "coeffs", self.n)
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
        func = "Algebra.from_array"
        blades = self.blade_order if blades is None else blade_bitmaps(blades, func, "blades", self.dim)
        arr = coefficient_array(arr, func, "arr", len(blades), " (one entry per blade of blades)")
        if arr.ndim == 1:
            return Multivector(self, {b: float(arr[i]) for i, b in enumerate(blades) if arr[i] != 0})
        return Multivector(self, {b: arr[..., i] for i, b in enumerate(blades)})

    # ------------------------------------------------- linear maps as matrices
    def left_matrix(self, A: Multivector, blades_in=None, blades_out=None) -> np.ndarray:
        """Matrix of ``X -> A X`` restricted to the given input/output blades (A one numeric multivector)."""
        return left_matrix(self, A, blades_in, blades_out)

    def versor_matrices(self, V: Multivector, grades) -> dict | None:
        """Matrices of ``X -> V X^ V^-1`` (2.82) on the given grades, or None.

        For a single numeric versor V (real coefficients, ``V ~V`` a non-zero
        scalar up to round-off) returns a :class:`~cga_lessons.algebra.versor_matrices.VersorMatrices`,
        ``{grade: k x k matrix}`` over the blades of that grade in the order of
        (2.9) (``self.grade_blades``): the outermorphism of the versor, built
        in closed form with no multivector products, for a motor of G(4,1)
        from its rotation and translation (:meth:`rigid_motion`), otherwise
        from one cached bilinear table per blade set
        (:meth:`~cga_lessons.algebra.versor_matrices.VersorActions.sandwich_table`).
        X^ is the grade involution, applied when V is odd.  Returns None for
        anything else (SymPy or batched coefficients, mixed parity, not a
        versor); the caller then uses the plain sandwich.
        """
        return self._versors.matrices(V, grades)

    def apply_matrices(self, mats: dict, X: Multivector) -> Multivector:
        """Apply per-grade matrices (from :meth:`versor_matrices`) to X, single or batched.

        ``mats`` is ``{grade: k x k matrix}`` over the blades of each grade in the order of (2.9); see
        :meth:`~cga_lessons.algebra.versor_matrices.VersorActions.apply_unchecked` for how a batch is applied.
        """
        return self._versors.apply(mats, X)

    def rigid_motion(self, V: Multivector):
        """``(R, t)`` of a motor of G(4,1): V moves the point x to ``R x + t`` (2.102, 2.103); else None.

        V is a single numeric multivector.  Written ``V = R + e n`` (2.140,
        2.143), with R in the even subalgebra of G3 (scalar and e12, e13, e23:
        the rotor ``(V ^ E) E`` of 2.141) and n in the odd one, V is a motor
        when it is even and commutes with e: its e+ and e- parts are equal and
        it has no E = e+e- part.  The parts that break this (the differences of
        the e+ and e- coefficients, the E blades, and the trivector of ``n ~R``,
        which must vanish for ``V ~V`` to be a scalar, 2.145) must be within
        :func:`motor_tolerance`: ``VERSOR_TOLERANCE`` plus the round-off a
        product of motors leaves in its e+/e- terms, up to
        ``MOTOR_TOLERANCE_CAP``, of the largest coefficient for the trivector
        and of the rotor's norm for the others (a dilation's E part is that
        fraction of the rotor at any distance, so a similarity far out is no
        motor).  A motor built by ``motor``, ``translator``,
        ``rotor`` or ``matrix_to_motor`` has no defect at all, at any distance.

        Both parts are read linearly off the coefficients: ``R`` is the
        rotation matrix of the rotor part normalised by its own norm (2.141),
        and ``t = 2 <n ~R>_1 / (R ~R)`` (2.142-2.144, divided by ``R ~R`` so that
        a scaled motor ``s M``, the same versor action ``V X V^-1``, gives the
        same motion), with n the negated e- coefficients.  So ``R x + t`` holds
        to machine precision at any distance, where the e+/e- form of a point
        at x holds ``x^2/2``.  Cached by value; the arrays are read-only.
        """
        return self._motors.rigid_motion(V)
