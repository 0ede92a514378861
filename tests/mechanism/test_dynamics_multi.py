"""Mechanism dynamics with several inputs (W = 2): virtual work, Lagrange's equations, energy, mesh losses.

Models: the five-bar with two cranks (examples/fivebar_two_inputs.toml), the ZRDPM gear contour
(gear 9 and lever 1 as inputs, a gear pair on a moving carrier) with masses added here, the geared
five-bar (one input, the gear pair makes it non-periodic over a crank turn), and a two-stage
planetary train (Wolfrom type, ratio -2/49) for the mesh efficiency.
"""

from __future__ import annotations

import math
import tomllib
from fractions import Fraction

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.gears.networks import Gear, Mesh, Network, SameShaft
from gearlever.gears.torques import network_torques
from gearlever.mechanism import Mechanism
from gearlever.mechanism.dynamics import dynamic_terms
from gearlever.mechanism.loads import metres_per_unit

from ._models import example
from .test_dynamics import _body_point

G_MM = np.array([0.0, -9810.0])

ZRDPM_MASSES = {
    "gear9": {"mass": 0.2, "centre": [3.0, 1.0], "inertia": 30.0},
    "gear8": {"mass": 0.3, "centre": [47.0, -2.0], "inertia": 50.0},
    "lever1": {"mass": 1.0, "centre": [20.0, 4.0], "inertia": 800.0},
}


def _zrdpm(**mech_keys):
    d = tomllib.loads(example("zrdpm_gear_contour").read_text())
    d["mechanism"].update(mech_keys)
    d["masses"] = ZRDPM_MASSES
    return Mechanism.from_dict(d)


def _fivebar():
    return Mechanism.load(example("fivebar_two_inputs"))


def _local(mech, link, c):
    """Body-fixed coordinates of a point name or a sketch location [x, y] of ``link`` (independent of loads.py)."""
    lk = mech.model.links[link]
    if isinstance(c, str):
        return np.asarray(lk.local[c], dtype=float)
    d = np.asarray(c, dtype=float) - np.asarray(lk.origin, dtype=float)
    co, si = math.cos(lk.angle0), math.sin(lk.angle0)
    return np.array([co * d[0] + si * d[1], -si * d[0] + co * d[1]])


def _power(mech, r, masses, loads, g):
    """Power of the loads, weights and d'Alembert inertia forces, from the link poses and their rates."""
    m = mech.model
    P = np.zeros(r.q.shape[0])
    si = metres_per_unit(m)  # kg and kg u^2 give forces in N (the library's unit rule)
    for ld in loads:
        if "force" in ld:
            _, vel, _ = _body_point(r, mech, ld["link"], _local(mech, ld["link"], ld["point"]))
            P += vel @ np.asarray(ld["force"], dtype=float)
        if "torque" in ld:
            P += ld["torque"] * r.pose_velocity[:, m.moving.index(ld["link"]), 2]
    for link, ms in masses.items():
        k = m.moving.index(link)
        _, vel, acc = _body_point(r, mech, link, _local(mech, link, ms["centre"]))
        f = si * ms["mass"] * (np.asarray(g, dtype=float) - acc)
        P += (
            np.sum(f * vel, axis=1)
            - si * ms.get("inertia", 0.0) * r.pose_acceleration[:, k, 2] * r.pose_velocity[:, k, 2]
        )
    return P


def _masses_or(mech):
    return ZRDPM_MASSES if "ZRDPM" in mech.name else mech.model.extra["masses"]


def _potential(mech, q, masses, g, loads=()):
    """Potential energy of the weights (- m g . x_G) and constant point forces (- F . x_P), from positions."""
    r = mech.solve(q)
    V = np.zeros(r.q.shape[0])
    si = metres_per_unit(mech.model)
    for link, ms in masses.items():
        pos, _, _ = _body_point(r, mech, link, _local(mech, link, ms["centre"]))
        V -= si * ms["mass"] * pos @ g
    for ld in loads:
        pos, _, _ = _body_point(r, mech, ld["link"], _local(mech, ld["link"], ld["point"]))
        V -= pos @ np.asarray(ld["force"], dtype=float)
    return V


