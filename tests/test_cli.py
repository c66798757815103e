"""Tests of the ``cga-lessons`` command line (cga_lessons.cli), run in-process through ``main(argv)``.

Independent truths: the walls of a synthetic scene the log was simulated in, the Intel log's points placed
at its own (SLAM-corrected) poses, the registry itself, and the bytes of the files the commands wrote.
"""

import csv
import gzip
import importlib.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import numpy as np
import pytest

from cga_lessons import cli, data_path, equations
from cga_lessons.cli import SEGMENT_COLUMNS
from cga_lessons.cli.progress import Progress
from cga_lessons.mapping2d import laser, read_carmen_log, wrap_angle

ROOT = Path(__file__).resolve().parents[1]
NO_RETURN = 81.83  # what the SICK scanners of the CARMEN logs report for no return


def run(argv, capsys):
    rc = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def write_carmen_log(path, scans, poses, odometry, stamps=None):
    """A CARMEN log of FLASER lines (old format), as the Radish logs hold them (timestamps 0.2 s apart by default)."""
    lines = ["# synthetic log for the tests", "PARAM robot_frontlaser_offset 0.0 nohost 0"]
    stamps = 0.2 * np.arange(len(poses)) if stamps is None else stamps
    for (ranges, _), p, o, t in zip(scans, poses, odometry, stamps):
        r = np.where(np.isfinite(ranges), ranges, NO_RETURN)
        fields = [f"{v:.4f}" for v in r] + [f"{v:.6f}" for v in (*p, *o)] + [f"{t:.3f}", "testhost", "0.0"]
        lines.append(f"FLASER {len(r)} " + " ".join(fields))
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "wt") as f:
        f.write("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="module")
def room_log(tmp_path_factory):
    """40 scans of 181 beams (the CARMEN layout, 1 degree apart) in the room scene; odometry drifts."""
    scene = laser.load_scene("room")
    truth = scene.trajectory[:40]
    rng = np.random.default_rng(7)
    scans = [laser.simulate_scan(scene, p, rng, n_beams=181, max_range=8.0) for p in truth]
    odometry = laser.simulate_odometry(truth, np.random.default_rng(8))
    path = write_carmen_log(tmp_path_factory.mktemp("room") / "room.log", scans, truth, odometry)
    return path, scene, truth, odometry


def point_to_walls(points, walls):
    """Distance of each point to the nearest wall segment (plain NumPy)."""
    a, v = walls[:, 0], walls[:, 1] - walls[:, 0]
    rel = points[:, None, :] - a[None]
    t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.einsum("wi,wi->w", v, v), 0, 1)
    return np.linalg.norm(rel - t[..., None] * v[None], axis=-1).min(axis=1)


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# --------------------------------------------------------------------------- lab


@pytest.mark.parametrize("euid", [0, 1000])
def test_lab_dry_run_is_local_root_safe_and_opens_the_notebooks(monkeypatch, capsys, euid):
    monkeypatch.setattr(os, "geteuid", lambda: euid)
    rc, out, _ = run(["lab", "--dry-run", "--port", "8899", "--no-browser"], capsys)
    assert rc == 0
    cmd = out.split()
    assert cmd[:3] == [sys.executable, "-m", "jupyterlab"]
    assert "--ServerApp.ip=127.0.0.1" in cmd and "--ServerApp.port=8899" in cmd and "--no-browser" in cmd
    root = [c.split("=", 1)[1] for c in cmd if c.startswith("--ServerApp.root_dir=")]
    assert root == [str(ROOT)] and (ROOT / "README.md").is_file() and (ROOT / "data").is_dir()  # the lab's root
    assert "--LabApp.default_url=/lab/tree/notebooks/00_start_here.ipynb" in cmd
    assert ("--allow-root" in cmd) == (euid == 0)


def test_lab_without_a_notebooks_folder_is_a_clear_error(tmp_path, capsys):
    rc, out, err = run(["lab", "--dry-run", "--notebook-dir", tmp_path / "nowhere"], capsys)
    assert rc == 1 and out == ""
    assert "no notebooks folder" in err and "Traceback" not in err


