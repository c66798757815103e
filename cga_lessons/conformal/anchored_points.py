"""A plain conformal point read as an anchored entity (:mod:`cga_lessons.conformal.anchored`): ``w up(x) = T_x
(w e0) ~T_x`` (2.62, 2.100), anchored at x with the local blade ``w e0``.

:func:`point_frame` decides whether a vector is a point to the resolution of its coefficients and reads its anchor
and weight as :func:`~cga_lessons.conformal.down` does (2.111, 2.114); :func:`point_about` is its local blade in
another anchor's frame, in closed form.  :mod:`~cga_lessons.conformal.anchored_ops` takes such points as operands,
and :mod:`~cga_lessons.conformal.point_wedges` anchors the ``^``, ``+``, ``-`` of plain points.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons.algebra import Multivector
from cga_lessons.scratch import scratch

from .model import G41
from .points import SUM_OVER_WEIGHT

__all__ = ["POINT_RTOL", "VECTOR", "WEIGHT_ULPS", "point_about", "point_frame", "point_parts"]

_FLOATS = (float, np.float64)
#: The blades of a vector of G(4,1): e1, e2, e3, e+, e-.
VECTOR = frozenset((1, 2, 4, 8, 16))
_EPS = float(np.finfo(float).eps)
#: A weight ``X_- - X_+`` within this many float epsilons of ``|X_-| + |X_+|`` is round-off (as for ``down``).
WEIGHT_ULPS = 4 * _EPS
#: A vector is read as a point when ``|s w - |E|^2| <= POINT_RTOL (|w| (|X_+| + |X_-|) + |E|^2)``, with
#: ``w = X_- - X_+``, ``s = X_+ + X_-`` and E its Euclidean part (:func:`point_frame`).
POINT_RTOL = 8 * _EPS


def point_frame(X: Multivector):
    """``(anchor, weight)`` when X is a conformal point, ``w up(x) = T_x (w e0) ~T_x`` (2.62, 2.100): an entity
    anchored at x whose local blade is ``w e0``; None for anything else.

    X is a point when it is a vector of real floats (one, or a batch of arrays of one shape) whose coefficients are
    those of a null vector of finite, non-zero weight to the resolution of its coefficients: with ``w = X_- - X_+``
    (``-e . X``, 2.111), ``s = X_+ + X_-`` and E the Euclidean part, ``X . X = E^2 - s w = 0`` (2.61) within
    :data:`POINT_RTOL` of ``|w| (|X_+| + |X_-|) + E^2`` (the sizes of its terms: s holds ``(|X_+| + |X_-|) eps``
    of round-off, ``w^2 x^2 + 1`` near the origin, about ``2 w^2 x^2`` far out), and w beyond :data:`WEIGHT_ULPS`
    of the terms it is the difference of.  Then ``x = E / w`` (2.114), as :func:`~cga_lessons.conformal.down` reads
    it (far out, where ``|X_+| + |X_-|`` passes :data:`~cga_lessons.conformal.points.SUM_OVER_WEIGHT` times w, with w
    read as ``E^2 / s``), to the accuracy of w, which the test bounds (``s w = E^2`` to 8 eps): exact where the
    weight is stored exactly (the images of ``up(x)`` under a motor, ``2 up(x)`` ... from 1e3 to 6.7e7 out, but for
    a fraction ~2/x^2 of them), a few eps of x nearer (measured: at most 8 eps |x| near |x| = 1-30).  A vector whose
    coefficients are bit for bit those ``up`` stores for its Euclidean part E (``(E^2 -+ 1) / 2``) is ``up(E)``:
    anchored at E, weight 1, even where ``x^2 + 1`` rounded its weight (a fraction ~2/x^2 of all x, by up to
    eps x^2 / 4, beyond the test from |x| = 8 on: ``2 up(x)`` or ``apply(M, up(x))`` of such an x is left plain).

    The test is as fine as the storage.  A sphere of radius rho about c, ``w (up(c) - rho^2 e / 2)``, has
    ``s w - E^2 = -w^2 rho^2``: it is read as a point only when ``rho^2 < 8 eps (max(|c|^2, 1) + |c|^2)`` (rho
    below 4e-8 at the origin, 0.06 at 1e6), where its e+/e- coefficients do not hold its radius (a reader of the
    sphere gets rho^2 to ~16 eps (|c|^2 + 1), :mod:`~cga_lessons.conformal.entities_frame`): to the storage it is
    a point.  A point whose weight the rounding of its e+/e- coefficients changed (``up(x) / 3`` beyond ~30 from
    the origin: w off by ~eps |x|^2 of itself) fails the test, since its coefficients do not tell it from a sphere
    (of radius ~3e-8 |x|^2); it is left plain.
    """
    parts = point_parts(X)
    if parts is None or type(parts[0]) is np.ndarray:
        return parts
    anchor = np.array(parts[0])
    anchor.flags.writeable = False
    return anchor, parts[1]


def point_parts(X: Multivector):
    """:func:`point_frame` with the anchor of one point as a tuple of three floats (an array is made when needed)."""
    c = X._c
    if not c.keys() <= VECTOR or (8 not in c and 16 not in c):  # (up(x) with |x| = 1 has no e+ coefficient)
        return None
    xp, xm = c.get(8, 0.0), c.get(16, 0.0)
    x1, x2, x3 = c.get(1, 0.0), c.get(2, 0.0), c.get(4, 0.0)
    if type(xp) is np.ndarray or type(xm) is np.ndarray:
        return _batch_point_frame(xp, xm, x1, x2, x3)
    if not (type(xp) is float and type(xm) is float and type(x1) is float and type(x2) is float
            and type(x3) is float):  # fmt: skip
        if not all(type(v) in _FLOATS for v in (xp, xm, x1, x2, x3)):
            return None
        xp, xm, x1, x2, x3 = float(xp), float(xm), float(x1), float(x2), float(x3)
    w, s, q = xm - xp, xp + xm, x1 * x1 + x2 * x2 + x3 * x3
    if xp == 0.5 * (q - 1.0) and xm == 0.5 * (q + 1.0):  # the bits of up(E) (2.62): the point E, of weight one
        w = 1.0
    else:
        t = abs(xm) + abs(xp)
        if not abs(w) > WEIGHT_ULPS * t or not abs(s * w - q) <= POINT_RTOL * (abs(w) * t + q):
            return None  # (NaN and inf fail the comparisons)
        if t > SUM_OVER_WEIGHT * abs(w):  # far out: the weight as down reads it, |E|^2 / (X_+ + X_-)
            w = q / s
    y1, y2, y3 = x1 / w, x2 / w, x3 / w
    if not (math.isfinite(y1) and math.isfinite(y2) and math.isfinite(y3)):
        return None
    return (y1, y2, y3), float(w)


def _batch_point_frame(xp, xm, x1, x2, x3):
    """:func:`point_frame` of a batch: every coefficient an array of floats of one shape (a missing one 0.0),
    every member a point; else None."""
    shape = (xp if type(xp) is np.ndarray else xm).shape
    for v in (xp, xm, x1, x2, x3):
        if type(v) is not float and (type(v) is not np.ndarray or v.dtype.kind != "f" or v.shape != shape):
            return None
    if not shape or 0 in shape:
        return None
    # Working rows kept by the thread (cga_lessons.scratch): fresh megabytes would cost a page fault per 4 kB.
    w, s, q, t, u, v = scratch(6 * math.prod(shape), "point_frame").reshape((6,) + shape)
    with np.errstate(all="ignore"):
        np.subtract(xm, xp, out=w)  # the weight, -e . X (2.111)
        np.multiply(x1, x1, out=q)  # E^2
        q += np.multiply(x2, x2, out=u)
        q += np.multiply(x3, x3, out=u)
        exact = np.multiply(np.subtract(q, 1.0, out=u), 0.5, out=u) == xp  # the bits of up(E) (2.62)
        exact &= np.multiply(np.add(q, 1.0, out=u), 0.5, out=u) == xm
        if not np.all(exact):
            np.add(xp, xm, out=s)
            np.abs(xm, out=t)  # |X_+| + |X_-|
            t += np.abs(xp, out=u)
            ok = np.abs(w, out=u) > np.multiply(t, WEIGHT_ULPS, out=v)
            s *= w  # s w - E^2 (2.61) against POINT_RTOL (|w| (|X_+| + |X_-|) + E^2)
            s -= q
            u *= t
            u += q
            u *= POINT_RTOL
            ok &= np.abs(s, out=s) <= u
            if not np.all(ok | exact):
                return None
            far = ~exact & (t > SUM_OVER_WEIGHT * np.abs(w))  # the weight as down reads it far out
            if far.any():
                sums = np.broadcast_to(np.add(xp, xm), shape)
                w[far] = q[far] / sums[far]
        w[exact] = 1.0
        anchor = np.empty(shape + (3,))
        if np.all(w == 1.0):  # up(x) and its images under a motor: x is E, the weight one number
            anchor[..., 0], anchor[..., 1], anchor[..., 2] = x1, x2, x3
            w = 1.0
        else:
            for i, x in enumerate((x1, x2, x3)):
                np.divide(x, w, out=anchor[..., i])
            w = w.copy()  # the weight outlives the call
    if not np.all(np.isfinite(anchor)):
        return None
    anchor.flags.writeable = False
    return anchor, w


def point_about(w, g, f) -> Multivector:
    """The point of weight w at g (:func:`point_frame`) about the anchor f: ``T_{g-f} (w e0) ~T_{g-f} = w up(g - f)``
    (2.62, 2.100), in closed form from y = g - f (``w e0`` when the anchors are one)."""
    if g is f:
        return Multivector(G41, {8: -0.5 * w, 16: 0.5 * w})
    if type(w) is float and g.shape == (3,) and f.shape == (3,):  # one point about one anchor: in floats
        y1, y2, y3 = float(g[0] - f[0]), float(g[1] - f[1]), float(g[2] - f[2])
        yy = y1 * y1 + y2 * y2 + y3 * y3
        parts = (w * y1, w * y2, w * y3, 0.5 * w * (yy - 1.0), 0.5 * w * (yy + 1.0))
        return Multivector(G41, {b: v for b, v in zip((1, 2, 4, 8, 16), parts) if v != 0})
    y = np.asarray(g - f, dtype=float)
    yy = (y * y).sum(axis=-1)
    parts = (w * y[..., 0], w * y[..., 1], w * y[..., 2], 0.5 * w * (yy - 1.0), 0.5 * w * (yy + 1.0))
    shape = np.broadcast_shapes(y.shape[:-1], np.shape(w))
    return Multivector(G41, {b: np.broadcast_to(v, shape).copy() for b, v in zip((1, 2, 4, 8, 16), parts)})
