"""Fuzz cases of :mod:`cga_lessons.viz`: the figures, the explorers (and their ``update`` methods), the 3D scene.

Each valid call is small (a few points, the smallest scene, a grid of a few nodes); the figures use tiny sizes.  The
heavy objects (a scene, a fused map, the explorers) are made once, on first use, and shared by the cases (their
``args`` are functions, so that they are not deep-copied for every call); an explorer's ``update`` case sets every
value it changes, so that a spoiled call that was accepted leaves nothing behind for the next one.  See
:mod:`fuzz.harness`.
"""

from __future__ import annotations

import functools
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cga_lessons import conformal as cga  # noqa: E402
from cga_lessons.viz import ch2 as vz_ch2  # noqa: E402
from cga_lessons.viz import ch2_3d as c3d  # noqa: E402
from cga_lessons.viz import ch2_accuracy as c2a  # noqa: E402
from cga_lessons.viz import ch2_transformations as c2t  # noqa: E402
from cga_lessons.viz import controls as vz_controls  # noqa: E402
from cga_lessons.viz import exploration as vz_exploration  # noqa: E402
from cga_lessons.viz import explore_conformal_map as vz_explore_conformal_map  # noqa: E402
from cga_lessons.viz import explore_entities as vz_explore_entities  # noqa: E402
from cga_lessons.viz import explore_motion as vz_explore_motion  # noqa: E402
from cga_lessons.viz import explore_nodes as vz_explore_nodes  # noqa: E402
from cga_lessons.viz import explore_null_cone as vz_explore_null_cone  # noqa: E402
from cga_lessons.viz import explore_products as vz_explore_products  # noqa: E402
from cga_lessons.viz import explore_relocalization as vz_explore_relocalization  # noqa: E402
from cga_lessons.viz import explore_robot as vz_explore_robot  # noqa: E402
from cga_lessons.viz import explore_scan as vz_explore_scan  # noqa: E402
from cga_lessons.viz import explore_stereo as vz_explore_stereo  # noqa: E402
from cga_lessons.viz import future_work as vz_future_work  # noqa: E402
from cga_lessons.viz import future_work_arms as vz_future_work_arms  # noqa: E402
from cga_lessons.viz import future_work_stereo as vz_future_work_stereo  # noqa: E402
from cga_lessons.viz import future_work_tables as vz_future_work_tables  # noqa: E402
from cga_lessons.viz import laser as vz_laser  # noqa: E402
from cga_lessons.viz import map3d as vz_map3d  # noqa: E402
from cga_lessons.viz import meshcat_scene as mc  # noqa: E402
from cga_lessons.viz import meshcat_server as vz_meshcat_server  # noqa: E402
from cga_lessons.viz import motions as vz_motions  # noqa: E402
from cga_lessons.viz import relocalization as vz_relocalization  # noqa: E402
from cga_lessons.viz import scene3d as s3  # noqa: E402
from cga_lessons.viz import scene3d_matplotlib as s3m  # noqa: E402
from cga_lessons.viz import stereo as vz_stereo  # noqa: E402
from fuzz.harness import Case, fresh_path, temporary_folder  # noqa: E402

