"""Conformal entities of table 2.1 and their properties (section 2.4).

Naming follows the thesis: the *dual* form of an entity is the outer product
of points (``a ^ b ^ c ^ d`` for a sphere, 2.75), the *standard* form is its
dual ``X = X* Ic`` (vectors for spheres and planes, 2.72, 2.89).  Functions
that read an entity accept either form and tell them apart by grade; they
check the kind too (a circle is not a line, a sphere is not a plane).

Every function takes NumPy points of shape (3,) or (N, 3) (a batch) or three
SymPy expressions, and returns NumPy at the Euclidean edge.  SymPy input takes
the printed formulas, exactly.

**Accuracy far from the origin** (:mod:`cga_lessons.conformal.entities_frame`,
:mod:`cga_lessons.conformal.anchored`).  Float constructors build each shape
in closed form at its points, and the rounds and lines carry it besides about
a point of the data (an ``Anchored`` entity): their properties are read there,
to a few eps of their size at any distance (positions plus the rounding of
their own coordinates).  Products, sums, scaling, duals, meet and intersect of
anchored entities (with each other, numbers, or what translations leave alone:
e, Ic) carry the frame too (:mod:`cga_lessons.conformal.anchored_ops`).  A
plain blade (the global coefficients alone, or a product with a point, e0, a
rotor) holds a round's rho^2 only to ``~eps (|c|^2 + size^2 + 1)`` absolute at
distance |c| (a unit sphere: 1e-10 at 1 km, 1e-4 at 1000 km), its e0 part (a
circle's normal, a pair's a - b) to ``~eps (|c|^2 + 1)`` relative.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector, any_sympy, is_sympy

from . import entities_frame as _F
from .anchored import frame, from_points, pair_about_an_end, sphere_at, times_invariant
from .entities_read import pair_points, read_pair, read_plane, read_sphere
from .model import CONSTANTS, G41, ModelConstants, einf, exact_constants
from .multivector_checks import COORD_LIMIT, check_points, multivector
from .points import euclidean, normalize_point, read_point, up, vector

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
    "standard_form",
    "dual_form",
]


def constants_of(X: Multivector) -> ModelConstants:
    """The constants of G(4,1) matching the coefficient kind of X: exact for SymPy (:func:`exact_constants`), else
    the float ones (:data:`~cga_lessons.conformal.model.CONSTANTS`)."""
    if any_sympy(X):
        return exact_constants()
    return CONSTANTS


def require_nonzero(X: Multivector, func: str, args: str, what: str) -> Multivector:
    """X, unless it simplifies to zero (symbolic input)."""
    if not X.simplify()._c:
        raise checks.degenerate(func, args, what)
    return X


def grade_of(X: Multivector, func: str, allowed: tuple[int, ...], arg: str | None = None) -> int:
    """The grade of ``X``, a finite multivector of G(4,1) with one grade among ``allowed``; else a clear error.

    ``arg`` names the argument in the message (give it: without it the message says "the entity").
    """
    name = arg or "the entity"
    multivector(X, func, name, nonzero=False)
    gs = X.grades_present()
    if len(gs) != 1 or gs[0] not in allowed:
        raise checks.fail(func, name, f"expected a blade of grade {' or '.join(map(str, allowed))}, got grades {gs}")
    return gs[0]


def standard_form(X: Multivector) -> Multivector:
    """The standard form X = X* Ic of a dual-form entity (inverse of 2.31).

    An anchored entity stays anchored (:mod:`~cga_lessons.conformal.anchored`): Ic commutes with the translator
    (2.100), so the local blade is dualised likewise.
    """
    multivector(X, "standard_form", "X", nonzero=False)
    return times_invariant(X, constants_of(X).Ic)


def dual_form(X: Multivector) -> Multivector:
    """The dual X* = X Ic^-1 (2.31); an anchored entity stays anchored, as in :func:`standard_form`."""
    multivector(X, "dual_form", "X", nonzero=False)
    return times_invariant(X, -constants_of(X).Ic)  # Ic^2 = -1, so Ic^-1 = -Ic


def _per_item(value, func: str, name: str, batch: tuple, *, low: float | None = None):
    """A number (float, or SymPy) or one per item: an (N,) array, N the length of ``batch`` = (its name, the
    validated array) when that is a batch (N, 3)."""
    if is_sympy(value):
        return value
    if isinstance(value, (list, tuple)) or (isinstance(value, np.ndarray) and value.ndim > 0):
        a = checks.array(value, func, name, (None,))
        if batch[1] is not None and np.ndim(batch[1]) == 2:
            checks.same_length(func, **{batch[0]: batch[1], name: a})
        if low is not None and np.any(a < low):
            raise checks.fail(func, name, f"must be >= {low}, got {float(np.min(a)):.3g}")
        return a
    return checks.real(value, func, name, low=low)


def euclid_point(x, func: str):
    """Float coordinates of x (Euclidean, or a conformal point); None when symbolic."""
    if isinstance(x, Multivector):
        return None if any_sympy(x) else read_point(x, func, "x")
    pts = _F.points(func, "x", x)
    return None if pts is None else pts[0]


def exact_up(x) -> Multivector:
    """up(x) of a point given with SymPy entries, every entry made exact (ints as integers, floats as the simplest
    rational that rounds to them), so that one float among symbols does not turn the result into floats."""
    import sympy

    if isinstance(x, Multivector):
        return up(x)  # up raises the usual error
    vals = list(x) if not isinstance(x, sympy.MatrixBase) else [x[i] for i in range(len(x))]
    return up([v if is_sympy(v) else sympy.nsimplify(v, rational=True) for v in vals])


# --------------------------------------------------------------- point pairs
def point_pair(a, b, frame: bool = True) -> Multivector:
    """Point pair in dual form PP* = a ^ b of two conformal points, Eq. (2.68).

    Floats: the closed form about the midpoint (or the end nearer the
    origin), its e0 part ``a - b`` put on the grid of its e+/e- coefficients
    (a change of ``~eps (|m|^2 + 1)`` relative), anchored at the end nearer
    the origin (exact there; ``frame=False``: the plain blade alone, which
    costs less and holds everything near the origin).  Raises
    :class:`DegenerateGeometryError` when a and b coincide.
    """
    frame = checks.flag(frame, "point_pair", "frame")
    pts = _F.points("point_pair", "a, b", a, b)
    if pts is None:
        return require_nonzero(exact_up(a) ^ exact_up(b), "point_pair", "a, b", "the two points coincide")
    if not frame:
        return _F.point_pair(*pts, "point_pair")
    return from_points(_F.point_pair, "point_pair", *pts, local=pair_about_an_end)


def point_pair_endpoints(PP: Multivector, min_separation: float | None = None):
    """The two points of a point pair, Eqs. (2.131)-(2.133).

    With B = PP* (grade 2; a grade-3 standard form is dualised first)::

        p1 = (B - sqrt(B B)) (B . e)^-1        numerator p1 p2, (2.132)
        p2 = (B + sqrt(B B)) (B . e)^-1        numerator -p2 p1, (2.133)

    For ``PP = point_pair(a, b)`` this returns ``(a, b)`` in that order; the
    orientation matters: ``-PP`` (that is ``b ^ a``) returns ``(b, a)``.
    SymPy input takes (2.131) as printed; floats the same points from the
    null parts of B, with Y = k (a - b) = B . e: the midpoint m from
    ``Y . m`` and ``Y x m`` (no cancellation), the half separation^2
    ``h^2 = 2 X . Y / |Y|^2 + m_par^2 - m_perp^2`` (X the e part; the
    cancellation of ``B B``, a difference of |m|^2-sized terms).

    Parameters
    ----------
    PP : Multivector
        Point pair, dual form (grade 2) or standard form (grade 3); a batch is fine.
    min_separation : float, optional
        Refuse pairs closer than this.  Default: the separation resolved to
        ``entities_frame.PAIR_RTOL`` = 1e-6 of itself, ``4 |m| sqrt(eps / 1e-6)``
        (h^2 carries a round-off of ``8 eps (|m|^2 + h^2)``), m the midpoint
        about the anchor of ``point_pair``'s pairs (never refused, exact), about
        the origin for a plain blade (whose ends also carry the storage limit
        of a - b, ``~eps (|m|^2 + 1) (s + 1/s)`` for a separation s, and the
        round-off of the products that made it).  0 disables the guard.

    Returns
    -------
    (p1, p2) : arrays of shape (3,) or (N, 3); 3x1 SymPy matrices when symbolic.

    Raises
    ------
    DegenerateGeometryError
        For an imaginary point pair (B B < 0), a single (tangent) point, or
        points closer than the guard (the message gives both numbers).
    """
    g = grade_of(PP, "point_pair_endpoints", (2, 3), "PP")
    if min_separation is not None:
        min_separation = checks.real(min_separation, "point_pair_endpoints", "min_separation", low=0)
    B = PP if g == 2 else dual_form(PP)
    if any_sympy(B):
        import sympy

        c = constants_of(B)
        root = sympy.sqrt(sympy.factor(sympy.simplify((B * B).scalar())))
        inv = (B | c.einf).inv()

        def endpoint(X):  # (2.131) is a vector: the other grades vanish once simplified
            X = X.simplify()
            rest = [b for b, v in X.coeffs.items() if G41.grades[b] != 1 and sympy.simplify(v) != 0]
            if rest:
                raise checks.degenerate(
                    "point_pair_endpoints",
                    "PP",
                    f"(2.131) did not simplify to a vector (blades {rest}); is the pair real (PP^2 > 0)?",
                )
            p = read_point(X.grade(1), "point_pair_endpoints", "PP")
            return p if isinstance(p, sympy.MatrixBase) else sympy.Matrix([sympy.nsimplify(float(v)) for v in p])

        return endpoint((B - root) * inv), endpoint((B + root) * inv)
    return pair_points(B, min_separation, "point_pair_endpoints", "PP")


def point_pair_sphere(PP: Multivector) -> Multivector:
    """Smallest sphere through a point pair, S = PP* / (PP* ^ e), Eq. (2.134).

    Returns the normalised standard form (grade 1, ``S . e = -1``): centre
    the pair's midpoint, radius half their distance.  Floats read the
    midpoint and h^2 as :func:`point_pair_endpoints` does (no guard), and
    refuse an imaginary pair (``B B < 0``, no real points; a circle's
    blade read as a pair is one).
    """
    g = grade_of(PP, "point_pair_sphere", (2, 3), "PP")
    B = PP if g == 2 else dual_form(PP)
    if any_sympy(B):
        S = (B * (B ^ constants_of(B).einf).inv()).grade(1)
        return normalize_point(S, "point_pair_sphere")
    f, loc = frame(B)
    m, h2, _, tol = read_pair(loc, "point_pair_sphere", "PP")
    if np.any(h2 < -(tol + 1e-12)):
        raise checks.degenerate("point_pair_sphere", "PP", "B B < 0, the point pair is imaginary (no real points)")
    if f is None:
        return _F.sphere_std(m, _F.dot(m, m) - h2, 1.0, "point_pair_sphere", "PP")
    return sphere_at(f, m, h2, "point_pair_sphere", "PP")  # anchored as the pair: exact at any distance


# ------------------------------------------------------------------- spheres
def sphere(center, radius, frame: bool = True) -> Multivector:
    """Sphere s = p - rho^2 e / 2 in standard form, Eq. (2.72).

    ``center`` has shape (3,) or (N, 3); ``radius`` a scalar or (N,) array, >= 0.
    In floats the weight 1 is stored exactly (``e- - e+`` is 1 to the bit;
    beyond |p| ~ 1e8 the smallest power of two that can be), anchored at p
    (``frame=False``: the plain blade alone, as :func:`point_pair`).
    """
    frame = checks.flag(frame, "sphere", "frame")
    pts = _F.points("sphere", "center", center)
    radius = _per_item(radius, "sphere", "radius", ("center", None if pts is None else pts[0]), low=0)
    if pts is None or is_sympy(radius):
        return up(center) - exact_constants().einf * (radius**2 / 2)
    r = np.asarray(
        checks.magnitude(radius, "sphere", "radius", limit=COORD_LIMIT, why="its square overflows a float"), dtype=float
    )
    p = pts[0]
    if not frame:
        return _F.sphere_std(p, _F.dot(p, p) - r * r, 1.0, "sphere", "center, radius")
    return sphere_at(p, 0.0 * p, r * r, "sphere", "center, radius")  # anchored at its centre


def sphere_from_points(a, b, c, d) -> Multivector:
    """Sphere through four points in dual form s* = a ^ b ^ c ^ d, Eq. (2.75).

    In floats: the circumcentre and the weight ``det[b - a, c - a, d - a]``
    (that of a ^ b ^ c ^ d) are computed at ``a``, the blade in closed form
    with its weight stored exactly; the scale equals that of the 4-blade up to
    a factor 1 + O(eps |p|^2).  Raises :class:`DegenerateGeometryError` when
    the points are coplanar (then the 4-blade is a plane or zero) or two of
    them coincide.
    """
    pts = _F.points("sphere_from_points", "a, b, c, d", a, b, c, d)
    if pts is None:
        S = exact_up(a) ^ exact_up(b) ^ exact_up(c) ^ exact_up(d)
        return require_nonzero(
            S, "sphere_from_points", "a, b, c, d", "the 4 points are coplanar, concyclic or coincident"
        )
    return dual_form(from_points(_F.sphere_from_points, "sphere_from_points", *pts))


def sphere_center_radius(S: Multivector):
    """Centre and radius of a sphere, Eqs. (2.73), (2.115)-(2.117).

    Accepts the standard form (grade 1) or the dual form (grade 4).
    Normalises with (2.115), takes the centre as ``(s ^ E) E`` (2.116) and
    the radius from ``s^2 = rho^2`` (2.73).  Floats: ``w = e- - e+`` (2.115),
    centre = Euclidean part / w (a few eps), ``rho^2 = |p|^2 - 2 s_e / w``,
    the factored ``s^2 / w^2`` (never the squares of the e+/e- coefficients),
    to about ``8 eps (|p|^2 + rho^2 + 1)`` absolute, p about the anchor of an
    anchored sphere (exact), about the origin for a plain blade.

    Returns
    -------
    center : array (3,) or (N, 3)
    radius : float or array (N,)

    Raises
    ------
    DegenerateGeometryError
        For a plane (``s . e = 0``) or an imaginary sphere (``s^2 < 0``).
    """
    g = grade_of(S, "sphere_center_radius", (1, 4), "S")
    s = S if g == 1 else standard_form(S)
    if any_sympy(s):
        import sympy

        s = normalize_point(s, "sphere_center_radius")
        c = constants_of(s)
        return euclidean((s ^ c.E) * c.E), sympy.sqrt(sympy.simplify((s * s).scalar()))
    p, r2, _, tol = read_sphere(s, "sphere_center_radius", "S")
    if np.any(r2 < -(tol + 1e-12)):
        raise checks.degenerate("sphere_center_radius", "S", "s^2 < 0, the sphere is imaginary")
    return p, _F.out(np.sqrt(np.maximum(r2, 0.0)))


def point_sphere_side(x, S: Multivector, atol: float = 1e-9):
    """Which side of a sphere a point lies on, Eq. (2.118).

    Returns +1 inside, 0 on (|x . s| <= atol, in units of length^2), -1 outside,
    from the sign of ``x . s = (rho^2 - |x - p|^2)/2`` with both normalised,
    computed as that difference with |x - p| taken at the point (x - f first
    for an anchored sphere, f its anchor).  A plain blade far out holds rho^2
    only to ``8 eps (|p|^2 + rho^2 + 1)`` (:func:`sphere_center_radius`):
    points closer to its surface than that, in length^2, get an arbitrary sign.
    """
    g = grade_of(S, "point_sphere_side", (1, 4), "S")
    atol = checks.real(atol, "point_sphere_side", "atol", low=0)
    s = S if g == 1 else standard_form(S)
    xe = euclid_point(x, "point_sphere_side")
    if xe is None or any_sympy(s):
        X = up(x) if not isinstance(x, Multivector) else normalize_point(x, "point_sphere_side")
        v = np.asarray((X | normalize_point(s, "point_sphere_side")).scalar(), dtype=float)
    else:
        f, loc = frame(s)  # an anchored sphere: x - f first, then the local centre (no |x|-sized rounding)
        p, r2, _, _ = read_sphere(loc, "point_sphere_side", "S")
        d = xe - p if f is None else (xe - f) - p
        v = 0.5 * (r2 - _F.dot(d, d))
    out = np.where(np.abs(v) <= atol, 0, np.sign(v)).astype(int)
    return int(out) if out.ndim == 0 else out


# -------------------------------------------------------------------- planes
def plane(normal, distance) -> Multivector:
    """Plane P = n + delta e in standard form, Eq. (2.89).

    ``normal`` is normalised to unit length; ``distance`` is the signed
    distance delta from the origin along it.
    """
    nv, sym = check_points(normal, "plane", "normal")
    distance = _per_item(distance, "plane", "distance", ("normal", None if sym else nv))
    if sym:
        return vector(nv) + exact_constants().einf * distance
    with np.errstate(over="ignore"):
        norm = np.linalg.norm(nv, axis=-1)
    if not np.all(np.isfinite(norm)):  # |normal|^2 overflows: scale it first
        nv = nv / np.max(np.abs(nv), axis=-1, keepdims=True)
        norm = np.linalg.norm(nv, axis=-1)
    if np.any(norm == 0):
        raise checks.degenerate("plane", "normal", "the normal is the zero vector")
    n = nv / (norm[..., None] if nv.ndim == 2 else norm)
    if is_sympy(distance):
        return vector(n) + exact_constants().einf * distance
    d = np.asarray(distance, dtype=float)
    return vector(n) + einf * (float(d) if d.ndim == 0 else d)


def plane_from_points(a, b, c) -> Multivector:
    """Plane through three points in dual form P* = e ^ a ^ b ^ c, Eq. (2.77).

    In floats: ``N E - (q . N) e123 ^ e`` with ``N = (b - a) x (c - a)`` and q
    the point nearest the origin, the closed form of the 4-blade.  Raises
    :class:`DegenerateGeometryError` when the points are collinear.
    """
    pts = _F.points("plane_from_points", "a, b, c", a, b, c)
    if pts is None:
        P = exact_constants().einf ^ exact_up(a) ^ exact_up(b) ^ exact_up(c)
        return require_nonzero(P, "plane_from_points", "a, b, c", "the 3 points are collinear")
    return _F.plane(*pts, "plane_from_points")


def plane_normal_distance(P: Multivector):
    """Unit normal n and signed distance delta of a plane (inverse of 2.89).

    Accepts the standard form (grade 1, ``n + delta e``) or the dual form
    (grade 4, 2.77).  For ``plane_from_points(a, b, c)`` the normal is along
    ``(b - a) x (c - a)``.  Raises :class:`InvalidInputError` for a sphere
    (``e . P != 0``).
    """
    g = grade_of(P, "plane_normal_distance", (1, 4), "P")
    p = P if g == 1 else standard_form(P)
    if g == 4:
        p = -p  # e ^ a ^ b ^ c (2.77) dualises to -(N + d e) with N along (b-a)x(c-a)
    if any_sympy(p):
        import sympy

        n = euclidean(p)
        norm = sympy.sqrt(sum(v**2 for v in n))
        return n / norm, p[16] / norm
    n, delta = read_plane(p, "plane_normal_distance", "P")
    norm = _F.norm(n)
    if np.any(norm <= 1e-300):
        raise checks.degenerate("plane_normal_distance", "P", "the input has no normal (not a plane)")
    return n / norm[..., None], _F.out(delta / norm)
