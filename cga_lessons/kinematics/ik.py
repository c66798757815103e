"""Inverse kinematics of a chain of motors by damped least squares (Levenberg-Marquardt), batched.

For a target pose ``M_t`` and joint values q, the error is the motor ``D = M_t ~M(q)`` that would carry the
end effector from where it is to the target, and its logarithm, the bivector ``log D = -theta/2 l + e ^ w``
(the inverse of 2.110; :func:`cga_lessons.conformal.versor_log.motor_log`), read as the spatial twist
``e = (theta n, 2 w)`` (:func:`cga_lessons.kinematics.twist_of_bivector`).  The spatial Jacobian J of the
moved axis lines (:func:`cga_lessons.kinematics.spatial_jacobian`) maps joint rates to the same twists, so
one Gauss-Newton step solves ``J dq = e``.  Damped (Levenberg 1944, Marquardt 1963; Wampler 1986 and
Nakamura & Hanafusa 1986 for robot arms)::

    dq = J^T (J J^T + lambda I)^-1 e        (n >= 6; the same as (J^T J + lambda I)^-1 J^T e, used for n < 6)

with lambda updated by Nielsen's rule (1999) from the gain ratio rho of the actual to the predicted decrease
of ``|e|^2``: after a step that lowers it lambda shrinks (by up to 3), after one that does not the step is
refused and lambda grows by 2, 4, 8, ...  Far from the target the steps are short and safe, near it they are
Newton's, which converge quadratically.  A target whose steps are refused ``restart_after`` times in a row is
stuck in a local minimum (in practice at a singular configuration, where J^T e = 0) and restarts its revolute
joints from random values (:class:`IKOptions`).  Every target runs in the same NumPy arrays (N targets at
once); each stops on its own when both its position error ``|t(q) - t_t|`` and its rotation error (the angle
of D) are within tolerance, and reports whether it did, after how many iterations (each one FK and one
Jacobian of the trial configuration).

>>> import numpy as np
>>> from cga_lessons import kinematics as kin
>>> arm = kin.chain([kin.revolute([0, 0, 1]), kin.revolute([0, 0, 1], point=[1, 0, 0])], home=[2.0, 0.0, 0.0])
>>> target = kin.forward_motor(arm, [0.4, 0.9])
>>> r = inverse_kinematics(arm, target, [0.3, 0.7])
>>> bool(r.converged), r.q.round(9), bool(r.position_error < 1e-10)
(True, array([0.4, 0.9]), True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector

from .motor_chain import Chain, check_configuration, jacobian_and_pose
from .motor_numbers import REVERSE_SIGNS, coefficients_to_matrix_unchecked, motor_coefficients, multiply_batches

__all__ = ["IKOptions", "IKResult", "inverse_kinematics", "twist_error"]


@dataclass(frozen=True)
class IKOptions:
    """Settings of :func:`inverse_kinematics` (metres, radians).

    A target counts as reached when its position error is at most ``tol_position`` and its rotation error at
    most ``tol_rotation``.  ``damping`` is the initial lambda (in units of J J^T, about m^2 for metre arms),
    ``damping`` is the initial lambda relative to the mean of diag(J J^T), ``max_step`` caps ``|dq|`` of one
    step.  After ``restart_after`` refused steps in a row (the error stuck in a local minimum, in practice at a
    singular configuration) the revolute joints restart from values drawn uniformly in [-pi, pi) by a
    generator seeded with ``seed`` (``restart_after=None``: never); the iterations keep counting.
    """

    max_iterations: int = 50
    tol_position: float = 1e-10
    tol_rotation: float = 1e-10
    damping: float = 1e-3
    max_step: float = 1.0
    restart_after: int | None = 3
    seed: int = 0

    def __post_init__(self):
        f = "IKOptions"
        for name, low in (("max_iterations", 0), ("restart_after", 1), ("seed", 0)):
            v = getattr(self, name)
            if not (v is None and name == "restart_after"):
                object.__setattr__(self, name, checks.integer(v, f, name, low=low))
        for name in ("tol_position", "tol_rotation", "damping", "max_step"):
            object.__setattr__(self, name, checks.real(getattr(self, name), f, name, low=0.0, strict_low=True))


@dataclass(frozen=True, eq=False)
class IKResult:
    """What :func:`inverse_kinematics` reached, per target (arrays of shape (N,), or scalars for one target).

    ``q`` is the last accepted configuration, whether it converged or not; ``iterations`` counts the steps
    taken (0 when the start was already on the target).
    """

    q: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    position_error: np.ndarray
    rotation_error: np.ndarray

    @property
    def success_rate(self) -> float:
        """The fraction of targets reached."""
        return float(np.mean(self.converged))


def twist_error(D: np.ndarray):
    """Spatial twist ``(omega, v)`` (N, 6) of ``log D``, with the translation (N, 3) and angle (N,) of D.

    D holds motor numbers (N, 8).  With ``D = T R``, ``R = cos(theta/2) - sin(theta/2) n I_E`` (2.95) folded to
    theta in [0, pi] (D and -D are one motion) and t its translation (2.144)::

        omega = theta n,   v = f t + g (omega . t) omega - omega x t / 2,
        f = (theta/2) cot(theta/2),   g = (1 - f) / theta^2,

    the twist of :func:`cga_lessons.conformal.versor_log.motor_log` (``v = 2 w``), summed by a series near theta = 0.
    """
    return _twist_error(checks.array(D, "twist_error", "D", (None, 8)))


def _twist_error(D: np.ndarray):
    D = D * np.where(D[:, :1] < 0, -1.0, 1.0)
    D = D / np.linalg.norm(D[:, :4], axis=1, keepdims=True)
    u = np.stack([-D[:, 3], D[:, 2], -D[:, 1]], axis=1)  # sin(theta/2) n, from 2.96
    s = np.linalg.norm(u, axis=1)
    c = D[:, 0]
    half = np.arctan2(s, c)
    ratio = np.where(s > 1e-8, half / np.where(s > 0, s, 1.0), (1.0 + s * s / 6.0) / c)  # half / sin(half)
    omega = 2.0 * ratio[:, None] * u
    t = coefficients_to_matrix_unchecked(D)[:, :3, 3]
    h2 = half * half
    small = half < 1e-2
    safe = np.where(small, 1.0, half)
    f = np.where(small, 1.0 - h2 / 3.0 - h2 * h2 / 45.0, safe * c / np.where(small, 1.0, s))
    g = np.where(small, 1.0 / 12.0 + h2 / 180.0 + h2 * h2 / 1890.0, (1.0 - f) / (4.0 * safe * safe))
    v = f[:, None] * t + (g * np.einsum("ni,ni->n", omega, t))[:, None] * omega - 0.5 * np.cross(omega, t)
    return np.concatenate([omega, v], axis=1), t, 2.0 * half


def _solve(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Batched ``A x = b``; a (numerically) singular A falls back to least squares for the whole batch."""
    try:
        return np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        return np.linalg.pinv(A) @ b


