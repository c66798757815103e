"""The drawing package's checks of its arguments, composed from the shared checking layer.

Every check here is a thin use of :mod:`cga_lessons.checks` (``fail``, ``real``, ``array``, ``text``, ...) for
the kinds of argument only a figure has: a matplotlib axes or figure, a figure size, a colour, a colormap, the
coordinates a figure draws (finite, and small enough for matplotlib's transforms: each limit with its reason), a
conformal entity of a given kind and its drawable parameters, chapter 2's reflection planes and accuracy curves.
Generic checks (arrays, random generators, seeds, relabelled errors) are :mod:`cga_lessons.checks`' own.  The
messages read ``"func: name: problem"`` as everywhere in the package.  This module has no ``__all__``:
it is no part of the package's face.
"""

from __future__ import annotations

import re

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import is_color_like
from matplotlib.figure import Figure

from cga_lessons.algebra import Multivector
from cga_lessons.checks import array, batch, choice, fail, magnitude, real, relabel, same_length, text

#: The largest coordinate a figure draws (metres, pixels, ...): beyond it matplotlib's transforms lose all
#: precision or overflow.
LIMIT = 1e12
#: Why a drawn coordinate is limited to :data:`LIMIT` (the ``why`` of :func:`cga_lessons.checks.magnitude`).
WHY = "a figure cannot draw them (matplotlib's transforms lose all precision or overflow)"
#: The largest coordinate of a figure that also draws values grown from its square (a conformal point's e+ and e-
#: coefficients, a squared distance, a pose's motor): 1e6 squared is :data:`LIMIT`.
SQUARED = 1e6
SQUARED_WHY = "the figure also draws values grown from their squares, which must stay within +-1e12"
#: Why an angle (radians, a Hough line's theta) is limited to +-1e6: a sanity bound, no figure's angle is that far
#: from [-pi, pi].
ANGLE_WHY = "angles (radians) that far from [-pi, pi] are a mistaken unit, not an angle to draw"
#: Resolution of every figure of chapter 2 (kept low so that the stored notebooks stay small).
DPI = 80
#: The largest side of a figure, in inches.
MAX_INCHES = 100.0


def axes(ax, func: str, name: str = "ax", *, three_d: bool = False, optional: bool = True):
    """``ax`` if it is a matplotlib axes (a 3D one if ``three_d``), or None when ``optional``."""
    if ax is None and optional:
        return None
    if not isinstance(ax, Axes):
        want = "a matplotlib 3D axis" if three_d else "a matplotlib axes"
        raise fail(func, name, f"expected {want}{' or None' if optional else ''}, got {type(ax).__name__}")
    if three_d and getattr(ax, "name", None) != "3d":
        raise fail(func, name, "must be a 3D axis (fig.add_subplot(projection='3d'))")
    return ax


def figure(fig, func: str, name: str = "fig") -> Figure:
    """``fig`` if it is a matplotlib figure."""
    if not isinstance(fig, Figure):
        raise fail(func, name, f"expected a matplotlib Figure, got {type(fig).__name__}")
    return fig


def figsize(value, func: str, name: str = "figsize") -> tuple[float, float]:
    """A figure size ``(width, height)`` in inches, each in ``(0, 100]``."""
    w, h = array(value, func, name, (2,))
    if not (0 < w <= MAX_INCHES and 0 < h <= MAX_INCHES):
        raise fail(func, name, f"width and height must lie in (0, {MAX_INCHES:g}] inches, got ({w:g}, {h:g})")
    return float(w), float(h)


def dpi(value, func: str, name: str = "dpi") -> float:
    """Dots per inch of a figure, from 10 to 1000."""
    return real(value, func, name, low=10, high=1000)


def color(value, func: str, name: str = "color"):
    """``value`` if matplotlib reads it as a colour (a name, ``"0.6"``, ``"tab:red"``, an RGB(A) tuple)."""
    if isinstance(value, (bool, np.bool_)) or not is_color_like(value):
        raise fail(func, name, f"not a matplotlib colour: {value!r}")
    return value


