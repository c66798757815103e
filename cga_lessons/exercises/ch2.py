"""Exercises of chapter 2, notebooks 01 and 02: products and the conformal model.

Those of notebooks 03 and 04 (versors, entity properties) are in :mod:`cga_lessons.exercises.ch2_motions`.

Every truth here is a closed form written out with plain NumPy/SymPy (Rodrigues' matrix, 4x4 homogeneous
matrices, coefficients worked out by hand from the rules (2.4) and (2.10)), not the library function a
student would call.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons.algebra import Algebra

from .checking import exercise
from .compare import compare_expression, compare_multivector, compare_number, compare_vector


def real_symbols(*names):
    """``{name: sympy.Symbol(name, real=True)}`` for each name, in order (the unknowns of a derived answer)."""
    import sympy

    return {n: sympy.Symbol(n, real=True) for n in names}


# --------------------------------------------------------------------------- notebook 01


@exercise(
    "ch2.1",
    title="derive the square of a general bivector x e12 + y e23 + z e31 of G(3)",
    notebook="01_geometric_algebra",
    kind="derive",
    expects="a SymPy expression in x, y, z",
    equations=("2.4", "2.10"),
)
def _ch2_1(answer):
    s = real_symbols("x", "y", "z")
    x, y, z = s.values()
    truth = -(x**2 + y**2 + z**2)
    compare_expression(
        answer,
        truth,
        s,
        hints=[(-truth, "the sign is wrong: each unit bivector squares to -1 (e12 e12 = e1 e2 e1 e2 = -e1 e1 e2 e2).")],
    )
    return "Every bivector of G(3) squares to minus its squared magnitude: it behaves like an imaginary unit."


@exercise(
    "ch2.2",
    title="the dual of v = e1 + 2 e2 + 3 e3 in G(3), Eq. (2.31)",
    notebook="01_geometric_algebra",
    kind="compute",
    expects="a Multivector of G(3) (Algebra(3))",
    equations=("2.31",),
)
def _ch2_2(answer):
    G3 = Algebra(3)
    # I = e123 and I^-1 = -e123;  e1 I^-1 = -e23,  e2 I^-1 = -e31,  e3 I^-1 = -e12  (by (2.10))
    truth = G3.blade("e23", -1.0) + G3.blade("e31", -2.0) + G3.blade("e12", -3.0)
    compare_multivector(
        answer,
        truth,
        hints=[(-truth, "the sign is wrong: that is v I. The dual multiplies by I^-1, and in G(3) I^-1 = -I.")],
    )
    return "The dual of a vector of G(3) is the bivector of the plane orthogonal to it."


@exercise(
    "ch2.3",
    title="exp(B) for B = e12 + e34 in G(4), where the one-plane closed form of (2.37) breaks",
    notebook="01_geometric_algebra",
    kind="break",
    expects="a Multivector of G(4) (Algebra(4))",
    equations=("2.37",),
)
def _ch2_3(answer):
    G4 = Algebra(4)
    c, s = math.cos(1.0), math.sin(1.0)
    # e12 and e34 commute, so exp(B) = exp(e12) exp(e34) = (c + s e12)(c + s e34), and e12 e34 = e1234
    truth = G4.scalar(c * c) + G4.blade("e12", c * s) + G4.blade("e34", c * s) + G4.blade("e1234", s * s)
    B = G4.blade("e12") + G4.blade("e34")
    r2 = math.sqrt(2.0)
    one_plane = B * (math.sin(r2) / r2) + math.cos(r2)
    compare_multivector(
        answer,
        truth,
        hints=[
            (
                one_plane,
                "that is the one-plane closed form cos|B| + sin|B| B/|B|. It assumes B^2 is a scalar; here B^2 "
                "= -2 + 2 e1234 is not. Use that e12 and e34 commute.",
            )
        ],
    )
    return "A bivector that is not a blade is a sum of commuting planes; its exponential is the product of theirs."


# --------------------------------------------------------------------------- notebook 02


@exercise(
    "ch2.4",
    title="the inner product of the conformal points of a = (1, 2, 2) and b = (4, 6, 2), Eq. (2.66)",
    notebook="02_conformal_model",
    kind="compute",
    expects="a float",
    equations=("2.62", "2.66"),
)
def _ch2_4(answer):
    a, b = np.array([1.0, 2.0, 2.0]), np.array([4.0, 6.0, 2.0])
    d2 = float(np.sum((a - b) ** 2))
    compare_number(
        answer,
        -d2 / 2,
        hints=[
            (d2 / 2, "the sign is wrong. The inner product of two conformal points is never positive."),
            (-d2, "that is minus the squared distance; (2.66) has a factor 1/2."),
            (d2, "that is (a - b)^2 of (2.67), the square of the difference, not the inner product."),
            (-math.sqrt(d2), "that is minus the distance; the inner product gives half its square."),
            (math.sqrt(d2), "that is the distance; the inner product gives minus half its square."),
        ],
    )
    return "a.b = -|a - b|^2 / 2: distances are inner products in the conformal model."


@exercise(
    "ch2.5",
    title="derive s^2 for s = up(c) + (rho^2/2) e (a plus sign): the imaginary sphere",
    notebook="02_conformal_model",
    kind="derive",
    expects="a SymPy expression in rho (c1, c2, c3 may appear if they cancel)",
    equations=("2.72", "2.73"),
)
def _ch2_5(answer):
    s = real_symbols("rho", "c1", "c2", "c3")
    rho = s["rho"]
    compare_expression(
        answer,
        -(rho**2),
        s,
        hints=[
            (rho**2, "that is s^2 for the real sphere p - (rho^2/2) e of (2.73); the plus sign flips the rho^2 term.")
        ],
    )
    return "s^2 = -rho^2 < 0: x.s = 0 asks |x - c|^2 = -rho^2, which no real point satisfies."


@exercise(
    "ch2.6",
    title="which Euclidean point the printed middle line of (2.63) represents, for x = (1, 2, 2)",
    notebook="02_conformal_model",
    kind="break",
    expects="a NumPy array of shape (3,)",
    equations=("2.63", "2.64"),
)
def _ch2_6(answer):
    x = np.array([1.0, 2.0, 2.0])
    # printed: x + x^2/2 (e- - e+) + (e- + e+)/2 = x + x^2 e0 + e/2 = x^2 up(x / x^2): the inverse point
    truth = x / (x @ x)
    compare_vector(
        answer,
        truth,
        hints=[
            (x, "that is the point of the corrected (2.63). The printed line swaps e and e0; work out what it is."),
            (x * (x @ x), "the direction is right; check the weight: divide the vector by -X.e, not multiply."),
        ],
    )
    return (
        "The printed form is still a null vector, so it looks like a point, "
        "but it is x^2 up(x/x^2): the inversion of x."
    )
