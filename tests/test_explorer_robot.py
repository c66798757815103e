"""Notebook 08's explorer of the robot's five degrees of freedom (cga_lessons.viz.explore_robot), without a browser.

The truth is the forward kinematics written out by hand for the default robot (rotations about z and y, no motor
and no 4x4 chain of the package), against what the explorer's artists hold after each update.
"""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cga_lessons.algebra import InvalidInputError  # noqa: E402
from cga_lessons.map3d import build_fused_map  # noqa: E402
from cga_lessons.map3d.robot import Robot  # noqa: E402
from cga_lessons.map3d.state import RobotGeometry, RobotState  # noqa: E402
from cga_lessons.map3d.tour import simulate_tour  # noqa: E402
from cga_lessons.viz.explore_robot import RobotExplorer  # noqa: E402
from cga_lessons.viz.meshcat_scene import Visualizer  # noqa: E402


@pytest.fixture(scope="module")
def fused():
    """A short tour (one leg, one view): a real FusedMap in half a second."""
    tour = simulate_tour(np.random.default_rng(3), waypoints=((1.5, 1.5), (4.0, 1.5), (4.0, 3.0)), stops=(20,),
                         pans=(0.4,), tilts=(0.3,))  # fmt: skip
    return build_fused_map(tour)


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])  # positive: +x turns towards -z (looks down)


def camera_closed_form(g: RobotGeometry, x, y, theta, pan, tilt):
    """Left camera centre and viewing direction of the default robot, whose pan (vertical) and tilt (along y) axes meet.

    World = (x, y, 0) + Rz(theta) (p + Rz(pan) Ry(tilt) eye_offset), p the axes' crossing point; the camera looks
    along its +x axis, Rz(theta) Rz(pan) Ry(tilt) e_x.
    """
    assert g.pan_direction == (0.0, 0.0, 1.0) and g.tilt_direction == (0.0, 1.0, 0.0)
    assert g.pan_point[:2] == g.tilt_point[:2]  # the axes meet
    p = np.array([g.pan_point[0], g.pan_point[1], g.tilt_point[2]])
    turn = rz(theta) @ rz(pan) @ ry(tilt)
    eye = np.array([x, y, 0.0]) + rz(theta) @ (p + rz(pan) @ ry(tilt) @ np.asarray(g.eye_offset))
    return eye, turn[:, 0]


def line_data(line):
    return np.array(line.get_data_3d(), float)


def verts3d(collection):
    """The 3D vertices a Poly3DCollection holds, (n, 3) (matplotlib has no public getter for them)."""
    if hasattr(collection, "_faces"):  # recent matplotlib: faces padded to the longest, the padding flagged invalid
        faces = np.asarray(collection._faces, float)
        return faces[~np.broadcast_to(collection._invalid_vertices, faces.shape[:2])]
    return np.asarray(collection._vec, float)[:3].T  # older matplotlib: homogeneous columns


STATES = [
    dict(x=2.0, y=1.5, theta=0.0, pan=0.0, tilt=0.0),
    dict(x=3.1, y=2.4, theta=2.5, pan=-1.2, tilt=0.6),
    dict(x=5.0, y=4.0, theta=-1.0, pan=2.9, tilt=-0.7),
]


@pytest.mark.parametrize("dofs", STATES)
def test_the_drawn_camera_is_where_the_forward_kinematics_puts_it(fused, dofs):
    ex = RobotExplorer(fused)
    ex.update(**dofs)
    eye, look = camera_closed_form(ex.robot.geometry, **dofs)
    for artists in ex._artists:  # the room and the close-up
        np.testing.assert_allclose(line_data(artists["camera"])[:, 0], eye, atol=1e-12)
        start, end = line_data(artists["sight"]).T
        np.testing.assert_allclose(start, eye, atol=1e-12)
        along = (end - start) / np.linalg.norm(end - start)
        np.testing.assert_allclose(along, look, atol=1e-12)
    # the line of sight ends after `sight` metres, or on the floor if that is nearer
    reach = ex.sight if look[2] >= 0 else min(ex.sight, eye[2] / -look[2])
    np.testing.assert_allclose(ex.sight_end, eye + reach * look, atol=1e-12)
    assert ex.sight_end[2] >= -1e-12
    # the body: a box centred over (x, y) (each corner is in three of its six faces: their mean is the centre)
    H = ex.robot.geometry.base_size[2]
    for artists in ex._artists:
        centre = verts3d(artists["robot/base"]).mean(axis=0)
        np.testing.assert_allclose(centre, [dofs["x"], dofs["y"], ex.robot.geometry.base_clearance + H / 2], atol=1e-12)


