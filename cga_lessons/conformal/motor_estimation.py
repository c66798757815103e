"""Motors from data: least-squares motors from points (from lines: :mod:`cga_lessons.conformal.motor_lines`),
averages of motors, quaternions.

The rotor part is found the way Valkenburg and Dorst do it in CGA [VD11]: the cost is a quadratic form in the
rotor's four coefficients ``r = (r0, r1, r2, r3)`` of ``R = r0 + r1 e23 + r2 e31 + r3 e12`` (the even subalgebra
of G3 inside G(4,1), rotors of table 2.2, Eqs. 2.94-2.96), the constraint ``R ~R = 1`` is ``|r| = 1``, so the best
rotor is an extreme eigenvector of a 4x4 symmetric matrix (an "eigenrotor"); the translation follows in closed
form (Eqs. 2.100-2.103: ``M = T R``).  The symmetric matrix is built with geometric products: its entries are
``sum_i w_i <b_i E_j a_i ~E_k>_0`` over the rotor basis ``E = (1, e23, e31, e12)``, linear in the cross-covariance
``S = sum_i w_i a_i b_i^T``, so the algebra supplies 144 structure constants once and the data a 3x3 matrix.

Quaternions (:func:`rotor_to_quaternion`): Hamilton's, active, ``q = (w, x, y, z)`` scalar first by default
(``scalar_first=False`` gives SciPy's ``(x, y, z, w)``).  With ``R = cos(theta/2) - sin(theta/2) n I_E`` of
:func:`~cga_lessons.conformal.versors_build.rotor` and ``n I_E = n1 e23 + n2 e31 + n3 e12`` (2.96)::

    w = <R>_0,   x = -<R>_e23,   y = -<R>_e31,   z = -<R>_e12       (i = e32, j = e13, k = e21)

so ``q = cos(theta/2) + sin(theta/2) (n1 i + n2 j + n3 k)``; q and -q (R and -R) are the same rotation.

References
----------
[VD11] R. Valkenburg, L. Dorst, "Estimating motors from a variety of geometric data in 3D conformal geometric
       algebra", in *Guide to Geometric Algebra in Practice*, Springer 2011, ch. 2.
[Ho87] B. K. P. Horn, "Closed-form solution of absolute orientation using unit quaternions", JOSA A 4(4), 1987.
[Ma07] F. L. Markley, Y. Cheng, J. L. Crassidis, Y. Oshman, "Averaging quaternions", J. Guidance, Control and
       Dynamics 30(4), 2007.
[HT13] R. Hartley, J. Trumpf, Y. Dai, H. Li, "Rotation averaging", IJCV 103, 2013 (the chordal L2 mean).
"""

from __future__ import annotations

from functools import lru_cache
from itertools import product

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector

from .model import G41, e1, e2, e3
from .multivector_checks import multivector
from .versors import apply_to_points
from .versors_build import translator
from .versors_rigid import decompose_motor, why_not_motor

__all__ = ["rotor_to_quaternion", "quaternion_to_rotor", "motor_from_points", "mean_motor"]

_BASIS = (e1 * e1, e2 * e3, e3 * e1, e1 * e2)  # 1, e23, e31, e12
_BLADES = tuple(next(iter(B.coeffs.items())) for B in _BASIS)  # (bitmap, sign) of each rotor basis element
_QSIGN = np.array([1.0, -1.0, -1.0, -1.0])  # q = r * _QSIGN, r = q * _QSIGN


# ------------------------------------------------------------------ helpers
def rotor_from_coeffs(r: np.ndarray) -> Multivector:
    """``r0 + r1 e23 + r2 e31 + r3 e12`` from an array (4,) or (N, 4)."""
    if r.ndim == 1:
        return Multivector(G41, {b: s * float(v) for (b, s), v in zip(_BLADES, r) if v != 0})
    return Multivector(G41, {b: s * r[:, k].copy() for k, (b, s) in enumerate(_BLADES)})


