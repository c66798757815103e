"""Relocalization from a sequence of scans: keep every candidate until the scans tell them apart.

One scan is often not enough: the thesis's own warning (symmetric rooms, few
lines) is the everyday case of a laser that sees 180 degrees.  What a robot
does then is look again, and a robotics engineer expects the method to use
every look.  :class:`Relocalizer` takes scans one by one with the odometry
between them (the robot turning on the spot, or driving on) and carries a set
of hypotheses, each a chain of laser poses, one per scan:

1. the first scan's ranked candidates (:func:`~cga_lessons.relocalization.relocalize`)
   start the chains;
2. at every new scan each chain is moved by the odometry increment (the rigid
   motion of Eq. 3.4) and snapped to the new scan's points
   (:func:`~cga_lessons.relocalization.verify.refine_pose_points`); the new
   scan is relocalized on its own as well, and every candidate that no chain
   already explains starts a new chain, carried back through the odometry and
   checked against the earlier scans; then every chain's poses are fitted to
   their scans and to the odometry's steps together
   (:func:`~cga_lessons.relocalization.chain.refine_chains`): the scans fix a
   pose across a corridor, the odometry along it;
3. a chain's score is the beam score of
   :func:`~cga_lessons.relocalization.verify.score_poses` summed over all its
   scans: ``(inliers - violations) / returned beams``;
4. the answer is *ambiguous* while a clearly different chain ties with the
   best (:func:`~cga_lessons.relocalization.candidates.tie_bar`, its deficit margin shrunk by the square root of
   the number of scans summed), or while the best chain moved rigidly by
   ``distinct_position`` along its least constrained direction (or turned by
   ``distinct_heading`` about its last pose) still does; that is the rule of a
   single relocalization, applied to all the scans together; and while the
   best chain's steps depart from the odometry's beyond what its drift model
   allows (a chain that slid from candidate to candidate along a corridor).

(The scans as evidence about a chain, its slide along the corridor and the
decision: :mod:`~cga_lessons.relocalization.chain_evidence`.)

Identical rooms stay ambiguous however often the robot looks around in one of
them, and are reported so (notebook 09 shows both cases).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import OdometryModel, compose, relative

from .candidates import Candidate, distinct, tie_bar
from .chain import Chain, SequenceRelocalization, refine_chains
from .chain_evidence import ScanEvidence, decide_chain, polish_chain
from .geometry import Observation, range_noise, reference_map
from .inputs import check_pose, check_scan
from .params import RelocParams, noise_scaled, resolve_params
from .relocalizer import combined_noise, relocalize

__all__ = ["Relocalizer", "relocalize_sequence", "relocalizer_for"]


class Relocalizer:
    """Relocalize from scans taken one after another, with the odometry between them.

    Parameters
    ----------
    map_segments : list of Segment, array_like (M, 2, 2) or ReferenceMap
        The map, as for :func:`~cga_lessons.relocalization.relocalize`.
    max_range : float
        The laser's reach (m).
    params : RelocParams, optional
        Thresholds by stage (keyword ``overrides`` replace single fields, a stage or some of its fields, as for
        :func:`~cga_lessons.relocalization.relocalize`).
    max_chains : int
        At most this many chains are kept (the best by score).
    keep_ratio : float
        Chains scoring below this fraction of the best are dropped.
    odometry_model : OdometryModel, optional
        How far the odometry may drift between two scans (default: the
        project's drift model); a best chain that moves against the odometry
        beyond it is reported ambiguous.
    joint : bool
        After every scan, fit each chain's poses to their scans and to the
        odometry together (:func:`~cga_lessons.relocalization.chain.refine_chains`),
        so that no chain slides along a corridor against the odometry's steps.
        False: each pose is snapped to its own scan alone (as before; measured
        with ``benchmarks/bench_reloc_logs.py``, runs of three on the six CARMEN
        logs, seeds 0-3: 1,111 of 1,444 runs located with the joint fit against
        1,087 without, 23 confidently wrong against 24).
    window : int
        The joint fit moves the last ``window`` poses and holds the earlier ones:
        its cost grows with the square of the window (one dense ``3 window``
        system per chain).  Runs of three scans are refitted whole.

    Examples
    --------
    >>> from cga_lessons.mapping2d.laser import load_scene, simulate_scan
    >>> room = load_scene("room")
    >>> loc = Relocalizer(room.walls)
    >>> rng = np.random.default_rng(0)
    >>> for turn in (0.0, np.pi / 2, np.pi):
    ...     pose = np.array([2.0, 1.5, 0.3 + turn])
    ...     result = loc.add(simulate_scan(room, pose, rng), odometry=pose)
    >>> result.n_scans, result.status
    (3, 'ambiguous')

    (A bare rectangle looks the same turned by 180 degrees about its centre.)
    """

    def __init__(
        self,
        map_segments,
        *,
        max_range: float = 5.0,
        params: RelocParams | None = None,
        max_chains: int = 64,
        keep_ratio: float = 0.7,
        odometry_model: OdometryModel | None = None,
        joint: bool = True,
        window: int = 5,
        **overrides,
    ):
        self._setup("Relocalizer", map_segments, max_range, max_chains, keep_ratio, odometry_model, joint, window)
        self.params = resolve_params(params, overrides, "Relocalizer")

    def _setup(
        self, func, map_segments, max_range, max_chains=64, keep_ratio=0.7, odometry_model=None, joint=True, window=5
    ):
        """Check the settings in the name of ``func`` (the public function called) and start with no scan."""
        self.max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
        self.max_chains = checks.integer(max_chains, func, "max_chains", low=1)
        self.keep_ratio = checks.real(keep_ratio, func, "keep_ratio", low=0.0, high=1.0, strict_low=True)
        if odometry_model is not None:
            checks.instance(odometry_model, func, "odometry_model", OdometryModel, "an OdometryModel or None")
        self.odometry_model = OdometryModel() if odometry_model is None else odometry_model
        self.joint = checks.flag(joint, func, "joint")
        self.window = checks.integer(window, func, "window", low=1)
        self.ref = reference_map(map_segments, func)
        self.scans = ScanEvidence(self.ref.lines)
        self.odometry: list[np.ndarray] = []
        self.chains: list[Chain] = []
        self.single: list = []

    # ------------------------------------------------------------------ public

    def add(self, scan, odometry) -> SequenceRelocalization:
        """Add one scan ``(ranges, angles)`` taken at odometry pose ``odometry`` (3,); return the current answer.

        Only the odometry increments between scans are used, so the odometry
        frame is arbitrary.
        """
        ranges, angles = check_scan(scan, "Relocalizer.add")
        odo = check_pose(odometry, "Relocalizer.add", "odometry")
        if self.odometry:
            step = relative(self.odometry[-1], odo)
            checks.finite_result(step, "Relocalizer.add", "odometry: the increment from the last scan")
        noise = range_noise(np.where(ranges < self.max_range, ranges, np.inf))
        spread = combined_noise(noise, self.ref)  # of the scan's points about the map's walls
        params = noise_scaled(self.params, spread)
        obs = Observation.from_scan(ranges, angles, self.max_range)
        k = len(self.scans)
        self.scans.add(obs, params.check, spread)
        self.odometry.append(odo)
        single = relocalize(self.ref, scan=(ranges, angles), max_range=self.max_range, params=self.params)
        self.single.append(single)

        if k > 0 and self.chains:
            self._advance(k, [c.pose for c in single.candidates])
        fresh = [
            c.pose for c in single.candidates if all(distinct(c.pose, ch.poses[k], params.check) for ch in self.chains)
        ]
        if fresh:
            self._start_chains(np.array(fresh), k)
        if self.joint and k > 0 and self.chains:
            self._refine_jointly()
        self._prune()
        return self.result()

    def result(self) -> SequenceRelocalization:
        """The answer after the scans added so far."""
        n = len(self.scans)
        if not self.chains:
            msg = self.single[-1].message if self.single else "no scan yet"
            return SequenceRelocalization(
                pose=None, score=-np.inf, status="failed", n_scans=n, message=msg, single=self.single
            )
        ranked = self._ranked()
        best = self.chains[ranked[0]]
        polish_chain(self.scans, best)
        cands = [self._candidate(self.chains[i]) for i in ranked]
        check, odo = self.params.check, self.odometry
        status, msg, probe = decide_chain(self.scans, best, cands, check, odo, self.odometry_model)
        if probe is not None:
            cands.insert(1, probe)
        return SequenceRelocalization(
            pose=np.array(best.poses[-1]),
            score=cands[0].score,
            status=status,
            candidates=cands,
            trajectory=np.array(best.poses),
            n_scans=n,
            message=msg,
            single=self.single,
        )

    # ------------------------------------------------------------------ internals

    def _advance(self, k, nearby):
        """Every chain moved by the odometry increment to scan ``k`` and snapped to it.

        The snap is local and can slide along a direction the new scan hardly
        fixes; so the new scan's own candidates (``nearby``, found and checked
        on that scan alone) within three times the distinctness thresholds of
        the prediction are tried too, and the best-scoring pose is kept.
        """
        step = relative(self.odometry[k - 1], self.odometry[k])
        pred = compose(np.array([ch.poses[k - 1] for ch in self.chains]), step)
        poses, inl, vio = self.scans.fit(k, pred)
        if len(nearby):
            near = np.array(nearby)
            sc_near, inl_near, vio_near = self.scans.score(k, near)
            dpos = np.hypot(*(near[None, :, :2] - pred[:, None, :2]).transpose(2, 0, 1))
            dang = np.abs(np.angle(np.exp(1j * (near[None, :, 2] - pred[:, None, 2]))))
            check = self.params.check
            close = (dpos < 3 * check.distinct_position) & (dang < 3 * check.distinct_heading)
            for c in range(len(pred)):
                for m in np.flatnonzero(close[c]):
                    if inl_near[m] - vio_near[m] > inl[c] - vio[c]:
                        poses[c], inl[c], vio[c] = near[m], inl_near[m], vio_near[m]
        for ch, p, i, v in zip(self.chains, poses, inl, vio):
            ch.poses.append(p)
            ch.inliers = np.append(ch.inliers, i)
            ch.violations = np.append(ch.violations, v)

    def _start_chains(self, poses, k):
        """New chains from poses at scan ``k``, carried back through the odometry to every earlier scan."""
        n = len(poses)
        chain = np.zeros((k + 1, n, 3))
        inl = np.zeros((k + 1, n))
        vio = np.zeros((k + 1, n))
        chain[k], inl[k], vio[k] = self.scans.fit(k, poses)
        for j in range(k - 1, -1, -1):
            back = compose(chain[j + 1], relative(self.odometry[j + 1], self.odometry[j]))
            chain[j], inl[j], vio[j] = self.scans.fit(j, back)
        for c in range(n):
            self.chains.append(Chain([chain[j, c] for j in range(k + 1)], inl[:, c].copy(), vio[:, c].copy()))

    def _refine_jointly(self):
        """Every chain's last ``window`` poses fitted to their scans and the odometry together
        (:func:`~cga_lessons.relocalization.chain.refine_chains`), the poses before them held."""
        n = len(self.scans)
        j0 = max(0, n - self.window)
        chains = np.array([ch.poses for ch in self.chains])
        odo = np.array(self.odometry)
        inc = relative(odo[max(j0 - 1, 0) : n - 1], odo[max(j0, 1) : n])
        # a noise-free (simulated) scan: 1 mm keeps weights finite
        sig = np.maximum(np.array(self.scans.sigmas[j0:]), 1e-3)
        anchor = chains[:, j0 - 1] if j0 > 0 else None
        obs = self.scans.observations[j0:]
        out = refine_chains(self.ref.lines, obs, inc, chains[:, j0:], sig, self.odometry_model, anchor=anchor)
        for j in range(j0, n):
            _, inl, vio = self.scans.score(j, out[:, j - j0])
            for c, ch in enumerate(self.chains):
                ch.poses[j] = out[c, j - j0]
                ch.inliers[j], ch.violations[j] = inl[c], vio[c]

    def _ranked(self):
        scores = np.array([ch.score(self.scans.returned) for ch in self.chains])
        return list(np.argsort(-scores, kind="stable"))

    def _prune(self):
        """Drop chains that are no longer clearly different from a better one, or score far below the best.

        Far below: under ``keep_ratio`` of the best and under the tie bar
        (:func:`~cga_lessons.relocalization.candidates.tie_bar`): a chain that still
        ties with a poorly scoring best is the evidence that the answer is
        ambiguous, and is kept.
        """
        if not self.chains:
            return
        order = self._ranked()
        best = self.chains[order[0]].score(self.scans.returned)
        floor = min(self.keep_ratio * best, tie_bar(best, self.params.check))
        kept = []
        for i in order:
            ch = self.chains[i]
            if len(kept) >= self.max_chains or ch.score(self.scans.returned) < floor:
                break
            if all(distinct(ch.poses[-1], o.poses[-1], self.params.check) for o in kept):
                kept.append(ch)
        self.chains = kept

    def _candidate(self, ch) -> Candidate:
        pose, score = np.array(ch.poses[-1]), ch.score(self.scans.returned)
        return Candidate(pose, score, float(ch.inliers.sum()), float(ch.violations.sum()))


def relocalizer_for(func: str, map_segments, max_range, kw: dict) -> Relocalizer:
    """A :class:`Relocalizer` made with keywords ``kw`` (its settings and thresholds), checked in the name of
    ``func``, the public function called."""
    kw = dict(kw)
    settings = {k: kw.pop(k) for k in ("max_chains", "keep_ratio", "odometry_model", "joint", "window") if k in kw}
    params = kw.pop("params", None)
    loc = Relocalizer.__new__(Relocalizer)
    loc._setup(func, map_segments, max_range, **settings)
    loc.params = resolve_params(params, kw, func)
    return loc


def relocalize_sequence(map_segments, scans, odometry, *, max_range: float = 5.0, stop_when_confident=False, **kw):
    """Relocalize from scans ``[(ranges, angles), ...]`` taken at odometry poses ``odometry`` (n, 3).

    With ``stop_when_confident`` the scans after the first confident answer
    are not used (a robot that stops turning as soon as it knows where it is).
    Other keywords go to :class:`Relocalizer`.

    Returns
    -------
    SequenceRelocalization
        The answer after the last scan used; ``pose`` is the laser's pose at that scan.
    """
    func = "relocalize_sequence"
    if scans is None or isinstance(scans, (str, bytes)) or not hasattr(scans, "__iter__"):
        raise checks.fail(func, "scans", f"expected a list of scans (ranges, angles), got {type(scans).__name__}")
    scans = [check_scan(s, func, f"scans[{i}]") for i, s in enumerate(scans)]
    if not scans:
        raise checks.fail(func, "scans", "expected at least one scan, got none")
    odo = checks.magnitude(checks.array(odometry, func, "odometry", (None, 3)), func, "odometry")
    if len(odo) != len(scans):
        raise checks.fail(func, "odometry", f"must have one row per scan; got {len(odo)} for {len(scans)} scan(s)")
    checks.finite_result(relative(odo[:-1], odo[1:]), func, "odometry: a step between scans")
    stop_when_confident = checks.flag(stop_when_confident, func, "stop_when_confident")
    loc = relocalizer_for(func, map_segments, max_range, kw)
    for scan, o in zip(scans, odo):
        res = loc.add(scan, o)
        if stop_when_confident and res.status == "ok":
            break
    return res
