"""Coulomb friction at pins and sliders: closed forms, the power balance, simulate's energy balance, bad input.

Checks against closed forms (a crank held against a load in its bearing; a
block pushed along a guide under a normal load), against the power balance
of the whole cycle (input power = power of loads, weights and inertia forces
+ power dissipated by the friction, independently of how the friction was
solved), and the friction circle ``rho = r sin(atan mu)`` of Uicker, Pennock
and Shigley, *Theory of Machines and Mechanisms*, 4th ed., section 13.8.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.friction import parse_friction

CRANK = {
    "points": {"O": [0.0, 0.0], "A": [2.0, 0.0]},
    "links": {"ground": ["O"], "crank": ["O", "A"]},
    "inputs": [{"link": "crank"}],
}
BLOCK = {
    "points": {"G": [0.0, -1.0], "B": [0.0, 0.0]},
    "links": {"ground": ["G"], "block": ["B"]},
    "sliders": [{"link": "block", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
    "inputs": [{"slider": "block"}],
}
SLIDER_CRANK_EXTRA = """
[masses]
crank = { mass = 0.5, centre = "O2", inertia = 1e-4 }
rod = { mass = 0.3, centre = [27.0, 2.5], inertia = 5e-5 }
piston = { mass = 0.4, centre = "B" }
[[loads]]
link = "piston"
point = "B"
force = [-500.0, 0.0]
[friction]
coefficient = 0.2
pin_radius = 3.0
"""


def slider_crank(extra=SLIDER_CRANK_EXTRA):
    return Mechanism.from_dict(tomllib.loads(example_path("slider_crank.toml").read_text() + extra))


@pytest.mark.parametrize("omega", [3.0, -3.0])
def test_a_crank_held_in_its_bearing_needs_the_friction_circle_moment_closed_form(omega):
    """Torque = F L + rho |R| (sign of the motion), rho = r sin(atan mu), R = F for a massless crank."""
    mu, r, F, L = 0.25, 0.1, 10.0, 2.0
    m = Mechanism.from_dict({**CRANK, "friction": {"coefficient": mu, "pin_radius": r}})
    d = m.inverse_dynamics([0.0], omega, 0.0, loads=[{"link": "crank", "point": "A", "force": [0.0, -F]}])
    rho = r * math.sin(math.atan(mu))
    assert d.input_force[0, 0] == pytest.approx(F * L + math.copysign(rho * F, omega), rel=1e-12)
    assert d.friction_torque["O"][0] == pytest.approx(-math.copysign(rho * F, omega), rel=1e-12)
    assert d.friction_loss["O"][0] == pytest.approx(rho * F * abs(omega), rel=1e-12)


@pytest.mark.parametrize("v", [0.5, -0.5])
def test_a_block_pushed_along_its_guide_needs_mu_times_the_normal_force_closed_form(v):
    mu, W, P = 0.3, 40.0, 5.0
    m = Mechanism.from_dict({**BLOCK, "friction": {"coefficient": mu}})
    loads = [{"link": "block", "point": "B", "force": [-P, -W]}]
    d = m.inverse_dynamics([0.0], v, 0.0, loads=loads)
    assert d.input_force[0, 0] == pytest.approx(P + math.copysign(mu * W, v), rel=1e-12)
    assert d.friction_force["block"][0] == pytest.approx(-math.copysign(mu * W, v), rel=1e-12)
    assert d.friction_loss["block"][0] == pytest.approx(mu * W * abs(v), rel=1e-12)


def test_the_power_balance_holds_over_the_cycle_with_pin_and_slider_friction():
    """sum tau qdot + power of loads, weights and inertia forces = dissipated power, row by row.

    The loads' and inertia forces' power is the frictionless input power (virtual work of the ideal
    mechanism), so the balance checks the friction solution independently of the fixed point.
    """
    m = slider_crank()
    q = np.linspace(0.0, 2 * np.pi, 181)[:-1]
    w = 50.0
    d = m.inverse_dynamics(q, w, 0.0)
    d0 = m.inverse_dynamics(q, w, 0.0, friction={})
    assert not d0.friction_loss and set(d.friction_loss) == {"O2", "A", "B", "piston"}
    loss = sum(d.friction_loss.values())
    assert np.all(loss >= 0) and loss.max() > 0
    balance = d.input_force[:, 0] * w - d0.input_force[:, 0] * w - loss
    assert np.abs(balance).max() <= 1e-10 * loss.max()
    # friction always costs input power
    assert np.all(d.input_force[:, 0] * w >= d0.input_force[:, 0] * w - 1e-9 * loss.max())


def test_friction_grows_with_the_coefficient_and_vanishes_at_zero():
    q = np.linspace(0.0, 2 * np.pi, 37)[:-1]
    losses = []
    for mu in (0.0, 0.05, 0.1, 0.2):
        m = slider_crank(SLIDER_CRANK_EXTRA.replace("coefficient = 0.2", f"coefficient = {mu}"))
        d = m.inverse_dynamics(q, 30.0, 0.0)
        losses.append(sum(d.friction_loss.values()).sum() if d.friction_loss else 0.0)
    assert losses[0] == 0.0 and losses[1] < losses[2] < losses[3]
    # small coefficients: the loss is nearly linear in mu (rho ~ mu r)
    assert losses[2] / losses[1] == pytest.approx(2.0, rel=0.05)


def test_simulate_with_friction_balances_energy():
    """A spinning crank with a mass and pin friction slows down; its kinetic energy goes to loss_work."""
    spec = {**CRANK, "friction": {"coefficient": 0.2, "pin_radius": 0.2}, "mechanism": {"gravity": [0.0, -9.81]}}
    m = Mechanism.from_dict(spec)
    masses = {"crank": {"mass": 2.0, "centre": "A", "inertia": 0.01}}
    s = m.simulate(np.linspace(0.0, 0.05, 6), [0.0], [20.0], torque=0.0, masses=masses, rtol=1e-8, atol=1e-10)
    assert np.all(np.diff(s.loss_work) > 0)
    balance = s.kinetic_energy - s.kinetic_energy[0] - (s.work + s.load_work - s.loss_work)
    assert np.abs(balance).max() <= 1e-6 * s.kinetic_energy[0]
    s0 = m.simulate(np.linspace(0.0, 0.05, 6), [0.0], [20.0], torque=0.0, masses=masses, friction={})
    assert s.qdot[-1, 0] < s0.qdot[-1, 0]


def test_the_friction_circle_is_r_sin_atan_mu():
    m = slider_crank()
    spec = parse_friction(m.model)
    mu, r, rho = spec.pins["A"]
    assert (mu, r) == (0.2, 3.0) and rho == pytest.approx(3.0 * 0.2 / math.sqrt(1.04), rel=1e-15)
    assert spec.sliders == {"piston": 0.2}


@pytest.mark.parametrize(
    "table, message",
    [
        ({"coefficient": -0.1, "pin_radius": 1}, "friction.coefficient must be from 0 to 1"),
        ({"coefficient": 7, "pin_radius": 1}, "friction.coefficient must be from 0 to 1"),
        ({"coefficient": 0.1, "pin_radius": 0}, "friction.pin_radius must be a positive length"),
        ({"coefficient": 0.1, "pin_radius": -2}, "friction.pin_radius must be a positive length"),
        ({"coefficient": 0.1}, "friction.pins.A: a coefficient without a journal radius"),
        ({"coefficent": 0.1}, "did you mean 'coefficient'"),
        ({"pins": {"Z": {"coefficient": 0.1}}}, "friction.pins: 'Z' is not a pin"),
        ({"pins": {"A": {"radius": "big"}}}, "friction.pins.A.radius must be a number"),
        ({"sliders": {"nope": {"coefficient": 0.1}}}, "friction.sliders: 'nope' is not a slider"),
        ({"sliders": {"piston": {"mu": 0.1}}}, "friction.sliders.piston: unknown key 'mu'"),
        ({"coefficient": True, "pin_radius": 1}, "friction.coefficient must be a number"),
    ],
)
def test_bad_friction_is_refused_naming_the_element(tmp_path, capsys, table, message):
    m = slider_crank("")
    with pytest.raises(GearleverError, match=message.replace("(", r"\(").replace(")", r"\)")):
        parse_friction(m.model, table)
    # the same in a model file: the CLI exits 2 with one line naming the element
    lines = ["[friction]"]
    for k, v in table.items():
        if isinstance(v, dict):
            continue
        lines.append(f"{k} = {str(v).lower() if isinstance(v, bool) else repr(v)}".replace("'", '"'))
    for sub in ("pins", "sliders"):
        for name, own in table.get(sub, {}).items():
            body = ", ".join(f"{k} = {repr(v)}".replace("'", '"') for k, v in own.items())
            lines.append(f"[friction.{sub}.{name}]\n{body.replace(', ', chr(10))}")
    path = tmp_path / "m.toml"
    path.write_text(example_path("slider_crank.toml").read_text() + "\n".join(lines) + "\n")
    assert main(["mechanism", "forces", str(path), "--points", "4"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "friction" in err


def test_forces_writes_the_friction_columns(tmp_path, capsys):
    path = tmp_path / "m.toml"
    path.write_text(example_path("slider_crank.toml").read_text() + SLIDER_CRANK_EXTRA)
    assert main(["mechanism", "forces", str(path), "--rpm", "300", "--points", "8", "--format", "json"]) == 0
    import json

    out = json.loads(capsys.readouterr().out)
    cols = out["columns"] if "columns" in out else out
    text = json.dumps(cols)
    for name in ("pin_A_friction_N_mm", "guide_piston_friction_N", "friction_loss_mW"):
        assert name in text, name
