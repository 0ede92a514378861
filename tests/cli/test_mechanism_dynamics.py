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
    assert rows.shape == (72, len(head)) and head[:4] == ["t_s", "crank_deg", "crank_rad_s", "crank_torque_N_m"]
    assert "pin_A_x_N" in head and "guide_piston_normal_N" in head and "ground_fy_N" in head
    mech = Mechanism.load(ENGINE)
    q = np.radians(rows[:, 1])
    d = mech.inverse_dynamics(q, 100 * math.pi, 0.0)
    # written to 10 digits of the column's largest value (gearlever._format)
    assert np.allclose(rows[:, 3], d.input_force[:, 0], rtol=0, atol=1e-9 * np.abs(d.input_force[:, 0]).max())
    assert np.allclose(rows[:, 2], 100 * math.pi, rtol=1e-9)
    assert abs(rows[:, 3].mean()) < 1e-9 * np.abs(rows[:, 3]).max()


def test_forces_json_lists_indeterminate_pairs_of_the_planetary(capsys):
    planetary = str(Path(ENGINE).with_name("planetary.toml"))
    assert main(["mechanism", "forces", planetary, "--rpm", "60", "--points", "3", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert "mesh sun-p1" in data["indeterminate"] and len(data["rows"]) == 3
    assert data["rows"][0]["mesh_sun-p1_N"] is None and data["units"]["force"] == "N"


def test_simulate_with_zero_torque_conserves_kinetic_plus_potential_energy(tmp_path):
    """No input torque: kinetic energy plus the potential of the engine's conservative loads (1 kN on the
    piston along -x: 1000 x_B; the rod's weight: m g y_G, G a third of the way from A to B) is constant."""
    out = tmp_path / "sim.csv"
    assert main(["mechanism", "simulate", ENGINE, "--rpm", "600", "--time", "0.5", "--out", str(out)]) == 0
    head = out.read_text().splitlines()[0].split(",")
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    q, ke = np.radians(rows[:, head.index("crank_deg")]), rows[:, head.index("kinetic_energy_J")]
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
        (["forces", ENGINE, "--rpm", "10", "--points", "10000000"], "--points: must be at most 10^5"),
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


ZRDPM = Path(ENGINE).with_name("zrdpm_gear_contour.toml")


def _zrdpm_with_masses(tmp_path, extra_mech: str = "") -> str:
    """The shipped ZRDPM contour (inputs gear9, lever1) with masses, gravity and a torque on gear 8."""
    text = ZRDPM.read_text().replace('units = "mm"', 'units = "mm"\ngravity = [0.0, -9810.0]\n' + extra_mech)
    text += (
        "\n[masses]\n"
        "gear9 = { mass = 0.2, centre = [3.0, 1.0], inertia = 30.0 }\n"
        'gear8 = { mass = 0.3, centre = "C8", inertia = 50.0 }\n'
        "lever1 = { mass = 1.0, centre = [20.0, 4.0], inertia = 800.0 }\n"
        '\n[[loads]]\nlink = "gear8"\ntorque = -4000.0\n'
    )
    f = tmp_path / "zrdpm_masses.toml"
    f.write_text(text)
    return str(f)


def _csv(text):
    lines = text.strip().splitlines()
    return lines[0].split(","), np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])


