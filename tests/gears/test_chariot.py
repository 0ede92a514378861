"""Tests of gearlever.gears.chariot: Nuttall sizing against the source, conventions, drift bounds."""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.errors import GearleverError
from gearlever.gears.chariot import (
    NuttallTeeth,
    design_nuttall,
    drift_on_the_spot,
    nuttall_closed_form,
    nuttall_network,
    parse_waypoints,
    random_path,
    simulate,
    waypoint_path,
)

teeth_sets = st.builds(NuttallTeeth, *[st.integers(6, 120)] * 7)
DESIGN = design_nuttall(NuttallTeeth(30, 24, 18, 36, 20, 25, 40))


@settings(max_examples=150, deadline=None)
@given(teeth_sets)
def test_solver_reproduces_source_closed_forms_exactly(teeth):
    d = design_nuttall(teeth)
    cf = nuttall_closed_form(teeth)
    assert d.rot1_per_pointer_turn == cf["rot1"]  # Nuttall (l=>), exact Fractions
    assert d.rot12_per_pointer_turn == cf["rot12"]
    assert d.d1_over_t == cf["d1_over_t"]  # (m=>)
    assert d.d12_over_t == cf["d12_over_t"]  # (p=>)


@settings(max_examples=60, deadline=None)
@given(teeth_sets)
def test_solver_relation_is_source_relation_l(teeth):
    n = {k: Fraction(v) for k, v in teeth.as_dict().items()}
    K = nuttall_closed_form(teeth)["K"]
    d = design_nuttall(teeth)
    # (l): K rot7 + n2/(n2+n5) rot1 - n11/(n9+n11) rot12 = 0 for every rot1, rot12
    assert K * d.pointer_per_right + n["n2"] / (n["n2"] + n["n5"]) == 0
    assert K * d.pointer_per_left - n["n11"] / (n["n9"] + n["n11"]) == 0
    a = d.solution.analysis
    assert (a.unknowns, a.rank, a.dof, a.redundant) == (10, 8, 2, ("e",))


def test_worked_designs_equal_teeth_and_geared_up_by_two():
    eq = design_nuttall(NuttallTeeth.uniform(17), track=2.5)
    assert (eq.d1_over_t, eq.d12_over_t) == (1, 1)
    assert eq.d1 == eq.d12 == 2.5
    up = design_nuttall(NuttallTeeth(20, 20, 20, 40, 20, 20, 20))
    assert (up.d1_over_t, up.d12_over_t) == (Fraction(1, 2), Fraction(1, 2))


def test_network_is_built_from_the_data_file_rows_a_to_i():
    net = nuttall_network(NuttallTeeth.uniform(20))
    assert [c.label for c in net.constraints] == list("abcdefghi")
    assert set(net.names) == {"1", "2", "4", "5", "6", "7", "8", "9", "11", "12"}


def test_bad_teeth_name_the_parameter():
    with pytest.raises(ValueError, match="n5 must be a positive integer"):
        NuttallTeeth(20, 0, 20, 20, 20, 20, 20)
    with pytest.raises(ValueError, match="track must be a positive"):
        design_nuttall(NuttallTeeth.uniform(20), track=-1.0)


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_spin_on_the_spot_sign_convention(direction):
    """Left spin: right wheel (1) forward, left wheel (12) back, chassis heading rises; pointer holds."""
    steps = 400
    s = np.full(steps, direction * math.pi * DESIGN.track / 2 / steps)  # half a turn: each wheel rolls pi t/2
    run = simulate(DESIGN, ds_left=-s, ds_right=s, heading0=0.3)
    assert run.chassis_heading[-1] == pytest.approx(0.3 + direction * math.pi, abs=1e-12)
    assert np.all(np.diff(run.chassis_heading) * direction > 0)
    assert run.max_drift < 1e-12
    assert np.allclose(run.pointer_heading, 0.3, atol=1e-12)
    assert run.distance == 0.0 and run.turns == pytest.approx(0.5, rel=1e-12)


