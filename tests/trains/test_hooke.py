"""Tests of gearlever.trains.hooke: single and double Hooke's coupling."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.trains.hooke import (
    HookeJoint,
    acceleration_ratio,
    double_acceleration_ratio,
    double_fluctuation,
    double_output_angle,
    double_velocity_ratio,
    output_angle,
    ratio_extremes,
    velocity_ratio,
)

betas = st.floats(min_value=0.0, max_value=1.45)  # up to ~83 deg
phis = st.floats(min_value=-20.0, max_value=20.0)
TURN = np.linspace(0.0, 2 * np.pi, 4001)


def test_output_angle_satisfies_tan_relation():
    beta = math.radians(35.0)
    phi = np.linspace(-3.0, 3.0, 101)
    phi = phi[np.abs(np.cos(phi)) > 1e-3]
    psi = output_angle(phi, beta)
    np.testing.assert_allclose(np.tan(psi) * math.cos(beta), np.tan(phi), rtol=1e-10, atol=1e-10)


def test_output_angle_continuous_and_monotone_over_turns():
    beta = math.radians(60.0)
    phi = np.linspace(-4 * np.pi, 4 * np.pi, 8001)
    psi = output_angle(phi, beta)
    assert np.all(np.diff(psi) > 0)
    np.testing.assert_allclose(output_angle(phi + 2 * np.pi, beta), psi + 2 * np.pi, atol=1e-12)
    quarter = np.arange(-8, 9) * np.pi / 2
    np.testing.assert_allclose(output_angle(quarter, beta), quarter, atol=1e-12)


@settings(max_examples=40, deadline=None)
@given(betas)
def test_single_joint_extremes_cos_and_sec(beta):
    lo, hi = ratio_extremes(beta)
    assert lo == pytest.approx(math.cos(beta)) and hi == pytest.approx(1 / math.cos(beta))
    ratio = velocity_ratio(TURN, beta)
    assert ratio.min() >= lo * (1 - 1e-12) and ratio.max() <= hi * (1 + 1e-12)
    assert float(velocity_ratio(0.0, beta)) == pytest.approx(hi, rel=1e-12)
    assert float(velocity_ratio(np.pi / 2, beta)) == pytest.approx(lo, rel=1e-12)


@settings(max_examples=30, deadline=None)
@given(betas, phis)
def test_single_velocity_and_acceleration_match_finite_differences(beta, phi):
    h = 1e-5
    fd_v = (output_angle(phi + h, beta) - output_angle(phi - h, beta)) / (2 * h)
    fd_a = (velocity_ratio(phi + h, beta) - velocity_ratio(phi - h, beta)) / (2 * h)
    scale = 1 / math.cos(beta) ** 3
    assert float(velocity_ratio(phi, beta)) == pytest.approx(float(fd_v), abs=1e-7 * scale)
    assert float(acceleration_ratio(phi, beta)) == pytest.approx(float(fd_a), abs=1e-6 * scale**2)


def test_mean_velocity_ratio_is_one_over_a_turn():
    ratio = velocity_ratio(TURN[:-1], math.radians(40.0))
    assert ratio.mean() == pytest.approx(1.0, rel=1e-10)


@settings(max_examples=40, deadline=None)
@given(betas, phis)
def test_double_equal_angles_in_phase_is_uniform(beta, phi):
    # the classic text on trains of wheelwork, section 70: first and last shafts turn alike
    assert float(double_output_angle(phi, beta)) == pytest.approx(phi, abs=1e-9)
    assert float(double_velocity_ratio(phi, beta, beta, 0.0)) == pytest.approx(1.0, abs=1e-9)
    assert float(double_acceleration_ratio(phi, beta, beta, 0.0)) == pytest.approx(0.0, abs=1e-7 / math.cos(beta) ** 6)


@settings(max_examples=30, deadline=None)
@given(betas, betas, st.floats(min_value=-3.2, max_value=3.2), phis)
def test_double_ratios_match_finite_differences(b1, b2, delta, phi):
    h = 1e-5
    fd_v = (double_output_angle(phi + h, b1, b2, delta) - double_output_angle(phi - h, b1, b2, delta)) / (2 * h)
    fd_a = (double_velocity_ratio(phi + h, b1, b2, delta) - double_velocity_ratio(phi - h, b1, b2, delta)) / (2 * h)
    scale = 1 / (math.cos(b1) * math.cos(b2)) ** 3
    assert float(double_velocity_ratio(phi, b1, b2, delta)) == pytest.approx(float(fd_v), abs=1e-7 * scale)
    assert float(double_acceleration_ratio(phi, b1, b2, delta)) == pytest.approx(float(fd_a), abs=1e-6 * scale**2)


def test_double_unequal_angles_in_phase_leaves_closed_form_fluctuation():
    b1, b2 = math.radians(30.0), math.radians(20.0)
    c = math.cos(b1) / math.cos(b2)  # acts as one joint with tan psi = tan phi / c
    f = double_fluctuation(b1, b2, 0.0)
    assert f.min_ratio == pytest.approx(c, rel=1e-10)
    assert f.max_ratio == pytest.approx(1 / c, rel=1e-10)
    assert f.fluctuation == pytest.approx(1 / c - c, rel=1e-9)


def test_double_forks_crossed_doubles_fluctuation():
    b = math.radians(25.0)
    f = double_fluctuation(b, b, np.pi / 2)
    c = math.cos(b) ** 2
    assert (f.min_ratio, f.max_ratio) == (pytest.approx(c, rel=1e-10), pytest.approx(1 / c, rel=1e-10))


def test_double_phase_fluctuation_grows_from_zero():
    b = math.radians(25.0)
    values = [double_fluctuation(b, b, math.radians(d)).fluctuation for d in (0, 15, 45, 90)]
    assert values[0] == pytest.approx(0.0, abs=1e-12)
    assert values[0] < values[1] < values[2] < values[3]


def test_arrays_keep_their_shape():
    phi = np.linspace(0, 1, 12).reshape(3, 4)
    for fn in (output_angle, velocity_ratio, acceleration_ratio):
        assert fn(phi, 0.3).shape == (3, 4)
    for fn in (double_output_angle, double_velocity_ratio, double_acceleration_ratio):
        assert fn(phi, 0.3, 0.2, 0.1).shape == (3, 4)


def test_hooke_joint_works_in_radians():
    j = HookeJoint(math.radians(30.0))
    c = math.cos(math.radians(30.0))
    np.testing.assert_allclose(j.velocity_ratio([0.0, np.pi / 2]), [1 / c, c])  # sections 66 and 70: 1/cos, cos
    np.testing.assert_allclose(j.output_angle([0.7]), output_angle(0.7, math.radians(30.0)))
    d = HookeJoint(0.5, 0.5, 0.0)
    np.testing.assert_allclose(d.velocity_ratio(np.linspace(0, 2 * np.pi, 37)), 1.0, atol=1e-12)
    np.testing.assert_allclose(d.acceleration_ratio([0.2, 1.2]), 0.0, atol=1e-12)
    turn = j.turn(np.linspace(0.0, np.pi, 5))
    assert turn.to_frame().shape == (5, 4) and list(turn.as_dict()) == [
        "phi",
        "psi",
        "velocity_ratio",
        "acceleration_ratio",
    ]


@settings(max_examples=60, deadline=None)
@given(st.floats(0.0, 89.0), st.one_of(st.none(), st.floats(0.0, 89.0)), st.floats(-360.0, 360.0), phis)
def test_hooke_joint_radians_agree_with_degrees(b1, b2, phase, phi):
    rad = HookeJoint(math.radians(b1), None if b2 is None else math.radians(b2), math.radians(phase))
    deg = HookeJoint.from_degrees(b1, b2, phase)
    kw = HookeJoint(shaft_angle_deg=b1, second_angle_deg=b2, phase_deg=phase)
    assert deg == kw
    assert deg.shaft_angle == pytest.approx(rad.shaft_angle, abs=0) and deg.shaft_angle_deg == pytest.approx(b1)
    phi_deg = math.degrees(phi)
    np.testing.assert_allclose(deg.velocity_ratio_deg([phi_deg]), rad.velocity_ratio([phi]), rtol=1e-12)
    np.testing.assert_allclose(
        deg.acceleration_ratio_deg([phi_deg]), rad.acceleration_ratio([phi]), rtol=1e-9, atol=1e-12
    )
    np.testing.assert_allclose(
        deg.output_angle_deg([phi_deg]), np.degrees(rad.output_angle([phi])), rtol=1e-12, atol=1e-9
    )


def test_hooke_joint_degree_keywords_checked_in_degrees():
    with pytest.raises(ValueError, match="^shaft_angle_deg must be at least 0 and below 90 degrees"):
        HookeJoint.from_degrees(90.0)
    with pytest.raises(ValueError, match="^second_angle_deg"):
        HookeJoint(shaft_angle_deg=10.0, second_angle_deg=95.0)
    with pytest.raises(ValueError, match="^shaft_angle is given twice"):
        HookeJoint(0.1, shaft_angle_deg=10.0)
    with pytest.raises(ValueError, match="^shaft_angle is required"):
        HookeJoint()


@pytest.mark.parametrize("beta", [math.pi / 2, 2.0, -0.1, float("nan"), float("inf")])
def test_bad_shaft_angle(beta):
    with pytest.raises(ValueError, match="^shaft_angle"):
        velocity_ratio(0.0, beta)
    with pytest.raises(ValueError, match="^second_angle"):
        double_velocity_ratio(0.0, 0.1, beta)


def test_bad_inputs_named():
    with pytest.raises(ValueError, match="^phi"):
        output_angle([0.0, float("nan")], 0.2)
    with pytest.raises(ValueError, match="^phase"):
        double_output_angle(0.0, 0.2, 0.2, float("nan"))
    with pytest.raises(ValueError, match="^shaft_angle"):
        HookeJoint(math.pi / 2)  # radians: 90 deg is refused
    with pytest.raises(ValueError, match="^shaft_angle"):
        HookeJoint(30.0)  # 30 rad, not 30 deg
    with pytest.raises(ValueError, match="^second_angle"):
        HookeJoint(0.1, 1.6)
    with pytest.raises(ValueError, match="^samples"):
        double_fluctuation(0.2, samples=0)
