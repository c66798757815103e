"""Chapter 5's relocalizer as the particle filter's proposal, and the test that confirms a mode with it.

While the filter tracks no confirmed place, every scan is relocalized by
:func:`cga_lessons.relocalization.relocalize`.  Its answer goes into the
particle set (:meth:`~cga_lessons.relocalization.mcl.MonteCarloLocalizer.inject`):

* ``"ok"``: particles around its pose; the answer *confirms* the filter's
  mode when it lies within ``gate`` of it;
* ``"ambiguous"``: particles around each of its *tied* candidates (those
  scoring at least :func:`~cga_lessons.relocalization.candidates.tie_bar`), the
  same number and spread around each, weighed like every newcomer by the
  remembered scans.  Chapter 5 cannot tell these places apart from one scan;
  the filter can, with the scans before it.  The answer confirms the mode when
  its best candidate lies within ``gate`` of it and every tied candidate outside
  the gate has lost to it: its particles hold at most
  ``(1 - converged_mass) / converged_mass`` of the weight of the mode's
  candidate's particles after the scan.  Both groups were drawn alike around
  poses refined alike on the same scan, so the ratio of their weights is the
  Bayes factor of the two places over the remembered scans and this one: a
  rival that the past explains as well keeps its weight, and the answer stays
  ambiguous.  Where chapter 5 ties more candidates than the filter tests
  (``proposal_candidates``), nothing is confirmed.

Measured on ACES (corridors; held-out sequences of ``benchmarks/bench_mcl.py``,
seed 0, folds 0-2): chapter 5 answered ``"ambiguous"`` on 272 of 440 held-out
scans, also where the filter already stood at the logged pose, so confirmations
by ``"ok"`` answers alone left 5 of 20 sequences unconfirmed at the right pose.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons.mapping2d import wrap_angle

__all__ = ["Proposal", "propose", "confirms", "within"]


def within(p, q, gate) -> bool:
    """Are poses ``p`` and ``q`` within ``gate`` (m, rad) of each other?"""
    return bool(np.hypot(p[0] - q[0], p[1] - q[1]) <= gate[0] and abs(wrap_angle(p[2] - q[2])) <= gate[1])


@dataclass
class Proposal:
    """Chapter 5's answer on one scan and the particles drawn around it.

    Attributes
    ----------
    result : Relocalization
        :func:`~cga_lessons.relocalization.relocalize`'s answer.
    centres : list of ndarray (3,)
        The poses particles were drawn around (empty when none were).
    groups : list of ndarray of int
        Indices, in the particle set after the injection, of the particles
        drawn around each centre.
    complete : bool
        Every tied candidate is among ``centres``.
    """

    result: object
    centres: list
    groups: list
    complete: bool

    @property
    def status(self) -> str:
        return self.result.status

    @property
    def pose(self):
        return self.result.pose


def propose(mcl, scan, inject: bool = True) -> Proposal:
    """Relocalize ``scan`` by chapter 5 and, if ``inject``, draw particles of ``mcl`` around its answer."""
    from .candidates import tie_bar
    from .params import RelocCheck
    from .relocalizer import relocalize

    cfg = mcl.config
    r = relocalize(mcl.reference, scan=scan, max_range=cfg.beam.max_range)
    centres, complete = [], True
    if r.status == "ok":
        centres = [r.pose]
    elif r.status == "ambiguous" and cfg.proposal_candidates > 0:
        bar = tie_bar(r.score, RelocCheck())
        tied = [c.pose for c in r.candidates if c.score >= bar]
        complete = len(tied) <= cfg.proposal_candidates
        centres = tied[: cfg.proposal_candidates]
    groups = mcl.inject(centres, cfg.proposal_fraction) if inject and centres else []
    if not groups:
        centres = []
    return Proposal(r, centres, groups, complete)


def confirms(proposal: Proposal | None, pose, w, gate, converged_mass: float) -> bool:
    """Does chapter 5's answer confirm the mode at ``pose`` (weights ``w`` after the scan)?  See the module."""
    if proposal is None:
        return False
    if proposal.status == "ok":
        return within(proposal.pose, pose, gate)
    if proposal.status != "ambiguous" or not proposal.centres or not proposal.complete:
        return False
    if not within(proposal.pose, pose, gate):
        return False
    inside = [within(c, pose, gate) for c in proposal.centres]
    mass = [float(np.sum(w[g])) for g in proposal.groups]
    mode = max(m for m, i in zip(mass, inside) if i)
    rivals = [m for m, i in zip(mass, inside) if not i]
    bar = (1.0 - converged_mass) / converged_mass
    return all(m <= bar * mode for m in rivals)
