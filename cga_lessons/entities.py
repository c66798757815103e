"""Conformal entities of table 2.1 and their properties (section 2.4).

Naming follows the thesis: the *dual* form of an entity is the outer product
of points (``a ^ b ^ c ^ d`` for a sphere, 2.75), the *standard* form is its
dual ``X = X* Ic`` (vectors for spheres and planes, 2.72, 2.89).  Functions
that read an entity accept either form and tell them apart by grade.

Every function takes NumPy points of shape (3,) or (N, 3) (a batch) or three
SymPy expressions, and returns NumPy at the Euclidean edge.
"""

from __future__ import annotations

import numpy as np

from .algebra import DegenerateGeometryError, InvalidInputError, Multivector, _is_sympy
from .model import (
    IE,
    E,
    Ic,
    _any_sym,
    _check_points,
    down,
    einf,
    ep,
    euclidean,
    exact_constants,
    normalize_point,
    up,
    vector,
)

__all__ = [
    "point_pair",
    "point_pair_endpoints",
    "point_pair_sphere",
    "sphere",
    "sphere_from_points",
    "sphere_center_radius",
    "point_sphere_side",
    "plane",
    "plane_from_points",
    "plane_normal_distance",
    "line_from_points",
    "normalize_line",
    "line_direction",
    "line_moment",
    "line_closest_point",
    "point_line_distance",
    "circle_from_points",
    "circle_center_radius",
    "circle_plane",
    "standard_form",
    "dual_form",
]


def _c(X: Multivector):
    """Constants matching the coefficient kind of X (exact for SymPy)."""
    if _any_sym(X):
        return exact_constants()
    return {"einf": einf, "E": E, "IE": IE, "Ic": Ic, "ep": ep}


def _scale(X: Multivector):
    """Largest absolute coefficient (per batch element)."""
    if not X._c:
        return 0.0
    return np.max(np.abs(np.stack([np.asarray(v, dtype=float) for v in X._c.values()])), axis=0)


def _require_nonzero(X: Multivector, ref, func: str, what: str, rtol: float = 1e-10):
    """Raise when X is zero relative to ``ref`` (the size of its factors)."""
    if _any_sym(X):
        if not X.simplify()._c:
            raise DegenerateGeometryError(f"{func}: {what}")
        return
    if np.any(_scale(X) <= rtol * np.maximum(ref, 1e-300)):
        raise DegenerateGeometryError(f"{func}: {what}")


def _grade_of(X: Multivector, func: str, allowed: tuple[int, ...]) -> int:
    if not isinstance(X, Multivector):
        raise InvalidInputError(f"{func}: expected a Multivector, got {type(X).__name__}")
    gs = X.grades_present()
    if len(gs) != 1 or gs[0] not in allowed:
        raise InvalidInputError(f"{func}: expected a blade of grade {' or '.join(map(str, allowed))}, got grades {gs}")
    return gs[0]


def standard_form(X: Multivector) -> Multivector:
    """The standard form X = X* Ic of a dual-form entity (inverse of 2.31)."""
    return X * _c(X)["Ic"]


def dual_form(X: Multivector) -> Multivector:
    """The dual X* = X Ic^-1 (2.31)."""
    return X * (-_c(X)["Ic"])  # Ic^2 = -1, so Ic^-1 = -Ic


def _span(*pts) -> float:
    """Scale of a set of Euclidean points (for relative degeneracy tests)."""
    return max(1.0, *(float(np.max(np.abs(p))) for p in pts if not isinstance(p, list)))


# --------------------------------------------------------------- point pairs
def point_pair(a, b) -> Multivector:
    """Point pair in dual form PP* = a ^ b of two conformal points, Eq. (2.68).

    Raises :class:`DegenerateGeometryError` when a and b coincide.
    """
    A, B = up(a), up(b)
    PP = A ^ B
    pa, _ = _check_points(a, "point_pair", "a")
    pb, _ = _check_points(b, "point_pair", "b")
    if not _any_sym(PP):
        d = np.linalg.norm(np.asarray(pa) - np.asarray(pb), axis=-1)
        if np.any(d <= 1e-12 * np.maximum(1.0, np.maximum(np.abs(pa).max(axis=-1), np.abs(pb).max(axis=-1)))):
            raise DegenerateGeometryError("point_pair: the two points coincide")
    else:
        _require_nonzero(PP, 1.0, "point_pair", "the two points coincide")
    return PP