# --------------------------------------------------------------------------- map2d


def test_map2d_synthetic_log_map_lies_on_the_walls(room_log, tmp_path, capsys):
    path, scene, truth, odometry = room_log
    rc, out, _ = run(["map2d", path, "--out-dir", tmp_path / "out", "--progress", "never"], capsys)
    assert rc == 0, out
    png, seg_csv, pose_csv = (tmp_path / "out" / f"room_{s}" for s in ("map.png", "segments.csv", "poses.csv"))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    rows = read_rows(seg_csv)
    assert list(rows[0]) == list(SEGMENT_COLUMNS) and len(rows) >= 4
    ends = np.array(
        [[float(r[c]) for c in ("x_start", "y_start")] for r in rows]
        + [[float(r[c]) for c in ("x_end", "y_end")] for r in rows]
    )
    d = point_to_walls(ends, scene.walls)
    assert np.median(d) < 0.03 and d.max() < 0.15
    for r in rows:  # the Hough columns are the normal form (3.3) of the stored end points
        (x0, y0, x1, y1, rho, theta) = (float(r[c]) for c in SEGMENT_COLUMNS[:6])
        assert abs(x0 * np.cos(theta) + y0 * np.sin(theta) - rho) < 1e-4
        assert abs(x1 * np.cos(theta) + y1 * np.sin(theta) - rho) < 1e-4
    poses = np.array([[float(r[c]) for c in ("x", "y", "theta")] for r in read_rows(pose_csv)])
    assert poses.shape == (len(truth), 3)
    # the logged odometry drifted; the corrected poses are much closer to the truth than it is
    err_odo = np.linalg.norm(odometry[:, :2] - truth[:, :2], axis=1).max()
    err_map = np.linalg.norm(poses[:, :2] - truth[:, :2], axis=1).max()
    assert err_map < 0.05 < err_odo
    assert "segments" in out and str(seg_csv) in out


def test_map2d_intel_slice_matches_the_logs_own_points(tmp_path, capsys):
    with gzip.open(data_path("carmen", "intel-corrected.log.gz"), "rt") as f:
        head = [line for line, _ in zip(f, range(2000))]
    flaser = [line for line in head if line.startswith("FLASER")][:60]
    log = tmp_path / "intel-slice.log"
    log.write_text("".join(head[:3] + flaser))
    # a short slice: further on, the builder's corrections move its poses off the log's SLAM poses (by 0.4 m
    # after 20 scans), which is the map builder's accuracy on this log, not the command line's
    n = 12
    rc, out, _ = run(["map2d", log, "--out-dir", tmp_path, "--limit", n, "--odometry", "poses"], capsys)
    assert rc == 0 and f"{n} scans" in out
    rows = read_rows(tmp_path / "intel-slice_segments.csv")
    ends = np.array([[float(r["x_start"]), float(r["y_start"])] for r in rows])
    # truth: the same 50 scans placed at the log's SLAM poses, as plain trigonometry
    parsed = read_carmen_log(log)
    pts = []
    for (ranges, angles), (x, y, th) in zip(parsed.scans[:n], parsed.poses[:n]):
        ok = ranges < 8.0
        pts.append(
            np.column_stack([x + ranges[ok] * np.cos(th + angles[ok]), y + ranges[ok] * np.sin(th + angles[ok])])
        )
    pts = np.concatenate(pts)
    d = np.sqrt(((ends[:, None, :] - pts[None]) ** 2).sum(-1)).min(axis=1)
    assert len(rows) >= 5 and np.median(d) < 0.05


def test_map2d_reads_gzip_and_refuses_to_overwrite_without_force(room_log, tmp_path, capsys):
    path, *_ = room_log
    gz = tmp_path / "room.log.gz"
    with open(path, "rb") as src, gzip.open(gz, "wb") as dst:
        dst.write(src.read())
    argv = ["map2d", gz, "--out-dir", tmp_path, "--limit", "12"]
    assert run(argv, capsys)[0] == 0
    seg = tmp_path / "room_segments.csv"
    seg.write_text("kept")
    rc, out, err = run(argv, capsys)
    assert rc == 1 and "will not overwrite" in err and "--force" in err and "Traceback" not in err
    assert seg.read_text() == "kept"
    assert run(argv + ["--force"], capsys)[0] == 0
    assert seg.read_text().startswith("x_start,")


