"""Tests of the 3D scene primitives, their matplotlib drawing, the meshcat viewer and the HTML export.

Viewer tests check the two promises of issue 5 from outside the code under test: the server's listening
sockets are read from /proc (inode of each socket fd of the server's pid, matched against
/proc/<pid>/net/tcp{,6}), and "no process left behind" is checked on the server's pid after its parent (a
child Python process, or a Jupyter kernel stopped the way nbval stops it) is gone.  The HTML export is
opened in headless Chromium and the screenshot is inspected for the objects' colours.
"""

import ipaddress
import os
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from headless import require_chromium, run_chromium

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError  # noqa: E402
from cga_lessons.viz.meshcat_scene import (  # noqa: E402
    Visualizer,
    export_html,
    scene_html,
    set_camera,
    show,
)
from cga_lessons.viz.meshcat_server import ViewerError, close_viewer, open_viewer  # noqa: E402
from cga_lessons.viz.scene3d import (  # noqa: E402
    Box,
    Cylinder,
    Frame,
    PointCloud,
    Polyline,
    Quad,
    Sphere,
    check_scene,
    scene_bounds,
)
from cga_lessons.viz.scene3d_matplotlib import draw_matplotlib  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
needs_proc = pytest.mark.skipif(not Path("/proc/self/net/tcp").exists(), reason="needs Linux /proc")


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def small_scene():
    pose = np.eye(4)
    pose[:3, :3] = rot_z(0.3)
    pose[:3, 3] = [0.2, 0.1, 0.0]
    return [
        Box("robot/base", (0.0, 0.0, 0.15), (0.5, 0.4, 0.3), rotation=rot_z(0.4), color=(0.2, 0.4, 0.8)),
        Sphere("objects/ball", (1.0, 0.5, 0.3), 0.15, (0.9, 0.1, 0.1)),
        Quad("walls/0", [[2, -1, 0], [2, 1, 0], [2, 1, 1], [2, -1, 1]], (0.7, 0.7, 0.6), opacity=0.6),
        Cylinder("objects/post", (1.5, -0.5, 0.0), (1.5, -0.5, 1.0), 0.05, (0.3, 0.3, 0.3)),
        Polyline("robot/path", [[0, 0, 0], [1, 0, 0], [1, 1, 0]], (0.0, 0.0, 0.0)),
        PointCloud("laser/points", np.random.default_rng(0).uniform(0, 1, (40, 3)), (0.1, 0.6, 0.2)),
        Frame("robot/frame", pose),
    ]


# ============================================================ primitives: validation and geometry
@pytest.mark.parametrize(
    "make, error, words",
    [
        (lambda: Box("robot base", (0, 0, 0), (1, 1, 1)), InvalidInputError, "name"),
        (lambda: Box("robot//base", (0, 0, 0), (1, 1, 1)), InvalidInputError, "name"),
        (lambda: Box("/robot", (0, 0, 0), (1, 1, 1)), InvalidInputError, "name"),
        (lambda: Box("b", (0, 0, np.nan), (1, 1, 1)), InvalidInputError, "center"),
        (lambda: Box("b", (0, 0), (1, 1, 1)), InvalidInputError, "shape"),
        (lambda: Box("b", (0, 0, 0), (1, 0, 1)), DegenerateGeometryError, "size"),
        (lambda: Box("b", (0, 0, 0), (1, 1, 1), rotation=2 * np.eye(3)), InvalidInputError, "rotation"),
        (lambda: Box("b", (0, 0, 0), (1, 1, 1), rotation=np.diag([1.0, 1, -1])), InvalidInputError, "rotation"),
        (lambda: Box("b", (0, 0, 0), (1, 1, 1), color=(255, 0, 0)), InvalidInputError, "[0, 1]"),
        (lambda: Box("b", (0, 0, 0), (1, 1, 1), opacity=1.5), InvalidInputError, "opacity"),
        (lambda: Sphere("s", (0, 0, 0), 0.0, (1, 0, 0)), DegenerateGeometryError, "radius"),
        (lambda: Sphere("s", (0, 0, 0), np.inf, (1, 0, 0)), InvalidInputError, "radius"),
        (lambda: Quad("q", np.zeros((3, 3)), (1, 0, 0)), InvalidInputError, "(4, 3)"),
        (lambda: Quad("q", [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]], (1, 0, 0)), DegenerateGeometryError, "area"),
        (lambda: Cylinder("c", (1, 1, 1), (1, 1, 1), 0.1, (1, 0, 0)), DegenerateGeometryError, "coincide"),
        (lambda: Polyline("p", [[0, 0, 0]], (0, 0, 0)), InvalidInputError, "at least 2"),
        (lambda: PointCloud("p", np.zeros((0, 3)), (0, 0, 0)), InvalidInputError, "at least one"),
        (lambda: PointCloud("p", [[0, 0, np.nan]], (0, 0, 0)), InvalidInputError, "NaN"),
        (lambda: Frame("f", np.eye(3)), InvalidInputError, "(4, 4)"),
        (lambda: Frame("f", np.diag([1.0, 1, 1, 2])), InvalidInputError, "last row"),
    ],
)
def test_primitives_reject_bad_input(make, error, words):
    with pytest.raises(error, match=None) as info:
        make()
    assert words in str(info.value)
    assert isinstance(info.value, ValueError)


