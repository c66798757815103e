"""Drawing the entities of section 4.1: the segment of a line, a circle and a plane's square as polylines.

4.1 draws a line from its direction (2.127) and the point nearest the origin (2.129) between the endpoints of a
stored point pair (2.131), and a circle (and a plane's square) by turning a perpendicular vector with rotors about
the normal (2.96, 2.98).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

from . import validate as vd

__all__ = ["line_polyline", "circle_polyline", "square_polyline", "frame"]


def frame(normal, hint=(0.0, 0.0, 1.0)):
    """Two unit vectors u, v spanning the plane orthogonal to ``normal`` (v along ``hint`` if possible)."""
    n = vd.direction(normal, "frame", "normal")
    v = np.asarray(hint, dtype=float) - np.dot(hint, n) * n
    if np.linalg.norm(v) < 1e-6:
        v = np.eye(3)[np.argmin(np.abs(n))] - n * n[np.argmin(np.abs(n))]
    v = vd.direction(v, "frame", "hint")
    return np.cross(v, n), v


def line_polyline(L, PP) -> np.ndarray:
    """The drawn segment of a line as 4.1 describes it (2.126, 2.127, 2.129, 2.131).

    The line is normalised, its direction r and the point p closest to the
    origin extracted; the endpoints of the stored point pair PP, projected onto
    the line, say how far from p to draw.

    Returns
    -------
    ndarray, shape (2, 3)
    """
    f = "line_polyline"
    L, PP = vd.entity(L, f, "L", ("line",)), vd.entity(PP, f, "PP", ("point pair",))
    r, p = cga.line_direction(L), cga.line_closest_point(L)
    ends = np.array(cga.point_pair_endpoints(PP))
    t = (ends - p) @ r
    return checks.finite_result(p + t[:, None] * r, f, "L, PP")


def circle_polyline(center, normal, radius, n: int = 64, phase: float = 0.0) -> np.ndarray:
    """Points on a circle drawn as in 4.1: a perpendicular vector turned by a rotor (2.96).

    A unit vector v orthogonal to the normal is scaled by the radius, turned
    about the normal by the rotors ``R_z(theta)`` (2.96, 2.98) and shifted by
    the centre.

    Returns
    -------
    ndarray, shape (n + 1, 3)
        Closed polyline (last point = first).
    """
    f = "circle_polyline"
    center, normal = vd.array(center, f, "center", (3,)), vd.direction(normal, f, "normal")
    radius = checks.real(radius, f, "radius", low=0.0, high=vd.LIMIT)
    n, phase = checks.integer(n, f, "n", low=1, high=10**7), checks.real(phase, f, "phase")
    return _circle(center, normal, radius, n, phase)


def _circle(center, normal, radius: float, n: int, phase: float) -> np.ndarray:
    u, _ = frame(normal)
    theta = phase + np.linspace(0.0, 2 * np.pi, n + 1)
    R = cga.rotor(normal, theta)  # a batch of rotors about the normal
    v = cga.vector(radius * u)
    return center + cga.euclidean(R * v * ~R)


def square_polyline(center, normal, half_diagonal) -> np.ndarray:
    """The square 4.1 draws for a plane: the circle construction with four 90-degree turns.

    Returns
    -------
    ndarray, shape (5, 3)
    """
    f = "square_polyline"
    center, normal = vd.array(center, f, "center", (3,)), vd.direction(normal, f, "normal")
    half_diagonal = checks.real(half_diagonal, f, "half_diagonal", low=0.0, high=vd.LIMIT)
    return _circle(center, normal, half_diagonal, 4, np.pi / 4)
