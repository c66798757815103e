"""The least-squares motor of corresponding oriented lines (Gauss-Newton on the motor's 6 parameters), next to
:mod:`cga_lessons.conformal.motor_estimation` (points, quaternions, means), whose eigenrotor it starts from.
"""

from __future__ import annotations

import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, GeometryError, InvalidInputError, Multivector

from .lines_circles import line_direction, line_moment
from .motor_estimation import item_sequence, pair_weights, rotor_from_coeffs, rotor_matrix, top_eigenvector
from .multivector_checks import multivector
from .versors import apply_to_points
from .versors_build import rotor, translator
from .versors_rigid import decompose_motor, motor_to_matrix

__all__ = ["motor_from_lines"]


def _plucker(lines, func: str, name: str):
    """Unit directions and moments (N, 3) of a sequence (or batch) of lines, Eqs. (2.126)-(2.128)."""
    items = (
        [lines] if isinstance(lines, Multivector) else item_sequence(lines, func, name, "CGA lines (line_from_points)")
    )
    for L in items:
        multivector(L, func, name, what="a CGA line (line_from_points)")
    try:
        d = np.vstack([np.reshape(line_direction(L), (-1, 3)) for L in items])
        m = np.vstack([np.reshape(line_moment(L), (-1, 3)) for L in items])
    except (GeometryError, AttributeError, TypeError) as exc:
        raise InvalidInputError(f"{func}: {name}: expected CGA lines (line_from_points): {exc}") from exc
    if not (np.all(np.isfinite(d)) and np.all(np.isfinite(m))):
        raise InvalidInputError(f"{func}: {name}: contains NaN or inf")
    return d, m


def _line_centre(d, m, w, func: str, name: str):
    """Point c minimising sum_i w_i dist(c, L_i)^2 (needs two non-parallel lines)."""
    sv = np.linalg.svd(np.sqrt(w)[:, None] * d, compute_uv=False)
    if sv[1] <= 1e-10 * sv[0]:
        raise DegenerateGeometryError(f"{func}: {name}: the lines are all parallel (the motion along them is unknown)")
    P = np.eye(3) - d[:, :, None] * d[:, None, :]  # projectors orthogonal to each line
    p = np.cross(d, m)  # closest point to the origin of each unit line (2.129)
    return np.linalg.solve(np.einsum("i,ijk->jk", w, P), np.einsum("i,ijk,ik->j", w, P, p))


def _skew(v):
    """The cross-product matrices [v]x (N, 3, 3) with [v]x u = v x u."""
    return np.cross(v[:, None, :], np.eye(3)).transpose(0, 2, 1)


def _lines_start(ds, ms, dt_, mt, w, func: str) -> Multivector:
    """Step 1 of :func:`motor_from_lines`: the rotor of the directions (an eigenrotor), then the translation that
    minimises the cost for that rotor (linear); the moments ``ms``, ``mt`` are about the lines' centres."""
    r = top_eigenvector(
        rotor_matrix((w[:, None] * ds).T @ dt_), func, "source_lines", "the rotation of the directions is not unique"
    )
    R = rotor_from_coeffs(r / np.linalg.norm(r))
    u, Rm = apply_to_points(R, ds), apply_to_points(R, ms)
    lhs = np.einsum("i,ijk->jk", w, np.eye(3) - u[:, :, None] * u[:, None, :])
    return translator(np.linalg.solve(lhs, w @ np.cross(u, mt - Rm))) * R


def _refine_lines(M, ds, ms, dt_, mt, w, length_scale: float, max_iterations: int) -> Multivector:
    """Gauss-Newton on the 6 parameters of ``T(dt) R(omega) M`` for :func:`motor_from_lines` (its step 2)."""

    def residual(M):
        H = motor_to_matrix(M)
        u = ds @ H[:3, :3].T
        mu = ms @ H[:3, :3].T + np.cross(H[:3, 3], u)
        res = np.concatenate([mu - mt, length_scale * (u - dt_)], axis=1) * np.sqrt(w)[:, None]
        return res, u, mu

    res, u, mu = residual(M)
    cost = float(np.sum(res**2))
    sw = np.sqrt(w)[:, None, None]
    size = max(length_scale, float(np.sqrt(w @ np.sum(mt**2, axis=1) / w.sum())))  # metres per radian of a step
    for _ in range(max_iterations):
        Su = _skew(u)
        J = np.concatenate(
            [np.concatenate([-_skew(mu), -Su], axis=2), np.concatenate([-length_scale * Su, 0 * Su], axis=2)], axis=1
        )
        step = -np.linalg.lstsq((J * sw).reshape(-1, 6), res.reshape(-1), rcond=None)[0]
        for _half in range(40):  # halve a step that raises E (beyond its round-off)
            ang = float(np.linalg.norm(step[:3]))
            trial = translator(step[3:]) * (rotor(step[:3], ang) if ang > 0 else 1.0) * M
            res2, u2, mu2 = residual(trial)
            if float(np.sum(res2**2)) <= cost * (1 + 1e-12):
                break
            step = step / 2
        else:
            break
        M, res, u, mu, cost = trial, res2, u2, mu2, float(np.sum(res2**2))
        if np.linalg.norm(step[:3]) + np.linalg.norm(step[3:]) / size <= 1e-13:
            break
    return M


