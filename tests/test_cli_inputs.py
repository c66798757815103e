"""The command line against hostile inputs and output paths (cga_lessons.cli, its errors, inputs and outputs).

Every case must give exit status 1 and a one-line error on stderr naming the problem, no traceback, and leave
the file system as it was: no partial file, the user's files intact, no symbolic link followed.  The truth is
the file system itself, snapshotted before and after.
"""

import math
import os
from pathlib import Path

import nbformat
import numpy as np
import pytest

from cga_lessons import cli
from cga_lessons.algebra import InvalidInputError
from cga_lessons.cli import SEGMENT_COLUMNS, segments_csv
from cga_lessons.cli import errors as cli_errors
from cga_lessons.cli import map2d as cli_map2d
from cga_lessons.mapping2d import Segment, laser

HEADER = ",".join(SEGMENT_COLUMNS)


def run(argv, capsys):
    rc = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def assert_one_line_error(rc, err, command, *words):
    """Exit status 1 and a single line ``cga-lessons COMMAND: error: ...`` holding every word, no traceback."""
    assert rc == 1, err
    assert "Traceback" not in err and err.count("\n") == 1 and err.endswith("\n"), err
    assert err.startswith(f"cga-lessons {command}: error: "), err
    for word in words:
        assert word in err, (word, err)


def snapshot(root: Path) -> dict:
    """Every entry under root: files with their bytes, links with their targets (never followed), folders."""
    found = {}
    for folder, dirs, files in os.walk(root):
        for name in dirs + files:
            p = Path(folder, name)
            if p.is_symlink():
                found[p.relative_to(root)] = ("link", os.readlink(p))
            elif p.is_dir():
                found[p.relative_to(root)] = ("folder",)
            else:
                found[p.relative_to(root)] = ("file", p.read_bytes())
    return found


@pytest.fixture(scope="module")
def tiny_log(tmp_path_factory):
    """A CARMEN log of 6 scans (181 beams) in the room scene, the odometry fields repeating the poses."""
    scene = laser.load_scene("room")
    poses = scene.trajectory[:6]
    rng = np.random.default_rng(1)
    lines = ["# tiny synthetic log"]
    for k, p in enumerate(poses):
        ranges, _ = laser.simulate_scan(scene, p, rng, n_beams=181, max_range=8.0)
        r = np.where(np.isfinite(ranges), ranges, 81.83)
        fields = [f"{v:.4f}" for v in r] + [f"{v:.6f}" for v in (*p, *p)] + [f"{0.2 * k:.3f}", "host", "0.0"]
        lines.append(f"FLASER {len(r)} " + " ".join(fields))
    path = tmp_path_factory.mktemp("tiny") / "tiny.log"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def no_build(monkeypatch):
    """Fail the test if map2d gets as far as building the map (every output path is checked before)."""

    def fail(*args, **kwargs):
        raise AssertionError("map2d built the map before checking its outputs")

    monkeypatch.setattr(cli_map2d, "_build_map_with_progress", fail)


# --------------------------------------------------------------------------- relocalize: the map file


