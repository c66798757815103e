"""The package's one file writer (:mod:`cga_lessons.files`): whole files or none, and never over a user's file unasked.

The truth each test checks is the file system afterwards, read back with plain ``os``/``pathlib`` calls: which
names the folder holds (no temporary file left), what the files contain, where symbolic links point.
"""

from __future__ import annotations

import errno
import os
import stat

import pytest

from cga_lessons import files
from cga_lessons.errors import InvalidInputError


def names(folder) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_an_existing_file_is_refused_without_overwrite_and_kept_intact(tmp_path):
    mine = tmp_path / "notes.txt"
    mine.write_text("the user's notes\n")
    with pytest.raises(files.ExistingFileError, match=r"^save: path: .*notes\.txt exists \(pass overwrite=True"):
        files.atomic_write(mine, "something else", "save")
    with pytest.raises(FileExistsError):  # also a FileExistsError and a ValueError
        with files.atomic_open(mine, "save") as f:
            f.write("never reached")
    assert issubclass(files.ExistingFileError, ValueError) and issubclass(files.ExistingFileError, InvalidInputError)
    assert mine.read_text() == "the user's notes\n" and names(tmp_path) == ["notes.txt"]


def test_overwrite_replaces_the_file_with_the_permissions_of_a_new_one(tmp_path):
    path = tmp_path / "out.txt"
    path.write_text("old")
    os.chmod(path, 0o600)
    assert files.atomic_write(path, "new ünïcode", "save", overwrite=True) == path
    assert path.read_text(encoding="utf-8") == "new ünïcode" and names(tmp_path) == ["out.txt"]
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~files.umask()
    files.atomic_write(str(path), b"\x00\x01bytes", "save", overwrite=True)  # a str path and bytes
    assert path.read_bytes() == b"\x00\x01bytes"


def test_a_failure_midway_leaves_no_file_and_no_temporary_file(tmp_path):
    new = tmp_path / "new.csv"
    with pytest.raises(ZeroDivisionError):
        with files.atomic_open(new, "save") as f:
            f.write("a,b\n")
            f.write(f"{1 / 0}\n")  # the caller's code producing the content fails
    assert names(tmp_path) == []
    kept = tmp_path / "kept.csv"
    kept.write_text("complete\n")
    with pytest.raises(KeyboardInterrupt):
        with files.atomic_open(kept, "save", overwrite=True) as f:
            f.write("half")
            raise KeyboardInterrupt
    assert kept.read_text() == "complete\n" and names(tmp_path) == ["kept.csv"]


@pytest.mark.parametrize("step", ["fsync", "replace"])
def test_a_failing_file_system_raises_its_own_error_and_leaves_nothing_behind(tmp_path, monkeypatch, step):
    def disk_full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    kept = tmp_path / "kept.txt"
    kept.write_text("complete\n")
    monkeypatch.setattr(files.os, step, disk_full)  # while the file is flushed, or while it is moved in
    with pytest.raises(OSError, match="No space left"):
        files.atomic_write(kept, "new", "save", overwrite=True)
    monkeypatch.undo()
    assert kept.read_text() == "complete\n" and names(tmp_path) == ["kept.txt"]


def test_a_missing_folder_is_named_in_the_error(tmp_path):
    missing = tmp_path / "no" / "such"
    with pytest.raises(InvalidInputError, match=rf"^export: target: no such folder: {missing}$"):
        files.atomic_write(missing / "x.txt", "text", "export", "target")
    assert names(tmp_path) == []


@pytest.mark.parametrize("bad", [None, 3, "", b"x.txt"])
def test_what_is_not_a_path_is_refused_naming_function_and_argument(tmp_path, bad):
    with pytest.raises(InvalidInputError, match=r"^save: where: expected a path"):
        files.atomic_write(bad, "text", "save", "where")


def test_a_folder_where_the_file_goes_is_refused_even_with_overwrite(tmp_path):
    (tmp_path / "out.txt").mkdir()
    with pytest.raises(InvalidInputError, match=r"^save: path: is a folder"):
        files.atomic_write(tmp_path / "out.txt", "text", "save", overwrite=True)
    assert names(tmp_path) == ["out.txt"] and (tmp_path / "out.txt").is_dir()


def test_a_symbolic_link_is_an_existing_file_and_overwrite_replaces_the_link_never_its_target(tmp_path):
    target = tmp_path / "target.txt"
    target.write_text("the user's file\n")
    link, dangling = tmp_path / "link.txt", tmp_path / "dangling.txt"
    link.symlink_to(target)
    dangling.symlink_to(tmp_path / "nowhere.txt")
    for p in (link, dangling):
        with pytest.raises(files.ExistingFileError):
            files.atomic_write(p, "text", "save")
        assert p.is_symlink()
        files.atomic_write(p, "written", "save", overwrite=True)
        assert not p.is_symlink() and p.read_text() == "written"
    assert target.read_text() == "the user's file\n" and not (tmp_path / "nowhere.txt").exists()


def test_a_file_that_appears_while_writing_is_not_overwritten(tmp_path):
    path = tmp_path / "out.txt"
    with pytest.raises(files.ExistingFileError, match="out.txt exists"):
        with files.atomic_open(path, "save") as f:
            f.write("mine")
            path.write_text("someone else's")  # appears between the check and the move
    assert path.read_text() == "someone else's" and names(tmp_path) == ["out.txt"]


def test_without_hard_links_the_move_still_refuses_an_existing_file(tmp_path, monkeypatch):
    def no_links(src, dst):
        raise OSError(errno.EPERM, "hard links not supported")

    monkeypatch.setattr(files.os, "link", no_links)
    src, dst = tmp_path / "src", tmp_path / "dst"
    src.write_text("new")
    dst.write_text("old")
    with pytest.raises(files.ExistingFileError, match=r"^move: dst: .*dst exists"):
        files.atomic_move(src, dst, "move", "dst")
    assert src.read_text() == "new" and dst.read_text() == "old"
    dst.unlink()
    assert files.atomic_move(src, dst, "move", "dst") == dst
    assert names(tmp_path) == ["dst"] and dst.read_text() == "new"


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="needs a user whom permissions bind")
def test_a_folder_one_cannot_write_in_is_named(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    os.chmod(locked, 0o555)
    try:
        with pytest.raises(InvalidInputError, match=rf"^save: path: cannot write in {locked}: "):
            files.atomic_write(locked / "x.txt", "text", "save")
    finally:
        os.chmod(locked, 0o755)
    assert names(locked) == []


def test_bad_content_and_a_bad_overwrite_flag_are_refused(tmp_path):
    with pytest.raises(InvalidInputError, match=r"^save: content: expected a str or bytes, got list"):
        files.atomic_write(tmp_path / "x.txt", ["text"], "save")
    with pytest.raises(InvalidInputError, match=r"^save: overwrite: must be True or False"):
        files.atomic_write(tmp_path / "x.txt", "text", "save", overwrite="yes")
    assert names(tmp_path) == []
