"""Atomic writes and the output-path check shared by every writer."""

from __future__ import annotations

import pytest

from rt_drake.atomic_file import output_problem, write_atomically, write_text_atomically
from rt_drake.errors import InputError


def test_output_problem_names_what_is_in_the_way(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").mkdir()
    (tmp_path / "f").write_text("x")
    assert output_problem("new/deeper/x.npz") is None  # parents are made
    assert output_problem("d") == "it is a directory, not a file"
    assert output_problem("f", directory=True) == "it is a file, not a directory"
    assert output_problem("d", directory=True) is None
    assert output_problem("f/x.npz") == "'f' is not a directory"
    assert output_problem("f/a/b/x.npz") == "'f' is not a directory"


def test_write_is_all_or_nothing_and_leaves_no_temporary_file(tmp_path):
    target = tmp_path / "sub" / "x.bin"
    write_text_atomically(target, "first")
    assert target.read_text() == "first"

    def fail_halfway(stream):
        stream.write(b"half")
        raise RuntimeError("interrupted")

    with pytest.raises(RuntimeError, match="interrupted"):
        write_atomically(target, fail_halfway)
    assert target.read_text() == "first"  # the old file, whole
    assert [p.name for p in target.parent.iterdir()] == ["x.bin"]


def test_write_refuses_a_directory_or_a_path_under_a_file(tmp_path):
    (tmp_path / "d").mkdir()
    (tmp_path / "f").write_text("keep")
    with pytest.raises(InputError, match="cannot write .*d': it is a directory"):
        write_text_atomically(tmp_path / "d", "x")
    with pytest.raises(InputError, match="'.*f' is not a directory"):
        write_text_atomically(tmp_path / "f" / "x.txt", "x")
    assert (tmp_path / "f").read_text() == "keep"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d", "f"]
