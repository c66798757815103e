"""Symbolic derivations of the conformal transformations (section 2.3.4, table 2.2, Eqs. 2.82-2.93): inversions,
reflections, translations and rotations as versors.

Unit vectors (plane normals) are symbolic with the relation ``n . n = 1``; identities are decided by reducing modulo
these relations (:class:`~cga_lessons.symbolic.core.Relations`), which is exact and fast.
"""

from __future__ import annotations

import sympy as sp

from cga_lessons.algebra import commutator
from cga_lessons.conformal import (
    invert_in_sphere,
    plane,
    reflect_in_plane,
    translator,
    up,
)

from .core import Ring, add3, const, dot3, euclid, inverse, sub3
from .records import Derivation, derivation

__all__ = ["conformal_transformations"]

HALF = sp.Rational(1, 2)


def _general_vector(name: str):
    """A general vector of R^{4,1}: five symbols on e1, e2, e3, e+, e-."""
    c = const()
    s = sp.symbols(f"{name}1:6", real=True)
    return c.e1 * s[0] + c.e2 * s[1] + c.e3 * s[2] + c.ep * s[3] + c.em * s[4]


# --------------------------------------------------------------- 2.82 - 2.93
@derivation
def conformal_transformations() -> Derivation:
    """Inversions, reflections, translations and rotations as versors,
    Eqs. (2.82)-(2.93) and table 2.2.

    A general vector versor keeps the null cone (2.82); a product of two
    vectors has ``V ~V`` scalar (2.83); the reflection formula (2.84); the
    inversion in the unit sphere (2.85) and in a symbolic sphere (2.86-2.88,
    with sigma of table 2.2); the reflection in the plane ``n + delta e``
    (2.89-2.91); the translator as two reflections (2.92, printed and
    corrected) and the rotation about a point c as two reflections (2.93).

    Returns
    -------
    Derivation
        values: ``translator`` (P1 P2 of 2.92), ``rotation_versor`` (2.93).
    """
    d = Derivation("Conformal transformations", tuple(f"2.{i}" for i in range(82, 94)) + ("table 2.2",))
    xs = sp.symbols("x1:4", real=True)
    X = up(list(xs))
    cs = sp.symbols("c1:4", real=True)  # the fixed point of 2.91 and the centre of 2.93
    _odd_versors(d, X, xs)
    _inversions(d, X, xs)
    _reflections_and_translation(d, X, xs, cs)
    _rotation_about_point(d, X, xs, cs)
    return d


def _odd_versors(d: Derivation, X, xs) -> None:
    """(2.82)-(2.84): a general vector versor keeps the null cone; V = ab; the reflection formula."""
    # exact polynomial arithmetic for the general vectors s, a, b of R^{4,1} and the point x
    gsyms = [sp.Symbol(f"{k}{i}", real=True) for k in "sab" for i in range(1, 6)]
    ring = Ring([*gsyms, *xs])
    s, a5, b5 = (ring.lift(_general_vector(k)) for k in "sab")
    Xr = ring.lift(X)
    s2 = (s * s).scalar()
    sx = ring.scalar((s | Xr).scalar())
    # (2.82) g(x) = G x G^^-1 for the odd versor G = s: G^ = -s, G^^-1 = -s / s^2
    g = s * Xr * s.involute()  # times s^2
    d.add("2.82 G x G^^-1 with G = s is -s x s^-1", "2.82", g, -(s * Xr * s))
    d.add("2.82 the null cone is invariant: g(x)^2 = 0", "2.82", g * g, 0)
    V = a5 * b5
    d.add("2.83 V = ab: V ~V = a^2 b^2 (a scalar)", "2.83", V * ~V, (a5 * a5).scalar() * (b5 * b5).scalar())
    d.add("2.83 V = ab is even: V^ = V", "2.83", V.involute(), V)
    d.add("2.84 s x + x s = 2 s . x", "2.84", s * Xr + Xr * s, sx * ring.scalar(2))
    d.add(
        "2.84 -s x s^-1 = x - 2 (s . x) s^-1",
        "2.84",
        -(s * Xr * s),
        Xr * ring.scalar(s2) - s * sx * ring.scalar(2),
        note="both sides multiplied by s^2",
    )


