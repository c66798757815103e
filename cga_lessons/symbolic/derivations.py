"""Verified derivations of chapter 2 with SymPy, and the errata they decide.

Every function here rebuilds a piece of the thesis with exact symbolic
coefficients and returns a :class:`~cga_lessons.symbolic.core.Derivation`:
the list of its checks (each printed step against what the algebra computes)
and the named values a notebook may display.  ``d.holds`` is true when every
correct step holds and every printed erratum fails::

    >>> from cga_lessons import symbolic
    >>> d = symbolic.stereographic_projection()
    >>> d.holds, d.values["a"]
    (True, 2*x/(x**2 + 1))
    >>> d["2.45 a = 2x/(x^2+1)"].holds
    True

The derivations, by section of chapter 2:

==============================  =========================================
function                        equations
==============================  =========================================
clifford_product_plane          2.1-2.8
basis_and_product_axioms        2.9-2.10
stereographic_projection        2.38-2.51 (solved with ``sympy.solve``)
minkowski_plane                 2.52-2.56 (each property of 2.56, two E's)
projection_rejection            2.57-2.60
null_cone_points                2.61-2.68
sphere_and_plane                2.69-2.77 (and table 2.1's plane)
circle_properties               2.78-2.80, 2.119-2.124
line_properties                 2.81, 2.125-2.130 (and table 2.1's line)
conformal_transformations       2.82-2.93 and table 2.2
point_pair_extraction           2.131-2.134
rotors_and_motors               2.135-2.145 (and 2.95, 2.106 on the way)
==============================  =========================================

:data:`ERRATA` lists the printed formulas that are wrong, with the correct
form and the check that decides; :func:`verify_errata` reruns those checks.

The code lives in :mod:`~cga_lessons.symbolic.axioms` (2.1-2.10), :mod:`~cga_lessons.symbolic.model` (2.38-2.68),
:mod:`~cga_lessons.symbolic.entities` (spheres, planes, point pairs),
:mod:`~cga_lessons.symbolic.circles_lines` and
:mod:`~cga_lessons.symbolic.transformations` and :mod:`~cga_lessons.symbolic.versors` (transformations, rotors,
motors), on the
machinery of :mod:`~cga_lessons.symbolic.core` (checks, exact polynomial
arithmetic modulo relations such as ``cos^2 + sin^2 = 1``).
"""

from __future__ import annotations

from dataclasses import dataclass

from cga_lessons import checks

from .axioms import basis_and_product_axioms, clifford_product_plane
from .circles_lines import circle_properties, line_properties
from .entities import point_pair_extraction, sphere_and_plane
from .model import (
    minkowski_plane,
    null_cone_points,
    projection_rejection,
    stereographic_projection,
)
from .records import Derivation
from .transformations import conformal_transformations
from .versors import rotors_and_motors

__all__ = [
    "DERIVATIONS",
    "run_all",
    "Erratum",
    "ERRATA",
    "verify_errata",
    "errata_table",
]

#: name -> derivation function, in the order of the chapter.
DERIVATIONS = {
    f.__name__: f
    for f in (
        clifford_product_plane,
        basis_and_product_axioms,
        stereographic_projection,
        minkowski_plane,
        projection_rejection,
        null_cone_points,
        sphere_and_plane,
        circle_properties,
        line_properties,
        conformal_transformations,
        point_pair_extraction,
        rotors_and_motors,
    )
}


def run_all() -> dict:
    """Run every derivation; returns ``{name: Derivation}`` (under 10 s the first time; each derivation is
    computed once per process, and later calls return copies)."""
    return {name: f() for name, f in DERIVATIONS.items()}


@dataclass(frozen=True)
class Erratum:
    """A printed formula of the thesis that is wrong.

    Attributes
    ----------
    label : str
        Equation number (``"2.56"``) or table (``"table 2.2"``).
    printed, correct : str
        The formula as printed and as it should read.
    decided_by : str
        Dotted name of the derivation whose checks decide.
    printed_check, correct_check : str
        Names of the checks in that derivation: the first must fail, the second hold.
    note : str
        Why, in a sentence.
    """

    label: str
    printed: str
    correct: str
    decided_by: str
    printed_check: str
    correct_check: str
    note: str = ""

    def __post_init__(self):
        for name in ("label", "printed", "correct", "decided_by", "printed_check", "correct_check"):
            checks.text(getattr(self, name), "Erratum", name)
        checks.text(self.note, "Erratum", "note", empty=True)
        prefix, _, name = self.decided_by.rpartition(".")
        if prefix != "cga_lessons.symbolic" or name not in DERIVATIONS:
            raise checks.fail(
                "Erratum", "decided_by", f"expected 'cga_lessons.symbolic.<derivation>', one of {list(DERIVATIONS)}"
            )

    @property
    def function(self):
        return DERIVATIONS[self.decided_by.rsplit(".", 1)[1]]


