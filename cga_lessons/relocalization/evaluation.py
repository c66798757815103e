"""The terms of a measured relocalization: the tolerances, the per-pose :class:`Evaluation`, scan agreement.

A relocalization is a *success* when it is confident (``status == "ok"``)
and within 10 cm and 2 degrees of the truth; *confidently wrong* when it is
confident and not within them.  :func:`scan_agreement` compares noise-free
scans from two poses: a tied candidate whose scan agrees with the true one is
a *witness* that no method could tell them apart.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import Scene, simulate_scan

from .geometry import pose_errors
from .inputs import as_segment_array, check_laser, check_pose, check_scene
from .params import STATUSES

__all__ = [
    "POSITION_TOLERANCE",
    "HEADING_TOLERANCE",
    "scan_agreement",
    "agreement",
    "Evaluation",
    "EvaluationSummary",
    "check_evaluation",
    "record_results",
]

#: A relocalization within this distance (m) and heading (radians) of the truth is right.
POSITION_TOLERANCE = 0.10
HEADING_TOLERANCE = np.radians(2.0)


def scan_agreement(walls, pose_a, pose_b, tolerance: float = 0.03, **scan_kw):
    """Fraction of beams on which the noise-free scans from two poses agree.

    A beam agrees when both scans have no return there or their ranges differ
    by less than ``tolerance``.  ``pose_b`` may be one pose (3,) (a float is
    returned) or several (k, 3) (a list of k fractions).
    """
    func = "scan_agreement"
    if isinstance(walls, Scene):
        walls = check_scene(walls, func, "walls").walls
    walls = as_segment_array(walls, func, "walls")
    pose_a = check_pose(pose_a, func, "pose_a")
    pose_b, one = checks.batch(pose_b, func, "pose_b", (3,))
    checks.magnitude(pose_b[:, :2], func, "pose_b")
    tolerance = checks.real(tolerance, func, "tolerance", low=0.0, strict_low=True)
    scan_kw = check_laser(func, **scan_kw)
    return agreement(walls, pose_a, pose_b if not one else pose_b[0], tolerance, **scan_kw)


def agreement(walls, pose_a, pose_b, tolerance, **scan_kw):
    """:func:`scan_agreement` of checked arguments."""
    ra, _ = simulate_scan(walls, pose_a, **scan_kw)
    many = np.ndim(pose_b) == 2
    out = []
    for pb in np.atleast_2d(pose_b):
        rb, _ = simulate_scan(walls, pb, **scan_kw)
        both_none = ~np.isfinite(ra) & ~np.isfinite(rb)
        with np.errstate(invalid="ignore"):
            close = np.abs(ra - rb) < tolerance
        out.append(float(np.mean(both_none | close)))
    return out if many else out[0]


@dataclass
class Evaluation:
    """Per-pose results of :func:`evaluate_poses` or :func:`evaluate_log` (arrays of length n).

    Attributes
    ----------
    truth, pose : ndarray, shape (n, 3)
        ``pose`` is NaN where no pose was returned (a failure).
    status : ndarray of str
    position_error, heading_error : ndarray
        m and radians; ``inf`` without a pose.
    n_lines : ndarray of int
        Segments extracted from the scan.
    score : ndarray
    witness : ndarray
        For ambiguous results: the largest scan agreement between the true
        pose and a tied, clearly different candidate (NaN when not computed).
    seconds : ndarray
        Time of each relocalization.
    """

    truth: np.ndarray
    pose: np.ndarray
    status: np.ndarray
    position_error: np.ndarray
    heading_error: np.ndarray
    n_lines: np.ndarray
    score: np.ndarray
    witness: np.ndarray
    seconds: np.ndarray
    results: list = field(default_factory=list, repr=False)

    def __post_init__(self):
        check_evaluation(self)

    def take(self, index) -> Evaluation:
        """The evaluation of some of the poses only (``index``: integer array or boolean mask)."""
        idx = np.arange(len(self.status))[index]
        return Evaluation(
            self.truth[idx],
            self.pose[idx],
            self.status[idx],
            self.position_error[idx],
            self.heading_error[idx],
            self.n_lines[idx],
            self.score[idx],
            self.witness[idx],
            self.seconds[idx],
            [self.results[i] for i in idx] if self.results else [],
        )

    @property
    def right(self) -> np.ndarray:
        """The returned pose is within the tolerances (whatever the status)."""
        return (self.position_error < POSITION_TOLERANCE) & (self.heading_error < HEADING_TOLERANCE)

    @property
    def success(self) -> np.ndarray:
        """Confident and right."""
        return (self.status == "ok") & self.right

    @property
    def confidently_wrong(self) -> np.ndarray:
        return (self.status == "ok") & ~self.right

    def indistinguishable(self, agreement: float = 0.98) -> np.ndarray:
        """Ambiguous with a witness: a clearly different pose whose scan agrees on at least ``agreement`` of beams."""
        return (self.status == "ambiguous") & (np.nan_to_num(self.witness, nan=0.0) >= agreement)

    def summary(self, agreement: float = 0.98) -> EvaluationSummary:
        """The counts and rates of the evaluation (:class:`EvaluationSummary`); ``agreement``: the scan agreement
        that makes an ambiguous result's witness (:meth:`indistinguishable`)."""
        n = len(self.status)
        ind = int(self.indistinguishable(agreement).sum())
        ok = int(self.success.sum())
        return EvaluationSummary(
            n=n,
            success=ok,
            confidently_wrong=int(self.confidently_wrong.sum()),
            ambiguous=int((self.status == "ambiguous").sum()),
            indistinguishable=ind,
            failed=int((self.status == "failed").sum()),
            success_rate=ok / n if n else float("nan"),
            success_rate_distinguishable=ok / (n - ind) if n > ind else float("nan"),
            median_ms=float(np.median(self.seconds) * 1000) if n else float("nan"),
        )


