"""The wrench-set cache: keyed by parameters, never loads another cup's file."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import rt_drake.contact.cache as cache
from rt_drake.contact import (
    CupParameters,
    cache_path,
    cached_wrench_polytope,
    contact_wrench_polytope,
    default_cache_dir,
    load_polytope,
)

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
    assert load_polytope(cache_path(CUP_B, tmp_path), CUP_B) is None
    got = cached_wrench_polytope(CUP_B, tmp_path)
    expected = contact_wrench_polytope(CUP_B)
    np.testing.assert_allclose(got.F, expected.F)
    np.testing.assert_allclose(got.g, expected.g)
    # ... and the bad file was replaced by B's.
    assert load_polytope(cache_path(CUP_B, tmp_path), CUP_B) is not None


def test_other_format_versions_and_corrupt_files_are_ignored(tmp_path, monkeypatch):
    cached_wrench_polytope(CUP_A, tmp_path)
    path = cache_path(CUP_A, tmp_path)
    monkeypatch.setattr(cache, "FORMAT_VERSION", cache.FORMAT_VERSION + 1)
    assert load_polytope(path, CUP_A) is None
    monkeypatch.undo()
    path.write_bytes(b"not a zip file")
    assert load_polytope(path, CUP_A) is None
    assert len(cached_wrench_polytope(CUP_A, tmp_path).F) > 0


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
