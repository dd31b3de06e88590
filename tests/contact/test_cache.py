"""The wrench-set cache: keyed by parameters, never loads another cup's file.

``load_polytope`` refuses, with an InputError naming the file and the reason,
a file that is missing, corrupt, of another format, or another cup's; the
cache then recomputes.
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import rt_drake.contact._cache as cache
from rt_drake.contact import (
    CupParameters,
    WrenchPolytope,
    cache_path,
    cached_wrench_polytope,
    contact_wrench_polytope,
    default_cache_dir,
    load_polytope,
    save_polytope,
)
from rt_drake.errors import InputError

CUP_A = CupParameters(points=4, friction=0.4)
CUP_B = CupParameters(points=4, friction=0.5)


def test_second_call_loads_the_file_without_recomputing(tmp_path, monkeypatch):
    first = cached_wrench_polytope(CUP_A, tmp_path)
    assert cache_path(CUP_A, tmp_path).is_file()

    def fail(cup):
        raise AssertionError("recomputed although cached")

    monkeypatch.setattr(cache, "contact_wrench_polytope", fail)
    second = cached_wrench_polytope(CUP_A, tmp_path)
    np.testing.assert_array_equal(second.F, first.F)
    np.testing.assert_array_equal(second.vertices, first.vertices)
    assert second.cup == CUP_A


def test_a_file_for_other_parameters_is_never_loaded(tmp_path):
    cached_wrench_polytope(CUP_A, tmp_path)
    # Plant A's file where B's belongs (a collision, a rename, a stale copy).
    shutil.copy(cache_path(CUP_A, tmp_path), cache_path(CUP_B, tmp_path))
    with pytest.raises(InputError, match="written for cup friction = 0.4, not 0.5"):
        load_polytope(cache_path(CUP_B, tmp_path), CUP_B)
    got = cached_wrench_polytope(CUP_B, tmp_path)
    expected = contact_wrench_polytope(CUP_B)
    np.testing.assert_allclose(got.F, expected.F)
    np.testing.assert_allclose(got.g, expected.g)
    # ... and the bad file was replaced by B's.
    assert load_polytope(cache_path(CUP_B, tmp_path), CUP_B).cup == CUP_B


def test_other_format_versions_and_corrupt_files_are_ignored(tmp_path, monkeypatch):
    cached_wrench_polytope(CUP_A, tmp_path)
    path = cache_path(CUP_A, tmp_path)
    monkeypatch.setattr(cache, "FORMAT_VERSION", cache.FORMAT_VERSION + 1)
    with pytest.raises(InputError, match="format_version"):
        load_polytope(path, CUP_A)
    monkeypatch.undo()
    path.write_bytes(b"not a zip file")
    with pytest.raises(InputError, match="not a wrench polytope .npz"):
        load_polytope(path, CUP_A)
    assert len(cached_wrench_polytope(CUP_A, tmp_path).F) > 0
    with pytest.raises(InputError, match="nope.npz.*does not exist"):
        load_polytope(tmp_path / "nope.npz", CUP_A)


def test_a_file_whose_vertices_break_its_rows_is_refused(tmp_path):
    exact = contact_wrench_polytope(CUP_A)
    F = exact.F.copy()
    F[0] = 0.0  # an all-zero row: constrains nothing
    save_polytope(
        tmp_path / "zero.npz", WrenchPolytope(CUP_A, F, exact.g, exact.vertices)
    )
    with pytest.raises(InputError, match="zero.npz.*row 0 is zero"):
        load_polytope(tmp_path / "zero.npz", CUP_A)
    g = exact.g.copy()
    g[3] -= 1.0  # a vertex now violates row 3
    save_polytope(
        tmp_path / "bad.npz", WrenchPolytope(CUP_A, exact.F, g, exact.vertices)
    )
    with pytest.raises(InputError, match="bad.npz.*violate their own H-rep"):
        load_polytope(tmp_path / "bad.npz", CUP_A)


def test_a_failed_write_leaves_no_temporary_file(tmp_path, monkeypatch):
    exact = cached_wrench_polytope(CUP_A, tmp_path / "cache")
    (tmp_path / "d.npz").mkdir()
    with pytest.raises(InputError, match="d.npz.*is a directory"):
        save_polytope(tmp_path / "d.npz", exact)
    (tmp_path / "f").write_text("a file")
    with pytest.raises(InputError, match="'f' is not a directory|f.*not a directory"):
        save_polytope(tmp_path / "f" / "w.npz", exact)

    def explode(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez", explode)
    with pytest.raises(InputError, match="No space left"):
        save_polytope(tmp_path / "w.npz", exact)
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cache", "d.npz", "f"]


def test_keys_differ_between_parameters_and_the_env_var_sets_the_directory(
    tmp_path, monkeypatch
):
    assert cache_path(CUP_A, tmp_path) != cache_path(CUP_B, tmp_path)
    monkeypatch.setenv("RT_DRAKE_CACHE_DIR", str(tmp_path / "elsewhere"))
    assert default_cache_dir() == tmp_path / "elsewhere"
    assert cache_path(CUP_A).parent == tmp_path / "elsewhere"
    cached_wrench_polytope(CUP_A)
    assert cache_path(CUP_A).is_file()
    monkeypatch.delenv("RT_DRAKE_CACHE_DIR")
    assert default_cache_dir().name == "rt_drake"


def test_use_cache_false_writes_nothing(tmp_path):
    cached_wrench_polytope(CUP_A, tmp_path, use_cache=False)
    assert list(tmp_path.iterdir()) == []


def test_bad_parameters_raise_and_write_nothing(tmp_path):
    cup = CupParameters()
    cup.radius = -1.0  # as a field set after construction (yaml loading)
    with pytest.raises(ValueError, match="radius"):
        cached_wrench_polytope(cup, tmp_path)
    assert list(tmp_path.iterdir()) == []