@pytest.mark.parametrize(
    "content, words",
    [
        (bytes(range(256)) * 4, ["binary", "NUL"]),
        (f"{HEADER}\n0,0,1,0,0,0,5,0,0\n".encode("utf-16"), ["UTF-16", "UTF-8"]),
        (f"{HEADER}\n0,0,1,0,0,0,5,0,0\n\xe9t\xe9\n".encode("latin-1"), ["line 3", "not UTF-8"]),
        (f"{HEADER}\n{'1' * 200_000},0,1,0,0,0,5,0,0\n".encode(), ["line 2", "a field longer than 131072"]),
        (f"{HEADER}\n{'1,' * 600_000}\n".encode(), ["line 2", "a line longer than"]),
        (f"{HEADER}\n0,0,1,0,0,0,1e12,0,0\n".encode(), ["line 2", "n_points '1e12'"]),
        (f"{HEADER}\n0,0,1,0,0,0,{10**12},0,0\n".encode(), ["line 2", "n_points '1000000000000'"]),
        (f"{HEADER}\n0,0,1,0,0,0,-4,0,0\n".encode(), ["line 2", "n_points '-4'"]),
        (f"{HEADER}\n0,0,1,0,0,0,inf,0,0\n".encode(), ["line 2", "n_points 'inf'"]),
    ],
    ids=["binary", "utf-16", "latin-1", "huge-field", "huge-line", "count-1e12", "count-10**12", "negative", "inf"],
)
def test_relocalize_refuses_a_map_file_that_is_not_a_segments_csv(tiny_log, tmp_path, capsys, content, words):
    bad = tmp_path / "map.csv"
    bad.write_bytes(content)
    before = snapshot(tmp_path)
    rc, out, err = run(["relocalize", bad, tiny_log, "--scan-index", "1"], capsys)
    assert_one_line_error(rc, err, "relocalize", "map.csv", *words)
    assert out == "" and snapshot(tmp_path) == before


def test_segments_csv_reader_takes_large_counts_without_making_the_points(tmp_path):
    """A count up to MAX_SEGMENT_POINTS costs no memory: the point sums are computed in closed form, and they
    are the sums Segment computes from n evenly spread points (the truth: Segment's own construction)."""
    path = tmp_path / "m.csv"
    path.write_text(
        f"{HEADER}\n0.5,-1,2.5,3,0,0,7,1,0\n-2,1,1,1,0,0,1,0,1\n3,3,4,5,0,0,{segments_csv.MAX_SEGMENT_POINTS},0,0\n"
    )
    segs = cli.read_segments_csv(path)
    for s, n in zip(segs, (7, 2)):  # a count below 2 is two points, as before
        own = Segment(s.start, s.end, n)
        assert s.n_points == n and np.allclose(s.sums, own.sums, rtol=1e-12, atol=1e-12)
    assert segs[2].n_points == segments_csv.MAX_SEGMENT_POINTS and np.all(np.isfinite(segs[2].sums))
    n = 1000  # the closed form against the sums of the points themselves, in plain arithmetic
    pts = [(3 + k / (n - 1), 3 + 2 * k / (n - 1)) for k in range(n)]
    plain = [n, sum(x for x, _ in pts), sum(y for _, y in pts)]
    plain += [sum(x * x for x, _ in pts), sum(x * y for x, y in pts), sum(y * y for _, y in pts)]
    assert np.allclose(segments_csv._even_sums(3, 3, 4, 5, n), plain, rtol=1e-12)
    assert [(s.start_is_edge, s.end_is_edge) for s in segs] == [(True, False), (False, True), (False, False)]


# --------------------------------------------------------------------------- map2d: output paths before the run


@pytest.mark.parametrize("where", ["file", "under-a-file", "dangling-link"])
def test_map2d_out_dir_that_cannot_be_a_folder_is_refused_before_the_run(tiny_log, tmp_path, capsys, no_build, where):
    (tmp_path / "notes.txt").write_text("mine")
    (tmp_path / "gone").symlink_to(tmp_path / "nowhere")
    out = {"file": "notes.txt", "under-a-file": "notes.txt/maps", "dangling-link": "gone"}[where]
    before = snapshot(tmp_path)
    rc, out_text, err = run(["map2d", tiny_log, "--out-dir", tmp_path / out], capsys)
    word = {"file": "is a file, not a folder", "under-a-file": "is a file", "dangling-link": "dangling"}[where]
    assert_one_line_error(rc, err, "map2d", word, "notes.txt" if where != "dangling-link" else "gone")
    assert out_text == "" and snapshot(tmp_path) == before


