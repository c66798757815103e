"""Lines and circles of table 2.1 and their properties (section 2.4): lines through two points (2.81), their
direction, moment, closest point and distance (2.125-2.130); circles through three points (2.80), their plane,
centre and radius (2.119-2.124).

The conventions (standard and dual forms, accuracy far from the origin) are those of
:mod:`cga_lessons.conformal.entities`; import all of them from :mod:`cga_lessons.conformal`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector, any_sympy

from . import entities_frame as _F
from .anchored import frame, from_points
from .entities import (
    constants_of,
    dual_form,
    euclid_point,
    exact_up,
    grade_of,
    plane_normal_distance,
    require_nonzero,
    sphere_center_radius,
    standard_form,
)
from .entities_read import read_circle, read_line
from .model import exact_constants
from .points import euclidean, normalize_point, up, vector

__all__ = [
    "line_from_points",
    "normalize_line",
    "line_direction",
    "line_moment",
    "line_closest_point",
    "point_line_distance",
    "circle_from_points",
    "circle_center_radius",
    "circle_plane",
]


# --------------------------------------------------------------------- lines
def line_from_points(a, b) -> Multivector:
    """Line through two points in dual form L* = e ^ a ^ b, Eq. (2.81).

    In floats: the closed form ``(q x d) ^ e + d E`` (2.81, e M + r E) with
    ``d = b - a`` and q the point nearer the origin.  Raises
    :class:`DegenerateGeometryError` when a and b coincide.
    """
    pts = _F.points("line_from_points", "a, b", a, b)
    if pts is None:
        L = exact_constants().einf ^ exact_up(a) ^ exact_up(b)
        return require_nonzero(L, "line_from_points", "a, b", "the two points coincide")
    return from_points(_F.line, "line_from_points", *pts)


def as_dual_line(L: Multivector, func: str) -> Multivector:
    g = grade_of(L, func, (2, 3), "L")
    return L if g == 3 else dual_form(L)


def normalize_line(L: Multivector) -> Multivector:
    """Unit line L* / sqrt(L* L*), Eq. (2.126) (L* L* = |a - b|^2 by 2.125).

    Accepts the dual form (grade 3) or the standard form (grade 2) and
    returns the same form.  In floats ``sqrt(L* L*)`` is read as the length of
    the E part d (2.81), not summed from the squares of the coefficients.
    """
    Ld = as_dual_line(L, "normalize_line")
    if any_sympy(Ld):
        import sympy

        return L / sympy.sqrt((Ld * Ld).scalar())
    d, _ = read_line(Ld, "normalize_line", "L")
    return L / _F.out(_F.norm(d))


def line_direction(L: Multivector):
    """Unit direction r = L* . E of a line, Eq. (2.127) (L normalised first, 2.126).

    For ``line_from_points(a, b)`` this is ``(b - a)/|b - a|``.  Raises
    :class:`InvalidInputError` for a circle (or any round).
    """
    Ld = as_dual_line(L, "line_direction")
    if any_sympy(Ld):
        Ln = normalize_line(L)
        return euclidean(as_dual_line(Ln, "line_direction") | constants_of(Ln).E)
    d, _ = read_line(Ld, "line_direction", "L")
    return d / _F.norm(d)[..., None]


def line_moment(L: Multivector):
    """Moment vector m = e+ . (L* Ic^-1) = -e+ . L of a unit line, Eq. (2.128), corrected.

    For the unit line through a with direction r this is the Pluecker moment
    ``m = a x r``.  The printed ``m = e+ L`` (a geometric product, with the
    standard form L = L* Ic of 2.31) gives -(a x r) as its vector part and
    adds other grades; see the erratum in the registry.  In floats: the e
    part of L* (``a x d``) over |d|.
    """
    Ld = as_dual_line(L, "line_moment")
    if any_sympy(Ld):
        Ln = normalize_line(Ld)
        return -euclidean(constants_of(Ln).ep | standard_form(Ln))
    d, mu = read_line(Ld, "line_moment", "L")
    return mu / _F.norm(d)[..., None]


def line_closest_point(L: Multivector):
    """Point of the line closest to the origin, p = -r . M with M = m I_E, Eq. (2.129) (= r x m)."""
    Ld = as_dual_line(L, "line_closest_point")
    if not any_sympy(Ld):
        d, mu = read_line(Ld, "line_closest_point", "L")
        return np.cross(d, mu) / _F.dot(d, d)[..., None]
    r, m = line_direction(L), line_moment(L)
    c = exact_constants()
    return -euclidean(vector(list(r)) | (vector(list(m)) * c.IE)).applyfunc(lambda v: v.simplify())


def point_line_distance(x, L: Multivector):
    """Distance from point(s) x to a line, Eq. (2.130).

    ``rho^2 = ((L* . x) / (L* . x . e))^2``: L* . x is the circle through x
    centred on the line, L* . x . e its plane; their quotient squared is the
    squared radius.  SymPy input takes that formula; floats take the same
    distance at the point, ``|(x - p0) x r|`` with p0 the line's closest point
    to the origin (2.129) and r its direction (2.127), which loses nothing to
    the distance from the origin (the formula above loses eps |x|^2 / rho);
    for a line of :func:`line_from_points` (anchored at one of its points f,
    :mod:`~cga_lessons.conformal.anchored`) ``x - f`` first and p0 about f, so
    that the distance keeps its relative accuracy even where it is far below
    the coordinates' own resolution.
    Returns a float (or an (N,) array); 0 for points on the line.
    """
    Ld = as_dual_line(L, "point_line_distance")
    xe = euclid_point(x, "point_line_distance")
    if not (xe is None or any_sympy(Ld)):
        f, loc = frame(Ld)
        d, mu = read_line(loc, "point_line_distance", "L")
        nd = _F.norm(d)
        p0 = np.cross(d, mu) / (nd * nd)[..., None]
        return _F.out(_F.norm(np.cross((xe if f is None else xe - f) - p0, d / nd[..., None])))
    import sympy

    Ln = normalize_line(Ld)
    X = up(x) if not isinstance(x, Multivector) else normalize_point(x, "point_line_distance")
    z = Ln | X
    q = z * (z | constants_of(Ln).einf).inv()
    return sympy.sqrt(sympy.simplify((q * q).scalar()))


# ------------------------------------------------------------------- circles
def circle_from_points(a, b, c) -> Multivector:
    """Circle through three points in dual form z* = a ^ b ^ c, Eq. (2.80).

    In floats: from the circumcentre p, rho^2 and ``N = (b - a) x (c - a)``
    in closed form, ``(p . N) e123 + xi ^ e + N ^ e0 + (p x N) E`` with
    ``xi = (rho^2 - p^2) N/2 + (p . N) p`` (bivectors written as their dual
    vectors), its e0 part N stored exactly.  Raises
    :class:`DegenerateGeometryError` when the points are collinear (the blade
    would be a line) or coincide.
    """
    pts = _F.points("circle_from_points", "a, b, c", a, b, c)
    if pts is None:
        Z = require_nonzero(
            exact_up(a) ^ exact_up(b) ^ exact_up(c),
            "circle_from_points",
            "a, b, c",
            "the 3 points are collinear or coincide",
        )
        if not (Z ^ exact_constants().einf).simplify().coeffs:  # z* ^ e = 0: a flat, the points are collinear
            raise checks.degenerate("circle_from_points", "a, b, c", "the 3 points are collinear (a line, no circle)")
        return Z
    return from_points(_F.circle, "circle_from_points", *pts)


def circle_plane(Z: Multivector) -> Multivector:
    """Plane of a circle, P_z* = z* ^ e (dual form), Eq. (2.119).

    Accepts the dual form (grade 3) or the standard form (grade 2) of a real circle; refuses a line (no e0 part,
    ``z* ^ e = 0``) and an imaginary circle (such as a point pair read as a circle), as
    :func:`circle_center_radius` does.
    """
    Zd = _circle_dual(Z, "circle_plane")
    return Zd ^ constants_of(Zd).einf


def _circle_dual(Z: Multivector, func: str) -> Multivector:
    """The dual form of a circle, checked to be one (in floats: a round with rho^2 >= 0)."""
    g = grade_of(Z, func, (2, 3), "Z")
    Zd = Z if g == 3 else dual_form(Z)
    if not any_sympy(Zd):
        _, r2, _, tol = read_circle(Zd, func, "Z")
        if np.any(r2 < -(tol + 1e-12)):
            raise checks.degenerate(func, "Z", "rho^2 < 0, the circle is imaginary")
    return Zd


def circle_center_radius(Z: Multivector):
    """Centre, radius and unit normal of a circle, Eqs. (2.119)-(2.124).

    Accepts the dual form z* = a ^ b ^ c (grade 3) or the standard form z
    (grade 2).  The sphere with the circle's centre and radius is
    ``s_z = (e . z) z`` (2.123, with z the standard form); its centre and
    radius come from :func:`sphere_center_radius`.  The radius agrees with the
    corrected (2.122), ``rho^2 = -z^2 / (e ^ z)^2``.  SymPy input takes that
    route; floats read the same centre and radius from the null parts of z*
    (see :func:`circle_from_points`): ``p = ((p . N) N + N x (p x N)) / |N|^2``
    without cancellation, rho^2 to about ``8 eps (|p|^2 + rho^2 + 1)``
    absolute and the normal to ``~eps (|p|^2 + 1)``, p about the anchor of an
    anchored circle (``circle_from_points``'s: exact at any distance), about
    the origin for a plain blade (limits of its storage).

    Returns
    -------
    center : array (3,) or (N, 3)
    radius : float or (N,)
    normal : array (3,) or (N, 3), unit normal of the circle's plane (2.119),
        along (b - a) x (c - a) for ``circle_from_points(a, b, c)``.

    Raises
    ------
    DegenerateGeometryError
        For a line (``z* ^ e = 0``) or an imaginary circle.
    """
    g = grade_of(Z, "circle_center_radius", (2, 3), "Z")
    Zd = Z if g == 3 else dual_form(Z)
    if any_sympy(Zd):
        z = standard_form(Zd)
        center, radius = sphere_center_radius(((constants_of(z).einf | z) * z).grade(1))
        n, _ = plane_normal_distance(-circle_plane(z))  # z* ^ e = -(e ^ a ^ b ^ c)
        return center, radius, n
    p, r2, n, tol = read_circle(Zd, "circle_center_radius", "Z")
    if np.any(r2 < -(tol + 1e-12)):
        raise checks.degenerate("circle_center_radius", "Z", "rho^2 < 0, the circle is imaginary")
    return p, _F.out(np.sqrt(np.maximum(r2, 0.0))), n