def test_primitives_are_frozen_copies():
    centre = np.array([1.0, 2.0, 3.0])
    b = Box("b", centre, (1, 1, 1))
    centre[0] = 99.0
    assert b.center[0] == 1.0
    with pytest.raises(ValueError):
        b.center[1] = 5.0  # read-only array
    with pytest.raises(AttributeError):
        b.name = "other"


def test_check_scene_flattens_and_rejects_duplicates_and_strangers():
    a, b = Sphere("a", (0, 0, 0), 1, (1, 0, 0)), Sphere("g/b", (0, 0, 0), 1, (1, 0, 0))
    assert check_scene([a, [b]]) == [a, b]
    with pytest.raises(InvalidInputError, match="unique"):
        check_scene([a, Sphere("a", (1, 1, 1), 1, (0, 1, 0))])
    with pytest.raises(InvalidInputError, match="parent path"):
        check_scene([Sphere("g", (0, 0, 0), 1, (1, 0, 0)), b])
    with pytest.raises(InvalidInputError, match="got str"):
        check_scene([a, "ball"])


def test_box_corners_match_homogeneous_transform():
    R = rot_z(0.7) @ rot_x(-0.4)
    c, size = np.array([0.3, -1.0, 2.0]), np.array([0.4, 1.2, 0.8])
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, c
    local = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * size / 2
    want = (T @ np.c_[local, np.ones(8)].T).T[:, :3]
    got = Box("b", c, size, rotation=R).corners()
    # same set of points (order is an implementation detail)
    d = np.linalg.norm(got[:, None] - want[None], axis=2)
    assert np.allclose(d.min(axis=1), 0, atol=1e-12) and np.allclose(d.min(axis=0), 0, atol=1e-12)


def test_cylinder_rotation_and_frame_axes():
    rng = np.random.default_rng(1)
    for _ in range(20):
        a, b = rng.normal(size=3), rng.normal(size=3)
        cyl = Cylinder("c", a, b, 0.1, (0, 0, 0))
        R = cyl.axis_rotation()
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and np.isclose(np.linalg.det(R), 1.0)
        assert np.allclose(R[:, 2] * cyl.length, b - a, atol=1e-12)
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = rot_z(np.pi / 2), [1.0, 2.0, 3.0]
    axes = Frame("f", pose, scale=0.5).axes()
    assert np.allclose(axes[:, 0], [1, 2, 3])
    assert np.allclose(axes[:, 1], [[1, 2.5, 3], [0.5, 2, 3], [1, 2, 3.5]], atol=1e-12)