_TMP = temporary_folder("cga-fuzz-viz-")
_SPHERE, _PLANE = cga.sphere([0.0, 0.0, 0.0], 1.0), cga.plane([0.0, 0.0, 1.0], 1.0)
_LINE = cga.line_from_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
_CIRCLE = cga.circle_from_points([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
_PAIR = cga.point_pair([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
_POSE = np.eye(4)


def _ax():
    return plt.figure(figsize=(2, 2), dpi=20).add_subplot()


def _ax3d():
    return plt.figure(figsize=(2, 2), dpi=20).add_subplot(projection="3d")


def _scene():
    """A box, a sphere and a frame."""
    return [
        s3.Box("robot/base", (0.0, 0.0, 0.1), (0.4, 0.3, 0.2)),
        s3.Sphere("ball", (1.0, 0.0, 0.5), 0.1),
        s3.Frame("robot/frame", _POSE),
    ]


@functools.cache
def _G2():
    from cga_lessons.algebra import Algebra

    return Algebra(2)


@functools.cache
def _recording_vis():
    return mc.Visualizer(window=mc._RecordingWindow())  # the offline recorder of export_html: no server


# ------------------------------------------------------------------ scene3d
_SCENE_CASES = [
    Case(s3.Box, {"name": "robot/base", "center": (0.0, 0.0, 0.1), "size": (0.4, 0.3, 0.2), "rotation": np.eye(3),
                  "color": (0.2, 0.4, 0.8), "opacity": 0.5}, strict=True,
         extra={"size": [(0.4, 0.0, 0.2), (-1.0, 1.0, 1.0)], "rotation": [2 * np.eye(3), np.diag([1.0, 1.0, -1.0])],
                "color": [(255, 0, 0)], "opacity": [1.5, -0.1], "name": ["a//b", "/a", "a b"]}),
    Case(s3.Sphere, {"name": "ball", "center": (1.0, 0.0, 0.5), "radius": 0.1, "color": (0.8, 0.2, 0.2),
                     "opacity": 1.0}, strict=True, extra={"radius": [0.0, -1.0]}),
    Case(s3.Quad, {"name": "walls/0", "corners": [[2, -1, 0], [2, 1, 0], [2, 1, 1], [2, -1, 1]],
                   "color": (0.7, 0.7, 0.7), "opacity": 0.6}, strict=True,
         extra={"corners": [[[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]], np.zeros((4, 3))]}),
    Case(s3.Cylinder, {"name": "post", "start": (1.5, -0.5, 0.0), "end": (1.5, -0.5, 1.0), "radius": 0.05,
                       "color": (0.3, 0.3, 0.3), "opacity": 1.0}, strict=True,
         extra={"end": [(1.5, -0.5, 0.0)], "radius": [0.0]}),
    Case(s3.Polyline, {"name": "path", "points": [[0, 0, 0], [1, 0, 0], [1, 1, 0]], "color": (0.0, 0.0, 0.0),
                       "width": 2.0}, strict=True, extra={"points": [[[0, 0, 0]]], "width": [0.0]}),
    Case(s3.PointCloud, {"name": "cloud", "points": [[0, 0, 0], [1, 0, 0]], "color": (0.1, 0.3, 0.9), "size": 0.02},
         strict=True, extra={"size": [0.0]}),
    Case(s3.Frame, {"name": "frame", "pose": _POSE, "scale": 0.2}, strict=True,
         extra={"pose": [np.diag([1.0, 1.0, 1.0, 2.0]), np.diag([1.0, 1.0, -1.0, 1.0])], "scale": [0.0]}),
    Case(s3.check_scene, lambda: {"primitives": _scene(), "func": "check_scene"}, strict=True,
         extra={"primitives": [[_scene()[0], _scene()[0]], [s3.Sphere("g", (0, 0, 0), 1.0),
                                                            s3.Sphere("g/b", (0, 0, 0), 1.0)],
                               [_scene()[0], "ball"], {"a": 1}]}),
    Case(s3.scene_bounds, lambda: {"primitives": _scene()}, extra={"primitives": [[], [[]]]}),
    Case(s3m.draw_matplotlib, lambda: {"ax": None, "primitives": _scene(), "limits": None, "labels": True, "pad": 0.05},
         strict=True, extra={"ax": [_ax()], "limits": [((0, 0, 0), (1, 1)), ((1, 1, 1), (0, 0, 0)), (np.nan, 1)]}),
    Case(s3m.set_equal_3d, lambda: {"ax": _ax3d_shared(), "lo": (0.0, 0.0, 0.0), "hi": (1.0, 1.0, 1.0), "pad": 0.05},
         strict=True, extra={"ax": [_ax()], "hi": [(-1.0, 0.0, 0.0)], "pad": [-1.0]}),
]  # fmt: skip


# ------------------------------------------------------------------ meshcat_scene (offline: no server)
def _existing_file() -> Path:
    p = _TMP / "keep-me.html"
    p.write_text("a user's file")
    return p


_MESHCAT_CASES = [
    Case(vz_controls.slider_panel, lambda: {"show": _show_x, "x": _slider()}, positional=("show",), strict=True,
         extra={"show": [print, lambda y: y]}),
    Case(vz_meshcat_server.close_viewer, lambda: {"vis": mc.Visualizer(window=mc._RecordingWindow())}, strict=True),
    Case(mc.show, lambda: {"vis": _recording_vis(), "primitives": _scene(), "clear": False}, strict=True,
         extra={"primitives": [[_scene()[0], "ball"]]}),
    Case(mc.set_camera, lambda: {"vis": _recording_vis(), "lo": (0.0, 0.0, 0.0), "hi": (1.0, 1.0, 1.0),
                                    "direction": (1.0, -1.4, 0.9), "distance": 1.3, "grid": 0.5}, strict=True,
         extra={"direction": [(0.0, 0.0, 0.0)], "hi": [(-1.0, 0.0, 0.0)], "distance": [0.0, -1.0], "grid": [0.0]}),
    Case(mc.scene_html, lambda: {"primitives": _scene()[:1], "frame_camera": True, "camera_distance": 1.3},
         strict=True, extra={"primitives": [[]], "camera_distance": [0.0]}),
    Case(mc.export_html, lambda: {"primitives": _scene()[:1], "path": fresh_path("scene.html"), "overwrite": False,
                                     "frame_camera": True}, strict=True,
         extra={"path": [_existing_file(), str(_TMP / "no-folder" / "x.html"), "", 3], "primitives": [[]]}),
    Case(mc.EmbeddedScene, {"html": "<p>a scene</p>", "n_primitives": 3, "height": 480}, strict=True,
         extra={"height": [480.0, 50, 10**6]}),
    Case(mc.scene_iframe, lambda: {"primitives": _scene()[:1], "height": 480, "frame_camera": True,
                                      "camera_distance": 1.3}, strict=True,
         extra={"height": [480.0, 50], "primitives": [[]]}),
]  # fmt: skip


# ------------------------------------------------------------------ controls, ch2
def _slider():
    from ipywidgets import FloatSlider

    return FloatSlider(value=1.0, min=0.0, max=2.0)


def _show_x(x):
    """A drawing function for the sliders (returns nothing to show)."""


@functools.cache
def _ax3d_shared():
    return _ax3d()  # one 3D axes for the cases that only set its limits (the harness closes its figure: no matter)


def _accuracy():
    return {"d = 1": (np.array([1e-16, 1e-12]), np.array([0, 1]), np.array([1, 0]))}


_GRID = np.array([[[0.0, -1.0, 0.0], [1.0, -1.0, 0.0]], [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]])
_TRIANGLE = np.array([[-1.6, 0.2, 0.0], [-0.6, 0.5, 0.0], [-1.3, 1.6, 0.0]])
_PLANE_LIST = [((1.0, 0.0, 0.0), 0.0, "first"), ((1.0, 0.0, 0.0), 0.5, "second")]
_PLANES = np.empty((2, 3), object)  # the harness cannot ravel a list of mixed triples: the same in an object array
_PLANES[:] = [list(p) for p in _PLANE_LIST]
_WRONG_PAIR, _WRONG_SPHERE, _WRONG_PLANE = (
    [_SPHERE, _LINE],
    [_PLANE, _PAIR, cga.up([0.0, 0.0, 0.0]) + 0.5 * cga.einf],
    [_SPHERE],
)
_CH2_CASES = [
    Case(vz_ch2.show, lambda: {"fig": plt.figure(figsize=(1, 1), dpi=20), "colors": 16}, strict=True,
         extra={"colors": [1, 1000]}),
    Case(vz_ch2.product_table, lambda: {"alg": _G2()}, kinds={"alg": [_SPHERE, "G2"]}),
    Case(vz_ch2.fig_bivectors, {"a": (2.0, 0.5), "b": (0.5, 1.5)}, strict=True),
    Case(vz_ch2.fig_stereographic_1d, {"xs": [-1.0, 0.5, 2.0]}, strict=True),
    Case(vz_ch2.fig_null_cone, {"xs": [-1.0, 0.5]}, strict=True),
    Case(vz_ch2.fig_minkowski_plane, {}),
    Case(c3d.fig_entities, lambda: {"points": [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], "point_pair": _PAIR,
                                       "sphere": _SPHERE, "plane": _PLANE, "line": _LINE, "circle": _CIRCLE},
         strict=True,
         allow={k: ["None"] for k in ("points", "point_pair", "sphere", "plane", "line", "circle", "title")},
         kinds={"point_pair": _WRONG_PAIR, "sphere": _WRONG_SPHERE, "plane": _WRONG_PLANE, "line": [_CIRCLE, _PLANE],
                "circle": [_LINE, _SPHERE]}),
    Case(c2t.grid_lines, {"lo": -1.0, "hi": 1.0, "n_lines": 3, "n_pts": 5}, strict=True,
         extra={"n_lines": [0, 10**9], "n_pts": [1, 10**9]}),
    Case(c2t.fig_inversion_grid, {"grid": _GRID, "image": _GRID * 0.5, "center": (0.3, 0.2, 0.0), "radius": 1.0,
                                     "window": (-2.5, 2.5, -2.5, 2.5), "highlight": 1}, strict=True,
         allow={"window": ["None"], "highlight": ["None"]},
         extra={"image": [_GRID[:1]], "radius": [0.0], "window": [(1.0, 0.0, 0.0, 1.0)], "highlight": [2, -1]}),
    Case(c2t.fig_two_reflections, {"shape": _TRIANGLE, "after_first": _TRIANGLE + 1.0,
                                      "after_second": _TRIANGLE + 2.0, "planes": _PLANES, "title": "two",
                                      "span": 3.0, "center": (0.0, 0.0, 0.0), "legend_loc": "best"}, strict=True,
         allow={"center": ["None"], "title": ["None"]},
         extra={"planes": [_PLANE_LIST[:1], [((0.0, 0.0, 1.0), 0.0, "z"), _PLANE_LIST[0]],
                           [(1.0, 2.0, 3.0)] * 2, [((np.nan, 1.0, 0.0), 0.0, "a"), _PLANE_LIST[0]]],
                "after_first": [_TRIANGLE[:2]], "span": [0.0]}),
    Case(c3d.fig_screw_helix, {"points": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.1], [-1.0, 0.0, 0.2]],
                                  "axis_point": (0.0, 0.0, 0.0), "axis_direction": (0.0, 0.0, 1.0), "title": "helix"},
         strict=True, allow={"title": ["None"]}, extra={"axis_direction": [(0.0, 0.0, 0.0)]}),
    Case(c3d.set_equal_3d, lambda: {"ax": _ax3d_shared(), "pts": [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]], "pad": 0.3,
                                       "labels": ("x", "y", "z")}, strict=True, extra={"ax": [_ax()], "pad": [-1.0]}),
    Case(c2a.point_pair_accuracy, lambda: {"separations": [0.1, 1e-9], "distance": 4.0,
                                              "rng": np.random.default_rng(0), "trials": 2}, strict=True,
         nonfinite_ok="documented: worst is NaN where every trial raised",
         extra={"separations": [[0.0], [-1.0]], "trials": [0, 10**9], "rng": [0, np.random.RandomState(0)]}),
    Case(c2a.fig_point_pair_accuracy, lambda: {"separations": [1e-3, 1e-1], "curves": _accuracy()}, strict=True,
         extra={"separations": [[0.0, 1.0]], "curves": [{}, {"a": (1, 2)}, {"a": ([np.inf, 1.0], [0, 0], [0, 0])},
                                                          {3: ([1.0, 1.0], [0, 0], [0, 0])}]}),
]  # fmt: skip


# ------------------------------------------------------------------ exploration
@functools.cache
def _ax_shared():
    return _ax()  # one 2D axes for the cases that draw on a given axes


@functools.cache
def _scenario():
    from cga_lessons import exploration as ex

    small = ex.Scenario(x_range=(-60.0, 0.0), y_range=(-30.0, 30.0), z_range=(0.0, 30.0), sphere_samples=6)
    return ex.run_scenario(small), ex.run_scenario(small, sphere_center=None)


@functools.cache
def _detour():
    from cga_lessons import exploration as ex

    return ex.detour((0.0, 0.0), (10.0, 0.0), (5.0, 0.2), 1.0, n_arc=4)


def _disagreements():
    from cga_lessons import exploration as ex

    return ex.DISAGREEMENTS


_EXPLORATION_CASES = [
    Case(vz_exploration.plot_scenario, lambda: {"result": _scenario()[0]}, strict=True,
         kinds={"result": [_detour(), _scenario()[0].grid]}),
    Case(vz_exploration.plot_nodes, lambda: {"ax": _ax_shared(), "result": _scenario()[0], "plane": "xz",
                                                "labels": np.zeros(18, int), "legend": False}, strict=True,
         allow={"labels": ["None"]}, extra={"labels": [np.full(18, 9)], "ax": [_ax3d_shared()]}),
    Case(vz_exploration.plot_occupancy_steps,
         lambda: {"result": _scenario()[0], "counts": (1, None), "window": 45.0},
         strict=True, kinds={"result": [_scenario()[1]]}, extra={"counts": [(), (-1,), (1.5,), ("a",)]}),
    Case(vz_exploration.plot_disagreements, lambda: {"result": _scenario()[0], "codes": np.zeros(18, int),
                                                        "names": _disagreements()}, strict=True,
         kinds={"result": [_scenario()[1]]}, extra={"codes": [np.full(18, 7)], "names": [{0: "agree"}]}),
    Case(vz_exploration.plot_detour, lambda: {"start": (0.0, 0.0), "goal": (10.0, 0.0), "center": (5.0, 0.2),
                                                 "radius": 1.0, "detour": _detour(),
                                                 "crossings_document": np.array([[4.0, 0.0], [6.0, 0.0]]),
                                                 "ax": _ax_shared()}, strict=True,
         allow={"crossings_document": ["None"], "ax": ["None"]}, kinds={"detour": [_scenario()[0]]},
         extra={"radius": [0.0]}),
]  # fmt: skip


# ------------------------------------------------------------------ the explorers and their update methods
@functools.cache
def _room():
    from cga_lessons import mapping2d

    return mapping2d.load_scene("room")


@functools.cache
def _room_scan():
    """A noise-free scan of the room, its segments (laser frame) and their point pairs."""
    from cga_lessons import mapping2d

    ranges, angles = mapping2d.simulate_scan(_room(), (3.0, 2.0, 0.3), None, n_beams=91)
    segments = mapping2d.extract_segments(ranges, angles)
    return ranges, angles, segments, mapping2d.segment_point_pair(segments)


@functools.cache
def _explorers():
    """One explorer of each kind (small: the room scene, short grids), shared by the ``update`` cases."""
    return {
        "correction": vz_explore_conformal_map.CorrectionExplorer(),
        "pair": vz_explore_entities.PairExplorer(grid=[1e-1, 1e-3]),
        "screw": vz_explore_motion.ScrewExplorer(vz_explore_motion.ScrewParams(steps=2)),
        "nodes": vz_explore_nodes.NodeExplorer(),
        "stereographic": vz_explore_null_cone.StereographicExplorer(),
        "product": vz_explore_products.ProductExplorer(),
        "relocalization": vz_explore_relocalization.RelocalizationExplorer("room", pose=(3.0, 2.0, 0.3), n_show=2),
        "robot": vz_explore_robot.RobotExplorer(_fused()),
        "hough": vz_explore_scan.HoughExplorer("room", pose=(3.0, 2.0, 0.3)),
        "depth": vz_explore_stereo.DepthErrorExplorer(depths=[1.0, 2.0], n_points=5),
    }


@functools.cache
def _fused():
    from cga_lessons import map3d

    tour = map3d.simulate_tour(np.random.default_rng(3), waypoints=((1.5, 1.5), (4.0, 1.5)), stops=(5,),
                               pans=(0.4,), tilts=(0.3,))  # fmt: skip
    return map3d.build_fused_map(tour)


def _update(key, label, values, **kw):
    """A case of ``explorer.update(**values)`` on the shared explorer; None leaves a value as it is."""
    cls = type(_explorers()[key])
    return Case(
        cls.update,
        lambda: {"self": _explorers()[key], **values},
        label=f"{cls.__name__}.update",
        positional=("self",),
        strict=True,
        allow={k: ["None"] for k in values},
        **kw,
    )


_PP_WRONG = [_SPHERE, _LINE, _CIRCLE]
_EXPLORER_CASES = [
    Case(vz_explore_conformal_map.CorrectionExplorer,
         lambda: {"scene": _room(), "pose": (3.0, 2.0, 0.3), "dx": 0.2, "dy": -0.1, "dtheta_deg": 5.0,
                  "max_range": 5.0, "theta_xi_deg": 30.0}, strict=True,
         extra={"scene": ["no-such-scene"], "pose": [(100.0, 100.0, 0.0)], "dtheta_deg": [40.0],
                "theta_xi_deg": [0.0, 100.0], "max_range": [0.0]}),
    _update("correction", "CorrectionExplorer.update", {"dx": 0.4, "dy": -0.3, "dtheta_deg": 10.0},
            extra={"dtheta_deg": [31.0]}),
    Case(vz_explore_conformal_map.place, lambda: {"PP": _room_scan()[3], "pose": (3.0, 2.0, 0.3)}, strict=True,
         kinds={"PP": _PP_WRONG}),
    Case(vz_explore_conformal_map.ends, lambda: {"PP": _room_scan()[3]}, kinds={"PP": _PP_WRONG}),
    Case(vz_explore_conformal_map.line_members, lambda: {"PP": _room_scan()[3], "centre": (3.0, 2.0)},
         strict=True, kinds={"PP": _PP_WRONG}),
    Case(vz_explore_conformal_map.rotor_about, {"centre": (1.0, 2.0), "angle": 0.3}, strict=True),
    Case(vz_explore_conformal_map.conformal_correction,
         lambda: {"PP_map": _room_scan()[3], "PP_scan": _room_scan()[3], "centre": (0.5, 0.2),
                  "theta_xi": 0.5}, strict=True, kinds={"PP_map": _PP_WRONG, "PP_scan": _PP_WRONG},
         extra={"PP_scan": [_PAIR], "theta_xi": [0.0, 2.0]}),
    Case(vz_explore_entities.PairExplorer, {"separation": 1e-3, "distance": 4.0, "grid": [1e-1, 1e-3]},
         strict=True, allow={"grid": ["None"]}, extra={"separation": [0.0, 1e-300], "grid": [[0.0, 1.0]]}),
    _update("pair", "PairExplorer.update", {"separation": 1e-2, "distance": 4.0}, extra={"separation": [0.0]}),
    Case(vz_explore_entities.pair_readback, {"separation": 1e-3, "distance": 4.0, "direction": (0.48, 0.6, 0.64)},
         strict=True, nonfinite_ok="documented: error, p1 and p2 are NaN where (2.131) has no answer in floats",
         extra={"separation": [0.0, 1e-300], "direction": [(0.0, 0.0, 0.0)]}),
    Case(vz_explore_motion.ScrewExplorer, lambda: {"params": vz_explore_motion.ScrewParams(steps=2),
                                                        "start": (0.9, 0.2, 0.1)}, strict=True,
         allow={"params": ["None"]}),
    _update("screw", "ScrewExplorer.update", {"azimuth": 20.0, "elevation": 70.0, "angle": 150.0, "pitch": 0.6},
            extra={"colour": ["red"]}),
    Case(vz_explore_motion.ScrewExplorer.motor, lambda: {"self": _explorers()["screw"], "s": 0.5},
         label="ScrewExplorer.motor", positional=("self",), strict=True),
    Case(vz_explore_motion.ScrewExplorer.tip_path, lambda: {"self": _explorers()["screw"], "n": 3},
         label="ScrewExplorer.tip_path", positional=("self",), strict=True, extra={"n": [1, 10**9]}),
    Case(vz_explore_nodes.NodeExplorer, {"heading_deg": 180.0, "fov_deg": 150.0, "diameter": 15.0}, strict=True,
         extra={"fov_deg": [0.0, 400.0], "diameter": [-1.0]}),
    _update("nodes", "NodeExplorer.update", {"heading_deg": 170.0, "fov_deg": 120.0, "diameter": 10.0}),
    Case(vz_explore_null_cone.StereographicExplorer, {"x": 1.5}, strict=True),
    Case(vz_explore_null_cone.StereographicExplorer.update, lambda: {"self": _explorers()["stereographic"],
                                                                          "x": 2.0},
         label="StereographicExplorer.update", positional=("self",), strict=True),
    Case(vz_explore_products.ProductExplorer, {"angle": 35.0, "len_a": 1.6, "len_b": 1.2, "direction": 15.0,
                                                    "test": (1.1, 0.35)}, strict=True,
         extra={"len_a": [0.0], "test": [(0.0, 0.0)]}),
    _update("product", "ProductExplorer.update", {"angle": 30.0, "len_a": 2.0, "len_b": 1.0, "direction": 0.0},
            extra={"len_b": [0.0, -1.0]}),
    Case(vz_explore_products.geometric_product, {"a": (3.0, 1.0), "b": (1.0, 2.0)}, strict=True),
    Case(vz_explore_products.reflect, {"v": (1.0, 0.5), "n": (0.0, 1.0)}, strict=True,
         extra={"n": [(0.0, 0.0)]}),
    Case(vz_explore_relocalization.RelocalizationExplorer,
         lambda: {"scene": _room(), "pose": (3.0, 2.0, 0.3), "seed": 0, "n_show": 2}, strict=True,
         allow={"pose": ["None"], "seed": ["None"]}, extra={"scene": ["no-such-scene"], "n_show": [0, 10**9]}),
    _update("relocalization", "RelocalizationExplorer.update", {"x": 3.0, "y": 2.0, "theta_deg": 20.0}),
    Case(vz_explore_relocalization.true_partners,
         {"map_segments": [[[0.0, 1.0], [4.0, 1.0]], [[0.0, -1.0], [4.0, -1.0]]],
          "scan_segments": [[[1.0, 0.0], [2.0, 0.0]]], "pose": (1.0, 1.0, 0.0), "distance": 0.05, "angle": 0.08},
         strict=True, extra={"map_segments": [[[[0.0, 1.0], [0.0, 1.0]]]], "distance": [0.0], "angle": [0.0, 2.0]}),
    Case(vz_explore_robot.RobotExplorer, lambda: {"fused": _fused(), "robot": None, "state": None, "sight": 2.0,
                                                       "vis": None}, strict=True,
         allow={"robot": ["None"], "state": ["None"], "vis": ["None"]},
         kinds={"fused": [_room()], "robot": [_room()], "state": [(1.0, 1.0, 0.0, 0.0, 0.0)]},
         extra={"sight": [0.0]}),
    _update("robot", "RobotExplorer.update", {"x": 2.0, "y": 1.5, "theta": 0.2, "pan": 0.3, "tilt": 0.1},
            extra={"pan": [10.0], "tilt": [-10.0]}),
    Case(vz_explore_scan.HoughExplorer, lambda: {"scene": _room(), "pose": (3.0, 2.0, 0.3), "seed": 0,
                                                      "max_range": 5.0}, strict=True,
         allow={"pose": ["None"], "seed": ["None"]}, extra={"scene": ["no-such-scene"], "max_range": [0.0]}),
    _update("hough", "HoughExplorer.update", {"x": 3.0, "y": 2.0, "theta_deg": 20.0}),
    Case(vz_explore_stereo.DepthErrorExplorer, {"baseline": 0.12, "focal_px": 700.0, "noise_px": 0.5,
                                                     "depths": [1.0, 2.0], "n_points": 5, "seed": 0}, strict=True,
         allow={"depths": ["None"]}, extra={"baseline": [0.0], "depths": [[0.0, 1.0]], "n_points": [0]}),
    _update("depth", "DepthErrorExplorer.update", {"baseline": 0.2, "focal_px": 800.0, "noise_px": 0.3},
            extra={"baseline": [0.0], "focal_px": [0.0]}),
]  # fmt: skip


# ------------------------------------------------------------------ future_work*
@functools.cache
def _estimate():
    from cga_lessons.relocalization import MCLEstimate

    return MCLEstimate(np.array([1.0, 1.0, 0.1]), np.diag([0.01, 0.02, 0.001]), True, 0.9, 3, 2.5)


def _snapshot(zoom=None):
    return vz_future_work.Snapshot(
        "a",
        np.array([[1.0, 1.0, 0.0], [1.1, 0.9, 0.1], [0.9, 1.2, 0.2]]),
        np.array([0.0, -1.0, -np.inf]),
        _estimate(),
        np.array([1.0, 1.0, 0.0]),
        zoom,
    )


@functools.cache
def _arm():
    from cga_lessons import kinematics as kin

    return kin.ur5()


@functools.cache
def _cloud():
    from cga_lessons.stereo.detect_scenes import TruthEntity
    from cga_lessons.stereo.detect_search import DetectedEntity

    X = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 0.5, 0.8], [2.0, 0.5, 0.2]])
    plane = {"normal": np.array([0, 0, 1.0]), "center": np.array([0.5, 0.5, 0]), "distance": 0.0}
    sphere = {"center": np.array([2.0, 0.5, 0.5]), "radius": 0.3}
    truth = [TruthEntity("plane", plane, 0.7, np.arange(3)), TruthEntity("sphere", sphere, 0.3, np.arange(3, 5))]
    names = ("a", "b", "c", "d")
    ents = [DetectedEntity("plane", dict(plane), None, np.arange(3), np.eye(4), names, 0.002, 1.0),
            DetectedEntity("sphere", dict(sphere), None, np.arange(3, 5), np.eye(4), names, 0.001, 1.0)]  # fmt: skip
    return X, np.array([0, 0, 0, 1, 1]), truth, ents


