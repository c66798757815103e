"""The four kinds of entity a detector looks for: hypotheses, residuals and fits (section 4.1, table 2.1).

Each kind is a conformal entity of table 2.1, built from a minimal set of
points exactly as section 4.1 builds it, and refined by the conformal least
squares of :mod:`cga_lessons.conformal.fitting` and :mod:`cga_lessons.conformal.line_fit`:

========  =======  ===============================  =====================================
kind      minimal  hypothesis (dual form)            least-squares refinement
========  =======  ===============================  =====================================
sphere    4        s* = a ^ b ^ c ^ d  (2.75)        ``M s = lambda G s`` (fit_sphere)
plane     3        P* = e ^ a ^ b ^ c  (2.77)        the same, without e0 (fit_plane)
circle    3        z* = a ^ b ^ c      (2.80)        two smallest eigenvectors, s1 ^ s2 (2.79)
line      2        L* = e ^ a ^ b      (2.81)        two best planes, L = pi1 ^ pi2 (fit_line)
========  =======  ===============================  =====================================

Parameters are read back with (2.115, 2.116, 2.73) for spheres, (2.89) for
planes, (2.119-2.124) for circles and (2.127, 2.129) for lines.  Every kind
also has a *residual*: the geometric distance of a point from the entity,
``codim`` components (1 for surfaces, 2 for curves), with its unit directions
B for the Mahalanobis test of :mod:`cga_lessons.stereo.detect_noise`.  For a
sphere it is the distance behind ``x . s = (rho^2 - |x - p|^2) / 2`` (2.71,
2.72); for a plane ``x . pi = x . n - delta`` (2.89); for a line (2.130).

Parameters are the records of :mod:`cga_lessons.conformal.parameters`; batches (made with the classes'
``unchecked``) carry a leading axis.  The maximum-likelihood polish of a fit and the covariance of its parameters are in
:mod:`cga_lessons.stereo.detect_ml`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError
from cga_lessons.conformal import CircleParameters, LineParameters, PlaneParameters, SphereParameters

__all__ = ["KINDS", "MINIMAL", "CODIM", "DOF", "PARAM_NAMES", "hypotheses", "residuals", "fit",
           "blade", "orient", "basis"]  # fmt: skip

#: Order of the model-selection test: manifold dimension first (curves before surfaces), then fewer parameters.
KINDS = ("line", "circle", "plane", "sphere")
MINIMAL = {"line": 2, "circle": 3, "plane": 3, "sphere": 4}
CODIM = {"line": 2, "circle": 2, "plane": 1, "sphere": 1}
#: Degrees of freedom of each kind (its minimal parametrisation).
DOF = {"line": 4, "circle": 6, "plane": 3, "sphere": 4}
#: Order of the parameters in an entity's covariance matrix.
PARAM_NAMES = {
    "plane": ("normal_x", "normal_y", "normal_z", "distance"),
    "sphere": ("center_x", "center_y", "center_z", "radius"),
    "circle": ("center_x", "center_y", "center_z", "normal_x", "normal_y", "normal_z", "radius"),
    "line": ("point_x", "point_y", "point_z", "direction_x", "direction_y", "direction_z"),
}


def _dot(a, b):
    return np.sum(a * b, axis=-1)


def cross(a, b):
    """Cross product over the last axis (np.cross's axis handling costs more than the product on small arrays)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def orient(v: np.ndarray) -> np.ndarray:
    """Unit vector(s) with their largest-magnitude component made positive (a fixed sign for normals)."""
    i = np.argmax(np.abs(v), axis=-1)
    s = np.sign(np.take_along_axis(v, i[..., None], axis=-1))
    return v * np.where(s == 0, 1.0, s)


def basis(n):
    """Two unit vectors (..., 3) orthogonal to the unit vector(s) n and to each other."""
    helper = np.where(np.abs(n[..., :1]) < 0.9, np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
    u = unit(cross(n, helper))
    return u, cross(n, u)


def _core(kind: str, params) -> dict:
    """The fields that define the entity (not the drawing's ``center`` of a plane nor a line's ``length``)."""
    names = {"plane": ("normal", "distance"), "sphere": ("center", "radius"), "circle": ("center", "radius", "normal"),
             "line": ("point", "direction")}[kind]  # fmt: skip
    return {name: getattr(params, name) for name in names}


# ------------------------------------------------------------- hypotheses
def hypotheses(kind: str, X: np.ndarray, idx: np.ndarray, min_conditioning: float = 0.05):
    """Entities of ``kind`` through minimal point sets, built in the conformal model.

    Parameters
    ----------
    X : ndarray, shape (N, 3)
    idx : ndarray of int, shape (H, MINIMAL[kind])
        Indices of the minimal sets.
    min_conditioning : float
        Sets whose shape is too flat are skipped: for triples the ratio of the
        triangle's area to its longest edge squared, for quadruples the
        tetrahedron's volume over the longest edge cubed (0.118 at best for a
        regular tetrahedron, 0.433 for an equilateral triangle).

    Returns
    -------
    params : PlaneParameters, SphereParameters, CircleParameters or LineParameters, or None
        A batch of H' <= H entities (every field with a leading axis), None when no set is kept.
    kept : ndarray of int
        The rows of idx they came from.
    """
    P = X[idx]  # (H, m, 3)
    edges = np.stack([np.linalg.norm(P[:, i] - P[:, j], axis=-1) for i in range(idx.shape[1])
                      for j in range(i + 1, idx.shape[1])], axis=1).max(axis=1)  # fmt: skip
    if kind == "line":
        ok = edges > 0
    elif kind in ("plane", "circle"):
        area = np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=-1) / 2
        ok = area > min_conditioning * np.maximum(edges, 1e-300) ** 2
    else:
        vol = np.abs(np.linalg.det(P[:, 1:] - P[:, :1])) / 6
        ok = vol > 0.25 * min_conditioning * np.maximum(edges, 1e-300) ** 3
    kept = np.flatnonzero(ok)
    a, b, c = (P[kept, i] for i in range(3)) if kind != "line" else (P[kept, 0], P[kept, 1], None)
    if len(kept) == 0:
        return None, kept
    if kind == "sphere":
        S = cga.sphere_from_points(a, b, c, P[kept, 3])  # (2.75)
        center, radius = cga.sphere_center_radius(S)  # (2.115), (2.116), (2.73)
        return SphereParameters.unchecked(center=np.atleast_2d(center), radius=np.atleast_1d(radius)), kept
    if kind == "plane":
        n, d = cga.plane_normal_distance(cga.plane_from_points(a, b, c))  # (2.77), (2.89)
        return PlaneParameters.unchecked(normal=np.atleast_2d(n), distance=np.atleast_1d(d)), kept
    if kind == "circle":
        center, radius, n = cga.circle_center_radius(cga.circle_from_points(a, b, c))  # (2.80), (2.119)-(2.124)
        return CircleParameters.unchecked(center=np.atleast_2d(center), radius=np.atleast_1d(radius),
                                          normal=np.atleast_2d(n)), kept  # fmt: skip
    L = cga.line_from_points(a, b)  # (2.81)
    return LineParameters.unchecked(point=np.atleast_2d(cga.line_closest_point(L)),
                                    direction=np.atleast_2d(cga.line_direction(L))), kept  # fmt: skip


# -------------------------------------------------------------- residuals
def residuals(kind: str, params, X: np.ndarray):
    """Geometric residuals of points X (N, 3) from a batch of entities (leading axis H) or from one entity.

    Returns
    -------
    r : ndarray, shape (H, N, c) (or (N, c) for one entity)
        Distances: along the normal (plane, 2.89; sphere, 2.72), or across a
        curve in two directions (circle: off its plane and off its rim in the
        plane; line: two directions orthogonal to it, whose norm is 2.130).
    B : ndarray, shape (H, N, 3, c) (or (N, 3, c))
        Unit directions of the components (the gradient of r in the point).
    """
    key = {"plane": "normal", "sphere": "center", "circle": "center", "line": "point"}[kind]
    single = np.ndim(getattr(params, key)) == 1
    p = {k: np.asarray(v, float)[None] if single else np.asarray(v, float) for k, v in _core(kind, params).items()}
    Xb = X[None]  # (1, N, 3)
    if kind == "plane":
        n = p["normal"][:, None, :]
        r = (_dot(Xb, n) - p["distance"][:, None])[..., None]
        B = np.broadcast_to(n[..., None], (n.shape[0], X.shape[0], 3, 1))
    elif kind == "sphere":
        w = Xb - p["center"][:, None, :]
        dist = np.linalg.norm(w, axis=-1)
        r = (dist - p["radius"][:, None])[..., None]
        B = (w / np.maximum(dist, 1e-300)[..., None])[..., None]
    elif kind == "circle":
        n = p["normal"][:, None, :]
        w = Xb - p["center"][:, None, :]
        h = _dot(w, n)
        q = w - h[..., None] * n
        qn = np.linalg.norm(q, axis=-1)
        rad = q / np.maximum(qn, 1e-300)[..., None]
        r = np.stack([h, qn - p["radius"][:, None]], axis=-1)
        B = np.stack([np.broadcast_to(n, rad.shape), rad], axis=-1)
    else:
        u, v = basis(p["direction"])
        w = Xb - p["point"][:, None, :]
        r = np.stack([_dot(w, u[:, None]), _dot(w, v[:, None])], axis=-1)
        B = np.broadcast_to(np.stack([u, v], axis=-1)[:, None], w.shape + (2,))
    return (r[0], B[0]) if single else (r, B)


# ------------------------------------------------------------------- fits
def fit(kind: str, X: np.ndarray) -> PlaneParameters | SphereParameters | CircleParameters | LineParameters | None:
    """The conformal least-squares fit of ``kind`` to X (N, 3), or None when X does not determine one."""
    if len(X) < MINIMAL[kind] + 1:
        return None
    try:
        if kind == "sphere":
            f = cga.fit_sphere(X)
            return SphereParameters(center=f.center, radius=float(f.radius))
        if kind == "plane":
            f = cga.fit_plane(X)
            n = orient(f.normal)
            return PlaneParameters(normal=n, distance=float(f.distance * (n @ f.normal)))
        if kind == "circle":
            f = cga.fit_circle(X)
            return CircleParameters(center=f.center, radius=float(f.radius), normal=orient(f.normal))
        f = cga.fit_line(X)
        return LineParameters(point=f.point, direction=f.direction)
    except (DegenerateGeometryError, np.linalg.LinAlgError, FloatingPointError):
        return None


def blade(kind: str, params):
    """The conformal entity: sphere (2.72) and plane (2.89) in standard form, circle (2.80) and line (2.81) dual."""
    if kind == "sphere":
        return cga.sphere(params.center, params.radius)
    if kind == "plane":
        return cga.plane(params.normal, params.distance)
    if kind == "line":
        return cga.line_from_points(params.point, params.point + params.direction)
    c, r, n = params.center, params.radius, params.normal
    u, v = basis(np.asarray(n, float))
    return cga.circle_from_points(c + r * u, c + r * v, c - r * u)