def _rows(mech, n, seed):
    rng = np.random.default_rng(seed)
    q = mech.sketch_inputs[None, :] + rng.uniform(-3.0, 3.0, (n, 2))
    return q, rng.normal(0.0, 3.0, (n, 2)), rng.normal(0.0, 5.0, (n, 2))


# ------------------------------------------------------------------ inverse dynamics, two inputs


@pytest.mark.parametrize("which", ["fivebar", "zrdpm"])
def test_two_input_torques_satisfy_virtual_work(which):
    """sum tau_i qdot_i = -(power of loads, weights and d'Alembert inertia forces), computed independently
    from the link poses, at 40 random rows with random speeds and accelerations of both inputs (1e-10)."""
    mech = _fivebar() if which == "fivebar" else _zrdpm()
    masses = _masses_or(mech)
    q, qd, qdd = _rows(mech, 40, 7)
    link = mech.model.moving[-1]
    loads = [
        {"link": link, "point": mech.model.links[link].points[0], "force": [120.0, -340.0]},
        {"link": mech.model.moving[0], "torque": 2500.0},
    ]
    d = mech.inverse_dynamics(q, qd, qdd, loads=loads, masses=masses, gravity=G_MM)
    assert d.ok.all() and d.input_force.shape == (40, 2)
    P = _power(mech, d.kinematics, masses, loads, G_MM)
    resid = np.abs(np.sum(d.input_force * qd, axis=1) + P)
    assert np.all(resid <= 1e-10 * (1.0 + np.abs(P)))


@pytest.mark.parametrize("which", ["fivebar", "zrdpm"])
def test_inverse_dynamics_is_mass_matrix_times_acceleration_plus_b(which):
    """tau = M(q) q'' + b(q, q') (Lagrange's equations in the inputs) at random rows, and M equals the
    reduced-inertia mass matrix, symmetric positive definite."""
    mech = _fivebar() if which == "fivebar" else _zrdpm()
    q, qd, qdd = _rows(mech, 30, 11)
    d = mech.inverse_dynamics(q, qd, qdd)
    M, b, _, ok = dynamic_terms(mech, q, qd)
    assert ok.all()
    tau = np.einsum("nij,nj->ni", M, qdd) + b
    assert np.allclose(tau, d.input_force, rtol=0, atol=1e-11 * np.abs(d.input_force).max())
    assert np.allclose(M, mech.reduced_inertia(q), rtol=1e-12, atol=0)
    assert np.allclose(M, np.transpose(M, (0, 2, 1)), rtol=0, atol=1e-12 * np.abs(M).max())
    assert np.all(np.linalg.eigvalsh(M)[:, 0] > 0)


@pytest.mark.parametrize("which", ["fivebar", "zrdpm"])
def test_velocity_terms_are_christoffel_terms_of_the_mass_matrix_by_finite_differences(which):
    """No loads, no gravity: b_i = sum_jk (dM_ij/dq_k - dM_jk/dq_i / 2) q'_j q'_k (Lagrange), with dM/dq by
    central differences (h = 1e-5) of the mass matrix; agreement 1e-6 relative."""
    mech = _fivebar() if which == "fivebar" else _zrdpm()
    masses = _masses_or(mech)
    q, qd, _ = _rows(mech, 12, 3)
    _, b, _, _ = dynamic_terms(mech, q, qd, masses=masses, loads=[], gravity=[0.0, 0.0])
    h = 1e-5
    dM = np.zeros((q.shape[0], 2, 2, 2))  # [n, i, j, k] = dM_ij / dq_k
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        dM[..., k] = (mech.reduced_inertia(q + e, masses=masses) - mech.reduced_inertia(q - e, masses=masses)) / (2 * h)
    c = np.einsum("nijk,nj,nk->ni", dM, qd, qd) - 0.5 * np.einsum("njki,nj,nk->ni", dM, qd, qd)
    assert np.abs(c).max() > 1e-3 * np.abs(b).max() > 0  # the terms are not trivially zero
    assert np.allclose(b, c, rtol=0, atol=1e-6 * np.abs(b).max())