def test_forces_two_inputs_named_rpm_match_lagrange_terms(capsys, tmp_path):
    """--rpm gear9=100 --rpm lever1=-30: rows span one turn of gear 9 (end excluded), lever 1 turns at its
    own speed; the torques equal b(q, q') of Lagrange's equations (virtual work, a separate computation
    from the CSV's equilibrium solve) to 1e-9, in N mm for a model in mm."""
    from gearlever.mechanism.dynamics import dynamic_terms

    model = _zrdpm_with_masses(tmp_path)
    argv = ["mechanism", "forces", model, "--rpm", "gear9=100", "--rpm", "lever1=-30", "--points", "36"]
    assert main(argv) == 0
    head, rows = _csv(capsys.readouterr().out)
    assert head[:7] == [
        "t_s",
        "gear9_deg",
        "gear9_rad_s",
        "lever1_deg",
        "lever1_rad_s",
        "gear9_torque_N_mm",
        "lever1_torque_N_mm",
    ]
    assert "mesh_z9-z8_N" in head and "pin_C8_x_N" in head
    assert rows.shape == (36, len(head))
    assert np.allclose(rows[:, 1], np.arange(36) * 10.0) and np.allclose(rows[:, 3], -0.3 * rows[:, 1], atol=1e-9)
    w = np.array([100.0, -30.0]) * math.pi / 30
    mech = Mechanism.load(model)
    _, b, _, ok = dynamic_terms(mech, np.radians(rows[:, [1, 3]]), w)
    assert ok.all()
    tau = rows[:, 5:7]
    assert np.allclose(tau, b, rtol=0, atol=1e-9 * np.abs(b).max())