def test_wheel_12_held_right_wheel_backwards_pointer_turns_once_relative_to_chassis():
    """Source (m)-(o): wheel 1 rolls a full circle of radius t about wheel 12's contact point."""
    steps = 1000
    ds_right = np.full(steps, -2 * math.pi * DESIGN.track / steps)
    run = simulate(DESIGN, np.zeros(steps), ds_right)
    assert run.chassis_heading[-1] == pytest.approx(-2 * math.pi, abs=1e-12)
    relative = run.pointer_heading - run.chassis_heading
    assert relative[-1] == pytest.approx(2 * math.pi, abs=1e-12)  # rot7 = +1 turn
    wheel_turns = ds_right.sum() / (math.pi * DESIGN.d1)
    assert wheel_turns == pytest.approx(float(DESIGN.rot1_per_pointer_turn), rel=1e-12)
    x, y = run.positions()  # the mid-point circles wheel 12's contact point at radius t/2
    cx, cy = 0.0, DESIGN.track / 2
    assert np.allclose(np.hypot(x - cx, y - cy), DESIGN.track / 2, atol=1e-12)


@settings(max_examples=25, deadline=None)
@given(teeth_sets, st.floats(-20, 20).filter(lambda r: abs(r) > 0.01))
def test_drift_per_full_turn_below_1e_9_with_computed_diameters(teeth, radius):
    d = design_nuttall(teeth, track=0.8)
    steps = 720
    dtheta = 2 * math.pi / steps  # heading change per step: one full left turn about a centre
    t = d.track  # at signed distance `radius` to the left (negative: driving backwards)
    run = simulate(d, np.full(steps, (radius - t / 2) * dtheta), np.full(steps, (radius + t / 2) * dtheta))
    assert run.turns == pytest.approx(1.0, rel=1e-12)
    assert run.max_drift < 1e-9
    x, y = run.positions()
    assert abs(x[-1]) < 1e-9 * max(1, abs(radius)) and abs(y[-1]) < 1e-9 * max(1, abs(radius))


def test_random_path_of_1000_turns_drifts_less_than_1e_6():
    d = design_nuttall(NuttallTeeth(13, 47, 29, 31, 17, 53, 41))
    dl, dr = random_path(1000, seed=11, steps_per_turn=60, track=d.track)
    run = simulate(d, dl, dr)
    assert run.turns == pytest.approx(1000, rel=1e-9)
    assert run.max_drift < 1e-6


def test_one_percent_wrong_d1_drifts_by_the_closed_form_amount():
    steps = 500
    s = np.full(steps, math.pi * DESIGN.track / steps)  # one full left turn on the spot
    run = simulate(DESIGN, -s, s, d1=1.01 * DESIGN.d1)
    expected = drift_on_the_spot(DESIGN, 1.01 * DESIGN.d1)
    assert expected == pytest.approx(math.pi * (1 - 1 / 1.01), rel=1e-12)
    assert run.final_drift == pytest.approx(expected, rel=1e-9)
    dl, dr = random_path(20, seed=3, steps_per_turn=200)
    assert simulate(DESIGN, dl, dr, d1=1.01 * DESIGN.d1).max_drift > 0.05


def test_simulation_agrees_with_per_member_rotations_from_the_solver():
    dl, dr = random_path(3, seed=5, steps_per_turn=100)
    run = simulate(DESIGN, dl, dr, d1=0.9, d12=0.7)
    rot1 = np.cumsum(dr) / (math.pi * 0.9)
    rot12 = np.cumsum(dl) / (math.pi * 0.7)
    rot7 = DESIGN.solution.rotation("7", {"1": rot1, "12": rot12})
    relative = run.pointer_heading[1:] - run.chassis_heading[1:]
    assert np.allclose(relative, 2 * math.pi * rot7, rtol=0, atol=1e-10)


def test_random_path_is_reproducible_and_seed_dependent():
    a = random_path(2, seed=4, steps_per_turn=100)
    b = random_path(2, seed=4, steps_per_turn=100)
    c = random_path(2, seed=5, steps_per_turn=100)
    assert np.array_equal(a[0], b[0]) and not np.array_equal(a[0], c[0])


