"""motor_between: the versor taking one object onto another, against objects moved by known motors."""

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.conformal.object_motors import motor_between


def _unit(X):
    return X * (1.0 / np.sqrt(abs(float((X * X).scalar()))))


def _same_object(A, B, tol=1e-8):
    """A and B are the same object up to a scale of either sign."""
    a, b = _unit(A), _unit(B)
    return min(max((abs(float(v)) for v in (a - s * b).coeffs.values()), default=0.0) for s in (1.0, -1.0)) < tol


KINDS = {
    "line": lambda a, b, c: cga.line_from_points(a, b),
    "plane": lambda a, b, c: cga.plane_from_points(a, b, c),
    "sphere": lambda a, b, c: cga.sphere(a, 1.5),
    "circle": lambda a, b, c: cga.circle_from_points(a, b, c),
    "point pair": lambda a, b, c: cga.point_pair(a, b),
}


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_the_versor_takes_x_onto_its_moved_copy_and_is_rigid(kind):
    rng = np.random.default_rng(abs(hash(kind)) % 2**32)
    probe = rng.normal(size=(6, 3))
    for _ in range(40):
        M = cga.motor(rng.normal(size=3), rng.uniform(-3, 3), rng.normal(scale=3.0, size=3))
        X = KINDS[kind](*rng.normal(size=(3, 3)))
        Y = cga.apply(M, X)
        V = motor_between(X, Y)
        assert _same_object(cga.apply(V, X), Y)
        assert abs(float((V * ~V).scalar()) - 1.0) < 1e-9
        moved = cga.apply_to_points(V, probe)  # equal sizes: a rigid motion, distances kept
        d0 = np.linalg.norm(probe[:, None] - probe[None], axis=-1)
        d1 = np.linalg.norm(moved[:, None] - moved[None], axis=-1)
        np.testing.assert_allclose(d1, d0, atol=1e-8)


def test_between_two_skew_lines_is_the_screw_along_their_common_perpendicular():
    """x axis onto the line along y at height 1: a quarter turn about z with a 1 m slide along it, (2.110)."""
    L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])
    L2 = cga.line_from_points([0, 0, 1], [0, 1, 1])
    V = motor_between(L1, L2)
    expected = cga.motor([0, 0, 1], np.pi / 2, [0, 0, 1])
    assert V.isclose(expected) or V.isclose(-expected)


def test_rounds_of_different_radii_have_no_rigid_motion_between_them():
    with pytest.raises(DegenerateGeometryError, match="motor_between: Y: radius"):
        motor_between(cga.sphere([0, 0, 0], 1.0), cga.sphere([3, 0, 0], 2.0))
    pts = np.array([[1.0, 0, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(DegenerateGeometryError, match="motor_between: Y: radius"):
        motor_between(cga.circle_from_points(*pts), cga.circle_from_points(*(2 * pts)))


def test_equal_spheres_are_translated_centre_to_centre():
    V = motor_between(cga.sphere([1, 2, 3], 1.5), cga.sphere([4, 0, -1], 1.5))
    np.testing.assert_allclose(cga.apply_to_points(V, [1.0, 2.0, 3.0]), [4.0, 0.0, -1.0], atol=1e-12)


def test_bad_input_names_the_function_and_the_argument():
    L = cga.line_from_points([0, 0, 0], [1, 0, 0])
    with pytest.raises(InvalidInputError, match="motor_between: X: expected an object"):
        motor_between(np.zeros(3), L)
    with pytest.raises(InvalidInputError, match="motor_between: Y: grade"):
        motor_between(L, cga.plane([0, 0, 1], 0.0))
    with pytest.raises(DegenerateGeometryError, match="motor_between: X: a null object"):
        motor_between(cga.up([1.0, 2.0, 3.0]), cga.up([0.0, 0.0, 0.0]))
    with pytest.raises(InvalidInputError, match="motor_between: Y: X squares to"):
        motor_between(cga.sphere([0, 0, 0], 1.0), cga.sphere([0, 0, 0], 1.0) + cga.einf * 1.0)  # imaginary
    with pytest.raises(InvalidInputError, match="motor_between: Y: a"):
        motor_between(L, cga.circle_from_points([1, 0, 0], [0, 1, 0], [0, 0, 1]))
    with pytest.raises(InvalidInputError, match="motor_between: X: contains NaN or inf"):
        motor_between(cga.Multivector(cga.G41, {b: float("nan") for b in L.coeffs}), L)
    with pytest.raises(InvalidInputError, match="not a blade"):
        motor_between(L + cga.line_from_points([0, 0, 1], [0, 1, 1]), L)