def colors(value, func: str, name: str = "colors") -> list:
    """A non-empty sequence of matplotlib colours."""
    if isinstance(value, str) or not isinstance(value, (list, tuple)) or not value:
        raise fail(func, name, f"expected a non-empty list of colours, got {value!r}")
    return [color(c, func, f"{name}[{k}]") for k, c in enumerate(value)]


def colormap(value, func: str, name: str = "cmap") -> str:
    """The name of a registered matplotlib colormap."""
    if not isinstance(value, str) or value not in mpl.colormaps:
        raise fail(func, name, f"not a matplotlib colormap name: {value!r}")
    return value


def optional_text(value, func: str, name: str = "label"):
    """An optional text (a title, a legend label): None or a string, which may be empty."""
    return None if value is None else text(value, func, name, empty=True)


def texts(value, func: str, name: str, n: int | None = None) -> list:
    """A sequence of ``n`` (any number if None) strings."""
    if isinstance(value, str) or not isinstance(value, (list, tuple)):
        raise fail(func, name, f"expected a list of strings, got {type(value).__name__}")
    if n is not None and len(value) != n:
        raise fail(func, name, f"expected {n} strings, got {len(value)}")
    return [text(v, func, f"{name}[{k}]", empty=True) for k, v in enumerate(value)]


def coords(value, func: str, name: str, shape: tuple, *, at_least: int = 0, limit: float = LIMIT, why: str = WHY):
    """``value`` as a finite float array of ``shape`` whose entries a figure can draw (``|x| <= limit``; a
    ``limit`` other than :data:`LIMIT` comes with its reason ``why``)."""
    return magnitude(array(value, func, name, shape, at_least=at_least), func, name, limit=limit, why=why)


def vector(value, func: str, name: str, sizes: tuple = (2, 3), *, limit: float = LIMIT, why: str = WHY):
    """``value`` as a finite, drawable 1-d float array whose length is one of ``sizes`` (``limit``, ``why``: as for
    :func:`coords`)."""
    a = array(value, func, name, (None,))
    if len(a) not in sizes:
        raise fail(func, name, f"expected {' or '.join(map(str, sizes))} numbers, got {len(a)}")
    return magnitude(a, func, name, limit=limit, why=why)


def points(value, func: str, name: str, width: int = 3, *, at_least: int = 1, limit: float = LIMIT, why: str = WHY):
    """One point ``(width,)`` or several ``(N, width)``, as a drawable ``(N, width)`` array."""
    a, _ = batch(value, func, name, (width,), at_least=at_least)
    return magnitude(a, func, name, limit=limit, why=why)


def scan_arrays(ranges, angles, func: str, name: str = "") -> tuple[np.ndarray, np.ndarray]:
    """A scan's ranges (N,) (NaN or inf: no return) and angles (N,), radians."""
    r = array(ranges, func, f"{name}ranges", (None,), finite=False)
    a = coords(angles, func, f"{name}angles", (None,), limit=1e6, why=ANGLE_WHY)
    same_length(func, **{f"{name}ranges": r, f"{name}angles": a})
    ok = np.isfinite(r)
    if np.any(r[ok] < 0) or np.any(r[ok] > LIMIT):
        raise fail(func, f"{name}ranges", f"ranges must lie in [0, {LIMIT:g}] (NaN or inf: no return)")
    return r, a


def scan_pair(scan, func: str, name: str = "scan") -> tuple[np.ndarray, np.ndarray]:
    """A scan given as one pair ``(ranges, angles)``."""
    if not isinstance(scan, (list, tuple)) or len(scan) != 2:
        raise fail(func, name, f"expected a scan (ranges, angles), got {type(scan).__name__}")
    return scan_arrays(scan[0], scan[1], func, f"{name} ")


