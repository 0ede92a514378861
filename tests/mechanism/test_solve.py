"""Kinematics of mechanism models: agreement with closed forms, Willis, the `mechanism` package, finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gearlever
from gearlever.gears.willis import driven_speed
from gearlever.loops import fourbar, slider_crank
from gearlever.mechanism.constraints import constraint_residual

from ._models import all_examples, example, sweep, wrap

FOURBAR = dict(
    ground=40.0, crank=10.0, coupler=math.dist((10, 0), (45.1, 28.3)), rocker=math.dist((40, 0), (45.1, 28.3))
)


def test_fourbar_model_agrees_with_closed_form_fourbar():
    m = gearlever.Mechanism.load(example("fourbar"))
    th = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    r = m.solve(th)
    f = fourbar(FOURBAR["ground"], FOURBAR["crank"], FOURBAR["coupler"], FOURBAR["rocker"], th)
    assert r.closed.all() and f.valid.all()
    assert np.abs(wrap(r.angle["coupler"] - f.theta3)).max() < 1e-9
    assert np.abs(wrap(r.angle["rocker"] - f.theta4)).max() < 1e-9
    assert np.abs(r.omega["coupler"] - f.dtheta3_dphi).max() < 1e-7
    assert np.abs(r.omega["rocker"] - f.dtheta4_dphi).max() < 1e-7
    assert np.abs(r.alpha["coupler"] - f.d2theta3_dphi2).max() < 1e-7
    assert np.abs(r.alpha["rocker"] - f.d2theta4_dphi2).max() < 1e-7


def test_offset_slider_crank_agrees_with_its_closed_form():
    m = gearlever.Mechanism.load(example("slider_crank"))
    th = np.linspace(0.0, 2 * np.pi, 721)
    r = m.solve(th)
    s = slider_crank(10.0, 35.0, th, offset=5.0)
    assert r.closed.all()
    assert np.abs(wrap(r.angle["rod"] - s["theta3"])).max() < 1e-9
    assert np.abs(r.point["B"][:, 0] - s["x_B"]).max() < 1e-9
    assert np.abs(r.velocity["B"][:, 0] - s.d1("x_B")).max() < 1e-7
    assert np.abs(r.acceleration["B"][:, 0] - s.d2("x_B")).max() < 1e-7
    assert np.abs(r.displacement["piston"] - (s["x_B"] - s["x_B"][0])).max() < 1e-9


def test_simple_planetary_agrees_with_willis():
    m = gearlever.Mechanism.load(example("planetary"))
    q = np.linspace(0.0, 4 * np.pi, 50)
    r = m.solve(q, qdot=np.full(50, 2.0))
    # ring fixed: (0 - w_arm) / (w_sun - w_arm) = -z_sun / z_ring
    w_arm = r.omega["arm"]
    assert np.allclose(driven_speed(2.0, w_arm, 24 / 60, "external") * 0 + w_arm, 2.0 * 24 / 84, atol=1e-12)
    w_p = driven_speed(2.0, w_arm, 24 / 18, "external")
    for k in (1, 2, 3):
        assert np.allclose(r.omega[f"planet{k}"], w_p, atol=1e-12)
    assert np.allclose(r.angle["arm"] - r.angle["arm"][0], (q - q[0]) * 24 / 84, atol=1e-12)


def test_compound_planetary_agrees_with_willis():
    m = gearlever.Mechanism.load(example("compound_planetary"))
    r = m.solve(np.linspace(0.0, 2 * np.pi, 20))
    w_planet = driven_speed(0.0, 1.0, 90 / 30, "internal")  # ring (lead) fixed, arm carrier
    w_sun = driven_speed(w_planet, 1.0, 20 / 40, "external")
    assert np.allclose(r.omega["planet"], w_planet, atol=1e-12)
    assert np.allclose(r.omega["sun"], w_sun, atol=1e-12)
    assert w_sun == pytest.approx(2.5)


def test_ferguson_paradox_turns():
    m = gearlever.Mechanism.load(example("ferguson"))
    r = m.solve(np.array([0.0, 2 * np.pi]))
    turns = {k: (r.angle[k][1] - r.angle[k][0]) / (2 * np.pi) for k in ("g99", "g100", "g101")}
    assert turns["g99"] == pytest.approx(-1 / 99, abs=1e-12)
    assert turns["g100"] == pytest.approx(0.0, abs=1e-12)
    assert turns["g101"] == pytest.approx(1 / 101, abs=1e-12)


def test_zrdpm_gear_contour_agrees_with_willis_closed_form():
    m = gearlever.Mechanism.load(example("zrdpm_gear_contour"))
    q, qd = sweep(m, 200)
    qdd = np.column_stack([np.full(200, 0.3), np.full(200, -0.7)])
    r = m.solve(q, qd, qdd)
    w8 = driven_speed(qd[:, 0], qd[:, 1], 20 / 25, "external")
    e8 = driven_speed(qdd[:, 0], qdd[:, 1], 20 / 25, "external")
    assert np.allclose(r.omega["gear8"], w8, atol=1e-12)
    assert np.allclose(r.alpha["gear8"], e8, atol=1e-12)


def _fd_check(m, q, qd, h=1e-4):
    """Analogues vs central differences of positions, accelerations vs differences of velocities.

    The three sweeps (``q - h qd``, ``q``, ``q + h qd``) are solved one by one: the solver follows its rows as one
    path (through branch points, :mod:`gearlever.mechanism.branch`), and the three sweeps laid end to end are not one.
    """
    lo, mid, hi = (m.solve(q + t * qd, qd) for t in (-h, 0.0, h))
    assert lo.closed.all() and mid.closed.all() and hi.closed.all(), m.name
    L = m.model.length_scale
    for k in m.model.moving:
        w, al = mid.omega[k], mid.alpha[k]
        scale = 1.0 + np.abs(w).max()
        assert np.abs(wrap(hi.angle[k] - lo.angle[k]) / (2 * h) - w).max() < 1e-6 * scale, (m.name, k)
        assert np.abs((hi.omega[k] - lo.omega[k]) / (2 * h) - al).max() < 1e-6 * (1.0 + np.abs(al).max()), (m.name, k)
    for p in m.model.points:
        v, acc = mid.velocity[p], mid.acceleration[p]
        assert np.abs((hi.point[p] - lo.point[p]) / (2 * h) - v).max() < 1e-6 * (L + np.abs(v).max()), (m.name, p)
        dv = (hi.velocity[p] - lo.velocity[p]) / (2 * h)
        assert np.abs(dv - acc).max() < 1e-6 * (L + np.abs(acc).max()), (m.name, p)
    return mid


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_every_example_rates_match_finite_differences(path):
    m = gearlever.Mechanism.load(path)
    q, qd = sweep(m, 37)
    # the PMKS+ Watt I rocks over 11 deg: third derivatives of its rates are ~1e3, so a step of 1e-5 (error h^2 / 6)
    _fd_check(m, q, qd, h=1e-5 if path.stem == "watt_i" else 1e-4)


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_every_example_closes_and_its_poses_satisfy_every_constraint(path):
    m = gearlever.Mechanism.load(path)
    q, _ = sweep(m, 181)
    r = m.solve(q)
    assert r.closed.all()
    res = constraint_residual(m.model, r.pose)
    assert np.abs(res).max() < 1e-9 * m.model.length_scale


def test_constraint_jacobian_matches_finite_differences_of_the_residual():
    for path in all_examples():
        m = gearlever.Mechanism.load(path)
        q, _ = sweep(m, 5)
        pose = m.solve(q).pose[2]
        J = m.constraint_jacobian(pose)
        h = 1e-6
        for c in range(J.shape[1]):
            dp = np.zeros(pose.size)
            dp[c] = h
            fd = (
                m.constraint_residual(pose + dp.reshape(pose.shape))
                - m.constraint_residual(pose - dp.reshape(pose.shape))
            ) / (2 * h)
            assert np.abs(fd - J[:, c]).max() < 1e-6, (path.stem, c)


def test_pose_rates_are_consistent_with_the_jacobian():
    m = gearlever.Mechanism.load(example("whitworth"))
    r = m.solve(np.linspace(0, 2 * np.pi, 50))
    J = m.constraint_jacobian(r.pose)
    v = r.pose_velocity.reshape(50, -1)
    assert np.abs(np.einsum("nij,nj->ni", J, v)).max() < 1e-9


def test_past_a_dead_point_rows_are_nan_and_say_why():
    # a triple-rocker (non-Grashof): the input link cannot make a full turn
    d = {
        "points": {"O2": [0.0, 0.0], "O4": [10.0, 0.0], "A": [0.0, 8.0], "B": [3.0, 12.0]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }
    m = gearlever.Mechanism.from_dict(d)
    q = np.pi / 2 + np.linspace(0.0, 2 * np.pi, 721)
    r = m.solve(q)
    assert r.closed[0] and not r.closed.all()
    first = int(np.argmin(r.closed))
    assert not r.closed[first:].any()  # no silent jump back onto another branch
    assert np.isnan(r.angle["rocker"][first:]).all()
    assert all(r.reason[first:] != "") and r.reason[0] == ""
    # continuity up to the dead point: no branch jump
    th = r.angle["rocker"][:first]
    assert np.abs(np.diff(th)).max() < 0.2


def test_to_frame_has_unit_columns_and_one_row_per_input():
    m = gearlever.Mechanism.load(example("fourbar"))
    df = m.solve(np.linspace(0, 1, 7)).to_frame()
    assert len(df) == 7
    # qdot not given: analogues per unit crank rate, and the name says so
    assert {
        "input_crank_rad",
        "qdot_crank_per_crank",
        "coupler_angle_rad",
        "omega_coupler_per_crank",
        "alpha_coupler_per_crank_sq",
        "P_x_mm",
        "v_P_x_mm_per_crank",
    } <= set(df.columns)
    assert (df["qdot_crank_per_crank"] == 1.0).all()
    # qdot given: velocities in rad/s and mm/s
    dv = m.solve(np.linspace(0, 1, 7), qdot=np.full(7, 10.0)).to_frame()
    assert {"qdot_crank_rad_s", "omega_coupler_rad_s", "alpha_coupler_rad_s2", "v_P_x_mm_s", "a_P_y_mm_s2"} <= set(
        dv.columns
    )
    assert np.allclose(dv["omega_coupler_rad_s"], 10.0 * df["omega_coupler_per_crank"], rtol=1e-12, atol=0)


@settings(max_examples=25, deadline=None)
@given(
    st.floats(2.0, 5.0),
    st.floats(6.0, 9.0),
    st.floats(6.0, 9.0),
    st.floats(0.0, 2 * np.pi),
)
def test_random_crank_rockers_close_and_rates_match_fd(crank, coupler, rocker, start):
    ground = 8.0
    # Grashof crank-rocker: shortest link is the crank and s + l < p + q
    lengths = sorted([ground, crank, coupler, rocker])
    if lengths[0] + lengths[3] >= lengths[1] + lengths[2] - 0.5:
        return
    f = fourbar(ground, crank, coupler, rocker, [start])
    A = (crank * np.cos(start), crank * np.sin(start))
    B = (ground + rocker * np.cos(f.theta4[0]), rocker * np.sin(f.theta4[0]))
    m = gearlever.Mechanism.from_dict(
        {
            "points": {"O2": [0.0, 0.0], "O4": [ground, 0.0], "A": list(map(float, A)), "B": list(map(float, B))},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )
    q = start + np.linspace(0.0, 2 * np.pi, 91)
    r = m.solve(q)
    assert r.closed.all()
    assert np.abs(constraint_residual(m.model, r.pose)).max() < 1e-12 * 10
    _fd_check(m, q[::10, None], np.ones((10, 1)))