def _inversions(d: Derivation, X, xs) -> None:
    """(2.85)-(2.88) and table 2.2: inversion in the unit sphere and in a symbolic sphere."""
    c = const()
    e, e0 = c.einf, c.eo
    x = euclid(xs)
    x2 = dot3(xs, xs)
    # (2.85) the unit sphere at the origin
    su = e0 - e * HALF
    d.add("2.85 unit sphere at the origin: s = e0 - e/2", "2.85", up([sp.Integer(0)] * 3) - e * HALF, su)
    d.add("2.85 s^2 = 1, so s^-1 = s", "2.85", su * su, 1)
    d.add("2.85 -2 (s . x) = x^2 - 1", "2.85", -2 * (su | X).scalar(), x2 - 1)
    img = -(su * X * su)
    d.add("2.85 sigma x' = x + (x^2 - 1)(e0 - e/2)", "2.85", img, X + su * (x2 - 1))
    d.add("2.85 = x^2 (x^-1 + x^-2 e / 2 + e0)", "2.85", img, (inverse(x) + e * (1 / (2 * x2)) + e0) * x2)
    d.add("2.85 = x^2 up(x / x^2), the conformal image of x^-1", "2.85", img, up([xi / x2 for xi in xs]) * x2)
    # (2.86)-(2.88) a sphere with symbolic centre and radius
    ps = sp.symbols("p1:4", real=True)
    rho = sp.Symbol("rho", positive=True)
    P = up(list(ps))
    sph = P - e * (rho**2 / 2)
    xp = sub3(xs, ps)
    dist2 = dot3(xp, xp)
    d.add("2.86 s . x = p . x - rho^2 (e . x)/2", "2.86", sph | X, (P | X) - (e | X) * (rho**2 / 2))
    d.add("2.86 = -((x - p)^2 - rho^2)/2", "2.86", sph | X, -(dist2 - rho**2) / 2)
    gx = [rho**2 * v / dist2 + p for v, p in zip(xp, ps)]  # (2.88)
    sring = Ring([*ps, rho, *xs])
    inv_img = -(sring.lift(sph) * sring.lift(X) * sring.lift(sph))  # -s x s^-1 times s^2 = rho^2
    # dist2 up(g) = G + (G . G / dist2) e / 2 + dist2 e0 with G = dist2 g = rho^2 (x - p) + dist2 p
    G = sring.vector([rho**2 * v + dist2 * p for v, p in zip(xp, ps)])
    GG = sring.divide(G * G, dist2)
    dist2_up_g = G + sring.lift(e) * GG * sring.scalar(HALF) + sring.lift(e0) * sring.scalar(dist2)
    d.add(
        "2.87 dist2 g(x) and (dist2 g(x))^2 / dist2 are polynomials",
        "2.87",
        [sring.to_expr(G), sring.to_expr(GG).scalar()],
        [euclid(gx) * dist2, dot3(gx, gx) * dist2],
    )
    d.add(
        "2.87 -s x s^-1 = ((x - p)/rho)^2 up(g(x))", "2.87", inv_img, dist2_up_g, note="both sides multiplied by rho^2"
    )
    d.add(
        "2.84-2.87 versors.invert_in_sphere(s, x) = -s x s^-1",
        "2.87",
        invert_in_sphere(sph, X) * rho**2,
        inv_img,
        rel=sring,
    )
    d.add(
        "2.88 g(x) = rho^2 (x - p)^-1 + p (vector inverse 2.19)",
        "2.88",
        inverse(euclid(xp)) * rho**2 + euclid(ps),
        euclid(gx),
    )
    d.add(
        "table 2.2 inversion: sigma = -e . (s x s^-1 image) = ((x - p)/rho)^2",
        "table 2.2",
        -(sring.lift(e) | inv_img),
        dist2,
        rel=sring,
        note="both sides multiplied by rho^2",
    )