_S = "cga_lessons.symbolic."

#: The errata of chapter 2 found by the derivations (numbered equations and tables).
ERRATA: tuple[Erratum, ...] = (
    Erratum(
        "2.55",
        "E := e0 ^ e = e+ ^ e- = e+ e-",
        "E := e ^ e0 = e+ ^ e- = e+ e-",
        _S + "minkowski_plane",
        "2.55 E := e0 ^ e = e+ e- (printed)",
        "2.55 E = e ^ e0 = e+ e- (corrected)",
        "e0 ^ e = -e+ e-; with e0 = (e- - e+)/2 and e = e- + e+ the pseudoscalar e+ e- is e ^ e0.",
    ),
    Erratum(
        "2.56",
        "e0 E = e0",
        "e0 E = -e0 (equivalently E e0 = e0)",
        _S + "minkowski_plane",
        "2.56 e0 E = e0 [E = e+e-]",
        "2.56 e0 E = -e0 (corrected)",
        "With E = e+ e- the other nine properties hold and this one fails; with the printed E = e0 ^ e it "
        "holds but six others fail, so no single sign of E makes all of (2.56) true.",
    ),
    Erratum(
        "2.63",
        "x + x^2 (e- - e+)/2 + (e- + e+)/2   (middle line)",
        "x + x^2 (e- + e+)/2 + (e- - e+)/2",
        _S + "null_cone_points",
        "2.63 middle line (printed)",
        "2.63 middle line (corrected)",
        "The expansions of e and e0 (2.53) are swapped; the final line of (2.63) is right.",
    ),
    Erratum(
        "2.92",
        "T = (n + delta e)(n + 0 e) = 1 + t e / 2",
        "T = (n + delta e) n = 1 + e t / 2  (= 1 - t e / 2), t = 2 delta n",
        _S + "conformal_transformations",
        "2.92 = 1 + t e/2 (printed)",
        "2.92 (n + delta e) n = 1 + e t/2, t = 2 delta n (corrected)",
        "e and t anticommute; 1 + e t/2 translates by +t as in (2.100), the printed 1 + t e/2 by -t "
        "(table 2.2 pairs 1 + t e/2 with x - t, which is consistent).",
    ),
    Erratum(
        "2.121",
        "L_z* . P_z* = e ^ s_e0",
        "L_z* P_z* = k (e ^ s_e0)*  (geometric product, a 3-vector; its vector part L_z* . P_z* is 0)",
        _S + "circle_properties",
        "2.121 L_z* . P_z* = e ^ s_e0 (printed, thesis inner product)",
        "2.121 L_z* P_z* = k (e ^ s_e0)* (corrected)",
        "A 3-vector . 4-vector is a vector; the product of the axis and the plane is the dual of e ^ s_e0.",
    ),
    Erratum(
        "2.122",
        "rho_z = z^2 / (e ^ z)^2",
        "rho_z^2 = -z^2 / (e ^ z)^2",
        _S + "circle_properties",
        "2.122 rho^2 = z^2 / (e ^ z)^2 (printed, squared)",
        "2.122 rho^2 = -z^2 / (e ^ z)^2 (corrected)",
        "The ratio is -rho^2 (for z = z* Ic, any scale); table 2.1 prints the same formula.",
    ),
    Erratum(
        "2.128",
        "m = e+ L",
        "m = -e+ . L  (= a x r for the unit line through a with direction r)",
        _S + "line_properties",
        "2.128 m = e+ L (printed)",
        "2.128 m = -e+ . L = a x r (corrected)",
        "e+ L also has 3- and 4-vector parts, and its vector part is -(a x r); with -e+ . L (2.129) holds.",
    ),
    Erratum(
        "2.131",
        "p_1,2 = (PP* +- sqrt(PP* PP*)) / (PP* . e)",
        "p_1,2 = (PP* -+ sqrt(PP* PP*)) (PP* . e)^-1",
        _S + "point_pair_extraction",
        "2.131 p1 = (B + sqrt(BB)) / (B . e) = a (printed +- order)",
        "2.131 p1 = (B - sqrt(BB)) (B . e)^-1 = a (corrected -+ order)",
        "With the division on the right, p1 = a comes from the numerator B - sqrt(B B) of (2.132), as the text "
        "says; the printed +- puts b first.",
    ),
    Erratum(
        "2.139",
        "R_L ~R_L = T R ~T ~T ~R  (first line)",
        "R_L ~R_L = T R ~T T ~R ~T = 1",
        _S + "rotors_and_motors",
        "2.139 first line T R ~T ~T ~R = 1 (printed)",
        "2.139 first line T R ~T T ~R ~T = 1 (corrected)",
        "The reverse of T R ~T is T ~R ~T; the printed first line is not 1 when t != 0.",
    ),
    Erratum(
        "table 2.1",
        "plane: P = N I_E - d e, d = (a ^ b ^ c) I_E",
        "d = (a ^ b ^ c) I_E^-1 = a . (b x c)  (so d I_E = a ^ b ^ c as in 2.77)",
        _S + "sphere_and_plane",
        "table 2.1 plane d = (a ^ b ^ c) I_E (printed)",
        "2.77 standard form = N I_E - d e = -(n + d e), n = (b-a)x(c-a)",
        "I_E^2 = -1, so the printed d has the wrong sign relative to (2.77).",
    ),
    Erratum(
        "table 2.1",
        "line: L = r I_E + e M I_E, r = a - b",
        "r = b - a (as in 2.81)",
        _S + "line_properties",
        "table 2.1 line L = r I_E + e M I_E, r = a - b (printed)",
        "table 2.1 line L = r I_E + e M I_E, r = b - a (corrected)",
        "L = L* Ic with L* = e ^ a ^ b of (2.81).",
    ),
    Erratum(
        "table 2.1",
        "circle: z = s1 ^ s1",
        "z = s1 ^ s2 (2.79)",
        _S + "circle_properties",
        "table 2.1 circle z = s1 ^ s1 (printed)",
        "2.80 (a ^ b ^ c) Ic = s1 ^ s2 up to scale",
        "s ^ s = 0 (perhaps a typesetting slip).",
    ),
    Erratum(
        "table 2.2",
        "reflection: g(x) = -n x n + 2 x delta",
        "g(x) = -n x n + 2 delta n (2.90)",
        _S + "conformal_transformations",
        "table 2.2 reflection g(x) = -n x n + 2 x delta (printed)",
        "table 2.2 reflection g(x) = -n x n + 2 delta n (corrected)",
        "The reflection in n . x = delta adds 2 delta n, not 2 delta x.",
    ),
)


