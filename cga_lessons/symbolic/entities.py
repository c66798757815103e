"""Symbolic derivations of spheres, planes and point pairs (table 2.1,
sections 2.3.3 and 2.4.5): spheres and planes (2.69)-(2.77) and point pairs
(2.131)-(2.134).  Circles and lines are in :mod:`cga_lessons.symbolic.circles_lines`.

Points on a sphere are placed with rational unit vectors around a symbolic
centre, so no square root appears.  Entities are homogeneous, so "equal up to
scale" is tested with :func:`~cga_lessons.symbolic.core.proportional`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from cga_lessons.conformal import (
    plane_from_points,
    point_pair,
    point_pair_endpoints,
    point_pair_sphere,
    sphere_center_radius,
    sphere_from_points,
    up,
)
from cga_lessons.conformal import sphere as sphere_entity

from .core import (
    Ring,
    add3,
    const,
    cross3,
    dot3,
    euclid,
    inverse,
    proportional,
    same,
    scale3,
    sphere_from_center,
    sub3,
)
from .records import Derivation, derivation

__all__ = ["sphere_and_plane", "point_pair_extraction"]

HALF = sp.Rational(1, 2)


# --------------------------------------------------------------- 2.69 - 2.77
@derivation
def sphere_and_plane() -> Derivation:
    """Spheres and planes, Eqs. (2.69)-(2.77), for a symbolic centre and radius.

    The sphere's equation (2.69) is rewritten with the inner product of
    points (2.70-2.71) and the solutions of ``x . s = 0`` for x3 are compared
    with those of ``(x - p)^2 = rho^2``; the vector s (2.72) has ``s^2 = rho^2``
    (2.73) and ``e . s = -1`` (2.74), and a general vector with those two
    properties is *solved* back to the form (2.72).  Four points on the sphere
    give its dual ``a ^ b ^ c ^ d`` (2.75), incidence ``x ^ s* = 0`` (2.76) is
    ``(x . s) Ic^-1`` for any point, and the plane through three symbolic
    points (2.77) is expanded as printed and compared with table 2.1.

    Returns
    -------
    Derivation
        values: ``s`` (the sphere), ``s_dual`` (2.75), ``plane_dual`` (2.77).
    """
    d = Derivation("Spheres and planes", tuple(f"2.{i}" for i in range(69, 78)))
    c = const()
    e, e0, E, IE, Ic = c.einf, c.eo, c.E, c.IE, c.Ic
    ps = sp.symbols("p1:4", real=True)
    xs = sp.symbols("x1:4", real=True)
    rho = sp.Symbol("rho", positive=True)
    X, P = up(list(xs)), up(list(ps))
    dist2 = dot3(sub3(xs, ps), sub3(xs, ps))
    p2 = dot3(ps, ps)
    s = P - e * (rho**2 / 2)
    d.values["s"] = s
    sphere_eq = dist2 - rho**2  # (2.69) as f(x) = 0
    d.add("2.70 x . p = -(x - p)^2 / 2", "2.70", X | P, -dist2 / 2)
    d.add("2.71 x . s = x . p - (x . e) rho^2 / 2", "2.71", X | s, (X | P) - (X | e) * (rho**2 / 2))
    d.add("2.71 x . s = -((x - p)^2 - rho^2) / 2", "2.71", X | s, -sphere_eq / 2)
    roots = sp.solve((X | s).scalar(), xs[2])
    d.add(
        "2.71 the two roots x3 of x . s = 0 satisfy (2.69)",
        "2.71",
        [len(roots)] + [sp.simplify(sphere_eq.subs(xs[2], x3)) for x3 in roots],
        [2] + [0] * len(roots),
    )
    d.add("2.72 s = p + (p^2 - rho^2) e / 2 + e0", "2.72", s, euclid(ps) + e * ((p2 - rho**2) / 2) + e0)
    d.add("2.72 entities.sphere(p, rho)", "2.72", sphere_entity(list(ps), rho), s)
    d.add("2.73 s^2 = rho^2", "2.73", s * s, rho**2)
    d.add("2.74 e . s = -1", "2.74", e | s, -1)
    center, radius = sphere_center_radius(s)
    d.add("2.73-2.74 entities.sphere_center_radius(s) = (p, rho)", "2.73", [list(center), radius], [list(ps), rho])
    # recover (2.72) from (2.73)-(2.74): a general vector w + alpha e + beta e0
    ws = sp.symbols("w1:4", real=True)
    al, be = sp.symbols("alpha beta")
    v = euclid(ws) + e * al + e0 * be
    sol = sp.solve([(e | v).scalar() + 1, (v * v).scalar() - rho**2], [al, be], dict=True)
    d.values["recovered"] = sol
    d.add_bool("2.73-2.74 determine alpha, beta uniquely", "2.74", len(sol) == 1, lhs=sol)
    if sol:
        d.add("2.73-2.74 recover the form (2.72)", "2.74", v.subs(sol[0]), sphere_from_center(ws, rho**2))
    _dual_sphere(d, Ic, X, ps, rho, s, xs)
    _plane_through_points(d, E, IE, Ic, e)
    return d


def _dual_sphere(d: Derivation, Ic, X, ps, rho, s, xs):
    """(2.75)-(2.76): the dual sphere a ^ b ^ c ^ d of four points on it, and incidence."""
    # (2.75): four points on the sphere, p + rho u with rational unit vectors u
    units = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [sp.Rational(-3, 5), sp.Rational(-4, 5), 0]]
    ring = Ring([*ps, rho, *xs])  # exact polynomial arithmetic for the 4-fold wedge
    pts = [ring.lift(up(add3(ps, scale3(rho, u)))) for u in units]
    S_dual = pts[0] ^ pts[1] ^ pts[2] ^ pts[3]
    d.values["s_dual"] = ring.to_expr(S_dual)
    sr, Icr, Xr = ring.lift(s), ring.lift(Ic), ring.lift(X)
    d.add_bool("2.75 (a ^ b ^ c ^ d) Ic is the sphere s (up to scale)", "2.75", proportional(S_dual * Icr, sr))
    d.add("2.75 s* = s Ic^-1 is a 4-blade", "2.75", (s * inverse(Ic)).grade(4), s * inverse(Ic))
    d.add("2.76 x ^ s* = (x . s) Ic^-1", "2.76", X ^ (s * inverse(Ic)), inverse(Ic) * (X | s).scalar())
    k_num, k_den = (S_dual * Icr)["e1"], sr["e1"]  # S_dual Ic = (k_num / k_den) s
    d.add(
        "2.76 x ^ (a ^ b ^ c ^ d) = k (x . s) Ic^-1",
        "2.76",
        (Xr ^ S_dual) * ring.scalar(k_den),
        ring.lift(inverse(Ic)) * ring.scalar((Xr | sr).scalar() * k_num),
    )
    sample = [
        [sp.Integer(v) for v in q] for q in ([4, 2, -1], [1, 5, -1], [1, 2, 2], [-2, 2, -1])
    ]  # centre (1, 2, -1), radius 3
    d.add_bool(
        "2.75 entities.sphere_from_points, at rational points: its standard form is sphere(p, rho)",
        "2.75",
        proportional(sphere_from_points(*sample) * Ic, sphere_from_center([1, 2, -1], 9)),
    )


def _plane_through_points(d: Derivation, E, IE, Ic, e):
    """(2.77): the plane through three symbolic points, as printed and as in table 2.1."""
    # (2.77) the plane through three symbolic points
    a_s, b_s, c_s = (sp.symbols(f"{n}1:4", real=True) for n in "abc")
    A, B, C = up(list(a_s)), up(list(b_s)), up(list(c_s))
    a, b, cc = euclid(a_s), euclid(b_s), euclid(c_s)
    Pd = e ^ A ^ B ^ C
    d.values["plane_dual"] = Pd
    N = (b - a) ^ (cc - a)
    abc = a ^ b ^ cc
    dd = (abc * inverse(IE)).scalar()  # d I_E = a ^ b ^ c
    d.add("2.77 e ^ a ^ b ^ c = e ^ a ^ b ^ c (Euclidean) + E N", "2.77", Pd, (e ^ abc) + E * N)
    d.add("2.77 = e I_E d + N E with d I_E = a ^ b ^ c", "2.77", Pd, e * IE * dd + N * E)
    d.add("2.77 a, b, c lie on the plane", "2.77", [A ^ Pd, B ^ Pd, C ^ Pd], [0, 0, 0])
    Pstd = Pd * Ic
    d.add("2.77 the standard form has e . P = 0 (radius infinite)", "2.77", e | Pstd, 0)
    nrm = cross3(sub3(b_s, a_s), sub3(c_s, a_s))
    det = dot3(a_s, cross3(b_s, c_s))
    d.add("2.77 standard form = N I_E - d e = -(n + d e), n = (b-a)x(c-a)", "2.77", Pstd, N * IE - e * dd)
    d.add("2.77 d = a . (b x c) (Hesse: |n| times the distance)", "2.77", dd, det)
    d.add("2.77 P = -(n + d e)", "2.77", Pstd, -(euclid(nrm) + e * det))
    pa, pb, pc = (
        [sp.Integer(v) for v in q] for q in ([1, 0, 2], [3, -1, 1], [0, 2, 5])
    )  # n = (b-a)x(c-a), d = a.(bxc)
    n_s, d_s = cross3(sub3(pb, pa), sub3(pc, pa)), dot3(pa, cross3(pb, pc))
    d.add_bool(
        "2.77 entities.plane_from_points, at rational points: standard form n + d e",
        "2.77",
        proportional(plane_from_points(pa, pb, pc) * Ic, euclid(n_s) + e * d_s),
    )
    d.add(
        "table 2.1 plane d = (a ^ b ^ c) I_E (printed)",
        "table 2.1",
        Pstd,
        N * IE - e * (abc * IE).scalar(),
        expected=False,
        note="with d I_E = a ^ b ^ c as in (2.77), d = (a ^ b ^ c) I_E^-1 = -(a ^ b ^ c) I_E",
    )


# --------------------------------------------------------------- point pairs
@derivation
def point_pair_extraction() -> Derivation:
    """The two points of a point pair, Eqs. (2.131)-(2.134), for symbolic a, b.

    With normalised points ``a . b = -|a - b|^2 / 2 <= 0`` (2.66) and
    ``B B = (a . b)^2`` for ``B = a ^ b``, so ``sqrt(B B) = -a . b`` (the
    non-negative root).  Then ``B - sqrt(B B) = a b`` (2.132),
    ``B + sqrt(B B) = -b a`` (2.133), ``B . e = b - a``, and the right
    divisions ``a b (b - a)^-1 = a``, ``-b a (b - a)^-1 = b`` (2.131) give
    the points in the order of the text (p1 from the numerator 2.132).
    Dividing on the left instead swaps the two points.  The sphere of the
    pair (2.134) is the midpoint sphere, up to scale.

    Returns
    -------
    Derivation
        values: ``p1``, ``p2`` (right division), ``sphere`` (2.134) and
        ``sphere_scale`` (its factor relative to ``sphere(mid, |a-b|/2)``).
    """
    d = Derivation("Point pair extraction", ("2.131", "2.132", "2.133", "2.134"))
    c = const()
    a_s = sp.symbols("a1:4", real=True)
    b_s = sp.symbols("b1:4", real=True)
    ring = Ring([*a_s, *b_s])  # exact polynomial arithmetic, no relations
    e, Ic = ring.lift(c.einf), ring.lift(c.Ic)
    A, B = ring.lift(up(list(a_s))), ring.lift(up(list(b_s)))
    PP = A ^ B
    sample_a, sample_b = [1, 2, -1], [sp.Rational(1, 2), 0, 3]
    d.add(
        "2.131 entities.point_pair(a, b) = a ^ b (2.68), at rational points",
        "2.131",
        point_pair(sample_a, sample_b),
        up(sample_a) ^ up(sample_b),
    )
    BB = PP * PP
    ab = (A | B).scalar()
    dist2 = ring.element(dot3(sub3(a_s, b_s), sub3(a_s, b_s)))
    d.add("2.131 B B is the scalar (a . b)^2", "2.131", BB, ab**2)
    root = -ab
    d.add("2.131 sqrt(B B) = -a . b = |a - b|^2 / 2 >= 0", "2.131", [root**2 - BB.scalar(), root], [0, dist2 / 2])
    num1 = PP - ring.scalar(root)
    num2 = PP + ring.scalar(root)
    d.add("2.132 B - sqrt(B B) = p1 p2", "2.132", num1, A * B)
    d.add("2.132 = p1 . p2 + p1 ^ p2", "2.132", num1, (A ^ B) + ring.scalar(ab))
    d.add("2.133 B + sqrt(B B) = -p2 p1", "2.133", num2, -(B * A))
    d.add("2.133 = -p1 . p2 + p1 ^ p2", "2.133", num2, (A ^ B) - ring.scalar(ab))
    Be = PP | e
    d.add("2.131 B . e = b - a", "2.131", Be, B - A)
    be2 = (Be * Be).scalar()  # (B . e)^-1 = (B . e) / (B . e)^2, (2.19)
    d.add("2.131 (B . e)^2 = |a - b|^2 > 0, so B . e is invertible", "2.131", be2, dist2)
    p1 = ring.divide(num1 * Be, be2)
    p2 = ring.divide(num2 * Be, be2)
    d.values["p1"], d.values["p2"] = ring.to_expr(p1), ring.to_expr(p2)
    d.add("2.131 p1 = (B - sqrt(BB)) (B . e)^-1 = a", "2.131", p1, A)
    d.add("2.131 p2 = (B + sqrt(BB)) (B . e)^-1 = b", "2.131", p2, B)
    d.add("2.131 left division swaps them: (B . e)^-1 (B - sqrt(BB)) = -b", "2.131", ring.divide(Be * num1, be2), -B)
    d.add(
        "2.131 p1 = (B + sqrt(BB)) / (B . e) = a (printed +- order)",
        "2.131",
        p2,
        A,
        expected=False,
        note="with the right division the + sign gives b; p1 comes from the numerator (2.132), the - sign",
    )
    d.add("2.131 p1 = (B - sqrt(BB)) (B . e)^-1 = a (corrected -+ order)", "2.131", p1, A)
    mid = [(x + y) / 2 for x, y in zip(a_s, b_s)]
    T = PP ^ e
    S = ring.divide(PP * ~T, (T * ~T).scalar())  # PP* (PP* ^ e)^-1, (2.19)
    target = ring.lift(sphere_from_center(mid, dot3(sub3(a_s, b_s), sub3(a_s, b_s)) / 4))
    d.add("2.134 PP*/(PP* ^ e) is a vector", "2.134", S.grade(3, 5), 0)
    d.add_bool("2.134 PP*/(PP* ^ e) = sphere(mid, |a-b|/2) up to scale", "2.134", proportional(S, target))
    d.add("2.134 the factor is -1", "2.134", S, -target)
    d.values["sphere"], d.values["sphere_scale"] = ring.to_expr(S), -1 if same(S, -target) else None
    _point_pair_numeric(d)
    _point_pair_of_spheres(d, A, B, Ic, PP, a_s, b_s, mid, ring)
    return d


def _point_pair_numeric(d: Derivation):
    """The numeric implementations of the point pair's extraction, in the derivation's order and scale."""
    # the numeric implementations follow the same order and scale
    fa, fb = np.array([1.0, 2.0, -1.0]), np.array([0.5, 0.0, 3.0])
    q1, q2 = point_pair_endpoints(point_pair(fa, fb))
    d.add_bool(
        "2.131 entities.point_pair_endpoints(a ^ b) = (a, b), at a sample",
        "2.131",
        np.allclose(q1, fa, atol=1e-12) and np.allclose(q2, fb, atol=1e-12),
        lhs=(q1, q2),
        rhs=(fa, fb),
    )
    centre, radius = sphere_center_radius(point_pair_sphere(point_pair(fa, fb)))
    d.add_bool(
        "2.134 entities.point_pair_sphere: centre (a + b)/2, radius |a - b|/2, at a sample",
        "2.134",
        np.allclose(centre, (fa + fb) / 2, atol=1e-12) and abs(radius - np.linalg.norm(fa - fb) / 2) < 1e-12,
        lhs=(centre, radius),
        rhs=((fa + fb) / 2, np.linalg.norm(fa - fb) / 2),
    )


def _point_pair_of_spheres(d: Derivation, A, B, Ic, PP, a_s, b_s, mid, ring):
    """Table 2.1: PP = s1 ^ s2 ^ s3 for three spheres through a and b."""
    # table 2.1: PP = s1 ^ s2 ^ s3 for three spheres through a and b, centred on
    # the bisector plane of a and b (centres m, m + (b - a) x e1, m + (b - a) x e2)
    ba = sub3(b_s, a_s)
    centers = [mid, add3(mid, cross3(ba, [1, 0, 0])), add3(mid, cross3(ba, [0, 1, 0]))]
    spheres = [ring.lift(sphere_from_center(m, dot3(sub3(m, a_s), sub3(m, a_s)))) for m in centers]
    d.add(
        "table 2.1 the three spheres contain a and b",
        "table 2.1",
        [A | s for s in spheres] + [B | s for s in spheres],
        [0] * 6,
    )
    three = spheres[0] ^ spheres[1] ^ spheres[2]
    d.add_bool("table 2.1 PP = s1 ^ s2 ^ s3 = PP* Ic up to scale", "table 2.1", proportional(three, PP * Ic))