def _reflections_and_translation(d: Derivation, X, xs, cs) -> None:
    """(2.89)-(2.92) and table 2.2: reflection in the plane n + delta e, translation as two reflections."""
    e = const().einf
    x = euclid(xs)
    # (2.89)-(2.91) reflection in the plane n + delta e, n a symbolic unit vector
    n = list(sp.symbols("n1:4", real=True))
    delta = sp.Symbol("delta", real=True)
    unit = Ring([*n, delta, *xs, *cs], [dot3(n, n) - 1])
    nv = euclid(n)
    Pl = nv + e * delta
    d.add("2.89 P^2 = 1 for a unit normal", "2.89", Pl * Pl, 1, rel=unit)
    d.add("2.89 e . P = 0 (a plane is a sphere through infinity)", "2.89", e | Pl, 0)
    d.add(
        "2.90 s . x = n . x - delta",
        "2.90",
        Pl | X,
        dot3(n, xs) - delta,
        note="the text's 's . x = n . x' holds for delta = 0 only",
    )
    mirror = [xi - 2 * (dot3(n, xs) - delta) * ni for xi, ni in zip(xs, n)]
    refl = -(Pl * X * Pl)
    d.add("2.90 -P x P^-1 = up(mirror image of x), sigma = 1", "2.90", refl, up(mirror), rel=unit)
    d.add("2.90 versors.reflect_in_plane(P, x) = -P x P^-1", "2.90", reflect_in_plane(Pl, X), refl, rel=unit)
    d.add("2.89 entities.plane(n, delta) = n + delta e", "2.89", plane(n, delta), Pl)
    g90 = nv * x * nv.involute() + nv * (2 * delta)
    d.add("2.90 g(x) = n x n^ + 2 delta n", "2.90", g90, euclid(mirror), rel=unit)
    d.add(
        "2.90 = n (x - delta n) n^ + delta n",
        "2.90",
        nv * (x - nv * delta) * nv.involute() + nv * delta,
        euclid(mirror),
        rel=unit,
    )
    d.add(
        "table 2.2 reflection g(x) = -n x n + 2 x delta (printed)",
        "table 2.2",
        -(nv * x * nv) + x * (2 * delta),
        euclid(mirror),
        rel=unit,
        expected=False,
        note="the translation term is 2 delta n, as in (2.90)",
    )
    d.add(
        "table 2.2 reflection g(x) = -n x n + 2 delta n (corrected)",
        "table 2.2",
        -(nv * x * nv) + nv * (2 * delta),
        euclid(mirror),
        rel=unit,
    )
    Pc = nv + e * dot3(n, cs)
    Cp = up(list(cs))
    d.add("2.91 c lies on n + (n . c) e", "2.91", Cp | Pc, 0)
    d.add("2.91 the reflection fixes c", "2.91", -(Pc * Cp * Pc), Cp, rel=unit)
    # (2.92) translation as two reflections
    T = Pl * nv
    tv = nv * (2 * delta)
    t = [2 * delta * ni for ni in n]
    d.values["translator"] = T.map(lambda v: unit.reduce(v).as_expr())  # n . n = 1 applied
    d.add("2.92 (n + delta e) n = 1 + e t/2, t = 2 delta n (corrected)", "2.92", T, e * tv * HALF + 1, rel=unit)
    d.add(
        "2.92 = 1 + t e/2 (printed)",
        "2.92",
        T,
        tv * e * HALF + 1,
        rel=unit,
        expected=False,
        note="t e = -e t: the printed order translates by -t",
    )
    d.add("2.92 P1 P2 = versors.translator(t)", "2.92", T, translator(t), rel=unit)
    d.add("2.92 T ~T = 1", "2.92", T * ~T, 1, rel=unit)
    d.add("2.92 T x ~T = up(x + t): moves by +t", "2.92", T * X * ~T, up(add3(xs, t)), rel=unit)
    Tp = tv * e * HALF + 1
    d.add("table 2.2 translation: 1 + t e/2 gives x - t", "table 2.2", Tp * X * ~Tp, up(sub3(xs, t)), rel=unit)


def _rotation_about_point(d: Derivation, X, xs, cs) -> None:
    """(2.93) and table 2.2: rotation about the point c as two reflections."""
    e = const().einf
    x = euclid(xs)
    # (2.93) rotation about c as two reflections, a and b unit normals
    a = list(sp.symbols("a1:4", real=True))
    b = list(sp.symbols("b1:4", real=True))
    av, bv, cv = euclid(a), euclid(b), euclid(cs)
    R = (av + e * dot3(a, cs)) * (bv + e * dot3(b, cs))
    Rr = av * bv
    d.values["rotation_versor"] = R
    d.add("2.93 (a + e(a.c))(b + e(b.c)) = ab + e(c . (a ^ b))", "2.93", R, Rr + e * (cv | (av ^ bv)))
    d.add("2.93 c . (a ^ b) = c x R (commutator 2.36)", "2.93", cv | (av ^ bv), commutator(cv, Rr))
    d.add("table 2.2 rotation versor R + e (c x R), R = ab", "table 2.2", R, Rr + e * commutator(cv, Rr))
    d.add("2.93 R = T_c (ab) ~T_c: the rotation ab moved to c", "2.93", R, translator(cs) * Rr * ~translator(cs))
    # the sandwich, in exact polynomial arithmetic modulo a.a = b.b = 1
    ring = Ring([*a, *b, *cs, *xs], [dot3(a, a) - 1, dot3(b, b) - 1])
    Rq, Rrq, Xq, xq, cq = (ring.lift(V) for V in (R, Rr, X, x, cv))
    d.add("2.93 R ~R = 1", "2.93", Rq * ~Rq, 1, rel=ring)
    y = Rrq * (xq - cq) * ~Rrq + cq
    d.add("2.93 R (x - c) ~R + c is a Euclidean vector", "2.93", y.grade(0, 2, 3), 0, rel=ring)
    y = y.grade(1)
    d.add("2.93 R x ~R = up(R (x - c) ~R + c): rotation about c", "2.93", Rq * Xq * ~Rq, ring.up(y), rel=ring)
