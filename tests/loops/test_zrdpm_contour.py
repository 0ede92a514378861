"""The ZRDPM contour re-expressed as vector loops gives the closed forms' analogues.

gearlever.loops.zrdpm_contour_system writes contour 1 (or 2) as four loops (the
double slider, the sliders turning the lever, the lever's point, the Willis
relation) and the batched Newton engine solves them; its analogues are compared
with the closed forms of gearlever.loops.closed (paper eqs. 6-7, 16) and of
gearlever.zrdpm (eqs. 9, 11, 14, 16) when that module is present.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.loops import closed, double_slider, double_slider_system, zrdpm_contour

PHI = np.linspace(0.0, 2 * np.pi, 145)


def test_engine_double_slider_equals_closed_closed_form():
    system = double_slider_system(21.0, 3.0)
    sol = system.solve(PHI, {"x_B": 20.0, "y_A": 2.0})  # Newton, not the closed form
    ref = closed.double_slider_projections(21.0, 3.0, PHI)
    assert sol.valid.all()
    for k, name in enumerate(("x_B", "y_A")):
        assert np.allclose(sol[name], ref[k], atol=1e-12)
        assert np.allclose(sol.d1(name), ref[2 + k], atol=1e-12)  # eq. 7
        assert np.allclose(sol.d2(name), ref[4 + k], atol=1e-12)
    assert np.array_equal(double_slider(21.0, 3.0, PHI).x[..., 0], ref[0])


@settings(max_examples=8, deadline=None)
@given(
    l=st.floats(1.0, 30.0),
    r_a=st.floats(0.5, 20.0),
    r_b=st.floats(0.5, 20.0),
    th0=st.floats(-3.0, 3.0),
    ratio=st.floats(0.2, 3.0),
    mesh=st.sampled_from(["external", "internal"]),
)
def test_engine_contour_matches_eq_9_14_16_closed_forms(l, r_a, r_b, th0, ratio, mesh):
    sol = zrdpm_contour(l, PHI, 1.5, r_a, r_b, ratio, mesh, th0)
    assert sol.valid.all()
    c = l / (r_a + r_b)
    u = c * (np.sin(PHI) + np.cos(PHI))  # eq. 9 (general gain)
    e = c * (np.cos(PHI) - np.sin(PHI))
    tol = 1e-11 * (1 + c)  # rounding grows with the lever's gain c
    assert np.allclose(sol.d1("theta1"), u, rtol=1e-10, atol=tol)
    assert np.allclose(sol.d2("theta1"), e, rtol=1e-10, atol=tol)
    ax, ay = closed.point_acceleration(l, sol["theta1"], u, e)  # eq. 16
    assert np.allclose(sol.d2("p_x"), ax, rtol=1e-10, atol=tol * l * (1 + c))
    assert np.allclose(sol.d2("p_y"), ay, rtol=1e-10, atol=tol * l * (1 + c))
    i = -ratio if mesh == "external" else ratio
    assert np.allclose(sol.d1("theta8"), (1 - i) * u + i, rtol=1e-10, atol=tol * (1 + ratio))  # eq. 11
    assert np.allclose(sol.d2("theta8"), (1 - i) * e, rtol=1e-10, atol=tol * (1 + ratio))  # eq. 14
    # the recovery without eq. 17's division (both projections) returns the engine's e
    u2, e_back = closed.recover_analogues(l, sol["theta1"], sol.d2("p_x"), sol.d2("p_y"))
    assert np.allclose(e_back, e, atol=10 * tol * (1 + c)) and np.allclose(u2, u * u, atol=10 * tol * (1 + c))


@pytest.mark.parametrize("contour", [1, 2])
@pytest.mark.parametrize(
    "kw",
    [
        {},
        {
            "l": 21.0,
            "r": 2.0,
            "r_a": 4.0,
            "r_b": 9.0,
            "r_lead": 3.0,
            "r_driven": 2.0,
            "mesh": "internal",
            "lever_angle0_deg": 20.0,
        },
    ],
)
def test_engine_contour_matches_gearlever_zrdpm(contour, kw):
    zrdpm = pytest.importorskip("gearlever.zrdpm")
    params = zrdpm.ZrdpmContour(contour=contour, **kw)
    ref = zrdpm.analogues(params, PHI)
    sol = zrdpm_contour(
        params.l,
        PHI,
        params.r,
        params.r_a,
        params.r_b,
        params.ratio,
        params.mesh,
        np.radians(params.lever_angle0_deg),
    )
    assert sol.valid.all()
    tol = 1e-11 * (1 + params.lever_gain)
    assert np.allclose(sol.d1("theta1"), ref.u_carrier, rtol=1e-10, atol=tol)
    assert np.allclose(sol.d2("theta1"), ref.e_carrier, rtol=1e-10, atol=tol)
    assert np.allclose(sol.d1("theta8"), ref.u_gear, rtol=1e-10, atol=tol)
    assert np.allclose(sol.d2("theta8"), ref.e_gear, rtol=1e-10, atol=tol)
    # point accelerations: eq. 16 / 35, x axis as the contour is tabulated (x_sign)
    assert np.allclose(params.x_sign * sol.d2("p_x"), ref.a_x, rtol=1e-10, atol=tol * params.l)
    assert np.allclose(sol.d2("p_y"), ref.a_y, rtol=1e-10, atol=tol * params.l)


@pytest.mark.parametrize("l", [20.0, 7.5])
def test_zrdpm_contour_default_radii_are_l_over_2_like_the_loops_contour(l):
    # Known bug: ZrdpmContour defaulted r_a = r_b = 5 cm whatever l, so that
    # ZrdpmContour(l=20) had u_1 twice the loops contour's (whose radii default
    # to l/2, paper eq. 9 as printed: u_1 = sin(phi) + cos(phi) for l = rA + rB).
    zrdpm = pytest.importorskip("gearlever.zrdpm")
    params = zrdpm.ZrdpmContour(l=l)
    assert params.r_a == params.r_b == l / 2
    ref = zrdpm.analogues(params, PHI)
    sol = zrdpm_contour(l, PHI)
    assert np.allclose(sol.d1("theta1"), ref.u_carrier, rtol=1e-10, atol=1e-10)
    assert np.allclose(ref.u_carrier, np.sin(PHI) + np.cos(PHI), atol=1e-14)  # eq. 9
