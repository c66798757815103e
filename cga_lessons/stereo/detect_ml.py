"""Maximum-likelihood refinement of a detected entity, and the covariance of its parameters.

The conformal least squares of section 4.1 (:mod:`cga_lessons.stereo.detect_models`)
are closed-form and weigh every point and direction alike.  Stereo points are
neither alike (depth noise grows as Z^2) nor isotropic (depth noise is 10-20
times the lateral noise), so the detector polishes each accepted entity by
Gauss-Newton on the Mahalanobis residuals of the noise model
(:mod:`cga_lessons.stereo.detect_noise`), starting from the conformal fit,
and reports the first-order covariance of the result.  Entities move by a
minimal local step (3 degrees of freedom for a plane, 4 for a sphere, 6 for
a circle, 4 for a line); both Jacobians are central differences.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.conformal import CircleParameters, LineParameters, PlaneParameters, SphereParameters

from .detect_models import DOF, basis, cross, fit, orient, residuals, unit
from .detect_noise import NoiseModel

__all__ = ["polish", "covariance", "fit_ml"]


# ------------------------------------------------- local parametrisation
def _perturb(kind: str, p, delta: np.ndarray):
    """The entity moved by a minimal local step ``delta`` (3 dof plane, 4 sphere, 6 circle, 4 line), unchecked
    (the classes' ``unchecked``: a trial step's radius may be negative)."""
    if kind == "plane":
        u, v = basis(p.normal)
        return PlaneParameters.unchecked(normal=unit(p.normal + delta[0] * u + delta[1] * v),
                                         distance=p.distance + delta[2])  # fmt: skip
    if kind == "sphere":
        return SphereParameters.unchecked(center=p.center + delta[:3], radius=p.radius + delta[3])
    if kind == "circle":
        u, v = basis(p.normal)
        return CircleParameters.unchecked(center=p.center + delta[:3],
                                          normal=unit(p.normal + delta[3] * u + delta[4] * v),
                                          radius=p.radius + delta[5])  # fmt: skip
    u, v = basis(p.direction)
    return LineParameters.unchecked(direction=unit(p.direction + delta[0] * u + delta[1] * v),
                                    point=p.point + delta[2] * u + delta[3] * v)  # fmt: skip


def _vector(kind: str, p) -> np.ndarray:
    keys = {"plane": ("normal", "distance"), "sphere": ("center", "radius"),
            "circle": ("center", "normal", "radius"), "line": ("point", "direction")}[kind]  # fmt: skip
    return np.concatenate([np.atleast_1d(np.asarray(getattr(p, k), float)) for k in keys])


def _whitener(kind, params, X, noise, idx):
    """The fixed parts of the whitened residuals at ``params``: inverse Cholesky factors (n, c, c) of the residual
    covariances ``B^T Sigma_i B`` (closed form, c <= 2) and the second-order residual means (n, c) (see polish)."""
    r, B = residuals(kind, params, X)
    S = noise.residual_cov(idx, B)
    W = np.zeros_like(S)
    a = np.sqrt(S[:, 0, 0])
    W[:, 0, 0] = 1.0 / a
    if S.shape[-1] == 2:
        b = S[:, 1, 0] / a
        c = np.sqrt(np.maximum(S[:, 1, 1] - b * b, 1e-300))
        W[:, 1, 0], W[:, 1, 1] = -b / (a * c), 1.0 / c
    off = np.zeros_like(r)
    if kind == "circle":  # E|q| = rho + t^T Sigma t / (2 rho), t the rim's tangent
        t = cross(B[..., 0], B[..., 1])
        w = X - params.center
        q = w - (w @ params.normal)[:, None] * params.normal
        off[:, 1] = noise.quad(idx, t, t) / (2 * np.linalg.norm(q, axis=-1))
    return W, off, noise, idx


def _sphere_white(params, X, noise, idx, iterations: int = 5):
    """Whitened residuals of points from a sphere by the exact Mahalanobis foot point, less their mean.

    The foot y of x minimises ``(x - y)^T Sigma^-1 (x - y)`` on the sphere, so
    ``y - x`` is along ``Sigma g(y)`` (g the normal): iterate g -> the
    intersection of the line ``x + mu Sigma g`` with the sphere (a quadratic
    in mu, smaller root) -> g at that point.  The residual is
    ``-mu sqrt(g^T Sigma g)`` (the signed Mahalanobis distance).  For stereo
    noise, long along the ray, y is where the ray meets the sphere: it does
    not move with the depth error, which removes the bias of the linearised
    residual.  Its mean for points on the sphere, from the Laplacian of the
    whitened distance, is ``(tr Sigma - |Sigma g|^2 / g^T Sigma g) / (2 rho sqrt(g^T Sigma g))``
    (``sigma / rho`` for isotropic noise, 0 for noise along one direction): subtracted.
    """
    w = X - params.center
    rho = params.radius
    g = w / np.linalg.norm(w, axis=-1, keepdims=True)
    cc = np.sum(w * w, axis=-1) - rho * rho
    for _ in range(iterations):
        v = noise.apply(idx, g)
        a, b = np.sum(v * v, axis=-1), np.sum(w * v, axis=-1)
        disc = b * b - a * cc
        q = b + np.where(b >= 0, 1.0, -1.0) * np.sqrt(np.maximum(disc, 0.0))
        mu = np.where(disc >= 0, -cc / np.where(q == 0, 1.0, q), -b / a)  # a miss: the closest approach
        s = np.sum(g * v, axis=-1)
        y = w + mu[:, None] * v
        g = y / np.linalg.norm(y, axis=-1, keepdims=True)
    tr = noise.trace(idx)
    return -mu * np.sqrt(s) - (tr - a / s) / (2 * rho * np.sqrt(s))


def _white(kind, params, X, ctx):
    W, off, noise, idx = ctx
    if kind == "sphere":
        return _sphere_white(params, X, noise, idx)
    return np.einsum("nab,nb->na", W, residuals(kind, params, X)[0] - off).ravel()


def _jacobians(kind, params, X, Wh):
    """Central-difference Jacobians (step 1e-6 m or rad) of the whitened residuals and of the reported parameters."""
    h, J, T = 1e-6, [], []
    for j in range(DOF[kind]):
        e = np.zeros(DOF[kind])
        e[j] = h
        pp, pm = _perturb(kind, params, e), _perturb(kind, params, -e)
        J.append((_white(kind, pp, X, Wh) - _white(kind, pm, X, Wh)) / (2 * h))
        T.append((_vector(kind, pp) - _vector(kind, pm)) / (2 * h))
    return np.array(J).T, np.array(T).T


def polish(kind: str, params, X: np.ndarray, noise: NoiseModel, idx: np.ndarray, iterations: int = 5):
    """Maximum-likelihood refinement of a conformal fit: Gauss-Newton on the Mahalanobis residuals.

    The conformal least squares weigh every point alike and every direction
    alike; stereo noise is neither (depth noise ~ Z^2, and 10-20 times the
    lateral noise).  Starting from the conformal fit, a few Gauss-Newton steps
    on the whitened residuals ``L_i^-1 (r_i - b_i)`` (``L_i L_i^T = B^T Sigma_i B``)
    reach the maximum-likelihood entity; a step is kept only if it lowers the
    cost (halved up to 5 times otherwise).

    ``b_i`` is the second-order mean of the residual of a round entity:
    noise tangent to a circle moves a point outwards by ``t^T Sigma t / (2 rho)``
    on average (t the tangent).  Spheres use the exact Mahalanobis distance
    instead of the linearised one (:func:`_sphere_white`): stereo depth noise
    is nearly tangent to the rim of a ball, where the linearised residual's
    normal turns with the noise; fitted with it, a 22 cm ball at 2.9 m and
    1 px shrinks towards the camera by ~2 cm (10 times its standard
    deviation).

    Returns the polished parameters, of the class of ``params`` (the kind's
    defining fields only: a plane's drawing ``center`` and a line's ``length`` are
    dropped once a step is taken), with the normal (direction) sign fixed by
    :func:`~cga_lessons.stereo.detect_models.orient`.
    """
    if len(X) <= DOF[kind]:
        return params
    Wh = _whitener(kind, params, X, noise, idx)
    cost = float(np.sum(_white(kind, params, X, Wh) ** 2))
    for _ in range(iterations):
        J, _ = _jacobians(kind, params, X, Wh)
        step = np.linalg.lstsq(J, -_white(kind, params, X, Wh), rcond=None)[0]
        for _ in range(6):
            new = _perturb(kind, params, step)
            if getattr(new, "radius", 1.0) > 0:
                Wn = _whitener(kind, new, X, noise, idx)
                c = float(np.sum(_white(kind, new, X, Wn) ** 2))
                if c < cost:
                    break
            step = step / 2
        else:
            break
        done = cost - c < 1e-10 * cost
        params, Wh, cost = new, Wn, c
        if done:
            break
    if kind in ("plane", "circle"):
        key = "normal"
    else:
        key = "direction" if kind == "line" else None
    if key is not None:
        n = orient(getattr(params, key))
        if kind == "plane":
            params = PlaneParameters.unchecked(normal=n, distance=float(params.distance * (n @ params.normal)))
        else:
            params = type(params).unchecked(**{**_fields(params), key: n})
    return params


def _fields(params) -> dict:
    return {name: getattr(params, name) for name in type(params).__dataclass_fields__}


def covariance(kind: str, params, X: np.ndarray, noise: NoiseModel, idx: np.ndarray) -> np.ndarray:
    """First-order covariance of the fitted parameters (order :data:`PARAM_NAMES`), from the noise of the inliers.

    For the maximum-likelihood entity of :func:`polish`, with J the Jacobian
    of the whitened residuals in a minimal local parametrisation (3 dof for a
    plane, 4 sphere, 6 circle, 4 line), the covariance of those parameters is
    ``(J^T J)^-1`` (the Cramer-Rao bound to first order); it is mapped to the
    reported, over-complete parameters with the Jacobian T of the
    parametrisation, ``T (J^T J)^-1 T^T`` (rank 3 for a plane, 6 for a circle,
    4 for a line).

    Parameters
    ----------
    X : ndarray, shape (n, 3)
        The inliers.
    idx : ndarray of int, shape (n,)
        Their indices in the noise model.
    """
    J, T = _jacobians(kind, params, X, _whitener(kind, params, X, noise, idx))
    return T @ np.linalg.pinv(J.T @ J) @ T.T


def fit_ml(kind: str, X: np.ndarray, noise: NoiseModel, idx: np.ndarray):
    """The conformal least-squares fit of ``kind`` (section 4.1) polished to maximum likelihood, or None.

    Returns a :class:`~cga_lessons.conformal.PlaneParameters`, ``SphereParameters``, ``CircleParameters`` or
    ``LineParameters`` (None when the points determine no entity of the kind)."""
    p = fit(kind, X)
    if p is None:
        return None
    try:
        return polish(kind, p, X, noise, idx)
    except np.linalg.LinAlgError:
        return p