def _rotor_coeffs(R, func: str, name: str = "R") -> np.ndarray:
    """The coefficients r (4,) or (N, 4) of a numeric rotor; other blades must vanish."""
    multivector(R, func, name, what="a rotor (Multivector of G(4,1))", numeric=True, nonzero=False)
    vals = {b: np.asarray(v, dtype=float) for b, v in R.coeffs.items()}
    scale = max((float(np.abs(v).max()) for v in vals.values() if v.size), default=0.0)
    known = {b for b, _ in _BLADES}
    bad = [G41.blade_names[b] for b, v in vals.items() if b not in known and np.abs(v).max() > 1e-9 * scale]
    if bad:
        raise InvalidInputError(f"{func}: {name}: a rotor has blades 1, e23, e31, e12 only, got also {bad}")
    shape = R.shape
    return np.stack([s * np.broadcast_to(vals.get(b, 0.0), shape) for b, s in _BLADES], axis=-1)


def pair_weights(weights, n: int, func: str) -> np.ndarray:
    """n finite, non-negative weights, not all zero (``checks.array``); None: all ones."""
    if weights is None:
        return np.ones(n)
    w = checks.array(weights, func, "weights", (None,))
    if w.shape != (n,):
        raise checks.fail(func, "weights", f"shape {w.shape} does not match the {n} data")
    if np.any(w < 0):
        raise InvalidInputError(f"{func}: weights: negative weight")
    if not np.any(w > 0):
        raise InvalidInputError(f"{func}: weights: all weights are zero")
    return w


@lru_cache(maxsize=1)
def _structure() -> np.ndarray:
    """T[p, q, j, k] = <e_q E_j e_p ~E_k>_0: the rotor matrix is sum_pq S_pq T[p, q] (Horn's matrix)."""
    ev, T = (e1, e2, e3), np.zeros((3, 3, 4, 4))
    for p, q, j, k in product(range(3), range(3), range(4), range(4)):
        T[p, q, j, k] = float((ev[q] * _BASIS[j] * ev[p] * ~_BASIS[k]).scalar())
    return T


def rotor_matrix(S: np.ndarray) -> np.ndarray:
    """N with r^T N r = sum_i w_i <b_i R a_i ~R>_0 for S = sum_i w_i a_i b_i^T (symmetric 4x4)."""
    N = np.einsum("pq,pqjk->jk", S, _structure())
    return 0.5 * (N + N.T)


def top_eigenvector(N: np.ndarray, func: str, name: str, why: str) -> np.ndarray:
    if not np.all(np.isfinite(N)):
        raise checks.fail(func, name, "the data's magnitudes are too large: their products overflow a float")
    vals, vecs = np.linalg.eigh(N)
    if vals[-1] - vals[-2] <= 1e-12 * max(float(np.abs(vals).max()), 1e-300):
        raise checks.degenerate(func, name, why)
    r = vecs[:, -1]
    return -r if r[0] < 0 else r


def _spread_checks(X: np.ndarray, w: np.ndarray, func: str, name: str, collinear: bool):
    """Centre X (N, 3) with weights w; raise on coincident (or collinear) data.  Returns (centroid, centred)."""
    x0 = X[int(np.argmax(w > 0))]
    D = X - x0  # shift first: the centroid is then accurate to the spread, not to |x|
    mean = w @ D / w.sum()
    A = D - mean
    sv = np.linalg.svd(np.sqrt(w)[:, None] * A, compute_uv=False)
    if sv[0] / np.sqrt(w.sum()) <= 1e-12 * max(1.0, float(np.abs(X).max())):
        raise DegenerateGeometryError(f"{func}: {name}: the points coincide")
    if collinear and sv[1] <= 1e-10 * sv[0]:
        raise DegenerateGeometryError(f"{func}: {name}: the points are collinear (rotation about the line unknown)")
    return x0 + mean, A


