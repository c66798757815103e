"""The course as a student meets it: the README's JupyterLab command, driven in a real (headless) Chromium.

The lab is started with the README's own course command (``jupyter lab ... --ServerApp.root_dir=.``, run from the
checkout) plus what a test needs: no browser of its own, a free loopback port, a token, and temporary settings,
workspaces, runtime and IPython folders, so nothing of the user's is read or written (autosave is off: the
notebooks on disk are not touched).  Chromium is Debian's, driven over the DevTools protocol on a pipe (no port
of its own, no package to add); every host name but the loopback one fails to resolve in it.

What is checked, from outside the code under test: the lab opens on the first notebook, on the environment's
Python kernel (the kernel's process is read from /proc); the lab's root file browser lists the checkout; in
notebook 05 (opened from the file browser) the cells from the first down to the Hough explorer's widget run with
Shift+Enter without an error, the widget's sliders render, a key press moves the heading slider and the kernel's
explorer turns with it (a new cell prints its heading); the figure inside the widget redraws; no dialog shows,
no kernel dies, no file is saved.

Every wait is bounded; the lab's and Chromium's process groups, and the kernels, are killed whatever happens.
"""

import base64
import fcntl
import html
import json
import os
import re
import secrets
import select
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest
from headless import CHROMIUM, require_chromium

ROOT = Path(__file__).resolve().parent.parent
CHAPTER = "notebooks/05_laser_line_maps.ipynb"
WIDGET_CELL = "hough_explorer.widget()"  # the last cell run: the explorer's sliders

# About 30 s: CGA_LESSONS_SKIP_BROWSER=1 leaves this module out of a local run (never in CI, which requires Chromium).
pytestmark = pytest.mark.skipif(
    bool(os.environ.get("CGA_LESSONS_SKIP_BROWSER")) and not os.environ.get("CGA_LESSONS_REQUIRE_CHROMIUM"),
    reason="CGA_LESSONS_SKIP_BROWSER is set",
)


def course_command(readme: Path = ROOT / "README.md") -> list[str]:
    """The README's command that opens the course in JupyterLab, as an argument list (``jupyter lab ...``).

    The line after a ``<!-- course command -->`` tag, or else the README's line that runs ``jupyter lab`` with
    the checkout as the lab's root; of a ``pip install ... && jupyter lab ...`` line, the ``jupyter lab`` part.
    """
    lines = readme.read_text(encoding="utf-8").splitlines()
    tagged = [i for i, line in enumerate(lines) if line.strip() == "<!-- course command -->"]
    candidates = [lines[i + 1 + k] for i in tagged for k in range(3) if i + 1 + k < len(lines)]
    candidates += [line for line in lines if "jupyter lab" in line and "--ServerApp.root_dir=." in line]
    for line in candidates:
        for part in line.split("&&"):
            argv = shlex.split(part.strip())
            if argv[:2] == ["jupyter", "lab"]:
                return argv
    raise AssertionError("README.md: no course command (a 'jupyter lab ... --ServerApp.root_dir=.' line)")


# ============================================================ processes: started in their own groups, always killed
def _children(pid: int) -> list[int]:
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            out.append(int(stat.parent.name))
    return out


def _descendants(pid: int) -> list[int]:
    found, todo = [], [pid]
    while todo:
        kids = _children(todo.pop())
        found += kids
        todo += kids
    return found


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state not in ("Z", "X")