_MCL_RECORD = {"logs": {"intel": {"n": 20, "located": {"1": 0.5, "3": 0.9, "10": 1.0}, "wrong": 1, "gross": 0,
                                  "particles": 300.0, "later_ms": 7.25, "single": {"1": 0.4, "3": 0.45, "10": 0.5},
                                  "seq3": 0.75}}}  # fmt: skip
_KIN_RECORD = {"cases": {"motors": {"median_ms": 1.0, "x_floor": 1.0}}, "floor": "motors", "configurations": 100,
               "max_deviation": {"motors": 1e-15}}  # fmt: skip
_STEREO_RECORD = {
    "kinds": ["plane"],
    "sections": [
        {
            "title": "t",
            "rows": [
                {"label": "x", "kinds": {"plane": {"tp": 3, "detected": 4, "truth": 6}}, "points": 10, "seconds": 1.0}
            ],
        }
    ],
}


def _record_file() -> Path:
    import json

    p = _TMP / "record.json"
    p.write_text(json.dumps(_MCL_RECORD))
    return p


def _not_json() -> Path:
    p = _TMP / "not-json.json"
    p.write_text("{ not json")
    return p


def _q(n=2):
    return np.linspace(0.0, 0.5, 6 * n).reshape(n, 6)


_FW_CASES = [
    Case(vz_future_work.metric_box, lambda: {"ax": _ax3d_shared(), "pts": [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]],
                                                  "pad": 0.1}, strict=True, extra={"ax": [_ax()], "pad": [-1.0]}),
    Case(vz_future_work.Snapshot, lambda: {"title": "a", "particles": np.array([[1.0, 1.0, 0.0], [1.1, 0.9, 0.1]]),
                                                "log_w": np.array([0.0, -1.0]), "estimate": _estimate(),
                                                "truth": np.array([1.0, 1.0, 0.0]), "zoom": 0.5}, strict=True,
         allow={k: ["None"] for k in ("log_w", "estimate", "truth", "zoom")},
         kinds={"estimate": [_snapshot(), (1.0, 1.0, 0.0)]},
         extra={"log_w": [np.array([np.nan, 0.0]), np.array([-np.inf, -np.inf])], "zoom": [0.0]}),
    Case(vz_future_work.covariance_ellipse, {"mean": (1.0, 2.0), "cov": [[4.0, 0.0], [0.0, 1.0]],
                                                  "n_sigma": 1.0, "n": 4}, strict=True,
         extra={"cov": [[[1.0, 2.0], [0.0, 1.0]], [[-1.0, 0.0], [0.0, 1.0]]], "n": [2, 10**9], "n_sigma": [0.0]}),
    Case(vz_future_work.draw_particles,
         lambda: {"ax": _ax_shared(), "particles": [[0.0, 0.0, 0.0], [1.0, 1.0, 0.1]],
                                                      "log_w": [0.0, -1.0], "s": 2.0, "cmap": "Blues"}, strict=True,
         allow={"log_w": ["None"]}, extra={"log_w": [[np.nan, 0.0], [np.inf, 0.0]], "s": [0.0]}),
    Case(vz_future_work.draw_pose, lambda: {"ax": _ax_shared(), "pose": (1.0, 2.0, 0.3), "color": "k",
                                                 "length": 0.6, "label": "truth"}, strict=True,
         allow={"label": ["None"]}, extra={"length": [0.0]}),
    Case(vz_future_work.mcl_figure, lambda: {"map_segments": [[[0.0, 0.0], [3.0, 0.0]], [[0.0, 0.0], [0.0, 3.0]]],
                                                  "rows": [[_snapshot(), _snapshot(0.5)]], "row_titles": ["row"],
                                                  "n_sigma": 3.0, "panel": 1.0}, strict=True,
         allow={"row_titles": ["None"]}, extra={"rows": [[], [[]], [["x"]]], "row_titles": [["a", "b"]]}),
    Case(vz_future_work.error_trace_figure, {"position_error": [0.5, 0.05], "heading_error": [0.1, 0.01],
                                                  "converged": np.array([False, True]), "events": [(1, "kidnapped")],
                                                  "tolerance": (0.1, 0.03), "figsize": (3.0, 2.0)}, strict=True,
         extra={"converged": [[1, 0], [True]], "events": [[(1,)], [("a", "b")]], "tolerance": [(0.0, 1.0)]}),
    Case(vz_future_work_arms.dh_home_points, lambda: {"p": vz_future_work_arms.kin.UR5_DH},
         kinds={"p": [_arm(), {"d": [1.0]}]}),
    Case(vz_future_work_arms.chain_points, lambda: {"ch": _arm(), "q": _q(), "points": np.zeros((2, 3)),
                                                         "attached": [0, 6]}, strict=True,
         allow={"points": ["None"], "attached": ["None"]}, kinds={"ch": [vz_future_work_arms.kin.UR5_DH]},
         extra={"attached": [[0, 9], [0.5, 1]], "q": [np.zeros(5), np.zeros((2, 2, 6))]}),
    Case(vz_future_work_arms.axis_segments, lambda: {"ch": _arm(), "q": np.zeros(6), "pts": np.zeros((2, 3)),
                                                          "half": 0.12}, strict=True, extra={"half": [0.0]}),
    Case(vz_future_work_arms.draw_arm, lambda: {"ax": _ax3d_shared(), "pts": np.eye(3), "color": "tab:blue",
                                                     "lw": 3.0, "alpha": 1.0, "label": "arm"}, strict=True,
         allow={"label": ["None"]}, extra={"alpha": [2.0], "pts": [np.zeros((1, 3))]}),
    Case(vz_future_work_arms.draw_frame, lambda: {"ax": _ax3d_shared(), "H": np.eye(4), "length": 0.1, "lw": 2.0},
         strict=True, extra={"ax": [_ax()], "length": [0.0]}),
    Case(vz_future_work_arms.arm_figure, lambda: {"ch": _arm(), "qs": _q(), "points": None, "attached": None,
                                                       "n_drawn": 2, "elev": 24.0, "azim": -60.0,
                                                       "cmap": "viridis", "axes": False, "figsize": (3.0, 3.0)},
         strict=True, allow={"points": ["None"], "attached": ["None"], "title": ["None"]},
         extra={"n_drawn": [0, 3], "qs": [_q(1)]}),
    Case(vz_future_work_arms.ik_figure, lambda: {"ch": _arm(), "q_start": np.zeros(6), "q_end": np.full(6, 0.1),
                                                      "target": np.eye(4), "position_errors": [0.1, 1e-5],
                                                      "rotation_errors": [0.01, 1e-6], "points": None,
                                                      "attached": None, "elev": 24.0, "azim": -60.0,
                                                      "figsize": (4.0, 2.0)}, strict=True,
         allow={"points": ["None"], "attached": ["None"]},
         extra={"rotation_errors": [[0.1]], "position_errors": [[-1.0, 0.0]]}),
    Case(vz_future_work_stereo.detections_figure,
         lambda: {"points": _cloud()[0], "labels": _cloud()[1], "truth": _cloud()[2], "entities": _cloud()[3],
                  "matches": [(0, 0), (1, 1)], "elev": 22.0, "azim": -170.0, "figsize": (4.0, 2.0)}, strict=True,
         kinds={"entities": [_cloud()[2], [_SPHERE]], "truth": [_cloud()[3][:0] + [_PLANE]]},
         extra={"matches": [[(0, 1)], [(5, 0)]], "labels": [[0, 0, 0, 1, 7]]}),
    Case(vz_future_work_stereo.detections_on_image,
         lambda: {"image": np.full((4, 6, 3), 128, np.uint8), "pixels": np.array([[0, 0], [1, 1], [2, 2], [3, 3],
                                                                                [4, 3]], float),
                  "entities": _cloud()[3], "step": 1, "names": ["floor", "ball"], "title": "detections",
                  "figsize": (3.0, 2.0)}, strict=True, allow={"names": ["None"], "title": ["None"]},
         extra={"names": [["one"]], "step": [0], "image": [np.full((4, 6), 3.0), np.full((4, 6, 3), 300.0)]}),
    Case(vz_future_work_stereo.depth_noise, {"z": [1.0, 2.0], "baseline": 0.4, "focal_px": 1200.0, "sigma_d": 1.0},
         strict=True, extra={"z": [[-1.0], [0.0], 2.0], "baseline": [0.0]}),
    Case(vz_future_work_stereo.depth_noise_figure, lambda: {"heads": {"a": (0.12, 700.0, (0.8, 1.6))},
                                                                 "sigma_d": 1.0, "figsize": (3.0, 2.0)}, strict=True,
         extra={"heads": [{}, {"a": (0.1, 700.0, (2.0, 1.0))}, {"a": (0.0, 700.0, (1.0, 2.0))}, {"a": "b"}]}),
    Case(vz_future_work_tables.read_record, lambda: {"path": _record_file()},
         extra={"path": [_not_json(), "", None, 3]}),
    Case(vz_future_work_tables.mcl_table, lambda: {"record": _MCL_RECORD},
         extra={"record": [{"logs": 3}, {"logs": {"a": {"n": "x"}}}, {"nothing": 1}]}),
    Case(vz_future_work_tables.kinematics_table, lambda: {"record": _KIN_RECORD},
         extra={"record": [{**_KIN_RECORD, "cases": {"motors": {"median_ms": "x"}}}, {**_KIN_RECORD, "cases": 3}]}),
    Case(vz_future_work_tables.stereo_table, lambda: {"record": _STEREO_RECORD, "section": 1}, strict=True,
         extra={"section": [0, 2], "record": [{"kinds": ["plane"], "sections": [{"title": "t", "rows": [{}]}]},
                                              {"kinds": 3, "sections": 4}]}),
]  # fmt: skip