def _points(x, func: str, name: str) -> np.ndarray:
    arr = checks.array(x, func, name, (None, None))
    if arr.shape[1] not in (2, 3):
        raise checks.fail(func, name, f"must have shape (N, 3) or (N, 2), got {arr.shape}")
    return arr


# -------------------------------------------------------------- quaternions
def rotor_to_quaternion(R: Multivector, *, scalar_first: bool = True) -> np.ndarray:
    """Unit quaternion of a rotor (or of a batch of rotors); convention in the module docstring.

    ``(w, x, y, z) = (<R>_0, -<R>_e23, -<R>_e31, -<R>_e12) / |R|`` for the rotor
    ``R = cos(theta/2) - sin(theta/2) n I_E`` of Eqs. (2.94)-(2.96), so ``q = cos(theta/2) + sin(theta/2) n``
    (Hamilton, active, the same rotation matrix as SciPy's ``Rotation.from_quat``).  ``scalar_first=False``
    returns SciPy's order ``(x, y, z, w)``.  R is scaled to unit norm; its sign is kept (q and -q are the same
    rotation).  A motor has other blades: take its rotor part with
    :func:`~cga_lessons.conformal.versors_rigid.decompose_motor`.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> np.round(rotor_to_quaternion(cga.rotor([0, 0, 1], np.pi / 2)), 4)
    array([0.7071, 0.    , 0.    , 0.7071])
    >>> np.round(rotor_to_quaternion(cga.rotor([0, 0, 1], np.pi / 2), scalar_first=False), 4)
    array([0.    , 0.    , 0.7071, 0.7071])
    """
    r = _rotor_coeffs(R, "rotor_to_quaternion")
    scalar_first = checks.flag(scalar_first, "rotor_to_quaternion", "scalar_first")
    norm = np.linalg.norm(r, axis=-1, keepdims=True)
    if np.any(norm <= 1e-300):
        raise DegenerateGeometryError("rotor_to_quaternion: R: the zero rotor has no rotation")
    q = r / norm * _QSIGN + 0.0  # + 0.0: no negative zeros
    return q if scalar_first else np.roll(q, -1, axis=-1)


def quaternion_to_rotor(q, *, scalar_first: bool = True) -> Multivector:
    """Rotor of a quaternion (w, x, y, z) (or (x, y, z, w) with ``scalar_first=False``), inverse of
    :func:`rotor_to_quaternion`: ``R = w - x e23 - y e31 - z e12`` after scaling q to unit norm.

    ``q`` has shape (4,) or (N, 4) (a batch of rotors).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> R = quaternion_to_rotor([np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)])  # +90 degrees about z
    >>> np.round(cga.apply_to_points(R, [1.0, 0.0, 0.0]), 12) + 0.0
    array([0., 1., 0.])
    """
    arr, single = checks.batch(q, "quaternion_to_rotor", "q", (4,), at_least=1)
    arr = arr[0] if single else arr
    scalar_first = checks.flag(scalar_first, "quaternion_to_rotor", "scalar_first")
    norm = np.linalg.norm(arr, axis=-1, keepdims=True)
    if np.any(norm <= 1e-300):
        raise DegenerateGeometryError("quaternion_to_rotor: q: the zero quaternion is not a rotation")
    arr = arr / norm
    if not scalar_first:
        arr = np.roll(arr, 1, axis=-1)
    return rotor_from_coeffs(arr * _QSIGN)