# ------------------------------------------------------------------ simulation, two inputs


@pytest.mark.parametrize("which", ["fivebar", "zrdpm"])
def test_free_motion_conserves_kinetic_plus_potential_energy(which):
    """No driving torques, gravity and (five-bar) a constant point force: T + V is constant (relative
    1e-8 of T), with V computed from the positions of the centres of mass and of the load's point."""
    mech = _fivebar() if which == "fivebar" else _zrdpm(gravity=[0.0, -9810.0])
    s = mech.simulate(np.linspace(0.0, 0.2, 11), mech.sketch_inputs, [6.0, -4.0])
    masses = _masses_or(mech)
    loads = mech.model.extra.get("loads", [])
    V = _potential(mech, s.q, masses, np.asarray(mech.model.extra["gravity"], float), loads)
    E = s.kinetic_energy + V
    assert np.abs(E - E[0]).max() < 1e-8 * s.kinetic_energy.max()
    assert np.allclose(s.load_work, -(V - V[0]), rtol=0, atol=1e-8 * s.kinetic_energy.max())
    assert s.kinetic_energy.max() > 1.2 * s.kinetic_energy.min()  # the speeds do change


@pytest.mark.parametrize("which", ["fivebar", "zrdpm"])
def test_work_of_constant_torques_is_the_change_of_energy(which):
    """Constant torques tau: their work is tau . (q - q0) (independently of the integrated work) and equals
    the change of kinetic plus potential energy (relative 1e-8)."""
    mech = _fivebar() if which == "fivebar" else _zrdpm(gravity=[0.0, -9810.0])
    labels = [s.label for s in mech.model.inputs]
    tau = np.array([3.0, -1.5])  # N mm
    s = mech.simulate(np.linspace(0.0, 0.25, 11), mech.sketch_inputs, [2.0, 1.0], torque=dict(zip(labels, tau)))
    work = (s.q - s.q[0]) @ tau
    masses = _masses_or(mech)
    V = _potential(mech, s.q, masses, np.asarray(mech.model.extra["gravity"], float), mech.model.extra.get("loads", []))
    scale = np.abs(work).max() + s.kinetic_energy.max()
    assert np.allclose(s.work, work, rtol=0, atol=1e-9 * scale)
    assert np.allclose(s.kinetic_energy - s.kinetic_energy[0] + V - V[0], work, rtol=0, atol=1e-8 * scale)
    assert np.allclose(s.torque, tau)


def test_inverse_dynamics_torques_drive_both_inputs_at_constant_speed():
    """Driving each input with the inverse-dynamics torque for constant speeds (a callable of q) gives
    q = q0 + w t for both inputs (1e-7 rad over 0.6 s)."""
    mech = _fivebar()
    w = np.array([5.0, -3.0])

    def torque(t, q, qd):
        return dynamic_terms(mech, q[None, :], w)[1][0]

    s = mech.simulate(np.linspace(0.0, 0.6, 13), mech.sketch_inputs, w, torque=torque)
    assert np.abs(s.q - (mech.sketch_inputs + s.t[:, None] * w)).max() < 1e-7
    assert np.abs(s.qddot).max() < 1e-5


