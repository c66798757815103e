"""A local frame for the entities of section 2.4: blades built and read near their data, in floats.

(The numeric side of :mod:`cga_lessons.conformal.entities`; import the entities from there.)

**Why.**  A blade of G(4,1) is stored on the basis e1 e2 e3 e+ e-.  Split by its null parts (2.53)::

    X = E + Xe ^ e + Y ^ e0 + D ^ E_pm        (E, Xe, Y, D Euclidean; E_pm = e+ e-)

the e+ and e- coefficients of each Euclidean blade are ``P = Xe - Y/2`` and ``M = Xe + Y/2``.  For an entity at
distance |c| from the origin ``Xe`` grows like |c|^2 while ``Y`` (the weight of a sphere, twice the half
difference of a point pair, the area bivector of a circle) keeps the size of the shape, so ``Y = M - P`` is a
difference of two |c|^2-sized numbers.  Built from ``up(a) ^ up(b) ^ ...`` in floats the blade loses its relative
accuracy like eps |c|^2 (and worse: the wedge products cancel |c|^4 terms; measured, rho^2 of a unit sphere through
four such points is off by up to ~1e-6 at 100 and ~0.1 at 1000 from the origin), and even a correctly rounded blade
moves its round by about eps |c|^4 / size, because a reader has to translate Y back by |c|.

**What is done here.**  Constructors compute the shape from differences of the points (exact up to one
rounding), write its null parts in closed form about a point of the data (the translator T_f, 2.100, applied
by hand: no |c|^2-sized terms cancel), and store Y *exactly*: Y is first rounded onto the grid of the e+/e-
coefficients it will be stored with, the shape is recomputed from that Y, and ``P`` and ``M = P + Y`` are written
on that grid, so that ``M - P`` gives Y back bit for bit.  The rounding changes Y by ~eps (|c|^2 + 1) relative,
the resolution the storage has anyway: for a sphere that is only its scale; a circle's normal and a point pair's
``a - b`` move by that much.  Readers read Y as ``M - P`` and the positions (centre, midpoint) from the parts that
hold them without cancellation; the one squared size (rho^2 of a sphere or circle, the half separation^2 of a
pair) is a difference of |c|^2-sized terms, good to about eps (|c|^2 + size^2 + 1) absolute: the storage's limit.
The readers are in :mod:`cga_lessons.conformal.entities_read`.

**Beyond the storage.**  That limit is the float64 blade's, not the formulas': a unit sphere 1e6 out cannot be
read to better than ~1e-4 from its 32 coefficients.  So the constructors build each closed form twice, on the data
and on the data translated by -f (f the point of the data nearest the origin; a sphere's centre), and return an
:class:`~cga_lessons.conformal.anchored.Anchored` entity: the global blade carrying the local one about f.  The
readers read the local blade and add f back, so that rho^2, a circle's normal and a pair's direction hold to a few
eps relative at any distance, the positions to that plus the rounding of their own coordinates, and the operations
between anchored entities carry the local blades along (:mod:`~cga_lessons.conformal.anchored_ops`).  The limit
above stays that of a *plain* blade: the global coefficients alone, and a product with what translations move.

Arrays of the parts have shape (..., 8), indexed by the bitmap of the Euclidean blade (0 scalar, 1 2 4 the
vectors, 3 5 6 the bivectors e12 e13 e23, 7 e123).
"""

from __future__ import annotations

import numpy as np

from cga_lessons.algebra import DegenerateGeometryError, Multivector
from cga_lessons.checks import degenerate, fail

from .model import G41
from .multivector_checks import check_points

EPS = float(np.finfo(float).eps)
_VEC = [1, 2, 4]
#: the coordinates of a point above this size have squares that overflow
#: point_pair_endpoints refuses pairs whose separation the coefficients resolve worse than this, relative
PAIR_RTOL = 1e-6


def quiet(f):
    """Run f with NumPy's overflow/invalid warnings off: the results are checked for finiteness instead."""

    def run(*args, **kw):
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return f(*args, **kw)

    run.__name__, run.__doc__ = f.__name__, f.__doc__
    return run


# ------------------------------------------------------------------ parts
def vec(A):
    """The vector part (e1, e2, e3) of a parts array."""
    return A[..., _VEC]


def biv(A):
    """The vector dual to the bivector part: (B23, -B13, B12), so that (a ^ b) -> a x b."""
    return np.stack([A[..., 6], -A[..., 5], A[..., 3]], axis=-1)


def parts(shape):
    return np.zeros(tuple(shape) + (8,))


