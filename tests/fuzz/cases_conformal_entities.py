"""Fuzz cases of the conformal model, entities and fits (cga_lessons.conformal: model, entities, fitting).

Every reader of one kind of entity (a line, a plane, a circle, a sphere, a point pair, a point) is given the other
kinds, in both forms (``kinds``): each must be refused.  A point is a sphere of radius zero (2.72), so the sphere
readers are not given points.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector
from fuzz.harness import Case

A, B, C, D = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]

POINT = cga.up([1.0, 2.0, 3.0])
SPHERE = cga.sphere([0.0, 0.0, 0.0], 1.0)
PLANE = cga.plane([0.0, 0.0, 1.0], 1.0)
LINE = cga.line_from_points(A, B)
CIRCLE = cga.circle_from_points(A, B, C)
PAIR = cga.point_pair(A, B)
FLAT_POINT = cga.up([1.0, 2.0, 3.0]) ^ cga.einf

ENTITIES = {
    "point": [POINT],
    "sphere": [SPHERE, cga.dual_form(SPHERE)],
    "plane": [PLANE, cga.dual_form(PLANE)],
    "line": [LINE, cga.standard_form(LINE)],
    "circle": [CIRCLE, cga.standard_form(CIRCLE)],
    "pair": [PAIR, cga.standard_form(PAIR)],
    "flat point": [FLAT_POINT, cga.standard_form(FLAT_POINT)],
}


# Blades whose numbers are finite but whose reading overflows (a centre of 1e300 / 1e-10).
HUGE_SPHERE = Multivector(cga.G41, {1: 1e300, 8: -1e-10, 16: 1e-10})
HUGE_PAIR = Multivector(cga.G41, {3: 1e300, 9: 0.5, 17: -0.5, 24: -0.5})
HUGE_CIRCLE = Multivector(cga.G41, {7: 1e300, 19: 1.0, 21: -1.0, 22: 1.0})
HUGE_LINE = Multivector(cga.G41, {11: 1e300, 19: 1e300, 25: 1e-300})


def fresh(**args):
    """The arguments of a valid call, handed over as they are: the harness deep-copies a plain dict, and a deep
    copy of a multivector carries a copy of G(4,1) that no other multivector can be combined with."""
    return lambda: dict(args)


def others(*kinds: str) -> list:
    """The entities of every kind but ``kinds``, in both forms."""
    return [X for k, Xs in ENTITIES.items() if k not in kinds for X in Xs]


# A tiny cloud on two planes (floor z = 0 and wall y = 2), for the RANSAC segmentation.
_g = np.linspace(0.0, 1.0, 4)
FLOOR = np.array([[x, y, 0.0] for x in _g for y in _g])
WALL = np.array([[x, 2.0, z] for x in _g for z in _g])
CLOUD = np.vstack([FLOOR, WALL])

SPHERE_PTS = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1.0]])
CIRCLE_PTS = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0.6, 0.8, 0]])
PLANE_PTS = np.array([[0.0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1.0]])  # on a plane, and on a circle
FLAT_PTS = np.array([[0.0, 0, 1], [1, 0, 1], [0, 1, 1], [2, 3, 1], [5, 1, 1.0]])  # on a plane, no circle
SAME_PTS = np.zeros((5, 3))
LINE_PTS = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [4, 0, 0]])

def _fields(fit) -> dict:
    """A fit's result as keyword arguments of its class."""
    return {k: getattr(fit, k) for k in type(fit).__dataclass_fields__}


