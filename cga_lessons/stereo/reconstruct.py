"""The conformal entities of section 4.1 rebuilt from a stereo pair: triangulated minimal point sets (A.14) and the
point, point pair, line, circle, plane and sphere through them in G(4,1).

The scene and its views are made in :mod:`cga_lessons.stereo.head`; the errors of the estimates against the truth
in :mod:`cga_lessons.stereo.accuracy`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail

from . import validate as vd
from .entities import SceneCircle, SceneLine, ScenePair, ScenePlane, ScenePoints, SceneSphere
from .rig import StereoRig, check_rig
from .triangulation import triangulate

__all__ = ["reconstruct_entities", "circle_center_via_plane"]


def circle_center_via_plane(Z):
    """Circle centre by the first way of 4.1: plane (2.119), axis (2.120), their meet (2.121).

    ``P_z* = z* ^ e`` is the circle's plane (2.119) and ``L_z* = z ^ e`` the
    axis through the centre (2.120).  Their intersection is the flat point
    ``e ^ s_e0`` of (2.121), where ``s_e0 = p_z + e0`` is the sphere centred
    at p_z through the origin.  As printed, (2.121) contracts the axis with
    the *dual* plane ``P_z*`` (a 4-blade), which gives a vector (zero); the
    flat point comes from the standard-form plane ``P_z = P_z* I_c``:
    ``L_z* . P_z = e ^ s_e0``.  Then ``s_e0 ~ -e0 . (e ^ s_e0)`` and p_z is
    its Euclidean part after normalising (2.115, 2.116).

    Parameters
    ----------
    Z : Multivector
        Circle in dual form ``a ^ b ^ c`` (grade 3).

    Returns
    -------
    ndarray, shape (3,)
    """
    Z = vd.entity(Z, "circle_center_via_plane", "Z", ("circle",))
    return _centre_via_plane(Z)


def _centre_via_plane(Z):
    z = cga.standard_form(Z)
    Pz = cga.standard_form(cga.circle_plane(Z))  # (2.119), standard form
    Lz = z ^ cga.einf  # (2.120)
    flat = Lz | Pz  # (2.121), corrected: e ^ s_e0
    s = -(cga.eo | flat)
    return cga.euclidean(cga.normalize_point(s, "circle_center_via_plane"))


def reconstruct_entities(rig: StereoRig, views: dict, method: str = "midpoint") -> dict:
    """Triangulate the minimal point sets and build every entity of 4.1 in G(4,1).

    Parameters
    ----------
    rig : StereoRig
    views : dict
        ``name -> (x1, x2)`` pixel coordinates for ``"points"`` (N),
        ``"segment"`` (2), ``"circle_key"`` (3), ``"plane_key"`` (3) and
        ``"sphere_key"`` (4), e.g. ``observe`` applied to :func:`sample_scene`.
    method : {"midpoint", "dlt"}
        Triangulation (A.14).

    Returns
    -------
    dict
        Entity name -> its record (:mod:`cga_lessons.stereo.entities`):
        ``"point"`` a :class:`ScenePoints` (up 2.62 and down 2.114),
        ``"pair"`` a :class:`ScenePair` (2.68, 2.131), ``"line"`` a
        :class:`SceneLine` (2.81, 2.125-2.129), ``"circle"`` a
        :class:`SceneCircle` (2.80, 2.119-2.124), ``"plane"`` a
        :class:`ScenePlane` (2.77; its circumcircle's centre and radius to
        draw it) and ``"sphere"`` a :class:`SceneSphere` (2.75, 2.115, 2.116,
        2.73).  Each holds its conformal ``blade``.
    """
    f = "reconstruct_entities"
    rig = check_rig(rig, f)
    method = checks.choice(method, f, "method", ("midpoint", "dlt"))
    views = checks.instance(views, f, "views", dict, "a dict name -> (x1, x2)")
    tri = {}
    for k, n in {**dict.fromkeys(views, 0), **_KEY_POINTS}.items():
        tri[k] = _triangulate_view(rig, views, k, n, method, f)
    try:
        return _entities(tri)
    except GeometryError as exc:
        raise degenerate(f, "views", f"the triangulated points are degenerate: {exc}") from None


#: The views :func:`reconstruct_entities` needs, and how many points each holds (0: any number).
_KEY_POINTS = {"points": 0, "segment": 2, "circle_key": 3, "plane_key": 3, "sphere_key": 4}


def _triangulate_view(rig, views: dict, key: str, n: int, method: str, func: str) -> np.ndarray:
    if key not in views:
        raise fail(func, "views", f"has no {key!r} (it needs {', '.join(_KEY_POINTS)})")
    pair = views[key]
    two = isinstance(pair, (tuple, list)) or isinstance(pair, np.ndarray) and pair.ndim > 0
    if not two or len(pair) != 2:
        raise fail(func, "views", f"{key!r} must be a pair (x1, x2) of pixel arrays, got {pair!r:.40}")
    name = f"views[{key!r}]"
    (x1, _), (x2, _) = vd.batch(pair[0], func, name, (2,), at_least=1), vd.batch(pair[1], func, name, (2,))
    checks.same_length(func, **{f"{name}[0]": x1, f"{name}[1]": x2})
    if n and len(x1) != n:
        raise fail(func, name, f"must hold {n} points, got {len(x1)}")
    try:
        return triangulate(rig.P1, rig.P2, x1, x2, method=method)
    except GeometryError as exc:
        raise degenerate(func, name, f"cannot be triangulated: {exc}") from None


def _entities(tri: dict) -> dict:
    out = {}
    X = cga.up(tri["points"])  # (2.62), a batch
    out["point"] = ScenePoints(points=cga.down(X), blade=X)  # (2.114)
    a, b = tri["segment"]
    PP = cga.point_pair(a, b)  # (2.68)
    out["pair"] = ScenePair(endpoints=np.array(cga.point_pair_endpoints(PP)), blade=PP)  # (2.131)
    L = cga.line_from_points(a, b)  # (2.81)
    length = float(np.sqrt((L * L).scalar()))  # (2.125)
    out["line"] = SceneLine(direction=cga.line_direction(L), closest_point=cga.line_closest_point(L), length=length,
                            midpoint=0.5 * (a + b), blade=L)  # fmt: skip
    Z = cga.circle_from_points(*tri["circle_key"])  # (2.80)
    c, r, n = cga.circle_center_radius(Z)
    out["circle"] = SceneCircle(center=c, radius=r, normal=n, center_via_plane=_centre_via_plane(Z), blade=Z)
    Pl = cga.plane_from_points(*tri["plane_key"])  # (2.77)
    n, d = cga.plane_normal_distance(Pl)
    c, r, _ = cga.circle_center_radius(cga.circle_from_points(*tri["plane_key"]))
    out["plane"] = ScenePlane(normal=n, distance=d, center=c, radius=r, blade=Pl)
    S = cga.sphere_from_points(*tri["sphere_key"])  # (2.75)
    c, r = cga.sphere_center_radius(S)
    out["sphere"] = SceneSphere(center=c, radius=r, blade=S)
    return out