def put_vec(A, v):
    A[..., _VEC] = v
    return A


def put_biv(A, v):
    A[..., 6], A[..., 5], A[..., 3] = v[..., 0], -v[..., 1], v[..., 2]
    return A


def dot(u, v):
    """u . v over the last axis, summed in one fixed order: a batch gives the bits of its single elements."""
    return u[..., 0] * v[..., 0] + u[..., 1] * v[..., 1] + u[..., 2] * v[..., 2]


def norm(v):
    return np.sqrt(dot(v, v))


def out(x):
    """A float for a single value, the array for a batch."""
    x = np.asarray(x, dtype=float)
    return float(x) if x.ndim == 0 else x


def split(X: Multivector, func: str, arg: str, finite: bool = True):
    """``(E, Xe, Y, D, P, M)`` of a numeric multivector; raises for NaN or inf coefficients (if ``finite``)."""
    a = X.to_array(list(range(32)))
    if finite and not np.all(np.isfinite(a)):
        raise fail(func, arg, "the coefficients contain NaN or inf")
    E, P, M, D = a[..., 0:8], a[..., 8:16], a[..., 16:24], a[..., 24:32]
    return E, 0.5 * (P + M), M - P, D, P, M


def grid(xe, y):
    """The power of two on which ``Xe -+ Y/2`` are stored with Y exact (one per component)."""
    _, e = np.frexp(2.0 * (np.abs(xe) + np.abs(y)))
    return np.maximum(np.ldexp(1.0, e - 53), 5e-324)


def snap(v, g):
    return np.rint(v / g) * g


def settle(y, xe_of, func: str, args: str):
    """Round the e0 part ``y`` onto the grid of the e+/e- coefficients of the shape it implies.

    ``xe_of(Y)`` gives the e part of the shape recomputed with the rounded Y; the grid only grows, a step or two.
    Returns ``(Y, g)``: Y on the grid g, and ``xe_of(Y)`` stored on g with Y exact.
    """
    xe = xe_of(y)
    if not (np.all(np.isfinite(xe)) and np.all(np.isfinite(y))):
        raise fail(func, args, "the coordinates are too large: the blade's coefficients overflow")
    g = grid(xe, y)
    for _ in range(8):
        Y = snap(y, g)
        g2 = np.maximum(g, grid(xe_of(Y), Y))
        if np.all(g2 == g):
            return Y, g
        g = g2
    raise DegenerateGeometryError("entities_frame.settle: the grid of the e0 part does not settle")  # not seen


@quiet
def join(E, xe, y, D, g, func: str, args: str) -> Multivector:
    """The multivector of the null parts; ``y`` must lie on the grid ``g`` (it is then stored exactly)."""
    P, M = xe.copy(), xe.copy()
    cols = np.flatnonzero(np.any(y != 0, axis=tuple(range(y.ndim - 1))))  # the components with an e0 part
    if cols.size:
        yc, xc, gc = y[..., cols], xe[..., cols], np.broadcast_to(g, y.shape)[..., cols]
        P[..., cols] = np.where(yc != 0, snap(xc - 0.5 * yc, gc), xc)
        M[..., cols] = np.where(yc != 0, P[..., cols] + yc, xc)
    if E.ndim == 1:
        a = np.concatenate([E, P, M, D])
        if not np.all(np.isfinite(a)):
            raise fail(func, args, "the coordinates are too large: the blade's coefficients overflow")
        return Multivector(G41, {k: float(a[k]) for k in range(32) if a[k] != 0})
    keys, cols = [], []
    for base, A in ((0, E), (8, P), (16, M), (24, D)):
        for k in np.flatnonzero(np.any(A != 0, axis=0)):  # the blades present in the batch
            keys.append(base + int(k))
            cols.append(A[:, k])
    rows = np.stack(cols) if cols else np.zeros((0, E.shape[0]))  # one block: each blade contiguous
    if not np.all(np.isfinite(rows)):
        raise fail(func, args, "the coordinates are too large: the blade's coefficients overflow")
    return Multivector(G41, dict(zip(keys, rows)))


def check_round(y, P, M, func: str, arg: str, what: str):
    """Raise unless the e0 part Y stands out of the round-off of the e+/e- coefficients (a round, not a flat)."""
    if np.any(np.all(np.abs(y) <= 16 * EPS * (np.abs(P) + np.abs(M)), axis=-1)):
        raise DegenerateGeometryError(
            f"{func}: {arg}: {what} (the e0 part is zero within the round-off of the e+/e- coefficients; "
            "a flat, or a round too far from the origin to be stored)"
        )


