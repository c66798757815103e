"""The conformal model G(4,1) of section 2.3: basis and null vectors (its points: :mod:`.points`).

(Re-exported by :mod:`cga_lessons.conformal`, which is the module to import.)

Basis vectors ``e1 e2 e3`` (Euclidean), ``ep`` (e+, squares to +1) and ``em``
(e-, squares to -1), (2.52).  The null basis (2.53), kept with the thesis's
signs::

    eo   = (e- - e+)/2      the origin, e_0
    einf = e- + e+          the point at infinity, e (the thesis writes plain e)

``E = e+ e- = einf ^ eo`` is the Minkowski plane's pseudoscalar (2.55; the
printed ``e0 ^ e`` has the wrong sign, see the erratum in the registry),
``IE = e1 e2 e3`` and ``Ic = E IE`` (2.60).

Import it through the facade: ``from cga_lessons import conformal as cga`` gives everything::

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> X = cga.up([1.0, 2.0, 3.0])
    >>> float(X | X), float(X | cga.einf)
    (0.0, -1.0)
    >>> cga.down(X)
    array([1., 2., 3.])
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from cga_lessons import checks
from cga_lessons.algebra import Algebra, Multivector, finite_multivector

__all__ = [
    "G41",
    "e1",
    "e2",
    "e3",
    "ep",
    "em",
    "einf",
    "eo",
    "E",
    "IE",
    "Ic",
    "ModelConstants",
    "exact_constants",
]

#: The conformal algebra G(4,1) with basis e1, e2, e3, e+, e- (2.60).
G41 = Algebra(4, 1, labels=["1", "2", "3", "+", "-"])

e1, e2, e3, ep, em = G41.basis_vectors()
#: e, the point at infinity (2.53)
einf = em + ep
#: e_0, the origin (2.53)
eo = 0.5 * (em - ep)
#: E = e+ e- = e ^ e0, pseudoscalar of the Minkowski plane (2.55, corrected)
E = ep * em
#: I_E = e1 e2 e3, pseudoscalar of G3
IE = e1 * e2 * e3
#: I_c = E I_E = e+-123, pseudoscalar of G(4,1) (2.60)
Ic = E * IE


@dataclass(frozen=True)
class ModelConstants:
    """The basis and null vectors of G(4,1) and its pseudoscalars, with float coefficients (:data:`CONSTANTS`) or
    exact SymPy ones (:func:`exact_constants`): ``e1 e2 e3`` (Euclidean), ``ep`` (e+) and ``em`` (e-) of (2.52),
    ``einf`` (e) and ``eo`` (e0) of (2.53), ``E = e+ e-`` (2.55, corrected), ``IE = e1 e2 e3`` and ``Ic = E IE``
    (2.60).  Each is a Multivector of :data:`G41`."""

    e1: Multivector
    e2: Multivector
    e3: Multivector
    ep: Multivector
    em: Multivector
    einf: Multivector
    eo: Multivector
    E: Multivector
    IE: Multivector
    Ic: Multivector

    def __post_init__(self):
        for f in fields(self):
            value = checks.instance(getattr(self, f.name), "ModelConstants", f.name, Multivector, "a Multivector")
            finite_multivector(value, "ModelConstants", f.name)
            if value.algebra is not G41:
                raise checks.fail(
                    "ModelConstants", f.name, f"expected a Multivector of G(4,1), got one of {value.algebra}"
                )


#: The constants with float coefficients (the module's ``e1 ... Ic``), as one :class:`ModelConstants`.
CONSTANTS = ModelConstants(e1, e2, e3, ep, em, einf, eo, E, IE, Ic)

_EXACT = None


def exact_constants() -> ModelConstants:
    """The constants with SymPy rational coefficients (for symbolic work), computed once.

    >>> from cga_lessons import conformal as cga
    >>> c = cga.exact_constants()
    >>> c.eo
    -1/2 e+ + 1/2 e-
    """
    global _EXACT
    if _EXACT is None:
        import sympy

        one = sympy.Integer(1)
        b = [Multivector(G41, {1 << i: one}) for i in range(5)]
        half = sympy.Rational(1, 2)
        einf_s = b[4] + b[3]
        eo_s = (b[4] - b[3]) * half
        E_s = b[3] * b[4]
        IE_s = b[0] * b[1] * b[2]
        _EXACT = ModelConstants(b[0], b[1], b[2], b[3], b[4], einf_s, eo_s, E_s, IE_s, E_s * IE_s)
    return _EXACT
