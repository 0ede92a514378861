"""``gearlever mechanism export``: DXF and SVG of every shipped example with gears, parts, bad input exits 2."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from gearlever.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
GEARED = ["geared_fivebar", "planetary", "compound_planetary", "ferguson", "zrdpm_gear_contour"]


@pytest.mark.parametrize("name", GEARED)
def test_export_every_shipped_example_with_gears(name, tmp_path, capsys):
    import ezdxf

    for suffix in ("dxf", "svg"):
        out = tmp_path / f"{name}.{suffix}"
        assert main(["mechanism", "export", str(EXAMPLES / f"{name}.toml"), "--out", str(out)]) == 0
        assert f"wrote {out}" in capsys.readouterr().out
    assert not ezdxf.readfile(tmp_path / f"{name}.dxf").audit().has_errors


def test_export_at_a_pose_with_parts(tmp_path, capsys):
    out, parts = tmp_path / "m.dxf", tmp_path / "parts"
    args = ["mechanism", "export", str(EXAMPLES / "fourbar.toml"), "--out", str(out), "--at", "crank=30"]
    assert main([*args, "--pin-diameter", "3", "--parts", str(parts)]) == 0
    assert sorted(p.name for p in parts.iterdir()) == ["coupler.dxf", "crank.dxf", "ground.dxf", "rocker.dxf"]
    text = capsys.readouterr().out
    assert text.count("wrote ") == 5


@pytest.mark.parametrize(
    "extra, words",
    [
        (["--at", "crnak=30"], "--at: unknown input 'crnak'"),
        (["--at", "crank=x"], "--at crank"),
        (["--pin-diameter", "-1"], "--pin-diameter"),
        (["--pin-diameter", "0"], "--pin-diameter"),
        (["--out", "/proc/m.dxf"], "--out"),
        (["--out", "m.png"], "--out must end with .dxf or .svg"),
    ],
)
def test_bad_input_exits_2_with_one_line_and_no_file(extra, words, tmp_path, capsys):
    os.chdir(tmp_path)
    args = ["mechanism", "export", str(EXAMPLES / "fourbar.toml")]
    if "--out" not in extra:
        args += ["--out", str(tmp_path / "m.dxf")]
    assert main([*args, *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err
    assert list(tmp_path.iterdir()) == []


def test_parts_must_be_a_folder_and_nothing_is_written(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    out = tmp_path / "m.svg"
    args = ["mechanism", "export", str(EXAMPLES / "fourbar.toml"), "--out", str(out), "--parts", str(blocker)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--parts" in err
    assert not out.exists()
    assert main(["mechanism", "export", str(EXAMPLES / "fourbar.toml")]) == 2
    assert "give --out" in capsys.readouterr().err


def test_a_pose_that_does_not_close_is_refused(tmp_path, capsys):
    # the whitworth quick-return closes everywhere; a slider crank's slider input beyond its stroke does not
    model = tmp_path / "sc.toml"
    model.write_text((EXAMPLES / "slider_crank.toml").read_text().replace('link = "crank"', 'slider = "piston"'))
    out = tmp_path / "m.dxf"
    assert main(["mechanism", "export", str(model), "--out", str(out), "--at", "piston=500"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--at: the mechanism does not close" in err
    assert not out.exists()