def _targets(target, func: str) -> np.ndarray:
    if isinstance(target, Multivector):
        c = motor_coefficients(target, func, "target")
        return c.reshape(-1, 8)
    if not isinstance(target, (list, tuple, np.ndarray)):
        raise checks.fail(func, "target", f"expected a motor, a 4x4 matrix or (N, 4, 4), got {type(target).__name__}")
    H, _ = checks.batch(target, func, "target", (4, 4))
    from cga_lessons import conformal as cga

    out = []
    for Hi in H.reshape(-1, 4, 4):  # the checked conversion of one matrix (a rigid transform or an error)
        with checks.relabel(func, "target"):
            out.append(motor_coefficients(cga.matrix_to_motor(Hi), func, "target"))
    return np.array(out).reshape(-1, 8)


def _errors(Mt: np.ndarray, M: np.ndarray, t_target: np.ndarray):
    """The twist error (N, 6), rotation error (N,) and position error (N,) of poses M (N, 8) from targets Mt."""
    err, _, angle = _twist_error(multiply_batches(Mt, M * REVERSE_SIGNS))
    return err, angle, np.linalg.norm(t_target - coefficients_to_matrix_unchecked(M)[:, :3, 3], axis=1)


def _damped_step(J: np.ndarray, e: np.ndarray, lam: np.ndarray, opt: IKOptions):
    """The damped least-squares step dq (N, n) for Jacobians J (N, 6, n) and errors e (N, 6), clipped to
    ``opt.max_step``; with the damping used (``lam``, a fresh one where it is NaN)."""
    n = J.shape[2]
    JT = np.swapaxes(J, 1, 2)
    G = J @ JT if n >= 6 else JT @ J
    lam = lam.copy()
    fresh = np.isnan(lam)
    lam[fresh] = opt.damping * np.einsum("kii->k", G)[fresh] / G.shape[1]
    A = G + lam[:, None, None] * np.eye(min(n, 6))
    if n >= 6:
        dq = (JT @ _solve(A, e[:, :, None]))[:, :, 0]
    else:
        dq = _solve(A, JT @ e[:, :, None])[:, :, 0]
    step = np.linalg.norm(dq, axis=1)
    return dq * np.minimum(1.0, opt.max_step / np.maximum(step, 1e-300))[:, None], lam