def _stop(proc: subprocess.Popen, grace: float = 10.0) -> None:
    """SIGTERM the process group of ``proc`` (started with a new session), then SIGKILL it and every descendant
    (the kernels have sessions of their own)."""
    family = _descendants(proc.pid) if Path("/proc").is_dir() else []
    if proc.poll() is None:
        try:
            os.killpg(proc.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        try:
            proc.wait(grace)
        except subprocess.TimeoutExpired:
            pass
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    for pid in family:
        if _alive(pid):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
    proc.wait(10)


# ============================================================ the lab
class Lab:
    """JupyterLab started with the README's course command, on a free loopback port with a token."""

    def __init__(self, tmp: Path):
        self.tmp, self.token = tmp, secrets.token_hex(16)
        for name in ("settings", "workspaces", "runtime", "config", "data", "ipython", "checkpoints"):
            (tmp / name).mkdir()
        # the lab's settings for a test: no autosave (the notebooks stay as they are), no news, no update check
        settings = tmp / "settings" / "@jupyterlab"
        for plugin, values in {
            "docmanager-extension/plugin": {"autosave": False},
            "apputils-extension/notification": {"fetchNews": "false", "checkForUpdates": False},
        }.items():
            path = settings / f"{plugin}.jupyterlab-settings"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(values))
        argv = course_command()
        assert "--ServerApp.root_dir=." in argv and "--ServerApp.ip=127.0.0.1" in argv, argv
        self.readme_argv = argv
        # `jupyter lab` of this environment (the one running the tests), with the README's arguments as they are
        self.argv = [sys.executable, "-m", "jupyter", *argv[1:]] + [
            "--no-browser",
            f"--ServerApp.port={_free_port()}",
            f"--IdentityProvider.token={self.token}",
            f"--LabApp.user_settings_dir={tmp / 'settings'}",
            f"--LabApp.workspaces_dir={tmp / 'workspaces'}",
            f"--FileCheckpoints.checkpoint_dir={tmp / 'checkpoints'}",  # the lab checkpoints what it opens: not here
            "--LabApp.expose_app_in_browser=True",  # window.jupyterapp: the test reads the kernel's state there
        ]
        env = dict(os.environ)
        env.update(
            JUPYTER_CONFIG_DIR=str(tmp / "config"),  # the user's ~/.jupyter is neither read nor written
            JUPYTER_DATA_DIR=str(tmp / "data"),  # nor their kernels and lab extensions in ~/.local/share/jupyter
            JUPYTER_RUNTIME_DIR=str(tmp / "runtime"),
            IPYTHONDIR=str(tmp / "ipython"),  # the kernel's history and profile
            PYTHONUNBUFFERED="1",
        )
        env.pop("JUPYTER_PATH", None)
        self.log_path = tmp / "lab.log"
        self._log = open(self.log_path, "wb")
        self.proc = subprocess.Popen(
            self.argv,
            cwd=ROOT,  # the README's command runs in the checkout
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=self._log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        self.url = None

    def log(self) -> str:
        return self.log_path.read_text(errors="replace")

    def wait_ready(self, timeout: float = 60.0) -> str:
        """The URL the README's command opens in the student's browser (the lab at ``00_start_here.ipynb``), read
        from the page the server writes for its browser; waits until the server answers."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for page in (self.tmp / "runtime").glob("jpserver-file-to-run-*-open.html"):
                found = re.search(r'href="([^"]+)"', page.read_text(errors="replace"))
                if found:
                    self.url = html.unescape(found.group(1))
            if self.url and self.api("/api/status", timeout=2) is not None:
                return self.url
            assert self.proc.poll() is None, f"the lab exited ({self.proc.returncode}):\n{self.log()[-3000:]}"
            time.sleep(0.25)
        raise AssertionError(f"the lab did not start in {timeout:.0f} s:\n{self.log()[-3000:]}")

    @property
    def base(self) -> str:
        return self.url.split("/lab", 1)[0]

    def api(self, path: str, timeout: float = 10.0):
        """GET a REST path of the server (JSON), or None when it does not answer."""
        request = urllib.request.Request(self.base + path, headers={"Authorization": f"token {self.token}"})
        try:
            with _DIRECT.open(request, timeout=timeout) as reply:
                return json.loads(reply.read())
        except (OSError, ValueError):
            return None

    def kernel_processes(self) -> list[list[str]]:
        """Command lines of the kernels the server started (its children running ipykernel)."""
        out = []
        for pid in _descendants(self.proc.pid):
            try:
                cmd = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            args = [c.decode(errors="replace") for c in cmd if c]
            if any("ipykernel" in a for a in args):
                out.append(args)
        return out

    def close(self) -> list[int]:
        """Stop the lab and its kernels; the processes of the lab that are still alive (none, unless it failed)."""
        family = _descendants(self.proc.pid)
        try:
            _stop(self.proc)
        finally:
            self._log.close()
        return [pid for pid in [self.proc.pid, *family] if _alive(pid)]


_DIRECT = urllib.request.build_opener(urllib.request.ProxyHandler({}))  # loopback: never through a proxy


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# ============================================================ Chromium over the DevTools protocol, on a pipe
class Browser:
    """Headless Chromium driven over ``--remote-debugging-pipe`` (fd 3 in, fd 4 out, NUL-separated JSON)."""

    def __init__(self, tmp: Path, size=(1400, 1000)):
        self.profile = tmp / "chromium-profile"
        self.profile.mkdir()
        to_child_r, self._to_child = os.pipe()
        self._from_child, from_child_w = os.pipe()

        def child_fds():  # in the child, before exec: the two pipe ends become fds 3 and 4
            a = fcntl.fcntl(to_child_r, fcntl.F_DUPFD, 10)
            b = fcntl.fcntl(from_child_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-quic",
            "--no-first-run",
            "--no-default-browser-check",
            "--mute-audio",
            "--no-proxy-server",
            "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",  # only the loopback address is reachable
            f"--user-data-dir={self.profile}",
            f"--window-size={size[0]},{size[1]}",
            "--remote-debugging-pipe",
            "about:blank",
        ]
        self.stderr_path = tmp / "chromium.log"
        self._stderr = open(self.stderr_path, "wb")
        self.proc = subprocess.Popen(
            args,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=self._stderr,
            pass_fds=(3, 4),
            preexec_fn=child_fds,
            start_new_session=True,
        )
        os.close(to_child_r)
        os.close(from_child_w)
        self._next_id, self._buffer, self.events = 0, b"", []
        self.session = None
        target = self.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True}, session=False)[
            "sessionId"
        ]
        self.send("Runtime.enable")  # the page's uncaught exceptions, shown when a wait fails
        self.send("Page.enable")  # (Page.addScriptToEvaluateOnNewDocument needs it)
        metrics = {"width": size[0], "height": size[1], "deviceScaleFactor": 1, "mobile": False}
        self.send("Emulation.setDeviceMetricsOverride", metrics)

    # ------------------------------------------------------------ protocol
    def send(self, method, params=None, session=True, timeout=30.0):
        self._next_id += 1
        msg = {"id": self._next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self._to_child, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            for reply in self._read(deadline, method):
                if reply.get("id") == msg["id"]:
                    if "error" in reply:
                        raise AssertionError(f"{method}: {reply['error']}")
                    return reply.get("result", {})
                self.events.append(reply)
                del self.events[:-500]

    def _read(self, deadline, what):
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            assert left > 0, f"chromium did not answer {what} in time"
            ready, _, _ = select.select([self._from_child], [], [], min(left, 1.0))
            if ready:
                chunk = os.read(self._from_child, 1 << 20)
                assert chunk, f"chromium closed its pipe ({self.proc.poll()}):\n{self.stderr()[-2000:]}"
                self._buffer += chunk
        *messages, self._buffer = self._buffer.split(b"\0")
        return [json.loads(m) for m in messages if m]

    def stderr(self) -> str:
        return self.stderr_path.read_text(errors="replace")

    def close(self):
        try:
            try:
                self.send("Browser.close", session=False, timeout=5)
            except (AssertionError, OSError):
                pass
        finally:
            _stop(self.proc, grace=5)
            for fd in (self._to_child, self._from_child):
                try:
                    os.close(fd)
                except OSError:
                    pass
            self._stderr.close()
            shutil.rmtree(self.profile, ignore_errors=True)

    # ------------------------------------------------------------ the page
    def evaluate(self, expression, timeout=30.0, await_promise=False):
        result = self.send(
            "Runtime.evaluate",
            {"expression": expression, "returnByValue": True, "awaitPromise": await_promise},
            timeout=timeout,
        )
        if "exceptionDetails" in result:
            raise AssertionError(f"{expression[:200]}: {result['exceptionDetails'].get('exception', result)}")
        return result["result"].get("value")

    def wait_for(self, expression, what, timeout=30.0, interval=0.2):
        """Poll ``expression`` until it is truthy; returns its value (a failed wait says ``what``, and the page's
        state)."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                raise AssertionError(f"waited {timeout:.0f} s for {what}; {self.describe()}")
            time.sleep(interval)

    def describe(self) -> str:
        errors = [
            e["params"]["exceptionDetails"].get("exception", {}).get("description", "?")[:300]
            for e in self.events
            if e.get("method") == "Runtime.exceptionThrown"
        ]
        try:
            dialogs = self.evaluate("[...document.querySelectorAll('.jp-Dialog')].map(d => d.innerText)")
            tabs = self.evaluate("[...document.querySelectorAll('.lm-TabBar-tabLabel')].map(t => t.innerText)")
        except AssertionError as exc:
            return f"(the page did not answer: {exc})"
        return f"dialogs: {dialogs!r}; tabs: {[t for t in tabs if t]!r}; page errors: {errors[-3:]!r}"

    def screenshot(self, path: Path) -> Path:
        data = self.send("Page.captureScreenshot", {"format": "png"})["data"]
        path.write_bytes(base64.b64decode(data))
        return path

    def navigate(self, url):
        self.send("Page.navigate", {"url": url})

    def center(self, finder: str, what: str, timeout=30.0):
        """Scroll the element ``finder`` (a JS expression) into view; its centre in CSS pixels."""
        js = f"""(() => {{
            const el = {finder};
            if (!el) return null;
            el.scrollIntoView({{block: 'center', inline: 'center'}});
            const r = el.getBoundingClientRect();
            return r.width > 0 && r.height > 0 ? [r.left + r.width / 2, r.top + r.height / 2] : null;
        }})()"""
        return self.wait_for(js, what, timeout=timeout)

    def click(self, finder: str, what: str, count: int = 1, timeout=30.0):
        x, y = self.center(finder, what, timeout)
        self.send("Input.dispatchMouseEvent", {"type": "mouseMoved", "x": x, "y": y})
        for n in range(1, count + 1):
            for kind, buttons in (("mousePressed", 1), ("mouseReleased", 0)):
                event = {"type": kind, "x": x, "y": y, "button": "left", "buttons": buttons, "clickCount": n}
                self.send("Input.dispatchMouseEvent", event)

    KEYS = {"ArrowRight": 39, "ArrowLeft": 37, "Enter": 13, "Escape": 27}

    def key(self, key: str, modifiers: int = 0):
        """Press and release ``key``: a name of :attr:`KEYS` or a letter (modifiers: 1 Alt, 2 Ctrl, 4 Meta, 8 Shift)."""
        if key in self.KEYS:
            code, vk = key, self.KEYS[key]
        else:
            assert len(key) == 1 and key.isalpha(), key
            code, vk = f"Key{key.upper()}", ord(key.upper())
        for kind in ("rawKeyDown", "keyUp"):
            params = {"type": kind, "key": key, "code": code, "windowsVirtualKeyCode": vk, "modifiers": modifiers}
            self.send("Input.dispatchKeyEvent", params)

    def type_text(self, text: str):
        self.send("Input.insertText", {"text": text})


# ============================================================ JavaScript the test reads the lab with
# Run in the page before the lab's own scripts: every dialog the lab shows (kept, even if it went away), and every
# request that would write a file through the server's contents API (the test must leave the notebooks as they are).
WATCH = """(() => {
    window.__cgaDialogs = [];
    window.__cgaWrites = [];
    new MutationObserver(records => {
        for (const r of records) for (const n of r.addedNodes) {
            if (n.nodeType !== 1) continue;
            if (n.classList.contains('jp-Dialog')) window.__cgaDialogs.push(n);
            else if (n.querySelector('.jp-Dialog')) window.__cgaDialogs.push(n.querySelector('.jp-Dialog'));
        }
    }).observe(document, {childList: true, subtree: true});
    const fetch = window.fetch;
    window.fetch = function (input, init) {
        try {
            const url = typeof input === 'string' ? input : (input && input.url) || String(input);
            const method = ((init && init.method) || (input && input.method) || 'GET').toUpperCase();
            if (method !== 'GET' && url.includes('/api/contents')) window.__cgaWrites.push(method + ' ' + url);
        } catch (e) {}
        return fetch.apply(this, arguments);
    };
})();"""
DIALOGS = "window.__cgaDialogs.map(d => (d.innerText || '(no text)').trim().slice(0, 300))"
WRITES = "window.__cgaWrites.slice()"
CURRENT = "window.jupyterapp.shell.currentWidget"
KERNEL_STATUS = f"""(() => {{
    const w = {CURRENT};
    const k = w && w.sessionContext && w.sessionContext.session && w.sessionContext.session.kernel;
    return k ? [w.context.path, k.name, k.status, k.connectionStatus] : null;
}})()"""
OUTPUT_ERRORS = f"""(() => {{
    const out = [];
    for (const cell of ({CURRENT}).content.widgets) {{
        if (cell.model.type !== 'code') continue;
        for (let i = 0; i < cell.model.outputs.length; i++) {{
            const o = cell.model.outputs.get(i).toJSON();
            if (o.output_type === 'error') out.push(o.ename + ': ' + o.evalue);
        }}
    }}
    return out;
}})()"""
FILE_BROWSER_SHOWN = "(f => !!f && f.offsetParent !== null)(document.querySelector('#filebrowser'))"
LISTING = "[...document.querySelectorAll('#filebrowser .jp-DirListing-itemText')].map(e => e.innerText.trim())"
TAB_LABELS = "[...document.querySelectorAll('.lm-TabBar-tab .lm-TabBar-tabLabel')].map(t => t.innerText)"


def cell_index(text: str) -> str:
    """JS: the index of the first cell of the current notebook whose source holds ``text`` (read from the model: the
    notebook may keep cells out of the page until they are scrolled to)."""
    return f"({CURRENT}).content.widgets.findIndex(c => c.model.sharedModel.getSource().includes({json.dumps(text)}))"


def cell_node(index: int) -> str:
    """JS: the page element of cell ``index`` of the current notebook."""
    return f"({CURRENT}).content.widgets[{index}].node"


def slider(cell: int, label: str) -> str:
    """JS: the slider labelled ``label`` in the output of cell ``cell``."""
    sliders = f"[...{cell_node(cell)}.querySelectorAll('.widget-slider')]"
    return f"{sliders}.find(s => s.innerText.includes({json.dumps(label)}))"


def wait_kernel_idle(browser, path, timeout=60.0):
    return browser.wait_for(
        f"(() => {{ const s = {KERNEL_STATUS}; "
        f"return s && s[0] === {json.dumps(path)} && s[2] === 'idle' && s[3] === 'connected' ? s : null; }})()",
        f"an idle kernel for {path}",
        timeout=timeout,
    )


def show_root_folder(browser):
    """Show the file browser (its tab in the left sidebar) at the lab's root (its home crumb)."""
    if not browser.evaluate(FILE_BROWSER_SHOWN):
        browser.click("document.querySelector('.jp-SideBar [data-id=\"filebrowser\"]')", "the file browser's tab")
    browser.click("document.querySelector('#filebrowser .jp-BreadCrumbs-home')", "the file browser's home crumb")


def assert_healthy(lab, browser):
    """No dialog ever shown, no file written, no kernel dead: the lab's view and the server's."""
    assert browser.evaluate(DIALOGS) == [], browser.evaluate(DIALOGS)
    writes = browser.evaluate(WRITES)
    for write in writes:  # nothing saved, made or deleted; the checkpoints of opened files go to the temporary folder
        method, url = write.split(" ", 1)
        found = re.fullmatch(r"/api/contents/(.+)/checkpoints", urllib.parse.urlsplit(url).path)
        assert method == "POST" and found, writes
        checkpoint = Path(urllib.parse.unquote(found.group(1)))
        assert (lab.tmp / "checkpoints" / f"{checkpoint.stem}-checkpoint{checkpoint.suffix}").is_file(), write
    kernels = lab.api("/api/kernels")
    assert kernels and all(k["execution_state"] in ("idle", "busy", "starting") for k in kernels), kernels
    assert len(lab.kernel_processes()) == len(kernels), (lab.kernel_processes(), kernels)


# ============================================================ fixtures: one lab and one browser for the module
@pytest.fixture(scope="module")
def lab_and_browser(tmp_path_factory):
    require_chromium()
    tmp = tmp_path_factory.mktemp("lab")
    lab = browser = None
    left = []
    try:
        lab = Lab(tmp)
        url = lab.wait_ready()
        browser = Browser(tmp)
        browser.send("Page.addScriptToEvaluateOnNewDocument", {"source": WATCH})
        browser.navigate(url)
        browser.wait_for("Array.isArray(window.__cgaDialogs)", "the page's watch on dialogs and writes")
        browser.wait_for("!!window.jupyterapp && !!document.querySelector('#jp-main-dock-panel')", "the lab", 60)
        browser.evaluate("window.jupyterapp.restored.then(() => true)", timeout=60, await_promise=True)
        yield lab, browser
    finally:
        try:
            if browser is not None:
                if os.environ.get("CGA_KEEP_SCREENSHOT"):
                    try:
                        browser.screenshot(Path(f"{os.environ['CGA_KEEP_SCREENSHOT']}_lab.png"))
                    except (AssertionError, OSError):
                        pass
                browser.close()
        finally:
            if lab is not None:
                left = lab.close()
    assert not left, f"processes of the lab outlived it: {left}"


@pytest.fixture(scope="module")
def hough_widget(lab_and_browser):
    """Notebook 05 opened from the root file browser, its cells run from the first down to the explorer's widget
    with Shift+Enter; the index of the widget's cell."""
    _, browser = lab_and_browser
    show_root_folder(browser)
    item = (
        "[...document.querySelectorAll('#filebrowser .jp-DirListing-item')]"
        ".find(e => e.querySelector('.jp-DirListing-itemText').innerText.trim() === {})"
    )
    browser.click(item.format(json.dumps("notebooks")), "the notebooks folder", count=2)
    name = Path(CHAPTER).name
    browser.click(item.format(json.dumps(name)), name, count=2)
    browser.wait_for(
        f"(() => {{ const w = {CURRENT}; return !!w && !!w.context && w.context.path === {json.dumps(CHAPTER)}; }})()",
        f"{name} in the current tab",
    )
    wait_kernel_idle(browser, CHAPTER)
    target = browser.evaluate(cell_index(WIDGET_CELL))
    assert target > 0, f"no cell with {WIDGET_CELL} in {CHAPTER}"
    browser.click(f"{cell_node(0)}.querySelector('.jp-InputPrompt')", "the first cell's prompt")
    browser.key("Escape")  # command mode
    for _ in range(target + 1):
        browser.key("Enter", modifiers=8)  # Shift+Enter: run the cell, select the next one
        time.sleep(0.05)
    browser.wait_for(
        f"{cell_node(target)}.querySelectorAll('.widget-slider').length === 3", "the explorer's three sliders", 60
    )
    wait_kernel_idle(browser, CHAPTER)
    return target


# ============================================================ the tests
def test_lab_opens_the_first_notebook_on_this_environments_kernel(lab_and_browser):
    lab, browser = lab_and_browser
    assert lab.url.startswith("http://127.0.0.1:") and "/lab/tree/notebooks/00_start_here.ipynb?" in lab.url
    browser.wait_for(f"{TAB_LABELS}.includes('00_start_here.ipynb')", "the tab of 00_start_here.ipynb")
    browser.wait_for(f"({CURRENT}).content.widgets.length > 5", "notebook 00's cells")
    _, name, _, _ = wait_kernel_idle(browser, "notebooks/00_start_here.ipynb")
    assert name == "python3"
    kernels = lab.kernel_processes()
    assert kernels, "no kernel process under the lab"
    for argv in kernels:  # the environment's Python (the one running these tests), not another one on the PATH
        assert os.path.realpath(argv[0]) == os.path.realpath(sys.executable), argv
    assert_healthy(lab, browser)


def test_root_file_browser_lists_the_checkout(lab_and_browser):
    lab, browser = lab_and_browser
    show_root_folder(browser)
    names = browser.wait_for(
        f"(n => ['README.md', 'notebooks', 'data'].every(x => n.includes(x)) && n)({LISTING})",
        "README.md, notebooks and data in the root folder's listing",
    )
    assert {"README.md", "notebooks", "data", "cga_lessons", "tests"} <= set(names), names
    assert_healthy(lab, browser)


def test_hough_explorer_runs_and_its_slider_moves_the_robot(lab_and_browser, hough_widget):
    lab, browser = lab_and_browser
    target = hough_widget
    assert browser.evaluate(OUTPUT_ERRORS) == [], browser.evaluate(OUTPUT_ERRORS)
    readout = f"{slider(target, 'heading')}.querySelector('.widget-readout').innerText"
    before = float(browser.evaluate(readout))
    image = f"(i => i && i.src)({cell_node(target)}.querySelector('.widget-output img'))"
    drawn = browser.wait_for(image, "the explorer's figure inside the widget", timeout=60)
    # move the heading slider one step with the keyboard: focus its handle, press the right arrow
    browser.click(f"{slider(target, 'heading')}.querySelector('.noUi-handle')", "the heading slider's handle")
    browser.key("ArrowRight")
    after = float(browser.wait_for(f"(r => r !== '{before:.2f}' && r)({readout})", "the heading slider to move"))
    assert after == pytest.approx(before + 5), (before, after)  # one step of 5 degrees
    # the kernel has the new value once it has redrawn the figure (an idle kernel alone may not have seen it yet)
    browser.wait_for(f"(s => s && s !== {json.dumps(drawn)} && s)({image})", "the figure redrawn", timeout=60)
    wait_kernel_idle(browser, CHAPTER)
    # the kernel's explorer turned with the slider: ask it in a new cell under the widget (b, Enter, type, Shift+Enter)
    browser.click(f"{cell_node(target)}.querySelector('.jp-InputPrompt')", "the widget cell's prompt")
    browser.key("Escape")
    browser.key("b")
    browser.wait_for(f"({CURRENT}).content.activeCellIndex === {target + 1}", "a new cell under the widget")
    browser.key("Enter")
    browser.type_text('print(f"heading {np.degrees(hough_explorer.pose[2]):.0f} deg")')
    browser.key("Enter", modifiers=8)
    printed = browser.wait_for(
        f"(o => o && o.innerText)({cell_node(target + 1)}.querySelector('.jp-OutputArea-output'))",
        "the new cell's output",
    )
    assert printed.strip() == f"heading {after:.0f} deg", printed
    wait_kernel_idle(browser, CHAPTER)
    assert browser.evaluate(OUTPUT_ERRORS) == []
    assert_healthy(lab, browser)


def test_hough_explorer_draws_its_figure_in_the_widget(lab_and_browser, hough_widget):
    lab, browser = lab_and_browser
    target = hough_widget
    image = f"(i => i && i.src)({cell_node(target)}.querySelector('.widget-output img'))"
    first = browser.wait_for(image, "the explorer's figure inside the widget", timeout=5)  # the kernel is idle
    assert first.startswith("data:image/png;base64,")
    readout = f"{slider(target, 'heading')}.querySelector('.widget-readout').innerText"
    before = browser.evaluate(readout)
    browser.click(f"{slider(target, 'heading')}.querySelector('.noUi-handle')", "the heading slider's handle")
    browser.key("ArrowRight")
    browser.wait_for(f"{readout} !== {json.dumps(before)}", "the heading slider to move")
    second = browser.wait_for(f"(s => s !== {json.dumps(first)} && s)({image})", "a new figure after the slider moved")
    assert second.startswith("data:image/png;base64,")
    wait_kernel_idle(browser, CHAPTER)
    assert browser.evaluate(OUTPUT_ERRORS) == []
    assert_healthy(lab, browser)
