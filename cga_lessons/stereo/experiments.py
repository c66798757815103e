"""The numerical experiments of the stereo notebook (appendix A and section 4.1), seeded and repeatable.

* :func:`fundamental_comparison`: the 8-point algorithm (A.6-A.9) with and
  without Hartley's normalisation and the rank-2 step.
* :func:`triangulation_error_curve`: 3D error of midpoint (A.14) and linear
  triangulation against pixel noise.
* :func:`entity_error_table`: the entities of 4.1 from their minimal point
  sets and from least-squares fits, against the truth.
* :func:`format_table`: fixed-width text for the notebook (stable for nbval).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import conformal

from . import camera as cam
from . import epipolar as epi
from . import head as st
from .rig import StereoRig

__all__ = [
    "random_points_in_view",
    "fundamental_comparison",
    "triangulation_error_curve",
    "entity_error_table",
    "format_table",
]


def random_points_in_view(rig: StereoRig, n: int, rng: np.random.Generator, depth=(1.0, 6.0)) -> np.ndarray:
    """``n`` world points seen by both cameras: uniform pixels of the left image at uniform depths.

    Returns
    -------
    ndarray, shape (n, 3)
    """
    w, h = rig.image_size
    Kinv = np.linalg.inv(rig.K)
    out = np.empty((0, 3))
    while len(out) < n:
        m = 2 * n
        pix = np.column_stack([rng.uniform(0, w - 1, m), rng.uniform(0, h - 1, m), np.ones(m)])
        rays = (rig.R1.T @ Kinv @ pix.T).T  # depth-1 rays (camera z = 1)
        X = rig.C1 + rng.uniform(*depth, size=(m, 1)) * rays
        out = np.vstack([out, X[rig.in_view(X)]])
    return out[:n]


def fundamental_comparison(rig: StereoRig, rng: np.random.Generator, n_points=20, noise_px=0.5, trials=50, n_test=200):
    """Accuracy of the 8-point algorithm with and without normalisation and rank 2.

    Each trial draws ``n_points`` correspondences with Gaussian pixel noise,
    estimates F four ways, and scores each on ``n_test`` noise-free held-out
    correspondences.

    Returns
    -------
    list of dict
        One row per variant: ``normalize``, ``rank2``, ``epipolar_px`` (mean
        symmetric epipolar distance of the held-out points, median over
        trials), ``F_error`` (Frobenius distance to the true F, both of unit
        norm; median), ``s3_over_s2`` (the smallest singular value of F
        relative to the middle one; median), ``cond_Z`` (condition number
        sigma_1/sigma_8 of the system (A.9) that was solved; median).
    """
    F_true = rig.F
    res: dict = {}
    for _ in range(trials):
        X = random_points_in_view(rig, n_points, rng)
        x1, x2 = st.observe(rig, X, noise_px, rng)
        y1, y2 = rig.project(random_points_in_view(rig, n_test, rng))
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
        {"normalize": k[0], "rank2": k[1], **{q: float(np.median(v)) for q, v in vals.items()}}
        for k, vals in res.items()
    ]


def triangulation_error_curve(rig: StereoRig, rng: np.random.Generator, noise_levels, n_points=300, depth=(1.0, 4.0)):
    """RMS 3D error (metres) of midpoint and DLT triangulation (A.14) for each pixel noise level.

    The same points and the same noise are given to both methods.

    Returns
    -------
    dict
        ``"noise_px"`` (K,), ``"midpoint"`` (K,), ``"dlt"`` (K,), and
        ``"difference"`` (K,), the RMS distance between the two methods' points,
        and ``"predicted"`` (K,), the first-order depth error of a parallel rig,
        ``sigma_Z = Z^2 sqrt(2) sigma / (f b)`` (RMS over the points).
    """
    X = random_points_in_view(rig, n_points, rng, depth)
    out = {"noise_px": np.asarray(noise_levels, float), "midpoint": [], "dlt": [], "difference": []}
    for s in out["noise_px"]:
        x1, x2 = st.observe(rig, X, s, rng)
        pm = cam.triangulate(rig.P1, rig.P2, x1, x2, "midpoint")
        pd = cam.triangulate(rig.P1, rig.P2, x1, x2, "dlt")
        out["midpoint"].append(np.sqrt(np.mean(np.sum((pm - X) ** 2, axis=1))))
        out["dlt"].append(np.sqrt(np.mean(np.sum((pd - X) ** 2, axis=1))))
        out["difference"].append(np.sqrt(np.mean(np.sum((pd - pm) ** 2, axis=1))))
    # First order, parallel rig: Z = f b / d, so sigma_Z = Z^2 sigma_d / (f b) with sigma_d = sqrt(2) sigma.
    Z = (X - rig.C1) @ rig.R1[2]
    out["predicted"] = np.sqrt(np.mean(Z**4)) * np.sqrt(2.0) * out["noise_px"] / (rig.K[0, 0] * rig.baseline)
    return {k: np.asarray(v, float) for k, v in out.items()}


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
    list of dict
        ``entity``, ``estimator``, ``position_mm`` (centre or endpoint error;
        for lines and planes the distance of the true object's centre from the
        estimated line or plane), ``radius_mm``, ``angle_deg`` (normal or direction); NaN where
        a quantity does not apply.
    """
    truth = scene.truth()
    errs: dict = {r: {"position_mm": [], "radius_mm": [], "angle_deg": []} for r in _ROWS}
    keys = ["points", "segment", "circle_key", "plane_key", "sphere_key"]
    for _ in range(trials):
        samples = st.sample_scene(scene, rig, rng)
        views = {k: st.observe(rig, samples[k], noise_px, rng) for k in keys + ["circle", "plane", "sphere"]}
        rec = st.reconstruct_entities(rig, {k: views[k] for k in keys})
        dense = {k: cam.triangulate(rig.P1, rig.P2, *views[k]) for k in ("circle", "plane", "sphere")}
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
            e = st.entity_errors(truth, {entity: est})[entity]
            if entity == "point":
                per_point = np.linalg.norm(est["points"] - truth["point"]["points"], axis=1)
                errs[row]["position_mm"].extend(1e3 * per_point)
                continue
            pos = e["center"] if "center" in e else e.get("offset", e.get("position"))
            errs[row]["position_mm"].append(1e3 * pos)
            if "radius" in e:
                errs[row]["radius_mm"].append(1e3 * e["radius"])
            ang = e.get("normal", e.get("direction"))
            if ang is not None:
                errs[row]["angle_deg"].append(np.degrees(ang))
    table = []
    for (entity, estimator), vals in errs.items():
        med = {k: float(np.median(v)) if v else float("nan") for k, v in vals.items()}
        table.append({"entity": entity, "estimator": estimator, **med})
    return table


def format_table(rows, columns, formats=None) -> str:
    """Rows of dicts as a fixed-width text table (NaN printed as '-').

    Parameters
    ----------
    rows : list of dict
    columns : list of str
        Keys to print, in order.
    formats : dict, optional
        ``key -> format spec`` (e.g. ``".2f"``); strings and bools print as they are.
    """
    formats = formats or {}

    def cell(row, k):
        v = row[k]
        if isinstance(v, float | np.floating) and np.isnan(v):
            return "-"
        if isinstance(v, bool | np.bool_) or isinstance(v, str):
            return str(v)
        return format(v, formats.get(k, ".3g"))

    cells = [[cell(r, k) for k in columns] for r in rows]
    widths = [max(len(k), *(len(c[i]) for c in cells)) for i, k in enumerate(columns)]
    lines = ["  ".join(k.ljust(w) for k, w in zip(columns, widths))]
    lines.append("  ".join("-" * w for w in widths))
    for c in cells:
        lines.append("  ".join(v.ljust(w) if i < 2 else v.rjust(w) for i, (v, w) in enumerate(zip(c, widths))))
    return "\n".join(lines)