def test_scene_bounds_cover_every_shape():
    lo, hi = scene_bounds(small_scene())
    # the wall reaches x = 2 and z = 1, the wall's y-span is +-1, the ball's top is 0.45
    assert np.allclose(hi, [2.0, 1.0, 1.0]) and lo[0] < -0.25 and np.isclose(lo[1], -1.0) and lo[2] == 0.0


def test_draw_matplotlib_equal_aspect_and_one_artist_per_primitive():
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    n_before = len(ax.collections) + len(ax.lines)
    prims = small_scene()
    draw_matplotlib(ax, prims)
    spans = [np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())]
    assert np.allclose(spans, spans[0])
    assert np.allclose(ax.get_box_aspect() / ax.get_box_aspect()[0], 1.0)
    # box, quad, sphere, cylinder, points -> 5 collections; polyline 1 line + frame 3 lines
    assert len(ax.collections) + len(ax.lines) - n_before == 5 + 4
    lo, hi = scene_bounds(prims)
    assert spans[0] >= np.max(hi - lo)
    for lim, a, b in zip((ax.get_xlim(), ax.get_ylim(), ax.get_zlim()), lo, hi):
        assert lim[0] <= a and lim[1] >= b
    with pytest.raises(InvalidInputError, match="3D axis"):
        draw_matplotlib(fig.add_subplot(2, 2, 4), prims)
    plt.close(fig)


# ============================================================ meshcat commands (recorded, no server)
class Recorder:
    """A stand-in meshcat window that keeps every lowered command (test-side, independent of the module)."""

    def __init__(self):
        self.commands = []

    def send(self, command):
        self.commands.append(command.lower())


def _by_path(commands, kind):
    return {c["path"]: c for c in commands if c["type"] == kind}


def _matrix(cmd):
    return np.array(cmd["matrix"]).reshape(4, 4).T  # meshcat sends column-major


def test_show_sends_geometry_at_one_to_one_scale():
    vis = Visualizer(window=Recorder())
    prims = small_scene()
    show(vis, prims)
    objs, poses = _by_path(vis.window.commands, "set_object"), _by_path(vis.window.commands, "set_transform")
    assert set(objs) == {"/meshcat/" + p.name for p in prims} == set(poses)
    box, ball, wall, post, path, cloud, frame = prims
    geom = {k: v["object"]["geometries"][0] for k, v in objs.items()}
    # box: its size, placed by [R | c]; the local corners land on the corners from rot_z
    g = geom["/meshcat/robot/base"]
    assert g["type"] == "BoxGeometry" and np.allclose([g["width"], g["height"], g["depth"]], [0.5, 0.4, 0.3])
    T = _matrix(poses["/meshcat/robot/base"])
    assert np.allclose(T[:3, :3], rot_z(0.4)) and np.allclose(T[:3, 3], [0, 0, 0.15])
    # sphere radius and centre
    assert np.isclose(geom["/meshcat/objects/ball"]["radius"], 0.15)
    assert np.allclose(_matrix(poses["/meshcat/objects/ball"])[:3, 3], [1.0, 0.5, 0.3])
    # cylinder: three.js's axis is local y, centred: (0, +-h/2, 0) must land on end / start
    g, T = geom["/meshcat/objects/post"], _matrix(poses["/meshcat/objects/post"])
    h = g["height"]
    assert np.isclose(h, 1.0) and np.isclose(g["radiusTop"], 0.05)
    assert np.allclose(T @ [0, h / 2, 0, 1], [1.5, -0.5, 1.0, 1])
    assert np.allclose(T @ [0, -h / 2, 0, 1], [1.5, -0.5, 0.0, 1])
    assert np.isclose(np.linalg.det(T[:3, :3]), 1.0)
    # frame: the pose itself
    assert np.allclose(_matrix(poses["/meshcat/robot/frame"]), frame.pose)
    # materials: colour as 0xRRGGBB, transparency when opacity < 1
    assert objs["/meshcat/robot/base"]["object"]["materials"][0]["color"] == 0x3366CC  # (0.2, 0.4, 0.8) * 255
    mat = objs["/meshcat/walls/0"]["object"]["materials"][0]
    assert mat["transparent"] and np.isclose(mat["opacity"], 0.6)
    assert not objs["/meshcat/objects/ball"]["object"]["materials"][0]["transparent"]
    with pytest.raises(InvalidInputError):
        show(vis, [box, "not a primitive"])


