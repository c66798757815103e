"""The accuracy of reconstructed entities: their errors against the truth (section 4.1, the stereo notebook).

Both sides are dicts ``entity -> {quantity: value}`` in the format of
:func:`cga_lessons.stereo.reconstruct_entities` (the estimate) and :meth:`cga_lessons.stereo.StereoScene.truth`
(the truth).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import fail

from . import validate as vd

__all__ = ["entity_errors"]


def _angle(u, v, signed=True) -> float:
    """The angle between two checked non-zero vectors (between lines if not ``signed``)."""
    u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
    c = float(np.dot(u, v))
    c = c if signed else abs(c)
    return float(np.arctan2(np.linalg.norm(np.cross(u, v)), c))


_POINTS, _VEC, _NUM = (None, 3), (3,), ()
#: The parameters :func:`entity_errors` reads, by entity (``midpoint`` of a true line is optional).
_TRUTH = {
    "point": {"points": _POINTS},
    "pair": {"endpoints": (2, 3)},
    "line": {"direction": _VEC, "closest_point": _VEC},
    "circle": {"center": _VEC, "radius": _NUM, "normal": _VEC},
    "plane": {"normal": _VEC, "point": _VEC},
    "sphere": {"center": _VEC, "radius": _NUM},
}
_ESTIMATE = {**_TRUTH, "plane": {"normal": _VEC, "distance": _NUM}}


def _parameters(d, func: str, name: str, spec: dict) -> dict:
    """The checked parameters ``entity -> {quantity: value}`` of ``d`` that ``spec`` names (scalars as floats)."""
    d = checks.instance(d, func, name, dict, "a dict entity -> parameters (as reconstruct_entities returns)")
    out = {}
    for k in (k for k in spec if k in d):
        where = f"{name}[{k!r}]"
        e = checks.instance(d[k], func, where, dict, "a dict of parameters")
        wanted = {**spec[k], "midpoint": _VEC} if k == "line" and "midpoint" in e else spec[k]
        out[k] = {}
        for q, shape in wanted.items():
            if q not in e:
                raise fail(func, where, f"has no {q!r}")
            a = vd.array(e[q], func, f"{where}[{q!r}]", shape, at_least=1 if shape else 0)
            if q in ("direction", "normal"):
                vd.direction(a, func, f"{where}[{q!r}]")
            out[k][q] = float(a) if shape == () else a
    return out


def entity_errors(truth: dict, est: dict) -> dict:
    """Errors of estimated entity parameters against the truth (metres, radians).

    Points and point pairs: largest position error.  Lines: direction angle,
    closest-point error and ``offset``, the distance of the true segment's
    midpoint from the estimated line.  Circles and spheres: centre and radius errors
    (and the circle's normal).  Planes: normal angle and ``offset``, the
    distance of the true object's centre from the estimated plane (the plane's
    distance to the world origin would mix in the normal error times a lever
    arm of metres).  Normals of circles and planes are compared as unoriented
    lines (their sign depends on the order of the points).

    Returns
    -------
    dict
        ``entity -> {quantity: error}`` for the entities present in both.
    """
    f = "entity_errors"
    truth, est = _parameters(truth, f, "truth", _TRUTH), _parameters(est, f, "est", _ESTIMATE)
    out = {}
    both = [k for k in _TRUTH if k in est and k in truth]
    for k in ("point", "pair"):
        if k in both:
            key = "points" if k == "point" else "endpoints"
            checks.same_length(f, **{f"est[{k!r}]": est[k][key], f"truth[{k!r}]": truth[k][key]})
    for k in both:
        e, t = est[k], truth[k]
        if k in ("point", "pair"):
            key = "points" if k == "point" else "endpoints"
            out[k] = {"position": float(np.max(np.linalg.norm(e[key] - t[key], axis=1)))}
        elif k == "line":
            pos = float(np.linalg.norm(e["closest_point"] - t["closest_point"]))
            out[k] = {"direction": _angle(e["direction"], t["direction"]), "position": pos}
            if "midpoint" in t:
                m = t["midpoint"] - e["closest_point"]
                out[k]["offset"] = float(np.linalg.norm(m - np.dot(m, e["direction"]) * e["direction"]))
        elif k == "plane":
            offset = abs(float(np.dot(e["normal"], t["point"])) - e["distance"])
            out[k] = {"normal": _angle(e["normal"], t["normal"], signed=False), "offset": offset}
        else:
            out[k] = {"center": float(np.linalg.norm(e["center"] - t["center"]))}
            out[k]["radius"] = abs(e["radius"] - t["radius"])
            if k == "circle":
                out[k]["normal"] = _angle(e["normal"], t["normal"], signed=False)
    return out
