"""CLI runs: gearlever mechanism forces|simulate on the shipped engine model."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.mechanism import Mechanism

ENGINE = str(Path(__file__).resolve().parents[2] / "examples" / "engine.toml")


def test_forces_csv_matches_the_api_and_virtual_work(capsys):
    """The CSV's input torque is the API's; with constant speed it equals minus the power of the piston
    load, the weights and the inertia forces per unit speed (checked here through energy: its mean over a
    turn is zero, since every load of the engine model is conservative and the speed is constant)."""
    assert main(["mechanism", "forces", ENGINE, "--rpm", "3000", "--points", "72"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    head = lines[0].split(",")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    assert rows.shape == (72, len(head)) and head[:2] == ["input_deg", "input_torque"]
    mech = Mechanism.load(ENGINE)
    q = np.radians(rows[:, 0])
    d = mech.inverse_dynamics(q, 100 * math.pi, 0.0)
    assert np.allclose(rows[:, 1], d.input_force[:, 0], rtol=1e-10, atol=1e-9)
    assert abs(rows[:, 1].mean()) < 1e-9 * np.abs(rows[:, 1]).max()


def test_forces_json_lists_indeterminate_pairs_of_the_planetary(capsys):
    planetary = str(Path(ENGINE).with_name("planetary.toml"))
    assert main(["mechanism", "forces", planetary, "--rpm", "60", "--points", "3", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert "mesh sun-p1" in data["indeterminate"] and len(data["rows"]) == 3
    assert data["rows"][0]["mesh_sun-p1"] is None


def test_simulate_with_zero_torque_conserves_kinetic_plus_potential_energy(tmp_path):
    """No input torque: kinetic energy plus the potential of the engine's conservative loads (1 kN on the
    piston along -x: 1000 x_B; the rod's weight: m g y_G, G a third of the way from A to B) is constant."""
    out = tmp_path / "sim.csv"
    assert main(["mechanism", "simulate", ENGINE, "--rpm", "600", "--time", "0.5", "--out", str(out)]) == 0
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    q, ke = np.radians(rows[:, 1]), rows[:, 4]
    r = Mechanism.load(ENGINE).solve(q)
    A, B = r.point["A"], r.point["B"]
    V = 1000.0 * B[:, 0] + 1.2 * 9.81 * (A + (B - A) / 3)[:, 1]
    E = ke + V
    assert np.abs(E - E[0]).max() < 1e-6 * ke.max()
    assert ke.max() > 1.5 * ke.min()  # the speed fluctuates though


@pytest.mark.parametrize(
    "args, needle",
    [
        (["forces", ENGINE, "--rpm", "x"], "--rpm"),
        (["forces", ENGINE, "--rpm", "10", "--points", "0"], "--points"),
        (["forces", ENGINE, "--rpm", "10", "--points", "10000000"], "--points must be at most"),
        (["simulate", ENGINE, "--rpm", "3000", "--time", "1e6"], "--time"),
        (["simulate", ENGINE, "--rpm", "3000", "--time", "-1"], "--time"),
        (["forces", "missing.toml", "--rpm", "10"], "missing.toml"),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, args, needle):
    assert main(["mechanism"] + args) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_bad_model_masses_exit_2_naming_the_element(capsys, tmp_path):
    text = Path(ENGINE).read_text().replace("mass = 1.2", "mass = -1.2")
    f = tmp_path / "bad.toml"
    f.write_text(text)
    assert main(["mechanism", "forces", str(f), "--rpm", "10"]) == 2
    err = capsys.readouterr().err
    assert "masses.rod.mass must be >= 0" in err and err.count("\n") == 1
