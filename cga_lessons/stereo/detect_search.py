"""The search behind :func:`cga_lessons.stereo.detect.detect_entities`: one round of RANSAC, model selection,
acceptance and the merging of duplicates (see that module's docstring for the method).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector
from cga_lessons.conformal import CircleParameters, LineParameters, PlaneParameters, SphereParameters

from . import detect_ml as ml
from . import detect_models as dm
from .detect_noise import NoiseModel, chi2_gate
from .detect_params import PARAMS, indices, of_kind, present, rows

__all__ = ["SelectionEvidence", "DetectedEntity", "Search", "merge"]


@dataclass(frozen=True)
class SelectionEvidence:
    """Why a detection is of its kind (model selection, :meth:`Search.select`).

    ``support``: kind -> the number of points each kind reached when fitted to the selection support and regrown;
    ``lr``: the likelihood-ratio statistic of the nested pair of the chosen dimension (plane vs sphere, line vs
    circle; the general kind wins above a chi-square quantile), None when only one kind of the pair was fitted.
    """

    support: dict = field(default_factory=dict)
    lr: float | None = None

    def __post_init__(self):
        f = "SelectionEvidence"
        support = checks.instance(self.support, f, "support", dict, "a dict kind -> number of points")
        support = {checks.choice(k, f, "support", dm.KINDS): checks.integer(n, f, "support", low=0)
                   for k, n in support.items()}  # fmt: skip
        object.__setattr__(self, "support", support)
        if self.lr is not None:
            object.__setattr__(self, "lr", checks.real(self.lr, f, "lr"))


@dataclass(frozen=True, eq=False)
class DetectedEntity:
    """One detected entity.

    Attributes
    ----------
    kind : str
        ``"plane"``, ``"sphere"``, ``"circle"`` or ``"line"``.
    params : PlaneParameters, SphereParameters, CircleParameters or LineParameters (a dict of its fields is made
        into one)
        plane: ``normal``, ``distance`` (``n . x = distance``), ``center`` (inliers' centroid on the plane);
        sphere: ``center``, ``radius``; circle: ``center``, ``normal``, ``radius``;
        line: ``point`` (foot of the inliers' centroid), ``direction``, ``length`` (extent of the inliers).
    blade : Multivector or None
        The conformal entity (sphere, plane: standard form 2.72, 2.89; circle, line: dual form 2.80, 2.81).
    inliers : ndarray of int
        Indices of its points in the input cloud.
    covariance : ndarray
        First-order covariance of the parameters named in ``covariance_names``.
    covariance_names : tuple of str
    rms : float
        RMS geometric distance of the inliers from the entity (metres).
    chi2 : float
        Mean squared Mahalanobis residual per degree of freedom (about 1 when the noise model is right).
    evidence : SelectionEvidence
        Model selection: the support each kind reached when regrown from the selection support (kind -> points),
        and ``lr``, the likelihood-ratio statistic of the nested pair (plane vs sphere, line vs circle).

    Every field is checked when the record is made (the blade may be None in a record made by hand).
    """

    kind: str
    params: PlaneParameters | SphereParameters | CircleParameters | LineParameters
    blade: object
    inliers: np.ndarray
    covariance: np.ndarray
    covariance_names: tuple
    rms: float
    chi2: float
    evidence: SelectionEvidence = field(default_factory=SelectionEvidence)

    def __post_init__(self):
        f, put = "DetectedEntity", lambda name, value: object.__setattr__(self, name, value)
        kind, params = of_kind(self.kind, self.params, f)
        put("kind", kind)
        put("params", params)
        if self.blade is not None:
            checks.instance(self.blade, f, "blade", Multivector, "a conformal blade (a Multivector) or None")
            if not all(np.all(np.isfinite(np.asarray(c, float))) for c in self.blade.coeffs.values()):
                raise checks.fail(f, "blade", "has NaN or inf coefficients")
        put("inliers", indices(self.inliers, f, "inliers"))
        names = checks.instance(self.covariance_names, f, "covariance_names", (tuple, list), "a tuple of names")
        if not all(isinstance(n, str) for n in names):
            raise checks.fail(f, "covariance_names", f"expected names (str), got {names!r:.60}")
        put("covariance_names", tuple(names))
        put("covariance", checks.array(self.covariance, f, "covariance", (len(names), len(names))))
        put("rms", checks.real(self.rms, f, "rms", low=0.0))
        put("chi2", checks.real(self.chi2, f, "chi2", low=0.0))
        checks.instance(self.evidence, f, "evidence", SelectionEvidence, "a SelectionEvidence")


class Search:
    """State of one detection: the cloud, its noise model, gates and the connectivity radius."""

    def __init__(self, X, noise: NoiseModel, cfg, eps: float):
        from scipy.spatial import cKDTree

        self.X, self.noise, self.cfg, self.eps, self._tree = X, noise, cfg, eps, cKDTree
        self.gate = {k: chi2_gate(dm.CODIM[k], cfg.confidence) for k in dm.KINDS}
        self.wide = {k: chi2_gate(dm.CODIM[k], cfg.removal_confidence) for k in dm.KINDS}

    # -- inliers
    def m2(self, kind, prm, idx):
        r, B = dm.residuals(kind, prm, self.X[idx])
        return self.noise.mahalanobis2(idx, r, B)

    def consensus(self, kind, prm, cand, gate=None):
        return cand[self.m2(kind, prm, cand) < (gate or self.gate)[kind]]

    def component(self, idx, anchor=None):
        """The connected piece of idx (neighbours closer than eps) with most anchor points (else the largest)."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        if len(idx) < 2:
            return idx
        pairs = self._tree(self.X[idx]).query_pairs(self.eps, output_type="ndarray")
        g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(idx), len(idx)))
        _, lab = connected_components(g, directed=False)
        size = np.bincount(lab)
        score = size.astype(float)
        if anchor is not None:
            score = np.bincount(lab, weights=np.isin(idx, anchor).astype(float)) * len(idx) + size
        return idx[lab == np.argmax(score)]

    def refine(self, kind, prm, cand, anchor=None, polish=False):
        """Local optimisation: inliers (connected) -> conformal least-squares fit -> inliers ... until stable.

        With ``polish`` the result is then polished to maximum likelihood
        (:func:`~cga_lessons.stereo.detect_ml.polish`) and its inliers re-selected, twice at most.
        """
        inl = self.component(self.consensus(kind, prm, cand), anchor)
        for _ in range(self.cfg.refine_iterations):
            new = dm.fit(kind, self.X[inl])
            if new is None:
                break
            new_inl = self.component(self.consensus(kind, new, cand), anchor)
            if len(new_inl) <= dm.MINIMAL[kind]:
                break
            prm, old, inl = new, inl, new_inl
            if np.array_equal(inl, old):
                break
        for _ in range(2 if polish else 0):
            prm = ml.polish(kind, prm, self.X[inl], self.noise, inl)
            new_inl = self.component(self.consensus(kind, prm, cand), anchor)
            if len(new_inl) <= dm.MINIMAL[kind] or np.array_equal(new_inl, inl):
                break
            inl = new_inl
        return prm, inl

    # -- one round of the search
    def best_support(self, free, rng):
        """Hypothesise every kind on the free points, refine each kind's best, return the largest support."""
        cfg, Xf, n = self.cfg, self.X[free], len(free)
        kmax = min(max(cfg.neighbourhoods), n - 1)
        tree = self._tree(Xf)
        sub = np.sort(rng.choice(n, size=min(n, cfg.score_points), replace=False))
        best = None
        for kind in [k for k in dm.KINDS if k in cfg.kinds]:
            H, m = cfg.hypotheses, dm.MINIMAL[kind]
            seeds = rng.integers(0, n, size=H)
            _, nb = tree.query(Xf[seeds], k=kmax + 1)
            ksize = np.minimum(rng.choice(np.asarray(cfg.neighbourhoods), size=H), kmax)
            keys = rng.random((H, kmax))
            keys[np.arange(kmax)[None, :] >= ksize[:, None]] = np.inf
            pick = np.argsort(keys, axis=1, kind="stable")[:, : m - 1]
            idx = np.column_stack([seeds, np.take_along_axis(nb[:, 1:], pick, axis=1)])
            P, kept = dm.hypotheses(kind, Xf, idx, cfg.min_conditioning)
            if P is None:
                continue
            counts = np.concatenate([
                np.sum(self.noise.mahalanobis2(free[sub], *dm.residuals(kind, rows(P, slice(s, s + 64)),
                                                                         Xf[sub])) < self.gate[kind], axis=1)
                for s in range(0, len(kept), 64)
            ])  # fmt: skip
            h = int(np.argmax(counts))
            prm, inl = self.refine(kind, rows(P, h), free)
            if best is None or len(inl) > len(best[2]):
                best = (kind, prm, inl)
        return best

    def select(self, S, free):
        """Model selection on the support S: which kind of entity is it?

        Every kind is fitted to S and regrown (maximum likelihood) on the free
        points.  Dimension first: the curves win when their best support is
        within ``selection_z`` Poisson deviations of the surfaces' best (points
        on a circle lie on its plane too).  Then, within the dimension, the
        nested pair (plane in sphere, line in circle) is decided by a
        likelihood-ratio test on the union U of their supports: the general
        kind wins when its truncated cost ``sum_U min(m, gate)`` is lower by
        more than the ``selection_confidence`` quantile of chi-square with the
        extra degrees of freedom (1 for the sphere, 2 for the circle).

        Returns
        -------
        kind, (params, support) of that kind, SelectionEvidence (or None, None, None: nothing fits).
        """
        fits = {}
        for kind in [k for k in dm.KINDS if k in self.cfg.kinds]:
            prm = dm.fit(kind, self.X[S])
            if prm is not None:
                prm = dm.fit(kind, self.X[self.consensus(kind, prm, S)]) or prm  # re-selected: robust to clutter
                fits[kind] = self.refine(kind, prm, free, anchor=S, polish=True)
        if not fits:
            return None, None, None
        size = {k: len(v[1]) for k, v in fits.items()}
        lr = None
        n_curve = max([size[k] for k in ("line", "circle") if k in size], default=-1)
        n_surf = max([size[k] for k in ("plane", "sphere") if k in size], default=-1)
        curves = n_curve >= n_surf - self.cfg.selection_z * np.sqrt(max(n_surf, 1))
        group = [k for k in (("line", "circle") if curves else ("plane", "sphere")) if k in fits]
        kind = group[0]
        if len(group) == 2:
            U = np.union1d(fits[group[0]][1], fits[group[1]][1])
            cost = [np.sum(np.minimum(self.m2(k, fits[k][0], U), self.gate[k])) for k in group]
            lr = float(cost[0] - cost[1])
            extra = dm.DOF[group[1]] - dm.DOF[group[0]]
            if lr > chi2_gate(extra, self.cfg.selection_confidence):
                kind = group[1]
        return kind, fits[kind], SelectionEvidence(support=size, lr=lr)

    def significant(self, kind, prm, inl, free) -> bool:
        """Enough points, and more than clutter at the free points' density would put in the gate."""
        cfg = self.cfg
        need = cfg.min_curve_inliers if dm.CODIM[kind] == 2 else cfg.min_surface_inliers
        if len(inl) < need:
            return False
        box = np.prod(np.maximum(np.ptp(self.X[free], axis=0), self.eps))
        density = len(free) / box
        expected = density * _support(kind, prm, self.X[inl]) * _gate_section(self, kind, prm, inl)
        return len(inl) >= expected + cfg.significance * np.sqrt(expected)

    def entity(self, kind, prm, inl, evidence: SelectionEvidence | None = None) -> DetectedEntity:
        inl = np.sort(inl)
        Xi = self.X[inl]
        r, B = dm.residuals(kind, prm, Xi)
        m2 = self.noise.mahalanobis2(inl, r, B)
        params = {k: (np.asarray(v, float) if np.ndim(v) else float(v)) for k, v in present(prm).items()}
        if kind == "plane":
            c = Xi.mean(axis=0)
            params["center"] = c - (c @ params["normal"] - params["distance"]) * params["normal"]
        if kind == "line":
            t = (Xi - params["point"]) @ params["direction"]
            params["length"] = float(np.ptp(t))
        params = PARAMS[kind](**params)
        return DetectedEntity(
            kind, params, dm.blade(kind, params), inl, ml.covariance(kind, params, Xi, self.noise, inl),
            dm.PARAM_NAMES[kind], float(np.sqrt(np.mean(np.sum(r * r, axis=1)))),
            float(np.mean(m2) / dm.CODIM[kind]), evidence or SelectionEvidence(),
        )  # fmt: skip