def test_forces_without_rpm_reports_unit_speeds_and_says_so(capsys, tmp_path):
    model = _zrdpm_with_masses(tmp_path)
    assert main(["mechanism", "forces", model, "--points", "4", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["speeds"] == {"gear9": 1.0, "lever1": 1.0} and "1 rad/s" in data["speeds_note"]
    assert data["units"]["torque"] == "N_mm"
    assert all(r["gear9_rad_s"] == 1.0 and r["lever1_rad_s"] == 1.0 for r in data["rows"])


def test_forces_with_mesh_efficiency_reports_losses_and_power_balance(capsys, tmp_path):
    """--efficiency 0.95: a loss column (mW for N mm/s); input power plus the power of loads, weights
    and inertia forces (from the ideal run: tau_ideal . q' = -that power) equals the loss, >= 0."""
    model = _zrdpm_with_masses(tmp_path)
    base = ["mechanism", "forces", model, "--rpm", "gear9=100", "--rpm", "lever1=-30", "--points", "12"]
    assert main(base) == 0
    head0, ideal = _csv(capsys.readouterr().out)
    assert main(base + ["--efficiency", "0.95"]) == 0
    head, lossy = _csv(capsys.readouterr().out)
    assert "mesh_z9-z8_loss_mW" in head and "mesh_z9-z8_loss_mW" not in head0
    loss = lossy[:, head.index("mesh_z9-z8_loss_mW")]
    w = np.array([100.0, -30.0]) * math.pi / 30
    p_in = lossy[:, 5:7] @ w
    p_loads = -(ideal[:, 5:7] @ w)
    assert np.all(loss >= 0) and loss.max() > 0
    assert np.allclose(p_in + p_loads, loss, rtol=0, atol=1e-8 * np.abs(p_loads).max())


def test_simulate_two_inputs_energy_balance_in_the_csv(tmp_path):
    """--torque gear9=5000 for 0.2 s: the drivers' work is 5000 (q9 - q9_0) and the change of kinetic energy
    is the drivers' plus the loads' work (1e-8 relative); lever 1 free (torque 0)."""
    model = _zrdpm_with_masses(tmp_path)
    out = tmp_path / "sim.csv"
    argv = ["mechanism", "simulate", model, "--rpm", "gear9=100", "--rpm", "lever1=-30", "--torque", "gear9=5000"]
    assert main(argv + ["--time", "0.2", "--points", "11", "--out", str(out)]) == 0
    head, rows = _csv(out.read_text())
    col = {k: rows[:, i] for i, k in enumerate(head)}
    assert np.allclose(col["gear9_torque_N_mm"], 5000.0) and np.allclose(col["lever1_torque_N_mm"], 0.0)
    assert np.allclose(col["gear9_rpm"][0], 100.0) and np.allclose(col["lever1_rpm"][0], -30.0)
    ke, work, lw = col["kinetic_energy_mJ"], col["work_mJ"], col["load_work_mJ"]
    scale = np.abs(ke).max()
    assert np.allclose(work, 5000.0 * np.radians(col["gear9_deg"] - col["gear9_deg"][0]), rtol=0, atol=1e-8 * scale)
    assert np.allclose(ke - ke[0], work + lw, rtol=0, atol=1e-8 * scale)


@pytest.mark.parametrize(
    "args, needle",
    [
        (["forces", "{m}", "--rpm", "100"], "--rpm must be NAME=VALUE"),
        (["forces", "{m}", "--rpm", "gear=100", "--rpm", "lever1=1"], "--rpm: unknown input 'gear'"),
        (["forces", "{m}", "--rpm", "gear9=1", "--rpm", "gear9=2"], "--rpm: input 'gear9' given twice"),
        (["forces", "{m}", "--rpm", "gear9=1"], "--rpm: give every rotary input"),
        (["forces", "{m}", "--rpm", "gear9=x", "--rpm", "lever1=1"], "--rpm gear9"),
        (["forces", "{m}", "--speed", "gear9=1"], "--speed"),
        (["forces", "{m}", "--efficiency", "1.5"], "--efficiency"),
        (["simulate", "{m}", "--time", "1"], "--rpm"),
        (["simulate", "{m}", "--rpm", "gear9=1", "--time", "1"], "missing: lever1"),
        (["simulate", "{m}", "--rpm", "gear9=1", "--rpm", "lever1=1", "--torque", "z=1", "--time", "1"], "--torque"),
        (["simulate", "{m}", "--rpm", "gear9=1e9", "--rpm", "lever1=1", "--time", "1"], "--time"),
    ],
)
def test_two_input_bad_flags_exit_2_with_one_line_naming_the_flag(capsys, tmp_path, args, needle):
    model = _zrdpm_with_masses(tmp_path)
    assert main(["mechanism"] + [a.replace("{m}", model) for a in args]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


CRANK_AND_BLOCK = """
[mechanism]
name = "crank and slider block"
units = "mm"
gravity = [0.0, -9810.0]
[points]
O = [0.0, 0.0]
A = [10.0, 0.0]
S = [50.0, 0.0]
C = [30.0, 30.0]
[links]
ground = ["O"]
crank = ["O", "A"]
block = ["S"]
l1 = ["A", "C"]
l2 = ["S", "C"]
[[sliders]]
link = "block"
on = "ground"
point = "S"
direction = [1.0, 0.0]
[[inputs]]
link = "crank"
[[inputs]]
slider = "block"
[masses]
crank = { mass = 0.1, centre = "A", inertia = 1.0 }
block = { mass = 0.5, centre = "S" }
l1 = { mass = 0.2, centre = "C", inertia = 5.0 }
l2 = { mass = 0.2, centre = "C", inertia = 5.0 }
"""


def test_forces_rotary_and_slider_inputs_name_torque_and_force_columns(capsys, tmp_path):
    """A crank (--rpm) and a slider block (--speed, mm/s) as inputs: the crank torque in N mm, the block's
    driving force in N; both equal b(q, q') of Lagrange's equations (virtual work) to 1e-9."""
    from gearlever.mechanism.dynamics import dynamic_terms

    f = tmp_path / "crank_block.toml"
    f.write_text(CRANK_AND_BLOCK)
    assert main(["mechanism", "forces", str(f), "--rpm", "crank=60", "--speed", "block=5", "--points", "8"]) == 0
    head, rows = _csv(capsys.readouterr().out)
    assert head[:7] == [
        "t_s",
        "crank_deg",
        "crank_rad_s",
        "block_mm",
        "block_mm_s",
        "crank_torque_N_mm",
        "block_force_N",
    ]
    assert np.allclose(rows[:, 3], 5.0 * rows[:, 0])  # the block moves 5 mm/s over the crank's turn (1 s)
    q = np.column_stack([np.radians(rows[:, 1]), rows[:, 3]])
    _, b, _, ok = dynamic_terms(Mechanism.load(f), q, [2 * math.pi, 5.0])
    assert ok.all() and np.allclose(rows[:, 5:7], b, rtol=0, atol=1e-9 * np.abs(b).max())


def test_simulate_with_mesh_efficiency_reports_the_dissipated_energy(tmp_path):
    """[mechanism] mesh_efficiency = 0.95 in the model: a mesh_loss_work column; the kinetic energy changes by
    work + load work - mesh losses (1e-8), the losses grow."""
    model = _zrdpm_with_masses(tmp_path, "mesh_efficiency = 0.95\n")
    out = tmp_path / "lossy.csv"
    argv = ["mechanism", "simulate", model, "--rpm", "gear9=100", "--rpm", "lever1=-30", "--torque", "gear9=20000"]
    assert main(argv + ["--time", "0.05", "--points", "3", "--out", str(out)]) == 0
    head, rows = _csv(out.read_text())
    col = {k: rows[:, i] for i, k in enumerate(head)}
    ke, loss = col["kinetic_energy_mJ"], col["mesh_loss_work_mJ"]
    assert np.all(np.diff(loss) > 0)
    bal = ke - ke[0] - col["work_mJ"] - col["load_work_mJ"] + loss
    assert np.abs(bal).max() < 1e-8 * np.abs(ke).max()


def test_simulate_beyond_the_work_cap_is_refused_naming_time(capsys, monkeypatch):
    """A motion that needs more evaluations than the cap ends with exit 2 and one line naming --time."""
    import gearlever.mechanism.dynamics as dyn

    monkeypatch.setattr(dyn, "MAX_EVALS", 50)
    model = str(Path(__file__).resolve().parents[2] / "examples" / "fivebar_two_inputs.toml")
    code = main(
        ["mechanism", "simulate", model, "--rpm", "left=60", "--rpm", "right=0", "--time", "1", "--points", "3"]
    )
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--time" in err[0] and "50 evaluations" in err[0]


def test_forces_of_a_rocking_input_span_one_oscillation_at_its_speed(capsys):
    model = str(Path(__file__).resolve().parents[2] / "examples" / "watt_i.toml")
    assert main(["mechanism", "forces", model, "--rpm", "10", "--points", "40", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    assert err == "AB rocks between 67.284 and 78.254 deg: sweeping one oscillation\n"
    d = json.loads(out)
    rows = d["rows"]
    w = 10 * math.pi / 30
    assert [r["direction"] for r in rows][:2] == [1, 1] and {r["direction"] for r in rows} == {1, -1}
    assert all(r["AB_rad_s"] == pytest.approx(w * r["direction"], abs=1e-9) for r in rows)
    from gearlever.mechanism import input_limits
    from gearlever.mechanism.sweep import oscillation

    m = Mechanism.load(model)
    lim = input_limits(m)
    v, dirs = oscillation(lim.start, lim.lower, lim.upper, 40)
    f = m.inverse_dynamics(v[:, None], w * dirs[:, None], np.zeros((40, 1)))
    tq = f.input_force[:, 0]  # printed to the digits rule: relative to the column's largest value
    assert np.allclose([r["AB_torque_N_m"] for r in rows], tq, rtol=0, atol=1e-8 * np.abs(tq).max())
    # time: the path of the oscillation (twice the range) at the speed
    lim = d["oscillation"]
    assert rows[-1]["t_s"] == pytest.approx(2 * (lim["upper"] - lim["lower"]) / w * 39 / 40, rel=1e-9)


def test_simulate_of_a_rocking_input_stops_in_one_line_at_its_limit_never_hangs(capsys):
    model = str(Path(__file__).resolve().parents[2] / "examples" / "watt_i.toml")
    assert main(["mechanism", "simulate", model, "--rpm", "10", "--time", "1", "--points", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "of the limit 78.254 deg of AB" in err and "--time 1" in err
