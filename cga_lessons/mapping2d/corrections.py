"""Heading and position corrections of the 2D line map (thesis section 3.1.3, Eqs. 3.6-3.12).

:func:`theta_correction` (3.8) and :func:`translation_correction` (3.9-3.12)
are the thesis's formulas; :func:`pose_correction` solves the two together as
one weighted least squares, with the odometry's prediction as one more
measurement, which is what :meth:`cga_lessons.mapping2d.builder.MapBuilder.correct`
uses; :func:`line_variances` gives the variance of a fitted line's angle and
offset that weights each correspondence, :func:`odometry_covariance` that of
the odometry's prediction.
"""

from __future__ import annotations

import functools

import numpy as np

from cga_lessons import checks

from .geometry import SegmentSet
from .inputs import covariance, vector
from .laser import OdometryModel
from .poses import relative_unchecked, wrap_unchecked

__all__ = [
    "theta_correction",
    "translation_correction",
    "pose_correction",
    "line_variances",
    "odometry_covariance",
    "chain_covariance",
]


# --------------------------------------------------------------------------- corrections (3.6-3.12)


def theta_correction(dth, weights=None) -> float:
    """Heading correction ``theta_corr`` (3.8): the (weighted) mean of diffTheta over the correspondences.

    .. math:: \\theta_{corr} = \\frac{1}{n} \\sum_{i=1}^n \\mathrm{diffTheta}(\\theta_{G_i}, \\theta_{L'_i})

    Parameters
    ----------
    dth : array_like, shape (n,)
        ``diffTheta(theta_G_i, theta_L'_i)`` for each correspondence.
    weights : array_like, shape (n,), optional
        The thesis takes the plain mean (all 1); weights give the
        inverse-variance mean.

    >>> theta_correction([0.01, 0.03])
    0.02
    """
    f = "theta_correction"
    dth = vector(dth, f, "dth", at_least=1)
    w = np.ones_like(dth) if weights is None else _weights(weights, None, f)
    checks.same_length(f, dth=dth, weights=w)
    with np.errstate(over="ignore", invalid="ignore"):
        out = float(np.sum(w * dth) / np.sum(w))
    return checks.finite_result(out, f, "dth, weights")


def _weights(weights, n, func: str, name: str = "weights") -> np.ndarray:
    """Weights (n,) (``n`` None: any length): finite, >= 0, not all zero."""
    w = checks.array(weights, func, name, (n,))
    if np.any(w < 0) or not np.any(w > 0):
        raise checks.fail(func, name, "must be >= 0 and not all zero")
    return w


def translation_correction(rho_g, rho_l, theta_l, weights=None, weak_ratio: float = 0.0, along=None):
    """Position correction ``T_corr`` from corresponding lines (3.9-3.12).

    Each correspondence gives the constraint (3.11)
    ``rho_G - ((p_L'c + t) . (cos theta_L', sin theta_L')) = 0``, i.e.
    ``n_i . t = rho_G_i - rho_L'_i``, and ``t`` minimises the (weighted) sum of
    squares (3.12).  With one correspondence, or lines all parallel, only the
    component along their normal is determined: it is the displacement
    between the two lines' closest points (3.9); the other component is then
    taken from ``along`` if given, else zero (the odometry is kept).

    Parameters
    ----------
    rho_g, rho_l, theta_l : array_like, shape (m,)
        Hough coordinates of the global lines and of the local lines after the
        heading correction (all seen from the same point).
    weights : array_like, shape (m,), optional
        Inverse variances of ``rho_G - rho_L'`` (default all 1).
    weak_ratio : float
        A direction whose information is below this fraction of the largest
        counts as undetermined (0: only an exactly singular one).
    along : tuple (offsets (k, 2), weights (k,)), optional
        Displacements (global - local) between matching real edges; their
        weighted mean fixes the undetermined direction.

    Returns
    -------
    ndarray, shape (2,)

    >>> translation_correction([1.0, 2.0], [0.9, 2.3], [0.0, np.pi / 2]).round(12).tolist()
    [0.1, -0.3]
    >>> translation_correction([1.0], [0.9], [np.pi / 2]).round(12).tolist()  # one line: (3.9)
    [0.0, 0.1]
    """
    f = "translation_correction"
    rho_g, rho_l = vector(rho_g, f, "rho_g", at_least=1), vector(rho_l, f, "rho_l", at_least=1)
    theta_l = vector(theta_l, f, "theta_l", at_least=1)
    checks.same_length(f, rho_g=rho_g, rho_l=rho_l, theta_l=theta_l)
    w = np.ones_like(rho_g) if weights is None else _weights(weights, None, f)
    checks.same_length(f, rho_g=rho_g, weights=w)
    weak_ratio = checks.real(weak_ratio, f, "weak_ratio", low=0.0, high=1.0)
    if along is not None:
        if not isinstance(along, (tuple, list)) or len(along) != 2:
            raise checks.fail(f, "along", "expected a pair (offsets (k, 2), weights (k,))")
        off = checks.array(along[0], f, "along", (None, 2))
        along = None if len(off) == 0 else (off, _weights(along[1], len(off), f, "along"))
    with np.errstate(over="ignore", invalid="ignore"):
        t = _translation(rho_g, rho_l, theta_l, w, weak_ratio, along)
    return checks.finite_result(t, f, "rho_g, rho_l, weights")