def test_one_input_geared_fivebar_repeating_after_three_turns_conserves_energy():
    """The geared five-bar repeats after three crank turns only (gear ratio 2/3): simulate tabulates over
    three turns; with no torque and no gravity the kinetic energy (from the kinematics, independently)
    is constant to 1e-8 over 1 s (more than a crank turn)."""
    mech = Mechanism.load(example("geared_fivebar"))
    masses = {k: {"mass": 0.1, "centre": mech.model.links[k].points[-1], "inertia": 20.0} for k in mech.model.moving}
    s = mech.simulate(np.linspace(0.0, 1.0, 11), mech.sketch_inputs, 8.0, masses=masses)
    assert s.q.shape == (11, 1) and s.q[-1, 0] - s.q[0, 0] > 2 * np.pi
    r = mech.solve(s.q, s.qdot)
    T = np.zeros(len(s.t))
    for link, ms in masses.items():
        k = mech.model.moving.index(link)
        _, v, _ = _body_point(r, mech, link, mech.model.links[link].local[ms["centre"]])
        T += 0.5 * ms["mass"] * np.sum(v * v, axis=1) + 0.5 * ms["inertia"] * r.pose_velocity[:, k, 2] ** 2
    T *= metres_per_unit(mech.model)  # kg mm^2/s^2 to N mm
    assert np.abs(T / T[0] - 1).max() < 1e-8
    assert np.allclose(s.kinetic_energy, T, rtol=1e-9)
    assert np.ptp(s.qdot) > 1e-3 * s.qdot.max()  # the speed varies though


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(torque={"crank": 1.0}), "unknown input 'crank'"),
        (dict(torque=5.0), "torque must be"),
        (dict(q0=[0.0]), "q0 must be 2"),
        (dict(max_evals=20), "max_evals = 20"),
        (dict(efficiency={"z9": 0.9}), "unknown mesh 'z9'"),
    ],
)
def test_simulate_refuses_bad_input_naming_it(kwargs, needle):
    mech = _zrdpm()
    args = dict(t=np.linspace(0.0, 1.0, 5), q0=mech.sketch_inputs, qdot0=[1.0, 2.0])
    args.update(kwargs)
    with pytest.raises(GearleverError, match=needle):
        mech.simulate(**args)


# ------------------------------------------------------------------ mesh efficiency


def _wolfrom(driven_by: str, eta):
    """Sun 51 held, compound planet 49/50 on the carrier, output sun 50: w_out = -2/49 w_carrier."""
    return Mechanism.from_dict(
        {
            "mechanism": {"units": "mm", "module": 1.0, "mesh_efficiency": eta},
            "points": {"O": [0, 0], "P": [50, 0]},
            "links": {"ground": ["O"], "carrier": ["O", "P"], "planet": ["P"], "out": ["O"]},
            "gears": {
                "s1": {"link": "ground", "centre": "O", "teeth": 51},
                "p1": {"link": "planet", "centre": "P", "teeth": 49},
                "p2": {"link": "planet", "centre": "P", "teeth": 50},
                "s2": {"link": "out", "centre": "O", "teeth": 50},
            },
            "meshes": [{"gears": ["s1", "p1"]}, {"gears": ["s2", "p2"]}],
            "inputs": [{"link": driven_by}],
        }
    )


def _wolfrom_network():
    return Network(
        [Gear("s1", 51), Gear("p1", 49), Gear("p2", 50), Gear("s2", 50), Gear("arm")],
        [
            SameShaft("fix", "s1", "frame"),
            Mesh("m1", "s1", "p1", carrier="arm"),
            Mesh("m2", "s2", "p2", carrier="arm"),
            SameShaft("pl", "p1", "p2"),
        ],
    )


