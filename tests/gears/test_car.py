"""Tests of gearlever.gears.car: the car differential model (speeds, torques, power)."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.gears.car import car_differential, car_network, speed_ratio

speeds = st.floats(-500, 500, allow_nan=False)
torques = st.floats(-1000, 1000, allow_nan=False)
teeth = st.integers(5, 80)


def test_straight_run_both_wheels_at_carrier_speed():
    s = car_differential(11, 41, 300.0, 100.0)
    w2 = 300.0 * 11 / 41
    assert s.carrier_speed == pytest.approx(w2, rel=1e-15)
    assert s.left_speed == s.right_speed == s.carrier_speed
    assert s.ring_torque == pytest.approx(100.0 * 41 / 11, rel=1e-15)  # G1/G2 = Z1/Z2
    assert s.left_torque == s.right_torque == s.ring_torque / 2  # G4 = G5 = G2/2


def test_turn_wheel_speeds_follow_their_radii_and_average_to_the_carrier():
    R, T = 6.0, 1.6
    s = car_differential(9, 37, 250.0, 80.0, turn_radius=R, track=T)
    assert s.right_speed / s.left_speed == pytest.approx((R + T / 2) / (R - T / 2), rel=1e-13)
    assert (s.left_speed + s.right_speed) / 2 == pytest.approx(s.carrier_speed, rel=1e-15)
    assert s.left_speed < s.carrier_speed < s.right_speed  # left turn: left wheel inside


def test_one_wheel_held_the_other_runs_at_twice_the_carrier_speed():
    s = car_differential(10, 43, 120.0, 50.0, left_speed=0.0)
    assert s.left_speed == 0.0
    assert s.right_speed == pytest.approx(2 * s.carrier_speed, rel=1e-15)
    inner = car_differential(10, 43, 120.0, 50.0, turn_radius=0.75, track=1.5)  # centre on the left contact
    assert inner.left_speed == pytest.approx(0.0, abs=1e-12)


@settings(max_examples=80, deadline=None)
@given(teeth, teeth, speeds, torques, speeds)
def test_power_balance_for_any_inputs(z1, z2, w1, g1, w4):
    s = car_differential(z1, z2, w1, g1, left_speed=w4)
    scale = abs(g1) * (abs(w1) + abs(w4) * z2 / z1) + 1e-300
    assert abs(s.power_in - s.power_out) <= 1e-12 * scale
    assert (s.left_speed + s.right_speed) / 2 == pytest.approx(s.carrier_speed, rel=1e-12, abs=1e-9)


@settings(max_examples=60, deadline=None)
@given(teeth, teeth, speeds, torques, speeds, st.floats(0.5, 100), st.floats(0.5, 3))
def test_swapping_left_and_right_swaps_the_outputs(z1, z2, w1, g1, w4, r, t):
    a = car_differential(z1, z2, w1, g1, left_speed=w4)
    b = car_differential(z1, z2, w1, g1, left_speed=a.right_speed)
    assert b.right_speed == pytest.approx(a.left_speed, rel=1e-12, abs=1e-9)
    assert (b.left_torque, b.right_torque) == (a.right_torque, a.left_torque)
    left = car_differential(z1, z2, w1, g1, turn_radius=r, track=t)
    right = car_differential(z1, z2, w1, g1, turn_radius=-r, track=t)
    assert right.left_speed == pytest.approx(left.right_speed, rel=1e-12, abs=1e-12)
    assert right.right_speed == pytest.approx(left.left_speed, rel=1e-12, abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(teeth, teeth, st.integers(8, 30))
def test_network_solver_gives_the_same_model_exactly(z1, z2, zs):
    sol = car_network(z1, z2, zs).solve(["pinion", "left"])
    assert sol.coefficients["carrier"] == (speed_ratio(z1, z2), 0)  # w2 = w1 Z1/Z2
    assert sol.coefficients["right"] == (2 * speed_ratio(z1, z2), -1)  # w5 = 2 w2 - w4
    s = car_differential(z1, z2, 7.0, 1.0, left_speed=3.0)
    assert s.right_speed == pytest.approx(float(2 * Fraction(z1, z2) * 7 - 3), rel=1e-12)


def test_arrays_broadcast():
    s = car_differential(11, 41, np.array([100.0, 200.0]), 10.0, left_speed=np.array([0.0, 10.0]))
    assert s.right_speed.shape == (2,)
    assert np.allclose(s.power_in, s.power_out, rtol=1e-14)


def test_bad_inputs():
    with pytest.raises(ValueError, match="pinion_teeth must be a positive integer"):
        car_differential(0, 41, 1.0, 1.0)
    with pytest.raises(ValueError, match="together"):
        car_differential(11, 41, 1.0, 1.0, turn_radius=5.0)
    with pytest.raises(ValueError, match="not both"):
        car_differential(11, 41, 1.0, 1.0, left_speed=0.0, turn_radius=5.0, track=1.0)
    with pytest.raises(ValueError, match="turn_radius must be non-zero"):
        car_differential(11, 41, 1.0, 1.0, turn_radius=0.0, track=1.0)
    with pytest.raises(ValueError, match="pinion_speed must be an array of finite"):
        car_differential(11, 41, float("nan"), 1.0)