# ------------------------------------------------------------------ laser, relocalization, motions
_WALLS = np.array([[[0.0, 0.0], [3.0, 0.0]], [[3.0, 0.0], [3.0, 2.0]]])
_TRAJ = np.array([[0.0, 0.0, 0.0], [1.0, 0.2, 0.1], [2.0, 0.3, 0.2]])
_RANGES, _ANGLES = np.array([1.0, np.inf, 2.0]), np.array([-0.5, 0.0, 0.5])


def _segs():
    return _room_scan()[2][:3]


def _history():
    from types import SimpleNamespace as NS

    cands = [NS(pose=np.array([1.0, 1.0, 0.1]), score=0.9), NS(pose=np.array([2.0, 1.0, 0.0]), score=0.5)]
    return [NS(trajectory=_TRAJ[:1], candidates=cands, status="ambiguous"),
            NS(trajectory=_TRAJ[:2], candidates=cands[:1], status="ok")]  # fmt: skip


_LASER_CASES = [
    Case(vz_laser.new_axes, lambda: {"figsize": (2.0, 2.0), "dpi": 40, "ax": None, "title": "t"}, strict=True,
         allow={"title": ["None"]}, extra={"dpi": [1, 10**6], "figsize": [(0.0, 1.0), (1e6, 1.0)]}),
    Case(vz_laser.draw_scene, lambda: {"scene": _room(), "ax": _ax_shared(), "color": "0.85", "edge": "0.55",
                                            "trajectory": True}, strict=True, allow={"ax": ["None"]},
         kinds={"scene": [_WALLS, _scenario()[0]]}, extra={"color": ["no-colour"], "ax": [_ax3d_shared()]}),
    Case(vz_laser.draw_walls, lambda: {"walls": _WALLS, "ax": _ax_shared(), "color": "0.6", "lw": 3.0,
                                            "alpha": 0.6}, strict=True, extra={"alpha": [2.0], "lw": [-1.0]}),
    Case(vz_laser.draw_scan, lambda: {"ranges": _RANGES, "angles": _ANGLES, "pose": (0.0, 0.0, 0.0),
                                           "ax": _ax_shared(), "color": "tab:blue", "s": 3.0, "rays": True},
         strict=True,
         extra={"ranges": [[-1.0, 1.0, 1.0], [1.0, 1.0]], "s": [-1]}),
    Case(vz_laser.draw_segments, lambda: {"segments": _segs(), "ax": _ax_shared(), "color": "tab:red", "lw": 2.0,
                                               "ends": True, "edges": True, "label": "s"}, strict=True,
         allow={"label": ["None"]}, kinds={"segments": [_WALLS, [_WALLS[0]]]}),
    Case(vz_laser.draw_trajectory, lambda: {"poses": _TRAJ, "ax": _ax_shared(), "color": "tab:green",
                                                 "label": "truth", "lw": 1.2, "ls": "--"}, strict=True,
         allow={"label": ["None"]}, extra={"ls": ["~~"], "poses": [_TRAJ[:, :1]]}),
    Case(vz_laser.draw_hough, lambda: {"hough_sets": [(np.array([1.0, 2.0]), np.array([0.1, 2.0]))],
                                            "labels": ["map"], "ax": _ax_shared(), "markers": ("o", "x"),
                                            "colors": ("tab:blue", "tab:red")}, strict=True,
         extra={"hough_sets": [[], [(np.array([1.0]), np.array([0.1, 0.2]))]], "labels": [["a", "b"]],
                "markers": [("no-marker",)]}),
    Case(vz_laser.draw_correspondences, lambda: {"global_segs": _segs(), "local_segs": _segs(),
                                                      "pairs": [(0, 1), (2, 2)], "ax": _ax_shared()}, strict=True,
         extra={"pairs": [[(0, 9)], [(0.5, 1)]]}),
    Case(vz_laser.draw_point_pair_spheres, lambda: {"pairs": [[(0.0, 0.0), (1.0, 0.0)], [(0.0, 1.0), (1.0, 2.0)]],
                                                         "ax": _ax_shared(), "colors": ("tab:blue", "tab:red")},
         strict=True, extra={"colors": [(), ("no-colour",)]}),
    Case(vz_laser.map_figure, lambda: {"segments": _segs(), "walls": _WALLS, "truth": _TRAJ, "odometry": _TRAJ,
                                            "corrected": _TRAJ, "title": "map", "figsize": (3.0, 2.0), "dpi": 40},
         strict=True, allow={k: ["None"] for k in ("walls", "truth", "odometry", "corrected", "title")}),
    Case(vz_laser.log_map_figure, lambda: {"segments": _segs(), "cloud": np.array([[0.0, 0.0], [1.0, 1.0]]),
                                                "truth": _TRAJ, "corrected": _TRAJ, "odometry": _TRAJ,
                                                "loops": [(0, 2)], "figsize": (4.0, 2.0), "dpi": 40}, strict=True,
         allow={"odometry": ["None"]}, extra={"loops": [[(0, 7)], [(0.5, 1)]]}),
    Case(vz_relocalization.hough_figure, lambda: {"M_h": [[1.0, 0.1], [2.0, 1.0]], "L_h": [[1.0, 0.2]],
                                                       "turned": [[1.0, 1.2]], "turn": 1.0, "ax": _ax_shared()},
         strict=True, allow={"L_h": ["None"], "turned": ["None"], "turn": ["None"]},
         extra={"turned": [[[1.0, 0.1], [2.0, 0.2]]]}),
    Case(vz_relocalization.steps_figure, lambda: {"walls": _WALLS, "map_segments": _WALLS,
                                                       "scan": (_RANGES, _ANGLES), "truth": (0.5, 0.5, 0.0),
                                                       "scan_segments": _WALLS[:1], "placed": _WALLS[:1],
                                                       "pairs": [(1, 0)], "figsize": (3.0, 3.0), "dpi": 30},
         strict=True, allow={"pairs": ["None"]},
         extra={"scan": [(_RANGES,), (_RANGES, _ANGLES[:2])], "pairs": [[(5, 0)]], "placed": [np.zeros((0, 2, 2))]}),
    Case(vz_relocalization.votes_figure, lambda: {"V": np.array([[1, 2], [3, 0]]), "ax": _ax_shared(),
                                                       "title": "votes"}, strict=True, allow={"title": ["None"]}),
    Case(vz_relocalization.placements_figure,
         lambda: {"map_segments": _WALLS, "scan": (_RANGES, _ANGLES), "poses": {"a": (0.5, 0.5, 0.0)},
                  "ax": _ax_shared(), "colors": ["tab:green"], "title": "t", "figsize": (3.0, 2.0), "dpi": 40,
                  "walls": _WALLS}, strict=True, allow={"colors": ["None"], "title": ["None"], "walls": ["None"]},
         extra={"poses": [{}, {"a": (0.0, 0.0)}, {"a": (np.nan, 0.0, 0.0)}], "colors": [[]]}),
    Case(vz_relocalization.rates_figure, lambda: {"x": [1.0, 2.0], "series": {"a": [0.5, 1.0]}, "xlabel": "noise",
                                                       "ax": _ax_shared(), "title": "t", "counts": [10, 20]},
         strict=True, allow={"title": ["None"], "counts": ["None"]},
         extra={"series": [{}, {"a": [0.5]}, {"a": [2.0, 0.0]}, {"a": [np.inf, 0.0]}, {"a": [np.nan, 0.5]}],
                "counts": [[1.5, 2.0], [-1, 2]]}),
    Case(vz_relocalization.look_around_figure, lambda: {"map_segments": _WALLS, "scans": [(_RANGES, _ANGLES)] * 2,
                                                             "history": _history(), "truth": _TRAJ[:2],
                                                             "figsize": (4.0, 2.0), "dpi": 30}, strict=True,
         allow={"truth": ["None"]}, extra={"history": [[], [_TRAJ]], "scans": [[], [(_RANGES,)]]}),
    Case(vz_motions.tool_outline, {"length": 0.4, "width": 0.12}, strict=True,
         extra={"length": [0.0], "width": [-1.0]}),
    Case(vz_motions.fig_motor_blend, lambda: {"outline": vz_motions.tool_outline(),
                                                   "motors": [cga.translator([0.1, 0.0, 0.0]),
                                                              cga.rotor([0, 0, 1], 0.3)],
                                                   "matrix_blend": [np.eye(4)], "axis_point": (0.0, 0.0, 0.0),
                                                   "axis_direction": (0.0, 0.0, 1.0)}, strict=True,
         allow={k: ["None"] for k in ("matrix_blend", "axis_point", "axis_direction", "title")},
         kinds={"motors": [[_SPHERE], [_LINE]]}, extra={"axis_direction": [(0.0, 0.0, 0.0)], "motors": [[]]}),
    Case(vz_motions.fig_scan_registration, {"target": [[0.0, 0.0], [1.0, 0.0]], "source": [[0.0, 1.0]],
                                                 "moved": [[0.1, 1.0]]}, strict=True),
]  # fmt: skip