def test_scene_html_is_offline_and_complete():
    prims = small_scene()
    html = scene_html(prims)
    assert html.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in html
    # self-contained: no external script/style/network URL in the page
    assert "<script src" not in html.lower() and "<link" not in html.lower()
    own = html.rsplit("<script>", 1)[1]  # the page's own script after meshcat's library
    assert "connect(" not in own and "http" not in own and "fetch(" not in own
    # one embedded command per object and per pose, plus the two camera commands
    assert html.count('\nrun("') == 2 * len(prims) + 2
    with pytest.raises(InvalidInputError, match="empty"):
        scene_html([])


def test_export_html_refuses_to_overwrite(tmp_path):
    target = tmp_path / "scene.html"
    target.write_text("keep me")
    with pytest.raises(InvalidInputError, match=r"export_html: path: .* exists \(pass overwrite=True"):
        export_html(small_scene(), target)
    assert target.read_text() == "keep me"
    out = export_html(small_scene(), target, overwrite=True)
    assert out == target and "MeshCat.Viewer" in target.read_text()
    target.write_text("keep me")
    assert export_html(small_scene(), target, force=True) == target  # the older name of overwrite
    assert "MeshCat.Viewer" in target.read_text()
    with pytest.raises(InvalidInputError, match="export_html: path: no such folder"):
        export_html(small_scene(), tmp_path / "missing" / "scene.html")
    with pytest.raises(InvalidInputError, match="export_html: primitives: the scene is empty"):
        export_html([], tmp_path / "empty.html")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.html"]  # no page, no partial file left