def index_pairs(value, func: str, name: str, first: tuple[str, int], second: tuple[str, int]) -> np.ndarray:
    """Pairs (k, 2) of whole indices into two lists given as ``(name, length)`` (an empty list: no pair)."""
    if isinstance(value, (list, tuple)) and not value:
        return np.zeros((0, 2), int)
    p = array(value, func, name, (None, 2))
    (a, n_first), (b, n_second) = first, second
    if np.any(p != np.round(p)) or np.any(p < 0) or np.any(p[:, 0] >= n_first) or np.any(p[:, 1] >= n_second):
        raise fail(func, name, f"expected pairs of whole indices into {a} ({n_first}) and {b} ({n_second})")
    return p.astype(int)


def trajectory(poses, func: str, name: str = "poses", *, at_least: int = 0, widths: tuple = (2, 3)) -> np.ndarray:
    """A trajectory (T, 3) (or, if 2 is among ``widths``, positions (T, 2)), drawable."""
    p = coords(poses, func, name, (None, None), at_least=at_least)
    if p.shape[1] not in widths:
        want = "poses (T, 3) or positions (T, 2)" if 2 in widths else "poses (T, 3)"
        raise fail(func, name, f"expected {want}, got {p.shape}")
    return p


def coord(value, func: str, name: str, *, limit: float = LIMIT, **kw) -> float:
    """One drawn number (a position, a length): finite and within ``+-limit``; ``kw`` as for :func:`real`."""
    return real(value, func, name, low=kw.pop("low", -limit), high=kw.pop("high", limit), **kw)


def scene(value, func: str, name: str = "scene"):
    """A laser scene: a :class:`~cga_lessons.mapping2d.Scene`, or the name (or path) :func:`load_scene` reads."""
    from cga_lessons import mapping2d

    if isinstance(value, mapping2d.Scene):
        return value
    if not isinstance(value, str) or not value:
        raise fail(func, name, f"expected a Scene or a scene's name ('room', 'corridor', 'office'), got {value!r}")
    with relabel(func, name):
        return mapping2d.load_scene(value)


_NAME_RE = re.compile(r"^[A-Za-z0-9_.\-]+(/[A-Za-z0-9_.\-]+)*$")


def slash_path(value, func: str, name: str = "name") -> str:
    """A scene-tree path such as ``"robot/base"``: parts of letters, digits, ``_ . -`` joined by ``/``."""
    if not _NAME_RE.match(text(value, func, name)):
        raise fail(func, name, "must be a slash path of letters, digits, '_', '.', '-' such as 'robot/base' "
                   f"(no empty parts, no leading/trailing '/'), got {value!r}")  # fmt: skip
    return value


def legend_loc(value, func: str, name: str = "legend_loc") -> str:
    """A legend location matplotlib knows by name ("best", "upper right", ...)."""
    from matplotlib.legend import Legend

    return choice(value, func, name, Legend.codes)


def function(value, func: str, name: str):
    """``value`` if it can be called."""
    if not callable(value):
        raise fail(func, name, f"expected a function, got {type(value).__name__}")
    return value


def entity(X, func: str, name: str, kinds: tuple[str, ...]) -> Multivector:
    """``X`` if it is a conformal blade whose :func:`~cga_lessons.conformal.classify` name is one of ``kinds``."""
    from cga_lessons import conformal as cga

    if not isinstance(X, Multivector):
        raise fail(func, name, f"expected a conformal {' or '.join(kinds)}, got {type(X).__name__}")
    with relabel(func, name):
        got = cga.classify(X).name
    if got not in kinds:
        raise fail(func, name, f"expected a {' or '.join(kinds)}, got a {got}")
    return X


def point_pairs(PP, func: str, name: str = "PP") -> Multivector:
    """``PP``: point pairs of G(4,1) (one, or a batch): a finite multivector of grade 2 only."""
    from cga_lessons import conformal as cga

    if not isinstance(PP, Multivector) or PP.algebra is not cga.G41:
        raise fail(func, name, f"expected point pairs (grade-2 multivectors of G(4,1)), got {type(PP).__name__}")
    grades = PP.grades_present()
    if grades != [2]:
        raise fail(func, name, f"expected point pairs (grade 2), got a multivector of grades {grades}")
    if not all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in PP.coeffs.values()):
        raise fail(func, name, "contains NaN or inf")
    return PP


