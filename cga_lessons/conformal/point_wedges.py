"""Raw wedges of plain conformal points, exact at any distance: ``up(a) ^ up(b) ^ up(c) ^ up(d)`` (the sphere of
table 2.1, 2.75) carries the local frame of :mod:`~cga_lessons.conformal.anchored`.

**The idea.**  A conformal point is itself translation-covariant: ``w up(x) = T_x (w e0) ~T_x`` (2.62, 2.100), an
entity anchored at x whose local blade is ``w e0``, and its coefficients hold x (``E / w``, 2.114, its Euclidean
part over its weight ``w = -e . X``, 2.111).  So the operators of plain points need not lose what the points hold:
:func:`framed_points`, registered on :data:`~cga_lessons.conformal.G41` as the algebra's operation hook
(:meth:`~cga_lessons.algebra.Algebra.set_operation_hook`), reads each operand of ``^``, ``+`` and ``-`` that is a
point (:func:`~cga_lessons.conformal.anchored_points.point_frame`: a null vector of finite, non-zero weight to the
resolution of its coefficients; never a sphere whose radius they resolve) as anchored at x with the local blade
``w e0``, and lets the frame follow (:func:`~cga_lessons.conformal.anchored_ops.follow`) when the other operand is
a point, anchored, or translation-invariant (e, ``e ^ A``, Ic, a scalar).  The result is an
:class:`~cga_lessons.conformal.Anchored`: its global coefficients are those of the plain operation, bit for bit;
its local blade, about the first point, is the same operation on ``w1 e0``, ``w2 up(x2 - x1)`` (built when first
read; the pair of two points in closed form, :func:`_pair`).  Anchored entities in turn take points as operands of
every covariant operation (``S ^ up(x)``, ``Z | up(x)``, :mod:`~cga_lessons.conformal.anchored_ops`), so a chain of
wedges keeps the frame from its first point on: ``up(a) ^ up(b)`` is the point pair (2.68), ``^ up(c)`` the circle
(2.80), ``^ up(d)`` the sphere (2.75), ``up(a) ^ up(b) ^ e`` the line (2.81), ``e ^ up(a) ^ up(b) ^ up(c)`` the
plane (2.77), ``up(c) - rho^2 e / 2`` the sphere of centre c (2.72), ``up(a) - up(b)`` the plane between them;
their readers (``sphere_center_radius``, ``circle_center_radius``, ``point_pair_endpoints``, the line and plane
readers, ``classify`` ...) are exact at any distance.

**Accuracy** (``tests/test_point_wedges.py``, against exact rationals).  The plain wedge of points near x holds
``|x|^2``-sized e+/e- coefficients whose differences are the entity's size, and the products add their round-off
(``eps |x|^4 / size^2`` relative): rho^2 of a unit sphere from a raw wedge was off by 8.5e-7 (relative) 100 from the
origin, 7e-2 at 1e3, 7e13 at 1e6 (a raw pair or line there was refused).  Through the frame: within 8.1e-16 at all
three (circles 8.8e-16, line distances 3e-16, pair ends to the rounding of their coordinates).  What remains is the
entity's own size s against the unit parts (+-1/2) of e0 in the e+/e- storage: rho^2 to ~eps / s^2 (measured
6.5e-9 for s = 1e-4, 4.8e-11 for 1e-3, whatever the distance; ``sphere_from_points`` 2.8e-8 and 2.9e-10); a pair is
exact at any size (its closed form).

**Layers and cost.**  The algebra does not import this layer: its ``^``, ``+`` and ``-`` call the hook when set
(one attribute read; the geometric and inner products, the versors' hot path, are not hooked).  The hook declines
in about a microsecond when an operand is neither a point, nor anchored, nor invariant (``M ^ X``: +1.6 us,
``e1 ^ X``: +1.2 us, a plain line ``^ e``: +0.1 us), the cheap tests first.  A recognised product adds the point test
and the closure that builds the local blade: ``up(a) ^ up(b)`` 3.0 -> 7.5 us, the four-point sphere 9 -> 25 us,
``up(c) - rho^2 e / 2`` 4.6 -> 10 us (reading the sphere then 56 -> ~150 us, where ``sphere_from_points`` and its
reader take 610 us); a batch of 100,000 points pays the test (0.6 ms, in the thread's scratch rows) and its anchors
(2.4 MB: fresh pages), ``A ^ B`` 6-7 -> 12.6 ms.  ``up``, ``down``, ``apply`` and the versors are untouched
(``benchmarks/bench_motor.py`` unchanged; ``apply(M, up(x))`` stays a plain point, recognised when it meets another
one).  No threshold near the origin: there the plain wedge and the frame hold rho^2 alike (``eps (|x|^4 + 1) /
s^2`` against ``eps / s^2``: the frame gains from |x| ~ 1 on, for an entity of any size s, which the first wedge
does not know yet), the frame costs the same everywhere, and an entity that changed type with its position would
surprise.  A frame is never built for SymPy input (exact), a vector that is no point to the storage's resolution
(a sphere whose radius it resolves; ``up(x) / 3`` 1e6 out, whose weight it does not), or a plain blade
(``Multivector(G41, dict(X.coeffs))`` of a wedge keeps the storage's limit).
"""

