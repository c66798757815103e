"""Chapter 2's derivations verified with SymPy (stereographic projection, point-pair extraction, motor
decomposition...) and the errata they decide.

Layer 3 of the package: imports layers 0-2 (errors, algebra, conformal) only (``tests/test_layers.py`` checks it).
Nothing here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in
``__all__``; its modules:

* :mod:`~cga_lessons.symbolic.axioms`: Symbolic derivations of sections 2.1-2.2: the Clifford product of vectors in
  the plane and the basis blades and product axioms of G(p, q, r), Eqs. (2.1)-(2.10)
* :mod:`~cga_lessons.symbolic.circles_lines`: Symbolic derivations of circles and lines (table 2.1, sections
  2.4.3-2.4.4):
* :mod:`~cga_lessons.symbolic.core`: Shared machinery of the symbolic derivations (:mod:`cga_lessons.symbolic`)
* :mod:`~cga_lessons.symbolic.derivations`: Verified derivations of chapter 2 with SymPy, and the errata they decide
* :mod:`~cga_lessons.symbolic.entities`: Symbolic derivations of spheres, planes and point pairs (table 2.1,
* :mod:`~cga_lessons.symbolic.model`: Symbolic derivations of sections 2.3-2.3.3: the stereographic projection, the
  Minkowski plane and conformal points, Eqs. (2.38)-(2.68)
* :mod:`~cga_lessons.symbolic.records`: The record of a derivation: its Check steps, the Derivation that holds them
* :mod:`~cga_lessons.symbolic.transformations`: Symbolic derivations of the conformal transformations (section
  2.3.4, table 2.2, Eqs. 2.82-2.93)
* :mod:`~cga_lessons.symbolic.versors`: Symbolic derivations of the rotor and motor properties (sections
  2.4.6-2.4.7, Eqs. 2.135-2.145)
"""

from .axioms import basis_and_product_axioms, clifford_product_plane
from .circles_lines import circle_properties, line_properties
from .core import Ring, is_zero, proportional, same
from .derivations import DERIVATIONS, ERRATA, Erratum, errata_table, run_all, verify_errata
from .entities import point_pair_extraction, sphere_and_plane
from .model import (
    MINKOWSKI_PROPERTIES,
    minkowski_plane,
    null_cone_points,
    projection_rejection,
    stereographic_projection,
)
from .records import Check, Derivation
from .transformations import conformal_transformations
from .versors import rotors_and_motors

__all__ = [
    "Check",
    "Derivation",
    "Ring",
    "is_zero",
    "same",
    "proportional",
    "clifford_product_plane",
    "basis_and_product_axioms",
    "stereographic_projection",
    "minkowski_plane",
    "MINKOWSKI_PROPERTIES",
    "projection_rejection",
    "null_cone_points",
    "sphere_and_plane",
    "circle_properties",
    "line_properties",
    "point_pair_extraction",
    "conformal_transformations",
    "rotors_and_motors",
    "DERIVATIONS",
    "run_all",
    "Erratum",
    "ERRATA",
    "verify_errata",
    "errata_table",
]
