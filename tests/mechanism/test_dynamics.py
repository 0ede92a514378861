"""Mechanism inverse dynamics, reduced inertia and simulation: virtual work, equilibrium, closed forms."""

from __future__ import annotations

import math
import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.loads import metres_per_unit

from ._models import all_examples, example, sweep

GRAV = np.array([0.0, -9.81])


def _cross(r, f):
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def _rot(th, rho):
    c, s = np.cos(th), np.sin(th)
    return np.stack([c * rho[0] - s * rho[1], s * rho[0] + c * rho[1]], axis=-1)


def _random_setup(mech, n, rng):
    m = mech.model
    masses = {
        k: {"mass": rng.uniform(0.1, 2.0), "centre": m.links[k].points[-1], "inertia": rng.uniform(0.01, 1.0)}
        for k in m.moving
    }
    loads = []
    for k in m.moving:
        loads.append({"link": k, "point": m.links[k].points[0], "force": rng.normal(size=(n, 2))})
        loads.append({"link": k, "torque": rng.normal(size=n)})
    return masses, loads


def _body_point(r, mech, link, rho):
    """Position, velocity, acceleration of a body point computed from the link poses (independently)."""
    k = mech.model.moving.index(link)
    th = r.pose[:, k, 2]
    w, al = r.pose_velocity[:, k, 2], r.pose_acceleration[:, k, 2]
    R = _rot(th, rho)
    perp = np.stack([-R[:, 1], R[:, 0]], axis=1)
    return (
        r.pose[:, k, :2] + R,
        r.pose_velocity[:, k, :2] + w[:, None] * perp,
        r.pose_acceleration[:, k, :2] + al[:, None] * perp - (w * w)[:, None] * R,
    )


def _load_power_and_wrench(mech, r, masses, loads):
    """Power of loads, weights and inertia forces, and their total force and moment about the origin."""
    m = mech.model
    N = r.q.shape[0]
    P = np.zeros(N)
    F = np.zeros((N, 2))
    M = np.zeros(N)
    for ld in loads:
        k = m.moving.index(ld["link"])
        if "force" in ld:
            pos, vel, _ = _body_point(r, mech, ld["link"], m.links[ld["link"]].local[ld["point"]])
            f = np.broadcast_to(ld["force"], (N, 2))
            P += np.sum(f * vel, axis=1)
            F += f
            M += _cross(pos, f)
        if "torque" in ld:
            P += ld["torque"] * r.pose_velocity[:, k, 2]
            M += ld["torque"]
    si = metres_per_unit(m)  # masses and inertias in kg give forces in N (the library's unit rule)
    for link, ms in masses.items():
        k = m.moving.index(link)
        pos, vel, acc = _body_point(r, mech, link, m.links[link].local[ms["centre"]])
        f = si * ms["mass"] * (GRAV - acc)
        tq = -si * ms["inertia"] * r.pose_acceleration[:, k, 2]
        P += np.sum(f * vel, axis=1) + tq * r.pose_velocity[:, k, 2]
        F += f
        M += _cross(pos, f) + tq
    return P, F, M


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_virtual_work_and_whole_mechanism_equilibrium_every_shipped_model(path):
    """Input power = minus the power of loads, weights and inertia forces (1e-9 relative), and the frame's
    total force and moment balance loads, weights and inertia forces (1e-9 relative), for random loads."""
    mech = Mechanism.load(path)
    rng = np.random.default_rng(zlib.crc32(path.stem.encode()))
    q, qd = sweep(mech, 40)
    qdd = rng.normal(size=qd.shape)
    masses, loads = _random_setup(mech, q.shape[0], rng)
    d = mech.inverse_dynamics(q, qd, qdd, loads=loads, masses=masses, gravity=GRAV)
    assert d.ok.all()
    P, F, M = _load_power_and_wrench(mech, d.kinematics, masses, loads)
    scale = 1.0 + np.abs(P)
    assert np.all(np.abs(np.sum(d.input_force * qd, axis=1) + P) <= 1e-9 * scale)
    fscale = 1.0 + np.abs(F).max() + np.abs(M).max() / mech.model.length_scale
    assert np.allclose(d.ground_force + F, 0.0, atol=1e-9 * fscale, rtol=0)
    assert np.allclose(d.ground_moment + M, 0.0, atol=1e-9 * fscale * mech.model.length_scale, rtol=0)


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "whitworth", "watt_sixbar"])
def test_frame_reactions_reported_balance_the_loads(name):
    """Equilibrium from the reported pin and guide forces themselves (their documented signs): the frame's
    pins, guides and the input torque balance loads, weights and inertia forces (force and moment)."""
    mech = Mechanism.load(example(name))
    m = mech.model
    rng = np.random.default_rng(3)
    q, qd = sweep(mech, 30)
    qdd = rng.normal(size=qd.shape)
    masses, loads = _random_setup(mech, q.shape[0], rng)
    d = mech.inverse_dynamics(q, qd, qdd, loads=loads, masses=masses, gravity=GRAV)
    r = d.kinematics
    F = np.zeros((q.shape[0], 2))
    M = np.zeros(q.shape[0])
    for key, (a, b) in d.pins.items():
        p = key.split(":")[0]
        pos = r.point[p]
        if a == "ground":
            f = d.reaction[key]  # force on the second link from the first (the frame)
        elif b == "ground":
            f = -d.reaction[key]
        else:
            continue
        F += f
        M += _cross(pos, f)
    for s in m.sliders:
        if "ground" not in (s.on, s.link):
            continue
        n = np.array([-s.direction[1], s.direction[0]])  # the guide on ground does not turn
        f = d.slider_force[s.name][:, None] * n
        pos = r.point[s.point]
        sign = 1.0 if s.on == "ground" else -1.0
        F += sign * f
        M += sign * (_cross(pos, f) + d.slider_moment[s.name])
    for i, spec in enumerate(m.inputs):
        if spec.kind == "link" and (spec.relative_to or "ground") == "ground":
            M += d.input_force[:, i]
    P, Fl, Ml = _load_power_and_wrench(mech, r, masses, loads)
    scale = 1.0 + np.abs(Fl).max()
    assert np.allclose(F + Fl, 0.0, atol=1e-9 * scale, rtol=0)
    assert np.allclose(M + Ml, 0.0, atol=1e-9 * scale * m.length_scale, rtol=0)