def _translation(rho_g, rho_l, theta_l, w, weak_ratio, along):
    """:func:`translation_correction` of checked arrays."""
    n = np.column_stack([np.cos(theta_l), np.sin(theta_l)])
    b = rho_g - rho_l
    A = (n * w[:, None]).T @ n
    rhs = (n * w[:, None]).T @ b
    vals, vecs = np.linalg.eigh(A)
    if vals[0] > max(weak_ratio * vals[1], 1e-12 * vals[1]):
        return np.linalg.solve(A, rhs)
    strong, weak = vecs[:, 1], vecs[:, 0]
    t = strong * (strong @ rhs) / vals[1]
    if along is not None:
        off, ew = along
        t = t + weak * float(np.sum(ew * (off @ weak)) / np.sum(ew))
    return t


def pose_correction(dth, var_theta, offset, var_offset, normal, lever, prior_cov=None, prior_offset=None, extra=None):
    """Heading and position corrections (3.8) and (3.12) solved together as one weighted least squares.

    Each correspondence ``i`` gives two measurements of the correction
    ``(t_x, t_y, theta_corr)`` of a pose, rotating about the robot's position:

    * its angle difference (3.8): ``diffTheta(theta_G, theta_L') = theta_corr``,
      variance ``var_theta``;
    * the offset of the local segment's centroid from the global line, along
      the global line's normal ``n`` (3.11 written at the centroid, where a
      fitted line's angle and offset errors are uncorrelated):
      ``offset = n . t + theta_corr (n . J lever)``, variance ``var_offset``,
      with ``lever`` the centroid's position relative to the robot and ``J``
      the quarter turn.

    The odometry's prediction enters as one more measurement: the correction
    ``prior_offset`` (default 0) with covariance ``prior_cov``.  Without it,
    and with the offsets left out (infinite ``var_offset``), the heading is the
    inverse-variance mean of (3.8); with the heading held, the position is the
    weighted least squares of (3.12).

    Parameters
    ----------
    dth, var_theta, offset, var_offset : array_like, shape (m,)
    normal, lever : array_like, shape (m, 2)
    prior_cov : array_like, shape (3, 3), optional
        Covariance of the prediction (x, y, theta); None: no prior.
    prior_offset : array_like, shape (3,), optional
        The correction the prediction asks for (the predicted pose minus the
        current one), default zero.
    extra : tuple (H (k, 3), r (k,), w (k,)), optional
        More linear measurements ``H delta = r`` with weights ``w`` (e.g. real
        edges seen again).

    Returns
    -------
    delta : ndarray, shape (3,)
        ``(t_x, t_y, theta_corr)``.
    cov : ndarray, shape (3, 3)
        Its covariance (the inverse of the information matrix).

    Raises
    ------
    InvalidInputError
        If the measurements do not determine the correction (no prior and too few lines).

    >>> d, _ = pose_correction([0.02, 0.04], [1.0, 1.0], [0.0, 0.0], [np.inf, np.inf],
    ...                        [[1.0, 0.0], [0.0, 1.0]], [[1.0, 0.0], [0.0, 1.0]],
    ...                        prior_cov=np.diag([1.0, 1.0, 1e12]))
    >>> round(float(d[2]), 9)  # the mean of (3.8)
    0.03
    """
    f = "pose_correction"
    dth, vt, off = vector(dth, f, "dth"), vector(var_theta, f, "var_theta"), vector(offset, f, "offset")
    vo = vector(var_offset, f, "var_offset", finite=False)
    normal = checks.array(normal, f, "normal", (None, 2))
    lever = checks.array(lever, f, "lever", (None, 2))
    checks.same_length(f, dth=dth, var_theta=vt, offset=off, var_offset=vo, normal=normal, lever=lever)
    if np.any(vt <= 0):
        raise checks.fail(f, "var_theta", "variances must be > 0")
    if np.any(np.isnan(vo)) or np.any(vo <= 0):
        raise checks.fail(f, "var_offset", "variances must be > 0 (inf: the offsets left out)")
    for name, v in (("dth", dth), ("offset", off), ("normal", normal), ("lever", lever)):
        checks.magnitude(v, f, name)
    prior = None if prior_cov is None else covariance(prior_cov, f, "prior_cov")
    prior_offset = None if prior_offset is None else checks.array(prior_offset, f, "prior_offset", (3,))
    if extra is not None:
        if not isinstance(extra, (tuple, list)) or len(extra) != 3:
            raise checks.fail(f, "extra", "expected a triple (H (k, 3), r (k,), w (k,))")
        H = checks.array(extra[0], f, "extra", (None, 3))
        extra = (H, checks.array(extra[1], f, "extra", (len(H),)), checks.array(extra[2], f, "extra", (len(H),)))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        A, b = _normal_equations(dth, vt, off, vo, normal, lever, prior, prior_offset, extra)
    checks.finite_result(np.append(A, b), f, "the measurements (their weights)")
    vals = np.linalg.eigvalsh(A)
    if not vals[0] > 1e-12 * max(vals[-1], 1e-300):
        raise checks.fail(f, "dth, prior_cov", "the measurements do not determine the correction")
    cov = np.linalg.inv(A)
    return checks.finite_result(cov @ b, f, "the measurements"), cov


