"""Reading the entities of section 2.4 back from their blades, in the local frame of
:mod:`cga_lessons.conformal.entities_frame`: centres, radii, directions and endpoints without cancellation.

Each reader splits a blade by its null parts (``E + Xe ^ e + Y ^ e0 + D ^ E_pm``, see
:mod:`~cga_lessons.conformal.entities_frame`), reads the weight-like part Y as ``M - P`` and the positions from
the parts that hold them without cancellation, and returns with the result the round-off bound of its one squared
size.  An anchored entity (:mod:`cga_lessons.conformal.anchored`) is read from its local blade, about its anchor,
and the anchor added back to the positions: its round-off bound is then that of the local blade, a few eps of its
own size.  (The numeric side of :mod:`cga_lessons.conformal.entities` and :mod:`cga_lessons.conformal.lines_circles`;
import the entities from there.)
"""

from __future__ import annotations

import numpy as np

from cga_lessons.algebra import DegenerateGeometryError, Multivector
from cga_lessons.checks import degenerate, fail

from .anchored import frame
from .entities_frame import EPS, PAIR_RTOL, biv, check_flat, check_round, dot, norm, quiet, split, vec


def at(p, f):
    """A position p read about the anchor f, back in global coordinates (p itself without an anchor)."""
    return p if f is None else f + p


@quiet
def read_sphere(s: Multivector, func: str, arg: str):
    """Centre p, rho^2, weight w and the round-off bound of rho^2 of a standard-form sphere (grade 1)."""
    f, s = frame(s)
    E, Xe, Y, _, P, M = split(s, func, arg)
    check_round(Y, P, M, func, arg, "s . e = 0, a plane, not a sphere")
    w = Y[..., 0]
    p = vec(E) / w[..., None] + 0.0
    q = 2.0 * Xe[..., 0] / w
    pp = dot(p, p)
    r2 = pp - q
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(r2))):
        raise fail(func, arg, "the coefficients are too large: reading them overflows")
    return at(p, f), r2, w, 16 * EPS * (pp + np.abs(q))


@quiet
def read_pair(B: Multivector, func: str, arg: str):
    """Midpoint m, half separation^2 h2, the unit direction of Y = k (a - b) and the round-off bound of h2."""
    f, B = frame(B)
    E, Xe, Y, D, P, M = split(B, func, arg)
    check_round(Y, P, M, func, arg, "B . e = 0, the point pair has no finite points")
    y = vec(Y)
    ny = norm(y)
    u = y / ny[..., None]
    m_par = (D[..., 0] / ny)[..., None] * u  # y . m = D, y x m = biv(E)
    m_perp = np.cross(biv(E) / ny[..., None], u)
    h2 = 2.0 * dot(vec(Xe), u) / ny + dot(m_par, m_par) - dot(m_perp, m_perp)
    m = m_par + m_perp + 0.0
    mm = dot(m, m)
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(h2))):
        raise fail(func, arg, "the coefficients are too large: reading them overflows")
    return at(m, f), h2, u, 8 * EPS * (mm + np.abs(h2))


@quiet
def read_circle(Zd: Multivector, func: str, arg: str):
    """Centre p, rho^2, the unit normal along N and the round-off bound of rho^2 of a dual circle (grade 3)."""
    f, Zd = frame(Zd)
    E, Xe, Y, D, P, M = split(Zd, func, arg)
    check_round(Y, P, M, func, arg, "the e0 part is zero: a line (a circle of infinite radius), not a circle")
    n = biv(Y)
    nn = norm(n)
    u = n / nn[..., None]
    p_par = (E[..., 7] / nn)[..., None] * u  # p . N = E123, p x N = D
    p_perp = np.cross(u, vec(D) / nn[..., None])
    r2 = 2.0 * dot(biv(Xe), u) / nn + dot(p_perp, p_perp) - dot(p_par, p_par)
    p = p_par + p_perp + 0.0
    pp = dot(p, p)
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(r2))):
        raise fail(func, arg, "the coefficients are too large: reading them overflows")
    return at(p, f), r2, u, 16 * EPS * (pp + np.abs(r2))


@quiet
def read_line(Ld: Multivector, func: str, arg: str):
    """Direction d (scaled) and moment mu = a x d of a dual line (grade 3): L* = mu ^ e + d E (2.81).

    NaN coefficients give NaN (callers such as motor_estimation report them in their own words).  An anchored line
    is read from its local blade (d, and the moment ``mu_f`` about the anchor f): ``mu = mu_f + f x d`` (a point
    a of the line is f + a_f).
    """
    f, Ld = frame(Ld)
    E, Xe, Y, D, P, M = split(Ld, func, arg, finite=False)
    check_flat(Y, P, M, D, func, arg, "a circle or other round, not a line", extra=E)
    d = vec(D)
    if np.any(norm(d) <= 1e-300):
        raise degenerate(func, arg, "the line has no direction (L* L* = 0: zero or a flat point)")
    return d, (biv(Xe) if f is None else biv(Xe) + np.cross(f, d))


@quiet
def read_plane(p: Multivector, func: str, arg: str):
    """Normal (scaled) and the e coefficient of a standard-form plane (grade 1): P = n + delta e (2.89).  An anchored
    plane (a derived one: a circle's plane, ...) is read from its local blade, ``n + delta_f e`` about its anchor f:
    ``delta = delta_f + n . f`` (T_f moves n to ``n + (n . f) e``, 2.100)."""
    f, p = frame(p)
    E, Xe, Y, D, P, M = split(p, func, arg)
    check_flat(Y, P, M, E, func, arg, "e . P != 0: a sphere, not a plane")
    n = vec(E)
    return n, (Xe[..., 0] if f is None else Xe[..., 0] + dot(n, f))


def pair_points(B: Multivector, min_separation, func: str, arg: str):
    """The endpoints ``m +- h Y/|Y|`` of a dual point pair, guarded (see ``point_pair_endpoints``)."""
    m, h2, u, tol = read_pair(B, func, arg)
    sep = 2.0 * np.sqrt(np.abs(h2))
    resolvable = 2.0 * np.sqrt(tol / (2.0 * PAIR_RTOL))  # where tol / (2 h^2) = PAIR_RTOL
    guard = resolvable if min_separation is None else np.full_like(sep, float(min_separation))
    if np.any((h2 < 0) & (sep > guard)):
        raise degenerate(func, arg, "B B < 0, the point pair is imaginary (no real points)")
    if np.any(sep <= guard) and min_separation is not None:
        i = np.unravel_index(np.argmin(sep - guard), np.shape(sep))
        raise degenerate(
            func, arg, f"the points are {float(sep[i]):.3g} apart, below min_separation = {float(guard[i]):.3g}"
        )
    if np.any(sep <= guard):
        i = np.unravel_index(np.argmin(sep - guard), np.shape(sep))
        raise DegenerateGeometryError(
            f"{func}: {arg}: the points are {float(sep[i]):.3g} apart, below the accuracy guard {float(guard[i]):.3g} "
            f"(at {float(norm(m[i])):.3g} from the origin the coefficients resolve a separation to "
            f"{PAIR_RTOL:g} of itself from {float(resolvable[i]):.3g} on): a tangent or nearly coincident pair"
        )
    h = (0.5 * sep)[..., None] * u
    return m + h + 0.0, m - h + 0.0  # + 0.0: no signed zeros in the output
