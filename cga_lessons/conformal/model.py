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

from cga_lessons.algebra import (
    Algebra,
    Multivector,
)

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

_EXACT = None


def exact_constants() -> dict:
    """The constants with SymPy rational coefficients (for symbolic work).

    Returns a dict with keys ``e1 e2 e3 ep em einf eo E IE Ic``.
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
        _EXACT = {
            "e1": b[0],
            "e2": b[1],
            "e3": b[2],
            "ep": b[3],
            "em": b[4],
            "einf": einf_s,
            "eo": eo_s,
            "E": E_s,
            "IE": IE_s,
            "Ic": E_s * IE_s,
        }
    return _EXACT