def _support(kind, prm, Xi) -> float:
    """Area (surfaces) or length (curves) covered by the inliers Xi, for the clutter expectation."""
    if kind == "line":
        return float(max(np.ptp((Xi - prm.point) @ prm.direction), 1e-9))
    if kind == "circle":
        u, v = dm.basis(np.asarray(prm.normal, float))
        ang = np.sort(np.arctan2((Xi - prm.center) @ v, (Xi - prm.center) @ u))
        gap = np.max(np.diff(np.concatenate([ang, ang[:1] + 2 * np.pi])))
        return float(prm.radius * (2 * np.pi - gap))
    n = prm.normal if kind == "plane" else dm.unit(np.mean(Xi - prm.center, axis=0))
    u, v = dm.basis(np.asarray(n, float))
    Q = np.column_stack([Xi @ u, Xi @ v])
    # an ellipse of semi-axes 2 sigma covers a uniform disc or rectangle of the same second moments
    return float(4 * np.pi * np.sqrt(max(np.linalg.det(np.cov(Q.T)), 0.0)))


def _gate_section(search: Search, kind, prm, inl) -> float:
    """Mean cross-section of the inlier gate: thickness 2 sqrt(g) sigma (surfaces), area pi g sqrt(det) (curves)."""
    _, B = dm.residuals(kind, prm, search.X[inl])
    C = search.noise.residual_cov(inl, B)
    g = search.gate[kind]
    if C.shape[-1] == 1:
        return float(np.mean(2 * np.sqrt(g * C[:, 0, 0])))
    return float(np.mean(np.pi * g * np.sqrt(np.linalg.det(C))))


def merge(search: Search, ents: list) -> list:
    """Non-maximum suppression: merge same-kind detections whose supports touch and whose union one entity explains."""
    ents = list(ents)
    merged = True
    while merged:
        merged = False
        for i in range(len(ents)):
            for j in range(i + 1, len(ents)):
                a, b = ents[i], ents[j]
                if a.kind != b.kind:
                    continue
                gapd, _ = search._tree(search.X[a.inliers]).query(search.X[b.inliers], k=1)
                if gapd.min() > 2 * search.eps:
                    continue
                U = np.union1d(a.inliers, b.inliers)
                prm = ml.fit_ml(a.kind, search.X[U], search.noise, U)
                if prm is None:
                    continue
                inl = search.consensus(a.kind, prm, U)
                if len(inl) < search.cfg.merge_fraction * len(U):
                    continue
                prm = ml.polish(a.kind, prm, search.X[inl], search.noise, inl)
                ents[i] = search.entity(a.kind, prm, inl, a.evidence)
                del ents[j]
                merged = True
                break
            if merged:
                break
    return ents
