"""Fuzz cases of the algebra (cga_lessons.algebra): the facade's functions, the Algebra and its Multivector.

Beyond the facade's functions, a user calls the methods of :class:`Algebra` and :class:`Multivector`: the operators
(``X * Y``, ``X ^ Y``, ``X | Y``, ``X << Y``, ``X >> Y``, ``X / Y``, ``X + s``, ``X - s``, ``X ** k``) are fuzzed
through their methods (``Multivector.__mul__`` ...), whose errors read ``"Multivector *: other: ..."`` (the class and
the operator the user wrote); the named methods' read ``"Multivector.grade: ..."`` and ``"Algebra.vector: ..."``.
"""

from __future__ import annotations

import math

import numpy as np
import sympy

from cga_lessons.algebra import (
    Algebra,
    Multivector,
    absmax,
    all_finite,
    any_sympy,
    commutator,
    exp,
    finite_multivector,
    is_real_batch,
    is_real_single,
    is_sympy,
    motor_tolerance,
)
from fuzz.harness import Case

G3 = Algebra(3)
G41 = Algebra(4, 1, labels=["1", "2", "3", "+", "-"])
e1, e2, e3 = G3.basis_vectors()
X = 1.0 + 2.0 * e1 - 0.5 * (e1 ^ e2) + 0.25 * e3  # a small mixed multivector of G3
V = G3.vector([1.0, 2.0, 0.5])  # a vector
ROTOR = exp(-0.3 * (e1 ^ e2))  # a versor
BIV = 0.4 * (e1 ^ e2) - 0.1 * (e2 ^ e3)
BATCH = G3.vector(np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 1.0]]))
OTHER_ALGEBRA = Algebra(2).vector([1.0, 1.0])  # a multivector of another algebra
NULL = G41.blade("e+") + G41.blade("e-")  # squares to 0: no inverse
T = sympy.Symbol("t")
SYMBOLIC = G3.blade("e1", T) + G3.blade("e23", 2 * T)
CHECKER = {"func": "the caller's own name, trusted", "name": "the caller's own argument name, trusted"}
ABSMAX_NAN = "absmax of NaN is NaN, its documented contract: it is the coefficient helper of the checks themselves"


def op(method, label: str, other, name: str | None = None, **kw) -> Case:
    """A case of one operator of a Multivector: ``method(self, other)``."""
    return Case(method, {"self": X, "other": other}, label=label, positional=("self", "other"), name=name, **kw)


