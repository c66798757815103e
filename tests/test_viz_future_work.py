"""The figures of notebook 11 (cga_lessons.viz.future_work*): what they draw is what the computations give.

The truths are independent of the drawing code: the localizer's own particles, a covariance ellipse checked through
the inverse covariance, the Denavit-Hartenberg product of plain 4x4 matrices written here from the published tables,
the derivative of ``z = f B / d`` by finite differences, and entities whose points are known by construction.
"""

import json

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cga_lessons import kinematics as kin  # noqa: E402
from cga_lessons.algebra import InvalidInputError  # noqa: E402
from cga_lessons.conformal import PlaneParameters, SphereParameters  # noqa: E402
from cga_lessons.kinematics.arms import PANDA_DH as PANDA_TABLE  # noqa: E402
from cga_lessons.kinematics.arms import UR5_DH as UR5_TABLE  # noqa: E402
from cga_lessons.kinematics.arms import panda, ur5  # noqa: E402
from cga_lessons.map3d import geometer_chains  # noqa: E402
from cga_lessons.mapping2d import laser  # noqa: E402
from cga_lessons.relocalization import MCLConfig  # noqa: E402
from cga_lessons.relocalization.mcl import MonteCarloLocalizer  # noqa: E402
from cga_lessons.relocalization.sampling import KLDConfig  # noqa: E402
from cga_lessons.stereo import (  # noqa: E402
    DetectedEntity,
    DetectionError,
    DetectionMatch,
    TruthEntity,
)
from cga_lessons.viz import future_work as fw  # noqa: E402
from cga_lessons.viz import future_work_arms as fwa  # noqa: E402
from cga_lessons.viz import future_work_stereo as fws  # noqa: E402
from cga_lessons.viz import future_work_tables as tables  # noqa: E402

# The published DH tables, typed in again here (not read from the code under test).
UR5 = dict(d=[0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823], a=[0.0, -0.425, -0.39225, 0.0, 0.0, 0.0],
           alpha=[np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0])  # fmt: skip
PANDA = dict(a=[0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088], d=[0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0],
             alpha=[0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2], flange=0.107)  # fmt: skip