def _normal_equations(dth, vt, off, vo, normal, lever, Pinv, prior_offset, extra):
    """The information matrix (3, 3) and vector (3,) of :func:`pose_correction`'s measurements."""
    A = np.zeros((3, 3))
    b = np.zeros(3)
    if len(dth):
        wt = 1.0 / vt
        wo = np.where(np.isfinite(vo), 1.0 / vo, 0.0)
        A[2, 2] += wt.sum()
        b[2] += wt @ dth
        H = np.column_stack([normal, normal[:, 1] * lever[:, 0] - normal[:, 0] * lever[:, 1]])
        A += (H * wo[:, None]).T @ H
        b += (H * wo[:, None]).T @ off
    if extra is not None and len(extra[0]):
        He, re, we = extra
        A += (He * we[:, None]).T @ He
        b += (He * we[:, None]).T @ re
    if Pinv is not None:
        A += Pinv
        if prior_offset is not None:
            b += Pinv @ prior_offset
    return A, b


def line_variances(segs: SegmentSet, centre, range_noise: float, angle_floor: float = 0.0, offset_floor: float = 0.0):
    """Variances of fitted lines' angles (rad^2) and offsets ``rho`` seen from ``centre`` (m^2).

    A line fitted to ``n`` points with range noise ``sigma`` spread over length
    ``L`` has angle variance ``12 sigma^2 / (n L^2)`` and offset variance
    ``sigma^2 / n`` at its centroid, which grows as ``sigma^2 (1 + 12 s^2 / L^2) / n``
    at the foot of the perpendicular from ``centre``, ``s`` along the line from
    the centroid: a short face seen far off to the side says little about its
    ``rho``.  The floors model walls that are not perfectly straight.

    Returns
    -------
    var_theta, var_rho : ndarray, shape (n,)
    """
    f = "line_variances"
    what = "a SegmentSet (SegmentSet.from_segments(list of Segment))"
    segs = checks.instance(segs, f, "segs", SegmentSet, what)
    centre = checks.magnitude(checks.array(centre, f, "centre", (2,)), f, "centre")
    noise = np.float64(checks.real(range_noise, f, "range_noise", low=0.0))  # a NumPy float: overflows to inf
    floors = [
        np.float64(checks.real(v, f, k, low=0.0))
        for k, v in (("angle_floor", angle_floor), ("offset_floor", offset_floor))
    ]
    with np.errstate(over="ignore", invalid="ignore"):
        out = line_variances_unchecked(segs, centre, noise, *floors)
    return checks.finite_result(out, f, "range_noise, angle_floor, offset_floor")


