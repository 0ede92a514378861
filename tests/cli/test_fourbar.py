"""CLI runs of `gearlever fourbar` and `gearlever animate`."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from gearlever import fourbar
from gearlever.cli import main

LINKS = ["--ground", "9", "--crank", "5", "--coupler", "8", "--rocker", "8"]


def test_fourbar_csv_matches_library(capsys):
    assert main(["fourbar", *LINKS, "--points", "12"]) == 0
    out = capsys.readouterr().out
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 12
    th = np.radians([float(r["theta2_deg"]) for r in rows])
    ref = fourbar(9, 5, 8, 8, th)
    assert np.allclose([float(r["theta4_deg"]) for r in rows], np.degrees(ref.theta4), atol=1e-9)
    assert np.allclose([float(r["d2theta3_dphi2"]) for r in rows], ref.d2theta3_dphi2, atol=1e-9)
    assert {r["valid"] for r in rows} == {"1"}


def test_fourbar_json_crossed_non_grashof_has_nulls(capsys):
    assert (
        main(
            [
                "fourbar",
                "--ground",
                "9",
                "--crank",
                "7",
                "--coupler",
                "8",
                "--rocker",
                "7",
                "--points",
                "8",
                "--branch",
                "crossed",
                "--format",
                "json",
            ]
        )
        == 0
    )
    recs = json.loads(capsys.readouterr().out)
    assert len(recs) == 8 and set(recs[0]) >= {"theta2_deg", "theta3_deg", "dtheta4_dphi", "valid"}
    bad = [r for r in recs if not r["valid"]]
    assert bad and all(r["theta4_deg"] is None for r in bad)  # theta2 = 180 deg cannot close


def test_fourbar_out_file_written(tmp_path, capsys):
    target = tmp_path / "fb.csv"
    assert main(["fourbar", *LINKS, "--points", "5", "--out", str(target)]) == 0
    assert target.read_text().count("\n") == 6


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["fourbar", "--ground", "-1", "--crank", "5", "--coupler", "8", "--rocker", "8"], "--ground"),
        (["fourbar", "--ground", "x", "--crank", "5", "--coupler", "8", "--rocker", "8"], "--ground"),
        (["fourbar", "--ground", "40", "--crank", "5", "--coupler", "8", "--rocker", "8"], "ground must be"),
        (["fourbar", *LINKS, "--points", "0"], "--points"),
        (["fourbar", *LINKS, "--branch", "up"], "--branch"),
        (["animate", "--fourbar", "9", "5", "8", "--out", "x.gif"], "--fourbar"),
        (["animate", "--fourbar", "9", "5", "8", "8", "--out", "x.png"], "out must be"),
        (["animate", "--fourbar", "40", "5", "8", "8", "--out", "x.gif"], "ground must be"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, needle, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err
    assert not list(tmp_path.iterdir())  # nothing written


def test_animate_writes_a_gif(tmp_path, capsys):
    from PIL import Image

    target = tmp_path / "fb.gif"
    assert main(["animate", "--fourbar", "9", "5", "8", "8", "--out", str(target), "--frames", "4"]) == 0
    with Image.open(target) as im:
        assert im.format == "GIF" and im.n_frames == 4
    assert [p.name for p in tmp_path.iterdir()] == ["fb.gif"]