def check_flat(y, P, M, carrier, func: str, arg: str, what: str, extra=None):
    """Raise unless the blade is a flat: no e0 part Y (nor the parts ``extra``) beyond the round-off of the parts
    that carry it (P, M and ``carrier``)."""
    ref = np.max(np.abs(P) + np.abs(M), axis=-1) + np.max(np.abs(carrier), axis=-1)
    bad = np.any(np.abs(y) > 64 * EPS * (np.abs(P) + np.abs(M)), axis=-1)
    if extra is not None:
        bad |= np.max(np.abs(extra), axis=-1) > 64 * EPS * ref
    if np.any(bad):
        raise fail(func, arg, what)


# ------------------------------------------------------------ point input
def points(func: str, names: str, *pts):
    """Validated float points (broadcast to one shape), or None when any is symbolic."""
    arrs = []
    for name, p in zip(names.split(", "), pts):
        arr, sym = check_points(p, func, name, limit=True)
        if sym:
            return None
        arrs.append(arr)
    shapes = {a.shape for a in arrs}
    if len(shapes) > 1 and len({s for s in shapes if len(s) == 2}) > 1:
        raise fail(func, names, f"batches of different lengths: {' and '.join(str(a.shape) for a in arrs)}")
    return np.broadcast_arrays(*arrs)


def _edge(*ds):
    return np.max(np.stack([norm(d) for d in ds]), axis=0)


def _coincide(a, b, func: str):
    d = norm(a - b)
    if np.any(d <= 1e-12 * np.maximum(1.0, np.maximum(np.abs(a).max(axis=-1), np.abs(b).max(axis=-1)))):
        raise degenerate(func, "a, b", "the two points coincide")


def _collinear(a, b, c, func: str):
    area = norm(np.cross(b - a, c - a))
    if np.any(area <= 1e-12 * max(np.max(np.abs(b - a)), np.max(np.abs(c - a)), 1e-300) ** 2):
        raise degenerate(func, "a, b, c", "the 3 points are collinear (or coincide)")


# ---------------------------------------------------------- constructors
@quiet
def sphere_std(p, q, w, func: str, args: str) -> Multivector:
    """Standard form ``w (p + q e / 2 + e0)`` (2.72, q = |p|^2 - rho^2) with its weight stored exactly."""
    w = np.broadcast_to(np.asarray(w, dtype=float), q.shape)
    ws, g = settle(w, lambda w: 0.5 * w * q, func, args)
    ws = np.where(ws == 0, np.copysign(g, w), ws)  # the weight must survive: round it up to the grid
    E, Xe, Y = put_vec(parts(q.shape), ws[..., None] * p), parts(q.shape), parts(q.shape)
    Xe[..., 0], Y[..., 0] = 0.5 * ws * q, ws
    return join(E, Xe, Y, parts(q.shape), g[..., None], func, args)


def nearest(*pts):
    """The point nearest the origin (per batch element): the base of the closed forms, so that an entity
    through (or near) the origin gets small e parts without cancellation."""
    P = np.stack(pts)
    i = np.argmin(dot(P, P), axis=0)  # summed in one fixed order: a batch picks what its single elements pick
    return np.take_along_axis(P, i[None, ..., None], axis=0)[0]


@quiet
def sphere_from_points(a, b, c, d, func: str):
    """Standard form of the sphere through four points, weight det[b - a, c - a, d - a] (that of a ^ b ^ c ^ d)."""
    ab, ac, ad = b - a, c - a, d - a
    w = dot(ab, np.cross(ac, ad))
    if np.any(np.abs(w) <= 1e-10 * _edge(ab, ac, ad, c - b, d - b, d - c) ** 3):
        raise degenerate(func, "a, b, c, d", "the 4 points are coplanar (or two coincide)")
    off = (
        dot(ab, ab)[..., None] * np.cross(ac, ad)
        + dot(ac, ac)[..., None] * np.cross(ad, ab)
        + dot(ad, ad)[..., None] * np.cross(ab, ac)
    ) / (2.0 * w[..., None])  # the circumcentre, from a
    p = a + off
    q = nearest(a, b, c, d)
    off = p - q  # rho^2 = |p - q|^2, so p^2 - rho^2 = q . (q + 2 (p - q)): small when the sphere passes near 0
    return sphere_std(p, dot(q, q + 2.0 * off), w, func, "a, b, c, d")