def point_pair_endpoints(PP: Multivector, min_separation: float | None = None):
    """The two points of a point pair, Eqs. (2.131)-(2.133).

    With B = PP* (grade 2; a grade-3 standard form is dualised first)::

        p1 = (B - sqrt(B B)) (B . e)^-1        numerator p1 p2, (2.132)
        p2 = (B + sqrt(B B)) (B . e)^-1        numerator -p2 p1, (2.133)

    The division is right multiplication by the inverse of the vector
    B . e (2.19).  For ``PP = point_pair(a, b)`` this returns ``(a, b)`` in
    that order; the orientation matters: ``-PP`` (that is ``b ^ a``) returns
    ``(b, a)``.

    Parameters
    ----------
    PP : Multivector
        Point pair, dual form (grade 2) or standard form (grade 3); a batch is fine.
    min_separation : float, optional
        Guard against the loss of accuracy of (2.131) for nearly coincident
        points.  Measured for points near |x| = 4: endpoint error about 2e-12 at
        separation 0.1, 2e-10 at 1e-2, 2e-8 at 1e-3, 2e-6 at 1e-4 (it grows like
        eps (1 + |x|^2)^2 / separation), and below about 1e-4 the separation
        estimated from B B is itself swamped by round-off.  Default guard
        ``2e-5 * (1 + |B| / |B . e|)``, where ``|B| / |B . e|`` grows like
        ``(1 + |x|^2)/2``.  Pass ``min_separation=0`` to disable it.

    Returns
    -------
    (p1, p2) : arrays of shape (3,) or (N, 3); 3x1 SymPy matrices when symbolic.

    Raises
    ------
    DegenerateGeometryError
        For an imaginary point pair (B B < 0), a single (tangent) point, or
        points closer than ``min_separation``.
    """
    g = _grade_of(PP, "point_pair_endpoints", (2, 3))
    B = PP if g == 2 else dual_form(PP)
    c = _c(B)
    BB = (B * B).scalar()
    Be = B | c["einf"]
    if _any_sym(B):
        import sympy

        root = sympy.sqrt(sympy.factor(sympy.simplify(BB)))
        inv = Be.inv()
        return down((B - root) * inv), down((B + root) * inv)
    BB = np.asarray(BB, dtype=float)
    Be2 = np.asarray((Be * Be).scalar(), dtype=float)
    if np.any(Be2 <= 1e-300):
        raise DegenerateGeometryError("point_pair_endpoints: B . e = 0, the point pair has no finite points")
    # Signed squared separation of the two points: B B = w^2 (d^2/2)^2 and
    # (B . e)^2 = w^2 d^2, so d^2 = 4 (B B) / (B . e)^2 ... as d^4 / d^2; we use
    # sep = 2 sqrt|B B| / |B . e|.  The ratio |B| / |B . e| ~ 1 + |x|^2 sets the
    # scale of the round-off (the accuracy of 2.131 degrades like eps |x|^2 / d).
    sep = 2.0 * np.sqrt(np.abs(BB)) / np.sqrt(Be2)
    ratio = np.asarray(_scale(B), dtype=float) / np.sqrt(Be2)
    guard = min_separation if min_separation is not None else 2e-5 * (1.0 + ratio)
    imaginary = (BB < 0) & (sep > guard)
    if np.any(imaginary):
        raise DegenerateGeometryError("point_pair_endpoints: B B < 0, the point pair is imaginary (no real points)")
    if np.any(sep <= guard):
        raise DegenerateGeometryError(
            f"point_pair_endpoints: the points are {float(np.min(sep)):.3g} apart, below the accuracy guard "
            f"{float(np.min(guard)):.3g} of (2.131) (a tangent or nearly coincident pair)"
        )
    root = np.sqrt(BB)
    Be_inv = Be * (1.0 / Be2)  # vector inverse (2.19)
    p1 = down((B - (float(root) if root.ndim == 0 else root)) * Be_inv)
    p2 = down((B + (float(root) if root.ndim == 0 else root)) * Be_inv)
    return p1, p2


def point_pair_sphere(PP: Multivector) -> Multivector:
    """Smallest sphere through a point pair, S = PP* / (PP* ^ e), Eq. (2.134).

    Returns the normalised standard form (grade 1, ``S . e = -1``): centre
    the pair's midpoint, radius half their distance.
    """
    g = _grade_of(PP, "point_pair_sphere", (2, 3))
    B = PP if g == 2 else dual_form(PP)
    c = _c(B)
    S = (B * (B ^ c["einf"]).inv()).grade(1)
    return normalize_point(S, "point_pair_sphere")


