"""The meshcat viewer: scene upload at 1:1 scale and the offline HTML export.

The scene is the backend-free list of primitives of
:mod:`cga_lessons.viz.scene3d`; :func:`show` uploads it (metres) to a viewer
opened with :func:`~cga_lessons.viz.meshcat_server.open_viewer`, whose loopback-only server, which dies
with its parent, is :mod:`cga_lessons.viz.meshcat_server`.
:func:`export_html` records
the same commands without any server and writes meshcat's self-contained page
(three.js inlined; opens offline); :func:`scene_iframe` embeds that page in a
notebook cell's output, so a saved notebook and its HTML export show the scene.
"""

from __future__ import annotations

import base64
import html as _html
import warnings
from pathlib import Path

import numpy as np
import umsgpack

from cga_lessons.algebra import InvalidInputError
from cga_lessons.checks import fail, flag, instance, integer, real, text
from cga_lessons.files import atomic_open
from cga_lessons.viz.scene3d import Box, Cylinder, Frame, PointCloud, Polyline, Quad, Sphere, check_scene, scene_bounds

from .inputs import LIMIT, coords

with warnings.catch_warnings():  # meshcat 0.3.2 imports a pyzmq module that warns it is deprecated; harmless here
    warnings.filterwarnings("ignore", message="zmq.eventloop.ioloop is deprecated", category=DeprecationWarning)
    import meshcat.geometry as g
    from meshcat import Visualizer  # noqa: F401  (re-exported without meshcat's warning)
    from meshcat.servers.zmqserver import VIEWER_ROOT

__all__ = [
    "show",
    "set_camera",
    "scene_html",
    "export_html",
    "EmbeddedScene",
    "scene_iframe",
]


# ====================================================================== scene upload
def _hex(color) -> int:
    red, green, blue = (int(round(255 * c)) for c in color)
    return (red << 16) | (green << 8) | blue


def _pose(R=None, t=None) -> np.ndarray:
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if t is not None:
        T[:3, 3] = t
    return T


def _material(p):
    return g.MeshLambertMaterial(color=_hex(p.color), opacity=p.opacity, transparent=p.opacity < 1.0)


def _upload(node, p):
    """Send one primitive to ``node`` (a Visualizer at the primitive's path): geometry, then its pose."""
    if isinstance(p, Box):
        node.set_object(g.Box(p.size.tolist()), _material(p))
        node.set_transform(_pose(p.rotation, p.center))
    elif isinstance(p, Sphere):
        node.set_object(g.Sphere(p.radius), _material(p))
        node.set_transform(_pose(t=p.center))
    elif isinstance(p, Quad):
        # two triangles; meshcat materials are double-sided (side=2) and the viewer computes normals
        node.set_object(g.TriangularMeshGeometry(p.corners, [[0, 1, 2], [0, 2, 3]]), _material(p))
        node.set_transform(np.eye(4))
    elif isinstance(p, Cylinder):
        # three.js cylinders run along their local y axis, centred on the origin
        R = p.axis_rotation()
        R = np.column_stack([R[:, 1], R[:, 2], R[:, 0]])  # local y -> axis start->end, still right-handed
        node.set_object(g.Cylinder(p.length, p.radius), _material(p))
        node.set_transform(_pose(R, (p.start + p.end) / 2))
    elif isinstance(p, Polyline):
        geom = g.PointsGeometry(p.points.T.astype(np.float32))
        node.set_object(g.Line(geom, g.LineBasicMaterial(color=_hex(p.color), linewidth=p.width)))
        node.set_transform(np.eye(4))
    elif isinstance(p, PointCloud):
        pts = p.points.T.astype(np.float32)
        colors = np.repeat(np.asarray(p.color, np.float32)[:, None], pts.shape[1], axis=1)
        node.set_object(g.Points(g.PointsGeometry(pts, colors), g.PointsMaterial(size=p.size)))
        node.set_transform(np.eye(4))
    elif isinstance(p, Frame):
        node.set_object(g.triad(p.scale))
        node.set_transform(np.array(p.pose))
    else:  # check_scene already rejects anything else
        raise InvalidInputError(f"show: cannot draw {type(p).__name__}")


def show(vis, primitives, *, clear: bool = False):
    """Upload primitives to a meshcat visualizer at 1:1 scale (metres, z up).

    Each primitive lands at ``vis[p.name]`` (its slash path), replacing what was there, so calling
    ``show`` again with new poses updates a live view.  ``clear=True`` first deletes everything under
    ``vis`` (including a framing shift from :func:`set_camera`: call that after ``show``).  Returns
    None, so a notebook cell ending in ``show(...)`` stores no output (the viewer's repr names its pid
    and port, which change every run).
    """
    _visualizer(vis, "show")
    prims = check_scene(primitives, "show")
    if flag(clear, "show", "clear"):
        vis.delete()
    for p in prims:
        _upload(vis[p.name], p)