@pytest.mark.parametrize(
    "content, message",
    [
        (None, "no such file"),
        ("", "holds no FLASER line"),
        ("FLASER 180 1.0 2.0 3.0\n", "line 1"),
        ("FLASER 3 1.0 2.0 abc 0 0 0 0 0 0 1.0 host 1.0\n", "non-numeric"),
        (b"\x1f\x8b\x08\x00garbage", "cannot read the log"),
    ],
    ids=["missing", "empty", "truncated", "non-numeric", "corrupt-gzip"],
)
def test_map2d_bad_logs_are_clear_errors(tmp_path, capsys, content, message):
    name = "bad.log.gz" if isinstance(content, bytes) else "bad.log"
    log = tmp_path / name
    if isinstance(content, bytes):
        log.write_bytes(content)
    elif content is not None:
        log.write_text(content)
    rc, out, err = run(["map2d", log, "--out-dir", tmp_path / "out"], capsys)
    assert rc == 1 and message in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("args", [["--limit", "0"], ["--max-range", "-1"], ["--max-range", "nan"], ["--odometry", "x"]])
def test_map2d_bad_arguments_exit_with_usage_status(tmp_path, capsys, args):
    assert cli.main(["map2d", str(tmp_path / "x.log"), *args]) == 2  # argparse's status, returned
    assert "error" in capsys.readouterr().err


def test_map2d_progress_bar_counts_every_scan(room_log, tmp_path, capsys):
    path, *_ = room_log
    rc, _, err = run(["map2d", path, "--out-dir", tmp_path, "--limit", "20", "--progress", "always"], capsys)
    assert rc == 0
    counts = [int(m) for m in re.findall(r"\] (\d+)/20 ", err)]
    assert counts[-1] == 20 and counts == sorted(counts) and len(counts) >= 5
    rc, _, err = run(["map2d", path, "--out-dir", tmp_path, "--limit", "20", "--force", "--progress", "never"], capsys)
    assert rc == 0 and "/20" not in err


ERRORS = r"ATE ([\d.]+) m RMS, heading ([\d.]+) deg RMS; RPE ([\d.]+) cm/m, ([\d.]+) deg/m"


def plain_ate(poses, truth):
    """Position (m) and heading (deg) RMS differences, in plain NumPy."""
    d = np.asarray(poses, float) - np.asarray(truth, float)
    heading = np.arctan2(np.sin(d[:, 2]), np.cos(d[:, 2]))
    return np.sqrt(np.mean(d[:, 0] ** 2 + d[:, 1] ** 2)), np.degrees(np.sqrt(np.mean(heading**2)))


@pytest.fixture(scope="module")
def room_log_repeating(tmp_path_factory):
    """The room scene logged as the Radish corrected logs are: the odometry fields repeat the poses."""
    scene = laser.load_scene("room")
    truth = scene.trajectory[:40]
    rng = np.random.default_rng(7)
    scans = [laser.simulate_scan(scene, p, rng, n_beams=181, max_range=8.0) for p in truth]
    path = write_carmen_log(tmp_path_factory.mktemp("repeat") / "repeat.log", scans, truth, truth)
    return path, scans, truth


def test_map2d_says_when_the_logged_odometry_repeats_the_poses(room_log_repeating, room_log, tmp_path, capsys):
    path, _, truth = room_log_repeating
    rc, out, err = run(["map2d", path, "--out-dir", tmp_path, "--progress", "never"], capsys)
    assert rc == 0, err
    assert "the log's odometry equals its corrected poses" in out and "--odometry simulated --seed N" in out
    odo = re.search(r"logged odometry:\s+" + ERRORS, out)
    assert odo and all(float(v) == 0.0 for v in odo.groups())  # nothing to correct
    drifting, *_ = room_log
    rc, out, _ = run(["map2d", drifting, "--out-dir", tmp_path / "drift", "--progress", "never"], capsys)
    assert rc == 0 and "equals its corrected poses" not in out and "logged odometry:" in out