# ------------------------------------------------------------------ map3d, stereo
@functools.cache
def _robot0():
    from cga_lessons import map3d

    return map3d.Robot()


def _robot():
    from cga_lessons import map3d

    return map3d.Robot(_fused().tour.geometry)


def _state():
    from cga_lessons import map3d

    return map3d.RobotState(2.0, 1.5, 0.0, 0.2, 0.1)


@functools.cache
def _curve():
    from cga_lessons import stereo as st

    a = np.array([1e-3, 2e-3])
    return st.TriangulationCurve(noise_px=np.array([0.5, 1.0]), midpoint=a, dlt=a, difference=np.zeros(2), predicted=a)


def _plane_fit():
    from cga_lessons import conformal as cga

    return cga.fit_plane([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])


def _stereo():
    from cga_lessons import stereo as st

    scene, rig = st.load_scene(), st.load_rig()
    samples = st.sample_scene(scene, rig, np.random.default_rng(2))
    keys = ["points", "segment", "circle_key", "plane_key", "sphere_key"]
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, samples[k]) for k in keys})
    return scene, rig, rec


_IMG = np.zeros((4, 5, 3), np.uint8)
_MAP3D_CASES = [
    Case(vz_map3d.robot_primitives, lambda: {"robot": _robot(), "state": _state(), "prefix": "robot",
                                                  "frames": True}, strict=True, allow={"state": ["None"]},
         kinds={"robot": [_room()], "state": [(2.0, 1.5, 0.0, 0.2, 0.1)]}, extra={"prefix": ["a//b", "/x"]}),
    Case(vz_map3d.map_primitives, lambda: {"fused": _fused(), "virtual_walls": True, "scans": True, "path": True,
                                                "points": True, "prefix": "map"}, strict=True,
         kinds={"fused": [_robot0(), _room()]}),
    Case(vz_map3d.truth_primitives, lambda: {"fused": _fused(), "prefix": "truth"}, strict=True,
         kinds={"fused": [_robot0()]}),
    Case(vz_map3d.plot_robot, lambda: {"robot": _robot(), "state": _state(), "ax": _ax3d_shared(), "elev": 22.0,
                                            "azim": -55.0}, strict=True, allow={"state": ["None"], "ax": ["None"]},
         kinds={"robot": [_room()]}, extra={"ax": [_ax()]}),
    Case(vz_map3d.plot_fused_map, lambda: {"fused": _fused(), "ax": _ax3d_shared(), "robot": _robot(),
                                                "state": _state(), "virtual_walls": False, "truth": True, "elev": 38.0,
                                                "azim": -62.0}, strict=True,
         allow={k: ["None"] for k in ("ax", "robot", "state", "title")}, kinds={"fused": [_robot0()]}),
    Case(vz_map3d.plot_virtual_walls, lambda: {"fused": _fused(), "figsize": (4.0, 2.0)}, strict=True,
         kinds={"fused": [_robot0()]}),
    Case(vz_stereo.plot_views, {"left": _IMG, "right": _IMG, "titles": ("l", "r"), "figsize": (3.0, 2.0)},
         strict=True, extra={"left": [np.full((4, 5, 3), 300.0), np.zeros((4, 5, 2))], "titles": [("l",)]}),
    Case(vz_stereo.plot_epipolar_lines, lambda: {"left": _IMG, "right": _IMG, "x1": [[1.0, 1.0], [2.0, 3.0]],
                                                      "x2": [[1.0, 1.5], [2.0, 3.5]],
                                                      "F": [[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
                                                      "figsize": (3.0, 2.0)}, strict=True,
         extra={"F": [np.zeros((3, 3))], "x2": [[[1.0, 1.0]]]}),
    Case(vz_stereo.plot_triangulation_curve, lambda: {"curve": _curve(), "theory": [1e-3, 2e-3],
                                                           "figsize": (3.0, 2.0)},
         strict=True, allow={"theory": ["None"]},
         extra={"curve": [{}, {"noise_px": [1.0], "midpoint": [1.0, 2.0], "dlt": [1.0]}], "theory": [[1.0]]}),
    Case(vz_stereo.plot_entities_3d, lambda: {"scene": _stereo()[0], "estimates": {"4.1": _stereo()[2]},
                                                   "rig": _stereo()[1], "ax": _ax3d_shared(), "elev": 18.0,
                                                   "azim": -150.0, "figsize": (3.0, 3.0)}, strict=True,
         allow={"rig": ["None"], "ax": ["None"], "title": ["None"]},
         kinds={"scene": [_room(), _WALLS], "rig": [_room()]},
         extra={"estimates": [{"a": {"sphere": {"center": 1.0}}}, {"a": 3}]}),
    Case(vz_stereo.plot_plane_segmentation, lambda: {"image": _IMG, "labels": np.zeros((4, 5), int),
                                                          "fits": [_plane_fit()], "names": ["floor"],
                                                          "figsize": (3.0, 2.0)}, strict=True,
         allow={"names": ["None"]}, extra={"fits": [[{"rms": 1.0}], [3]], "names": [["a", "b"]],
                                           "labels": [np.zeros((4, 4))]}),
]  # fmt: skip

CASES = [*_SCENE_CASES, *_MESHCAT_CASES, *_CH2_CASES, *_EXPLORATION_CASES, *_EXPLORER_CASES, *_FW_CASES,
         *_LASER_CASES, *_MAP3D_CASES]  # fmt: skip


def _none_documented(case: Case) -> None:
    """A parameter whose default is None takes None (a new axes, no title, ...): strict cases allow it."""
    import inspect

    try:
        params = inspect.signature(case.func).parameters
    except (TypeError, ValueError):
        return
    for name, p in params.items():
        if p.default is None:
            case.allow.setdefault(name, ["None"])


for _case in CASES:
    _none_documented(_case)

EXEMPT = {
    "viz.meshcat_server.Viewer": "a meshcat Visualizer whose construction starts a server process (loopback)",
    "viz.meshcat_server.open_viewer": "starts a meshcat server process; its argument checks: tests/test_viewer.py",
}
