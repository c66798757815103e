"""The meshcat server of the 3D viewer: loopback only, ephemeral ports, and it dies with its parent.

meshcat 0.3.2's own ``Visualizer()`` starts ``python -m meshcat.servers.zmqserver``
in a new session; that server's web (tornado) socket listens on *every*
interface, and when a Jupyter kernel is killed (as ``pytest --nbval`` does with
SIGKILL to the kernel's process group) meshcat's ``atexit`` hook never runs, so
the server lives on as an orphan holding its ports.  This module starts the
same bridge class differently:

* both sockets are bound to ``127.0.0.1`` on free ephemeral ports (the web
  socket through ``tornado.netutil.bind_sockets(0, "127.0.0.1")``, the zmq
  socket through ``tcp://127.0.0.1:*``), never on 0.0.0.0 and never on the
  fixed ports 6000/7000;
* the server stays in its parent's process group (so a signal to the kernel's
  group reaches it too) but ignores SIGINT (so interrupting a cell does not
  kill it);
* the server watches its parent: it exits when ``os.getppid()`` changes
  (parent gone, polled every 0.2 s) and, on Linux, asks the kernel for SIGTERM
  on parent death (``prctl(PR_SET_PDEATHSIG)``);
* the parent ends it from :func:`close_viewer`, a context manager, a
  ``weakref.finalize`` on the window and an ``atexit`` hook.

Scene upload and the offline HTML export are :mod:`cga_lessons.viz.meshcat_scene`.
"""

from __future__ import annotations

import atexit
import os
import select
import signal
import subprocess
import sys
import tempfile
import threading
import time
import warnings
import weakref

import zmq

from cga_lessons.checks import fail, instance, real
from cga_lessons.paths import PROJECT_ROOT

with warnings.catch_warnings():  # meshcat 0.3.2 imports a pyzmq module that warns it is deprecated; harmless here
    warnings.filterwarnings("ignore", message="zmq.eventloop.ioloop is deprecated", category=DeprecationWarning)
    from meshcat import Visualizer
    from meshcat.visualizer import ViewerWindow

__all__ = ["LOOPBACK", "Viewer", "ViewerError", "open_viewer", "close_viewer"]

LOOPBACK = "127.0.0.1"
_LIVE: dict[int, subprocess.Popen] = {}  # pid -> server process started by this interpreter
_LIVE_LOCK = threading.Lock()
_OWNER_PID = os.getpid()  # a forked copy of this interpreter must not stop its parent's servers


class ViewerError(RuntimeError):
    """The meshcat server did not start, did not answer in time, or the viewer was closed."""


# ====================================================================== server side (child process)
def _watch_parent(parent_pid: int, use_pdeathsig: bool):
    """In the server: exit as soon as the parent process is gone."""
    if use_pdeathsig and sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):
            pass  # the polling watchdog below still works
    if os.getppid() != parent_pid:  # parent died before prctl took effect
        os._exit(0)

    def poll():
        while True:
            time.sleep(0.2)
            if os.getppid() != parent_pid:
                os._exit(0)

    threading.Thread(target=poll, name="parent-watchdog", daemon=True).start()