def test_update_moves_the_artists_in_place_and_only_what_the_change_reaches(fused):
    ex = RobotExplorer(fused, Robot(), RobotState(2.0, 2.0, 0.3, 0.0, 0.0))
    room = ex._artists[0]
    ids = {name: id(a) for name, a in room.items() if not isinstance(a, list)}
    base, mast, head = (verts3d(room[k]) for k in ("robot/base", "robot/mast", "robot/camera_left"))
    sight = line_data(room["sight"])
    changed = ex.update(pan=0.8)
    assert changed == ("R_pan", "R_pt", "T_opt", "M_mpt", "M_eu", "R_Lpan", "M_eu_lines")  # not the laser's chain
    assert "R_pan" in ex.ax_close.get_title() and "M_lu" not in ex.ax_close.get_title()
    assert {name: id(a) for name, a in room.items() if not isinstance(a, list)} == ids  # the same artists
    np.testing.assert_array_equal(verts3d(room["robot/base"]), base)  # a pan moves neither the body nor the mast
    np.testing.assert_array_equal(verts3d(room["robot/mast"]), mast)
    assert not np.allclose(verts3d(room["robot/camera_left"]), head)
    assert not np.allclose(line_data(room["sight"]), sight)
    assert "pan 0.80 rad" in ex.ax_room.get_title()
    changed = ex.update(x=2.5)
    assert "M_lu" in changed and "R_pan" not in changed
    assert not np.allclose(verts3d(room["robot/base"]), base)
    assert ex.ax_close.get_xlim() == pytest.approx((2.5 - 0.9, 2.5 + 0.9))  # the close-up follows the robot
    assert ex.update() == () and "nothing" in ex.ax_close.get_title()


def test_the_widget_drives_the_explorer(fused):
    pytest.importorskip("ipywidgets")
    ex = RobotExplorer(fused, state=RobotState(2.0, 1.5, 0.0, 0.0, 0.0))
    w = ex.widget()
    sliders = {c.description: c for c in w.children if getattr(c, "description", "")}
    assert {"x (m)", "y (m)", "theta (rad)", "pan (rad)", "tilt (rad)"} <= set(sliders)
    g = ex.robot.geometry
    assert (sliders["tilt (rad)"].min, sliders["tilt (rad)"].max) == pytest.approx(g.tilt_limits)
    sliders["tilt (rad)"].value = 0.5
    assert ex.state.tilt == pytest.approx(0.5)
    eye, _ = camera_closed_form(g, **{k: getattr(ex.state, k) for k in ("x", "y", "theta", "pan", "tilt")})
    np.testing.assert_allclose(ex.camera_position, eye, atol=1e-12)


def test_a_meshcat_viewer_receives_the_moved_robot(fused):
    class Recorder:
        def __init__(self):
            self.commands = []

        def send(self, command):
            self.commands.append(command.lower())

    vis = Visualizer(window=Recorder())
    ex = RobotExplorer(fused, vis=vis)
    ex.update(x=3.0, y=2.0, theta=0.5)
    poses = [c for c in vis.window.commands if c["type"] == "set_transform" and c["path"] == "/meshcat/robot/base"]
    T = np.array(poses[-1]["matrix"], float).reshape(4, 4).T  # meshcat sends column-major
    np.testing.assert_allclose(T[:3, :3], rz(0.5), atol=1e-12)
    np.testing.assert_allclose(T[:2, 3], [3.0, 2.0], atol=1e-12)


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda f: RobotExplorer("a map"), "fused"),
        (lambda f: RobotExplorer(f, robot="geometer"), "robot"),
        (lambda f: RobotExplorer(f, state=(1.0, 2.0, 0.0)), "state"),
        (lambda f: RobotExplorer(f, state=RobotState(1.0, 2.0, 0.0, 0.0, -1.2)), "tilt"),
        (lambda f: RobotExplorer(f, sight=0.0), "sight"),
        (lambda f: RobotExplorer(f, sight=np.inf), "sight"),
        (lambda f: RobotExplorer(f).update(pan=10.0), "pan"),
        (lambda f: RobotExplorer(f).update(tilt=np.nan), "tilt"),
        (lambda f: RobotExplorer(f).update(x="east"), "x"),
    ],
)
def test_bad_input_names_the_function_and_the_argument(fused, make, words):
    with pytest.raises(InvalidInputError, match="RobotExplorer") as info:
        make(fused)
    assert words in str(info.value) and isinstance(info.value, ValueError)


def test_a_refused_update_leaves_the_robot_where_it_was(fused):
    ex = RobotExplorer(fused, state=RobotState(2.0, 1.5, 0.0, 0.2, 0.1))
    before = line_data(ex._artists[1]["camera"])
    with pytest.raises(InvalidInputError):
        ex.update(x=3.0, pan=4.0)  # pan outside its range: x does not move either
    assert ex.state == RobotState(2.0, 1.5, 0.0, 0.2, 0.1)
    np.testing.assert_array_equal(line_data(ex._artists[1]["camera"]), before)