def set_camera(vis, lo, hi, *, direction=(1.0, -1.4, 0.9), distance: float = 1.3, grid: float = 0.5):
    """Frame the box ``lo..hi`` (world, z up): look at its centre from ``direction``.

    meshcat 0.3.2's orbit controls always turn about the origin of its scene, and no command moves that
    target.  So the whole scene (the ``/meshcat`` node) is translated horizontally by minus the box's
    centre, rounded to the floor grid's ``grid`` metres so the grid lines keep their place; scale and
    relative positions stay exact.  The camera then sits at ``distance`` times the box's largest side
    along ``direction``.  Returns None.
    """
    func = "set_camera"
    _visualizer(vis, func)
    lo, hi, d = coords(lo, func, "lo", (3,)), coords(hi, func, "hi", (3,)), coords(direction, func, "direction", (3,))
    if np.any(hi < lo):
        raise fail(func, "hi", f"must be >= lo on every axis, got lo {lo.tolist()} and hi {hi.tolist()}")
    if not np.linalg.norm(d) > 0:
        raise fail(func, "direction", "must not be the zero vector")
    distance = real(distance, func, "distance", low=0.0, strict_low=True, high=1e6)
    grid = real(grid, func, "grid", low=1e-6, high=LIMIT)
    centre = (lo + hi) / 2
    shift = np.array([*(np.round(centre[:2] / grid) * grid), 0.0])
    reach = distance * max(float(np.max(hi - lo)), 0.5)
    eye = centre - shift + reach * d / np.linalg.norm(d)
    vis["/meshcat"].set_transform(_pose(t=-shift))
    # the camera hangs under /Cameras/default/rotated, a +90 deg turn about x (y up): world (x, y, z) -> (x, z, -y)
    vis["/Cameras/default/rotated/<object>"].set_property("position", [eye[0], eye[2], -eye[1]])


# ====================================================================== offline export
class _RecordingWindow:
    """Stands in for meshcat's ViewerWindow: keeps the scene tree the server would keep, no process."""

    def __init__(self):
        self.nodes: dict[tuple, dict] = {}  # path -> {"object", "properties", "transform"}, insertion order

    def _node(self, path):
        return self.nodes.setdefault(path, {"object": None, "properties": [], "transform": None})

    def send(self, command):
        data = command.lower()
        path = tuple(s for s in data["path"].split("/") if s)
        blob = umsgpack.packb(data)
        kind = data["type"]
        if kind == "set_object":
            node = self._node(path)
            node["object"], node["properties"] = blob, []
        elif kind == "set_transform":
            self._node(path)["transform"] = blob
        elif kind == "set_property":
            self._node(path)["properties"].append(blob)
        elif kind == "delete":
            for key in [k for k in self.nodes if k[: len(path)] == path]:
                del self.nodes[key]
        else:
            raise InvalidInputError(f"export_html: command {kind!r} is not supported offline")

    def html(self) -> str:
        script = Path(VIEWER_ROOT, "main.min.js").read_text(encoding="utf-8")
        calls = []
        for node in self.nodes.values():
            for blob in [node["object"], *node["properties"], node["transform"]]:
                if blob is not None:
                    calls.append(f'run("{base64.b64encode(blob).decode("ascii")}");')
        if "</script" in script.lower():
            raise RuntimeError("scene_html: meshcat's main.min.js contains '</script' and cannot be inlined as is")
        # Commands are decoded synchronously (meshcat's own page fetch()es data: URLs, which finishes after
        # the load event and is refused by some browsers for file:// pages).
        return (
            "<!DOCTYPE html>\n<html>\n<head><meta charset=utf-8><title>cga-lessons scene</title>\n"
            "<style>html, body { margin: 0; height: 100%; overflow: hidden; }\n"
            "#meshcat-pane { width: 100%; height: 100%; overflow: hidden; }</style>\n"
            '</head>\n<body>\n<div id="meshcat-pane"></div>\n'
            f"<script>\n{script}\n</script>\n"
            "<script>\n"
            'var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));\n'
            "function run(b64) {\n"
            "  const s = atob(b64), a = new Uint8Array(s.length);\n"
            "  for (let i = 0; i < s.length; i++) a[i] = s.charCodeAt(i);\n"
            "  viewer.handle_command_bytearray(a);\n"
            "}\n" + "\n".join(calls) + "\n</script>\n</body>\n</html>\n"
        )


def _visualizer(vis, func: str):
    return instance(vis, func, "vis", Visualizer, "a meshcat Visualizer (open_viewer())")


def _check_distance(value, func: str) -> float:
    return real(value, func, "camera_distance", low=0.0, strict_low=True, high=1e6)


def scene_html(primitives, *, frame_camera: bool = True, camera_distance: float = 1.3) -> str:
    """The self-contained HTML page of a scene (meshcat's viewer with three.js inlined), built offline.

    No server is started: the commands :func:`show` (and :func:`set_camera`, if ``frame_camera``) would
    send are kept per scene-tree node the way meshcat's server keeps them, and embedded base64-encoded
    in the page, which replays them on load (what ``Visualizer.static_html()`` does with a server).
    ``camera_distance`` is :func:`set_camera`'s ``distance`` (times the scene's largest side).
    """
    func = "scene_html"
    prims = _nonempty(primitives, func)
    return _page(prims, flag(frame_camera, func, "frame_camera"), _check_distance(camera_distance, func))