def test_export_html_leaves_no_partial_file(tmp_path, monkeypatch):
    from cga_lessons import files

    def fail_midway(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(files.os, "fsync", fail_midway)
    with pytest.raises(OSError, match="disk full"):
        export_html(small_scene(), tmp_path / "scene.html")
    assert list(tmp_path.iterdir()) == []


# ============================================================ live server: loopback only, no orphans
def _socket_inodes(pid):
    out = set()
    for fd in Path(f"/proc/{pid}/fd").iterdir():
        try:
            target = os.readlink(fd)
        except OSError:
            continue
        if target.startswith("socket:["):
            out.add(target[8:-1])
    return out


def _decode_addr(hexaddr):
    ip, port = hexaddr.split(":")
    raw = bytes.fromhex(ip)
    # /proc/net/tcp{,6} print each 32-bit word in host (little-endian) byte order
    raw = b"".join(raw[i : i + 4][::-1] for i in range(0, len(raw), 4))
    return ipaddress.ip_address(raw), int(port, 16)


def listening_sockets(pid):
    """(address, port) of every TCP socket in LISTEN state held by process ``pid``."""
    inodes, found = _socket_inodes(pid), []
    for table in ("tcp", "tcp6"):
        path = Path(f"/proc/{pid}/net/{table}")
        if not path.exists():
            continue
        for line in path.read_text().splitlines()[1:]:
            cols = line.split()
            if cols[3] == "0A" and cols[9] in inodes:  # 0A = TCP_LISTEN
                found.append(_decode_addr(cols[1]))
    return found


def process_gone(pid, timeout=8.0):
    """True once ``pid`` no longer runs (gone, or a zombie nobody reaped yet)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except (FileNotFoundError, ProcessLookupError):
            return True
        if stat.rsplit(")", 1)[1].split()[0] in ("Z", "X"):
            return True
        time.sleep(0.05)
    return False


def _port_listening(port):
    for table in ("tcp", "tcp6"):
        path = Path(f"/proc/self/net/{table}")
        for line in path.read_text().splitlines()[1:] if path.exists() else []:
            cols = line.split()
            if cols[3] == "0A" and _decode_addr(cols[1])[1] == port:
                return True
    return False


def port_is_free(port, timeout=5.0):
    """No socket of this network namespace listens on ``port`` (any address), per /proc/net/tcp{,6}.

    Waits up to ``timeout``: a dying multi-threaded process shows as a zombie before its last thread
    has closed its files.
    """
    deadline = time.monotonic() + timeout
    while _port_listening(port):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


@needs_proc
def test_socket_inspector_sees_a_wildcard_listener():
    """Negative control for the next test: the /proc reader must flag a socket bound to 0.0.0.0."""
    with socket.socket() as s:
        s.bind(("0.0.0.0", 0))
        s.listen()
        port = s.getsockname()[1]
        found = dict((p, a) for a, p in listening_sockets(os.getpid()))
    assert port in found and not found[port].is_loopback


@needs_proc
def test_viewer_listens_on_loopback_only_and_stops():
    with open_viewer() as vis:
        proc = vis.window.server_proc
        socks = listening_sockets(proc.pid)
        web_port = int(vis.url().rsplit(":", 1)[1].split("/")[0])
        zmq_port = int(vis.window.zmq_url.rsplit(":", 1)[1])
        assert {web_port, zmq_port} <= {p for _, p in socks}
        assert socks and all(addr.is_loopback for addr, _ in socks), socks
        assert 7000 not in (web_port, zmq_port) or not port_is_free(7000)  # picked free ports, not fixed ones
        with urllib.request.urlopen(vis.url(), timeout=10) as page:
            assert page.status == 200 and b"meshcat" in page.read().lower()
        prims = small_scene()
        show(vis, prims)
        html = vis.static_html()  # the server's own copy of the scene
        assert html.count("data:application/octet-binary;base64,") == 2 * len(prims)
    assert proc.poll() is not None and process_gone(proc.pid)
    assert repr(vis) == "<meshcat viewer on 127.0.0.1 (closed) at /meshcat>"  # stable for nbval
    assert port_is_free(web_port) and port_is_free(zmq_port)
    close_viewer(vis)  # idempotent


def test_closed_or_dead_viewer_raises_instead_of_hanging():
    vis = open_viewer(reply_timeout=1.0)
    proc = vis.window.server_proc
    show(vis, [Sphere("a", (0, 0, 0), 1.0, (1, 0, 0))])
    proc.kill()  # the server dies behind the viewer's back
    proc.wait(10)
    t0 = time.monotonic()
    with pytest.raises(ViewerError, match="did not answer"):
        show(vis, [Sphere("b", (0, 0, 0), 1.0, (1, 0, 0))])
    assert time.monotonic() - t0 < 10
    with pytest.raises(ViewerError, match="closed"):
        vis.static_html()
    close_viewer(vis)
    with pytest.raises(InvalidInputError, match="open_viewer: reply_timeout"):
        open_viewer(reply_timeout=0)


CHILD = """
import sys, threading, time
from cga_lessons.viz.meshcat_server import open_viewer
box = {}
def start():
    box["vis"] = open_viewer()
if sys.argv[1] == "thread":  # started off the main thread: no PDEATHSIG, only the watchdog
    t = threading.Thread(target=start); t.start(); t.join()
else:
    start()
vis = box["vis"]
print(vis.window.server_proc.pid, vis.url().rsplit(":", 1)[1].split("/")[0], flush=True)
time.sleep(120)
"""


@needs_proc
def test_server_dies_when_its_parent_is_killed():
    """SIGKILL the parent alone (no atexit, no finalizer): PDEATHSIG or, off the main thread, the watchdog."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    children = {
        where: subprocess.Popen(
            [sys.executable, "-c", CHILD, where], stdout=subprocess.PIPE, env=env, cwd=ROOT, start_new_session=True
        )
        for where in ("main", "thread")  # both at once: the test waits for one start-up, not two
    }
    try:
        servers = {}
        for where, child in children.items():
            line = child.stdout.readline().decode().split()
            assert len(line) == 2, f"{where}: child did not start a viewer (exit {child.poll()})"
            servers[where] = int(line[0]), int(line[1])
            assert not process_gone(servers[where][0], timeout=0.2)
        for child in children.values():
            child.kill()
            child.wait(10)
        for where, (server_pid, web_port) in servers.items():
            assert process_gone(server_pid), f"{where}: meshcat server outlived its parent"
            assert port_is_free(web_port), f"{where}: port {web_port} still listening"
    finally:
        for child in children.values():
            if child.poll() is None:
                child.kill()
                child.wait(10)
            child.stdout.close()


