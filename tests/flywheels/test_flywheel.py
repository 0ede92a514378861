"""Flywheel sizing: closed-form turning-moment diagrams (no published textbook answer is used here)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import gearlever
from gearlever.errors import GearleverError
from gearlever.flywheels.flywheel import flywheel


@pytest.mark.parametrize("k, amp", [(1, 300.0), (2, 300.0), (3, 1500.0)])
def test_sinusoidal_torque_energy_fluctuation_is_2A_over_k(k, amp):
    """T = Tm + A sin(k theta), constant load Tm: E = A/k (1 - cos k theta), dE = 2A/k,
    maximum speed at theta = pi/k, minimum at theta = 0; trapezoid error O(h^2)."""
    th = np.linspace(0.0, 2 * np.pi, 7201)
    f = flywheel(th, 1200.0 + amp * np.sin(k * th), 300.0)
    h = th[1] - th[0]
    assert f.mean_torque == pytest.approx(1200.0, rel=1e-12)
    assert f.energy_fluctuation == pytest.approx(2 * amp / k, rel=h**2)
    # k equal loops: the extremes repeat every 2 pi / k, any of them may be reported
    lobe = 2 * np.pi / k
    assert (f.theta_max_speed - np.pi / k) / lobe == pytest.approx(round((f.theta_max_speed - np.pi / k) / lobe))
    assert f.theta_min_speed / lobe == pytest.approx(round(f.theta_min_speed / lobe), abs=1e-9)
    assert f.power == pytest.approx(1200.0 * 300.0 * np.pi / 30, rel=1e-12)


def test_triangular_diagram_is_integrated_exactly_with_interior_extremes():
    """Excess torque -50, +50 at 0 and 90 deg (linear between): it crosses zero at 45 deg, inside an interval.
    Over 0..360 with samples -50, 50, -50, 50, -50 every half-loop is a triangle of area 1/2 * (pi/4) * 50,
    and E runs from its minimum (45 deg) up two of them to its maximum (135 deg): dE = 2 * 25 pi / 4."""
    th = np.radians([0.0, 90.0, 180.0, 270.0, 360.0])
    excess = np.array([-50.0, 50.0, -50.0, 50.0, -50.0])
    f = flywheel(th, 1000.0 + excess, 100.0)
    loop = 0.5 * (np.pi / 4) * 50.0  # one triangle between a sample and the zero crossing
    assert f.energy_fluctuation == pytest.approx(2 * loop, rel=1e-14)
    assert min(abs(f.theta_min_speed_deg - t) for t in (45.0, 225.0)) < 1e-12  # two equal loops
    assert min(abs(f.theta_max_speed_deg - t) for t in (135.0, 315.0)) < 1e-12


def test_three_crank_engine_with_varying_load_against_the_primitive():
    """T = 25000 - 7500 sin 3t, L = 25000 + 3600 sin t (N m): E = 2500 cos 3t + 3600 cos t + C; its extremes
    lie at sin t = 0 or sin^2 t = (3*7500 + 3600)/(4*7500) (zeros of T - L), evaluated in closed form."""
    th = np.linspace(0.0, 2 * np.pi, 20001)
    f = flywheel(th, 25000 - 7500 * np.sin(3 * th), 450.0, load=25000 + 3600 * np.sin(th), inertia=360.0)
    a = math.asin(math.sqrt((3 * 7500 + 3600) / (4 * 7500)))
    roots = np.array([0.0, a, np.pi - a, np.pi, np.pi + a, 2 * np.pi - a])
    F = 2500 * np.cos(3 * roots) + 3600 * np.cos(roots)
    dE = F.max() - F.min()
    assert f.energy_fluctuation == pytest.approx(dE, rel=1e-6)
    assert f.theta_max_speed == pytest.approx(roots[np.argmax(F)], abs=1e-6)
    assert f.fluctuation == pytest.approx(dE / (360.0 * (450 * np.pi / 30) ** 2), rel=1e-6)
    assert f.load_shift == pytest.approx(0.0, abs=1e-6)


def test_inertia_and_fluctuation_are_inverse_and_hold_the_kinetic_energy_swing():
    """I from Cs and Cs from I round-trip; and with that I the kinetic energy I w^2/2 swings by exactly dE
    between w(1 - Cs/2) and w(1 + Cs/2) (the flywheel equation, exact for the arithmetic mean speed)."""
    th = np.linspace(0, 4 * np.pi, 721)
    T = 100 + 400 * np.maximum(np.sin(th / 2 - 0.3), 0) - 60 * np.cos(th)
    a = flywheel(th, T, 1500.0, fluctuation=0.02)
    b = flywheel(th, T, 1500.0, inertia=a.inertia)
    assert b.fluctuation == pytest.approx(0.02, rel=1e-13)
    w = 1500 * np.pi / 30
    swing = 0.5 * a.inertia * ((w * 1.01) ** 2 - (w * 0.99) ** 2)
    assert swing == pytest.approx(a.energy_fluctuation, rel=1e-13)


def test_period_wraps_the_last_interval_like_a_closing_sample():
    th = np.radians(np.arange(0, 720, 10.0))
    T = 500 + 900 * np.sin(th / 2) ** 8 - 200 * np.sin(th)
    closed = flywheel(np.append(th, 4 * np.pi), np.append(T, T[0]), 2000.0)
    wrapped = flywheel(th, T, 2000.0, period=4 * np.pi)
    assert wrapped.energy_fluctuation == pytest.approx(closed.energy_fluctuation, rel=1e-13)
    assert wrapped.mean_torque == pytest.approx(closed.mean_torque, rel=1e-13)
    assert wrapped.theta_max_speed == pytest.approx(closed.theta_max_speed, abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    arrays(np.float64, st.integers(3, 40), elements=st.floats(-1e3, 1e3)),
    st.integers(1, 5),
    st.integers(0, 39),
)
def test_piecewise_linear_diagram_exact_under_refinement_and_rotation(values, refine, shift):
    """The diagram is the linear interpolant of the samples: inserting samples on it, or starting the cycle
    at another sample, leaves dE and the mean torque unchanged (to rounding)."""
    n = values.size
    th = np.linspace(0.0, 2 * np.pi, n + 1)[:-1]
    base = flywheel(th, values, 100.0, period=2 * np.pi)
    fine_th = np.linspace(0.0, 2 * np.pi, n * refine + 1)[:-1]
    fine = flywheel(
        fine_th, np.interp(fine_th, np.append(th, 2 * np.pi), np.append(values, values[0])), 100.0, period=2 * np.pi
    )
    s = shift % n
    rot = flywheel(np.append(th[s:], th[:s] + 2 * np.pi), np.roll(values, -s), 100.0, period=2 * np.pi)
    scale = 1e-9 * (1 + np.abs(values).max() * 2 * np.pi)
    assert fine.energy_fluctuation == pytest.approx(base.energy_fluctuation, abs=scale)
    assert rot.energy_fluctuation == pytest.approx(base.energy_fluctuation, abs=scale)
    assert fine.mean_torque == pytest.approx(base.mean_torque, abs=scale)
    assert base.energy_fluctuation >= 0


def test_result_is_a_frozen_result_with_a_frame_and_exported():
    th = np.linspace(0, 2 * np.pi, 9)
    f = gearlever.flywheel(th, 10 + np.sin(th), 60.0, fluctuation=0.1)
    assert f.to_frame().shape[0] == 9
    with pytest.raises(AttributeError):
        f.inertia = 1.0


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(theta=[0.0, 1.0, 1.0], torque=[1, 2, 3]), "strictly increasing"),
        (dict(theta=[0.0], torque=[1]), "at least 2"),
        (dict(torque=[1, 2]), "shape of theta"),
        (dict(mean_speed_rpm=-3.0), "mean_speed_rpm"),
        (dict(fluctuation=0.1, inertia=2.0), "not both"),
        (dict(fluctuation=-0.1), "fluctuation"),
        (dict(load=[5.0, 5.0, 5.0, 5.0]), "load: its mean"),
        (dict(period=1.0), "period must exceed"),
        (dict(torque=[1.0, np.nan, 1.0, 2.0]), "torque"),
    ],
)
def test_bad_input_is_refused_naming_it(kwargs, needle):
    args = dict(theta=[0.0, 1.0, 2.0, 3.0], torque=[1.0, 2.0, 0.0, 1.0], mean_speed_rpm=100.0)
    args.update(kwargs)
    with pytest.raises(GearleverError, match=needle):
        flywheel(**args)
