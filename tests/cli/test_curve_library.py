"""CLI: gearlever curve library build/info; synthesize curve writes the same files with the cached library or not."""

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.synthesis.curve import library as L
from tests.synthesis.curve import _designs

cache, small = _designs.cache, _designs.small  # fixtures


def test_build_then_info(cache, capsys):
    assert main(["curve", "library", "info"]) == 0
    assert capsys.readouterr().out.splitlines() == [
        f"cache folder: {cache}",
        "no library stored (gearlever curve library build --size N)",
    ]
    assert main(["curve", "library", "build", "--size", "900", "--seed", "2"]) == 0
    out, err = capsys.readouterr()
    path = cache / "curves-library-v1-size900-seed2.npz"
    entries = L.build_library(2, size=900).rms.size
    assert out == f"{path}: 900 mechanisms, seed 2, {entries} entries, {path.stat().st_size} bytes\n"
    assert err == ""  # no progress when stderr is not a terminal
    assert main(["curve", "library", "info"]) == 0
    assert capsys.readouterr().out.splitlines() == [
        f"cache folder: {cache}",
        f"{path.name}: 900 mechanisms, seed 2, {entries} entries, {path.stat().st_size} bytes",
    ]


@pytest.mark.parametrize("size", ["0", "200001", "1.5", "x"])
def test_build_refuses_a_size_out_of_its_cap_in_one_line(cache, capsys, size):
    assert main(["curve", "library", "build", "--size", size]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--size" in err
    assert not cache.exists()


def test_build_into_a_folder_that_cannot_be_made_exits_2(tmp_path, monkeypatch, capsys):
    (tmp_path / "file").write_text("")
    monkeypatch.setenv("GEARLEVER_CACHE", str(tmp_path / "file" / "cache"))
    assert main(["curve", "library", "build", "--size", "50"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "cache folder" in err and "file/cache" in err


def test_synthesize_curve_writes_the_same_bytes_with_the_cached_library(tmp_path, cache, small, capsys):
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    tgt = tmp_path / "egg.csv"
    tgt.write_text("x,y\n" + "".join(f"{0.3 * np.cos(a) * (1 + 0.2 * np.sin(a))},{0.24 * np.sin(a)}\n" for a in t))

    def run(out):
        argv = ["synthesize", "curve", str(tgt), "--out", str(out), "--budget", "1000", "--designs", "5"]
        assert main([*argv, "--library-size", "540", "--library-seed", "1", "--report", str(out) + ".json"]) == 0
        capsys.readouterr()
        files = {p.name: p.read_bytes() for p in sorted(out.iterdir())}
        rep = (tmp_path / (out.name + ".json")).read_text().splitlines()
        return files, [ln for ln in rep if '"seconds"' not in ln and '"out"' not in ln]

    without = run(tmp_path / "a")
    assert main(["curve", "library", "build", "--size", "540", "--seed", "1"]) == 0
    capsys.readouterr()
    with_cache = run(tmp_path / "b")
    assert with_cache[0] == without[0] and with_cache[1] == without[1]
    assert "0001.links.json" in without[0]


@pytest.mark.parametrize(
    "flag, value", [("--library-size", "0"), ("--library-size", "300000"), ("--library-seed", "-1")]
)
def test_synthesize_curve_refuses_bad_library_flags(tmp_path, capsys, flag, value):
    tgt = tmp_path / "t.csv"
    t = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    tgt.write_text("x,y\n" + "".join(f"{np.cos(a)},{np.sin(a)}\n" for a in t))
    assert main(["synthesize", "curve", str(tgt), "--out", str(tmp_path / "o"), flag, value]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and flag in err


def test_ctrl_c_during_the_build_leaves_no_file_and_no_folder(cache, capsys, monkeypatch):
    def interrupted(*a, progress=None, **k):
        progress("library", 1, 2)
        raise KeyboardInterrupt

    monkeypatch.setattr(L, "build_library", interrupted)
    assert main(["curve", "library", "build", "--size", "600"]) == 130
    assert "\n" not in capsys.readouterr().err.strip()
    assert not cache.exists()