@quiet
def point_pair(a, b, func: str) -> Multivector:
    """a ^ b (2.68) about a fixed point f, with Y = a - b (the translator T_f, 2.100)::

    (Y x f) + X ^ e + Y ^ e0 + (Y . f + s |Y|^2 / 2) E
    X = ((|f|^2 - (s^2 - 1) |Y|^2 / 4) Y - (2 f . Y + s |Y|^2) f) / 2

    (bivectors as their dual vectors), for a = f + (s + 1) Y / 2, b = f + (s - 1) Y / 2.  f is the midpoint (s = 0),
    unless one end is much nearer the origin: then f is that end (s = +1 for b, -1 for a), so that rounding Y onto
    its grid moves the far end only and the e parts (which the near end sets) stay put.
    """
    _coincide(a, b, func)
    y = a - b
    na, nb = dot(a, a), dot(b, b)
    near = np.minimum(na, nb) < 0.25 * np.maximum(na, nb)
    sg = np.where(near, np.where(nb <= na, 1.0, -1.0), 0.0)
    f = np.where(near[..., None], np.where((nb <= na)[..., None], b, a), 0.5 * (a + b))
    sh = y.shape[:-1]

    def xe_of(Y):
        y, y2 = vec(Y), dot(vec(Y), vec(Y))
        x = (dot(f, f) - 0.25 * (sg * sg - 1.0) * y2)[..., None] * y - (2.0 * dot(f, y) + sg * y2)[..., None] * f
        return put_vec(parts(sh), 0.5 * x)

    Y, g = settle(put_vec(parts(sh), y), xe_of, func, "a, b")
    if np.any(np.all(Y == 0, axis=-1)):
        sep = float(np.min(norm(a - b)))
        raise DegenerateGeometryError(
            f"{func}: a, b: the points are {sep:.3g} apart, below the resolution {float(np.max(g[..., _VEC])):.3g} "
            "of the coefficients at this distance from the origin"
        )
    y = vec(Y)
    D = parts(sh)
    D[..., 0] = dot(y, f) + 0.5 * sg * dot(y, y)
    return join(put_biv(parts(sh), np.cross(y, f)), xe_of(Y), Y, D, g, func, "a, b")


@quiet
def line(a, b, func: str) -> Multivector:
    """e ^ a ^ b (2.81) = (q x d) ^ e + d E with d = b - a and q the point nearer the origin."""
    _coincide(a, b, func)
    d, q = b - a, nearest(a, b)
    sh = d.shape[:-1]
    return join(parts(sh), put_biv(parts(sh), np.cross(q, d)), parts(sh), put_vec(parts(sh), d), 1.0, func, "a, b")


@quiet
def plane(a, b, c, func: str) -> Multivector:
    """e ^ a ^ b ^ c (2.77) = -(q . N) e123 ^ e + N E, with N = (b - a) x (c - a) and q the point nearest 0."""
    _collinear(a, b, c, func)
    n = np.cross(b - a, c - a)
    sh = n.shape[:-1]
    Xe = parts(sh)
    Xe[..., 7] = -dot(nearest(a, b, c), n)
    return join(parts(sh), Xe, parts(sh), put_biv(parts(sh), n), 1.0, func, "a, b, c")


@quiet
def circle(a, b, c, func: str) -> Multivector:
    """a ^ b ^ c (2.80) from the circumcentre p, the point q nearest 0 and N = (b - a) x (c - a) (T_p, 2.100)::

    (p . N) e123 + xi ^ e + N ^ e0 + (p x N) E,   xi = (rho^2 - p^2) N / 2 + (p . N) p    (as vectors)

    with rho^2 - p^2 = -q . (q + 2 (p - q)) and p . N = q . N + (p - q) . N, small when the circle passes near 0.
    """
    _collinear(a, b, c, func)
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    off = (np.cross(n, ab) * dot(ac, ac)[..., None] + np.cross(ac, n) * dot(ab, ab)[..., None]) / (
        2.0 * dot(n, n)[..., None]
    )
    p = a + off
    q = nearest(a, b, c)
    pq = p - q
    k = -dot(q, q + 2.0 * pq)  # rho^2 - p^2

    def pn(n):
        return dot(q, n) + dot(pq, n)

    def xi_of(n):
        return 0.5 * k[..., None] * n + pn(n)[..., None] * p

    sh = n.shape[:-1]
    N, g = settle(put_biv(parts(sh), n), lambda N: put_biv(parts(sh), xi_of(biv(N))), func, "a, b, c")
    n = biv(N)
    E, D = parts(sh), put_vec(parts(sh), np.cross(p, n))
    E[..., 7] = pn(n)
    return join(E, put_biv(parts(sh), xi_of(n)), N, D, g, func, "a, b, c")