def test_map2d_force_does_not_replace_a_folder_where_an_output_file_goes(tiny_log, tmp_path, capsys, no_build):
    (tmp_path / "tiny_map.png").mkdir()
    (tmp_path / "tiny_map.png" / "keep.txt").write_text("mine")
    before = snapshot(tmp_path)
    rc, out, err = run(["map2d", tiny_log, "--out-dir", tmp_path, "--force"], capsys)
    assert_one_line_error(rc, err, "map2d", "tiny_map.png", "is a folder")
    assert out == "" and snapshot(tmp_path) == before


# --------------------------------------------------------------------------- symbolic links where a file goes


def test_map2d_refuses_symbolic_links_and_force_replaces_the_link_not_its_target(tiny_log, tmp_path, capsys):
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    out.mkdir()
    elsewhere.mkdir()
    (elsewhere / "precious.csv").write_text("the user's own file\n")
    (out / "tiny_segments.csv").symlink_to(elsewhere / "precious.csv")
    (out / "tiny_trajectory.tum").symlink_to(elsewhere / "missing.tum")  # dangling
    before = snapshot(tmp_path)
    rc, _, err = run(["map2d", tiny_log, "--out-dir", out, "--progress", "never"], capsys)
    assert_one_line_error(rc, err, "map2d", "symbolic link", "--force")
    assert snapshot(tmp_path) == before
    rc, _, err = run(["map2d", tiny_log, "--out-dir", out, "--progress", "never", "--force"], capsys)
    assert rc == 0, err
    for name in ("tiny_segments.csv", "tiny_trajectory.tum"):
        assert not (out / name).is_symlink() and (out / name).is_file()
    assert (out / "tiny_segments.csv").read_text().startswith("x_start,")
    assert (elsewhere / "precious.csv").read_text() == "the user's own file\n"
    assert sorted(p.name for p in elsewhere.iterdir()) == ["precious.csv"]  # the dangling link's target: not made
    assert sorted(p.name for p in out.iterdir()) == [
        f"tiny_{s}" for s in ("map.png", "poses.csv", "segments.csv", "trajectory.tum")
    ]


# --------------------------------------------------------------------------- export-html: all pages or none


def tiny_notebook(path, title):
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("1 + 1", execution_count=1)
    cell.outputs = [nbformat.v4.new_output("execute_result", {"text/plain": "2"}, execution_count=1)]
    nb.cells = [nbformat.v4.new_markdown_cell(f"# {title}"), cell]
    nbformat.write(nb, path)


@pytest.mark.parametrize("existing_site", [False, True], ids=["new-site", "existing-site"])
@pytest.mark.parametrize("corrupt", ["{ not json", '{"cells": 5, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}'])
def test_export_html_with_a_corrupt_notebook_writes_no_page_and_a_rerun_works(tmp_path, capsys, existing_site, corrupt):
    nbdir, site = tmp_path / "nb", tmp_path / "site"
    nbdir.mkdir()
    tiny_notebook(nbdir / "01_good.ipynb", "Good")
    if existing_site:  # a site from an earlier run, to be replaced with --force
        site.mkdir()
        (site / "01_good.html").write_text("old page")
        (site / "index.html").write_text("old index")
    (nbdir / "02_broken.ipynb").write_text(corrupt)
    force = ["--force"] if existing_site else []
    before = snapshot(tmp_path)
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, *force], capsys)
    assert_one_line_error(rc, err, "export-html", "02_broken.ipynb", "no page was written")
    assert snapshot(tmp_path) == before  # no page, no hidden temporary folder, the old site intact
    tiny_notebook(nbdir / "02_broken.ipynb", "Mended")
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, *force], capsys)
    assert rc == 0, err
    assert sorted(p.name for p in site.iterdir()) == ["01_good.html", "02_broken.html", "index.html", "mathjax"]
    assert "Mended" in (site / "index.html").read_text() and "old page" not in (site / "01_good.html").read_text()