def _readers() -> dict:
    """``argument name -> (kind, reader of its Euclidean parameters)`` for :func:`entity_parameters`."""
    from cga_lessons import conformal as cga

    return {
        "point_pair": ("point pair", cga.point_pair_endpoints),
        "sphere": ("sphere", cga.sphere_center_radius),
        "plane": ("plane", cga.plane_normal_distance),
        "line": ("line", lambda X: (cga.line_closest_point(X), cga.line_direction(X))),
        "circle": ("circle", cga.circle_center_radius),
    }


def entity_parameters(X, func: str, name: str) -> tuple:
    """The Euclidean parameters of the entity given as ``name`` ("point_pair", "sphere", "plane", "line" or
    "circle": also its kind), read back with :mod:`cga_lessons.conformal` and checked drawable."""
    kind, read = _readers()[name]
    X = entity(X, func, name, (kind,))
    with relabel(func, name):
        out = read(X)
    values = np.concatenate([np.ravel(v) for v in out])
    if not np.all(np.isfinite(values)):
        raise fail(func, name, f"its {kind}'s parameters are not finite: it cannot be drawn")
    magnitude(values, func, name, limit=LIMIT, why=f"its {kind}'s parameters: {WHY}")
    return out


def reflection_planes(planes, func: str) -> list:
    """``planes``: two ``(normal, distance, label)`` triples, each normal with a part in the (e1, e2) plane."""
    if not isinstance(planes, (list, tuple, np.ndarray)) or len(planes) != 2:
        raise fail(func, "planes", f"expected two (normal, distance, label) triples, got {type(planes).__name__}")
    out = []
    for k, plane in enumerate(planes):
        if not isinstance(plane, (list, tuple, np.ndarray)) or len(plane) != 3:
            raise fail(func, f"planes[{k}]", "expected a triple (normal, distance, label)")
        n = vector(plane[0], func, f"planes[{k}] normal", (2, 3))
        if not np.hypot(n[0], n[1]) > 1e-12 * max(1.0, np.abs(n).max()):
            raise fail(func, f"planes[{k}] normal", "has no part in the (e1, e2) plane: its trace is not a line")
        distance = coord(plane[1], func, f"planes[{k}] distance")
        out.append((n, distance, optional_text(plane[2], func, f"planes[{k}] label")))
    return out


def accuracy_curves(separations, curves, func: str):
    """The separations (> 0) and ``{label: (worst, failed, refused)}`` of
    :func:`~cga_lessons.viz.ch2_accuracy.point_pair_accuracy`, checked."""
    seps = coords(separations, func, "separations", (None,), at_least=1)
    if np.any(seps <= 0):
        raise fail(func, "separations", "must all be > 0 (a log scale)")
    if not isinstance(curves, dict) or not curves:
        raise fail(func, "curves", "expected a non-empty dict label -> (worst, failed, refused)")
    out = {}
    for name, curve in curves.items():
        where = f"curves[{name!r}]"
        if not isinstance(name, str) or not isinstance(curve, (list, tuple)) or len(curve) != 3:
            raise fail(func, where, "expected a label (str) -> (worst, failed, refused) of point_pair_accuracy")
        worst = array(curve[0], func, f"{where} worst", (None,), finite=False)  # NaN: every trial raised
        same_length(func, separations=seps, **{f"{where} worst": worst})
        if np.any(worst < 0) or np.any(worst == np.inf):
            raise fail(func, f"{where} worst", "errors must be >= 0 (or NaN where every trial raised)")
        counts = [array(c, func, f"{where} {k}", seps.shape) for k, c in zip(("failed", "refused"), curve[1:])]
        if any(np.any(c < 0) for c in counts):
            raise fail(func, where, "failed and refused are counts (>= 0)")
        out[name] = (worst, *counts)
    return seps, out
