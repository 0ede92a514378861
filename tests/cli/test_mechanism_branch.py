"""``gearlever mechanism``: rocking inputs oscillate in every command, and ``--branch`` through branch points.

The Watt I six-bar of the PMKS+ verification cases rocks its input AB between 67.284 and 78.254 deg (issue 34,
item 1): analyze, forces, draw, view and simulate each run on it with no row of NaN and the sign of the motion
(a ``direction`` column, or the page's); the square-rod slider-crank turns through its square pose (item 2).
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

from gearlever.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
WATT = str(EXAMPLES / "watt_i.toml")
SQUARE = str(EXAMPLES / "square_rod_slider_crank.toml")
ROCKS = "AB rocks between 67.284 and 78.254 deg"


def _rows(text):
    return list(csv.DictReader(io.StringIO(text)))


def _no_nan(rows):
    return all(v not in ("nan", "", None) for r in rows for k, v in r.items() if k != "reason")


def test_watt_i_analyze_one_oscillation_no_nan_and_a_direction_column(capsys):
    assert main(["mechanism", "analyze", WATT, "--points", "48"]) == 0
    out, err = capsys.readouterr()
    rows = _rows(out)
    assert err == f"{ROCKS}: sweeping one oscillation\n"
    assert len(rows) == 48 and _no_nan(rows) and {r["closed"] for r in rows} == {"1"}
    assert {r["direction"] for r in rows} == {"1", "-1"} and "branch" not in rows[0]


def test_watt_i_forces_one_oscillation_no_null_and_a_direction_column(capsys):
    assert main(["mechanism", "forces", WATT, "--points", "24", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    rows = json.loads(out)["rows"]
    assert err == f"{ROCKS}: sweeping one oscillation\n"
    assert len(rows) == 24 and all(v is not None for r in rows for v in r.values())
    assert {r["direction"] for r in rows} == {1, -1}


def test_watt_i_draw_sweeps_one_oscillation(tmp_path, capsys):
    png = tmp_path / "w.png"
    assert main(["mechanism", "draw", WATT, "--out", str(png), "--points", "40"]) == 0
    assert capsys.readouterr().err == f"{ROCKS}: sweeping one oscillation\n"
    assert png.stat().st_size > 0


def test_watt_i_view_every_frame_closed_both_directions(tmp_path, capsys):
    out = tmp_path / "w.html"
    assert main(["mechanism", "view", WATT, "--out", str(out), "--frames", "24"]) == 0
    assert capsys.readouterr().err == f"{ROCKS}: sweeping one oscillation\n"
    from gearlever.mechanism import Mechanism
    from gearlever.plotting.viewer import viewer_data

    d = viewer_data(Mechanism.load(WATT), frames=24)
    assert d["closed"] == "1" * 24 and set(d["osc"]["dir"]) == {1, -1}


def test_watt_i_simulate_reverses_where_the_dynamics_turn_it_back_with_a_direction_column(capsys):
    # no torque: gravity and the load turn the input back before its upper limit
    assert main(["mechanism", "simulate", WATT, "--rpm", "1", "--time", "0.6", "--points", "13"]) == 0
    out, err = capsys.readouterr()
    rows = _rows(out)
    assert err == f"{ROCKS}: the run stops short of them (1% of the range)\n"
    assert len(rows) == 13 and _no_nan(rows)
    assert [r["direction"] for r in rows][:2] == ["1", "1"] and rows[-1]["direction"] == "-1"
    assert all(np.sign(float(r["AB_rpm"])) == int(r["direction"]) for r in rows)
    assert all(67.284 < float(r["AB_deg"]) < 78.254 for r in rows)


def test_watt_i_simulate_into_a_limit_is_refused_in_one_line_naming_the_limits(capsys):
    # arriving at a dead point with speed is an impact the rigid model cannot carry through
    assert main(["mechanism", "simulate", WATT, "--rpm", "10", "--time", "1", "--points", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "limit 78.254 deg of AB" in err and "between 67.284 and 78.254 deg" in err


def test_square_rod_analyze_turns_through_the_square_pose_and_says_where_the_branch_changed(capsys):
    assert main(["mechanism", "analyze", SQUARE, "--points", "720"]) == 0
    out, err = capsys.readouterr()
    rows = _rows(out)
    assert err == (
        "crank passes a branch point at 270.000 deg (row 540): continuing on the other assembly branch, "
        "the velocity continuous\n"
    )
    assert len(rows) == 720 and _no_nan(rows) and {r["closed"] for r in rows} == {"1"}
    assert [r["branch"] for r in rows[539:542]] == ["1", "-1", "-1"] and "direction" not in rows[0]
    v = np.array([float(r["v_B_x_mm_per_crank"]) for r in rows])
    assert v[540] == pytest.approx(10 - 10 * math.sqrt(3), abs=1e-8)
    assert np.abs(np.diff(v)).max() < 0.2  # no jump anywhere


def test_square_rod_branch_keep_and_stop(capsys):
    assert main(["mechanism", "analyze", SQUARE, "--points", "8", "--branch", "keep"]) == 0
    out, err = capsys.readouterr()
    assert "keeping the assembly branch, the velocity jumps there" in err
    assert {r["branch"] for r in _rows(out)} == {"1"}
    assert main(["mechanism", "analyze", SQUARE, "--points", "8", "--branch", "stop"]) == 0
    out, err = capsys.readouterr()
    assert err == "crank rocks between -90.000 and 270.000 deg: sweeping one oscillation\n"
    assert "branch" not in _rows(out)[0]


def test_branch_flag_is_refused_when_unknown_in_one_line(capsys):
    assert main(["mechanism", "analyze", SQUARE, "--branch", "smooth"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--branch" in err and "'smooth'" in err and "Traceback" not in err


def test_square_rod_draws_and_animates_through_the_square_pose(tmp_path, capsys):
    png, gif = tmp_path / "s.png", tmp_path / "s.gif"
    assert main(["mechanism", "draw", SQUARE, "--out", str(png), "--points", "90"]) == 0
    assert main(["mechanism", "animate", SQUARE, "--out", str(gif), "--frames", "8"]) == 0
    err = capsys.readouterr().err
    assert err.count("passes a branch point at 270.000 deg") == 2


@pytest.mark.parametrize("command", ["analyze", "draw", "animate", "forces", "view"])
def test_every_motion_command_has_the_one_branch_flag(command, capsys):
    from gearlever.cli._shared import BRANCH_HELP

    with pytest.raises(SystemExit):
        main(["mechanism", command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--branch {continue,keep,stop}" in text and " ".join(BRANCH_HELP.split()) in text
    assert main(["mechanism", command, SQUARE, "--out", "x.png", "--branch", "smooth"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--branch" in err and "'smooth'" in err and "Traceback" not in err


def test_square_rod_forces_take_the_branch_policy_and_say_where_it_changed(capsys):
    assert main(["mechanism", "forces", SQUARE, "--points", "720"]) == 0
    out, err = capsys.readouterr()
    assert err == (
        "crank passes a branch point at 270.000 deg (row 540): continuing on the other assembly branch, "
        "the velocity continuous\n"
    )
    rows = _rows(out)
    assert len(rows) == 720
    # the row on the pose: the constraint Jacobian loses rank there, so the pin forces along the line of crank,
    # rod and guide normal (a state of self-stress) are not unique in a rigid model: NaN; the torque, which that
    # self-stress does not change, is solved (0: the example has no masses or loads), and so is every other row
    assert [rows[540][k] for k in ("pin_O2_y_N", "pin_A_y_N", "pin_B_y_N", "guide_piston_normal_N")] == ["nan"] * 4
    assert rows[540]["crank_torque_N_mm"] == "0" and rows[540]["pin_O2_x_N"] == "0"
    assert all("nan" not in r.values() for r in rows[:540] + rows[541:])
    assert main(["mechanism", "forces", SQUARE, "--points", "8", "--branch", "keep"]) == 0
    assert "keeping the assembly branch, the velocity jumps there" in capsys.readouterr().err
    assert main(["mechanism", "forces", SQUARE, "--points", "8", "--branch", "stop"]) == 0
    out, err = capsys.readouterr()
    assert err == "crank rocks between -90.000 and 270.000 deg: sweeping one oscillation\n"
    assert {r["direction"] for r in _rows(out)} == {"1", "-1"}


def test_square_rod_view_takes_the_branch_policy_and_says_where_it_changed(tmp_path, capsys):
    page = tmp_path / "square.html"
    assert main(["mechanism", "view", SQUARE, "--out", str(page), "--frames", "72"]) == 0
    err = capsys.readouterr().err
    assert err == (
        "crank passes a branch point at 270.000 deg (row 54): continuing on the other assembly branch, "
        "the velocity continuous\n"
    )
    assert page.stat().st_size > 0
    assert main(["mechanism", "view", SQUARE, "--out", str(page), "--frames", "72", "--branch", "keep"]) == 0
    assert "keeping the assembly branch, the velocity jumps there" in capsys.readouterr().err
    assert main(["mechanism", "view", SQUARE, "--out", str(page), "--frames", "72", "--branch", "stop"]) == 0
    assert capsys.readouterr().err == "crank rocks between -90.000 and 270.000 deg: sweeping one oscillation\n"
