"""Headless Chromium for the tests that look at a page: Debian's browser, found or required, run once and cleaned up.

``.ci/run`` installs Debian's ``chromium`` and sets ``CGA_LESSONS_REQUIRE_CHROMIUM``: there a missing browser fails
the test; elsewhere it skips it.  :func:`run_chromium` starts one headless session with its own profile and process
group, waits at most ``timeout`` seconds, and kills the group and removes the profile whatever happens.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"

#: The flags of every session: no sandbox (root in CI), software WebGL asked of SwiftShader (Chromium's automatic
#: fallback to it is deprecated), and nothing fetched in the background.
BASE_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--use-gl=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-background-networking",
    "--disable-quic",
    "--no-first-run",
    "--disable-component-update",
    "--disable-sync",
)


def require_chromium() -> None:
    """Skip the test without Chromium, or fail it when ``CGA_LESSONS_REQUIRE_CHROMIUM`` is set (CI)."""
    if not Path(CHROMIUM).exists():
        why = "chromium is not installed (.ci/run installs Debian's package 'chromium')"
        if os.environ.get("CGA_LESSONS_REQUIRE_CHROMIUM"):
            pytest.fail(f"{why}, and CGA_LESSONS_REQUIRE_CHROMIUM is set")
        pytest.skip(why)


def run_chromium(url, *, screenshot=None, size=(640, 480), budget_ms=3000, dump_dom=False, extra=(), timeout=60):
    """One headless session on ``url``: ``(return code, standard output, standard error)`` as text.

    ``screenshot`` a PNG path to write, ``budget_ms`` the page's virtual time (its scripts and timers run in it, at
    no cost in wall time once the page is idle), ``dump_dom`` the final DOM on standard output, ``extra`` more flags.
    """
    profile = tempfile.mkdtemp(prefix="chromium-profile-")
    args = [CHROMIUM, *BASE_FLAGS, *extra, f"--user-data-dir={profile}", f"--window-size={size[0]},{size[1]}",
            f"--virtual-time-budget={int(budget_ms)}"]  # fmt: skip
    if screenshot is not None:
        args.append(f"--screenshot={screenshot}")
    if dump_dom:
        args.append("--dump-dom")
    args.append(url)
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                            start_new_session=True)  # fmt: skip
    try:
        out, err = proc.communicate(timeout=timeout)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)  # any helper process of this session
        except ProcessLookupError:
            pass
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
    return proc.returncode, out.decode(errors="replace"), err.decode(errors="replace")
