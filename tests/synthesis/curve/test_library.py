"""The retrieval library's cache: stored bit for bit, the synthesis the same with or without it, atomic, refusals."""

import json

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.synthesis.curve import library as L
from gearlever.synthesis.curve import search as S
from tests.synthesis.curve import _designs

cache, small = _designs.cache, _designs.small  # fixtures


def _same(a, b):
    assert [t.key() for t in a.topologies] == [t.key() for t in b.topologies]
    for f in ("entry_topology", "descriptors", "rms", "source_joints"):
        x, y = getattr(a, f), getattr(b, f)
        assert x.dtype.kind == y.dtype.kind and np.array_equal(x, y), f
    assert len(a.sketches) == len(b.sketches)
    assert all(x.tobytes() == y.tobytes() for x, y in zip(a.sketches, b.sketches))


def test_a_stored_library_is_the_built_one_bit_for_bit_and_limits_like_a_build(cache):
    built, path = L.build_cached(1000, 3)
    assert path == cache / "curves-library-v1-size1000-seed3.npz" and path.is_file()
    assert sorted(p.name for p in cache.iterdir()) == [path.name]  # no temporary file left
    again = L.build_library(3, size=1000)
    _same(built, again)
    loaded = L.cached_library(1000, 3)
    _same(loaded, again)
    for mj in (4, 6, 8):
        _same(loaded.limited(mj), L.build_library(3, size=1000, max_joints=mj))
    assert L.cached_library(1000, 4) is None and L.cached_library(999, 3) is None
    (row,) = L.library_files()
    assert (row["size"], row["seed"], row["entries"], row["bytes"]) == (1000, 3, again.rms.size, path.stat().st_size)
    assert row["problem"] is None


def test_the_default_size_is_the_synthesis_library():
    assert L.library_counts(L.LIBRARY_TOPOLOGIES * L.LIBRARY_SKETCHES) == [L.LIBRARY_SKETCHES] * L.LIBRARY_TOPOLOGIES
    _same(L.build_library(0, size=600), L.build_library(0, 2, 300))
    with pytest.raises(GearleverError, match="library_size must be 1 to 200000"):
        L.library_counts(200_001)


def _dump(res):
    return json.dumps(res.summary()), [lk.as_dict() for lk in res.designs]


@pytest.mark.parametrize("max_joints", [20, 6])
def test_the_synthesis_is_the_same_with_the_cached_library_and_without(cache, small, monkeypatch, max_joints):
    t = np.linspace(0, 2 * np.pi, 120)
    egg = np.stack([0.3 * np.cos(t) * (1 + 0.2 * np.sin(t)), 0.24 * np.sin(t)], -1)
    kw = {"budget": 1000, "seed": 1, "workers": 1, "max_joints": max_joints, "designs": 20}
    without = S.synthesize_curve(egg, library_size=600, **kw)
    L.build_cached(600, 0)
    real = S.build_library

    def refuse(*a, **k):
        raise AssertionError("the cached library was not used")

    monkeypatch.setattr(S, "build_library", refuse)
    with_cache = S.synthesize_curve(egg, library_size=600, **kw)
    assert _dump(with_cache) == _dump(without)
    monkeypatch.setattr(S, "build_library", real)
    # a damaged file is not used: the library is built in memory, the same designs again
    L.library_path(600, 0).write_bytes(b"PK\x03\x04 not a zip")
    assert L.cached_library(600, 0) is None
    assert _dump(S.synthesize_curve(egg, library_size=600, **kw)) == _dump(without)


@pytest.mark.parametrize(
    "kw, needle",
    [
        ({"library_size": 0}, "library_size"),
        ({"library_size": 200_001}, "library_size"),
        ({"library_size": 1.5}, "library_size"),
        ({"library_seed": -1}, "library_seed"),
    ],
)
def test_bad_library_arguments_are_refused_naming_them(kw, needle):
    t = np.linspace(0, 2 * np.pi, 50)
    with pytest.raises(GearleverError, match=needle):
        S.synthesize_curve(np.stack([np.cos(t), np.sin(t)], -1), **kw)


def test_ctrl_c_while_writing_leaves_no_file(cache, monkeypatch):
    def interrupted(fh, **arrays):
        fh.write(b"PK\x03\x04 half")
        raise KeyboardInterrupt

    monkeypatch.setattr(L.np, "savez_compressed", interrupted)
    with pytest.raises(KeyboardInterrupt):
        L.build_cached(200, 0)
    assert not cache.exists() or list(cache.iterdir()) == []


def test_files_of_another_format_or_settings_are_listed_and_not_used(cache, monkeypatch):
    L.build_cached(300, 0)
    old = cache / "curves-library-v0-size300-seed0.npz"
    old.write_bytes(b"old")
    monkeypatch.setattr(L, "LIBRARY_SKETCHES", 100)  # another build setting: the stored file does not match it
    assert L.cached_library(300, 0) is None
    rows = L.library_files()
    assert [r["format"] for r in rows] == [1, 0]
    assert "other settings" in rows[0]["problem"] and "format v0" in rows[1]["problem"]
    with pytest.raises(GearleverError, match=r"size300-seed0\.npz: built with other settings"):
        L.load_library(L.library_path(300, 0), 300, 0)


def test_the_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("GEARLEVER_CACHE", str(tmp_path / "g"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "x"))
    assert L.cache_folder() == tmp_path / "g"
    monkeypatch.delenv("GEARLEVER_CACHE")
    assert L.cache_folder() == tmp_path / "x" / "gearlever"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/path")  # ignored, as the XDG specification says
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert L.cache_folder() == tmp_path / "home" / ".cache" / "gearlever"
