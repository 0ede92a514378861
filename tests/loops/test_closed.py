"""Closed forms of the double-slider contour (paper eqs. 6-9, 15-16, 25-28, 34-35)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.loops import closed as vl
from tests._zrdpm_fd import assert_rel, d1, d2

angles = st.lists(st.floats(-2 * math.pi, 2 * math.pi), min_size=1, max_size=20).map(np.array)
lengths = st.floats(0.1, 50.0)


@settings(max_examples=40, deadline=None)
@given(l=lengths, r=st.floats(-10, 10), phi=angles)
def test_double_slider_analogues_are_derivatives_of_the_projections(l, r, phi):
    x, y, dx, dy, d2x, d2y = vl.double_slider_projections(l, r, phi)
    assert_rel(d1(lambda p: vl.double_slider_projections(l, r, p)[0], phi), dx, l)
    assert_rel(d1(lambda p: vl.double_slider_projections(l, r, p)[1], phi), dy, l)
    assert_rel(d1(lambda p: vl.double_slider_projections(l, r, p)[2], phi), d2x, l)
    assert_rel(d1(lambda p: vl.double_slider_projections(l, r, p)[3], phi), d2y, l)


@settings(max_examples=40, deadline=None)
@given(l=lengths, ra=st.floats(0.1, 20), rb=st.floats(0.1, 20), phi=angles)
def test_slider_lever_analogues_are_derivatives_and_follow_eq8(l, ra, rb, phi):
    dtheta, u, e = vl.slider_lever(l, ra, rb, phi)
    c = l / (ra + rb)
    assert_rel(d1(lambda p: vl.slider_lever(l, ra, rb, p)[0], phi), u, c)
    assert_rel(d1(lambda p: vl.slider_lever(l, ra, rb, p)[1], phi), e, c)
    # eq. 8: omega_1 = (V_A - V_B) / (rA + rB) with the slider speeds of eq. 7
    _, _, dx_b, dy_a, _, _ = vl.double_slider_projections(l, 0.0, phi)
    np.testing.assert_allclose(u, (dy_a - dx_b) / (ra + rb), rtol=1e-12, atol=1e-12)


def test_slider_lever_is_eq9_when_l_equals_ra_plus_rb():
    phi = np.deg2rad([0, 45, 90, 225])
    _, u, _ = vl.slider_lever(4.0, 1.0, 3.0, phi)
    np.testing.assert_allclose(u, np.sin(phi) + np.cos(phi), atol=1e-15)
    assert u[1] == pytest.approx(math.sqrt(2))


@settings(max_examples=40, deadline=None)
@given(l=lengths, t0=st.floats(-4, 4), a=st.floats(-2, 2), b=st.floats(-2, 2), phi=angles)
def test_point_acceleration_is_second_derivative_of_the_point(l, t0, a, b, phi):
    # a link turning as theta(phi) = t0 + a sin(phi) + b phi
    theta = lambda p: t0 + a * np.sin(p) + b * p  # noqa: E731
    u = a * np.cos(phi) + b
    e = -a * np.sin(phi)
    ax, ay = vl.point_acceleration(l, theta(phi), u, e)
    scale = l * (1 + (abs(a) + abs(b)) ** 2 + abs(a))
    assert_rel(d2(lambda p: l * np.cos(theta(p)), phi), ax, scale)
    assert_rel(d2(lambda p: l * np.sin(theta(p)), phi), ay, scale)


@settings(max_examples=60, deadline=None)
@given(l=lengths, theta=angles, u=st.floats(-5, 5), e=st.floats(-5, 5))
def test_recover_analogues_inverts_point_acceleration(l, theta, u, e):
    u2, e_back = vl.recover_analogues(l, theta, *vl.point_acceleration(l, theta, u, e))
    np.testing.assert_allclose(u2, u * u, atol=1e-9 * (1 + u * u))
    np.testing.assert_allclose(e_back, e, atol=1e-9 * (1 + abs(e) + u * u))


def test_recover_analogues_is_finite_at_0_and_180_degrees():
    theta = np.array([0.0, math.pi, 2 * math.pi])
    u2, e = vl.recover_analogues(3.0, theta, *vl.point_acceleration(3.0, theta, 1.5, -0.7))
    assert np.all(np.isfinite(u2)) and np.all(np.isfinite(e))
    np.testing.assert_allclose(u2, 2.25, atol=1e-12)
    np.testing.assert_allclose(e, -0.7, atol=1e-12)


def test_outputs_keep_the_shape_of_phi():
    phi = np.zeros((3, 4))
    assert all(a.shape == (3, 4) for a in vl.double_slider_projections(1.0, 0.0, phi))
    assert all(a.shape == (3, 4) for a in vl.slider_lever(1.0, 1.0, 1.0, phi))


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: vl.double_slider_projections(0.0, 0.0, [0.0]), "l"),
        (lambda: vl.double_slider_projections(1.0, float("nan"), [0.0]), "r"),
        (lambda: vl.point_acceleration(-1.0, 0.0, 1.0, 0.0), "l"),
        (lambda: vl.recover_analogues(1.0, [float("inf")], 0.0, 0.0), "theta"),
        (lambda: vl.slider_lever(1.0, 0.0, 1.0, [0.0]), "r_a"),
        (lambda: vl.slider_lever(1.0, 1.0, -1.0, [0.0]), "r_b"),
        (lambda: vl.slider_lever(1.0, 1.0, 1.0, ["x"]), "phi"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=f"^{name} must"):
        call()