def inverse_kinematics(ch: Chain, target, q0, options: IKOptions | None = None) -> IKResult:
    """Joint values reaching ``target`` from the start ``q0``, by damped least squares (module docstring).

    Parameters
    ----------
    ch : Chain
    target : Multivector (one motor or a batch of N) or 4x4 matrices (4, 4) / (N, 4, 4)
    q0 : array (n,) or (N, n); one start for every target when (n,) and N > 1
    options : IKOptions

    Returns
    -------
    IKResult, with arrays of shape (N,) (scalars and q of shape (n,) for one target and one start).
    """
    func = "inverse_kinematics"
    opt = IKOptions() if options is None else checks.instance(options, func, "options", IKOptions, "IKOptions")
    q, single = check_configuration(ch, q0, func, "q0")
    Mt = _targets(target, func)
    q = q.copy()  # the solve writes into it, never into the caller's q0
    if len(q) == 1 and len(Mt) > 1:
        q = np.repeat(q, len(Mt), axis=0)
    if len(q) != len(Mt):
        raise checks.fail(func, "q0", f"{len(q)} starts for {len(Mt)} targets")
    t_target = coefficients_to_matrix_unchecked(Mt)[:, :3, 3]
    N, n = q.shape
    lam = np.full(N, np.nan)
    nu = np.full(N, 2.0)
    iters = np.zeros(N, dtype=int)
    done = np.zeros(N, dtype=bool)
    J, M = jacobian_and_pose(ch, q)
    err, angle, pos = _errors(Mt, M, t_target)
    rng = np.random.default_rng(opt.seed)
    rev = ch._tables.revolute
    for _ in range(opt.max_iterations + 1):
        done |= (pos <= opt.tol_position) & (angle <= opt.tol_rotation)
        act = np.flatnonzero(~done & (iters < opt.max_iterations))
        if act.size == 0:
            break
        Ja, ea = J[act], err[act]
        dq, la = _damped_step(Ja, ea, lam[act], opt)
        q_new = q[act] + dq
        J_new, M_new = jacobian_and_pose(ch, q_new)
        e_new, a_new, p_new = _errors(Mt[act], M_new, t_target[act])
        Jdq = (Ja @ dq[:, :, None])[:, :, 0]
        predicted = np.einsum("ki,ki->k", ea, ea) - np.einsum("ki,ki->k", ea - Jdq, ea - Jdq)
        actual = np.einsum("ki,ki->k", ea, ea) - np.einsum("ki,ki->k", e_new, e_new)
        rho = np.minimum(actual / np.maximum(predicted, 1e-300), 2.0)
        better = (actual > 0) & (rho > 0)
        iters[act] += 1
        ok = act[better]
        q[ok], J[ok], err[ok] = q_new[better], J_new[better], e_new[better]
        pos[ok], angle[ok] = p_new[better], a_new[better]
        # Nielsen (1999): lambda shrinks by up to 3 after a good step, grows by nu = 2, 4, 8, ... after a refused one
        lam[ok] = la[better] * np.maximum(1.0 / 3.0, 1.0 - (2.0 * rho[better] - 1.0) ** 3)
        nu[ok] = 2.0
        bad = act[~better]
        lam[bad] = np.minimum(la[~better] * nu[bad], 1e30)
        nu[bad] = np.minimum(nu[bad] * 2.0, 1e6)
        stuck = bad[nu[bad] >= 2.0 ** (opt.restart_after or np.inf)] if rev.any() else bad[:0]
        if stuck.size:  # refused again and again: a local minimum at a singularity; start over elsewhere
            q[np.ix_(stuck, rev)] = rng.uniform(-np.pi, np.pi, (stuck.size, int(rev.sum())))
            J[stuck], Ms = jacobian_and_pose(ch, q[stuck])
            err[stuck], angle[stuck], pos[stuck] = _errors(Mt[stuck], Ms, t_target[stuck])
            lam[stuck], nu[stuck] = np.nan, 2.0
    for value in (q, pos, angle):
        checks.finite_result(value, func, "q0, target: the solve")
    one = single and N == 1
    return IKResult(
        q=q[0] if one else q,
        converged=bool(done[0]) if one else done,
        iterations=int(iters[0]) if one else iters,
        position_error=float(pos[0]) if one else pos,
        rotation_error=float(angle[0]) if one else angle,
    )
