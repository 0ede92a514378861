"""CLI runs: gearlever flywheel --torque-file F --rpm N (--fluctuation CS | --inertia I)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.cli.flywheel import read_torque_file


def _write(tmp_path, text, name="torque.csv"):
    f = tmp_path / name
    f.write_text(text)
    return str(f)


@pytest.fixture
def sine_file(tmp_path):
    """T = 1000 + 300 sin 2 theta over 0..360 deg, 1 deg steps, with a header and a comment."""
    deg = np.arange(0, 361)
    rows = "\n".join(f"{d},{1000 + 300 * math.sin(2 * math.radians(d))!r}" for d in deg)
    return _write(tmp_path, "# crank angle (deg), torque (N m)\nangle_deg,torque_Nm\n" + rows + "\n")


def test_flywheel_json_keys_and_closed_form(capsys, sine_file):
    """dE = 2 A / k = 300 J; I = dE / (w^2 Cs) at 250 rpm, Cs = 0.01."""
    assert (
        main(["flywheel", "--torque-file", sine_file, "--rpm", "250", "--fluctuation", "0.01", "--format", "json"]) == 0
    )
    data = json.loads(capsys.readouterr().out)
    for key in ("mean_torque", "power", "energy_fluctuation", "inertia", "fluctuation"):
        assert key in data
    assert data["energy_fluctuation"] == pytest.approx(300.0, rel=math.radians(1) ** 2)  # trapezoid error O(h^2)
    w = 250 * math.pi / 30
    assert data["inertia"] == pytest.approx(data["energy_fluctuation"] / (w**2 * 0.01), rel=1e-12)
    assert data["theta_max_speed_deg"] == pytest.approx(90.0, abs=1e-6)
    assert data["power"] == pytest.approx(1000 * w, rel=1e-9)


def test_flywheel_table_with_inertia_and_out_file(tmp_path, capsys, sine_file):
    out = tmp_path / "r.txt"
    assert main(["flywheel", "--torque-file", sine_file, "--rpm", "250", "--inertia", "40", "--out", str(out)]) == 0
    text = out.read_text()
    assert "energy fluctuation" in text and "fluctuation Cs" in text
    assert capsys.readouterr().out == ""


def test_flywheel_third_column_is_the_load(tmp_path, capsys):
    """Driving torque constant, load 1000 - 300 sin 2 theta: same dE as the sine file, mirrored."""
    rows = "\n".join(f"{d},1000,{1000 - 300 * math.sin(2 * math.radians(d))!r}" for d in range(0, 361))
    f = _write(tmp_path, rows)
    assert main(["flywheel", "--torque-file", f, "--rpm", "100", "--inertia", "10", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["energy_fluctuation"] == pytest.approx(300.0, rel=math.radians(1) ** 2)  # trapezoid error O(h^2)


def test_period_deg_closes_the_cycle(tmp_path, capsys):
    rows = "\n".join(f"{d},{100 + 50 * math.sin(math.radians(d))!r}" for d in range(0, 360, 5))
    f = _write(tmp_path, rows)
    args = ["flywheel", "--torque-file", f, "--rpm", "100", "--inertia", "1", "--format", "json"]
    assert main(args + ["--period-deg", "360"]) == 0
    assert json.loads(capsys.readouterr().out)["energy_fluctuation"] == pytest.approx(100.0, rel=1e-3)


@pytest.mark.parametrize(
    "text, extra, needle",
    [
        ("0,1\n90,x\n180,1\n", [], "row 2, column 2"),
        ("0,1\n90,2\n90,1\n", [], "row 3, column 1: crank angle must increase"),
        ("0,1\n90,2,3\n", [], "row 2: has 3 columns"),
        ("0\n90\n", [], "must have 2 or 3 columns"),
        ("0,1\n", [], "at least 2 rows"),
        ("0,1\n90,inf\n", [], "row 2, column 2"),
        ("0,1,5\n180,3,5\n360,1,5\n", [], "load: its mean"),
        ("0,1\n180,3\n360,1\n", ["--period-deg", "90"], "--period-deg"),
    ],
)
def test_bad_torque_file_exits_2_with_one_line(tmp_path, capsys, text, extra, needle):
    f = _write(tmp_path, text)
    assert main(["flywheel", "--torque-file", f, "--rpm", "100", "--inertia", "1"] + extra) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--rpm", "-5", "--inertia", "1"], "--rpm"),
        (["--rpm", "100", "--inertia", "0"], "--inertia"),
        (["--rpm", "100", "--inertia", "1", "--fluctuation", "0.1"], "not allowed with"),
        (["--rpm", "100"], "--fluctuation --inertia"),
    ],
)
def test_bad_flags_exit_2_naming_the_flag(tmp_path, capsys, args, needle):
    f = _write(tmp_path, "0,1\n180,3\n360,1\n")
    assert main(["flywheel", "--torque-file", f] + args) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_missing_file_and_row_cap(tmp_path, capsys):
    assert main(["flywheel", "--torque-file", str(tmp_path / "none.csv"), "--rpm", "1", "--inertia", "1"]) == 2
    assert "--torque-file" in capsys.readouterr().err
    f = _write(tmp_path, "0,1\n1,2\n2,3\n3,4\n")
    with pytest.raises(ValueError, match="more than 3 rows"):
        read_torque_file(f, max_rows=3)
