"""The package installed from a wheel, not from this checkout: its bundled data and its command line still work.

A wheel is built from a copy of the checkout (no network: ``--no-build-isolation``, the build tools of the test
environment), installed with ``--no-deps`` into a new virtual environment that sees the test environment's
packages (NumPy, SciPy... but not this checkout: ``PYTHONPATH`` is cleared and the working directory is a
temporary folder), and used from there.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(cmd, cwd, **kw):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=600, **kw)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(python, cga-lessons script, folder) of a venv holding the package installed from a fresh wheel."""
    if not (ROOT / "pyproject.toml").is_file():
        pytest.skip("not a checkout: nothing to build a wheel from")
    base = tmp_path_factory.mktemp("wheel")
    source = base / "source"  # a copy: building in the checkout would leave build/ and egg-info folders there
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for name in ("cga_lessons", "data"):
        shutil.copytree(ROOT / name, source / name, symlinks=True, ignore=ignore)
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, source / name)
    built = run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(base), str(source)],
        cwd=base,
    )
    assert built.returncode == 0, built.stderr[-3000:]
    (wheel,) = base.glob("cga_lessons-*.whl")
    env_dir = base / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env_dir)
    python = env_dir / "bin" / "python"
    # pip of the test environment, pointed at the new environment's interpreter
    done = run(
        [sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "--no-index", "-q", str(wheel)],
        cwd=base,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return python, env_dir / "bin" / "cga-lessons", base


def test_the_installed_package_is_the_wheel_and_finds_its_data(installed):
    python, _, base = installed
    probe = (
        "import cga_lessons, pathlib; from cga_lessons import data_path; "
        "print(pathlib.Path(cga_lessons.__file__).resolve()); "
        "print(data_path('carmen', 'intel-corrected.log.gz').stat().st_size); "
        "print(data_path('scenes', 'office.json').is_file(), data_path('stereo_rig.json').is_file())"
    )
    out = run([str(python), "-c", probe], cwd=base)
    assert out.returncode == 0, out.stderr[-3000:]
    where, size, found = out.stdout.strip().splitlines()
    assert Path(where).is_relative_to(base / "venv"), where  # not this checkout
    assert int(size) == (ROOT / "data" / "carmen" / "intel-corrected.log.gz").stat().st_size
    assert found == "True True"


def test_the_installed_command_line_maps_a_bundled_log(installed):
    python, script, base = installed
    log = run(
        [str(python), "-c", "from cga_lessons import data_path; print(data_path('carmen', 'intel-corrected.log.gz'))"],
        cwd=base,
    )
    path = log.stdout.strip()
    assert Path(path).is_relative_to(base / "venv")
    out_dir = base / "out"
    done = run(
        [str(script), "map2d", path, "--limit", "40", "--out-dir", str(out_dir), "--progress", "never"], cwd=base
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    names = sorted(p.name for p in out_dir.iterdir())
    assert names == sorted(
        f"intel-corrected{s}" for s in ("_map.png", "_segments.csv", "_poses.csv", "_trajectory.tum")
    )