from __future__ import annotations

import operator

import numpy as np

from cga_lessons.algebra import GeometryError, Multivector

from .anchored import Anchored, pair_about_an_end
from .anchored_ops import NoFrame, Pending, follow, operand_kinds, read_only, unhooked
from .model import G41

__all__ = ["framed_points"]


_LOCAL = {"+": unhooked("+", operator.add), "-": unhooked("-", operator.sub), "^": unhooked("^", operator.xor)}


def framed_points(Y: Multivector, op: str, A: Multivector, B: Multivector) -> Multivector:
    """The operation hook of G41 (:meth:`~cga_lessons.algebra.Algebra.set_operation_hook`): ``Y = A op B`` (the
    plain result) anchored when an operand is a plain conformal point and the other a point, an anchored entity or
    translation-invariant (module docstring); Y itself otherwise."""
    if not Y._c:
        return Y
    kinds = operand_kinds((A, B))  # the cheap tests first: a motor or e1 is declined before a point is read
    if kinds is None:
        return Y
    if op == "^" and type(kinds[0]) is tuple and type(kinds[1]) is tuple:
        return _pair(Y, *kinds)
    return follow(Y, _LOCAL[op], A, B, derive=Anchored.derive, kinds=kinds)


def _pair(Y: Multivector, a, b) -> Anchored:
    """``Y = A ^ B`` of two points ``(anchor, weight)``, anchored at A's point with the local blade in closed form:
    ``T_{-x_a} Y ~T_{-x_a} = w_a w_b e0 ^ up(y) = w_a w_b (e0 ^ y - |y|^2 / 2 E)``, y = x_b - x_a (2.68; the local blade
    of ``point_pair``, :func:`~cga_lessons.conformal.anchored.pair_about_an_end`): |y|^2 kept apart from the unit
    e+/e- parts of e0, so that the pair is exact at any size (a product of the two local points would hold
    ``|y|^2 / 2`` beside 1/2: eps / |y|^2 relative)."""
    (f, wa), (g, wb) = a, b

    def build():
        try:
            x = np.array(f, dtype=float)
            y = np.asarray(g, dtype=float) - x
            L = pair_about_an_end(np.zeros_like(y), y) * (wa * wb)
            if L.shape != Y.shape:
                raise NoFrame("the local blade has another batch shape")
            return read_only(x, Y.shape), L
        except NoFrame:
            raise
        except (GeometryError, ArithmeticError) as exc:
            raise NoFrame(str(exc)) from None

    return Anchored.derive(Y, Pending(build, 1))


G41.set_operation_hook(framed_points)
