"""Symbolic derivations of the conformal transformations (section 2.3.4,
table 2.2, Eqs. 2.82-2.93) and of the rotor and motor properties
(sections 2.4.6-2.4.7, Eqs. 2.135-2.145).

Unit vectors (plane normals, rotation axes) are symbolic with the relation
``n . n = 1``, and a rotor's half-angle appears as ``cos(theta/2)``,
``sin(theta/2)``; identities are decided by reducing modulo these relations
(:class:`~cga_lessons.symbolic.core.Relations`), which is exact and fast.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from cga_lessons.algebra import commutator
from cga_lessons.conformal import (
    decompose_motor,
    invert_in_sphere,
    line_from_points,
    plane,
    reflect_in_plane,
    rotor_about_line,
    rotor_angle_axis,
    translator,
    up,
)

from .core import Ring, add3, const, cross3, dot3, euclid, inverse, sub3
from .records import Derivation, derivation

__all__ = ["conformal_transformations", "rotors_and_motors"]

HALF = sp.Rational(1, 2)


def _general_vector(name: str):
    """A general vector of R^{4,1}: five symbols on e1, e2, e3, e+, e-."""
    c = const()
    s = sp.symbols(f"{name}1:6", real=True)
    return c["e1"] * s[0] + c["e2"] * s[1] + c["e3"] * s[2] + c["ep"] * s[3] + c["em"] * s[4]


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
    c = const()
    e, e0 = c["einf"], c["eo"]
    xs = sp.symbols("x1:4", real=True)
    X = up(list(xs))
    x = euclid(xs)
    x2 = dot3(xs, xs)
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
    # (2.89)-(2.91) reflection in the plane n + delta e, n a symbolic unit vector
    n = list(sp.symbols("n1:4", real=True))
    delta = sp.Symbol("delta", real=True)
    cs = sp.symbols("c1:4", real=True)
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
    return d


# --------------------------------------------------------------- 2.135 - 2.145
@derivation
def rotors_and_motors() -> Derivation:
    """Rotor and motor properties and the motor decomposition, Eqs. (2.135)-(2.145).

    Symbolic angle theta, unit axis n (``n . n = 1``), translations t and w.
    The rotor ``R = cos(theta/2) - sin(theta/2) n I_E`` (2.95) is checked to
    rotate by +theta about n (Rodrigues' formula), then: the angle (2.135,
    2.136, up to sign), the axis (2.137), the rotor at the origin of a
    general rotation (2.138), ``R_L ~R_L = 1`` (2.139), and for the motor
    ``M = T R`` (2.140) the rotor part (2.141), R' (2.142, with v1 . v2 = 0),
    (2.143), every step of the translation (2.144) and ``M ~M = 1`` (2.145).
    On the way, the general rotation (2.106) and the rotor about a line
    ``exp(-theta/2 L)`` (2.109), which turns by +theta about the line's
    direction.  Finally the remark after (2.144): for ``M = T1 T2 R ~T2`` the
    decomposition returns R and a translation t3 with ``T3 R = M``, and
    :func:`cga_lessons.conformal.versors.decompose_motor`, ``rotor_angle_axis`` and
    ``rotor_about_line`` agree.

    The products are computed in exact polynomial arithmetic
    (:class:`~cga_lessons.symbolic.core.Ring`) with ``c = cos(theta/2)``,
    ``s = sin(theta/2)`` and the relations ``c^2 + s^2 = 1``, ``n . n = 1``.

    Returns
    -------
    Derivation
        values (SymPy coefficients, in cos/sin of theta/2): ``R``, ``M``,
        ``R_prime`` (2.142) and ``t3``.
    """
    d = Derivation("Rotors and motors", tuple(f"2.{i}" for i in range(135, 146)))
    c = const()
    th = sp.Symbol("theta", real=True)
    ch, sh = sp.symbols("c s", real=True)
    n = list(sp.symbols("n1:4", real=True))
    xs = list(sp.symbols("x1:4", real=True))
    ts = list(sp.symbols("t1:4", real=True))
    ws = list(sp.symbols("w1:4", real=True))
    cos2, sin2 = sp.cos(th / 2), sp.sin(th / 2)
    ring = Ring(
        [ch, sh, *n, *xs, *ts, *ws],
        [ch**2 + sh**2 - 1, dot3(n, n) - 1],
        subs={sp.cos(th): ch**2 - sh**2, sp.sin(th): 2 * sh * ch, cos2: ch, sin2: sh},
    )
    back = {ch: cos2, sh: sin2}
    e, e0, E, IE, Ic, em = (ring.lift(c[k]) for k in ("einf", "eo", "E", "IE", "Ic", "em"))
    half = ring.scalar(HALF)
    X = ring.lift(up(xs))
    nv, tv, wv = ring.vector(n), ring.vector(ts), ring.vector(ws)
    l = nv * IE
    R = l * ring.scalar(-sh) + ring.scalar(ch)  # (2.95)
    d.values["R"] = ring.to_expr(R, back)
    d.add("2.95 R ~R = 1", "2.95", R * ~R, 1, rel=ring)
    ndx = dot3(n, xs)
    nxx = cross3(n, xs)
    rod = [xi * sp.cos(th) + ci * sp.sin(th) + ni * ndx * (1 - sp.cos(th)) for xi, ci, ni in zip(xs, nxx, n)]
    rotated = ring.vector(rod)
    d.add("2.95 R x ~R rotates x by +theta about n (Rodrigues)", "2.95", R * X * ~R, ring.up(rotated), rel=ring)
    d.add("2.135 (R + ~R)/2 = cos(theta/2)", "2.135", (R + ~R) * half, ch, rel=ring)
    c_expr = ring.to_expr((R + ~R) * half, back).scalar()
    th2 = 2 * sp.acos(c_expr)  # (2.136)
    d.add("2.136 theta' = 2 acos(c): cos(theta'/2) = cos(theta/2)", "2.136", sp.cos(th2 / 2), cos2, rel=ring)
    d.add("2.136 sin(theta'/2)^2 = sin(theta/2)^2: theta' = +-theta", "2.136", sp.sin(th2 / 2) ** 2, sin2**2, rel=ring)
    sample = {th: sp.Rational(6, 5), n[0]: sp.Rational(2, 7), n[1]: sp.Rational(3, 7), n[2]: sp.Rational(6, 7)}
    R_num = d.values["R"].subs(sample).map(float)
    angle, axis = rotor_angle_axis(R_num)
    d.add_bool(
        "2.135-2.137 versors.rotor_angle_axis recovers (theta, n) at a sample",
        "2.136",
        abs(angle - 1.2) < 1e-12 and np.allclose(axis, [2 / 7, 3 / 7, 6 / 7], atol=1e-12),
        lhs=(angle, axis),
        rhs=(1.2, [2 / 7, 3 / 7, 6 / 7]),
    )
    L = R - ring.scalar(ch)
    d.add("2.137 L = R - c = (R - ~R)/2", "2.137", L, (R - ~R) * half, rel=ring)
    d.add("2.137 L = -sin(theta/2) n I_E", "2.137", L, l * ring.scalar(-sh), rel=ring)
    Ls = L * ring.lift(inverse(c["Ic"]))
    d.add("2.137 L* L* = sin(theta/2)^2: (2.126) divides by |sin(theta/2)|", "2.137", Ls * Ls, sh**2, rel=ring)
    d.add("2.137 L* . E = -sin(theta/2) n: the unit axis up to sign", "2.137", Ls | E, nv * ring.scalar(-sh), rel=ring)
    T = ring.lift(translator(ts))
    RL = T * R * ~T
    d.add(
        "2.138 R_L = T R ~T = cos - sin (l + e (t . l)) (2.106)",
        "2.106",
        RL,
        (l + e * (tv | l)) * ring.scalar(-sh) + ring.scalar(ch),
        rel=ring,
    )
    d.add("2.138 (2.135) holds for R_L", "2.138", (RL + ~RL) * half, ch, rel=ring)
    d.add("2.138 (R_L ^ E) E = R", "2.138", (RL ^ E) * E, R, rel=ring)
    d.add("2.139 T ~T = 1", "2.139", T * ~T, 1, rel=ring)
    d.add("2.139 R_L ~R_L = 1", "2.139", RL * ~RL, 1, rel=ring)
    d.add(
        "2.139 first line T R ~T ~T ~R = 1 (printed)",
        "2.139",
        T * R * ~T * ~T * ~R,
        1,
        expected=False,
        rel=ring,
        note="~(T R ~T) is T ~R ~T, not ~T ~R",
    )
    d.add("2.139 first line T R ~T T ~R ~T = 1 (corrected)", "2.139", T * R * ~T * T * ~R * ~T, 1, rel=ring)
    M = T * R
    d.values["M"] = ring.to_expr(M, back)
    d.add("2.140 M = T R = R + e t R / 2", "2.140", M, R + e * tv * R * half, rel=ring)
    d.add("2.140 M x ~M = up(rotated x + t)", "2.140", M * X * ~M, ring.up(rotated + tv), rel=ring)
    Rm = (M ^ E) * E
    d.add("2.141 (M ^ E) E = R", "2.141", Rm, R, rel=ring)
    Rp = (em | M) * IE
    d.values["R_prime"] = ring.to_expr(Rp, back)
    d.add("2.142 R' = (e- . M) I_E = -t R I_E / 2", "2.142", Rp, tv * R * IE * ring.scalar(-HALF), rel=ring)
    d.add("2.142 R' lies in the even subalgebra of G3 (like R)", "2.142", Rp.grade(1, 3, 4, 5), 0, rel=ring)
    v1 = [Rm[k] for k in ("1", "e12", "e13", "e23")]
    v2 = [Rp[k] for k in ("1", "e12", "e13", "e23")]
    dot12 = sum((ring.element(p) * ring.element(q) for p, q in zip(v1, v2)), ring.R.zero)
    d.add("2.142 v1 . v2 = 0", "2.142", dot12, 0, rel=ring)
    d.add("2.143 M = R + e R' I_E", "2.143", M, R + e * Rp * IE, rel=ring)
    d.add("2.144 step 2: e t R / 2 = e R' I_E", "2.144", e * tv * R * half, e * Rp * IE, rel=ring)
    d.add("2.144 step 3: e t R ~R / 2 = e t / 2", "2.144", e * tv * R * ~R * half, e * tv * half, rel=ring)
    d.add("2.144 step 4: e t = 2 e R' I_E ~R", "2.144", e * tv, e * Rp * IE * ~R * ring.scalar(2), rel=ring)
    d.add("2.144 step 5: -e0 . (e t) = t", "2.144", -(e0 | (e * tv)), tv, rel=ring)
    d.add("2.144 t = 2 R' I_E ~R", "2.144", Rp * IE * ~R * ring.scalar(2), tv, rel=ring)
    d.add("2.145 M ~M = 1", "2.145", M * ~M, 1, rel=ring)
    _rotation_about_line(d, th, ch, sh, xs)
    # remark after (2.144): M = T1 R_L = T1 T2 R ~T2
    T2 = ring.lift(translator(ws))
    M2 = T * T2 * R * ~T2
    R2 = (M2 ^ E) * E
    t3 = (em | M2) * IE * IE * ~R2 * ring.scalar(2)
    d.values["t3"] = ring.to_expr(t3, back)
    d.add("2.141 for M = T1 T2 R ~T2: (M ^ E) E = R", "2.141", R2, R, rel=ring)
    d.add("2.144 for M = T1 T2 R ~T2: t3 = t + w - R w ~R", "2.144", t3, tv + wv - R * wv * ~R, rel=ring)
    T3 = ring.lift(translator([ring.to_expr(t3)[k] for k in ("e1", "e2", "e3")]))
    d.add("2.144 T3 R = M (the same motion)", "2.144", T3 * R2, M2, rel=ring)
    Rd, td = decompose_motor(ring.to_expr(M))
    d.add("2.141-2.144 versors.decompose_motor(M) = (R, t)", "2.144", [Rd, list(td)], [ring.to_expr(R), ts], rel=ring)
    return d


def _rotation_about_line(d: Derivation, th, ch, sh, xs) -> None:
    """Checks of (2.109) used by (2.138): exp(-theta/2 L) for the unit line through a and a + r.

    r is a symbolic unit vector (``r . r = 1``), so ``L* = e ^ a ^ (a + r)``
    is normalised (2.126), ``L = L* Ic`` squares to -1 and
    ``exp(-theta/2 L) = cos(theta/2) - sin(theta/2) L``.  The rotation is by
    +theta about the direction r (right-hand rule) through a.
    """
    c = const()
    r = list(sp.symbols("r1:4", real=True))
    a = list(sp.symbols("a1:4", real=True))
    ring = Ring([ch, sh, *r, *a, *xs], [ch**2 + sh**2 - 1, dot3(r, r) - 1])
    e, Ic = ring.lift(c["einf"]), ring.lift(c["Ic"])
    Ld = e ^ ring.lift(up(a)) ^ ring.lift(up(add3(a, r)))
    d.add("2.109 the line through a and a + r is normalised: L* L* = 1", "2.109", Ld * Ld, 1, rel=ring)
    L = Ld * Ic
    d.add("2.109 L = L* Ic squares to -1", "2.109", L * L, -1, rel=ring)
    RL = L * ring.scalar(-sh) + ring.scalar(ch)  # exp(-theta/2 L) in closed form
    xa = sub3(xs, a)
    cos1, sin1 = ch**2 - sh**2, 2 * sh * ch
    rxa = cross3(r, xa)
    moved = [ai + v * cos1 + q * sin1 + ri * dot3(r, xa) * (1 - cos1) for ai, v, q, ri in zip(a, xa, rxa, r)]
    X = ring.lift(up(list(xs)))
    d.add(
        "2.109 exp(-theta/2 L) rotates by +theta about the line's direction",
        "2.109",
        RL * X * ~RL,
        ring.up(ring.vector(moved)),
        rel=ring,
    )
    d.add(
        "2.109 = T R ~T with T moving the origin to a (2.104)",
        "2.109",
        RL,
        ring.lift(translator(a))
        * (ring.vector(r) * ring.lift(c["IE"]) * ring.scalar(-sh) + ring.scalar(ch))
        * ring.lift(~translator(a)),
        rel=ring,
    )
    sample = {
        th: sp.Rational(6, 5),
        r[0]: sp.Rational(2, 7),
        r[1]: sp.Rational(3, 7),
        r[2]: sp.Rational(6, 7),
        a[0]: 1,
        a[1]: 2,
        a[2]: -1,
    }
    expected = ring.to_expr(RL, {ch: sp.cos(th / 2), sh: sp.sin(th / 2)}).subs(sample).map(float)
    numeric = rotor_about_line(line_from_points([1.0, 2.0, -1.0], [1 + 2 / 7, 2 + 3 / 7, -1 + 6 / 7]), 1.2)
    d.add_bool(
        "2.109 versors.rotor_about_line agrees at a sample",
        "2.109",
        numeric.isclose(expected, atol=1e-12),
        lhs=numeric,
        rhs=expected,
    )