# ------------------------------------------------------------------- points
def motor_from_points(source, target, weights=None) -> Multivector:
    """Least-squares motor of corresponding points, min over M of ``sum_i w_i |M x_i ~M - y_i|^2`` [VD11].

    ``source`` and ``target`` are (N, 3) arrays (N >= 3, not collinear), or (N, 2) planar points (N >= 2, not
    coincident), for which the motion is sought in the plane z = 0 (a rotation about e3, a translation in the
    plane: the laser scans of chapter 3).  Returns the unit motor ``M = T R`` (2.102) with ``y ~ M x ~M``.

    Derivation.  For conformal points (2.62) ``-2 X . Y = |x - y|^2``, so the cost is
    ``-2 sum_i w_i (M X_i ~M) . Y_i``, quadratic in M [VD11].  With ``M = T R`` and
    ``T = 1 + e t / 2`` (2.100) the minimum over t for a fixed R is ``t = ybar - R xbar ~R`` with the weighted
    centroids xbar, ybar (the Schur complement of [VD11] for points); what remains, with the centred points
    ``a_i = x_i - xbar`` and ``b_i = y_i - ybar``, is

        sum_i w_i |R a_i ~R - b_i|^2 = sum_i w_i (|a_i|^2 + |b_i|^2) - 2 r^T N r,
        N_jk = sum_i w_i <b_i E_j a_i ~E_k>_0,   E = (1, e23, e31, e12),

    so r is the eigenvector of the largest eigenvalue of the symmetric 4x4 N (Horn's matrix [Ho87], here from
    geometric products).  It is unique when the top eigenvalue is simple: for non-collinear source and target,
    except for reflection-like data (``det S < 0`` with a double singular value); the result is a proper
    rotation (never a reflection).  In the plane only ``r0`` and ``r3``
    (the e12 part) vary, and the 2x2 block of N gives the angle ``atan2(sum w (a x b)_z, sum w a . b)``.
    Centring first makes the accuracy depend on the spread of the points, not on their distance to the origin.

    Raises :class:`~cga_lessons.algebra.InvalidInputError` (shapes, NaN/inf, negative or all-zero weights) or
    :class:`~cga_lessons.algebra.DegenerateGeometryError` (too few, coincident or collinear points), with a
    message ``"motor_from_points: source: <problem>"`` (or ``target:``, ``weights:``).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> x = np.array([[0.0, 0, 0], [1, 0, 0], [0, 2, 0], [0, 0, 3]])
    >>> M = motor_from_points(x, cga.apply_to_points(cga.motor([0, 0, 1], 0.5, [1, 2, 3]), x))
    >>> angle, axis = cga.rotor_angle_axis(cga.decompose_motor(M)[0])
    >>> round(angle, 10), np.round(axis, 10) + 0.0, np.round(cga.decompose_motor(M)[1], 10) + 0.0
    (0.5, array([0., 0., 1.]), array([1., 2., 3.]))
    """
    func = "motor_from_points"
    X, Y = _points(source, func, "source"), _points(target, func, "target")
    if Y.shape != X.shape:
        raise InvalidInputError(f"{func}: target: shape {Y.shape} does not match the source's {X.shape}")
    w = pair_weights(weights, X.shape[0], func)
    planar = X.shape[1] == 2
    need = 2 if planar else 3
    if np.count_nonzero(w > 0) < need:
        raise DegenerateGeometryError(
            f"{func}: source: needs at least {need} points with positive weight, got {np.count_nonzero(w > 0)}"
        )
    if planar:
        X, Y = np.pad(X, ((0, 0), (0, 1))), np.pad(Y, ((0, 0), (0, 1)))
    xbar, A = _spread_checks(X, w, func, "source", collinear=not planar)
    ybar, B = _spread_checks(Y, w, func, "target", collinear=not planar)
    N = rotor_matrix((w[:, None] * A).T @ B)
    if planar:
        sub = top_eigenvector(N[np.ix_([0, 3], [0, 3])], func, "source, target", "the rotation is not unique")
        r = np.array([sub[0], 0.0, 0.0, sub[1]])
    else:
        r = top_eigenvector(N, func, "source, target", "the rotation is not unique (degenerate correspondences)")
    R = rotor_from_coeffs(r / np.linalg.norm(r))
    t = ybar - apply_to_points(R, xbar)
    if planar:
        t[2] = 0.0
    return translator(t) * R