def motor_from_lines(
    source_lines, target_lines, weights=None, *, length_scale: float = 1.0, max_iterations: int = 50
) -> Multivector:
    """Least-squares motor of corresponding oriented lines (at least 2 non-parallel), Gauss-Newton on 6 parameters.

    A motor moves the line with unit direction d and moment m (2.127, 2.128) to ``M L ~M`` (2.103), with
    direction ``u = R d`` and moment ``mu = R m + t x R d``.  The cost, with ``(d'_i, m'_i)`` the targets, is

        E(M) = sum_i w_i ( |mu_i - m'_i|^2 + length_scale^2 |u_i - d'_i|^2 ),

    the moments taken about the point c closest (least squares) to all the target lines, so that E does not
    depend on where the origin is; ``|mu_i - m'_i|`` measures how far the moved line passes from the target
    line near c.  ``length_scale`` (metres) weighs directions against positions.  Lines are oriented: orient
    each target like its source (``line_from_points(a, b)`` runs from a to b).  [VD11] treat lines with a
    closed form for a cost that is not origin-free; this function minimises the geometric cost above instead:

    1. start: the rotor from the directions (the eigenrotor of :func:`motor_from_points` with
       ``S = sum_i w_i d_i d'_i^T``, not centred), then the translation that minimises E for that rotor
       (linear, ``sum_i w_i (I - u_i u_i^T) t = sum_i w_i u_i x (m'_i - R m_i)``);
    2. Gauss-Newton: the increment ``M <- T(dt) R(omega) M`` changes ``u`` by ``omega x u`` and ``mu`` by
       ``omega x mu + dt x u``, giving a 6x6 linear system per step; a step that raises E is halved.  Stops
       when the step is below 1e-13 (radians, and metres over the lines' size) or after ``max_iterations``
       (``max_iterations=0`` returns the start).

    Noiseless data are recovered to round-off; with noise the result is the local minimum of E nearest the
    closed-form start (Gauss-Newton converges linearly, faster for smaller noise).  The lines are a sequence of
    lines or one batch (``line_from_points`` of (N, 3) arrays).  Precision: a CGA line built far from the origin
    carries its own error (its e+ and e- coefficients cancel in ``e ^ A ^ B``, about 1e-10 in the direction at
    100 m), so build the lines in a local frame.  Errors as for :func:`motor_from_points`
    (``"motor_from_lines: source_lines: <problem>"``).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> a, b = np.array([[0.0, 0, 0], [0, 1, 0], [1, 1, 1]]), np.array([[1.0, 0, 0], [0, 1, 1], [1, 2, 1]])
    >>> M0 = cga.motor([1, 1, 0], 0.4, [0.5, -1, 2])
    >>> M = motor_from_lines(cga.line_from_points(a, b),
    ...                      cga.line_from_points(cga.apply_to_points(M0, a), cga.apply_to_points(M0, b)))
    >>> bool(np.allclose(cga.motor_to_matrix(M), cga.motor_to_matrix(M0), atol=1e-12))
    True
    """
    func = "motor_from_lines"
    ds, ms = _plucker(source_lines, func, "source_lines")
    dt_, mt = _plucker(target_lines, func, "target_lines")
    checks.same_length(func, source_lines=ds, target_lines=dt_)
    w = pair_weights(weights, len(ds), func)
    if np.count_nonzero(w > 0) < 2:
        raise DegenerateGeometryError(f"{func}: source_lines: needs at least 2 lines with positive weight")
    length_scale = checks.real(length_scale, func, "length_scale", low=0.0, strict_low=True)
    if not isinstance(max_iterations, numbers.Integral):
        raise checks.fail(func, "max_iterations", f"must be a whole number (an int), got {max_iterations!r}")
    max_iterations = checks.integer(max_iterations, func, "max_iterations", low=0)
    cs = _line_centre(ds, ms, w, func, "source_lines")
    ct = _line_centre(dt_, mt, w, func, "target_lines")
    ms, mt = ms - np.cross(cs, ds), mt - np.cross(ct, dt_)  # moments about the centres
    M = _lines_start(ds, ms, dt_, mt, w, func)
    M = _refine_lines(M, ds, ms, dt_, mt, w, length_scale, max_iterations)
    Rf, tf = decompose_motor(M)
    # back to the original origin: x_t - ct = R (x_s - cs) + t  =>  t_total = ct + t - R cs
    return translator(ct + tf - apply_to_points(Rf, cs)) * Rf
