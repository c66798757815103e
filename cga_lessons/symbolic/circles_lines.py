"""Symbolic derivations of circles and lines (table 2.1, sections 2.4.3-2.4.4):
circles (2.78)-(2.80), (2.119)-(2.124) and lines (2.81), (2.125)-(2.130).

Points on a circle are placed with rational unit vectors around a symbolic
centre; a line's unit direction is symbolic with ``r . r = 1`` imposed by
:class:`~cga_lessons.symbolic.core.Ring`.  Entities are homogeneous, so
"equal up to scale" is tested with :func:`~cga_lessons.symbolic.core.proportional`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from cga_lessons.conformal import (
    circle_center_radius,
    circle_from_points,
    line_closest_point,
    line_direction,
    line_from_points,
    line_moment,
    point_line_distance,
    up,
)

from .core import (
    Ring,
    add3,
    const,
    cross3,
    dot3,
    euclid,
    inverse,
    proportional,
    scale3,
    sphere_from_center,
    sub3,
)
from .records import Derivation, derivation

__all__ = ["circle_properties", "line_properties"]


# --------------------------------------------------------------- circles
@derivation
def circle_properties() -> Derivation:
    """Circles, Eqs. (2.78)-(2.80) and (2.119)-(2.124), symbolic centre and radius.

    The circle of radius r centred at q (q, r symbolic; n a fixed rational
    unit normal) is the intersection of the sphere about q of radius r with
    the plane ``n + (n . q) e`` (2.78-2.79) (any circle is a great circle of
    such a sphere, and the plane is a sphere through infinity), and
    the dual ``a ^ b ^ c`` of three of its points (2.80).  Then the plane
    (2.119), the axis (2.120), the product of the two (2.121), the radius
    (2.122, printed and corrected), the sphere of the circle (2.123) and its
    dual (2.124).

    Returns
    -------
    Derivation
        values: ``z`` (standard form from three points), ``z_spheres``
        (s ^ pi), ``radius2`` (the corrected 2.122).
    """
    d = Derivation("Circles", ("2.78", "2.79", "2.80", "2.119", "2.120", "2.121", "2.122", "2.123", "2.124"))
    c = const()
    e, e0, Ic = c.einf, c.eo, c.Ic
    q = list(sp.symbols("q1:4", real=True))
    r = sp.Symbol("r", positive=True)
    n = [sp.Rational(2, 7), sp.Rational(3, 7), sp.Rational(6, 7)]
    u1 = [sp.Rational(3, 7), sp.Rational(-6, 7), sp.Rational(2, 7)]
    u2 = cross3(n, u1)
    s = sphere_from_center(q, r**2)
    pi = euclid(n) + e * dot3(n, q)
    on_circle = [add3(q, scale3(r, u1)), add3(q, scale3(r, u2)), sub3(q, scale3(r, u1)), sub3(q, scale3(r, u2))]
    A, B, C, D = (up(x) for x in on_circle)
    d.add(
        "2.78 the points lie on both sphere and plane", "2.78", [A | s, B | s, C | s, A | pi, B | pi, C | pi], [0] * 6
    )
    z_sp = (s ^ pi).expand()
    vs = [euclid(sp.symbols(f"{k}1:4")) + e * sp.Symbol(f"{k}4") + e0 * sp.Symbol(f"{k}5") for k in "xyw"]
    xg, s1, s2 = vs
    d.add(
        "2.79 x . (s1 ^ s2) = (x . s1) s2 - (x . s2) s1",
        "2.79",
        xg | (s1 ^ s2),
        s2 * (xg | s1).scalar() - s1 * (xg | s2).scalar(),
    )
    d.add("2.79 x . z = 0 for the points of the circle", "2.79", [A | z_sp, B | z_sp, C | z_sp, D | z_sp], [0] * 4)
    d.add(
        "table 2.1 circle z = s1 ^ s1 (printed)",
        "table 2.1",
        s ^ s,
        z_sp,
        expected=False,
        note="s ^ s = 0; the circle is s1 ^ s2 (2.79)",
    )
    z_dual = (A ^ B ^ C).expand()
    z = (z_dual * Ic).expand()
    d.values["z"], d.values["z_spheres"] = z, z_sp
    d.add_bool("2.80 (a ^ b ^ c) Ic = s1 ^ s2 up to scale", "2.80", proportional(z, z_sp))
    d.add("2.80 a fourth point of the circle: x ^ z* = 0", "2.80", D ^ z_dual, 0)
    Pz = _circle_plane_and_axis(d, Ic, e, e0, n, pi, q, z, z_dual)
    _circle_radius_and_sphere(d, Ic, Pz, e, q, r, z, z_sp)
    return d


def _circle_plane_and_axis(d: Derivation, Ic, e, e0, n, pi, q, z, z_dual):
    """(2.119)-(2.121): the plane and the axis of a circle z."""
    Pz = (z_dual ^ e).expand()
    d.add_bool("2.119 z* ^ e is the circle's plane (dual, up to scale)", "2.119", proportional(Pz, pi * inverse(Ic)))
    Lz = (z ^ e).expand()
    Q, Qn = up(q), up(add3(q, n))
    d.add("2.120 z ^ e passes through the centre and along n", "2.120", [Q ^ Lz, Qn ^ Lz], [0, 0])
    s_e0 = euclid(q) + e0  # the sphere about q through the origin: up(q) - q^2 e / 2
    d.add("2.121 s_e0 has centre q and passes through the origin", "2.121", [e0 | s_e0, s_e0 | e], [0, -1])
    d.add(
        "2.121 L_z* . P_z* = e ^ s_e0 (printed, thesis inner product)",
        "2.121",
        Lz | Pz,
        e ^ s_e0,
        expected=False,
        note="a 3-vector . 4-vector is a vector (here zero); the bivector e ^ s_e0 needs the dual",
    )
    LP = (Lz * Pz).expand()
    d.add("2.121 L_z* P_z* has no vector part", "2.121", LP.grade(1), 0)
    d.add_bool("2.121 L_z* P_z* = k (e ^ s_e0)* (corrected)", "2.121", proportional(LP, (e ^ s_e0) * inverse(Ic)))
    return Pz


def _circle_radius_and_sphere(d: Derivation, Ic, Pz, e, q, r, z, z_sp):
    """(2.122)-(2.124): the radius and the sphere of a circle z, and the numeric implementation."""
    z2 = (z * z).scalar()
    ez = e ^ z
    ez2 = (ez * ez).scalar()
    printed = sp.cancel(z2 / ez2)
    d.values["radius2"] = sp.cancel(-z2 / ez2)
    d.add("2.122 rho = z^2 / (e ^ z)^2 (printed)", "2.122", printed, r, expected=False)
    d.add(
        "2.122 rho^2 = z^2 / (e ^ z)^2 (printed, squared)",
        "2.122",
        printed,
        r**2,
        expected=False,
        note="the printed ratio is -rho^2",
    )
    d.add("2.122 rho^2 = -z^2 / (e ^ z)^2 (corrected)", "2.122", -z2 / ez2, r**2)
    d.add("2.122 z^2 and (e ^ z)^2 are scalars", "2.122", [(z * z).grade(2, 4), (ez * ez).grade(2, 4, 6)], [0, 0])
    sz = ((e | z) * z).expand()
    d.add("2.123 (e . z) z is a vector", "2.123", sz.grade(3), 0)
    s_z = sphere_from_center(q, r**2)
    d.add_bool("2.123 (e . z) z = sphere(q, r) up to scale", "2.123", proportional(sz, s_z))
    d.add_bool("2.123 also with z = s1 ^ s2", "2.123", proportional(((e | z_sp) * z_sp).expand(), s_z))
    fq, fr, fn = np.array([1.0, -2.0, 0.5]), 1.5, np.array([2.0, 3.0, 6.0]) / 7
    fu1, fu2 = np.array([3.0, -6.0, 2.0]) / 7, np.cross(fn, np.array([3.0, -6.0, 2.0]) / 7)
    cc, cr, cn = circle_center_radius(circle_from_points(fq + fr * fu1, fq + fr * fu2, fq - fr * fu1))
    d.add_bool(
        "2.119-2.124 entities.circle_center_radius at a sample circle",
        "2.122",
        np.allclose(cc, fq, atol=1e-12) and abs(cr - fr) < 1e-12 and np.allclose(cn, fn, atol=1e-12),
        lhs=(cc, cr, cn),
        rhs=(fq, fr, fn),
    )
    szd = (z * ~Pz).expand()  # = z / P_z* times the scalar P_z* ~P_z*
    d.add_bool("2.124 z / P_z* = s_z* up to scale", "2.124", proportional(szd, s_z * inverse(Ic)))


# --------------------------------------------------------------- lines
@derivation
def line_properties() -> Derivation:
    """Lines, Eqs. (2.81) and (2.125)-(2.130) with table 2.1.

    Symbolic points a, b for (2.81), (2.125) and the table's standard form;
    for the normalised line (2.126)-(2.129) the second point is
    ``b = a + lam r`` with lam > 0 and r a symbolic unit vector (identities
    reduced modulo ``r . r = 1``), so that |b - a| = lam needs no square root.  (2.130) is checked for
    a symbolic point x against the squared distance ``|x - a|^2 - ((x - a) . r)^2``.

    Returns
    -------
    Derivation
        values: ``L_dual`` (e ^ a ^ b), ``moment`` (-e+ . L of the unit line).
    """
    d = Derivation("Lines", ("2.81", "2.125", "2.126", "2.127", "2.128", "2.129", "2.130"))
    c = const()
    e, E, IE, Ic, ep = c.einf, c.E, c.IE, c.Ic, c.ep
    a_s = sp.symbols("a1:4", real=True)
    b_s = sp.symbols("b1:4", real=True)
    A, B = up(list(a_s)), up(list(b_s))
    a, b = euclid(a_s), euclid(b_s)
    Ld = e ^ A ^ B
    d.values["L_dual"] = Ld
    M = a ^ b
    d.add("2.81 e ^ a ^ b = e ^ a ^ b (Euclidean) + (b - a) ^ E", "2.81", Ld, (e ^ a ^ b) + ((b - a) ^ E))
    d.add("2.81 = e M + r E, r = b - a", "2.81", Ld, e * M + (b - a) * E)
    d.add("2.81 entities.line_from_points(a, b) = e ^ a ^ b", "2.81", line_from_points(a_s, b_s), Ld)
    L = Ld * Ic
    d.add(
        "table 2.1 line L = r I_E + e M I_E, r = a - b (printed)",
        "table 2.1",
        L,
        (a - b) * IE + e * M * IE,
        expected=False,
        note="with L = L* Ic and L* of (2.81), r = b - a",
    )
    d.add("table 2.1 line L = r I_E + e M I_E, r = b - a (corrected)", "table 2.1", L, (b - a) * IE + e * M * IE)
    d.add("2.125 (e ^ a ^ b)^2 = (a - b)^2", "2.125", Ld * Ld, dot3(sub3(a_s, b_s), sub3(a_s, b_s)))
    d.add("2.125 first step: -(b ^ a ^ e)(e ^ a ^ b)", "2.125", Ld * Ld, -((B ^ A ^ e) * Ld))
    _normalised_line(d, A, E, IE, Ic, a, a_s, e, ep)
    _line_numeric(d)
    _point_line_distance(d, a_s, b_s, e)
    return d


def _normalised_line(d: Derivation, A, E, IE, Ic, a, a_s, e, ep):
    """(2.125)-(2.129): the normalised line through a with unit direction r."""
    # normalised line through a with unit direction r (r1^2 + r2^2 + r3^2 = 1)
    r = list(sp.symbols("r1:4", real=True))
    lam = sp.Symbol("lam", positive=True)
    unit = Ring([*r, *a_s, lam], [dot3(r, r) - 1])
    b2 = add3(a_s, scale3(lam, r))
    Ld2 = e ^ A ^ up(b2)
    d.add("2.126 L* L* = lam^2 = |b - a|^2", "2.126", Ld2 * Ld2, lam**2, rel=unit)
    Ln = Ld2 * (1 / lam)
    d.add("2.126 normalised: L* L* = 1", "2.126", Ln * Ln, 1, rel=unit)
    d.add("2.127 r = L* . E is the unit direction b - a", "2.127", Ln | E, euclid(r), rel=unit)
    Lstd = Ln * Ic
    m_true = euclid(cross3(a_s, r))
    d.add(
        "2.128 m = e+ L (printed)",
        "2.128",
        ep * Lstd,
        m_true,
        expected=False,
        rel=unit,
        note="e+ L has other grades, and its vector part is -(a x r)",
    )
    d.add("2.128 vector part of e+ L = -(a x r)", "2.128", (ep * Lstd).grade(1), -m_true, rel=unit)
    moment = -(ep | Lstd)
    d.values["moment"] = moment
    d.add("2.128 m = -e+ . L = a x r (corrected)", "2.128", moment, m_true, rel=unit)
    Mb = moment * IE
    closest = sub3(a_s, scale3(dot3(a_s, r), r))
    d.add(
        "2.129 p = -r . M, M = m I_E, is the closest point to the origin",
        "2.129",
        -(euclid(r) | Mb),
        euclid(closest),
        rel=unit,
    )
    d.add("2.129 M = m I_E = a ^ r", "2.129", Mb, a ^ euclid(r), rel=unit)


def _line_numeric(d: Derivation):
    """The numeric implementations of (2.127)-(2.130), at a sample line and point."""
    # the numeric implementations of (2.127)-(2.130), at a sample line and point
    fa, fb, fx = np.array([1.0, 2.0, -1.0]), np.array([3.0, -1.0, 2.0]), np.array([0.5, 0.0, 4.0])
    fL = line_from_points(fa, fb)
    fr = (fb - fa) / np.linalg.norm(fb - fa)
    d.add_bool(
        "2.127-2.130 entities line_direction, line_moment, line_closest_point, point_line_distance at a sample",
        "2.128",
        np.allclose(line_direction(fL), fr, atol=1e-12)
        and np.allclose(line_moment(fL), np.cross(fa, fr), atol=1e-12)
        and np.allclose(line_closest_point(fL), fa - np.dot(fa, fr) * fr, atol=1e-12)
        and abs(point_line_distance(fx, fL) - np.linalg.norm(np.cross(fx - fa, fr))) < 1e-12,
    )


def _point_line_distance(d: Derivation, a_s, b_s, e):
    """(2.130): the distance of a symbolic point x from a line through two rational points."""
    # (2.130) distance of a symbolic point x from a line through two rational points
    xs = sp.symbols("x1:4", real=True)
    ring = Ring(xs)  # exact polynomial arithmetic in x
    X = ring.lift(up(list(xs)))
    a_s = [sp.Integer(1), sp.Integer(2), sp.Integer(-1)]
    b_s = [sp.Integer(3), sp.Integer(-1), sp.Integer(2)]
    er = ring.lift(e)
    zc = ring.lift(e ^ up(a_s) ^ up(b_s)) | X
    pl = zc | er
    pl2 = (pl * pl).scalar()
    # z P^-1 = z P / P^2, so (z P^-1)^2 = (z P z P) / (P^2)^2: compare numerators
    # with the distance |x - a|^2 - ((x - a) . (b - a))^2 / |b - a|^2
    xa = sub3(xs, a_s)
    ba = sub3(b_s, a_s)
    dist2_num = dot3(xa, xa) * dot3(ba, ba) - dot3(xa, ba) ** 2
    d.add(
        "2.130 ((L* . x)/(L* . x . e))^2 = squared distance",
        "2.130",
        zc * pl * zc * pl * ring.scalar(dot3(ba, ba)),
        ring.scalar(ring.element(dist2_num) * pl2**2),
        note="both sides multiplied by (P^2)^2 |b - a|^2",
    )
    d.add("2.130 L* . x . e is a plane (e . P = 0)", "2.130", pl | er, 0)
