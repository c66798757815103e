"""Fuzz cases of the conformal versors, motors, logarithms, blades and motor estimation (group conformal_versors).

One valid call per public callable of :mod:`cga_lessons.conformal` defined in ``versors``, ``versors_build``,
``versors_rigid``, ``versor_log``, ``versor_powers``, ``blades``, ``blades_span``, ``blades_classify``,
``motor_estimation``, ``object_motors`` and the :class:`ModelConstants` of ``model`` (the
other modules of the facade are in ``cases_conformal_entities.py``).  ``kinds`` hold entities that a function
reading one kind of thing must refuse: a rotor reader given a translator or a sphere, a motor reader given a point,
a line reader given a circle.
"""

from __future__ import annotations

import copy

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra
from fuzz.harness import Case


def fresh(**kwargs):
    """The arguments of a valid call, deep-copied for every call with G41 itself kept (the memo maps the algebra to
    itself, whether or not ``Algebra`` defines ``__deepcopy__``: a copied algebra cannot be combined with G41's
    constants)."""
    return lambda: copy.deepcopy(kwargs, {id(cga.G41): cga.G41})


# ------------------------------------------------------------------ small valid objects
M = cga.motor([0.0, 0.0, 1.0], 0.5, [1.0, 2.0, 3.0])
M1 = cga.motor([0.0, 1.0, 0.0], 0.8, [0.0, -1.0, 2.0])
R = cga.rotor([0.0, 0.0, 1.0], 0.5)
T = cga.translator([1.0, 0.0, 0.0])
SCREW = cga.screw([0.0, 0.0, 1.0], [1.0, 2.0, 0.0], 1.0, 0.5)
D = cga.dilator(2.0)
X = cga.up([1.0, 2.0, 3.0])
S = cga.sphere([0.0, 0.0, 0.0], 2.0)
P = cga.plane([0.0, 0.0, 1.0], 1.0)
L = cga.line_from_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
L2 = cga.line_from_points([0.0, 0.0, 1.0], [0.0, 1.0, 1.0])
Z = cga.circle_from_points([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
PP = cga.point_pair([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
VEC = cga.e1 + 2 * cga.e2  # a Euclidean vector: odd, a reflection, no rotor
MIXED = 1 + cga.e1  # mixed parity: no versor
HUGE = 1e200 * cga.e1 + 1e200 * cga.e2  # finite coefficients whose squares overflow

H = cga.motor_to_matrix(M)
SHEAR = np.eye(4)
SHEAR[0, 1] = 0.5
SRC = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]])
DST = cga.apply_to_points(M, SRC)
COLLINEAR = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]])
A_PTS = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 1.0]])
B_PTS = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [1.0, 2.0, 1.0]])
SRC_LINES = cga.line_from_points(A_PTS, B_PTS)
DST_LINES = cga.line_from_points(cga.apply_to_points(M, A_PTS), cga.apply_to_points(M, B_PTS))
PARALLEL_LINES = cga.line_from_points(A_PTS, A_PTS + [1.0, 0.0, 0.0])
POINTS_NOT_LINES = cga.up(A_PTS)

ANGLES = ("[1.0, 2.0]",)  # a list of angles (or fractions) is a batch, valid
NOT_MOTORS = [X, S, P, VEC, D]  # a motor reader given a point, a sphere, a plane, a vector, a dilation
NOT_ROTORS = [T, M, X, S, VEC]  # a rotor (about the origin) reader given a translator, a motor, ...
NOT_LINES = [Z, S, X, PP]  # a line reader given a circle, a sphere, a point, a point pair
NOT_BLADES = [MIXED, cga.e1 * cga.e2 + cga.e3 * cga.ep]

