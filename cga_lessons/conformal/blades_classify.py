"""What a blade of G(4,1) is, and the intersection of the thesis's entities in the form they come in.

Two readings of one blade (the thesis's words first, section 2.3.3 and table 2.1):

* ``"dual"`` form = OPNS, Dorst's *direct* form: the points x with ``x ^ X = 0`` (2.76); the outer product of
  points returns it (``point_pair``, ``circle_from_points``, ``line_from_points``, ``sphere_from_points``,
  ``plane_from_points``);
* ``"standard"`` form = IPNS, Dorst's *dual* form: the points x with ``x . X = 0`` (2.71, 2.79); ``sphere`` and
  ``plane`` return it, and the thesis intersects in it (``z = s1 ^ s2``, ``L = P1 ^ P2``, ``PP = s1 ^ s2 ^ s3``).

They are related by ``dual form = standard form * Ic^-1`` (2.31).  The grade alone cannot tell them apart for
grades 2 and 3 (a grade-2 blade is a dual-form point pair or a standard-form circle), so ``form="auto"`` reads a
vector as a standard form (sphere, plane; a null vector is a point either way) and every other grade as a dual form,
which is what the constructors return.  Pass ``form=`` explicitly for anything else, in particular for the
standard-form results of :func:`intersect`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError

from .anchored import frame
from .anchored_ops import follow
from .blades import dual, left_contraction, meet, undual
from .blades_span import require_blade
from .model import einf

__all__ = ["BladeKind", "classify", "intersect"]

_FORMS = {"auto": "auto", "dual": "dual", "opns": "dual", "standard": "standard", "ipns": "standard"}
_KINDS = ("scalar", "point", "round", "tangent", "flat", "direction", "dual flat", "pseudoscalar")
_NAMES = {
    "round": {-1: "round of dimension -1 (no points)", 0: "point pair", 1: "circle", 2: "sphere"},
    "flat": {0: "flat point", 1: "line", 2: "plane"},
    "tangent": {1: "tangent vector", 2: "tangent bivector", 3: "tangent trivector"},
    "direction": {0: "point at infinity", 1: "free vector", 2: "free bivector", 3: "free trivector"},
    "dual flat": {0: "dual flat point", 1: "dual line", 2: "dual plane"},
}


@dataclass(frozen=True)
class BladeKind:
    """What :func:`classify` found.

    kind : "scalar", "point", "round", "tangent", "flat", "direction", "dual flat" or "pseudoscalar".
    dimension : of the round, flat or tangent/direction element (point pair 0, circle and line 1, sphere and
        plane 2; a tangent or direction of grade k has dimension k - 1); None for scalars and pseudoscalars.
    imaginary : True for a round with a negative squared radius (no real points).
    grade : grade of the blade as given; ``form``: the reading used, "dual" (OPNS) or "standard" (IPNS).
    radius2 : squared radius of a round (negative when imaginary, 0 for tangents and points), else None.
    """

    kind: str
    dimension: int | None
    imaginary: bool
    grade: int
    form: str
    radius2: float | None = None

    def __post_init__(self):
        func = "BladeKind"
        checks.choice(self.kind, func, "kind", _KINDS)
        for f, low, high in (("dimension", -1, 3), ("grade", 0, 5)):
            v = getattr(self, f)
            if v is None and f == "dimension":
                continue
            if not isinstance(v, numbers.Integral) or isinstance(v, (bool, np.bool_)):
                raise checks.fail(func, f, f"must be a whole number (an int), got {v!r}")
            checks.integer(v, func, f, low=low, high=high)
        checks.flag(self.imaginary, func, "imaginary")
        checks.choice(self.form, func, "form", ("dual", "standard"))
        if self.radius2 is not None:
            checks.real(self.radius2, func, "radius2")

    @property
    def name(self) -> str:
        """A readable name: "point pair", "imaginary circle", "line", "free bivector", ..."""
        base = _NAMES.get(self.kind, {}).get(self.dimension, self.kind)
        return f"imaginary {base}" if self.imaginary else base


def _form(form, k: int, func: str, name: str) -> str:
    f = _FORMS.get(form if isinstance(form, str) else None)
    if f is None:
        raise InvalidInputError(f"{func}: {name}: form must be one of {sorted(_FORMS)}, got {form!r}")
    if f == "auto":
        return "standard" if k == 1 else "dual"
    return f


def _size(X) -> float:
    return math.hypot(*X.coeffs.values())


def classify(X, form: str = "auto", tol: float = 1e-10, tangent_tol: float = 1e-12) -> BladeKind:
    """The kind of a CGA blade: round, flat, tangent, direction, point (DFM 2007, ch. 14 and its summary table).

    With ``X`` in OPNS (dual form; a standard form is first turned into it with ``X Ic^-1``, 2.31), of grade k:

    ============================================  ===========================  ============
    test                                          kind                         dimension
    ============================================  ===========================  ============
    ``einf ^ X = 0`` and ``einf _| X = 0``        direction (``einf ^ E``)     k - 1
    ``einf ^ X = 0``                              flat (``einf ^ a ^ ...``)    k - 2
    ``einf _| X = 0``                             dual flat (a flat's IPNS)    3 - k
    ``X X^ = 0``                                  tangent (a null vector:      k - 1
                                                  "point")
    otherwise                                     round                        k - 2
    ============================================  ===========================  ============

    A round has ``radius2 = X X^ / (einf _| X)^2`` (DFM ch. 14, rounds; ``X^`` the grade involution, 2.35),
    negative for an imaginary round; for two spheres this is Theorem 2.4.1's sign test of ``(s1 ^ s2)^2``.  Grade 0
    in OPNS is "scalar" (the empty set, e.g. the meet of disjoint blades), grade 5 "pseudoscalar" (the whole space).

    ``tol`` is relative to the coefficient norm (the zero tests of ``einf ^ X``, ``einf _| X``); ``tangent_tol``
    to its square (the test of ``X X^``, which tells a small round from a tangent).  Both sit above round-off, but
    floats resolve small rounds far from the origin badly in this representation: for a point pair of separation d
    at distance D, ``|X X^| / |X|^2`` is about ``d^2 / (2 (1 + D^2)^2)``, its round-off about ``eps D / d``, and
    ``radius2`` has a relative error near ``eps D^5 / d^3`` (measured: 10 % for a pair 1 cm apart, 70 m out).  An
    entity the constructors built carries its local frame (:mod:`~cga_lessons.conformal.anchored`) and is classified
    by its local blade, which has the same kind and radius (the tests are invariant under translation) at any distance.

    >>> from cga_lessons import conformal as cga
    >>> classify(cga.circle_from_points([1, 0, 0], [0, 1, 0], [-1, 0, 0])).name
    'circle'
    >>> k = classify(cga.sphere([0, 0, 0], 2.0))          # a vector: read as a standard form
    >>> k.kind, k.dimension, round(k.radius2, 9), k.imaginary
    ('round', 2, 4.0, False)
    >>> classify(cga.line_from_points([0, 0, 0], [1, 2, 3])).name, classify(cga.up([1, 2, 3])).name
    ('line', 'point')
    """
    tol = checks.real(tol, "classify", "tol", low=0.0, high=1.0, strict_high=True)
    tangent_tol = checks.real(tangent_tol, "classify", "tangent_tol", low=0.0, high=1.0, strict_high=True)
    X, k = require_blade(frame(X)[1], "classify", "X")  # an anchored entity: its local blade (the same kind, radius)
    f = _form(form, k, "classify", "form")
    if k == 1 and abs(float((X * X).scalar())) <= tangent_tol * _size(X) ** 2:  # null: a point in both readings
        at_infinity = _size(einf ^ X) <= tol * _size(X)
        return BladeKind("direction" if at_infinity else "point", 0, False, 1, f, None if at_infinity else 0.0)
    Xo, ko = (X, k) if f == "dual" else (dual(X), 5 - k)
    if ko in (0, 5):
        return BladeKind("scalar" if ko == 0 else "pseudoscalar", None, False, k, f)
    scale = _size(Xo) * 2**0.5  # |einf| = sqrt(2)
    contraction = left_contraction(einf, Xo)
    no_wedge, no_contraction = _size(einf ^ Xo) <= tol * scale, _size(contraction) <= tol * scale
    if no_wedge or no_contraction:
        if no_wedge and no_contraction:
            return BladeKind("direction", ko - 1, False, k, f)
        return BladeKind("flat", ko - 2, False, k, f) if no_wedge else BladeKind("dual flat", 3 - ko, False, k, f)
    XX = float((Xo * Xo.involute()).scalar())
    if abs(XX) <= tangent_tol * _size(Xo) ** 2:
        return BladeKind("point" if ko == 1 else "tangent", ko - 1, False, k, f, 0.0)
    CC = float((contraction * contraction).scalar())
    if CC == 0.0:
        raise DegenerateGeometryError(f"classify: X: einf _| X squares to zero, no radius ({Xo!r})")
    radius2 = XX / CC
    return BladeKind("round", ko - 2, radius2 < 0, k, f, radius2)


def intersect(X, Y, forms=("auto", "auto"), out: str = "auto", tol: float = 1e-10):
    """Intersection of two entities of table 2.1, in the form they come in (section 2.3.3; DFM 5.3, ch. 15).

    ``forms`` says how to read X and Y ("auto": a vector is a standard form, other grades dual forms, see the
    module docstring).  Both are turned into dual form (OPNS, ``X Ic^-1`` for a standard form, 2.31) and met with
    :func:`cga_lessons.conformal.blades.meet`.  The result comes back in dual form, or in standard form when both inputs
    were standard (``out="auto"``; or ask with ``out="dual"``/``"standard"``).  The standard form carries the sign that
    makes it, in general position, exactly the thesis's outer product: ``s1 ^ s2`` for two spheres (2.79),
    ``P1 ^ P2`` for two planes and ``s1 ^ s2 ^ s3`` for a point pair (table 2.1).

    Degenerate positions are not errors: parallel planes give a free bivector, a line that misses a sphere an
    imaginary point pair, tangent spheres a tangent bivector, concentric spheres a dual flat point.  Ask
    :func:`classify` (with the same ``form``) what came back.  Anchored entities
    (:mod:`~cga_lessons.conformal.anchored`) keep their frames and are met in them
    (:func:`~cga_lessons.conformal.blades.meet` decides on the local blades): two unit spheres 1e6 out give their
    circle, exact, at the default ``tol``.

    >>> from cga_lessons import conformal as cga
    >>> z = intersect(cga.sphere([0, 0, 0], 1.0), cga.sphere([1, 0, 0], 1.0))  # standard form, (2.79)
    >>> (z - (cga.sphere([0, 0, 0], 1.0) ^ cga.sphere([1, 0, 0], 1.0))).iszero(1e-12)
    True
    >>> k = classify(z, form="standard")
    >>> k.name, round(k.radius2, 6)                                            # r^2 = 1 - (1/2)^2
    ('circle', 0.75)
    >>> PP = intersect(cga.line_from_points([-5, 0, 0], [5, 0, 0]), cga.sphere([0, 0, 0], 2.0))
    >>> [p.round(9).tolist() for p in cga.point_pair_endpoints(PP)]            # a dual-form point pair
    [[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
    """
    if not isinstance(forms, (tuple, list)) or len(forms) != 2:
        raise InvalidInputError(f"intersect: forms: expected a pair of forms, got {forms!r}")
    tol = checks.real(tol, "intersect", "tol", low=0.0, high=1.0, strict_high=True)
    X0, Y0 = X, Y
    X, kx = require_blade(X, "intersect", "X")
    Y, ky = require_blade(Y, "intersect", "Y")
    # anchored entities keep their frames (their local blades, at the grade kept); dual, meet and undual carry them
    X, Y = follow(X, lambda a: a.grade(kx), X0), follow(Y, lambda b: b.grade(ky), Y0)
    fx, fy = _form(forms[0], kx, "intersect", "forms[0]"), _form(forms[1], ky, "intersect", "forms[1]")
    Xo, Yo = (X if fx == "dual" else dual(X)), (Y if fy == "dual" else dual(Y))
    M = meet(Xo, Yo, tol)
    fo = _FORMS.get(out) if isinstance(out, str) else None
    if fo is None:
        raise InvalidInputError(f"intersect: out: must be one of {sorted(_FORMS)}, got {out!r}")
    if fo == "auto":
        fo = "standard" if fx == fy == "standard" else "dual"
    if fo == "dual":
        return M
    xs, ys = 5 - Xo.grades_present()[0], 5 - Yo.grades_present()[0]
    return undual(M) * (-1.0 if (xs * ys) % 2 == 0 else 1.0)
