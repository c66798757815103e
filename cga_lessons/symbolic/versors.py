"""Symbolic derivations of the rotor and motor properties (sections 2.4.6-2.4.7, Eqs. 2.135-2.145); the
conformal transformations (2.82-2.93) are in :mod:`cga_lessons.symbolic.transformations`.

Unit vectors (plane normals, rotation axes) are symbolic with the relation
``n . n = 1``, and a rotor's half-angle appears as ``cos(theta/2)``,
``sin(theta/2)``; identities are decided by reducing modulo these relations
(:class:`~cga_lessons.symbolic.core.Relations`), which is exact and fast.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import sympy as sp

from cga_lessons.conformal import (
    decompose_motor,
    line_from_points,
    rotor_about_line,
    rotor_angle_axis,
    translator,
    up,
)

from .core import Ring, add3, const, cross3, dot3, inverse, sub3
from .records import Derivation, derivation

__all__ = ["rotors_and_motors"]

HALF = sp.Rational(1, 2)


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
    :func:`cga_lessons.conformal.versors_rigid.decompose_motor`, ``rotor_angle_axis`` and
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
    sv = _rotor_setting()
    rotated = _rotor_angle_and_axis(d, sv)
    T = _rotor_about_point(d, sv)
    M = _motor_parts(d, sv, T, rotated)
    _rotation_about_line(d, sv.th, sv.ch, sv.sh, sv.xs)
    _motor_remark(d, sv, M, T)
    return d


def _rotor_setting() -> SimpleNamespace:
    """The symbols, the ring (``c^2 + s^2 = 1``, ``n . n = 1``) and the rotor R (2.95) of :func:`rotors_and_motors`."""
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
    e, e0, E, IE, Ic, em = (ring.lift(getattr(c, k)) for k in ("einf", "eo", "E", "IE", "Ic", "em"))
    half = ring.scalar(HALF)
    X = ring.lift(up(xs))
    nv, tv, wv = ring.vector(n), ring.vector(ts), ring.vector(ws)
    l = nv * IE
    R = l * ring.scalar(-sh) + ring.scalar(ch)  # (2.95)
    return SimpleNamespace(
        E=E,
        IE=IE,
        Ic=Ic,
        R=R,
        X=X,
        back=back,
        c=c,
        ch=ch,
        cos2=cos2,
        e=e,
        e0=e0,
        em=em,
        half=half,
        l=l,
        n=n,
        nv=nv,
        ring=ring,
        sh=sh,
        sin2=sin2,
        th=th,
        ts=ts,
        tv=tv,
        ws=ws,
        wv=wv,
        xs=xs,
    )


def _rotor_angle_and_axis(d: Derivation, sv: SimpleNamespace):
    """(2.95) the rotor and Rodrigues' formula, (2.135)-(2.137) its angle and axis."""
    E, R, X, back, c, ch, cos2, half, l, n, nv, ring, sh, sin2, th, xs = (
        sv.E,
        sv.R,
        sv.X,
        sv.back,
        sv.c,
        sv.ch,
        sv.cos2,
        sv.half,
        sv.l,
        sv.n,
        sv.nv,
        sv.ring,
        sv.sh,
        sv.sin2,
        sv.th,
        sv.xs,
    )
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
    Ls = L * ring.lift(inverse(c.Ic))
    d.add("2.137 L* L* = sin(theta/2)^2: (2.126) divides by |sin(theta/2)|", "2.137", Ls * Ls, sh**2, rel=ring)
    d.add("2.137 L* . E = -sin(theta/2) n: the unit axis up to sign", "2.137", Ls | E, nv * ring.scalar(-sh), rel=ring)
    return rotated


def _rotor_about_point(d: Derivation, sv: SimpleNamespace):
    """(2.138)-(2.139) and (2.106): the rotor R_L = T R ~T about a moved centre."""
    E, R, ch, e, half, l, ring, sh, ts, tv = sv.E, sv.R, sv.ch, sv.e, sv.half, sv.l, sv.ring, sv.sh, sv.ts, sv.tv
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
    return T


def _motor_parts(d: Derivation, sv: SimpleNamespace, T, rotated):
    """(2.140)-(2.145): the motor M = T R, its rotor and translation parts."""
    E, IE, R, X, back, e, e0, em, half, ring, tv = (
        sv.E,
        sv.IE,
        sv.R,
        sv.X,
        sv.back,
        sv.e,
        sv.e0,
        sv.em,
        sv.half,
        sv.ring,
        sv.tv,
    )
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
    return M


def _motor_remark(d: Derivation, sv: SimpleNamespace, M, T) -> None:
    """The remark after (2.144): M = T1 T2 R ~T2 decomposes into T3 R; decompose_motor agrees."""
    E, IE, R, back, em, ring, ts, tv, ws, wv = sv.E, sv.IE, sv.R, sv.back, sv.em, sv.ring, sv.ts, sv.tv, sv.ws, sv.wv
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
    e, Ic = ring.lift(c.einf), ring.lift(c.Ic)
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
        * (ring.vector(r) * ring.lift(c.IE) * ring.scalar(-sh) + ring.scalar(ch))
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
