"""Fuzz cases of the symbolic derivations (cga_lessons.symbolic): the checks machinery and every derivation.

The derivations take no argument (a valid call each; they are computed once per process and copied after, so
that :func:`run_all` and :func:`verify_errata` cost nothing more here); the machinery (:class:`Check`,
:class:`Derivation`, :class:`Ring`, :func:`same`, :func:`is_zero`, :func:`proportional`, :class:`Erratum`) takes
SymPy expressions, which the checks let through.
"""

from __future__ import annotations

import sympy as sp

from cga_lessons import symbolic
from cga_lessons.conformal import up
from fuzz.harness import Case

x, y = sp.symbols("x y", real=True)
X = up([x, y, sp.Integer(0)])
RING = symbolic.Ring([x, y], [x**2 + y**2 - 1])


def _derivation():
    d = symbolic.Derivation("a test", ("2.1",))
    d.add("first", "2.1", x, x)
    return d


NO_ARGUMENT = [
    symbolic.clifford_product_plane,
    symbolic.stereographic_projection,
    symbolic.minkowski_plane,
    symbolic.projection_rejection,
    symbolic.null_cone_points,
    symbolic.sphere_and_plane,
    symbolic.circle_properties,
    symbolic.line_properties,
    symbolic.point_pair_extraction,
    symbolic.conformal_transformations,
    symbolic.rotors_and_motors,
    symbolic.run_all,
    symbolic.errata_table,
]

CASES = [Case(f) for f in NO_ARGUMENT] + [
    Case(symbolic.basis_and_product_axioms, {"signatures": ((2, 0, 0), (1, 1, 0))},
         extra={"signatures": [((2, 0),), ((-1, 0, 0),), ((11, 0, 0),), ((2.5, 0, 0),), ("abc",), ()]}),
    Case(symbolic.verify_errata, lambda: {"derivations": symbolic.run_all()},
         extra={"derivations": [{"minkowski_plane": None}, {"no_such": symbolic.minkowski_plane()}]}),
    # ---------------------------------------------------------------- the machinery
    Case(symbolic.Check, {"name": "2.1 x = x", "label": "2.1", "raw_lhs": x, "raw_rhs": x, "holds": True,
                          "expected": True, "note": "a note"},
         strict=True, allow={"raw_lhs": ["None"], "raw_rhs": ["None"]}),  # None: a side add_bool did not keep
    Case(symbolic.Derivation, {"title": "a test", "labels": ("2.1", "2.2"), "checks": [], "values": {}},
         strict=True),
    Case(symbolic.Derivation.add, {"self": _derivation(), "name": "second", "label": "2.1", "lhs": x + y,
                                   "rhs": y + x, "expected": True, "note": "", "rel": None},
         label="Derivation.add", positional=("self",), strict=True, allow={"rel": ["None"]},
         extra={"name": ["first"], "rel": [RING]}),
    Case(symbolic.Derivation.add_bool, {"self": _derivation(), "name": "second", "label": "2.1", "value": True,
                                        "expected": True, "note": ""},
         label="Derivation.add_bool", positional=("self",), strict=True, extra={"name": ["first"]}),
    Case(symbolic.Derivation.__getitem__, {"self": _derivation(), "name": "first"}, label="Derivation[]",
         positional=("self", "name"), extra={"name": ["no such check"]}),
    Case(symbolic.Derivation.for_label, {"self": _derivation(), "label": "2.1"}, label="Derivation.for_label",
         positional=("self",), extra={"label": ["2.999"]}),
    Case(symbolic.Ring, {"symbols": [x, y], "relations": [x**2 + y**2 - 1], "subs": ()},
         extra={"symbols": [[], ["x"], [x, x]], "relations": [[sp.sin(x)], ["text"]], "subs": [[(x,)]]}),
    Case(symbolic.is_zero, {"x": x - x, "rel": None}, extra={"rel": ["text", 1.0]}),
    Case(symbolic.is_zero, lambda: {"x": x**2 + y**2 - 1, "rel": RING}, name="is_zero (ring)"),  # a Ring: no deepcopy
    Case(symbolic.same, {"a": X * X, "b": sp.Integer(0), "rel": None}, extra={"rel": ["text"]}),
    Case(symbolic.proportional, {"X": X * 3, "Y": X, "rel": None}, kinds={"X": [x], "Y": [x]}),
    Case(symbolic.Erratum, {"label": "2.55", "printed": "E := e0 ^ e", "correct": "E := e ^ e0",
                            "decided_by": "cga_lessons.symbolic.minkowski_plane",
                            "printed_check": "2.55 E := e0 ^ e = e+ e- (printed)",
                            "correct_check": "2.55 E = e ^ e0 = e+ e- (corrected)", "note": ""},
         strict=True, extra={"decided_by": ["cga_lessons.symbolic.no_such", "minkowski_plane"]}),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