def line_variances_unchecked(segs: SegmentSet, centre, range_noise, angle_floor=0.0, offset_floor=0.0):
    """:func:`line_variances` of checked arguments; ``centre`` (2,) or one per segment (n, 2)."""
    n = segs.n_points
    L = np.maximum(segs.length, 1e-3)
    d = (segs.end - segs.start) / L[:, None]
    s = np.einsum("ij,ij->i", np.asarray(centre, float) - segs.centroid, d)
    var_t = 12.0 * range_noise**2 / (n * L**2) + angle_floor**2
    var_r = range_noise**2 / n + s**2 * var_t + offset_floor**2
    return var_t, var_r


def odometry_covariance(increment, params) -> np.ndarray:
    """Covariance (3, 3) of one odometry step ``(dx, dy, dtheta)`` under the stated drift model ``params`` (an
    :class:`~cga_lessons.mapping2d.params.OdometryPriorParams`).

    With ``d`` the step's length: position variance ``odo_sigma_xy^2 d`` per
    axis, heading variance ``odo_sigma_heading^2 d + odo_sigma_turn^2 |dtheta|
    + (odo_heading_bias d)^2`` (the bias counted as one more error), as in
    :class:`cga_lessons.mapping2d.laser.OdometryModel`.
    """
    return _drift_model(params).step_covariance_unchecked(increment) + np.diag([1e-8, 1e-8, 1e-10])


@functools.lru_cache(maxsize=8)
def _drift_model(params) -> OdometryModel:
    """The drift model of a (frozen, hashable) :class:`~cga_lessons.mapping2d.params.OdometryPriorParams`."""
    return OdometryModel(params.odo_sigma_xy, params.odo_sigma_heading, params.odo_sigma_turn, params.odo_heading_bias)


def chain_covariance(odometry, first, last, params) -> tuple[np.ndarray, np.ndarray]:
    """The odometry's increment from pose ``first`` to pose ``last`` and its covariance under the drift model
    ``params`` (an :class:`~cga_lessons.mapping2d.params.OdometryPriorParams`).

    The steps' covariances (:func:`odometry_covariance`) are carried through the composition
    ``u = u_1 o u_2 o ...``: with ``u' = u o s``, ``cov(u') = J_u cov(u) J_u' + J_s cov(s) J_s'`` (the
    Jacobians of the planar composition).  Over ``k`` steps the odometry's error grows about ``k``-fold in
    variance, while a registration of the two scans has the error of one: the two are told apart by it.

    Returns
    -------
    increment : ndarray, shape (3,)
    cov : ndarray, shape (3, 3)
    """
    odo = np.asarray(odometry, float)
    u = np.zeros(3)
    cov = np.zeros((3, 3))
    for k in range(int(first) + 1, int(last) + 1):
        s = relative_unchecked(odo[k - 1], odo[k])
        c, sn = np.cos(u[2]), np.sin(u[2])
        Ju = np.array([[1.0, 0.0, -sn * s[0] - c * s[1]], [0.0, 1.0, c * s[0] - sn * s[1]], [0.0, 0.0, 1.0]])
        Js = np.array([[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]])
        cov = Ju @ cov @ Ju.T + Js @ odometry_covariance(s, params) @ Js.T
        u = np.array([u[0] + c * s[0] - sn * s[1], u[1] + sn * s[0] + c * s[1], u[2] + s[2]])
    u[2] = wrap_unchecked(u[2])
    return u, cov
