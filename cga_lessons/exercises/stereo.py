"""Exercises of appendix A (notebook 07): camera centres, epipoles, and the 8-point algorithm on a plane.

The inputs come from :func:`cga_lessons.exercises.given` (cameras whose construction the notebook does not
show); the truths are the construction itself: the centre the camera was built from, the projection of one
centre into the other camera, and the rank of a matrix built here with NumPy.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.stereo import rotation_matrix  # Rodrigues in plain NumPy: independent of the algebra

from .answers import Wrong, as_float
from .checking import exercise
from .compare import compare_number, compare_vector

_K = np.array([[700.0, 0.0, 320.0], [0.0, 700.0, 240.0], [0.0, 0.0, 1.0]])


def _camera(R, C) -> np.ndarray:
    """P = K R [I | -C], Eq. (A.1)."""
    return _K @ R @ np.hstack([np.eye(3), -np.asarray(C, float)[:, None]])


# chA.1: one camera, turned and moved
_R_A1 = rotation_matrix([0.2, 1.0, 0.1], 0.4)
_C_A1 = np.array([0.5, -0.2, -2.0])

# chA.2, chA.3: a verging pair, the second camera 0.3 m to the right and turned 0.15 rad toward the first
_R2 = rotation_matrix([0.0, 1.0, 0.0], -0.15)
_C2 = np.array([0.3, 0.0, 0.05])
_P1 = _camera(np.eye(3), np.zeros(3))
_P2 = _camera(_R2, _C2)


def _dehomogenise(P, X) -> np.ndarray:
    x = P @ np.append(X, 1.0)
    return x[:2] / x[2]


def _given_a1():
    """The camera matrix of exercise chA.1, shape (3, 4)."""
    return _camera(_R_A1, _C_A1)


@exercise(
    "chA.1",
    title="the centre C of the camera P = exercises.given('chA.1'): P C = 0, Eqs. (A.1), (A.3)",
    notebook="07_stereo_reconstruction",
    kind="compute",
    expects="a NumPy array of shape (3,) (or the homogeneous 4-vector, any scale)",
    equations=("A.1", "A.3"),
    given=_given_a1,
)
def _chA_1(answer):
    v = np.asarray(answer, dtype=float) if not isinstance(answer, (str, bytes)) else answer
    if isinstance(v, np.ndarray) and v.shape == (4,):
        if abs(v[3]) < 1e-12 * max(np.abs(v).max(), 1e-300):
            raise Wrong("your homogeneous vector has W = 0: a point at infinity. A finite camera has a finite centre.")
        answer = v[:3] / v[3]
    t = -_R_A1 @ _C_A1
    compare_vector(
        answer,
        _C_A1,
        hints=[
            (t, "that is t = -R C, the last column of [R | t] (A.3), not the centre."),
            (-t, "that is -t = R C, the centre turned by the rotation; undo the rotation."),
        ],
    )
    return "The centre is the null vector of P: every image point's ray passes through it."


def _given_a2():
    """The fundamental matrix of exercise chA.2, shape (3, 3), scaled to unit Frobenius norm."""
    e2 = _P2 @ np.array([0.0, 0.0, 0.0, 1.0])  # the first centre seen by the second camera
    ex = np.array([[0, -e2[2], e2[1]], [e2[2], 0, -e2[0]], [-e2[1], e2[0], 0]])
    F = ex @ _P2 @ np.linalg.pinv(_P1)
    return F / np.linalg.norm(F)


@exercise(
    "chA.2",
    title="the epipole e' in the second image of F = exercises.given('chA.2'): F^T e' = 0",
    notebook="07_stereo_reconstruction",
    kind="compute",
    expects="a NumPy array of shape (2,) in pixels (or the homogeneous 3-vector, any scale)",
    equations=("A.6", "A.11"),
    given=_given_a2,
)
def _chA_2(answer):
    v = np.asarray(answer, dtype=float) if not isinstance(answer, (str, bytes)) else answer
    if isinstance(v, np.ndarray) and v.shape == (3,):
        if abs(v[2]) < 1e-12 * max(np.abs(v).max(), 1e-300):
            raise Wrong("your epipole is at infinity (third coordinate 0); for these verging cameras it is finite.")
        answer = v[:2] / v[2]
    truth = _dehomogenise(_P2, np.zeros(3))  # e' = P' C: the first camera's centre in the second image
    e1 = _dehomogenise(_P1, _C2)
    compare_vector(
        answer,
        truth,
        rtol=1e-6,
        atol=1e-6,
        hints=[(e1, "that is the epipole of the first image (F e = 0). e' is the left null vector: F^T e' = 0.")],
    )
    return (
        "e' is where the second camera sees the first camera's centre; "
        "every epipolar line of image 2 passes through it."
    )


def _plane_points():
    rng = np.random.default_rng(11)
    u, v = rng.uniform(-0.6, 0.6, 8), rng.uniform(-0.4, 0.4, 8)
    # eight points on the plane z = 2.5 + 0.3 x (a tilted board in front of both cameras)
    return np.column_stack([u, v, 2.5 + 0.3 * u])


def _given_a3():
    """Eight correspondences (x1, x2), shape (8, 2) each, of points on one plane, seen by the chA.2 cameras."""
    X = _plane_points()
    x1 = np.array([_dehomogenise(_P1, p) for p in X])
    x2 = np.array([_dehomogenise(_P2, p) for p in X])
    return x1, x2


def _null_space_dimension() -> int:
    x1, x2 = _given_a3()
    # normalised image coordinates (K^-1 x) keep the matrix well conditioned
    h1 = np.column_stack([x1, np.ones(8)]) @ np.linalg.inv(_K).T
    h2 = np.column_stack([x2, np.ones(8)]) @ np.linalg.inv(_K).T
    Z = np.array([np.kron(b, a) for a, b in zip(h1, h2)])  # row: x'^T F x = kron(x', x) . vec(F)
    s = np.linalg.svd(Z, compute_uv=False)
    s = np.concatenate([s, np.zeros(9 - len(s))])
    return int(np.sum(s < 1e-10 * s[0]))


@exercise(
    "chA.3",
    title="the dimension of the null space of Z (A.9) for eight points on one plane: exercises.given('chA.3')",
    notebook="07_stereo_reconstruction",
    kind="break",
    expects="an int",
    equations=("A.7", "A.8", "A.9"),
    given=_given_a3,
)
def _chA_3(answer):
    value = as_float(answer)
    if value != int(value):
        raise Wrong("a dimension is a whole number.")
    truth = _null_space_dimension()
    compare_number(
        value,
        truth,
        hints=[
            (
                1,
                "one is what eight points in general position give. Count the singular values of Z that are zero "
                "to round-off (relative to the largest), not just the last one.",
            ),
            (
                truth - 1,
                "close: np.linalg.svd of the 8 x 9 matrix Z returns only 8 singular values, and the 9th "
                "column adds one more null direction than the zero singular values you counted.",
            ),
            (9 - truth, "that is the rank of Z; the null space is what is left of the 9 unknowns."),
            (9, "that is the number of unknowns in f, not the dimension of the null space."),
            (8, "that is the number of equations (rows of Z)."),
        ],
    )
    return "Points on a plane fix F only up to a 3-parameter family F = [v]x H: the 8-point algorithm needs depth."