def _nonempty(primitives, func: str) -> list:
    prims = check_scene(primitives, func)
    if not prims:
        raise fail(func, "primitives", "the scene is empty")
    return prims


def _page(prims: list, frame_camera: bool, camera_distance: float) -> str:
    """The page of checked primitives."""
    vis = Visualizer(window=_RecordingWindow())
    show(vis, prims)
    if frame_camera:
        set_camera(vis, *scene_bounds(prims), distance=camera_distance)
    return vis.window.html()


def export_html(primitives, path, *, overwrite: bool = False, frame_camera: bool = True, force=None) -> Path:
    """Write the scene to a self-contained HTML file that opens offline in a browser; return its path.

    Refuses to replace an existing file unless ``overwrite=True`` (``force=True``, its older name, too).  The
    parent folder must exist.  The page is written by :func:`cga_lessons.files.atomic_open`: to a temporary file
    beside ``path``, renamed onto it, so a failed export leaves no partial file.  No server process is started.
    """
    func = "export_html"
    overwrite = flag(overwrite, func, "overwrite") or (force is not None and flag(force, func, "force"))
    with atomic_open(path, func, overwrite=overwrite) as out:  # the path is checked before the page is made
        out.write(_page(_nonempty(primitives, func), flag(frame_camera, func, "frame_camera"), 1.3))
    return Path(path)


# ====================================================================== embedded in a notebook's output
_HIDDEN_NOTE = (
    "An interactive 3D view of {n} primitives (meshcat) is stored in this output. If you read this note instead, "
    "it was removed or cannot draw: JupyterLab removes iframes from the outputs of a notebook it does not trust "
    "(run <i>Trust Notebook</i> from the command palette, or run the cell), and a browser without WebGL cannot "
    "draw it. The pages of <code>cga-lessons export-html</code> show it offline."
)


def _height(value, func: str) -> int:
    """A height in whole pixels, 100 to 4000 (an int: a float is a mistake for a pixel count)."""
    if not isinstance(value, (int, np.integer)) or isinstance(value, (bool, np.bool_)):
        raise fail(func, "height", f"must be a whole number of pixels from 100 to 4000, got {value!r}")
    return integer(value, func, "height", low=100, high=4000)


class EmbeddedScene:
    """A scene for a notebook cell's output: meshcat's offline page inside an ``<iframe srcdoc>``.

    Jupyter stores :attr:`html` as the output's ``text/html``; the plain-text form names the scene.  Where
    the iframe is dropped (JupyterLab sanitizes the outputs of an untrusted notebook and keeps no iframe),
    the note it lies over says how to see the view.
    """

    def __init__(self, html: str, n_primitives: int, height: int):
        func = "EmbeddedScene"
        self.html = text(html, func, "html")
        self.n_primitives = integer(n_primitives, func, "n_primitives", low=0)
        self.height = _height(height, func)

    def _repr_html_(self) -> str:
        return self.html

    def __repr__(self) -> str:
        return f"<meshcat scene of {self.n_primitives} primitives, an interactive 3D view {self.height} px high>"


def scene_iframe(
    primitives, *, height: int = 480, frame_camera: bool = True, camera_distance: float = 1.3
) -> EmbeddedScene:
    """The scene as a cell output: the page of :func:`scene_html` in an iframe ``height`` pixels high.

    The page goes in the iframe's ``srcdoc`` attribute (HTML-escaped), so the output needs no file and no
    server: it turns and zooms in a trusted JupyterLab, in nbconvert's HTML and in ``cga-lessons
    export-html``'s pages, offline.  ``sandbox="allow-scripts"`` lets meshcat run without access to the
    notebook's page.  The iframe lies over a note, which shows where the iframe is removed or cannot draw.
    ``camera_distance``: see :func:`scene_html`.  Each call inlines one copy of meshcat's library (about
    0.85 MB): embed a notebook's scene once.
    """
    func = "scene_iframe"
    height = _height(height, func)
    camera_distance = _check_distance(camera_distance, func)
    frame_camera = flag(frame_camera, func, "frame_camera")
    prims = _nonempty(primitives, func)
    page = _page(prims, frame_camera, camera_distance)
    note = _HIDDEN_NOTE.format(n=len(prims))
    box = (
        f'<div class="cga-lessons-scene" style="position: relative; width: 100%; height: {int(height)}px; '
        'background: #f4f4f6; border: 1px solid #d0d0d8; box-sizing: border-box; overflow: hidden;">\n'
        f'<p style="margin: 0; padding: 1em; color: #444;">{note}</p>\n'
        '<iframe title="3D scene (meshcat)" sandbox="allow-scripts" '
        'style="position: absolute; top: 0; left: 0; width: 100%; height: 100%; border: 0;" '
        f'srcdoc="{_html.escape(page, quote=True)}"></iframe>\n</div>'
    )
    return EmbeddedScene(box, len(prims), int(height))