CASES = [
    # ---------------------------------------------------------------- versors.py
    Case(cga.apply, fresh(V=M, X=X), kinds={"V": [X, MIXED]}, extra={"X": [HUGE]}),
    Case(cga.apply, fresh(V=S, X=L), name="apply (inversion of a line)", kinds={"V": [X, MIXED]}),
    Case(cga.apply_to_points, fresh(V=M, x=[[1.0, 2.0, 3.0], [0.0, 1.0, 0.0]]), kinds={"V": [X, MIXED]}),
    Case(
        cga.apply_to_points,
        fresh(V=S, x=[1.0, 0.0, 0.0]),
        name="apply_to_points (inversion)",
        extra={"x": [[0.0, 0.0, 0.0]]},  # the centre goes to infinity
    ),
    Case(cga.versor_matrix, fresh(V=M, grade=1), strict=True, kinds={"V": [X, MIXED]}),
    Case(cga.translator, fresh(t=[1.0, 2.0, 3.0]), extra={"t": [[1e200, 0.0, 0.0]]}),
    Case(cga.translator, fresh(t=[[1.0, 2.0, 3.0], [0.0, 0.0, 1.0]]), name="translator (batch)"),
    Case(
        cga.rotor,
        fresh(axis=[0.0, 0.0, 1.0], angle=0.5),
        strict=True,
        allow={"angle": ANGLES},
        extra={"axis": [[0.0, 0.0, 0.0]], "angle": [np.zeros(0), np.zeros((2, 2))]},
    ),
    Case(cga.rotor, fresh(axis=[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], angle=[0.5, 1.0]), name="rotor (batch)"),
    Case(
        cga.rotor_about_line,
        fresh(L=L, angle=0.5),
        strict=True,
        allow={"angle": ANGLES},
        kinds={"L": NOT_LINES},
        extra={"L": [1e-300 * L, 1e200 * L]},
    ),
    Case(
        cga.motor,
        fresh(rotation_axis=[0.0, 0.0, 1.0], angle=0.5, translation=[1.0, 2.0, 3.0]),
        strict=True,
        allow={"angle": ANGLES},
        extra={"rotation_axis": [[0.0, 0.0, 0.0], [1e200, 1e200, 0.0]], "translation": [[1e200, 0.0, 0.0]]},
    ),
    Case(
        cga.screw,
        fresh(axis=[0.0, 0.0, 1.0], point=[1.0, 2.0, 0.0], angle=1.0, distance=0.5),
        strict=True,
        extra={"axis": [[0.0, 0.0, 0.0]], "angle": [0.0, 1e-300]},
    ),
    Case(cga.reflect_in_plane, fresh(P=P, X=X), kinds={"P": [S, X, Z, L, M]}),
    Case(cga.invert_in_sphere, fresh(S=S, X=X), kinds={"S": [X, L, Z, M]}),
    # ---------------------------------------------------------------- versors_rigid.py
    Case(cga.rotor_angle_axis, fresh(R=R), kinds={"R": [X, S, VEC, P, D]}),
    Case(cga.decompose_motor, fresh(M=M), kinds={"M": NOT_MOTORS}),
    Case(cga.motor_to_matrix, fresh(M=M), kinds={"M": NOT_MOTORS}),
    Case(cga.matrix_to_motor, fresh(H=H), extra={"H": [SHEAR, np.diag([1.0, 1.0, -1.0, 1.0]), 2 * H]}),
    Case(cga.why_not_motor, fresh(M=M)),
    # ---------------------------------------------------------------- versor_log.py
    Case(cga.motor_log, fresh(M=M), kinds={"M": NOT_MOTORS + [2 * M]}),
    Case(cga.rotor_log, fresh(R=R), kinds={"R": NOT_ROTORS}),
    Case(cga.screw_parameters, fresh(M=SCREW), kinds={"M": NOT_MOTORS + [T]}),
    Case(
        cga.motor_interpolate,
        fresh(M0=M, M1=M1, s=0.5, shortest=True),
        strict=True,
        allow={"s": ANGLES},
        kinds={"M0": NOT_MOTORS, "M1": NOT_MOTORS},
    ),
    Case(cga.motor_interpolate, fresh(M0=M, M1=M1, s=[0.0, 0.5, 1.0]), name="motor_interpolate (batch)"),
    Case(cga.versor_sqrt, fresh(M=M), kinds={"M": NOT_MOTORS}),
    Case(cga.versor_root, fresh(M=M, n=3), strict=True, kinds={"M": NOT_MOTORS}),
    Case(
        cga.dilator,
        fresh(scale=2.0, center=[1.0, 1.0, 1.0]),
        strict=True,
        allow={"center": ("None",)},  # the documented default: the origin
        extra={"scale": [0.0, -1.0, 1e-320], "center": [[1e200, 0.0, 0.0]]},
    ),
    Case(cga.dilator, fresh(scale=2.0), name="dilator (at the origin)", strict=True),
    # ---------------------------------------------------------------- blades.py
    Case(
        cga.require_blade,
        fresh(A=L, func="require_blade", name="A", tol=1e-6),
        strict=True,
        kinds={"A": NOT_BLADES},
    ),
    Case(cga.left_contraction, fresh(A=cga.e1, B=cga.e1 ^ cga.e2), extra={"A": [HUGE], "B": [HUGE]}),
    Case(cga.right_contraction, fresh(A=cga.e1 ^ cga.e2, B=cga.e2), extra={"A": [HUGE], "B": [HUGE]}),
    Case(cga.scalar_product, fresh(A=X, B=cga.up([3.0, 4.0, 0.0])), extra={"A": [HUGE], "B": [HUGE]}),
    Case(cga.dual, fresh(A=cga.e1)),
    Case(cga.undual, fresh(A=cga.e1 ^ cga.e2)),
    Case(cga.regressive_product, fresh(A=P, B=S), extra={"A": [HUGE * cga.e3], "B": [HUGE * cga.e3]}),
    Case(cga.is_blade, fresh(A=L, tol=1e-6), strict=True),
    Case(cga.blade_factors, fresh(A=L, tol=1e-6), strict=True, kinds={"A": NOT_BLADES + [cga.G41.scalar(2.0)]}),
    Case(cga.join, fresh(A=L, B=L2, tol=1e-10), strict=True, kinds={"A": NOT_BLADES, "B": NOT_BLADES}),
    Case(cga.meet, fresh(A=L, B=P.dual(), tol=1e-10), strict=True, kinds={"A": NOT_BLADES, "B": NOT_BLADES}),
    Case(cga.project, fresh(A=cga.e1 + 2 * cga.e2 + 3 * cga.ep, B=cga.E), kinds={"A": NOT_BLADES, "B": [X]}),
    Case(cga.reject, fresh(A=cga.e1 + 2 * cga.e2 + 3 * cga.ep, B=cga.E), kinds={"A": NOT_BLADES, "B": [X]}),
    Case(cga.is_versor, fresh(V=T, tol=1e-9), strict=True),
    # ---------------------------------------------------------------- blades_classify.py
    Case(
        cga.BladeKind,
        fresh(kind="round", dimension=1, imaginary=False, grade=3, form="dual", radius2=1.0),
        strict=True,
        allow={"radius2": ("None",), "dimension": ("None",)},
    ),
    Case(cga.classify, fresh(X=Z, form="auto", tol=1e-10, tangent_tol=1e-12), strict=True, kinds={"X": NOT_BLADES}),
    Case(
        cga.intersect,
        fresh(X=S, Y=cga.sphere([1.0, 0.0, 0.0], 1.0), forms=("auto", "auto"), out="auto", tol=1e-10),
        strict=True,
        kinds={"X": NOT_BLADES, "Y": NOT_BLADES},
        extra={"forms": [("auto",), ("auto", 3), ["dual", "nonsense"]]},
    ),
    # ---------------------------------------------------------------- motor_estimation.py
    Case(cga.rotor_to_quaternion, fresh(R=R, scalar_first=True), strict=True, kinds={"R": NOT_ROTORS}),
    Case(
        cga.quaternion_to_rotor,
        fresh(q=[0.9, 0.0, 0.0, 0.1], scalar_first=True),
        strict=True,
        extra={"q": [[0.0, 0.0, 0.0, 0.0]]},
    ),
    Case(
        cga.motor_from_points,
        fresh(source=SRC, target=DST, weights=[1.0, 1.0, 2.0, 1.0]),
        extra={"source": [COLLINEAR, SRC[:2]], "target": [COLLINEAR], "weights": [[0.0] * 4, [-1.0, 1.0, 1.0, 1.0]]},
    ),
    Case(
        cga.motor_from_points,
        fresh(source=SRC[:, :2], target=DST[:, :2]),
        name="motor_from_points (planar)",
        extra={"source": [np.zeros((3, 2))]},
    ),
    Case(
        cga.motor_from_lines,
        fresh(
            source_lines=SRC_LINES,
            target_lines=DST_LINES,
            weights=[1.0, 1.0, 1.0],
            length_scale=1.0,
            max_iterations=5,
        ),
        strict=True,
        allow={"weights": ("None",)},
        kinds={"source_lines": [POINTS_NOT_LINES, S, Z], "target_lines": [POINTS_NOT_LINES, S, Z]},
        extra={"source_lines": [PARALLEL_LINES, [L]]},
    ),
    Case(
        cga.mean_motor,
        fresh(motors=[M, M1], weights=[1.0, 2.0]),
        allow={"weights": ("None",)},
        kinds={"motors": [[M, X], [X], X, [M, S], [M, D]]},
        extra={"motors": [[]]},
    ),
    # ---------------------------------------------------------------- object_motors.py
    Case(cga.motor_between, fresh(X=L, Y=L2), kinds={"X": [X, M], "Y": [X, M, Z, P]}),
    Case(
        cga.motor_between,
        fresh(X=Z, Y=cga.circle_from_points([1.0, 0.0, 5.0], [0.0, 1.0, 5.0], [-1.0, 0.0, 5.0])),
        name="motor_between (circles)",
        kinds={"Y": [L, S]},
    ),
    # ---------------------------------------------------------------- model.py (its constants as one result)
    Case(
        cga.ModelConstants,
        lambda: {f: getattr(cga.exact_constants(), f) for f in cga.ModelConstants.__dataclass_fields__},
        strict=True,
        extra={"einf": [Algebra(3).scalar(1.0)]},  # a multivector of another algebra
    ),
]

EXEMPT: dict[str, str] = {}