# ------------------------------------------------------------------- spheres
def sphere(center, radius) -> Multivector:
    """Sphere s = p - rho^2 e / 2 in standard form, Eq. (2.72).

    ``center`` has shape (3,) or (N, 3); ``radius`` a scalar or (N,) array, >= 0.
    """
    P = up(center)
    if _any_sym(P) or _is_sympy(radius):
        return P - exact_constants()["einf"] * (radius**2 / 2)
    r = np.asarray(radius, dtype=float)
    if not np.all(np.isfinite(r)) or np.any(r < 0):
        raise InvalidInputError(f"sphere: radius must be finite and >= 0, got {radius!r}")
    return P - einf * (0.5 * (float(r) if r.ndim == 0 else r) ** 2)


def sphere_from_points(a, b, c, d) -> Multivector:
    """Sphere through four points in dual form s* = a ^ b ^ c ^ d, Eq. (2.75).

    Raises :class:`DegenerateGeometryError` when the points are coplanar
    (then the 4-blade is a plane or zero) or two of them coincide.
    """
    S = up(a) ^ up(b) ^ up(c) ^ up(d)
    if _any_sym(S):
        _require_nonzero(S, 1.0, "sphere_from_points", "the 4 points are coplanar, concyclic or coincident")
        return S
    s = standard_form(S)
    w = np.abs(np.asarray((s | einf).scalar(), dtype=float))
    ref = np.maximum(_scale(s), 1e-300)
    pts = [np.asarray(p, dtype=float) for p in (a, b, c, d)]
    span = max(1.0, max(float(np.max(np.abs(p))) for p in pts))
    if np.any(w <= 1e-10 * ref / span) or np.any(_scale(S) <= 1e-14 * span**4):
        raise DegenerateGeometryError("sphere_from_points: the 4 points are coplanar (or two coincide)")
    return S


def sphere_center_radius(S: Multivector):
    """Centre and radius of a sphere, Eqs. (2.73), (2.115)-(2.117).

    Accepts the standard form (grade 1) or the dual form (grade 4).
    Normalises with (2.115), takes the centre as ``(s ^ E) E`` (2.116) and
    the radius from ``s^2 = rho^2`` (2.73).

    Returns
    -------
    center : array (3,) or (N, 3)
    radius : float or array (N,)

    Raises
    ------
    DegenerateGeometryError
        For a plane (``s . e = 0``) or an imaginary sphere (``s^2 < 0``).
    """
    g = _grade_of(S, "sphere_center_radius", (1, 4))
    s = S if g == 1 else standard_form(S)
    s = normalize_point(s, "sphere_center_radius")
    c = _c(s)
    center = euclidean((s ^ c["E"]) * c["E"])
    r2 = (s * s).scalar()
    if _any_sym(s):
        import sympy

        return center, sympy.sqrt(sympy.simplify(r2))
    r2 = np.asarray(r2, dtype=float)
    tol = 1e-12 * (1.0 + np.sum(center * center, axis=-1))
    if np.any(r2 < -tol):
        raise DegenerateGeometryError("sphere_center_radius: s^2 < 0, the sphere is imaginary")
    r = np.sqrt(np.maximum(r2, 0.0))
    return center, (float(r) if r.ndim == 0 else r)


def point_sphere_side(x, S: Multivector, atol: float = 1e-9):
    """Which side of a sphere a point lies on, Eq. (2.118).

    Returns +1 inside, 0 on (|x . s| <= atol, in units of length^2), -1 outside,
    from the sign of ``x . s = (rho^2 - |x - p|^2)/2`` with both normalised.
    """
    X = up(x) if not isinstance(x, Multivector) else normalize_point(x, "point_sphere_side")
    g = _grade_of(S, "point_sphere_side", (1, 4))
    s = normalize_point(S if g == 1 else standard_form(S), "point_sphere_side")
    v = np.asarray((X | s).scalar(), dtype=float)
    out = np.where(np.abs(v) <= atol, 0, np.sign(v)).astype(int)
    return int(out) if out.ndim == 0 else out


# -------------------------------------------------------------------- planes
def plane(normal, distance) -> Multivector:
    """Plane P = n + delta e in standard form, Eq. (2.89).

    ``normal`` is normalised to unit length; ``distance`` is the signed
    distance delta from the origin along it.
    """
    nv, sym = _check_points(normal, "plane", "normal")
    if sym:
        return vector(nv) + exact_constants()["einf"] * distance
    norm = np.linalg.norm(nv, axis=-1)
    if np.any(norm == 0):
        raise DegenerateGeometryError("plane: the normal is the zero vector")
    d = np.asarray(distance, dtype=float)
    if not np.all(np.isfinite(d)):
        raise InvalidInputError("plane: distance contains NaN or inf")
    n = nv / (norm[..., None] if nv.ndim == 2 else norm)
    return vector(n) + einf * (float(d) if d.ndim == 0 else d)