def test_map2d_simulated_odometry_prints_the_errors_against_the_logs_poses(room_log_repeating, tmp_path, capsys):
    from evo.core import metrics
    from evo.core.trajectory import PoseTrajectory3D
    from evo.tools import file_interface

    path, _, truth = room_log_repeating
    argv = ["map2d", path, "--out-dir", tmp_path, "--progress", "never", "--odometry", "simulated", "--seed", "3"]
    rc, out, err = run(argv, capsys)
    assert rc == 0, err
    assert "equals its corrected poses" not in out and "seed 3" in out and "the log's poses" in out
    # the drift printed is the drift of laser.simulate_odometry(poses, default_rng(3)) with the default model
    odometry = laser.simulate_odometry(truth, np.random.default_rng(3))
    printed = [float(v) for v in re.search(r"simulated odometry:\s+" + ERRORS, out).groups()]
    position, heading = plain_ate(odometry, truth)
    assert position > 0.01 and printed[0] == pytest.approx(position, abs=6e-4)  # printed: mm, 0.01 deg
    assert printed[1] == pytest.approx(heading, abs=6e-3)
    # the corrected line is the error of the poses written, which are the TUM file's (read here by evo)
    corrected = [float(v) for v in re.search(r"corrected:\s+" + ERRORS, out).groups()]
    rows = read_rows(tmp_path / "repeat_poses.csv")
    poses = np.array([[float(r[c]) for c in ("x", "y", "theta")] for r in rows])
    position, heading = plain_ate(poses, truth)
    assert corrected[0] == pytest.approx(position, abs=6e-4) and corrected[1] == pytest.approx(heading, abs=6e-3)
    traj = file_interface.read_tum_trajectory_file(str(tmp_path / "repeat_trajectory.tum"))
    assert np.allclose(traj.positions_xyz[:, :2], poses[:, :2], atol=1e-6)
    assert np.allclose(traj.timestamps[:3], [0, 0.2, 0.4])  # the log's own times
    # evo's RPE over 1 m of the log's path, per metre, is the printed RPE (cm/m)
    ref = read_carmen_log(path).poses
    quat = np.column_stack([np.cos(ref[:, 2] / 2), np.zeros((len(ref), 2)), np.sin(ref[:, 2] / 2)])
    ref_traj = PoseTrajectory3D(np.column_stack([ref[:, :2], np.zeros(len(ref))]), quat, traj.timestamps)
    rpe = metrics.RPE(metrics.PoseRelation.translation_part, 1.0, metrics.Unit.meters, pairs_from_reference=True)
    rpe.process_data((ref_traj, traj))
    steps = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(ref[:, :2], axis=0).T))])
    ends = [0, *rpe.delta_ids]
    per_metre = np.sqrt(np.mean((rpe.error / np.diff(steps[ends])) ** 2))
    assert corrected[2] == pytest.approx(100 * per_metre, abs=0.01)


def test_map2d_trajectory_file_refuses_to_overwrite_before_the_run(room_log, tmp_path, capsys):
    path, *_ = room_log
    tum = tmp_path / "room_trajectory.tum"
    tum.write_text("kept\n")
    rc, out, err = run(["map2d", path, "--out-dir", tmp_path, "--odometry", "simulated"], capsys)
    assert rc == 1 and "will not overwrite" in err and "room_trajectory.tum" in err and out == ""
    assert tum.read_text() == "kept\n" and sorted(p.name for p in tmp_path.iterdir()) == ["room_trajectory.tum"]
    assert run(["map2d", path, "--out-dir", tmp_path, "--limit", "12", "--force"], capsys)[0] == 0
    assert len(tum.read_text().splitlines()) == 12