def test_waypoint_path_ends_at_the_last_point():
    pts = np.array([[0, 0], [3, 0], [3, 0], [3, 2], [-1, 5]], float)
    dl, dr, h0 = waypoint_path(pts, track=DESIGN.track, step=0.05)
    run = simulate(DESIGN, dl, dr, heading0=h0, start=pts[0])
    x, y = run.positions()
    assert (x[-1], y[-1]) == pytest.approx((-1.0, 5.0), abs=1e-9)
    assert np.max(np.abs(dl)) <= 0.05 + 1e-15 and np.max(np.abs(dr)) <= 0.05 + 1e-15
    assert run.max_drift < 1e-12


def test_parse_waypoints_csv_whitespace_and_errors():
    assert parse_waypoints("0 0\n1.5,2\n").tolist() == [[0, 0], [1.5, 2]]
    with pytest.raises(ValueError, match="waypoints line 2"):
        parse_waypoints("0 0\n1 2 3\n")
    with pytest.raises(ValueError, match="waypoints line 1"):
        parse_waypoints("a b\n1 2\n")
    with pytest.raises(ValueError, match="waypoints line 2"):
        parse_waypoints("0 0\nnan 1\n")
    with pytest.raises(ValueError, match="at least two"):
        parse_waypoints("# only\n1 1\n")
    with pytest.raises(ValueError, match="two distinct"):
        waypoint_path([[1, 1], [1, 1]])


def test_simulate_bad_inputs():
    with pytest.raises(ValueError, match="ds_right must be an array of finite numbers"):
        simulate(DESIGN, [0.0, 0.1], [0.0, np.nan])
    with pytest.raises(ValueError, match="one length"):
        simulate(DESIGN, [0.0, 0.1], [0.0])
    with pytest.raises(ValueError, match="d1 must be a positive"):
        simulate(DESIGN, [0.1], [0.1], d1=0.0)
    with pytest.raises(ValueError, match="turns must be a positive"):
        random_path(0)


def test_random_path_refuses_more_steps_than_the_cap():
    from gearlever.gears.chariot import MAX_STEPS, random_path

    with pytest.raises(GearleverError, match=r"^turns: turns\*steps_per_turn must be at most 10,000,000"):
        random_path(MAX_STEPS / 1000 + 1, steps_per_turn=1000)
    with pytest.raises(GearleverError, match="^turns"):
        random_path(1e300, steps_per_turn=10**9)


def test_waypoint_path_refuses_a_step_that_implies_too_many_steps(monkeypatch):
    import gearlever.gears.chariot as chariot

    with pytest.raises(GearleverError, match=r"^step: the way-points need"):
        chariot.waypoint_path([[0, 0], [1, 0]], step=1 / chariot.MAX_STEPS / 2)
    with pytest.raises(GearleverError, match=r"^step"):
        chariot.waypoint_path([[0, 0], [1, 0]], step=1e-300)
    monkeypatch.setattr(chariot, "MAX_STEPS", 1000)
    dl, _, _ = chariot.waypoint_path([[0, 0], [1, 0]], step=1 / 1000 * 1.0000001)
    assert dl.size == 1000
    with pytest.raises(GearleverError, match=r"more than the cap 1,000 "):
        chariot.waypoint_path([[0, 0], [1, 0], [1, 1]], step=1 / 1000 * 1.0000001)


def test_parse_waypoints_refuses_more_points_than_the_cap(monkeypatch):
    import gearlever.gears.chariot as chariot

    monkeypatch.setattr(chariot, "MAX_WAYPOINTS", 3)
    assert chariot.parse_waypoints("0 0\n1 1\n2 2\n").shape == (3, 2)
    with pytest.raises(GearleverError, match="^waypoints must hold at most 3 points"):
        chariot.parse_waypoints("0 0\n1 1\n2 2\n3 3\n")