CASES = [
    # ---------------------------------------------------------------- the facade's functions
    Case(Algebra, {"p": 3, "q": 0, "r": 0}, strict=True),
    Case(Algebra, {"p": 2, "q": 1, "r": 0, "labels": ["x", "y", "z"]}, name="Algebra (labels)"),
    Case(Multivector, {"algebra": G3, "coeffs": {0: 1.0, 3: 2.0}}, kinds={"algebra": [X, "G3"]}),
    Case(commutator, {"A": e1, "B": X}, kinds={"A": [1.0], "B": [1.0]}, extra={"B": [OTHER_ALGEBRA]}),
    Case(exp, {"B": BIV}, kinds={"B": [V, X]}, extra={"B": [1e300 * BIV, 1e8 * (e1 ^ e2)]}),
    Case(exp, {"B": G3.scalar(0.5) + BIV}, name="exp (scalar + bivector)", extra={"B": [G3.scalar(1e4)]}),
    # a check for other functions: the error names the caller (func) and the caller's argument (name, here "X")
    Case(finite_multivector, {"X": X, "func": "caller", "name": "X"}, label="caller", skip=CHECKER, kinds={"X": [1.0]}),
    Case(
        finite_multivector,
        {"X": BATCH, "func": "caller", "name": "X"},
        label="caller",
        skip=CHECKER,
        name="finite_multivector (batch)",
    ),
    Case(absmax, {"v": -2.5}, nonfinite_ok=ABSMAX_NAN),
    Case(absmax, {"v": np.array([1.0, -3.0])}, name="absmax (array)", nonfinite_ok=ABSMAX_NAN),
    Case(all_finite, {"arr": np.array([1.0, 2.0])}),
    Case(any_sympy, {"mvs": X}, positional=("mvs",)),
    Case(is_real_batch, {"M": BATCH}, kinds={"M": [1.0, "text"]}),
    Case(is_real_single, {"M": X}, kinds={"M": [1.0, "text"]}),
    Case(is_sympy, {"x": 1.0}),
    Case(motor_tolerance, {"vmax": 1.0, "n_norm": 0.5, "r_norm": 1.0}),
    Case(motor_tolerance, {"vmax": np.ones(2), "n_norm": np.ones(2), "r_norm": np.ones(2)},
         name="motor_tolerance (arrays)"),
    # ---------------------------------------------------------------- Algebra's methods
    Case(Algebra.parse_blade, {"self": G3, "name": "e31"}, label="Algebra.parse_blade", positional=("self",),
         extra={"name": ["e4", "x12", "e11e"]}),
    Case(Algebra.blade, {"self": G3, "name": "e12", "coeff": 2.0}, label="Algebra.blade", positional=("self",),
         extra={"name": ["e4"]}),
    Case(Algebra.scalar, {"self": G3, "value": 1.5}, label="Algebra.scalar", positional=("self",)),
    Case(Algebra.vector, {"self": G3, "coeffs": [1.0, 2.0, 3.0]}, label="Algebra.vector", positional=("self",)),
    Case(Algebra.vector, {"self": G3, "coeffs": np.array([[1.0, 2.0, 3.0], [0.0, 1.0, 0.0]])},
         label="Algebra.vector", positional=("self",), name="Algebra.vector (batch)"),
    Case(Algebra.from_array, {"self": G3, "arr": np.arange(8.0)}, label="Algebra.from_array", positional=("self",)),
    Case(Algebra.from_array, {"self": G3, "arr": [1.0, 2.0], "blades": [0, 3]}, label="Algebra.from_array",
         positional=("self",), name="Algebra.from_array (blades)", extra={"blades": [[0, 8], [0, -1], [0, 0]]}),
    Case(Algebra.basis_vectors, {"self": G3}, label="Algebra.basis_vectors", positional=("self",)),
    Case(Algebra.pseudoscalar, {"self": G3}, label="Algebra.pseudoscalar", positional=("self",)),
    Case(Algebra.left_matrix, {"self": G3, "A": X}, label="Algebra.left_matrix", positional=("self",),
         extra={"A": [OTHER_ALGEBRA]}),
    Case(Algebra.versor_matrices, {"self": G3, "V": ROTOR, "grades": (1,)}, label="Algebra.versor_matrices",
         positional=("self",), extra={"grades": [(7,), (-1,), ("1",)], "V": [OTHER_ALGEBRA]}),
    Case(Algebra.apply_matrices, {"self": G3, "mats": G3.versor_matrices(ROTOR, (1,)), "X": V},
         label="Algebra.apply_matrices", positional=("self",), extra={"X": [OTHER_ALGEBRA]}),
    Case(Algebra.rigid_motion, {"self": G41, "V": G41.scalar(1.0)}, label="Algebra.rigid_motion", positional=("self",)),
    # ---------------------------------------------------------------- Multivector's operators
    op(Multivector.__mul__, "Multivector *", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__mul__, "Multivector *", 2.0, name="Multivector * (scalar)"),
    op(Multivector.__mul__, "Multivector *", np.array([1.0, 2.0]), name="Multivector * (array)"),
    op(Multivector.__rmul__, "Multivector *", 2.0),
    op(Multivector.__xor__, "Multivector ^", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__xor__, "Multivector ^", 2.0, name="Multivector ^ (scalar)"),
    op(Multivector.__rxor__, "Multivector ^", 2.0),
    op(Multivector.__or__, "Multivector |", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__ror__, "Multivector |", 2.0),
    op(Multivector.__lshift__, "Multivector <<", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__rshift__, "Multivector >>", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__truediv__, "Multivector /", V, extra={"other": [OTHER_ALGEBRA, 0 * V, NULL]}),
    op(Multivector.__truediv__, "Multivector /", 2.0, name="Multivector / (scalar)", extra={"other": [0.0, 1e-320]}),
    op(Multivector.__truediv__, "Multivector /", np.array([1.0, 2.0]), name="Multivector / (array)",
       extra={"other": [np.array([1.0, 0.0])]}),
    op(Multivector.__rtruediv__, "Multivector /", 2.0),
    op(Multivector.__add__, "Multivector +", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__add__, "Multivector +", 2.0, name="Multivector + (scalar)"),
    op(Multivector.__radd__, "Multivector +", 2.0),
    op(Multivector.__sub__, "Multivector -", V, extra={"other": [OTHER_ALGEBRA]}),
    op(Multivector.__sub__, "Multivector -", 2.0, name="Multivector - (scalar)"),
    op(Multivector.__rsub__, "Multivector -", 2.0),
    # the operators without the algebra's operation hook: checked and named as the operator ("Multivector ^: other")
    Case(Multivector.plain_operation, {"self": X, "op": "^", "other": V}, label="Multivector ^",
         positional=("self", "op", "other"), extra={"other": [OTHER_ALGEBRA]},
         skip={"op": "the calling layer's own symbol; a wrong one raises 'Multivector.plain_operation: op: ...' "
                     "(tests/test_point_wedges.py)"}),
    Case(Multivector.__pow__, {"self": X, "k": 3}, label="Multivector **", positional=("self", "k"), strict=True,
         extra={"k": [10**6]}),
    Case(Multivector.__pow__, {"self": V, "k": -2}, label="Multivector **", positional=("self", "k"),
         name="Multivector ** (negative)"),
    op(Multivector.__eq__, "Multivector ==", V),
    op(Multivector.__ne__, "Multivector !=", V),
    # ---------------------------------------------------------------- Multivector's named methods
    Case(Multivector.__getitem__, {"self": X, "name": "e21"}, label="Multivector[]", positional=("self", "name"),
         extra={"name": ["e4", "x", 8, -1]}),
    Case(Multivector.grade, {"self": X, "k": 1}, label="Multivector.grade", positional=("self", "k")),
    Case(Multivector.batch_item, {"self": BATCH, "index": 1}, label="Multivector.batch_item", positional=("self",)),
    Case(Multivector.to_array, {"self": X, "blades": [0, 1, 3]}, label="Multivector.to_array", positional=("self",),
         extra={"blades": [[0, 8], [-1]]}),
    Case(Multivector.inner, {"self": X, "other": V}, label="Multivector.inner", positional=("self",)),
    Case(Multivector.left_contraction, {"self": X, "other": V}, label="Multivector.left_contraction",
         positional=("self",)),
    Case(Multivector.scalar_product, {"self": X, "other": V}, label="Multivector.scalar_product", positional=("self",)),
    Case(Multivector.isclose, {"self": X, "other": V, "rtol": 1e-9, "atol": 1e-12}, label="Multivector.isclose",
         positional=("self",), strict=True),
    Case(Multivector.iszero, {"self": X, "atol": 1e-12}, label="Multivector.iszero", positional=("self",),
         strict=True),
    Case(Multivector.map, {"self": X, "fn": abs}, label="Multivector.map", positional=("self",),
         extra={"fn": [lambda v: v * math.inf]}),
    Case(Multivector.simplify, {"self": X, "fn": None}, label="Multivector.simplify", positional=("self",)),
    Case(Multivector.subs, {"self": SYMBOLIC, "old": T, "new": 2.0}, label="Multivector.subs",
         positional=("self", "old", "new")),
    Case(Multivector.inv, {"self": V}, label="Multivector.inv", positional=("self",)),
    Case(Multivector.inv, {"self": X}, label="Multivector.inv", positional=("self",), name="Multivector.inv (general)"),
    Case(Multivector.dual, {"self": X}, label="Multivector.dual", positional=("self",)),
    Case(Multivector.undual, {"self": X}, label="Multivector.undual", positional=("self",)),
    Case(Multivector.normalized, {"self": V}, label="Multivector.normalized", positional=("self",)),
    Case(Multivector.norm, {"self": X}, label="Multivector.norm", positional=("self",)),
    Case(Multivector.norm2, {"self": X}, label="Multivector.norm2", positional=("self",)),
    Case(Multivector.reverse, {"self": X}, label="Multivector.reverse", positional=("self",)),
    Case(Multivector.involute, {"self": X}, label="Multivector.involute", positional=("self",)),
    Case(Multivector.conjugate, {"self": X}, label="Multivector.conjugate", positional=("self",)),
    Case(Multivector.even, {"self": X}, label="Multivector.even", positional=("self",)),
    Case(Multivector.odd, {"self": X}, label="Multivector.odd", positional=("self",)),
    Case(Multivector.scalar, {"self": X}, label="Multivector.scalar", positional=("self",)),
    Case(Multivector.__float__, {"self": G3.scalar(2.0)}, label="float", positional=("self",)),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