@pytest.mark.parametrize("eta", ["1", "0.99", "0.9"])
def test_mesh_losses_match_the_gear_network_torques(eta):
    """Carrier driven, output sun loaded by 1000 (against its motion): the carrier torque equals the exact
    lossy gear-network result (gearlever.gears.torques, same efficiency concept) to 1e-10; input power
    minus output power equals the meshes' losses, which are >= 0."""
    mech = _wolfrom("carrier", float(Fraction(eta)))
    q = np.linspace(0.0, 2.0, 5)
    d = mech.inverse_dynamics(q, 1.0, 0.0, loads=[{"link": "out", "torque": 1000.0}])
    ref = network_torques(_wolfrom_network(), {"s2": 1000}, ["arm"], speeds={"arm": 1}, efficiency=Fraction(eta))
    assert np.allclose(d.input_force[:, 0], float(ref.torques["arm"]), rtol=1e-10)
    p_in = d.input_force[:, 0] * 1.0
    p_out = -1000.0 * (-2.0 / 49.0)  # power taken by the load
    loss = sum(d.mesh_loss.values())
    assert np.allclose(p_in - p_out, loss, rtol=1e-10, atol=1e-9)
    assert all(np.all(v >= 0) for v in d.mesh_loss.values())
    assert (eta == "1") == np.allclose(loss, 0.0)


def test_train_driven_from_its_output_self_locks_and_is_reported():
    """Driven from the output sun at efficiency 0.9 the train self-locks (the network code says so too);
    at 0.99 it runs backwards with the network's torque."""
    q = np.linspace(0.0, 1.0, 3)
    loads = [{"link": "carrier", "torque": 1000.0}]
    with pytest.raises(GearleverError, match="self-locking"):
        _wolfrom("out", 0.9).inverse_dynamics(q, 1.0, 0.0, loads=loads)
    with pytest.raises(GearleverError, match="self-locks"):
        network_torques(_wolfrom_network(), {"arm": 1000}, ["s2"], speeds={"s2": 1}, efficiency=Fraction("0.9"))
    d = _wolfrom("out", 0.99).inverse_dynamics(q, 1.0, 0.0, loads=loads)
    ref = network_torques(_wolfrom_network(), {"arm": 1000}, ["s2"], speeds={"s2": 1}, efficiency=Fraction("0.99"))
    assert np.allclose(d.input_force[:, 0], float(ref.torques["s2"]), rtol=1e-10)


def test_two_input_power_balance_with_mesh_losses_on_the_zrdpm():
    """ZRDPM with masses, gravity, a torque on gear 8 and mesh efficiency 0.97: sum tau_i qdot_i plus the
    power of loads, weights and inertia forces equals the mesh loss, >= 0 (1e-9), at random rows with
    both inputs moving; with efficiency 1 the loss is zero and the torques are the ideal ones."""
    mech = _zrdpm(mesh_efficiency=0.97, gravity=[0.0, -9810.0])
    masses = ZRDPM_MASSES
    q, qd, qdd = _rows(mech, 40, 5)
    loads = [{"link": "gear8", "torque": -4000.0}]
    d = mech.inverse_dynamics(q, qd, qdd, loads=loads, masses=masses)
    P = _power(mech, d.kinematics, masses, loads, G_MM)
    loss = d.mesh_loss["z9-z8"]
    scale = 1.0 + np.abs(P).max()
    assert np.allclose(np.sum(d.input_force * qd, axis=1) + P, loss, rtol=0, atol=1e-9 * scale)
    assert np.all(loss >= 0) and loss.max() > 1e-3 * scale
    ideal = mech.inverse_dynamics(q, qd, qdd, loads=loads, masses=masses, efficiency=1.0)
    assert np.all(ideal.mesh_loss["z9-z8"] == 0)
    assert np.allclose(np.sum(ideal.input_force * qd, axis=1) + P, 0.0, rtol=0, atol=1e-9 * scale)
    assert np.abs(ideal.input_force - d.input_force).max() > 1e-4 * np.abs(d.input_force).max()