def test_map2d_tum_file_uses_the_scan_index_when_the_log_time_stands_still(room_log_repeating, tmp_path, capsys):
    _, scans, truth = room_log_repeating
    log = write_carmen_log(tmp_path / "still.log", scans[:15], truth[:15], truth[:15], stamps=np.zeros(15))
    rc, out, err = run(["map2d", log, "--out-dir", tmp_path, "--odometry", "poses"], capsys)
    assert rc == 0, err
    assert "scan index" in out
    stamps = [float(line.split()[0]) for line in (tmp_path / "still_trajectory.tum").read_text().splitlines()]
    assert stamps == list(range(15))
    assert "RPE: the log's poses travel less than 1 m" not in out  # 15 scans of the room travel more


@pytest.mark.parametrize("args", [["--seed", "-1"], ["--seed", "x"], ["--odometry", "simulate"]])
def test_map2d_bad_seed_arguments_exit_with_usage_status(tmp_path, capsys, args):
    assert cli.main(["map2d", str(tmp_path / "x.log"), "--odometry", "simulated", *args]) == 2
    assert "error" in capsys.readouterr().err


def test_map2d_seed_without_simulated_odometry_is_a_clear_error(room_log, tmp_path, capsys):
    path, *_ = room_log
    rc, _, err = run(["map2d", path, "--out-dir", tmp_path / "o", "--seed", "2"], capsys)
    assert rc == 1 and "--seed applies to --odometry simulated only" in err and not (tmp_path / "o").exists()


