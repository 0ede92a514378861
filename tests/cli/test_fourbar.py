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


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["fourbar", *LINKS, "--points", "100000000"], "--points: must be at most 10^5"),
        (
            ["animate", "--fourbar", "9", "5", "8", "8", "--out", "x.gif", "--frames", "100000"],
            "--frames: must be at most 360",
        ),
        (["animate", "--fourbar", "9", "5", "8", "8", "--out", "x.gif", "--fps", "1000"], "--fps: must be at most 100"),
        (["animate", "--fourbar", "9", "5", "8", "8", "--out", "x.png"], "--out must be a .gif"),
    ],
)
def test_size_arguments_above_their_cap_are_refused_naming_flag_and_cap(argv, needle, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err
    assert not list(tmp_path.iterdir())


def test_huge_link_is_refused_with_the_true_sum_of_the_others(capsys):
    # known bug: 1e308 + 3 - 1e308 reported the other links' sum as "(0)"
    assert main(["fourbar", "--ground", "1e308", "--crank", "1", "--coupler", "1", "--rocker", "1"]) == 2
    err = capsys.readouterr().err
    assert "--ground" in err and "other three links (3)" in err and "(0)" not in err


def test_huge_equal_links_give_the_same_angles_as_unit_links(capsys):
    # angles and analogues are scale-free: 1e308 links must not overflow
    big = ["--ground", "1e308", "--crank", "5e307", "--coupler", "1e308", "--rocker", "9e307", "--points", "8"]
    assert main(["fourbar", *big]) == 0
    out_big = capsys.readouterr().out
    assert main(["fourbar", "--ground", "10", "--crank", "5", "--coupler", "10", "--rocker", "9", "--points", "8"]) == 0
    rows_big = list(csv.DictReader(io.StringIO(out_big)))
    rows_ref = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    for rb, rr in zip(rows_big, rows_ref):
        for k in ("theta3_deg", "theta4_deg", "dtheta4_dphi", "d2theta4_dphi2"):
            assert float(rb[k]) == pytest.approx(float(rr[k]), rel=1e-9, abs=1e-9)


def test_parallelogram_fold_is_flagged_as_a_change_point(capsys):
    # 4/2/4/2 folds flat at theta2 = 0 and 180 deg (s + l = p + q, Norton sec. 2.12):
    # the open branch is a parallelogram on one side (theta3 = 0, theta4 = theta2)
    # and an antiparallelogram on the other; the switch is flagged, not silent.
    assert main(["fourbar", "--ground", "4", "--crank", "2", "--coupler", "4", "--rocker", "2", "--points", "8"]) == 0
    cap = capsys.readouterr()
    rows = list(csv.DictReader(io.StringIO(cap.out)))
    flagged = [float(r["theta2_deg"]) for r in rows if r["change_point"] == "1"]
    assert flagged == [0.0, 180.0]
    assert "change point at theta2 = 0, 180 deg" in cap.err and cap.err.count("\n") == 1
    th3 = {float(r["theta2_deg"]): float(r["theta3_deg"]) for r in rows}
    assert abs(th3[90.0]) < 1e-9 and abs(th3[270.0]) > 10.0  # parallelogram, then antiparallelogram
    # library: the result field and the angles
    r = fourbar(4, 2, 4, 2, np.radians([0.0, 90.0, 180.0, 270.0]))
    assert r.change_point.tolist() == [True, False, True, False]
    from gearlever.loops import change_points

    assert np.degrees(change_points(4, 2, 4, 2)).tolist() == [0.0, 180.0]
    assert change_points(9, 5, 8, 8).size == 0
    # a crank-rocker has no change point and no note
    assert main(["fourbar", *LINKS, "--points", "8"]) == 0
    cap = capsys.readouterr()
    assert cap.err == "" and all(r["change_point"] == "0" for r in csv.DictReader(io.StringIO(cap.out)))