def plane_from_points(a, b, c) -> Multivector:
    """Plane through three points in dual form P* = e ^ a ^ b ^ c, Eq. (2.77).

    Raises :class:`DegenerateGeometryError` when the points are collinear.
    """
    A, B, C = up(a), up(b), up(c)
    einf_ = _c(A)["einf"]
    P = einf_ ^ A ^ B ^ C
    if _any_sym(P):
        _require_nonzero(P, 1.0, "plane_from_points", "the 3 points are collinear")
        return P
    pa, pb, pc = (np.asarray(p, dtype=float) for p in (a, b, c))
    area = np.linalg.norm(np.cross(pb - pa, pc - pa), axis=-1)
    span = max(np.max(np.abs(pb - pa)), np.max(np.abs(pc - pa)), 1e-300)
    if np.any(area <= 1e-12 * span**2):
        raise DegenerateGeometryError("plane_from_points: the 3 points are collinear (or coincide)")
    return P


def plane_normal_distance(P: Multivector):
    """Unit normal n and signed distance delta of a plane (inverse of 2.89).

    Accepts the standard form (grade 1, ``n + delta e``) or the dual form
    (grade 4, 2.77).  For ``plane_from_points(a, b, c)`` the normal is along
    ``(b - a) x (c - a)``.
    """
    g = _grade_of(P, "plane_normal_distance", (1, 4))
    p = P if g == 1 else standard_form(P)
    if g == 4:
        p = -p  # e ^ a ^ b ^ c (2.77) dualises to -(N + d e) with N along (b-a)x(c-a)
    n = euclidean(p)
    norm = np.linalg.norm(n, axis=-1)
    if np.any(norm <= 1e-300):
        raise DegenerateGeometryError("plane_normal_distance: the input has no normal (not a plane)")
    # delta is the e coefficient: P = n + delta e, and e = e- + e+ carries delta on both
    delta = np.asarray(p[16], dtype=float) if 16 in p._c else np.zeros(norm.shape)
    scale = norm[..., None] if n.ndim == 2 else norm
    out_d = delta / norm
    return n / scale, (float(out_d) if np.ndim(out_d) == 0 else out_d)


# --------------------------------------------------------------------- lines
def line_from_points(a, b) -> Multivector:
    """Line through two points in dual form L* = e ^ a ^ b, Eq. (2.81).

    Raises :class:`DegenerateGeometryError` when a and b coincide.
    """
    A, B = up(a), up(b)
    L = _c(A)["einf"] ^ A ^ B
    if _any_sym(L):
        _require_nonzero(L, 1.0, "line_from_points", "the two points coincide")
        return L
    pa, pb = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = np.linalg.norm(pb - pa, axis=-1)
    if np.any(d <= 1e-12 * np.maximum(1.0, np.maximum(np.abs(pa).max(axis=-1), np.abs(pb).max(axis=-1)))):
        raise DegenerateGeometryError("line_from_points: the two points coincide")
    return L


def _as_dual_line(L: Multivector, func: str) -> Multivector:
    g = _grade_of(L, func, (2, 3))
    return L if g == 3 else dual_form(L)


def normalize_line(L: Multivector) -> Multivector:
    """Unit line L* / sqrt(L* L*), Eq. (2.126) (L* L* = |a - b|^2 by 2.125).

    Accepts the dual form (grade 3) or the standard form (grade 2) and
    returns the same form.
    """
    g = _grade_of(L, "normalize_line", (2, 3))
    Ld = L if g == 3 else dual_form(L)
    sq = (Ld * Ld).scalar()
    if _any_sym(Ld):
        import sympy

        return L / sympy.sqrt(sq)
    sq = np.asarray(sq, dtype=float)
    if np.any(sq <= 1e-300):
        raise DegenerateGeometryError("normalize_line: L* L* <= 0, not a line (a circle or zero)")
    k = np.sqrt(sq)
    return L / (float(k) if k.ndim == 0 else k)


def line_direction(L: Multivector):
    """Unit direction r = L* . E of a line, Eq. (2.127) (L normalised first, 2.126).

    For ``line_from_points(a, b)`` this is ``(b - a)/|b - a|``.
    """
    Ln = normalize_line(_as_dual_line(L, "line_direction"))
    return euclidean(Ln | _c(Ln)["E"])