CASES = [
    # ---------------------------------------------------------------- model
    Case(cga.up, {"x": [1.0, 2.0, 3.0]}, extra={"x": [[1e200, 0.0, 0.0], [1.0 + 1j, 2.0, 3.0], [10**400, 0, 0]]}),
    Case(cga.up, {"x": np.array([[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]])}, name="up (batch)"),
    Case(cga.vector, {"x": [1.0, 2.0, 3.0]}),
    Case(
        cga.down,
        fresh(X=POINT),
        kinds={"X": others("point")},
        extra={"X": [cga.einf, 0 * POINT, 1e-200 * SPHERE, cga.up([1e8, 0.0, 0.0])]},
    ),
    Case(
        cga.down,
        fresh(X=cga.up(np.eye(3))),
        name="down (batch)",
        kinds={"X": [cga.sphere(np.eye(3), 1.0), cga.sphere(np.eye(3), np.array([0.0, 0.0, 1.0]))]},
        extra={"X": [cga.up(np.eye(3)) + cga.e1 * cga.e2 * np.ones(3), cga.einf * np.ones(3)]},
    ),
    Case(cga.euclidean, fresh(X=POINT)),
    Case(cga.normalize_point, fresh(X=2.0 * POINT), kinds={"X": others("point", "sphere")}),
    Case(cga.point_weight, fresh(X=2.0 * POINT), kinds={"X": others("point", "sphere", "plane")}),
    Case(cga.exact_constants, {}),
    # ------------------------------------------------------------ point pairs
    Case(cga.point_pair, {"a": A, "b": B}, extra={"b": [A, [1.0 + 1e-15, 0.0, 0.0]]}),
    Case(
        cga.point_pair_endpoints,
        fresh(PP=PAIR, min_separation=1e-9),
        kinds={"PP": others("pair")},
        extra={"PP": [cga.point_pair([1e7, 0, 0], [1e7, 1e-3, 0]), HUGE_PAIR], "min_separation": [2.0, -1.0]},
        allow={"min_separation": ["None"]},  # None: the default guard
        strict=True,
    ),
    Case(cga.point_pair_sphere, fresh(PP=PAIR), kinds={"PP": others("pair")}, extra={"PP": [HUGE_PAIR]}),
    # --------------------------------------------------------------- spheres
    Case(
        cga.sphere,
        {"center": [1.0, 2.0, 3.0], "radius": 2.0},
        strict=True,
        extra={"radius": [-1.0, 1e200, [1.0, -2.0], [[1.0]]]},
        allow={"radius": ["[1.0, 2.0]"]},  # several radii about one centre: a batch of concentric spheres
    ),
    Case(
        cga.sphere,
        {"center": np.array([[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]]), "radius": np.array([1.0, 2.0])},
        name="sphere (batch)",
        extra={"radius": [[1.0, 2.0, 3.0]]},
    ),
    Case(cga.sphere_from_points, {"a": A, "b": B, "c": C, "d": D}, extra={"d": [A, [1.0, 1.0, -1.0]]}),
    Case(
        cga.sphere_center_radius,
        fresh(S=SPHERE),
        kinds={"S": others("sphere", "point")},
        extra={"S": [SPHERE + 2 * cga.einf, 1e150 * SPHERE, HUGE_SPHERE]},
    ),
    Case(
        cga.point_sphere_side,
        fresh(x=[0.5, 0.0, 0.0], S=SPHERE, atol=1e-9),
        kinds={"S": others("sphere", "point"), "x": others("point")},
        extra={"x": [[1e200, 0.0, 0.0]], "S": [1e150 * SPHERE, HUGE_SPHERE], "atol": [-1.0]},
        strict=True,
    ),
    # ---------------------------------------------------------------- planes
    Case(
        cga.plane,
        {"normal": [0.0, 0.0, 1.0], "distance": 1.0},
        extra={"normal": [[0.0, 0.0, 0.0]], "distance": [[[1.0]]]},
        allow={"distance": ["[1.0, 2.0]"]},  # several distances along one normal: a batch of parallel planes
        strict=True,
    ),
    Case(cga.plane_from_points, {"a": A, "b": B, "c": C}, extra={"c": [A, [2.0, -1.0, 0.0], [1e200, 0.0, 0.0]]}),
    Case(cga.plane_normal_distance, fresh(P=PLANE), kinds={"P": others("plane")}, extra={"P": [0 * PLANE]}),
    # ----------------------------------------------------------------- lines
    Case(cga.line_from_points, {"a": A, "b": B}, extra={"b": [A, [1e200, 0.0, 0.0]]}),
    Case(cga.normalize_line, fresh(L=LINE), kinds={"L": others("line")}, extra={"L": [HUGE_LINE]}),
    Case(cga.line_direction, fresh(L=LINE), kinds={"L": others("line")}, extra={"L": [HUGE_LINE]}),
    Case(cga.line_moment, fresh(L=LINE), kinds={"L": others("line")}, extra={"L": [HUGE_LINE]}),
    Case(cga.line_closest_point, fresh(L=LINE), kinds={"L": others("line")}, extra={"L": [HUGE_LINE]}),
    Case(
        cga.point_line_distance,
        fresh(x=[0.0, 0.0, 1.0], L=LINE),
        kinds={"L": others("line"), "x": others("point")},
        extra={"x": [[1e200, 0.0, 0.0]], "L": [HUGE_LINE]},
    ),
    # --------------------------------------------------------------- circles
    Case(
        cga.circle_from_points,
        {"a": A, "b": B, "c": C},
        extra={"c": [A, [2.0, -1.0, 0.0], [1e200, 0.0, 0.0]], "b": [[1e100, 0.0, 0.0]]},
    ),
    Case(cga.circle_center_radius, fresh(Z=CIRCLE), kinds={"Z": others("circle")}, extra={"Z": [HUGE_CIRCLE]}),
    Case(cga.circle_plane, fresh(Z=CIRCLE), kinds={"Z": others("circle")}, extra={"Z": [HUGE_CIRCLE]}),
    # ----------------------------------------------------------------- forms
    Case(cga.standard_form, fresh(X=CIRCLE)),
    Case(cga.dual_form, fresh(X=CIRCLE)),
    # ------------------------------------------------------------------ fits
    Case(cga.fit_sphere, {"X": SPHERE_PTS}, extra={"X": [SAME_PTS, PLANE_PTS, FLAT_PTS, LINE_PTS]}),
    Case(cga.fit_sphere_kasa, {"X": SPHERE_PTS}, extra={"X": [SAME_PTS, PLANE_PTS, FLAT_PTS, LINE_PTS]}),
    Case(
        cga.fit_sphere_geometric,
        {"X": SPHERE_PTS, "init": {"center": [0.1, 0.0, 0.0], "radius": 1.0}, "iterations": 20},
        extra={
            "X": [SAME_PTS, PLANE_PTS, FLAT_PTS, LINE_PTS],
            "init": [
                {"center": [np.nan, 0, 0], "radius": 1.0},
                {"center": [0, 0, 0]},
                {"center": [0, 0], "radius": 1},
                {"center": [0, 0, 0], "radius": -1.0},
            ],
        },
        allow={"init": ["None"]},  # None: start from Kasa's fit
        strict=True,
    ),
    Case(cga.fit_plane, {"X": PLANE_PTS}, extra={"X": [SAME_PTS, LINE_PTS]}),
    Case(cga.fit_plane_euclidean, {"X": PLANE_PTS}, extra={"X": [SAME_PTS, LINE_PTS]}),
    Case(cga.fit_circle, {"X": CIRCLE_PTS}, extra={"X": [SAME_PTS, LINE_PTS]}),
    Case(
        cga.fit_circle_euclidean,
        {"X": CIRCLE_PTS, "iterations": 20},
        extra={"X": [SAME_PTS, LINE_PTS]},
        strict=True,
    ),
    Case(
        cga.segment_planes,
        lambda: {
            "X": CLOUD,
            "rng": np.random.default_rng(0),
            "n_planes": 2,
            "threshold": 0.01,
            "iterations": 20,
            "min_inliers": 5,
        },
        extra={"X": [SAME_PTS, LINE_PTS], "threshold": [0.0]},
        strict=True,
    ),
    # the fits' results, as the fits build them
    Case(cga.SphereFit, lambda: _fields(cga.fit_sphere(SPHERE_PTS)), strict=True),
    Case(cga.PlaneFit, lambda: _fields(cga.fit_plane(PLANE_PTS)), strict=True),
    Case(cga.CircleFit, lambda: _fields(cga.fit_circle(CIRCLE_PTS)), strict=True),
    # the least-squares line
    Case(cga.fit_line, {"X": np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 0.5], [2.0, 2.1, 1.0], [3.0, 2.9, 1.5]])},
         extra={"X": [np.ones((4, 3)), np.ones((1, 3))]}),
    Case(cga.LineFit, lambda: _fields(cga.fit_line(np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 0.5], [2.0, 2.1, 1.0]]))),
         strict=True, kinds={"blade": [SPHERE, POINT, PAIR], "pair": [SPHERE, LINE]}),
    # an entity's Euclidean parameters
    Case(
        cga.PlaneParameters,
        {"normal": [0.0, 0.0, 1.0], "distance": 1.0, "center": [0.1, 0.2, 1.0]},
        strict=True,
        allow={"center": ["None"]},
    ),
    Case(cga.SphereParameters, {"center": [0.0, 0.0, 2.0], "radius": 0.25}, strict=True, extra={"radius": [-0.1]}),
    Case(cga.CircleParameters, {"center": [0.0, 0.0, 2.0], "radius": 0.2, "normal": [0.0, 1.0, 0.0]}, strict=True),
    Case(
        cga.LineParameters,
        {"direction": [1.0, 0.0, 0.0], "point": [0.0, 0.0, 2.0], "length": 0.5},
        strict=True,
        allow={"length": ["None"]},
        extra={"length": [-0.5]},
    ),
]

EXEMPT: dict[str, str] = {}