def _serve(parent_pid: int, use_pdeathsig: bool):
    """Run meshcat's zmq <-> websocket bridge with both sockets on loopback; print the two URLs."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a cell interrupt signals the whole group: not for us
    signal.signal(signal.SIGTERM, lambda *_: os._exit(0))
    _watch_parent(parent_pid, use_pdeathsig)

    import tornado.httpserver
    import tornado.ioloop
    import tornado.netutil
    from meshcat.servers.tree import SceneTree
    from meshcat.servers.zmqserver import ZMQWebSocketBridge

    class LoopbackBridge(ZMQWebSocketBridge):
        # meshcat's own __init__ calls app.listen(port) with no address (= all interfaces); this one binds
        # the same application and zmq socket to loopback on ephemeral ports.
        def __init__(self):  # noqa: D401 - deliberately not calling super().__init__
            self.host = LOOPBACK
            self.websocket_pool = set()
            self.app = self.make_app()
            self.ioloop = tornado.ioloop.IOLoop.current()
            self.zmq_socket, self.zmq_stream, _ = self.setup_zmq(f"tcp://{LOOPBACK}:*")
            self.zmq_url = self.zmq_socket.getsockopt(zmq.LAST_ENDPOINT).decode()
            sockets = tornado.netutil.bind_sockets(0, address=LOOPBACK)
            tornado.httpserver.HTTPServer(self.app).add_sockets(sockets)
            self.fileserver_port = sockets[0].getsockname()[1]
            self.web_url = f"http://{LOOPBACK}:{self.fileserver_port}/static/"
            self.tree = SceneTree()

    bridge = LoopbackBridge()
    sys.stdout.write(f"zmq_url={bridge.zmq_url}\nweb_url={bridge.web_url}\n")
    sys.stdout.flush()
    devnull = os.open(os.devnull, os.O_WRONLY)  # nobody reads our stdout from now on: never block on it
    os.dup2(devnull, 1)
    bridge.run()


# ====================================================================== client side
def _package_root() -> str:
    """The folder that holds the package (put on the server's ``PYTHONPATH``)."""
    return str(PROJECT_ROOT)


def _stop_process(proc: subprocess.Popen, timeout: float = 5.0):
    """Terminate, then kill, one server process; idempotent."""
    if os.getpid() != _OWNER_PID:
        return
    with _LIVE_LOCK:
        _LIVE.pop(proc.pid, None)
    if proc.poll() is None:
        try:
            proc.terminate()
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout)
        except ProcessLookupError:
            pass
    if proc.stdout is not None:
        proc.stdout.close()


def _stop_all():
    with _LIVE_LOCK:
        procs = list(_LIVE.values())
    for proc in procs:
        _stop_process(proc)


atexit.register(_stop_all)


def _read_handshake(proc: subprocess.Popen, timeout: float) -> dict:
    """Read the ``key=value`` URL lines the server prints at start-up, with a deadline."""
    fd = proc.stdout.fileno()
    buf, deadline = b"", time.monotonic() + timeout
    while buf.count(b"\n") < 2:
        left = deadline - time.monotonic()
        if left <= 0:
            raise ViewerError(f"open_viewer: the meshcat server did not report its URLs within {timeout} s")
        ready, _, _ = select.select([fd], [], [], min(left, 0.5))
        if ready:
            chunk = os.read(fd, 4096)
            if not chunk:
                break
            buf += chunk
        elif proc.poll() is not None:
            break
    lines = dict(line.split("=", 1) for line in buf.decode().splitlines() if "=" in line)
    if "zmq_url" not in lines or "web_url" not in lines:
        raise ViewerError("open_viewer: the meshcat server exited before reporting its URLs")
    return lines


def _start_server(timeout: float):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (_package_root(), env.get("PYTHONPATH")) if p)
    pdeathsig = threading.current_thread() is threading.main_thread()  # the signal follows the forking *thread*
    args = [sys.executable, "-u", "-m", "cga_lessons.viz.meshcat_server", "--serve", "--parent-pid", str(os.getpid())]
    if pdeathsig:
        args.append("--pdeathsig")
    with tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=err, env=env)
        with _LIVE_LOCK:
            _LIVE[proc.pid] = proc
        try:
            urls = _read_handshake(proc, timeout)
        except ViewerError as exc:
            _stop_process(proc)
            err.seek(0)
            detail = err.read().decode(errors="replace").strip()[-2000:]
            raise ViewerError(f"{exc}; server stderr:\n{detail}") from None
    return proc, urls["zmq_url"], urls["web_url"]