@dataclass(frozen=True)
class EvaluationSummary:
    """The counts and rates of an :class:`Evaluation` (:meth:`Evaluation.summary`).

    Attributes
    ----------
    n : int
        Poses evaluated.
    success, confidently_wrong, ambiguous, indistinguishable, failed : int
        How many were confident and right, confident and wrong, ambiguous, ambiguous with a witness (no method
        could tell the tied poses apart), and failed.
    success_rate : float
        ``success / n`` (NaN for no pose, and only then).
    success_rate_distinguishable : float
        ``success / (n - indistinguishable)`` (NaN when every pose is indistinguishable, and only then).
    median_ms : float
        Median time of one relocalization (ms; NaN for no pose, and only then).
    """

    n: int
    success: int
    confidently_wrong: int
    ambiguous: int
    indistinguishable: int
    failed: int
    success_rate: float
    success_rate_distinguishable: float
    median_ms: float

    def __post_init__(self):
        f = "EvaluationSummary"
        n = checks.integer(self.n, f, "n", low=0)
        object.__setattr__(self, "n", n)
        for name in ("success", "confidently_wrong", "ambiguous", "indistinguishable", "failed"):
            object.__setattr__(self, name, checks.integer(getattr(self, name), f, name, low=0, high=n))
        # a rate is NaN exactly when it counts nothing
        none = {
            "success_rate": n == 0,
            "success_rate_distinguishable": n == self.indistinguishable,
            "median_ms": n == 0,
        }
        for name, high in (("success_rate", 1.0), ("success_rate_distinguishable", 1.0), ("median_ms", None)):
            value = getattr(self, name)
            if none[name] and isinstance(value, (float, np.floating)) and np.isnan(value):
                continue
            object.__setattr__(self, name, checks.real(value, f, name, low=0.0, high=high))


def record_results(results, truths, walls, scan_kw, witness, ratio):
    n = len(results)
    pose = np.full((n, 3), np.nan)
    perr = np.full(n, np.inf)
    herr = np.full(n, np.inf)
    wit = np.full(n, np.nan)
    for i, (r, t) in enumerate(zip(results, truths)):
        if r.pose is not None:
            pose[i] = r.pose
            perr[i], herr[i] = pose_errors(r.pose, t)
        if witness and r.status == "ambiguous" and walls is not None:
            tied = [
                c.pose
                for c in r.candidates
                if c.score >= ratio * r.score
                and (
                    pose_errors(c.pose, t)[0] > 2 * POSITION_TOLERANCE
                    or pose_errors(c.pose, t)[1] > 2 * HEADING_TOLERANCE
                )
            ]
            wit[i] = max(scan_agreement(walls, t, np.array(tied), **scan_kw)) if tied else 0.0
    return pose, perr, herr, wit


def check_evaluation(ev) -> None:
    """Check (and convert to arrays) the fields of an :class:`~cga_lessons.relocalization.evaluation.Evaluation`."""
    f = "Evaluation"
    ev.truth = checks.array(ev.truth, f, "truth", (None, 3))
    ev.pose = checks.array(ev.pose, f, "pose", (None, 3), finite=False)
    none = np.all(np.isnan(ev.pose), axis=1)
    if not np.all(np.isfinite(ev.pose[~none])):
        raise checks.fail(f, "pose", "rows must be finite, or all NaN where no pose was returned")
    ev.status = np.asarray(ev.status)
    if ev.status.ndim != 1 or not all(isinstance(x, str) and x in STATUSES for x in ev.status.tolist()):
        raise checks.fail(f, "status", f"must be an array of {', '.join(map(repr, STATUSES))}")
    for name in ("position_error", "heading_error"):
        e = checks.array(getattr(ev, name), f, name, (None,), finite=False)
        if np.any(np.isnan(e)) or np.any(e < 0):
            raise checks.fail(f, name, "must be >= 0 (inf without a pose), not NaN")
        setattr(ev, name, e)
    lines = checks.array(ev.n_lines, f, "n_lines", (None,))
    if np.any(lines < 0) or np.any(lines != np.round(lines)):
        raise checks.fail(f, "n_lines", "must be whole numbers >= 0")
    ev.n_lines = lines.astype(int)
    ev.score = checks.array(ev.score, f, "score", (None,), finite=False)
    if np.any(np.isnan(ev.score)) or np.any(ev.score == np.inf):
        raise checks.fail(f, "score", "must be finite, or -inf where no pose was returned")
    ev.witness = checks.array(ev.witness, f, "witness", (None,), finite=False)
    if np.any((ev.witness < 0) | (ev.witness > 1)):
        raise checks.fail(f, "witness", "must lie in [0, 1] (NaN where not computed)")
    ev.seconds = checks.array(ev.seconds, f, "seconds", (None,))
    if np.any(ev.seconds < 0):
        raise checks.fail(f, "seconds", "must be >= 0")
    checks.instance(ev.results, f, "results", list, "a list of results")
    named = {k: getattr(ev, k) for k in ("truth", "pose", "status", "position_error", "heading_error")}
    named.update(n_lines=ev.n_lines, score=ev.score, witness=ev.witness, seconds=ev.seconds)
    checks.same_length(f, **named)