def test_export_html_checks_its_outputs_before_converting(tmp_path, capsys):
    nbdir, site = tmp_path / "nb", tmp_path / "site"
    nbdir.mkdir()
    site.mkdir()
    tiny_notebook(nbdir / "01_good.ipynb", "Good")
    (site / "index.html").symlink_to(tmp_path / "nowhere.html")
    before = snapshot(tmp_path)
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert_one_line_error(rc, err, "export-html", "symbolic link", "index.html")
    assert snapshot(tmp_path) == before
    (site / "index.html").unlink()
    (site / "index.html").mkdir()
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, "--force"], capsys)
    assert_one_line_error(rc, err, "export-html", "index.html", "is a folder")
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", nbdir / "01_good.ipynb"], capsys)
    assert_one_line_error(rc, err, "export-html", "01_good.ipynb", "not a folder")
    assert not (tmp_path / "nowhere.html").exists() and sorted(p.name for p in site.iterdir()) == ["index.html"]


# --------------------------------------------------------------------------- write_segments_csv


def test_write_segments_csv_never_clobbers_nor_leaves_a_partial_file(tmp_path):
    good = [Segment([0.0, 0.0], [2.0, 1.0], 30, None, True, False), Segment([1.0, -1.0], [1.0, 3.0], 5)]
    path = tmp_path / "map.csv"
    path.write_text("the user's map\n")
    with pytest.raises(FileExistsError) as exc:  # also an InvalidInputError, a ValueError
        cli.write_segments_csv(path, good)
    assert isinstance(exc.value, InvalidInputError) and "will not overwrite" in str(exc.value)
    assert path.read_text() == "the user's map\n"

    class NotFinite:
        start, end, rho, theta, n_points, start_is_edge, end_is_edge = [0, 0], [1, math.nan], 0, 0, 2, 0, 0

    class BadCount(NotFinite):
        end, n_points = [1, 0], "lots"

    for bad, word in [(None, "segment 2 (NoneType)"), (NotFinite(), "finite"), (BadCount(), "n_points 'lots'")]:
        with pytest.raises(InvalidInputError, match=r"write_segments_csv: segments: segment 2") as exc:
            cli.write_segments_csv(path, [*good, bad], overwrite=True)  # the bad one last: nothing written before
        assert word in str(exc.value)
        assert path.read_text() == "the user's map\n" and sorted(p.name for p in tmp_path.iterdir()) == ["map.csv"]
    with pytest.raises(InvalidInputError, match="iterable"):
        cli.write_segments_csv(tmp_path / "new.csv", 5)
    assert cli.write_segments_csv(path, good, overwrite=True) == path
    back = cli.read_segments_csv(path)
    assert [(b.n_points, b.start_is_edge) for b in back] == [(30, True), (5, False)]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.csv"]  # no temporary file left


def test_write_segments_csv_replaces_a_symbolic_link_only_with_overwrite(tmp_path):
    seg = [Segment([0.0, 0.0], [1.0, 0.0], 3)]
    target = tmp_path / "target.csv"
    target.write_text("the user's file\n")
    link, dangling = tmp_path / "link.csv", tmp_path / "dangling.csv"
    link.symlink_to(target)
    dangling.symlink_to(tmp_path / "nowhere.csv")
    for p in (link, dangling):
        with pytest.raises(cli_errors.OutputPathError, match="symbolic link"):
            cli.write_segments_csv(p, seg)
        assert p.is_symlink()
        cli.write_segments_csv(p, seg, overwrite=True)
        assert not p.is_symlink() and p.read_text().startswith("x_start,")
    assert target.read_text() == "the user's file\n" and not (tmp_path / "nowhere.csv").exists()
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(cli_errors.OutputPathError, match="is a folder"):
        cli.write_segments_csv(tmp_path / "folder.csv", seg, overwrite=True)


def test_cli_errors_are_value_errors():
    assert issubclass(cli.CLIError, ValueError) and cli.CLIError.__module__ == "cga_lessons.cli"
    for cls in (cli_errors.OutputPathError, cli_errors.OutputExistsError, cli_errors.InputFileError):
        assert issubclass(cls, cli.CLIError) and issubclass(cls, InvalidInputError)
