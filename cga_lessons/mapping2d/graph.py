"""A pose graph for the 2D line map: poses tied by relative-pose measurements, relaxed by sparse least squares.

Used by :mod:`cga_lessons.mapping2d.loops` to spread the error a revisit
reveals along the chain of corrected poses.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from cga_lessons import checks

from .inputs import broadcast, covariance, pose_array
from .observations import Growing
from .poses import wrap_unchecked

__all__ = ["PoseGraph", "relative_pose", "relative_pose_unchecked", "chain_uncertainty"]


def relative_pose(a, b):
    """Pose ``b`` in the frame of pose ``a``: ``a^-1 b`` (arrays (3,) or (n, 3), which broadcast)."""
    a, b = pose_array(a, "relative_pose", "a"), pose_array(b, "relative_pose", "b")
    broadcast("relative_pose", a=a, b=b)
    return relative_pose_unchecked(a, b)


def relative_pose_unchecked(a, b):
    """:func:`relative_pose` of float arrays the caller made (the pose graph's and loop closure's inner loops)."""
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    th = wrap_unchecked(b[..., 2] - a[..., 2])
    return np.stack([c * dx + s * dy, -s * dx + c * dy, th], axis=-1)


PERMUTATION = "MMD_AT_PLUS_A"  # SuperLU's ordering for the normal matrix (symmetric): 2x faster than its default
# (COLAMD) on the windows of 1,800 poses of the Intel log three laps over, the same steps to 1e-13 m


class PoseGraph:
    """Poses tied by relative-pose measurements; :meth:`optimize` relaxes them by sparse least squares.

    An edge ``(i, j, z, cov)`` says that pose ``j`` seen from pose ``i`` is
    ``z = (dx, dy, dtheta)`` with covariance ``cov``; its error is
    ``e = z^-1 (x_i^-1 x_j)`` as a 3-vector.  Loop edges get a Cauchy weight
    ``1 / (1 + e' cov^-1 e / c^2)`` so that one wrong revisit cannot bend the
    whole map.
    """

    def __init__(self):
        self.i, self.j, self.z, self.info, self.is_loop = [], [], [], [], []
        self._arrays = None  # the edges as arrays, for the edges added so far (optimize reads them once per call)

    def __len__(self):
        return len(self.i)

    def add(self, i, j, z, cov, loop=False):
        """Add the measurement ``x_i^-1 x_j = z`` with covariance ``cov`` (3, 3), symmetric positive definite."""
        f = "PoseGraph.add"
        i, j = checks.integer(i, f, "i", low=0), checks.integer(j, f, "j", low=0)
        if i == j:
            raise checks.fail(f, "j", f"an edge ties two different poses, got i = j = {i}")
        z = checks.array(z, f, "z", (3,))
        info = covariance(cov, f, "cov")
        self.i.append(i)
        self.j.append(j)
        self.z.append(z)
        self.info.append(info)
        self.is_loop.append(checks.flag(loop, f, "loop"))

    @property
    def loops(self):
        """The loop edges as a list of (i, j)."""
        return [(i, j) for i, j, lp in zip(self.i, self.j, self.is_loop) if lp]

    def _edge_arrays(self):
        """(i, j, z, info, is_loop) as arrays; the edges added since the last call are appended, not all copied."""
        if self._arrays is None:
            self._arrays = (Growing((), int), Growing((), int), Growing((3,)), Growing((3, 3)), Growing((), bool))
        done = len(self._arrays[0])
        if done > len(self.i):  # edges removed from the lists by hand: start again
            self._arrays = None
            return self._edge_arrays()
        if done < len(self.i):
            for arr, src in zip(self._arrays, (self.i, self.j, self.z, self.info, self.is_loop)):
                arr.extend(np.asarray(src[done:]))
        return tuple(arr.view for arr in self._arrays)

    def errors(self, poses):
        """Edge errors (E, 3) at ``poses`` (T, 3), T beyond every pose an edge ties."""
        x = self._poses(poses, "PoseGraph.errors")
        if len(self.i) == 0:
            return np.zeros((0, 3))
        return relative_pose_unchecked(np.array(self.z), relative_pose_unchecked(x[self.i], x[self.j]))

    def _poses(self, poses, func: str) -> np.ndarray:
        x = checks.array(poses, func, "poses", (None, 3))
        ei, ej = self._edge_arrays()[:2]
        last = int(max(ei.max(), ej.max())) if len(ei) else -1
        if len(x) <= last:
            raise checks.fail(func, "poses", f"{len(x)} poses, but an edge ties pose {last}")
        return x

    def optimize(self, poses, iterations: int = 10, robust: float = 3.0, tol: float = 1e-4, first_free: int = 1):
        """Gauss-Newton relaxation of ``poses`` (T, 3); the poses before ``first_free`` stay fixed.

        With ``first_free`` the earliest pose a new revisit ties to, only the
        part of the chain the revisit can move is relaxed (edges into the
        fixed poses hold it in place), so the cost of a closure grows with
        the loop's length, not with the whole log's.

        Returns
        -------
        ndarray, shape (T, 3)
        """
        func = "PoseGraph.optimize"
        x = self._poses(poses, func).copy()
        iterations = checks.integer(iterations, func, "iterations", low=0)
        robust = np.float64(checks.real(robust, func, "robust", low=0.0))  # a NumPy float: robust**2 may be inf
        tol = checks.real(tol, func, "tol", low=0.0)
        T = len(x)
        f = max(checks.integer(first_free, func, "first_free", low=0), 1)
        if len(self.i) == 0 or T < 2 or f >= T:
            return x
        ei, ej, Z, Om, loop = self._edge_arrays()
        sel = np.flatnonzero(np.maximum(ei, ej) >= f)  # the edges that touch a free pose
        ei, ej, Z, Om, loop = ei[sel], ej[sel], Z[sel], Om[sel], loop[sel]
        cz, sz = np.cos(Z[:, 2]), np.sin(Z[:, 2])
        RzT = np.stack([np.stack([cz, sz], -1), np.stack([-sz, cz], -1)], -2)
        for _ in range(iterations):
            xi, xj = x[ei], x[ej]
            ci, si = np.cos(xi[:, 2]), np.sin(xi[:, 2])
            dt = xj[:, :2] - xi[:, :2]
            RiT = np.stack([np.stack([ci, si], -1), np.stack([-si, ci], -1)], -2)
            dRiT = np.stack([np.stack([-si, ci], -1), np.stack([-ci, -si], -1)], -2)
            e = relative_pose_unchecked(Z, np.column_stack([np.einsum("nij,nj->ni", RiT, dt), xj[:, 2] - xi[:, 2]]))
            A = np.zeros((len(ei), 3, 3))
            B = np.zeros((len(ei), 3, 3))
            A[:, :2, :2] = -np.einsum("nij,njk->nik", RzT, RiT)
            A[:, :2, 2] = np.einsum("nij,njk,nk->ni", RzT, dRiT, dt)
            A[:, 2, 2] = -1.0
            B[:, :2, :2] = np.einsum("nij,njk->nik", RzT, RiT)
            B[:, 2, 2] = 1.0
            w = np.ones(len(ei))
            if robust:
                chi2 = np.einsum("ni,nij,nj->n", e, Om, e)
                w = np.where(loop, 1.0 / (1.0 + chi2 / robust**2), 1.0)
            W = Om * w[:, None, None]
            J = np.concatenate([A, B], axis=2)  # (E, 3, 6)
            JW = np.matmul(J.transpose(0, 2, 1), W)  # (E, 6, 3)
            Hb = np.matmul(JW, J)  # (E, 6, 6)
            gb = np.matmul(JW, e[:, :, None])[:, :, 0]  # (E, 6)
            idx = np.concatenate([3 * ei[:, None] + np.arange(3), 3 * ej[:, None] + np.arange(3)], axis=1)  # (E, 6)
            rows = np.repeat(idx, 6, axis=1).ravel()
            cols = np.tile(idx, (1, 6)).ravel()
            keep = (rows >= 3 * f) & (cols >= 3 * f)  # the fixed poses are no unknowns
            n = 3 * (T - f)
            H = sp.csc_matrix((Hb.ravel()[keep], (rows[keep] - 3 * f, cols[keep] - 3 * f)), shape=(n, n))
            free = idx.ravel() >= 3 * f
            g = np.zeros(n)
            np.add.at(g, idx.ravel()[free] - 3 * f, gb.ravel()[free])
            dx = spla.spsolve(H, -g, permc_spec=PERMUTATION)
            if not np.all(np.isfinite(dx)):  # a singular system: a free pose no edge ties to the fixed ones
                raise checks.degenerate(func, "poses", "the edges leave some free pose undetermined")
            x[f:] += dx.reshape(-1, 3)
            x[:, 2] = wrap_unchecked(x[:, 2])
            if np.max(np.abs(dx)) < tol:
                break
        return x


def chain_uncertainty(poses, var_xy, var_theta, j, k):
    """Standard deviations (position m, heading rad) of pose ``k`` relative to pose ``j`` along the chain.

    Each step ``i`` in ``(j, k]`` adds its own variances ``var_xy[i]``,
    ``var_theta[i]``, and its heading error moves pose ``k`` by the lever
    ``|p_k - p_i|``.
    """
    if k <= j:
        return 0.0, 0.0
    sl = slice(j + 1, k + 1)
    lever2 = np.sum((poses[sl, :2] - poses[k, :2]) ** 2, axis=1)
    v_th = float(np.sum(var_theta[sl]))
    v_xy = float(np.sum(var_xy[sl] + var_theta[sl] * lever2))
    return np.sqrt(v_xy), np.sqrt(v_th)
