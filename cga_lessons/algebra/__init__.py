"""The geometric algebra G(p, q, r) of chapter 2 (section 2.2), numeric and symbolic: the Algebra and its Multivector,
the products, inverse, exponential and the versor matrices.

Layer 1 of the package: imports the errors and paths of layer 0 only (``tests/test_layers.py`` checks it). Nothing
here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in ``__all__``; its
modules:

* :mod:`~cga_lessons.algebra.access`: Reading and comparing a multivector: coefficients by blade name, batches,
  arrays, ``isclose`` and ``==``
* :mod:`~cga_lessons.algebra.coefficients`: The three kinds of coefficient a multivector holds, and cheap tests for
  them
* :mod:`~cga_lessons.algebra.core`: The geometric algebra G(p, q, r) of chapter 2 (section 2.2)
* :mod:`~cga_lessons.algebra.display`: How a multivector reads: its text and LaTeX forms, and tidying of SymPy
  coefficients
* :mod:`~cga_lessons.algebra.exponential`: The exponential of a bivector (2.37), summed in closed form
* :mod:`~cga_lessons.algebra.exponential_coefficients`: The scalar coefficients of the closed-form exponential of a
  bivector (2.37)
* :mod:`~cga_lessons.algebra.inverse`: Norms and the inverse of a multivector (2.19)
* :mod:`~cga_lessons.algebra.involutions`: Grade projection, the involutions and the dual of a multivector
  (2.16-2.18, 2.31-2.35)
* :mod:`~cga_lessons.algebra.motor_matrices`: Motors of G(4,1) in closed form: their rotor and translation read off
  the coefficients, and their matrices built from (R, t) in the null basis (2.102, 2.141-2.144)
* :mod:`~cga_lessons.algebra.multivector`: The Multivector type of :mod:`cga_lessons.algebra` and its operators
* :mod:`~cga_lessons.algebra.operands`: The checks of the algebra's operands (on :mod:`cga_lessons.checks`): what
  the operators refuse, and what they check where
* :mod:`~cga_lessons.algebra.products`: Products of multivectors: the cached (blade, blade, result, sign) terms and
  the code that runs them
* :mod:`~cga_lessons.algebra.versor_matrices`: A versor's action as one matrix per grade, built in closed form
  (2.82)
"""

from cga_lessons.errors import DegenerateGeometryError, GeometryError, InvalidInputError

from .coefficients import REAL_TYPES, absmax, all_finite, any_sympy, is_real_batch, is_real_single, is_sympy
from .core import Algebra
from .exponential import exp
from .motor_matrices import motor_tolerance
from .multivector import Multivector, commutator
from .operands import finite_multivector

__all__ = [
    "Algebra",
    "Multivector",
    "GeometryError",
    "DegenerateGeometryError",
    "InvalidInputError",
    "commutator",
    "exp",
    "finite_multivector",
    "REAL_TYPES",
    "absmax",
    "all_finite",
    "any_sympy",
    "is_real_batch",
    "is_real_single",
    "is_sympy",
    "motor_tolerance",
]