def test_map2d_help_states_the_drift_model_it_uses(capsys):
    assert cli.main(["map2d", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    model = laser.OdometryModel()
    assert "OdometryModel" in text and "simulated" in text
    for value in (model.sigma_xy, model.heading_bias, model.sigma_heading, model.sigma_turn):
        assert f"{value:g}" in text


def test_progress_bar_redraws_in_place_on_a_terminal():
    class Tty:
        text = ""

        def write(self, s):
            Tty.text += s

        def flush(self):
            pass

        def isatty(self):
            return True

    bar = Progress(4, "x", stream=Tty())
    for k in range(5):
        bar.update(k)
    bar.close()
    assert Tty.text.count("\n") == 1 and "\r" in Tty.text and "4/4" in Tty.text


# --------------------------------------------------------------------------- relocalize


def test_relocalize_finds_the_scans_pose_on_a_map_from_map2d(room_log, tmp_path, capsys):
    pytest.importorskip("cga_lessons.relocalization")
    path, _, truth, _ = room_log
    assert run(["map2d", path, "--out-dir", tmp_path, "--odometry", "poses"], capsys)[0] == 0
    k = 25
    rc, out, err = run(["relocalize", tmp_path / "room_segments.csv", path, "--scan-index", k], capsys)
    assert rc == 0, err
    assert re.search(r"ambiguous: (yes|no)", out) and "score" in out
    poses = [
        (float(x), float(y), np.radians(float(t)))
        for x, y, t in re.findall(r"x = (-?[\d.]+) m, y = (-?[\d.]+) m, theta = (-?[\d.]+) deg", out)
    ]
    best = poses[0]
    assert np.hypot(best[0] - truth[k, 0], best[1] - truth[k, 1]) < 0.1
    assert abs(wrap_angle(best[2] - truth[k, 2])) < np.radians(2)


def test_relocalize_a_sequence_of_scans_with_the_logs_odometry(room_log, tmp_path, capsys):
    pytest.importorskip("cga_lessons.relocalization.sequence")
    path, _, truth, _ = room_log
    assert run(["map2d", path, "--out-dir", tmp_path, "--odometry", "poses"], capsys)[0] == 0
    ks = [20, 25, 30]
    rc, out, err = run(["relocalize", tmp_path / "room_segments.csv", path, "--scan-index", *ks], capsys)
    assert rc == 0, err
    assert "scans 20, 25, 30 (pose at scan 30)" in out
    x, y, t = re.findall(r"x = (-?[\d.]+) m, y = (-?[\d.]+) m, theta = (-?[\d.]+) deg", out)[0]
    assert np.hypot(float(x) - truth[30, 0], float(y) - truth[30, 1]) < 0.1
    assert abs(wrap_angle(np.radians(float(t)) - truth[30, 2])) < np.radians(2)


def test_relocalize_bad_inputs_are_clear_errors(room_log, tmp_path, capsys):
    path, *_ = room_log
    bad = tmp_path / "bad.csv"
    bad.write_text("x_start,y_start,x_end,y_end\n1,2,3\n")
    nomap = tmp_path / "none.csv"
    for argv, message in [
        (["relocalize", nomap, path, "--scan-index", "1"], "no such map file"),
        (["relocalize", bad, path, "--scan-index", "1"], "line 2"),
    ]:
        rc, _, err = run(argv, capsys)
        assert rc == 1 and message in err and "Traceback" not in err
    good = tmp_path / "good.csv"
    good.write_text("x_start,y_start,x_end,y_end\n0,0,1,0\n1,0,1,1\n")
    rc, _, err = run(["relocalize", good, path, "--scan-index", "999"], capsys)
    available = importlib.util.find_spec("cga_lessons.relocalization") is not None
    assert rc == 1 and ("out of range" in err if available else "not in this checkout" in err)


def test_segments_csv_round_trip(tmp_path):
    from cga_lessons.mapping2d import Segment

    segs = [Segment([0.0, 0.0], [2.0, 1.0], 30, None, True, False), Segment([1.0, -1.0], [1.0, 3.0], 5)]
    cli.write_segments_csv(tmp_path / "s.csv", segs)
    back = cli.read_segments_csv(tmp_path / "s.csv")
    assert [(b.n_points, b.start_is_edge, b.end_is_edge) for b in back] == [(30, True, False), (5, False, False)]
    assert all(np.allclose(a.start, b.start) and np.allclose(a.end, b.end) for a, b in zip(segs, back))


# --------------------------------------------------------------------------- equations


def test_equations_text_and_todo_listing(capsys):
    rc, out, _ = run(["equations"], capsys)
    assert rc == 0 and "Chapter 2" in out and equations.coverage_summary() in out
    labels_listed = re.findall(r"^  (\d\.\d+|A\.\d+) ", out, flags=re.M)
    assert set(labels_listed) == set(equations.THESIS_LABELS)
    rc, out, _ = run(["equations", "--todo"], capsys)
    todo = [k for k in equations.THESIS_LABELS if equations.REGISTRY[k].status == "todo"]
    listed = re.findall(r"^  (\S+)\s+todo\b", out, flags=re.M)
    assert rc == 0 and listed == todo
    rc, out, _ = run(["equations", "--format", "markdown"], capsys)
    assert rc == 0 and out == equations.readme_section()


def test_equations_write_and_check_readme(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_text(f"# Title\n\nbefore\n\n{equations.README_START}\nOLD TABLE\n{equations.README_END}\n\nafter\n")
    rc, _, err = run(["equations", "--check-readme", "--readme", readme], capsys)
    assert rc == 1 and "stale" in err and "--write-readme" in err
    assert run(["equations", "--write-readme", "--readme", readme], capsys)[0] == 0
    text = readme.read_text()
    assert text.startswith("# Title\n\nbefore\n\n") and text.endswith(f"{equations.README_END}\n\nafter\n")
    assert "OLD TABLE" not in text and "| 2.131 |" in text
    assert run(["equations", "--check-readme", "--readme", readme], capsys)[0] == 0
    readme.write_text("no markers here\n")
    rc, _, err = run(["equations", "--write-readme", "--readme", readme], capsys)
    assert rc == 1 and "marker" in err and readme.read_text() == "no markers here\n"
    rc, _, err = run(["equations", "--write-readme", "--readme", tmp_path / "missing.md"], capsys)
    assert rc == 1 and "no such README" in err


# --------------------------------------------------------------------------- export-html

PNG_1x1 = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg=="


def small_notebook(path):
    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_markdown_cell("# A tiny chapter\n\nThe inner product $a \\cdot b = -\\frac12 d^2$."),
        nbformat.v4.new_code_cell("1 / 0  # would raise if it were executed", execution_count=1),
        nbformat.v4.new_code_cell("show()", execution_count=2),
    ]
    nb.cells[1].outputs = [nbformat.v4.new_output("execute_result", {"text/plain": "42"}, execution_count=1)]
    nb.cells[2].outputs = [nbformat.v4.new_output("display_data", {"image/png": PNG_1x1, "text/plain": "<Figure>"})]
    nbformat.write(nb, path)


def external_resources(page: str) -> list:
    """Every script, style, image or font the page would fetch from the network."""
    found = re.findall(r"""<(?:script|link|img|iframe)\b[^>]*\b(?:src|href)\s*=\s*["']((?:https?:)?//[^"']+)""", page)
    found += re.findall(r"""@import\s+(?:url\()?["']?((?:https?:)?//[^"')]+)""", page)
    found += re.findall(r"""url\(\s*["']?((?:https?:)?//[^"')]+)""", page)
    return found


def test_export_html_is_offline_and_executes_nothing(tmp_path, capsys):
    nbdir = tmp_path / "nb"
    nbdir.mkdir()
    small_notebook(nbdir / "01_tiny.ipynb")
    small_notebook(nbdir / "teacher_solutions.ipynb")
    site = tmp_path / "site"
    rc, out, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 0, err
    assert sorted(p.name for p in site.iterdir()) == ["01_tiny.html", "index.html", "mathjax"]  # solutions stay out
    page = (site / "01_tiny.html").read_text()
    assert external_resources(page) == [] and "require.js" not in page and 'src="mathjax/MathJax.js?config=' in page
    assert "42" in page and "ZeroDivisionError" not in page  # the stored output, not a new run
    assert f"data:image/png;base64,{PNG_1x1}" in page
    index = (site / "index.html").read_text()
    assert 'href="01_tiny.html"' in index and "A tiny chapter" in index and external_resources(index) == []
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 1 and "will not overwrite" in err
    rc, _, _ = run(
        [
            "export-html",
            "--notebook-dir",
            nbdir,
            "--out-dir",
            site,
            "--force",
            "--include-solutions",
            "--mathjax-url",
            "mathjax/MathJax.js?config=TeX-AMS_CHTML",
        ],
        capsys,
    )
    page = (site / "01_tiny.html").read_text()
    assert rc == 0 and (site / "teacher_solutions.html").is_file() and 'src="mathjax/MathJax.js' in page


def test_export_html_of_a_real_notebook_loads_nothing_from_the_network(tmp_path, capsys):
    nbdir = tmp_path / "nb"
    nbdir.mkdir()
    shutil.copy(ROOT / "notebooks" / "10_exploration.ipynb", nbdir)
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", tmp_path / "site"], capsys)
    assert rc == 0, err
    page = (tmp_path / "site" / "10_exploration.html").read_text()
    assert external_resources(page) == [] and page.count("data:image/png;base64,") >= 5


def test_export_html_bad_notebooks_are_clear_errors(tmp_path, capsys):
    nbdir = tmp_path / "nb"
    nbdir.mkdir()
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", tmp_path / "s"], capsys)
    assert rc == 1 and "no notebooks" in err
    (nbdir / "02_broken.ipynb").write_text("{ not json")
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", tmp_path / "s"], capsys)
    assert rc == 1 and "02_broken.ipynb" in err and "Traceback" not in err


# --------------------------------------------------------------------------- entry points


def test_no_command_prints_help(capsys):
    rc, out, _ = run([], capsys)
    assert rc == 2 and "map2d" in out and "export-html" in out


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return env


def test_python_dash_m_runs_the_same_program():
    done = subprocess.run(
        [sys.executable, "-m", "cga_lessons", "equations", "--todo"], capture_output=True, text=True, env=_env()
    )
    assert done.returncode == 0 and equations.coverage_summary() in done.stdout


def test_console_script_is_installed_and_reports_errors_without_traceback(tmp_path):
    script = shutil.which("cga-lessons")
    if script is None:
        pytest.skip("the cga-lessons script is not on PATH (pip install -e . installs it)")
    done = subprocess.run(
        [script, "map2d", str(tmp_path / "missing.log")], capture_output=True, text=True, env=_env(), cwd=tmp_path
    )
    assert done.returncode == 1 and "no such file" in done.stderr and "Traceback" not in done.stderr