def item_sequence(items, func: str, name: str, what: str) -> list:
    """``items`` (any iterable but a string or a mapping) as a non-empty list."""
    if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__iter__"):
        raise checks.fail(func, name, f"expected a sequence or a batch of {what}, got {type(items).__name__}")
    items = list(items)
    if not items:
        raise checks.fail(func, name, f"needs at least one of the {what}")
    return items


# ------------------------------------------------------------------ averages
def _unit_motor(M, func: str, i: int):
    name = f"motors[{i}]"
    multivector(M, func, name, what="a motor (Multivector of G(4,1))", single=True, numeric=True)
    MM = M * ~M
    s = float(MM.scalar())
    if not np.isfinite(s) or s <= 1e-300:
        raise DegenerateGeometryError(f"{func}: motors[{i}]: M ~M = {s}, not a motor")
    if max((abs(float(v)) for b, v in MM.coeffs.items() if b), default=0.0) > 1e-8 * s:
        raise InvalidInputError(f"{func}: motors[{i}]: M ~M is not a scalar, not a motor")
    M = M / np.sqrt(s)
    why = why_not_motor(M)
    if why:
        raise checks.fail(func, name, why)
    R, t = decompose_motor(M)
    return _rotor_coeffs(R, func, name), np.asarray(t, dtype=float)


def mean_motor(motors, weights=None) -> Multivector:
    """Weighted mean of motors: the chordal L2 mean rotation [HT13] by Markley's eigenvector method [Ma07],
    and the weighted mean translation.

    The rotor part: with r_i the (unit) rotor coefficients, ``K = sum_i w_i r_i r_i^T`` and r the eigenvector
    of its largest eigenvalue, which maximises ``sum_i w_i (r . r_i)^2``.  Since the Frobenius distance of the
    rotation matrices is ``|Rot(r) - Rot(r_i)|_F^2 = 8 (1 - (r . r_i)^2)``, this is exactly the rotation
    minimising ``sum_i w_i |Rot - Rot_i|_F^2`` (the chordal mean, SciPy's ``Rotation.mean``); it ignores the
    signs of the r_i (the double cover).  It differs from the geodesic (Karcher) mean by O(spread^3) and is
    undefined (``DegenerateGeometryError``) when the top eigenvalue is double.  The translation is
    ``sum_i w_i t_i / sum_i w_i`` (the t_i of ``M_i = T_i R_i``, 2.144), the minimiser of
    ``sum_i w_i |t - t_i|^2``.  Returns the unit motor ``T(t) R``.  ``motors`` is a sequence of motors
    (each is scaled to ``M ~M = 1``) or a batch motor.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> M = mean_motor([cga.motor([0, 0, 1], 0.2, [1, 0, 0]), cga.motor([0, 0, 1], 0.4, [3, 0, 0])])
    >>> round(cga.rotor_angle_axis(cga.decompose_motor(M)[0])[0], 12), np.round(cga.decompose_motor(M)[1], 12) + 0.0
    (0.3, array([2., 0., 0.]))
    """
    func = "mean_motor"
    if isinstance(motors, Multivector):
        multivector(motors, func, "motors", what="motors")
        motors = [motors.batch_item(i) for i in range(len(motors))] if motors.shape else [motors]
    motors = item_sequence(motors, func, "motors", "motors")
    parts = [_unit_motor(M, func, i) for i, M in enumerate(motors)]
    w = pair_weights(weights, len(motors), func)
    r = np.array([p[0] for p in parts])
    t = np.array([p[1] for p in parts])
    K = np.einsum("i,ij,ik->jk", w, r, r)
    rbar = top_eigenvector(K, func, "motors", "the mean rotation is not unique (rotations spread symmetrically)")
    return translator(w @ t / w.sum()) * rotor_from_coeffs(rbar / np.linalg.norm(rbar))
