"""Tests of the vector-loop engine (gearlever.loops): four-bar, sliders, general Newton."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import gearlever
from gearlever.loops import (
    INPUT,
    Input,
    LoopSystem,
    Unknown,
    Vector,
    closed,
    double_slider,
    double_slider_system,
    fourbar,
    fourbar_system,
    grashof,
    inverted_slider_crank,
    inverted_slider_crank_system,
    limit_positions,
    slider_crank,
    slider_crank_system,
    transmission_angle,
)

TURN = np.linspace(0.0, 2 * np.pi, 721)


def wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def closure(d, a, b, c, r):
    """Loop residual |a e^{i th2} + b e^{i th3} - c e^{i th4} - d| per point."""
    z = a * np.exp(1j * r.phi) + b * np.exp(1j * r.theta3) - c * np.exp(1j * r.theta4) - d
    return np.abs(z)


def central(f, x, h):
    return (f(x + h) - f(x - h)) / (2 * h)


# ----------------------------------------------------------------- four-bar
def test_fourbar_is_exported_from_package():
    assert gearlever.fourbar is fourbar


def test_fourbar_crank_rocker_closes_and_is_valid_over_a_turn():
    r = fourbar(9, 5, 8, 8, TURN)
    assert r.valid.all() and r.closed.all()
    assert closure(9, 5, 8, 8, r).max() < 1e-12


def test_fourbar_parameter_object_delegates_and_validates():
    from gearlever.loops import FourBar

    fb = FourBar(9, 5, 8, 8, branch="crossed")
    r = fb.solve(TURN)
    assert np.array_equal(r.theta4, fourbar(9, 5, 8, 8, TURN, branch="crossed").theta4, equal_nan=True)
    assert fb.grashof().kind == "crank-rocker" and fb.system().unknowns == ("theta3", "theta4")
    assert fb.limit_positions().theta4_extremes.size == 2
    with pytest.raises(ValueError, match="branch"):
        FourBar(9, 5, 8, 8, branch="x")
    with pytest.raises(ValueError, match="rocker"):
        FourBar(9, 5, 8, -8)


def test_fourbar_keeps_shape_of_input():
    th = np.linspace(0, 1, 12).reshape(3, 4)
    r = fourbar(9, 5, 8, 8, th)
    for arr in (r.theta3, r.theta4, r.dtheta3_dphi, r.d2theta4_dphi2, r.valid):
        assert arr.shape == (3, 4)


def test_fourbar_open_branch_is_continuous_and_crossed_is_its_mirror():
    ro = fourbar(9, 5, 8, 8, TURN)
    rc = fourbar(9, 5, 8, 8, TURN, branch="crossed")
    # no jump: consecutive rocker angles differ by less than the largest analogue allows
    step = TURN[1] - TURN[0]
    assert np.abs(wrap(np.diff(ro.theta4))).max() < 1.1 * step * np.abs(ro.dtheta4_dphi).max()
    assert np.abs(wrap(np.diff(rc.theta4))).max() < 1.1 * step * np.abs(rc.dtheta4_dphi).max()
    # mirror image about the ground line: crossed(theta2) = -open(-theta2)
    rm = fourbar(9, 5, 8, 8, -TURN)
    assert np.allclose(wrap(rc.theta4 + rm.theta4), 0, atol=1e-12)
    assert closure(9, 5, 8, 8, rc).max() < 1e-12


def test_fourbar_analogues_match_central_differences_of_positions():
    th = np.linspace(0.05, 6.2, 50)
    h = 1e-5
    r = fourbar(9, 5, 8, 8, th)
    for pos, d1, d2 in (
        ("theta3", "dtheta3_dphi", "d2theta3_dphi2"),
        ("theta4", "dtheta4_dphi", "d2theta4_dphi2"),
    ):
        fd1 = wrap(getattr(fourbar(9, 5, 8, 8, th + h), pos) - getattr(fourbar(9, 5, 8, 8, th - h), pos)) / (2 * h)
        fd2 = (getattr(fourbar(9, 5, 8, 8, th + h), d1) - getattr(fourbar(9, 5, 8, 8, th - h), d1)) / (2 * h)
        assert np.allclose(fd1, getattr(r, d1), rtol=1e-7, atol=1e-8)
        assert np.allclose(fd2, getattr(r, d2), rtol=1e-7, atol=1e-8)


lengths = st.floats(min_value=1.0, max_value=10.0, allow_nan=False)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(d=lengths, a=lengths, b=lengths, c=lengths, branch=st.sampled_from(["open", "crossed"]))
def test_random_fourbars_close_mask_and_match_finite_differences(d, a, b, c, branch):
    ls = sorted([d, a, b, c])
    assume(ls[3] < 0.98 * (ls[0] + ls[1] + ls[2]))
    assume(abs(ls[0] + ls[3] - ls[1] - ls[2]) > 1e-3)  # not a change-point linkage
    th = np.linspace(0.0, 2 * np.pi, 181)
    r = fourbar(d, a, b, c, th, branch=branch)
    # the mask says exactly where |O4 A| lies outside [|b - c|, b + c]
    f = np.abs(a * np.exp(1j * th) - d)
    can = (f >= abs(b - c) - 1e-12) & (f <= b + c + 1e-12)
    assert np.array_equal(r.closed, can)
    assert np.all(np.isnan(r.theta3[~r.closed])) and np.all(np.isnan(r.dtheta4_dphi[~r.valid]))
    if r.closed.any():
        assert closure(d, a, b, c, r)[r.closed].max() < 1e-12 * max(d, a, b, c)
    # analogues vs fourth-order central differences (h = 1e-4), away from dead points
    h = 1e-4
    rs = {k: fourbar(d, a, b, c, th + k * h, branch=branch) for k in (-2, -1, 1, 2)}
    S = np.abs(np.sin(r.theta3 - r.theta4))
    ok = r.valid & np.all([v.valid for v in rs.values()], axis=0) & (S > 0.2)

    def fd(name, wrapped):
        g = (lambda z: wrap(z)) if wrapped else (lambda z: z)
        d1_ = g(getattr(rs[1], name) - getattr(rs[-1], name))
        d2_ = g(getattr(rs[2], name) - getattr(rs[-2], name))
        return ((8 * d1_ - d2_) / (12 * h))[ok]

    for pos, d1, d2 in (
        ("theta3", "dtheta3_dphi", "d2theta3_dphi2"),
        ("theta4", "dtheta4_dphi", "d2theta4_dphi2"),
    ):
        fd1, fd2 = fd(pos, True), fd(d1, False)
        an1, an2 = getattr(r, d1)[ok], getattr(r, d2)[ok]
        assert np.all(np.abs(fd1 - an1) <= 1e-6 * (1 + np.abs(an1)))
        assert np.all(np.abs(fd2 - an2) <= 1e-5 * (1 + np.abs(an2)))
    # Grashof crank-rockers and double-cranks turn fully; non-Grashof do not
    g = grashof(d, a, b, c)
    assert r.closed.all() == (g.crank_rotates or np.all(can))
    if g.condition == "non-grashof":
        assert not r.closed.all()


def test_fourbar_non_grashof_is_masked_outside_its_range():
    # triple rocker: crank 7 oscillates between the toggle angles
    r = fourbar(9, 7, 8, 7, TURN)
    lp = limit_positions(9, 7, 8, 7)
    assert grashof(9, 7, 8, 7).kind == "triple-rocker"
    lim = lp.input_limits.max()
    inside = np.abs(wrap(TURN)) < lim - 1e-9
    outside = np.abs(wrap(TURN)) > lim + 1e-9
    assert r.closed[inside].all() and not r.closed[outside].any()
    with np.errstate(invalid="ignore"):
        assert np.all(np.isnan(r.theta4[outside]))


def test_fourbar_dead_point_is_masked_and_strict_raises():
    lp = limit_positions(9, 7, 8, 7)
    th = np.array([0.3, lp.input_limits.max()])
    r = fourbar(9, 7, 8, 7, th)
    assert r.valid.tolist() == [True, False]
    assert r.closed[1] and np.isnan(r.dtheta3_dphi[1])
    with pytest.raises(ValueError, match="phi"):
        fourbar(9, 7, 8, 7, th, strict=True)
    with pytest.raises(ValueError, match="phi"):
        fourbar(9, 7, 8, 7, TURN, strict=True)


@pytest.mark.parametrize(
    "args, match",
    [
        ((0, 5, 8, 8), "ground"),
        ((9, -5, 8, 8), "crank"),
        ((9, 5, float("nan"), 8), "coupler"),
        ((9, 5, 8, "x"), "rocker"),
        ((30, 5, 8, 8), "ground must be shorter"),
    ],
)
def test_fourbar_bad_lengths_raise_naming_the_link(args, match):
    with pytest.raises(ValueError, match=match):
        fourbar(*args, [0.0])


def test_fourbar_bad_branch_and_angles_raise():
    with pytest.raises(ValueError, match="branch"):
        fourbar(9, 5, 8, 8, [0.0], branch="left")
    with pytest.raises(ValueError, match="phi"):
        fourbar(9, 5, 8, 8, [0.0, np.inf])


@pytest.mark.parametrize(
    "links, kind",
    [
        ((9, 5, 8, 8), "crank-rocker"),
        ((4, 5, 8, 8), "double-crank"),
        ((9, 8, 3, 8), "double-rocker"),
        ((9, 8, 8, 5), "rocker-crank"),
        ((9, 7, 8, 7), "triple-rocker"),
        ((4, 2, 4, 2), "change point"),
    ],
)
def test_grashof_classification(links, kind):
    g = grashof(*links)
    assert g.kind == kind
    r = fourbar(*links, TURN)
    # a crank that "rotates" closes everywhere, one that does not fails somewhere
    if kind in ("crank-rocker", "double-crank"):
        assert r.closed.all()
    if kind in ("rocker-crank", "double-rocker", "triple-rocker"):
        assert not r.closed.all()


def test_limit_positions_are_where_the_rocker_stops():
    lp = limit_positions(9, 5, 8, 8)
    assert lp.theta2_at_rocker_extremes.size == 2
    r = fourbar(9, 5, 8, 8, lp.theta2_at_rocker_extremes)
    assert np.allclose(r.dtheta4_dphi, 0.0, atol=1e-9)
    assert np.allclose(r.theta4, lp.theta4_extremes, atol=1e-12)
    dense = fourbar(9, 5, 8, 8, np.linspace(0, 2 * np.pi, 20001))
    assert np.isclose(dense.theta4.min(), lp.theta4_extremes.min(), atol=1e-7)
    assert np.isclose(dense.theta4.max(), lp.theta4_extremes.max(), atol=1e-7)


def test_transmission_angle_is_the_angle_between_coupler_and_rocker():
    r = fourbar(9, 5, 8, 8, TURN)
    mu = transmission_angle(9, 5, 8, 8, TURN)
    folded = np.abs(wrap(r.theta3 - r.theta4))
    assert np.allclose(mu, folded, atol=1e-9)
    with np.errstate(invalid="ignore"):
        assert np.isnan(transmission_angle(9, 7, 8, 7, np.pi))


# ------------------------------------------------------- general engine (Newton)
def test_newton_engine_matches_fourbar_closed_form_over_a_turn():
    system = fourbar_system(9, 5, 8, 8)
    r = fourbar(9, 5, 8, 8, TURN)
    sol = system.solve(TURN, {"theta3": r.theta3[0] + 0.05, "theta4": r.theta4[0] - 0.05})
    assert sol.valid.all()
    assert np.abs(system.residual(TURN, sol.x)).max() < 1e-12
    assert np.abs(wrap(sol["theta3"] - r.theta3)).max() < 1e-12
    assert np.abs(wrap(sol["theta4"] - r.theta4)).max() < 1e-12
    assert np.allclose(sol.d1("theta4"), r.dtheta4_dphi, rtol=1e-10, atol=1e-12)
    assert np.allclose(sol.d2("theta3"), r.d2theta3_dphi2, rtol=1e-10, atol=1e-12)


def test_newton_engine_follows_the_seeded_branch_and_masks_beyond_the_toggle():
    system = fourbar_system(9, 7, 8, 7)
    th = np.linspace(0.0, 2 * np.pi, 361)
    for branch in ("open", "crossed"):
        r = fourbar(9, 7, 8, 7, th, branch=branch)
        sol = system.solve(th, {"theta3": r.theta3[0], "theta4": r.theta4[0]})
        lim = limit_positions(9, 7, 8, 7).input_limits.max()
        # valid exactly up to the toggle, on the seeded branch only, then masked
        assert sol.valid[th < lim - 0.02].all()
        assert not sol.valid[th > lim].any()
        assert np.all(np.isnan(sol.x[~sol.closed]))
        v = sol.valid
        assert np.abs(wrap(sol["theta4"][v] - r.theta4[v])).max() < 1e-10
        with pytest.raises(ValueError, match="phi"):
            system.solve(th, {"theta3": r.theta3[0], "theta4": r.theta4[0]}, strict=True)


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_newton_engine_on_a_coarse_and_backward_input_keeps_the_branch(branch):
    th = np.linspace(2 * np.pi, -2 * np.pi, 9)  # 90 deg apart, turning backwards twice
    r = fourbar(9, 5, 8, 8, th, branch=branch)
    sol = fourbar_system(9, 5, 8, 8).solve(th, {"theta3": r.theta3[0] + 0.1, "theta4": r.theta4[0] + 0.1})
    assert sol.valid.all()
    assert np.abs(wrap(sol["theta3"] - r.theta3)).max() < 1e-12
    assert np.abs(wrap(sol["theta4"] - r.theta4)).max() < 1e-12


def test_newton_engine_watt_six_bar_with_shared_unknown_matches_chained_closed_forms():
    # loop 1: four-bar O2-A-B-O4; loop 2: the rocker carries C at theta4 + 0.7 and
    # drives a second dyad C-D-O6 with O6 = O4 + (6, 0).
    delta = 0.7
    system = LoopSystem(
        [
            [
                Vector("A", 5.0, INPUT),
                Vector("BA", 8.0, "theta3"),
                Vector("B", 8.0, "theta4", -1),
                Vector("O4", 9.0, 0.0, -1),
            ],
            [
                Vector("C", 4.0, Unknown("theta4", delta)),
                Vector("DC", 7.0, "theta5"),
                Vector("D", 6.5, "theta6", -1),
                Vector("O6", 6.0, 0.0, -1),
            ],
        ]
    )
    assert system.unknowns == ("theta3", "theta4", "theta5", "theta6")
    th = np.linspace(0, 2 * np.pi, 181)
    r1 = fourbar(9, 5, 8, 8, th)
    psi = r1.theta4 + delta
    r2 = fourbar(6.0, 4.0, 7.0, 6.5, psi)
    assert r2.valid.all()
    sol = system.solve(
        th, {"theta3": r1.theta3[0], "theta4": r1.theta4[0], "theta5": r2.theta3[0], "theta6": r2.theta4[0]}
    )
    assert sol.valid.all()
    assert np.abs(system.residual(th, sol.x)).max() < 1e-12
    assert np.abs(wrap(sol["theta6"] - r2.theta4)).max() < 1e-11
    # chain rule: d theta6/d phi = theta6'(psi) psi';  d2 = theta6''(psi) psi'^2 + theta6'(psi) psi''
    d1 = r2.dtheta4_dphi * r1.dtheta4_dphi
    d2 = r2.d2theta4_dphi2 * r1.dtheta4_dphi**2 + r2.dtheta4_dphi * r1.d2theta4_dphi2
    assert np.allclose(sol.d1("theta6"), d1, rtol=1e-9, atol=1e-12)
    assert np.allclose(sol.d2("theta6"), d2, rtol=1e-9, atol=1e-11)


def test_loop_system_rejects_bad_definitions():
    with pytest.raises(ValueError, match="2 unknowns per loop"):
        LoopSystem([[Vector("A", 5.0, INPUT), Vector("B", 8.0, "theta3"), Vector("G", 9.0, 0.0, -1)]])
    with pytest.raises(ValueError, match="loops"):
        LoopSystem([])
    with pytest.raises(ValueError, match="sign"):
        Vector("A", 1.0, 0.0, sign=2)
    with pytest.raises(ValueError, match="length"):
        Vector("A", float("nan"), 0.0)
    system = fourbar_system(9, 5, 8, 8)
    with pytest.raises(ValueError, match="guess"):
        system.solve([0.0], {"theta3": 1.0})
    with pytest.raises(ValueError, match="phi"):
        system.solve([], {"theta3": 1.0, "theta4": 1.0})


# ----------------------------------------------------------- slider families
@settings(max_examples=20, deadline=None)
@given(
    a=st.floats(0.5, 3.0),
    b=st.floats(0.5, 6.0),
    e=st.floats(-1.0, 1.0),
    branch=st.sampled_from(["open", "crossed"]),
)
def test_slider_crank_closed_form_matches_newton_and_finite_differences(a, b, e, branch):
    th = np.linspace(0, 2 * np.pi, 121)
    s = slider_crank(a, b, th, offset=e, branch=branch)
    system = slider_crank_system(a, b, e)
    assert np.array_equal(s.closed, np.abs(e - a * np.sin(th)) <= b)
    if s.closed.any():
        assert np.abs(system.residual(th, s.x)[s.closed]).max() < 1e-12
    h = 1e-5
    sp, sm = slider_crank(a, b, th + h, e, branch), slider_crank(a, b, th - h, e, branch)
    ok = s.valid & sp.valid & sm.valid & (np.abs(np.cos(s["theta3"])) > 0.2)
    fd1 = np.stack([wrap(sp["theta3"] - sm["theta3"]), sp["x_B"] - sm["x_B"]], -1) / (2 * h)
    fd2 = (sp.dx_dphi - sm.dx_dphi) / (2 * h)
    assert np.all(np.abs(fd1 - s.dx_dphi)[ok] <= 1e-6 * (1 + np.abs(s.dx_dphi[ok])))
    assert np.all(np.abs(fd2 - s.d2x_dphi2)[ok] <= 1e-5 * (1 + np.abs(s.d2x_dphi2[ok])))
    if b > a + abs(e) + 0.1:  # turns fully: Newton along the input agrees everywhere
        sol = system.solve(th, {"theta3": s["theta3"][0], "x_B": s["x_B"][0]})
        assert sol.valid.all()
        assert np.abs(wrap(sol["theta3"] - s["theta3"])).max() < 1e-11
        assert np.allclose(sol["x_B"], s["x_B"], atol=1e-11)
        assert np.allclose(sol.d2x_dphi2, s.d2x_dphi2, atol=1e-9)


def test_inverted_slider_crank_closed_form_matches_newton_and_finite_differences():
    th = np.linspace(0, 2 * np.pi, 241)
    s = inverted_slider_crank(4.0, 1.5, th, offset=0.5)
    system = inverted_slider_crank_system(4.0, 1.5, 0.5)
    assert s.valid.all()
    assert np.abs(system.residual(th, s.x)).max() < 1e-12
    sol = system.solve(th, {"b": s["b"][0], "theta4": s["theta4"][0]})
    assert np.allclose(sol["b"], s["b"], atol=1e-12)
    assert np.abs(wrap(sol["theta4"] - s["theta4"])).max() < 1e-12
    assert np.allclose(sol.dx_dphi, s.dx_dphi, atol=1e-10)
    h = 1e-5
    sp, sm = inverted_slider_crank(4.0, 1.5, th + h, 0.5), inverted_slider_crank(4.0, 1.5, th - h, 0.5)
    fd1 = np.stack([sp["b"] - sm["b"], wrap(sp["theta4"] - sm["theta4"])], -1) / (2 * h)
    assert np.allclose(fd1, s.dx_dphi, atol=1e-8)
    assert np.allclose((sp.dx_dphi - sm.dx_dphi) / (2 * h), s.d2x_dphi2, atol=1e-7)
    # crank longer than the ground offset: the pin passes O4 (b = 0) -> masked dead point
    t = inverted_slider_crank(1.0, 1.0, np.array([0.0, 1.0]))
    assert t.valid.tolist() == [False, True]


def test_double_slider_closed_form_equals_closed_and_engine_newton():
    phi = np.linspace(0, 2 * np.pi, 73)
    s = double_slider(21.0, 2.5, phi)
    ref = closed.double_slider_projections(21.0, 2.5, phi)
    assert np.array_equal(s["x_B"], ref[0]) and np.array_equal(s.d2("y_A"), ref[5])
    system = double_slider_system(21.0, 2.5)
    assert np.abs(system.residual(phi, s.x)).max() < 1e-12
    # the general analogue solve on the same loop gives the closed forms (eq. 7)
    d1, d2, bad = system.analogues(phi, s.x)
    assert not bad.any()
    assert np.allclose(d1, s.dx_dphi, atol=1e-12) and np.allclose(d2, s.d2x_dphi2, atol=1e-12)
    sol = system.solve(phi, {"x_B": 20.0, "y_A": 0.0})
    assert np.allclose(sol.x, s.x, atol=1e-12)


def test_input_with_coefficient_and_offset():
    # the same double slider written with the link angle pi - phi (input k=-1, offset pi)
    system = LoopSystem(
        [
            [
                Vector("B", "x_B", 0.0),
                Vector("AB", 2.0, Input(-1.0, math.pi)),
                Vector("A", "y_A", math.pi / 2, -1),
            ]
        ]
    )
    phi = np.linspace(0, 6, 25)
    sol = system.solve(phi, {"x_B": 2.0, "y_A": 0.0})
    assert np.allclose(sol["x_B"], 2 * np.cos(phi), atol=1e-12)
    assert np.allclose(sol.d2("y_A"), -2 * np.sin(phi), atol=1e-12)


def test_newton_engine_sub_steps_never_exceed_max_step():
    # Known bug: the sub-stepping doubled its step up to a fixed 0.1 rad, ignoring
    # max_step.  Every Newton call is recorded; consecutive inputs on the path
    # from 0 to 1 rad (one gap, so all of it is sub-stepped) must be <= max_step.
    system = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1), Vector("y", "y", math.pi / 2, -1)]])
    seen = []
    newton = system._newton

    def spy(phi, x, *args, **kwargs):
        seen.extend(np.asarray(phi).reshape(-1).tolist())
        return newton(phi, x, *args, **kwargs)

    system._newton = spy
    max_step = 0.01
    sol = system.solve([0.0, 1.0], {"x": 2.0, "y": 0.0}, max_step=max_step)
    assert sol.valid.all() and np.allclose(sol["x"], 2 * np.cos([0.0, 1.0]))
    steps = np.diff(seen)
    assert steps.size > 50 and np.all(np.abs(steps) <= max_step * (1 + 1e-12))


def test_newton_engine_strict_raises_closure_error():
    from gearlever.errors import ClosureError

    system = fourbar_system(9.0, 7.0, 8.0, 7.0)  # non-Grashof: the crank cannot turn fully
    r = fourbar(9.0, 7.0, 8.0, 7.0, [0.0])
    guess = {"theta3": float(r.theta3[0]), "theta4": float(r.theta4[0])}
    with pytest.raises(ClosureError, match="phi"):
        system.solve(np.linspace(0, 2 * np.pi, 50), guess, strict=True)
    with pytest.raises(ClosureError, match="phi"):
        fourbar(9.0, 7.0, 8.0, 7.0, np.linspace(0, 2 * np.pi, 50), strict=True)


def test_fourbar_result_is_a_result_with_phi_and_the_theta2_alias():
    from gearlever._result import Result

    th = np.linspace(0.0, 1.0, 4)
    r = fourbar(9, 5, 8, 8, th)
    assert isinstance(r, Result) and r.to_frame().shape == (4, 10)
    assert r.theta2 is r.phi and np.array_equal(r.phi, th)


def test_loop_solution_frame_names_each_unknown_and_its_analogues():
    from gearlever.loops import INPUT, LoopSystem, Vector

    loop = LoopSystem(
        [
            [
                Vector("A", 5.0, INPUT),
                Vector("BA", 8.0, "theta3"),
                Vector("B", 8.0, "theta4", -1),
                Vector("O4", 9.0, 0.0, -1),
            ]
        ]
    )
    sol = loop.solve(np.linspace(0, 1, 3), {"theta3": 1.3, "theta4": 1.8})
    df = sol.to_frame()
    assert list(df.columns[:4]) == ["phi", "theta3", "dtheta3_dphi", "d2theta3_dphi2"]
    np.testing.assert_array_equal(df["dtheta4_dphi"].to_numpy(), sol.d1("theta4"))
    assert sol.as_dict()["names"] == ("theta3", "theta4")