def test_per_mesh_efficiency_in_the_model_and_bad_values_refused():
    d = tomllib.loads(example("zrdpm_gear_contour").read_text())
    d["meshes"][0]["efficiency"] = 0.95
    mech = Mechanism.from_dict(d)
    assert mech.model.meshes[0].efficiency == 0.95
    from gearlever.mechanism.loads import mesh_efficiency_of

    assert mesh_efficiency_of(mech.model) == {"z9-z8": 0.95}
    d["meshes"][0]["efficiency"] = 1.5
    with pytest.raises(GearleverError, match=r"meshes\[0\] \(z9-z8\).efficiency must be in \(0, 1\]"):
        Mechanism.from_dict(d)
    d["meshes"][0].pop("efficiency")
    d["mechanism"]["mesh_efficiency"] = 0.0
    with pytest.raises(GearleverError, match=r"mechanism.mesh_efficiency must be in \(0, 1\]"):
        Mechanism.from_dict(d).inverse_dynamics([[0.0, 0.0]])
    with pytest.raises(GearleverError, match="unknown mesh 'nope'"):
        mech.inverse_dynamics([[0.0, 0.0]], efficiency={"nope": 0.9})


def test_rates_broadcast_per_input_row():
    """qdot given as one row (W,) is every row's; a wrong shape is refused naming qdot."""
    mech = _zrdpm()
    q = mech.sketch_inputs[None, :] + np.linspace(0, 1, 4)[:, None]
    a = mech.inverse_dynamics(q, [2.0, -1.0], [0.5, 0.0])
    b = mech.inverse_dynamics(q, np.tile([2.0, -1.0], (4, 1)), np.tile([0.5, 0.0], (4, 1)))
    assert np.array_equal(a.input_force, b.input_force)
    with pytest.raises(GearleverError, match="qdot must be"):
        mech.inverse_dynamics(q, [1.0, 2.0, 3.0])
    assert math.isfinite(float(a.input_force.sum()))


def test_simulation_with_mesh_losses_balances_energy_and_satisfies_lossy_inverse_dynamics():
    """ZRDPM, efficiency 0.95, gear 9 driven by 20 N mm, lever 1 free, gravity: T - T0 = work + load work
    - losses (1e-8 of T), losses never decrease; the lossy inverse dynamics at the simulated states (q, q', q'')
    gives back the applied torques (1e-9 relative); the run ends slower than the ideal one."""
    mech = _zrdpm(mesh_efficiency=0.95, gravity=[0.0, -9810.0])
    t = np.linspace(0.0, 0.1, 5)
    s = mech.simulate(t, mech.sketch_inputs, [10.0, -3.0], torque={"gear9": 20.0})
    bal = s.kinetic_energy - s.kinetic_energy[0] - s.work - s.load_work + s.loss_work
    assert np.abs(bal).max() < 1e-8 * s.kinetic_energy.max()
    assert s.loss_work[-1] > 1e-3 * s.work[-1] > 0 and np.all(np.diff(s.loss_work) >= 0)
    d = mech.inverse_dynamics(s.q, s.qdot, s.qddot)
    assert np.allclose(d.input_force, s.torque, rtol=0, atol=1e-9 * 20.0)
    ideal = mech.simulate(t, mech.sketch_inputs, [10.0, -3.0], torque={"gear9": 20.0}, efficiency=1.0)
    assert np.all(ideal.loss_work == 0) and s.kinetic_energy[-1] < ideal.kinetic_energy[-1]


def test_simulation_of_a_train_driven_from_its_output_self_locks_at_low_efficiency():
    masses = {
        "carrier": {"mass": 1.0, "centre": "P", "inertia": 100.0},
        "planet": {"mass": 0.2, "centre": "P", "inertia": 10.0},
        "out": {"mass": 0.5, "centre": "O", "inertia": 50.0},
    }
    t = np.linspace(0.0, 0.05, 3)
    s = _wolfrom("out", 0.99).simulate(t, [0.0], 0.1, torque=1000.0, masses=masses)
    assert np.all(np.diff(s.qdot[:, 0]) > 0) and s.loss_work[-1] > 0
    with pytest.raises(GearleverError, match="self-locking"):
        _wolfrom("out", 0.9).simulate(t, [0.0], 0.1, torque=1000.0, masses=masses)