def verify_errata(derivations: dict | None = None) -> list:
    """Rerun the deciding checks; returns ``[(erratum, printed_fails, correct_holds)]``.

    ``derivations`` may hold already computed results (``run_all()``).
    """
    func = "verify_errata"
    if derivations is not None and not isinstance(derivations, dict):
        raise checks.fail(func, "derivations", f"expected None or {{name: Derivation}}, got {derivations!r:.40}")
    derivations = dict(derivations or {})
    for name, d in derivations.items():
        if name not in DERIVATIONS or not isinstance(d, Derivation):
            raise checks.fail(
                func, "derivations", f"expected {{name: Derivation}} with names of DERIVATIONS, got {name!r}"
            )
    out = []
    for err in ERRATA:
        name = err.decided_by.rsplit(".", 1)[1]
        if name not in derivations:
            derivations[name] = DERIVATIONS[name]()
        d = derivations[name]
        try:
            out.append((err, not d[err.printed_check].holds, d[err.correct_check].holds))
        except KeyError as exc:
            raise checks.fail(func, "derivations", f"{name}: {exc}") from None
    return out


def errata_table() -> str:
    """The errata as a Markdown table (label, printed, correct, decided by)."""
    rows = ["| eq. | printed | correct | decided by |", "|---|---|---|---|"]
    for err in ERRATA:
        rows.append(f"| {err.label} | `{err.printed}` | `{err.correct}` | `{err.decided_by}` |")
    return "\n".join(rows)