def _inline_slider_crank(r, l):
    return Mechanism.from_dict(
        {
            "points": {"O": [0.0, 0.0], "A": [r, 0.0], "B": [r + l, 0.0]},
            "links": {"ground": ["O"], "crank": ["O", "A"], "rod": ["A", "B"], "piston": ["B"]},
            "sliders": [{"link": "piston", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
            "inputs": [{"link": "crank"}],
        }
    )


@settings(max_examples=30, deadline=None)
@given(st.floats(0.05, 0.5), st.floats(2.5, 6.0), st.floats(100.0, 1e5))
def test_slider_crank_crank_effort_and_side_thrust_closed_form(r, ratio, F):
    """Gas force F on the piston towards the crank, no masses.  The rod is a two-force member along its line
    (angle beta, sin beta = r sin theta / l): its thrust F / cos beta gives the crank torque
    T = F r sin(theta + beta) / cos beta (the motor must supply -T) and the guide's side thrust F tan beta."""
    l = ratio * r
    mech = _inline_slider_crank(r, l)
    th = np.linspace(0.1, 2 * np.pi - 0.1, 37)
    d = mech.inverse_dynamics(th, loads=[{"link": "piston", "point": "B", "force": [-F, 0.0]}])
    beta = np.arcsin(r * np.sin(th) / l)
    T = F * r * np.sin(th + beta) / np.cos(beta)
    assert np.allclose(d.input_force[:, 0], -T, rtol=1e-9, atol=1e-9 * F * r)
    assert np.allclose(np.abs(d.slider_force["piston"]), F * np.abs(np.tan(beta)), rtol=1e-9, atol=1e-9 * F)
    assert np.allclose(
        np.linalg.norm(d.reaction["B:rod-piston"] if "B:rod-piston" in d.reaction else d.reaction["B"], axis=1),
        F / np.cos(beta),
        rtol=1e-9,
    )


def test_rotating_crank_with_tip_mass_centripetal_reaction_and_gravity_torque():
    """Point mass m at radius R, uniform speed w: the frame pulls with m w^2 R toward the pivot plus the
    weight; the motor gives m g R cos(theta)."""
    mass, R, w = 2.0, 0.3, 12.0
    mech = Mechanism.from_dict(
        {
            "points": {"O": [0, 0], "A": [R, 0]},
            "links": {"ground": ["O"], "crank": ["O", "A"]},
            "inputs": [{"link": "crank"}],
        }
    )
    th = np.linspace(0, 2 * np.pi, 13)
    d = mech.inverse_dynamics(
        th, np.full_like(th, w), 0.0, masses={"crank": {"mass": mass, "centre": "A"}}, gravity=[0.0, -9.81]
    )
    radial = -mass * w * w * R * np.stack([np.cos(th), np.sin(th)], axis=1)
    assert np.allclose(d.reaction["O"], radial + [0.0, mass * 9.81], rtol=1e-12, atol=1e-12)
    assert np.allclose(d.input_force[:, 0], mass * 9.81 * R * np.cos(th), atol=1e-12)


def test_redundant_planetary_reports_undetermined_shares_and_determined_input():
    """Three planets share the load in a statically indeterminate way: their tooth and pin forces are NaN and
    listed, never guessed; the input torque is fixed by virtual work: sun torque = arm torque x z_s/(z_s+z_r)."""
    mech = Mechanism.load(example("planetary"))
    th = np.linspace(0, 1, 5)
    d = mech.inverse_dynamics(th, loads=[{"link": "arm", "torque": -100.0}])
    assert "mesh sun-p1" in d.indeterminate and "mesh p1-ring" in d.indeterminate
    assert np.all(np.isnan(d.mesh_force["sun-p1"]))
    assert np.allclose(d.input_force[:, 0], 100.0 * 24 / (24 + 60), rtol=1e-12)


def test_single_planet_tooth_forces_closed_form():
    """Sun 24, one planet 18, fixed ring 60 (module 2): arm torque T out means a tangential force
    T / (2 * 42) at each of the two meshes; the sun needs T * 24 / 84; the line-of-action force is F_t / cos 20."""
    d = {
        "mechanism": {"module": 2.0},
        "points": {"O": [0.0, 0.0], "P": [42.0, 0.0]},
        "links": {"ground": ["O"], "sun": ["O"], "arm": ["O", "P"], "planet": ["P"]},
        "gears": {
            "sun": {"link": "sun", "centre": "O", "teeth": 24},
            "ring": {"link": "ground", "centre": "O", "teeth": 60, "internal": True},
            "p": {"link": "planet", "centre": "P", "teeth": 18},
        },
        "meshes": [{"gears": ["sun", "p"]}, {"gears": ["p", "ring"]}],
        "inputs": [{"link": "sun"}],
    }
    mech = Mechanism.from_dict(d)
    T = 840.0
    res = mech.inverse_dynamics(np.linspace(0, 2, 7), loads=[{"link": "arm", "torque": -T}])
    assert res.indeterminate == ()
    Ft = T / (2 * 42.0)
    for name in ("sun-p", "p-ring"):
        assert np.allclose(np.abs(res.mesh_tangential[name]), Ft, rtol=1e-12)
        assert np.allclose(res.mesh_force[name], Ft / math.cos(math.radians(20)), rtol=1e-12)
    assert np.allclose(res.input_force[:, 0], T * 24 / 84, rtol=1e-12)
    # planet pin: the two tangential forces add (2 Ft), the radial ones cancel
    assert np.allclose(np.linalg.norm(res.reaction["P"], axis=1), 2 * Ft, rtol=1e-9)


def test_inverse_dynamics_torque_is_reduced_inertia_equation():
    """No loads: tau = J(q) q'' + J'(q) q'^2 / 2 (J' by central differences of reduced_inertia)."""
    mech = Mechanism.load(example("fourbar"))
    m = mech.model
    masses = {
        k: {"mass": 1.0 + i, "centre": m.links[k].points[-1], "inertia": 0.1 * (i + 1)} for i, k in enumerate(m.moving)
    }
    q0 = mech.sketch_inputs[0]
    q = q0 + np.linspace(0, 2 * np.pi, 25)[:-1]
    qd, qdd = 3.0, -1.7
    d = mech.inverse_dynamics(q, qd, qdd, masses=masses)
    h = 1e-5
    J = mech.reduced_inertia(q, masses=masses)
    dJ = (mech.reduced_inertia(q + h, masses=masses) - mech.reduced_inertia(q - h, masses=masses)) / (2 * h)
    assert np.allclose(d.input_force[:, 0], J * qdd + 0.5 * dJ * qd * qd, rtol=1e-7, atol=1e-7 * np.abs(J).max())


def _fourbar_masses(mech):
    m = mech.model
    return {k: {"mass": 1.0, "centre": m.links[k].points[-1], "inertia": 10.0} for k in m.moving}


def _kinetic_energy(mech, q, qd, masses):
    """Sum of m v_G^2 / 2 + I w^2 / 2 from the kinematic solution (not from the simulation's J table)."""
    r = mech.solve(q, qd)
    T = np.zeros(len(q))
    for link, ms in masses.items():
        k = mech.model.moving.index(link)
        _, v, _ = _body_point(r, mech, link, mech.model.links[link].local[ms["centre"]])
        T += 0.5 * ms["mass"] * np.sum(v * v, axis=1) + 0.5 * ms["inertia"] * r.pose_velocity[:, k, 2] ** 2
    return T


def test_free_motion_keeps_kinetic_energy_over_100_cycles():
    """No torque, no losses: the kinetic energy (from the kinematics, independently) is constant,
    relative drift < 1e-6 over more than 100 crank turns, while the speed itself varies."""
    mech = Mechanism.load(example("fourbar"))
    masses = _fourbar_masses(mech)
    q0 = mech.sketch_inputs[0]
    s = mech.simulate(np.linspace(0.0, 100.0, 801), q0, 2 * np.pi, torque=0.0, masses=masses)
    q, qd = s.q[:, 0], s.qdot[:, 0]
    assert (q[-1] - q0) / (2 * np.pi) > 100
    T = _kinetic_energy(mech, q, qd, masses)
    assert np.abs(T / T[0] - 1).max() < 1e-6
    assert qd.max() / qd.min() > 1.01


def test_simulate_driven_by_inverse_dynamics_torque_reproduces_uniform_motion():
    from scipy.interpolate import CubicSpline

    mech = Mechanism.load(example("fourbar"))
    masses = _fourbar_masses(mech)
    q0 = mech.sketch_inputs[0]
    w = 2 * np.pi
    qg = q0 + np.linspace(0, 2 * np.pi, 721)
    tau = mech.inverse_dynamics(qg, np.full_like(qg, w), 0.0, masses=masses).input_force[:, 0]
    spline = CubicSpline(qg, np.append(tau[:-1], tau[0]), bc_type="periodic")

    def torque(t, q, qd):
        return spline(q0 + np.mod(q - q0, 2 * np.pi))

    s = mech.simulate(np.linspace(0, 3, 61), q0, w, torque=torque, masses=masses)
    assert np.abs(s.qdot[:, 0] / w - 1).max() < 1e-6
    assert np.abs(s.q[:, 0] - (q0 + w * s.t)).max() < 1e-6


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(masses={"crank": {"mass": -1.0, "centre": "A"}}), "masses.crank.mass must be >= 0"),
        (dict(masses={"crank": {"mass": 1.0, "centre": "A", "inertia": -2}}), "masses.crank.inertia"),
        (dict(masses={"nope": {"mass": 1.0, "centre": "A"}}), "unknown link 'nope'"),
        (dict(masses={"crank": {"mass": 1.0, "centre": "B"}}), "point 'B' is not on link 'crank'"),
        (dict(loads=[{"link": "crank", "point": "Z", "force": [1, 0]}]), "point 'Z' is not on link"),
        (dict(loads=[{"link": "rod", "torque": 1.0}]), "unknown link 'rod'"),
        (dict(loads=[{"link": "crank", "point": "A", "force": [[1, 0]] * 5}]), "shape"),
        (dict(pressure_angle=1.2), "pressure_angle"),
    ],
)
def test_bad_masses_and_loads_are_refused_naming_them(kwargs, needle):
    mech = Mechanism.from_dict(
        {
            "points": {"O": [0, 0], "A": [2, 0], "B": [5, 5]},
            "links": {"ground": ["O", "B"], "crank": ["O", "A"]},
            "inputs": [{"link": "crank"}],
        }
    )
    with pytest.raises(GearleverError, match=needle):
        mech.inverse_dynamics([0.0, 0.5], **kwargs)