def line_moment(L: Multivector):
    """Moment vector m = e+ . (L* Ic^-1) = -e+ . L of a unit line, Eq. (2.128), corrected.

    For the unit line through a with direction r this is the Pluecker moment
    ``m = a x r``.  The printed ``m = e+ L`` (a geometric product, with the
    standard form L = L* Ic of 2.31) gives -(a x r) as its vector part and
    adds other grades; see the erratum in the registry.
    """
    Ln = normalize_line(_as_dual_line(L, "line_moment"))
    return -euclidean(_c(Ln)["ep"] | standard_form(Ln))


def line_closest_point(L: Multivector):
    """Point of the line closest to the origin, p = -r . M with M = m I_E, Eq. (2.129)."""
    r = line_direction(L)
    m = line_moment(L)
    if isinstance(r, np.ndarray) and r.dtype != object:
        return -euclidean(vector(r) | (vector(m) * IE))
    c = exact_constants()
    return -euclidean(vector(list(r)) | (vector(list(m)) * c["IE"])).applyfunc(lambda v: v.simplify())


def point_line_distance(x, L: Multivector):
    """Distance from point(s) x to a line, Eq. (2.130).

    ``rho^2 = ((L* . x) / (L* . x . e))^2``: L* . x is the circle through x
    centred on the line, L* . x . e its plane; their quotient squared is the
    squared radius.  Returns a float (or an (N,) array); 0 for points on the line.
    """
    Ln = normalize_line(_as_dual_line(L, "point_line_distance"))
    X = up(x) if not isinstance(x, Multivector) else normalize_point(x, "point_line_distance")
    z = Ln | X
    c = _c(z) if z._c else _c(Ln)
    P = z | c["einf"]
    if _any_sym(z):
        import sympy

        q = z * P.inv()
        return sympy.sqrt(sympy.simplify((q * q).scalar()))
    P2 = np.asarray((P * P).scalar(), dtype=float)
    on_line = P2 <= 1e-300
    if not z._c:
        return 0.0 if X.shape == () else np.zeros(X.shape)
    Pinv = P * (1.0 / np.where(on_line, 1.0, P2))
    q = z * Pinv
    rho2 = np.asarray((q * q).scalar(), dtype=float)
    rho = np.sqrt(np.maximum(np.where(on_line, 0.0, rho2), 0.0))
    return float(rho) if rho.ndim == 0 else rho


# ------------------------------------------------------------------- circles
def circle_from_points(a, b, c) -> Multivector:
    """Circle through three points in dual form z* = a ^ b ^ c, Eq. (2.80).

    Raises :class:`DegenerateGeometryError` when the points are collinear
    (the blade would be a line) or coincide.
    """
    Z = up(a) ^ up(b) ^ up(c)
    if _any_sym(Z):
        _require_nonzero(Z, 1.0, "circle_from_points", "the 3 points are collinear or coincide")
        return Z
    pa, pb, pc = (np.asarray(p, dtype=float) for p in (a, b, c))
    area = np.linalg.norm(np.cross(pb - pa, pc - pa), axis=-1)
    span = max(np.max(np.abs(pb - pa)), np.max(np.abs(pc - pa)), 1e-300)
    if np.any(area <= 1e-12 * span**2):
        raise DegenerateGeometryError("circle_from_points: the 3 points are collinear (or coincide)")
    return Z


def circle_plane(Z: Multivector) -> Multivector:
    """Plane of a circle, P_z* = z* ^ e (dual form), Eq. (2.119)."""
    g = _grade_of(Z, "circle_plane", (2, 3))
    Zd = Z if g == 3 else dual_form(Z)
    return Zd ^ _c(Zd)["einf"]


def circle_center_radius(Z: Multivector):
    """Centre, radius and unit normal of a circle, Eqs. (2.119)-(2.124).

    Accepts the dual form z* = a ^ b ^ c (grade 3) or the standard form z
    (grade 2).  The sphere with the circle's centre and radius is
    ``s_z = (e . z) z`` (2.123, with z the standard form); its centre and
    radius come from :func:`sphere_center_radius`.  The radius agrees with the
    corrected (2.122), ``rho^2 = -z^2 / (e ^ z)^2``.

    Returns
    -------
    center : array (3,) or (N, 3)
    radius : float or (N,)
    normal : array (3,) or (N, 3), unit normal of the circle's plane (2.119),
        along (b - a) x (c - a) for ``circle_from_points(a, b, c)``.
    """
    g = _grade_of(Z, "circle_center_radius", (2, 3))
    z = Z if g == 2 else standard_form(Z)
    c = _c(z)
    s = ((c["einf"] | z) * z).grade(1)
    center, radius = sphere_center_radius(s)
    n, _ = plane_normal_distance(-circle_plane(z))  # z* ^ e = -(e ^ a ^ b ^ c)
    return center, radius, n