@needs_proc
def test_server_dies_with_a_jupyter_kernel_stopped_like_nbval():
    jupyter_client = pytest.importorskip("jupyter_client")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    km = jupyter_client.KernelManager(kernel_name="python3")
    km.start_kernel(cwd=str(ROOT), env=env)
    kc = km.client()
    kc.start_channels()
    try:
        kc.wait_for_ready(timeout=60)
        out = []
        code = "from cga_lessons.viz.meshcat_server import open_viewer\nvis = open_viewer()\n"
        code += "print(vis.window.server_proc.pid, vis.url().rsplit(':', 1)[1].split('/')[0])"
        reply = kc.execute_interactive(code, timeout=60, output_hook=lambda m: out.append(m))
        assert reply["content"]["status"] == "ok", reply["content"]
        text = "".join(m["content"].get("text", "") for m in out if m["msg_type"] == "stream")
        server_pid, web_port = map(int, text.split())
        assert listening_sockets(server_pid) and not process_gone(server_pid, timeout=0.2)
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)  # what nbval's RunningKernel.stop() does
    assert process_gone(server_pid), "meshcat server outlived the Jupyter kernel"
    assert port_is_free(web_port)


# ============================================================ HTML export opened in headless Chromium
def chromium_screenshot(url, png_path, size=(640, 480), timeout=60):
    code, _, err = run_chromium(url, screenshot=png_path, size=size, timeout=timeout)
    return code, err


@pytest.mark.parametrize("source", ["export", "live"])
def test_scene_draws_in_headless_chromium(tmp_path, source):
    """The exported file (offline) and the live viewer page (websocket to our loopback server) both draw."""
    from PIL import Image

    require_chromium()
    # a red ball on the viewer's left and a green box on its right (camera looks from +x, -y, above)
    prims = [
        Sphere("ball", (0.0, -0.6, 0.3), 0.25, (1.0, 0.0, 0.0)),
        Box("board", (0.0, 0.6, 0.3), (0.4, 0.4, 0.4), color=(0.0, 1.0, 0.0)),
    ]
    png = tmp_path / "scene.png"
    if source == "export":
        page = export_html(prims, tmp_path / "scene.html")
        code, err = chromium_screenshot(page.resolve().as_uri(), png)
    else:
        with open_viewer() as vis:
            show(vis, prims)
            set_camera(vis, *scene_bounds(prims))
            code, err = chromium_screenshot(vis.url(), png)
    assert code == 0 and png.exists(), err[-2000:]
    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    assert img.shape == (480, 640, 3)
    assert img.reshape(-1, 3).std(axis=0).max() > 10, "blank screenshot"
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    red = (r > 120) & (r > 2 * g) & (r > 2 * b)
    green = (g > 120) & (g > 2 * r) & (g > 2 * b)
    # meshcat's background is a blue gradient and its grid grey: neither colour occurs without our objects
    assert red.sum() > 500 and green.sum() > 500, (red.sum(), green.sum())
    x_red, x_green = np.nonzero(red)[1].mean(), np.nonzero(green)[1].mean()
    assert x_red < 320 < x_green, (x_red, x_green)
    if os.environ.get("CGA_KEEP_SCREENSHOT"):
        shutil.copy(png, f"{os.environ['CGA_KEEP_SCREENSHOT']}_{source}.png")
