"""Willis equation of the ZRDPM differentials (paper eqs. 2-4, 12-14, 21-23, 31-33)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gearlever
from gearlever.gears import willis as df
from gearlever.loops import closed as vl
from tests._zrdpm_fd import assert_rel, d1

ratios = st.floats(0.05, 20.0)
speeds = st.floats(-100, 100)
meshes = st.sampled_from(["external", "internal"])


@settings(max_examples=50, deadline=None)
@given(k=ratios, w=speeds, mesh=meshes)
def test_carrier_at_rest_gives_the_plain_gear_ratio(k, w, mesh):
    sign = -1.0 if mesh == "external" else 1.0
    assert float(df.driven_speed(w, 0.0, k, mesh)) == pytest.approx(sign * k * w, abs=1e-12)


@settings(max_examples=50, deadline=None)
@given(k=ratios, w=speeds, mesh=meshes)
def test_all_members_turning_together_stay_together(k, w, mesh):
    assert float(df.driven_speed(w, w, k, mesh)) == pytest.approx(w, rel=1e-12, abs=1e-12)


@settings(max_examples=50, deadline=None)
@given(k=ratios, wl=speeds, wc=speeds, mesh=meshes)
def test_willis_ratio_of_the_driven_speed_is_the_basic_ratio(k, wl, wc, mesh):
    if abs(wl - wc) < 1e-3:
        wc = wl + 1.0
    wd = df.driven_speed(wl, wc, k, mesh)
    i = df.basic_ratio(k, 1.0, mesh)
    assert float(df.willis_ratio(wd, wl, wc)) == pytest.approx(i, rel=1e-8, abs=1e-8)


def test_paper_eq3_form_for_an_external_mesh():
    # omega_8 = (1 + r9/r8) omega_1 - (r9/r8) omega_9 with r9/r8 = 0.25
    assert float(df.driven_speed(2.0, 3.0, 0.25)) == pytest.approx(1.25 * 3.0 - 0.25 * 2.0)


@settings(max_examples=40, deadline=None)
@given(k=ratios, mesh=meshes, phi=st.lists(st.floats(-6.3, 6.3), min_size=1, max_size=10).map(np.array))
def test_driven_analogues_are_derivatives_of_the_driven_angle(k, mesh, phi):
    # carrier turned by the slider lever; the driven gear's angle by Willis in angles
    i = df.basic_ratio(k, 1.0, mesh)

    def gear_angle(p):
        return (1 - i) * vl.slider_lever(2.0, 1.0, 1.0, p)[0] + i * p

    _, u_c, e_c = vl.slider_lever(2.0, 1.0, 1.0, phi)
    u_g, e_g = df.driven_analogues(u_c, e_c, k, mesh)
    scale = 1 + abs(1 - i) + abs(i)
    assert_rel(d1(gear_angle, phi), u_g, scale)
    u_of = lambda p: df.driven_analogues(*vl.slider_lever(2.0, 1.0, 1.0, p)[1:], k, mesh)[0]  # noqa: E731
    assert_rel(d1(u_of, phi), e_g, scale)


def test_driven_analogues_with_accelerating_lead():
    # eq. 14 keeps the -(r9/r8) e_9 term
    _, e = df.driven_analogues(0.0, 1.0, 0.5, e_lead=2.0)
    assert float(e) == pytest.approx(1.5 * 1.0 - 0.5 * 2.0)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: df.basic_ratio(0.0, 1.0), "r_lead"),
        (lambda: df.basic_ratio(1.0, -2.0), "r_driven"),
        (lambda: df.basic_ratio(1.0, 1.0, "bevel"), "mesh"),
        (lambda: df.driven_speed(1.0, 0.0, -1.0), "ratio"),
        (lambda: df.driven_analogues(1.0, 0.0, 0.5, "spur"), "mesh"),
        (lambda: df.willis_ratio(1.0, 2.0, 2.0), "omega_lead"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=f"^{name} must"):
        call()


@given(st.integers(1, 500), st.integers(1, 500), st.sampled_from([(1, "external"), (-1, "internal")]))
def test_willis_row_is_the_signed_ratio_in_tooth_form(z_a, z_b, kind):
    """The integer row of gear networks and the float ratio of the ZRDPM are one Willis relation."""
    sign, mesh = kind
    c_a, c_b, c_c = df.willis_row(z_a, z_b, sign)
    # seen from the carrier: (rot_b - rot_c)/(rot_a - rot_c) = -c_a/c_b
    assert c_a + c_b + c_c == 0
    assert -c_a / c_b == pytest.approx(df.signed_ratio(z_a / z_b, mesh), rel=1e-15)


def test_willis_row_refuses_a_sign_other_than_one():
    with pytest.raises(gearlever.GearleverError, match="sign"):
        df.willis_row(20, 30, 0)