def rot_z(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def rot_x(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def trans(x=0.0, z=0.0):
    T = np.eye(4)
    T[0, 3], T[2, 3] = x, z
    return T


def ur5_frames(q):
    """Origins of the UR5's frames 0..6: T_1 ... T_i, T_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)."""
    T, out = np.eye(4), [np.zeros(3)]
    for qi, d, a, al in zip(q, UR5["d"], UR5["a"], UR5["alpha"]):
        T = T @ rot_z(qi) @ trans(z=d) @ trans(x=a) @ rot_x(al)
        out.append(T[:3, 3])
    return np.array(out), T


def panda_frames(q):
    """Origins along the Panda (Craig): base, then per joint Rx Tx (on its axis) and Rz Tz; then the flange."""
    T, out = np.eye(4), [np.zeros(3)]
    for qi, d, a, al in zip(q, PANDA["d"], PANDA["a"], PANDA["alpha"]):
        T = T @ rot_x(al) @ trans(x=a) @ rot_z(qi)
        out.append(T[:3, 3])
        T = T @ trans(z=d)
        out.append(T[:3, 3])
    T = T @ trans(z=PANDA["flange"])
    out.append(T[:3, 3])
    return np.array(out), T


@pytest.fixture
def rng():
    return np.random.default_rng(20070607)


# --------------------------------------------------------------------------- Monte Carlo localization


@pytest.fixture(scope="module")
def room_filter():
    scene = laser.load_scene("room")
    cfg = MCLConfig(kld=KLDConfig(n_min=100, n_max=1500), hough=False)
    mcl = MonteCarloLocalizer(scene.walls, config=cfg, rng=np.random.default_rng(3))
    truth = np.array([3.0, 2.0, 0.3])
    est = mcl.update(np.zeros(3), laser.simulate_scan(scene, truth, np.random.default_rng(4)))
    return scene, mcl, est, truth


def test_drawn_particles_are_the_localizers_particles(room_filter):
    _, mcl, _, truth = room_filter
    fig, ax = plt.subplots()
    col = fw.draw_particles(ax, mcl.particles, mcl.log_w)
    drawn = np.asarray(col.get_offsets())
    want = mcl.particles[:, :2]
    assert drawn.shape == want.shape
    assert np.array_equal(drawn[np.lexsort(drawn.T)], want[np.lexsort(want.T)])
    log_w = -np.hypot(*(mcl.particles[:, :2] - truth[:2]).T)  # weights of our own: heavier nearer the truth
    col = fw.draw_particles(ax, mcl.particles, log_w)
    drawn = np.asarray(col.get_offsets())
    assert np.allclose(drawn[-1], want[np.argmax(log_w)])  # the heaviest drawn last, on top
    shades = np.asarray(col.get_array())
    assert np.all(np.diff(shades) >= 0) and shades[-1] == pytest.approx(1.0)
    plt.close(fig)


def test_mcl_figure_draws_the_particles_the_estimate_and_its_ellipse(room_filter):
    scene, mcl, est, truth = room_filter
    rows = [[fw.Snapshot("a", mcl.particles, mcl.log_w, est, truth),
             fw.Snapshot("b", mcl.particles, None, est, truth, zoom=0.5)]]  # fmt: skip
    fig = fw.mcl_figure(scene.walls, rows, ["row"])
    for ax in fig.axes[:2]:
        pts = np.asarray(ax.collections[1].get_offsets())  # [0]: the walls
        assert len(pts) == len(mcl.particles)
        ring = [ln for ln in ax.lines if len(ln.get_xdata()) > 10][0]
        xy = np.column_stack([ring.get_xdata(), ring.get_ydata()])
        d = xy - est.pose[:2]
        m = np.einsum("ni,ij,nj->n", d, np.linalg.inv(est.covariance[:2, :2]), d)
        assert np.allclose(m, 9.0, rtol=1e-6)  # the 3-sigma ellipse of the estimate's covariance
    zx, zy = fig.axes[1].get_xlim(), fig.axes[1].get_ylim()
    assert np.allclose([np.mean(zx), np.mean(zy)], est.pose[:2]) and np.isclose(zx[1] - zx[0], 1.0)
    plt.close(fig)


def test_covariance_ellipse_against_the_inverse_covariance(rng):
    A = rng.normal(size=(2, 2))
    C = A @ A.T + 0.1 * np.eye(2)
    e = fw.covariance_ellipse([1.0, -2.0, 0.4], np.pad(C, (0, 1)), n_sigma=2.0, n=50)
    d = e - [1.0, -2.0]
    assert np.allclose(np.einsum("ni,ij,nj->n", d, np.linalg.inv(C), d), 4.0)
    lam, vec = np.linalg.eigh(C)
    assert np.isclose(np.abs(d @ vec[:, 1]).max(), 2.0 * np.sqrt(lam[1]), rtol=1e-2)  # the long half-axis


def test_error_trace_plots_the_errors():
    pe, he = np.array([3.0, 0.05, 0.02, 12.0]), np.array([0.5, 0.01, 0.001, 1.0])
    conv = np.array([False, True, True, True])
    fig = fw.error_trace_figure(pe, he, conv, events=[(3, "kidnapped")])
    a, b = fig.axes
    assert np.allclose(a.lines[0].get_ydata(), pe) and np.allclose(b.lines[0].get_ydata(), np.degrees(he))
    assert len(a.collections[0].get_offsets()) == conv.sum()  # converged updates, filled
    plt.close(fig)


# --------------------------------------------------------------------------- arms


def test_ur5_skeleton_is_the_dh_chain_of_4x4_matrices(rng):
    pts, att = fwa.dh_home_points(UR5_TABLE)
    assert att.tolist() == list(range(7))
    qs = rng.uniform(-np.pi, np.pi, (50, 6))
    drawn = fwa.chain_points(ur5(), qs, pts, att)
    for q, P in zip(qs, drawn):
        frames, T = ur5_frames(q)
        assert np.allclose(P, frames, atol=1e-12)
        assert np.allclose(P[-1], kin.forward_matrix(ur5(), q)[:3, 3], atol=1e-12)


def test_panda_skeleton_is_the_modified_dh_chain(rng):
    pts, att = fwa.dh_home_points(PANDA_TABLE)
    qs = rng.uniform(-np.pi, np.pi, (30, 7))
    drawn = fwa.chain_points(panda(), qs, pts, att)
    for q, P in zip(qs, drawn):
        frames, T = panda_frames(q)
        assert np.allclose(P, frames, atol=1e-12) and np.allclose(P[-1], T[:3, 3], atol=1e-12)


def test_default_points_lie_on_the_moved_axes_and_end_at_the_tool(rng):
    geo = geometer_chains().camera
    q = rng.uniform(-1, 1, 5)
    P = fwa.chain_points(geo, q)
    assert np.allclose(P[-1], kin.forward_matrix(geo, q)[:3, 3])
    segs = fwa.axis_segments(ur5(), np.zeros(6), fwa.chain_points(ur5(), np.zeros(6)))
    frames, _ = ur5_frames(np.zeros(6))
    T = np.eye(4)
    for seg, d, a, al in zip(segs, UR5["d"], UR5["a"], UR5["alpha"]):
        z = T[:3, 2]  # joint i + 1 turns about the z axis of frame i
        mid, u = seg.mean(axis=0), seg[1] - seg[0]
        assert np.isclose(abs(u @ z), np.linalg.norm(u))  # along the axis
        assert np.allclose(np.cross(mid - T[:3, 3], z), 0.0, atol=1e-12)  # through it
        T = T @ rot_z(0.0) @ trans(z=d) @ trans(x=a) @ rot_x(al)


def test_arm_figure_draws_the_picked_configurations_and_the_tool_path():
    q0, q1 = np.zeros(6), np.array([0.5, -1.0, 1.2, -0.3, 0.8, 0.1])
    qs = q0 + np.linspace(0, 1, 11)[:, None] * (q1 - q0)
    fig = fwa.arm_figure(ur5(), qs, *fwa.dh_home_points(UR5_TABLE), n_drawn=3)
    ax = fig.axes[0]
    for line, i in zip(ax.lines[:3], (0, 5, 10)):
        assert np.allclose(np.array(line.get_data_3d()).T, ur5_frames(qs[i])[0], atol=1e-12)
    tool = np.array(ax.lines[3].get_data_3d()).T
    assert np.allclose(tool, [ur5_frames(q)[1][:3, 3] for q in qs], atol=1e-12)
    plt.close(fig)


def test_ik_figure_draws_start_solution_and_errors():
    q0, q1 = np.zeros(7), np.array([0.2, -0.4, 0.1, -2.0, 0.3, 1.8, 0.5])
    target = panda_frames(q1)[1]
    fig = fwa.ik_figure(panda(), q0, q1, target, [1e-1, 1e-5], [1e-2, 1e-6], *fwa.dh_home_points(PANDA_TABLE))
    ax, ax2 = fig.axes
    assert np.allclose(np.array(ax.lines[0].get_data_3d()).T, panda_frames(q0)[0], atol=1e-12)
    assert np.allclose(np.array(ax.lines[1].get_data_3d()).T[-1], target[:3, 3], atol=1e-12)
    assert np.allclose(ax2.lines[0].get_ydata(), [1e-1, 1e-5])
    plt.close(fig)


# --------------------------------------------------------------------------- detected entities


def _cloud(rng):
    """A plane patch (points 0-99), a sphere (100-179) and clutter (180-199), known by construction."""
    plane = np.column_stack([rng.uniform(0, 1, 100), rng.uniform(0, 1, 100), np.zeros(100)])
    u = rng.normal(size=(80, 3))
    sphere = np.array([2.0, 0.5, 0.5]) + 0.3 * u / np.linalg.norm(u, axis=1, keepdims=True)
    X = np.vstack([plane, sphere, rng.uniform(-1, 3, (20, 3))])
    labels = np.r_[np.zeros(100, int), np.ones(80, int), -np.ones(20, int)]
    truth = [
        TruthEntity(
            "plane",
            PlaneParameters(normal=np.array([0, 0, 1.0]), distance=0.0, center=np.array([0.5, 0.5, 0])),
            0.7,
            np.arange(100),
        ),
        TruthEntity("sphere", SphereParameters(center=np.array([2.0, 0.5, 0.5]), radius=0.3), 0.3, np.arange(100, 180)),
    ]
    ents = [DetectedEntity("sphere", truth[1].params, None, np.arange(100, 180), np.eye(4),
                           ("center_x", "center_y", "center_z", "radius"), 0.001, 1.0),
            DetectedEntity("plane", truth[0].params, None, np.arange(0, 90), np.eye(4),
                           ("normal_x", "normal_y", "normal_z", "distance"), 0.002, 1.0),
            DetectedEntity("plane", truth[0].params, None, np.arange(185, 200), np.eye(4),
                           ("normal_x", "normal_y", "normal_z", "distance"), 0.01, 1.0)]  # fmt: skip
    return X, labels, truth, ents


def test_detections_figure_draws_each_detections_points_in_its_truths_colour(rng):
    X, labels, truth, ents = _cloud(rng)
    fig = fws.detections_figure(X, labels, truth, ents, [(0, 1, {}), (1, 0, {})])
    left, right = fig.axes
    for i, e in enumerate(ents):
        sc = right.collections[i]
        assert np.allclose(np.array(sc._offsets3d).T, X[e.inliers])
        want = fws.PALETTE[{0: 1, 1: 0}[i]] if i < 2 else fws.UNMATCHED
        assert np.allclose(sc.get_facecolor()[0], want)
    assert np.allclose(np.array(left.collections[0]._offsets3d).T, X[labels < 0])  # clutter, grey
    assert "2 planes, 1 sphere " in right.get_title() and "(2 matched" in right.get_title()
    plt.close(fig)


def test_detections_figure_reads_the_matches_of_evaluate(rng):
    X, labels, truth, ents = _cloud(rng)
    matches = [DetectionMatch(0, 1, DetectionError(center=0.0, radius=0.0)),
               DetectionMatch(1, 0, DetectionError(center=0.0, angle=0.0, offset=0.0))]  # fmt: skip
    fig = fws.detections_figure(X, labels, truth, ents, matches)
    assert np.allclose(fig.axes[1].collections[0].get_facecolor()[0], fws.PALETTE[1])
    assert "(2 matched" in fig.axes[1].get_title()
    plt.close(fig)


def test_detections_on_image_paints_the_inliers_pixels(rng):
    img = rng.integers(0, 256, (40, 60, 3)).astype(np.uint8)
    cells = rng.choice(40 * 60, 200, replace=False)  # one point per pixel
    px = np.column_stack([cells % 60, cells // 60]).astype(float)
    _, _, _, ents = _cloud(rng)
    fig = fws.detections_on_image(img, px, ents[:2], step=1)
    shown = np.asarray(fig.axes[0].images[0].get_array())
    for i, e in enumerate(ents[:2]):
        for j in e.inliers[:5]:
            c, r = px[j].astype(int)
            grey = 0.3 + 0.7 * img[r, c].astype(float).mean() / 255.0
            assert np.allclose(shown[r, c], 0.4 * grey + 0.6 * fws.PALETTE[i][:3])
    c, r = px[195].astype(int)  # a clutter point: the grey photo only
    assert np.allclose(shown[r, c], 0.3 + 0.7 * img[r, c].astype(float).mean() / 255.0)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[0].startswith("sphere: 80 pts") and labels[1].startswith("plane: 90 pts")
    plt.close(fig)


def test_depth_noise_is_the_derivative_of_depth_from_disparity():
    f, B, z, sigma = 700.0, 0.12, 1.6, 1.4
    d = f * B / z
    h = 1e-4
    dz = (f * B / (d - h) - f * B / (d + h)) / (2 * h)
    assert np.isclose(fws.depth_noise(z, B, f, sigma), dz * sigma, rtol=1e-6)
    fig = fws.depth_noise_figure({"a": (B, f, (0.8, 1.6)), "b": (0.4, 1200.0, (1.2, 2.8))}, sigma)
    thick = fig.axes[0].lines[1]
    assert np.allclose(thick.get_ydata(), 100 * thick.get_xdata() ** 2 * sigma / (f * B))
    plt.close(fig)


# --------------------------------------------------------------------------- tables


def test_tables_format_the_records(tmp_path):
    mcl = {"logs": {"intel": {"n": 20, "located": {"1": 0.5, "3": 0.9, "10": 1.0}, "wrong": 1, "gross": 0,
                              "particles": 300.0, "later_ms": 7.25, "single": {"1": 0.4, "3": 0.45, "10": 0.5},
                              "seq3": 0.75}}}  # fmt: skip
    text = tables.mcl_table(mcl)
    assert "intel" in text and " 50.0%" in text and "100.0%" in text and "1/0" in text and "75.0%" in text
    stereo = {
        "kinds": ["plane"],
        "sections": [
            {
                "title": "t",
                "rows": [
                    {
                        "label": "x",
                        "kinds": {"plane": {"tp": 3, "detected": 4, "truth": 6}},
                        "points": 10,
                        "seconds": 1.0,
                    }
                ],
            }
        ],
    }
    assert "  0.75   0.50" in tables.stereo_table(stereo, 1)
    path = tmp_path / "r.json"
    path.write_text(json.dumps(mcl))
    assert tables.read_record(path) == mcl and tables.read_record(tmp_path / "none.json") is None
    path.write_text("{ not json")
    with pytest.raises(InvalidInputError, match="read_record"):
        tables.read_record(path)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: fw.draw_particles(plt.subplots()[1], np.zeros((3, 2))), r"draw_particles: particles: expected shape"),
        (lambda: fw.draw_particles(plt.subplots()[1], [[0, 0, np.nan]]), "draw_particles: particles: contains NaN"),
        (lambda: fw.draw_particles(None, np.zeros((3, 3))), "draw_particles: ax: expected a matplotlib axes"),
        (lambda: fw.covariance_ellipse([0, 0], [[1, 2], [0, 1]]), "covariance_ellipse: cov: not symmetric"),
        (lambda: fw.covariance_ellipse([0, 0], np.eye(2), n_sigma=-1), "covariance_ellipse: n_sigma"),
        (lambda: fw.covariance_ellipse("ab", np.eye(2)), "covariance_ellipse: mean"),
        (lambda: fw.mcl_figure(np.zeros((2, 2)), [[]]), "mcl_figure: map_segments"),
        (lambda: fw.mcl_figure(np.ones((1, 2, 2)), [["x"]]), "mcl_figure: rows"),
        (lambda: fw.error_trace_figure([1.0], [1.0, 2.0], [True]), "error_trace_figure: heading_error"),
        (lambda: fwa.chain_points("arm", np.zeros(6)), "chain_points: chain"),
        (lambda: fwa.chain_points(ur5(), np.zeros(5)), r"chain_points: q: expected shape \(6,\) or \(N, 6\)"),
        (lambda: fwa.chain_points(ur5(), np.zeros(6), np.zeros((2, 3)), [0, 9]), "chain_points: attached"),
        (lambda: fwa.dh_home_points({"d": [1]}), "dh_home_points: p"),
        (lambda: fwa.arm_figure(ur5(), np.zeros((4, 6)), n_drawn=9), "arm_figure: n_drawn"),
        (lambda: fwa.draw_frame(plt.figure().add_subplot(projection="3d"), np.eye(3)), "draw_frame: H"),
        (lambda: fwa.draw_frame(None, np.eye(4)), "draw_frame: ax: expected a matplotlib 3D axis"),
        (lambda: fws.depth_noise(-1.0, 0.1, 700.0), "depth_noise: z"),
        (lambda: fws.depth_noise(1.0, 0.0, 700.0), "depth_noise: baseline"),
        (lambda: fws.depth_noise_figure({"a": (0.1, 700.0, (2.0, 1.0))}), "depth_noise_figure"),
        (lambda: fws.detections_figure(np.zeros((3, 3)), [0, 0, 5], [], []), "detections_figure: labels"),
        (lambda: fws.detections_on_image(np.zeros((4, 4)), np.zeros((1, 2)), []), "detections_on_image: image"),
        (lambda: tables.mcl_table({"nothing": 1}), "mcl_table: record: missing"),
        (lambda: tables.stereo_table({"sections": [], "kinds": []}, 1), "stereo_table: section"),
    ],
)
def test_bad_input_raises_naming_function_and_argument(call, match):
    with pytest.raises(InvalidInputError, match=match):
        call()
    plt.close("all")
