"""The normalised motions: endpoints, derivatives against finite differences, and the
peak factors tabulated by Norton (Design of Machinery, ch. 8, "Cam design") and Rothbart
(Cam Design Handbook, ch. 3)."""

import math

import numpy as np
import pytest

from gearlever.laws.motions import MOTIONS

RISING = [n for n, m in MOTIONS.items() if m.rises]


@pytest.mark.parametrize("name", list(MOTIONS))
def test_each_motion_derivatives_match_central_finite_differences(name):
    u = np.linspace(0.01, 0.99, 397)
    # avoid the joints of piecewise motions, where higher derivatives have kinks
    u = u[np.min(np.abs(u[:, None] - np.arange(1, 8)[None, :] / 8), axis=1) > 2e-3]
    h = 1e-5
    d = MOTIONS[name].derivs
    for k in range(3):
        fd = (d(u + h)[k] - d(u - h)[k]) / (2 * h)
        scale = max(1.0, float(np.max(np.abs(d(u)[k + 1]))))
        np.testing.assert_allclose(fd, d(u)[k + 1], atol=1e-6 * scale, err_msg=f"{name} derivative {k + 1}")


@pytest.mark.parametrize("name", RISING)
def test_each_rising_motion_goes_from_0_to_1(name):
    y, dy, _, _ = MOTIONS[name].derivs(np.array([0.0, 1.0]))
    np.testing.assert_allclose(y, [0.0, 1.0], atol=1e-14)
    if name != "linear":
        np.testing.assert_allclose(dy, [0.0, 0.0], atol=1e-13)


def test_dwell_is_zero_with_zero_derivatives():
    for arr in MOTIONS["dwell"].derivs(np.linspace(0, 1, 11)):
        assert np.all(arr == 0)


# Peak factors C_v, C_a, C_j of |y'|, |y''|, |y'''|: the closed forms (cycloidal 2, 2 pi, 4 pi^2;
# harmonic pi/2, pi^2/2, pi^3/2) and the four-digit values tabulated in Norton, Design of
# Machinery, ch. 8, "Factors for peak velocity and acceleration of some cam functions", and
# Rothbart, Cam Design Handbook, ch. 3 (3-4-5: 1.875, 5.7735, 60; 4-5-6-7: 2.1875, 7.5132, 52.5;
# modified trapezoid: 2.0, 4.8881, 61.43; modified sine: 1.7596, 5.5280, 69.47).
PEAKS = {
    "harmonic": (math.pi / 2, math.pi**2 / 2, math.pi**3 / 2),
    "cycloidal": (2.0, 2 * math.pi, 4 * math.pi**2),
    "345": (1.875, 5.7735, 60.0),
    "4567": (2.1875, 7.5132, 52.5),
    "modified-trapezoid": (2.0, 4.8881, 61.43),
    "modified-sine": (1.7596, 5.5280, 69.47),
    "linear": (1.0, 0.0, 0.0),
}


@pytest.mark.parametrize("name", sorted(PEAKS))
def test_peak_factors_match_the_tabulated_values(name):
    u = np.linspace(0, 1, 400001)
    _, dy, d2y, d3y = MOTIONS[name].derivs(u)
    got = [np.max(np.abs(x)) for x in (dy, d2y, d3y)]
    np.testing.assert_allclose(got, PEAKS[name], rtol=1e-4, atol=1e-12)


def test_symmetric_motions_pass_half_rise_at_half_input():
    for name in RISING:
        assert float(MOTIONS[name].y(0.5)) == pytest.approx(0.5, abs=1e-14)