class _LoopbackWindow(ViewerWindow):
    """meshcat's ViewerWindow for a server this module started (no banner print, timeouts, close())."""

    def __init__(self, proc, zmq_url, web_url, timeout):
        self.server_proc, self.zmq_url, self.web_url = proc, zmq_url, web_url
        self._timeout_ms = int(timeout * 1000)
        self._finalizer = weakref.finalize(self, _stop_process, proc)
        self.connect_zmq()

    def connect_zmq(self):
        super().connect_zmq()
        self.zmq_socket.setsockopt(zmq.RCVTIMEO, self._timeout_ms)  # a dead server raises, never hangs
        self.zmq_socket.setsockopt(zmq.SNDTIMEO, self._timeout_ms)
        self.zmq_socket.setsockopt(zmq.LINGER, 0)

    def _guarded(self, what, call, *args):
        if not self._finalizer.alive:
            raise ViewerError(f"{what}: this viewer has been closed; open a new one with open_viewer()")
        try:
            return call(*args)
        except zmq.Again:
            self.close()  # a REQ socket that missed its reply is unusable
            raise ViewerError(
                f"{what}: the meshcat server (pid {self.server_proc.pid}) did not answer within "
                f"{self._timeout_ms / 1000} s; the viewer was closed"
            ) from None

    def send(self, command):
        return self._guarded("show", super().send, command)

    def get_scene(self):
        return self._guarded("static_html", super().get_scene)

    def close(self):
        self.zmq_socket.close(linger=0)
        self._finalizer()

    def __repr__(self):
        state = "running" if self.server_proc.poll() is None else "stopped"
        return f"<meshcat server pid {self.server_proc.pid} {state} at {self.web_url}>"


class Viewer(Visualizer):
    """A meshcat ``Visualizer`` whose server this module owns; ``with open_viewer() as vis:`` closes it."""

    __slots__ = ()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        close_viewer(self)
        return False

    def close(self):
        close_viewer(self)

    def __repr__(self):  # no pid/port: stable in stored notebook outputs (vis.url() and vis.window have them)
        alive = self.window.server_proc.poll() is None and self.window._finalizer.alive
        return f"<meshcat viewer on 127.0.0.1 ({'running' if alive else 'closed'}) at {self.path.lower()}>"


def open_viewer(*, start_timeout: float = 30.0, reply_timeout: float = 10.0):
    """Start a meshcat server on loopback and return a connected visualizer.

    The web page is at ``vis.url()`` (``http://127.0.0.1:<free port>/static/``); in a trusted notebook
    ``vis.jupyter_cell()`` embeds it.  The server ends with :func:`close_viewer`, at the end of a
    ``with open_viewer() as vis:`` block, when ``vis`` is garbage-collected, at interpreter exit, and
    (watchdog) within a fraction of a second of its parent process dying, even by SIGKILL.

    Parameters
    ----------
    start_timeout : float
        Seconds to wait for the server to start.
    reply_timeout : float
        Seconds to wait for each reply of the server afterwards; past it, :class:`ViewerError`.

    Returns
    -------
    Viewer
        A ``meshcat.Visualizer`` subclass; ``vis.window.server_proc`` is the server's ``Popen``.
    """
    for name, value in (("start_timeout", start_timeout), ("reply_timeout", reply_timeout)):
        real(value, "open_viewer", name, low=0.0, strict_low=True, high=86400.0)
    proc, zmq_url, web_url = _start_server(start_timeout)
    try:
        window = _LoopbackWindow(proc, zmq_url, web_url, reply_timeout)
    except Exception:
        _stop_process(proc)
        raise
    return Viewer(window=window)


def close_viewer(vis) -> None:
    """Stop the viewer's server (if this module started it) and close its socket; safe to call twice."""
    window = getattr(instance(vis, "close_viewer", "vis", Visualizer, "a meshcat Visualizer"), "window", None)
    if window is None:
        raise fail("close_viewer", "vis", "this Visualizer has no window to close")
    if hasattr(window, "_finalizer"):
        window.close()
        return
    proc = getattr(window, "server_proc", None)  # a plain meshcat.Visualizer(): end its server too
    if proc is not None:
        _stop_process(proc)
    sock = getattr(window, "zmq_socket", None)
    if sock is not None:
        sock.close(linger=0)


def _main(argv=None):
    import argparse

    parser = argparse.ArgumentParser(description="cga-lessons meshcat server (loopback only; exits with its parent)")
    parser.add_argument("--serve", action="store_true", required=True)
    parser.add_argument("--parent-pid", type=int, required=True)
    parser.add_argument("--pdeathsig", action="store_true")
    args = parser.parse_args(argv)
    _serve(args.parent_pid, args.pdeathsig)


if __name__ == "__main__":
    _main()
