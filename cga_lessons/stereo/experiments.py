"""The numerical experiments of the stereo notebook (appendix A and section 4.1), seeded and repeatable.

* :func:`fundamental_comparison`: the 8-point algorithm (A.6-A.9) with and
  without Hartley's normalisation and the rank-2 step.
* :func:`triangulation_error_curve`: 3D error of midpoint (A.14) and linear
  triangulation against pixel noise.
* :func:`entity_error_table`: the entities of 4.1 from their minimal point
  sets and from least-squares fits, against the truth.
* :func:`format_table`: fixed-width text for the notebook (stable for nbval).

Each table is a list of frozen records (:class:`FundamentalRow`, :class:`EntityErrorRow`); NaN marks a quantity
that does not apply to a row.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks, conformal
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail

from . import epipolar as epi
from . import head as st
from . import validate as vd
from .accuracy import entity_errors
from .reconstruct import reconstruct_entities
from .rig import StereoRig, check_rig
from .triangulation import triangulate

__all__ = [
    "random_points_in_view",
    "fundamental_comparison",
    "FundamentalRow",
    "TriangulationCurve",
    "triangulation_error_curve",
    "entity_error_table",
    "EntityErrorRow",
    "format_table",
]


@dataclass(frozen=True)
class FundamentalRow:
    """One variant of the 8-point algorithm in :func:`fundamental_comparison`: ``normalize`` (Hartley's
    normalisation used), ``rank2`` (rank 2 enforced), and the medians over the trials of ``epipolar_px`` (mean
    symmetric epipolar distance of the held-out points, pixels), ``F_error`` (Frobenius distance to the true F, both
    of unit norm), ``s3_over_s2`` (the smallest singular value of F relative to the middle one) and ``cond_Z``
    (condition number sigma_1/sigma_8 of the system (A.9) that was solved)."""

    normalize: bool
    rank2: bool
    epipolar_px: float
    F_error: float
    s3_over_s2: float
    cond_Z: float

    def __post_init__(self):
        checks.record(self, normalize=checks.flag, rank2=checks.flag, epipolar_px=checks.length, F_error=checks.length,
                      s3_over_s2=checks.length, cond_Z=checks.length)  # fmt: skip


@dataclass(frozen=True)
class EntityErrorRow:
    """One estimator of one entity in :func:`entity_error_table`: ``entity`` (``"point"``, ``"pair"``, ``"line"``,
    ``"circle"``, ``"plane"``, ``"sphere"``), ``estimator`` (its description), and median errors over the trials:
    ``position_mm`` (centre or endpoint error; for lines and planes the distance of the true object's centre from
    the estimated line or plane), ``radius_mm`` and ``angle_deg`` (normal or direction); NaN where a quantity does
    not apply."""

    entity: str
    estimator: str
    position_mm: float
    radius_mm: float = float("nan")
    angle_deg: float = float("nan")

    def __post_init__(self):
        checks.record(self, entity=checks.text, estimator=checks.text, position_mm=checks.measure,
                      radius_mm=checks.measure, angle_deg=checks.measure)  # fmt: skip


def random_points_in_view(rig: StereoRig, n: int, rng: np.random.Generator, depth=(1.0, 6.0)) -> np.ndarray:
    """``n`` world points seen by both cameras: uniform pixels of the left image at uniform depths.

    Returns
    -------
    ndarray, shape (n, 3)
    """
    f = "random_points_in_view"
    rig, rng = check_rig(rig, f), checks.generator(rng, f)
    n, depth = checks.integer(n, f, "n", low=0, high=10**7), vd.depth_range(depth, f)
    return _in_view(rig, n, rng, depth, f)


def _count(n, func: str, name: str, low: int = 1) -> int:
    return checks.integer(n, func, name, low=low, high=10**7)


def _in_view(rig: StereoRig, n: int, rng, depth: tuple, func: str) -> np.ndarray:
    w, h = rig.image_size
    Kinv = np.linalg.inv(rig.K)
    out = np.empty((0, 3))
    for _ in range(300):  # rounds of 2n candidates: the view holds more than 1/600 of them, or no point at all
        if len(out) >= n:
            break
        m = 2 * n
        pix = np.column_stack([rng.uniform(0, w - 1, m), rng.uniform(0, h - 1, m), np.ones(m)])
        rays = (rig.R1.T @ Kinv @ pix.T).T  # depth-1 rays (camera z = 1)
        X = rig.C1 + rng.uniform(*depth, size=(m, 1)) * rays
        out = np.vstack([out, X[rig.in_view(X)]])
    if len(out) < n:
        raise degenerate(func, "depth", f"no point at depths {depth} is seen by both cameras of the rig")
    return out[:n]


def fundamental_comparison(rig: StereoRig, rng: np.random.Generator, n_points=20, noise_px=0.5, trials=50, n_test=200):
    """Accuracy of the 8-point algorithm with and without normalisation and rank 2.

    Each trial draws ``n_points`` correspondences with Gaussian pixel noise,
    estimates F four ways, and scores each on ``n_test`` noise-free held-out
    correspondences.

    Returns
    -------
    list of FundamentalRow
        One row per variant (normalised or not, rank 2 or not), medians over the trials.
    """
    f = "fundamental_comparison"
    rig, rng, trials = check_rig(rig, f), checks.generator(rng, f), _count(trials, f, "trials")
    n_points, n_test = _count(n_points, f, "n_points", 8), _count(n_test, f, "n_test")
    noise_px = checks.real(noise_px, f, "noise_px", low=0.0, high=1e6)
    try:
        return _comparison(rig, rng, n_points, noise_px, trials, n_test, f)
    except GeometryError as exc:  # pixel noise so large that the correspondences degenerate
        raise degenerate(f, "noise_px", f"the noisy correspondences are degenerate: {exc}") from None


def _comparison(rig, rng, n_points, noise_px, trials, n_test, func):
    F_true = rig.F
    res: dict = {}
    for _ in range(trials):
        X = _in_view(rig, n_points, rng, (1.0, 6.0), func)
        x1, x2 = st.observe(rig, X, noise_px, rng)
        y1, y2 = rig.project(_in_view(rig, n_test, rng, (1.0, 6.0), func))
        for normalize in (True, False):
            a, b = (epi.hartley_normalization(x1)[1], epi.hartley_normalization(x2)[1]) if normalize else (x1, x2)
            s = np.linalg.svd(epi.eight_point_matrix(a, b), compute_uv=False)
            for rank2 in (True, False):
                F = epi.fundamental_8point(x1, x2, normalize=normalize, rank2=rank2)
                sv = np.linalg.svd(F, compute_uv=False)
                row = res.setdefault(
                    (normalize, rank2), {"epipolar_px": [], "F_error": [], "s3_over_s2": [], "cond_Z": []}
                )
                row["epipolar_px"].append(float(np.mean(epi.epipolar_distance(F, y1, y2))))
                row["F_error"].append(float(min(np.linalg.norm(F - F_true), np.linalg.norm(F + F_true))))
                row["s3_over_s2"].append(float(sv[2] / sv[1]))
                row["cond_Z"].append(float(s[0] / s[7]))
    return [
        FundamentalRow(normalize=k[0], rank2=k[1], **{q: float(np.median(v)) for q, v in vals.items()})
        for k, vals in res.items()
    ]


@dataclass(frozen=True)
class TriangulationCurve:
    """RMS 3D errors (metres) against pixel noise: ``noise_px`` (K,) the noise levels (std, pixels), ``midpoint`` (K,)
    and ``dlt`` (K,) the errors of the two triangulations (A.14), ``difference`` (K,) the RMS distance between their
    points, and ``predicted`` (K,) the first-order depth error of a parallel rig, ``sigma_Z = Z^2 sqrt(2) sigma /
    (f b)`` (RMS over the points)."""

    noise_px: np.ndarray
    midpoint: np.ndarray
    dlt: np.ndarray
    difference: np.ndarray
    predicted: np.ndarray

    def __post_init__(self):
        f = "TriangulationCurve"
        k = len(vd.array(self.noise_px, f, "noise_px", (None,), at_least=1))
        for name in self.__dataclass_fields__:
            a = vd.array(getattr(self, name), f, name, (None,))
            if len(a) != k:
                raise fail(f, f"noise_px, {name}", f"must have one length, got {k} and {len(a)}")
            object.__setattr__(self, name, a)


def triangulation_error_curve(rig: StereoRig, rng: np.random.Generator, noise_levels, n_points=300, depth=(1.0, 4.0)):
    """RMS 3D error (metres) of midpoint and DLT triangulation (A.14) for each pixel noise level.

    The same points and the same noise are given to both methods.  Returns a :class:`TriangulationCurve`.
    """
    f = "triangulation_error_curve"
    rig, rng, n_points, depth = (
        check_rig(rig, f),
        checks.generator(rng, f),
        _count(n_points, f, "n_points"),
        vd.depth_range(depth, f),
    )
    noise_levels = vd.array(noise_levels, f, "noise_levels", (None,), at_least=1)
    if np.any(noise_levels < 0) or np.any(noise_levels > 1e6):
        raise fail(f, "noise_levels", "must lie between 0 and 1e6 pixels")
    X = _in_view(rig, n_points, rng, depth, f)
    out = {"noise_px": noise_levels, "midpoint": [], "dlt": [], "difference": []}
    for s in out["noise_px"]:
        x1, x2 = st.observe(rig, X, s, rng)
        try:
            pm = triangulate(rig.P1, rig.P2, x1, x2, "midpoint")
            pd = triangulate(rig.P1, rig.P2, x1, x2, "dlt")
        except GeometryError as exc:  # noise so large that rays turn parallel
            raise degenerate(f, "noise_levels", f"the noisy views cannot be triangulated: {exc}") from None
        out["midpoint"].append(np.sqrt(np.mean(np.sum((pm - X) ** 2, axis=1))))
        out["dlt"].append(np.sqrt(np.mean(np.sum((pd - X) ** 2, axis=1))))
        out["difference"].append(np.sqrt(np.mean(np.sum((pd - pm) ** 2, axis=1))))
    # First order, parallel rig: Z = f b / d, so sigma_Z = Z^2 sigma_d / (f b) with sigma_d = sqrt(2) sigma.
    Z = (X - rig.C1) @ rig.R1[2]
    out["predicted"] = np.sqrt(np.mean(Z**4)) * np.sqrt(2.0) * out["noise_px"] / (rig.K[0, 0] * rig.baseline)
    return TriangulationCurve(**{k: np.asarray(v, float) for k, v in out.items()})


_ROWS = [
    ("point", "4.1: up/down (2.62, 2.114)"),
    ("pair", "4.1: a ^ b, endpoints (2.68, 2.131)"),
    ("line", "4.1: e ^ a ^ b (2.81, 2.127, 2.129)"),
    ("circle", "4.1: 3 points (2.80, 2.122, 2.123)"),
    ("circle", "conformal LS, 48 points"),
    ("circle", "Euclidean LS (plane + circle)"),
    ("plane", "4.1: 3 corners (2.77)"),
    ("plane", "conformal LS, 64 points"),
    ("plane", "Euclidean LS (SVD)"),
    ("sphere", "4.1: 4 points (2.75, 2.116, 2.73)"),
    ("sphere", "conformal LS, 96 points"),
    ("sphere", "Euclidean algebraic (Kasa)"),
    ("sphere", "Euclidean geometric"),
]


def entity_error_table(rig: StereoRig, scene: st.StereoScene, rng: np.random.Generator, noise_px=0.5, trials=50):
    """Median errors of every entity of 4.1 over ``trials`` noisy views, minimal sets vs least squares.

    Returns
    -------
    list of EntityErrorRow
        One row per entity and estimator; NaN where a quantity does not apply.
    """
    f = "entity_error_table"
    rig, scene, rng = (
        check_rig(rig, f),
        checks.instance(scene, f, "scene", st.StereoScene, "a StereoScene"),
        checks.generator(rng, f),
    )
    noise_px, trials = checks.real(noise_px, f, "noise_px", low=0.0, high=1e6), _count(trials, f, "trials")
    try:
        return _error_table(rig, scene, rng, noise_px, trials)
    except GeometryError as exc:
        raise degenerate(f, "scene, rig, noise_px", f"the noisy views give degenerate entities: {exc}") from None


def _error_table(rig, scene, rng, noise_px, trials):
    truth = scene.truth()
    errs: dict = {r: {"position_mm": [], "radius_mm": [], "angle_deg": []} for r in _ROWS}
    keys = ["points", "segment", "circle_key", "plane_key", "sphere_key"]
    for _ in range(trials):
        samples = st.sample_scene(scene, rig, rng)
        views = {k: st.observe(rig, samples[k], noise_px, rng) for k in keys + ["circle", "plane", "sphere"]}
        rec = reconstruct_entities(rig, {k: views[k] for k in keys})
        dense = {k: triangulate(rig.P1, rig.P2, *views[k]) for k in ("circle", "plane", "sphere")}
        fits = {
            ("circle", _ROWS[4][1]): conformal.fit_circle(dense["circle"]),
            ("circle", _ROWS[5][1]): conformal.fit_circle_euclidean(dense["circle"]),
            ("plane", _ROWS[7][1]): conformal.fit_plane(dense["plane"]),
            ("plane", _ROWS[8][1]): conformal.fit_plane_euclidean(dense["plane"]),
            ("sphere", _ROWS[10][1]): conformal.fit_sphere(dense["sphere"]),
            ("sphere", _ROWS[11][1]): conformal.fit_sphere_kasa(dense["sphere"]),
            ("sphere", _ROWS[12][1]): conformal.fit_sphere_geometric(dense["sphere"]),
        }
        for row in _ROWS:
            entity = row[0]
            est = rec[entity] if row[1].startswith("4.1") else fits[row]
            e = entity_errors(truth, {entity: est})[entity]
            if entity == "point":
                per_point = np.linalg.norm(est.points - truth["point"].points, axis=1)
                errs[row]["position_mm"].extend(1e3 * per_point)
                continue
            pos = e.center if hasattr(e, "center") else getattr(e, "offset", getattr(e, "position", None))
            errs[row]["position_mm"].append(1e3 * pos)
            if hasattr(e, "radius"):
                errs[row]["radius_mm"].append(1e3 * e.radius)
            ang = getattr(e, "normal", getattr(e, "direction", None))
            if ang is not None:
                errs[row]["angle_deg"].append(np.degrees(ang))
    table = []
    for (entity, estimator), vals in errs.items():
        med = {k: float(np.median(v)) if v else float("nan") for k, v in vals.items()}
        table.append(EntityErrorRow(entity=entity, estimator=estimator, **med))
    return table


def format_table(rows, columns, formats=None) -> str:
    """Rows as a fixed-width text table (NaN printed as '-').

    Parameters
    ----------
    rows : list of records or dicts
        Typed rows (dataclass instances such as :class:`FundamentalRow`, read by field name) or dicts.
    columns : list of str
        Field names (or keys) to print, in order.
    formats : dict, optional
        ``key -> format spec`` (e.g. ``".2f"``); strings and bools print as they are.
    """
    f = "format_table"
    rows = checks.instance(rows, f, "rows", (list, tuple), "a list of records or dicts")
    columns = checks.instance(columns, f, "columns", (list, tuple), "a list of keys (strings)")
    columns = [checks.text(k, f, "columns", empty=True) for k in columns]
    formats = {} if formats is None else checks.instance(formats, f, "formats", dict, "a dict key -> format spec")
    rows = [_as_mapping(row, i, f) for i, row in enumerate(rows)]
    for i, row in enumerate(rows):
        missing = [k for k in columns if k not in row]
        if missing:
            raise fail(f, "rows, columns", f"row {i} has no {', '.join(map(repr, missing))}")

    def cell(row, k):
        v = row[k]
        if isinstance(v, float | np.floating) and np.isnan(v):
            return "-"
        if isinstance(v, bool | np.bool_) or isinstance(v, str):
            return str(v)
        try:
            return format(v, formats.get(k, ".3g"))
        except (TypeError, ValueError) as exc:
            spec = formats.get(k, ".3g")
            raise fail(f, "rows, formats", f"cannot format {v!r:.30} of column {k!r} as {spec!r:.20} ({exc})") from None

    cells = [[cell(r, k) for k in columns] for r in rows]
    widths = [max([len(k), *(len(c[i]) for c in cells)]) for i, k in enumerate(columns)]
    lines = ["  ".join(k.ljust(w) for k, w in zip(columns, widths))]
    lines.append("  ".join("-" * w for w in widths))
    for c in cells:
        lines.append("  ".join(v.ljust(w) if i < 2 else v.rjust(w) for i, (v, w) in enumerate(zip(c, widths))))
    return "\n".join(lines)


def _as_mapping(row, i: int, func: str) -> dict:
    """A table row as a dict: a dataclass record by its field names, a dict as it is."""
    if dataclasses.is_dataclass(row) and not isinstance(row, type):
        return {fld.name: getattr(row, fld.name) for fld in dataclasses.fields(row)}
    return checks.instance(row, func, "rows", dict, f"a record (dataclass) or a dict in row {i}")
