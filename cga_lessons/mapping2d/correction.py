"""The correction of one scan's pose against line segments (thesis section 3.1.3, Eqs. 3.5-3.12), as an estimator.

:class:`ScanCorrector` holds what the corrector learns about the sensor and
the robot while a map is built (the range noise, the model floors of the
measurements, how good the odometry and the registration are:
:mod:`cga_lessons.mapping2d.noise`) and offers

* :meth:`ScanCorrector.register`: the thesis's correspondences (3.5, with the
  guards of 3.19) at the current pose, gated by their innovation and, in the
  first round, by the consensus of their angles; heading and position
  estimated together by robust weighted least squares with the prediction as
  prior (:func:`~cga_lessons.mapping2d.estimation.estimate_correction`),
  repeated with fresh correspondences;
* :meth:`ScanCorrector.decide`: whether the correction is applied: the
  chi-square test of its innovation against the prediction's covariance
  (which uses how good the odometry has proved to be);
* :meth:`ScanCorrector.learn_odometry`: the same registration of a scan on
  the scan before it alone, whose innovation against the odometry increment
  tells how good the odometry is.  Against the map that would not work: a
  pose left uncorrected puts its error into the map, and the next scans then
  agree with it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .corrections import chain_covariance, line_variances_unchecked
from .estimation import Correction, Measurements, estimate_correction
from .geometry import SegmentSet, correspondences_unchecked
from .lines import diff_theta_unchecked
from .noise import InnovationModel, NoiseFloors, scan_range_noise
from .poses import wrap_unchecked

__all__ = ["Registration", "ScanCorrector"]


@dataclass(frozen=True)
class Registration:
    """The result of :meth:`ScanCorrector.register`.

    Attributes
    ----------
    pose : ndarray, shape (3,)
        The estimated pose (prediction and lines fused).
    cov : ndarray, shape (3, 3)
    gi, li : ndarray of int
        Corresponding segments of the last round: indices into the reference set and into the scan's.
    estimate : Correction
        The last round's estimate (its innovation, test and noise figures).
    measurements : Measurements
        The last round's rows (fit variances, before the floors).
    """

    pose: np.ndarray
    cov: np.ndarray
    gi: np.ndarray
    li: np.ndarray
    estimate: Correction
    measurements: Measurements


class ScanCorrector:
    """Correction of scan poses against reference segments, and the noise model it learns (section 3.1.3).

    Parameters
    ----------
    geometry : PlainGeometry or ConformalGeometry
    correspondence : CorrespondenceParams
        Which segments correspond (3.5, 3.19).
    correction : CorrectionParams
        The estimate, its test and what is learnt.
    odometry_prior : OdometryPriorParams
        The odometry's drift model (for :meth:`learn_lagged`).
    mount : ndarray, shape (3,)
        Laser pose on the robot.
    """

    def __init__(self, geometry, correspondence, correction, odometry_prior, mount=(0.0, 0.0, 0.0)):
        self.geometry = geometry
        self.correspondence = correspondence
        self.correction = correction
        self.odometry_prior = odometry_prior
        self.mount = np.asarray(mount, float).reshape(3)
        self.noise = 0.01  # range noise (m) until a scan says otherwise
        self.factor = 1.0  # running a posteriori variance factor of the corrections
        self.floors = NoiseFloors((correction.angle_floor, correction.offset_floor, correction.edge_sigma))
        self.innovations = InnovationModel(level=correction.significance)  # how good the odometry and registration are
        self.registration_ref = np.diag([correction.registration_xy**2] * 2 + [correction.registration_theta**2])

    @property
    def registration_cov(self):
        """The registration error common to all lines of a scan, as learnt so far (3, 3)."""
        return self.innovations.c * self.registration_ref

    @property
    def odometry_scale(self):
        """How much of its drift model the odometry shows, as learnt so far (a variance ratio)."""
        return self.innovations.q if self.correction.estimate_odometry else 1.0

    def range_noise(self, L):
        """The range noise (m) for scan segments ``L``: ``range_noise`` if set, else estimated from ``L`` itself."""
        if self.correction.range_noise is not None:
            return self.correction.range_noise
        est = scan_range_noise(L)
        if est is not None:
            self.noise = est
        return self.noise

    def _pair_terms(self, Gn, Lw, gi, li, centre, noise):
        """Angle and centroid-offset measurements of corresponding pairs, with variances and normals."""
        p = self.correction
        G2, L2 = Gn.take(gi), Lw.take(li)
        _, tg = self.geometry.hough(G2, centre)
        _, tl = self.geometry.hough(L2, centre)
        dth = diff_theta_unchecked(tg, tl, self.correspondence.theta_xi)
        ng = np.column_stack([np.cos(tg), np.sin(tg)])
        lever = L2.centroid - centre
        offset = np.einsum("ij,ij->i", ng, G2.centroid - L2.centroid)
        vt_l, vr_l = line_variances_unchecked(L2, L2.centroid, noise, p.angle_floor, p.offset_floor)
        vt_g, vr_g = line_variances_unchecked(G2, L2.centroid, noise, p.angle_floor, p.offset_floor)
        return dth, vt_l + vt_g, offset, vr_l + vr_g, ng, lever

    def _edge_terms(self, Gn, Lw, gi, li, centre):
        """Along-line measurements from ends that are real edges in both the map and the scan.

        Each pair's ends are matched in the scan segment's sense (the map segment's ends swapped when it runs the
        other way); an end gives a row when it is a real edge in both and the two lie within ``edge_match``.
        Rows come pair by pair, start before end.
        """
        if len(gi) == 0:
            return None
        ls, le = Lw.start[li], Lw.end[li]
        dl = le - ls
        dl = dl / np.hypot(dl[:, 0], dl[:, 1])[:, None]
        gs, ge = Gn.start[gi], Gn.end[gi]
        same = np.einsum("ij,ij->i", ge - gs, dl) >= 0
        g_first = np.where(same[:, None], gs, ge)
        g_last = np.where(same[:, None], ge, gs)
        gflags = np.where(same[:, None], Gn.edge[gi], Gn.edge[gi][:, ::-1])
        gends = np.stack([g_first, g_last], axis=1).reshape(-1, 2)  # pair by pair: start, end
        lends = np.stack([ls, le], axis=1).reshape(-1, 2)
        ok = (Lw.edge[li].reshape(-1) > 0) & (gflags.reshape(-1) > 0)
        if ok.any():
            ok[ok] = self.geometry.distance_rows(gends[ok], lends[ok]) < self.correspondence.edge_match
        if not ok.any():
            return None
        d = np.repeat(dl, 2, axis=0)[ok]
        lev = lends[ok] - centre
        rows = np.column_stack([d[:, 0], d[:, 1], d[:, 1] * lev[:, 0] - d[:, 0] * lev[:, 1]])
        return rows, d[:, 0] * (gends[ok, 0] - lends[ok, 0]) + d[:, 1] * (gends[ok, 1] - lends[ok, 1])

    def _gate(self, dth, vt, off, vo, h, cov):
        """Pairs whose innovation (angle, offset) lies within ``gate`` of zero in the Mahalanobis sense.

        The innovation's covariance is the pair's own plus the pose's seen
        through the measurement: ``S = diag(var_theta, var_offset) + H cov H'``.
        """
        s_tt = vt + cov[2, 2]
        s_oo = vo + np.einsum("ij,jk,ik->i", h, cov, h)
        s_to = h @ cov[:, 2]
        det = s_tt * s_oo - s_to**2
        d2 = (dth**2 * s_oo - 2 * dth * off * s_to + off**2 * s_tt) / det
        return d2 < self.correction.gate**2

    def _angle_consensus(self, dth, vt, weight, ok):
        """Mask of the largest set (by total ``weight``) of pairs whose angle differences agree.

        Two pairs agree when their diffTheta (3.5) differ by at most ``gate``
        standard deviations or ``consensus_angle``, whichever is larger; each
        pair in ``ok`` proposes the set of those that agree with it.
        """
        tol = np.maximum(self.correction.gate * np.sqrt(vt[:, None] + vt[None, :]), self.correction.consensus_angle)
        agree = (np.abs(dth[:, None] - dth[None, :]) <= tol) & ok[None, :]
        score = np.where(ok, agree @ weight, -1.0)
        return agree[int(np.argmax(score))]

    # ------------------------------------------------------------------ the estimate

    def _estimate(self, meas, floors, predicted, pose, prior_cov):
        back = np.asarray(predicted, float) - pose  # the correction that returns to the prediction
        back[2] = wrap_unchecked(back[2])
        return estimate_correction(
            meas.with_floors(floors),
            prior_cov,
            back,
            level=self.correction.significance,
            kernel=self.correction.robust_kernel,
            prior_factor=self.factor,
            model_cov=self.registration_cov,
        )

    def _move(self, pose, delta):
        """``pose`` moved by the correction ``delta``, each component bounded (T_xi of 3.12, theta_max)."""
        p = self.correction
        d = np.array(delta, float)
        d[:2] = np.clip(d[:2], -p.t_xi, p.t_xi)
        d[2] = np.clip(d[2], -p.theta_max, p.theta_max)
        out = np.asarray(pose, float) + d  # (3.6), (3.7)
        out[2] = wrap_unchecked(out[2])
        return out

    def register(self, ref: SegmentSet, L: SegmentSet, predicted, prior_cov, widen=True, gate_cov=None):
        """Register the scan's segments ``L`` (laser frame) on the reference segments ``ref`` (3.5-3.12).

        Each round finds the thesis's correspondences at the current pose,
        keeps the pairs whose angle and offset innovations lie within
        ``gate`` standard deviations (their own variance plus the pose's),
        and estimates heading and position together with the prediction as
        prior; the next round's gate uses the new, smaller covariance, so
        pairs that disagree with the consensus drop out.  With ``widen`` the
        first round's gate uses the prediction's covariance times ``gate^2``
        and keeps only the largest set of pairs that agree on the heading:
        the odometry may do worse than its model says, and one long wrong
        line must not pull the rest.  ``gate_cov`` (default ``prior_cov``) is
        the covariance widened there: the odometry's model covariance, when the
        prior has learnt a better odometry.

        Returns
        -------
        Registration or None
            None when no pair corresponds.
        """
        p = self.correction
        predicted = np.array(predicted, float)
        pose, cov = predicted.copy(), np.asarray(prior_cov, float)
        if len(ref) == 0 or len(L) == 0:
            return None
        noise = self.range_noise(L)
        floors = self.floors.variances
        found = None
        for it in range(p.n_iterations):
            Lw = self.geometry.to_global(L, pose, self.mount)
            C, _, _ = correspondences_unchecked(ref, Lw, pose[:2], self.correspondence, self.geometry)
            gi = np.flatnonzero(C >= 0)
            if len(gi) == 0:
                break
            li = C[gi]
            dth, vt, off, vo, ng, lever = self._pair_terms(ref, Lw, gi, li, pose[:2], noise)
            h = np.column_stack([ng, ng[:, 1] * lever[:, 0] - ng[:, 0] * lever[:, 1]])
            gvt, gvo = self.factor * (vt + floors[0]), self.factor * (vo + floors[1])
            first = widen and it == 0
            wide = (cov if gate_cov is None else np.asarray(gate_cov, float)) * p.gate**2
            ok = self._gate(dth, gvt, off, gvo, h, wide if first else cov)
            if first and ok.any():
                ok &= self._angle_consensus(dth, gvt, np.minimum(ref.length[gi], Lw.length[li]), ok)
            if not ok.any():
                break
            gi, li = gi[ok], li[ok]
            edges = self._edge_terms(ref, Lw, gi, li, pose[:2])
            meas = Measurements.from_pairs(dth[ok], vt[ok], off[ok], vo[ok], ng[ok], lever[ok], edges)
            est = self._estimate(meas, floors, predicted, pose, prior_cov)
            pose, cov = self._move(pose, est.delta), est.cov
            found = Registration(pose, cov, gi, li, est, meas)
            if np.hypot(*est.delta[:2]) < 1e-3 and abs(est.delta[2]) < 1e-4:  # converged: the pairs will not change
                break
        return found

    def decide(self, reg: Registration, predicted, carried, step_cov):
        """Whether to apply a registration to a predicted pose: (pose, cov, applied).

        The estimate's innovation must pass the chi-square test against the
        prediction's covariance ``carried + q step_cov`` (``q`` how good the
        odometry has proved to be).  While the noise model is still learning
        (its first innovations), a disagreement is settled by the odometry's
        own model (``q`` at least 1) instead: the odometry may simply be worse
        than the first scans suggested.  Also records the scan's residuals for
        the noise floors and the variance factor.
        """
        est, meas = reg.estimate, reg.measurements
        prior = carried + self.odometry_scale * step_cov
        if est.dof >= 1:
            self.factor = 0.9 * self.factor + 0.1 * est.variance_factor
            inlier = est.weights >= 1.0
            if self.correction.estimate_floors:
                self.floors.add(meas.kind[inlier], meas.var[inlier], est.residuals[inlier])
        if est.rank > 0 and not est.valid and self.innovations.learning and self.correction.estimate_odometry:
            wide = carried + max(self.odometry_scale, 1.0) * step_cov
            again = self._estimate(meas, self.floors.variances, predicted, reg.pose, wide)
            if again.valid:
                return self._move(reg.pose, again.delta), again.cov, True
        if est.rank == 0 or not est.valid:
            return np.array(predicted, float), prior, False
        return reg.pose, reg.cov, True

    def learn_lagged(self, earlier: SegmentSet, L: SegmentSet, odometry, first: int, last: int):
        """Register scan ``last``'s segments ``L`` on scan ``first``'s (``earlier``) and learn from the innovation.

        The odometry's increment over the steps between them and its covariance are carried through the
        steps (:func:`~cga_lessons.mapping2d.corrections.chain_covariance`).  The odometry's error over
        ``last - first`` steps adds up over them; the registration's does not (one registration, whatever
        the lag).  With step-by-step innovations alone the two are confounded when the steps are all of
        about one length (the bundled logs: about one metre).
        """
        if not (len(earlier) and len(L)):
            return None
        inc, cov = chain_covariance(odometry, first, last, self.odometry_prior)
        return self.learn_odometry(earlier, L, inc, cov)

    def learn_odometry(self, previous: SegmentSet, L: SegmentSet, increment, step_cov):
        """Register scan ``L`` on the scan before it (``previous``) alone and learn from the innovation.

        Both are in their laser frames; the prediction is the odometry
        ``increment`` with its model covariance ``step_cov``.  The innovation
        (where the lines put the scan minus where the odometry did) feeds
        :class:`~cga_lessons.mapping2d.noise.InnovationModel`.  Returns the
        registration (or None).
        """
        if not self.correction.estimate_odometry:
            return None
        ref = self.geometry.to_global(previous, np.zeros(3), self.mount)
        reg = self.register(ref, L, increment, step_cov)
        if reg is None or reg.estimate.rank == 0:
            return reg
        est, V = reg.estimate, reg.estimate.basis
        known = est.meas_cov - V.T @ self.registration_cov @ V
        self.innovations.add(est.innovation, known, V.T @ step_cov @ V, V.T @ self.registration_ref @ V)
        return reg
